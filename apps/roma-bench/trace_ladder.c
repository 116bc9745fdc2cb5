#include "trace_ladder.h"

#include <math.h>
#include <stdlib.h>

#include "app_common.h"
#include "frame.h"
#include "roma_shared.h"
#include "study/study_shaders.h"
#include "vulkan/vk_internal.h"

#define RUNGS 5

static const char *const rung_names[RUNGS] = {
    "empty dispatch (launch only)", "+ read the ray, write a hit", "+ resolve the direction (map, fold)",
    "+ map the origin, fetch one word", "whole snapped any-hit trace"};

/* The driver's statistics of the whole trace's pipeline (VK_KHR_pipeline_executable_properties:
 * registers, spills, instructions, as the driver names them), made again with
 * VK_PIPELINE_CREATE_CAPTURE_STATISTICS_BIT_KHR on layout. */
static void print_statistics(roma_context *ctx, VkPipelineLayout layout, const uint32_t constants[3])
{
    PFN_vkGetPipelineExecutablePropertiesKHR get_properties =
        (PFN_vkGetPipelineExecutablePropertiesKHR)vkGetDeviceProcAddr(ctx->device, "vkGetPipelineExecutablePropertiesKHR");
    PFN_vkGetPipelineExecutableStatisticsKHR get_statistics =
        (PFN_vkGetPipelineExecutableStatisticsKHR)vkGetDeviceProcAddr(ctx->device, "vkGetPipelineExecutableStatisticsKHR");
    VkShaderModule shader = VK_NULL_HANDLE;
    VkPipeline pipeline = VK_NULL_HANDLE;
    roma_specialization spec;
    roma_specialization_make(ctx, "trace_ladder.comp", constants, 3, 0, &spec);
    if (!get_properties || !get_statistics || roma_shader_module_create(ctx, "trace_ladder.comp", &shader) != ROMA_SUCCESS)
        return;
    VkComputePipelineCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO,
        .flags = VK_PIPELINE_CREATE_CAPTURE_STATISTICS_BIT_KHR,
        .stage = {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
                  .stage = VK_SHADER_STAGE_COMPUTE_BIT,
                  .module = shader,
                  .pName = "main",
                  .pSpecializationInfo = &spec.info},
        .layout = layout};
    if (vkCreateComputePipelines(ctx->device, VK_NULL_HANDLE, 1, &info, ctx->allocator, &pipeline) == VK_SUCCESS) {
        VkPipelineInfoKHR pi = {.sType = VK_STRUCTURE_TYPE_PIPELINE_INFO_KHR, .pipeline = pipeline};
        VkPipelineExecutablePropertiesKHR props[4];
        uint32_t count = 4;
        for (uint32_t i = 0; i < 4; ++i)
            props[i] = (VkPipelineExecutablePropertiesKHR){.sType = VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_PROPERTIES_KHR};
        if (get_properties(ctx->device, &pi, &count, props) >= 0)
            for (uint32_t e = 0; e < count && e < 4; ++e) {
                VkPipelineExecutableInfoKHR ei = {.sType = VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_INFO_KHR,
                                                  .pipeline = pipeline, .executableIndex = e};
                VkPipelineExecutableStatisticKHR stats[32];
                uint32_t n = 32;
                for (uint32_t i = 0; i < 32; ++i)
                    stats[i] = (VkPipelineExecutableStatisticKHR){.sType = VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_STATISTIC_KHR};
                if (get_statistics(ctx->device, &ei, &n, stats) < 0)
                    continue;
                printf("\nthe whole trace's pipeline, executable %s (subgroup %u), as the driver reports it:", props[e].name,
                       props[e].subgroupSize);
                for (uint32_t i = 0; i < n && i < 32; ++i) {
                    const VkPipelineExecutableStatisticValueKHR v = stats[i].value;
                    printf("%s %s ", i ? ";" : "", stats[i].name);
                    switch (stats[i].format) {
                    case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_BOOL32_KHR: printf("%s", v.b32 ? "yes" : "no"); break;
                    case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_INT64_KHR: printf("%lld", (long long)v.i64); break;
                    case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_UINT64_KHR: printf("%llu", (unsigned long long)v.u64); break;
                    default: printf("%g", v.f64); break;
                    }
                }
                printf("\n");
            }
        vkDestroyPipeline(ctx->device, pipeline, ctx->allocator);
    }
    vkDestroyShaderModule(ctx->device, shader, ctx->allocator);
}

/* One rung (step) at a workgroup size (group): medians of runs after a warm-up, timestamps and
 * host-observed. Returns 0 on success. */
static int time_rung(roma_context *ctx, const roma_trace_push *push, uint32_t runs, roma_gpu_timer *timer,
                     uint32_t step, uint32_t group, double *samples, double *ts, double *host)
{
    const uint32_t constants[3] = {0u, step, group};
    roma_compute_pipeline p = {0};
    if (roma_compute_pipeline_create_flags(ctx, "trace_ladder.comp", NULL, 0, sizeof *push, constants, 3, 0, &p) !=
        ROMA_SUCCESS)
        return 1;
    int status = 0;
    for (uint32_t k = 0; k <= runs && !status; ++k) { /* run 0 warms up */
        VkCommandBuffer cmd;
        if (roma_begin_one_shot(ctx, &cmd) != ROMA_SUCCESS) {
            status = 1;
            break;
        }
        roma_gpu_timer_reset(timer, cmd);
        const uint32_t scope = roma_gpu_timer_begin(timer, cmd, "rung");
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.pipeline);
        vkCmdPushConstants(cmd, p.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof *push, push);
        roma_cmd_dispatch_linear(cmd, push->config[2], group);
        roma_gpu_timer_end(timer, cmd, scope);
        const double h = roma_bench_submit_ms(ctx, cmd, ROMA_SUCCESS);
        roma_gpu_timing t;
        uint32_t count = 1;
        const double g = roma_gpu_timer_read(timer, &t, &count) == ROMA_SUCCESS && count == 1 ? t.milliseconds : NAN;
        if (k > 0)
            samples[k - 1] = g, samples[runs + k - 1] = h;
        status = !isfinite(h);
    }
    roma_compute_pipeline_destroy(ctx, &p);
    *ts = roma_app_median(samples, (int)runs);
    *host = roma_app_median(samples + runs, (int)runs);
    return status;
}

int roma_bench_trace_ladder(roma_context *ctx, const roma_map *map, VkDeviceAddress rays, VkDeviceAddress hits,
                            uint32_t n, uint32_t runs, roma_gpu_timer *timer, int cpu_device, int statistics, FILE *csv)
{
    roma_map_info info;
    if (roma_map_get_info(map, &info) != ROMA_SUCCESS || !info.params_address || !info.maps_address)
        return 1;
    roma_study_shaders_use(ctx); /* the ladder's shader is in the study's table */
    double *samples = malloc(sizeof(double) * 2 * runs);
    if (!samples)
        return 1;
    const roma_trace_push push = {.rays = rays, .hits = hits, .params = info.params_address,
                                  .maps = info.maps_address, .config = {0u, 8u, n, 0u}};
    printf("\nThe trace ladder: the snapped any-hit trace of the same %u rays by address, cut after each step "
           "(each rung adds one; workgroups of %u; medians of %u runs; the last column: ms the rung adds, %s), then "
           "the whole trace in other workgroup sizes\n\n"
           "| rung | ms (timestamps) | ms (host-observed) | ns a ray | added |\n|---|---|---|---|---|\n",
           n, ROMA_TRACE_WORKGROUP_SIZE, runs, cpu_device ? "host-observed" : "timestamps");
    int status = 0;
    double previous = 0.0;
    for (uint32_t step = 0; step < RUNGS && !status; ++step) {
        double ts, host;
        status = time_rung(ctx, &push, runs, timer, step, ROMA_TRACE_WORKGROUP_SIZE, samples, &ts, &host);
        if (status)
            break;
        const double ms = cpu_device ? host : ts;
        if (csv) {
            fprintf(csv, "ladder,%s timestamp,%u,%u,%.6f,ms\n", rung_names[step], info.resolution, info.angular, ts);
            fprintf(csv, "ladder,%s host,%u,%u,%.6f,ms\n", rung_names[step], info.resolution, info.angular, host);
        }
        printf("| %s | %.3f | %.2f | %.2f | %+.3f |\n", rung_names[step], ts, host, ms * 1e6 / n, ms - previous);
        previous = ms;
    }
    /* The workgroup's shape: the whole trace in groups of 32 to 256 invocations (those the
     * device allows). */
    static const uint32_t groups[3] = {32u, 128u, 256u};
    for (int g = 0; g < 3 && !status; ++g) {
        if (groups[g] > ctx->properties.limits.maxComputeWorkGroupSize[0] ||
            groups[g] > ctx->properties.limits.maxComputeWorkGroupInvocations)
            continue;
        double ts, host;
        status = time_rung(ctx, &push, runs, timer, RUNGS - 1, groups[g], samples, &ts, &host);
        if (status)
            break;
        const double ms = cpu_device ? host : ts;
        char name[64];
        snprintf(name, sizeof name, "whole trace, workgroups of %u", groups[g]);
        if (csv)
            fprintf(csv, "ladder,%s timestamp,%u,%u,%.6f,ms\nladder,%s host,%u,%u,%.6f,ms\n", name, info.resolution,
                    info.angular, ts, name, info.resolution, info.angular, host);
        printf("| %s | %.3f | %.2f | %.2f | - |\n", name, ts, host, ms * 1e6 / n);
    }
    /* The driver's statistics of the whole trace (libroma's workgroup), where it reports them. */
    const uint32_t whole[3] = {0u, RUNGS - 1, ROMA_TRACE_WORKGROUP_SIZE};
    roma_compute_pipeline p = {0};
    if (!status && statistics &&
        roma_compute_pipeline_create_flags(ctx, "trace_ladder.comp", NULL, 0, sizeof push, whole, 3, 0, &p) ==
            ROMA_SUCCESS) {
        print_statistics(ctx, p.layout, whole);
        roma_compute_pipeline_destroy(ctx, &p);
    }
    free(samples);
    return status;
}
