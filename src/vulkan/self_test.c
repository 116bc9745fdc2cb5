#include <string.h>

#include "roma_shared.h"
#include "vulkan/vk_internal.h"

#define SELF_TEST_COUNT 4096u

/* Dispatches fill_u32.comp into a host-visible buffer and checks every word,
 * with the dispatch timed: device, embedded SPIR-V, descriptors and timers in one go. */
roma_result roma_context_self_test(roma_context *ctx, double *out_gpu_ms)
{
    if (out_gpu_ms)
        *out_gpu_ms = 0.0;
    if (!ctx)
        return roma_fail(NULL, ROMA_ERROR_INVALID_ARGUMENT, "roma_context_self_test: context is NULL");
    roma_compute_pipeline pipe;
    roma_buffer buffer = {0};
    roma_gpu_timer *timer = NULL;
    roma_descriptor_set set = {0};
    const VkDescriptorType type = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    roma_result r = roma_compute_pipeline_create(ctx, "fill_u32.comp", 1, sizeof(roma_fill_push), &pipe);
    if (r != ROMA_SUCCESS)
        return r;
    r = roma_buffer_create(ctx, SELF_TEST_COUNT * sizeof(uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                           ROMA_MEMORY_READBACK, &buffer);
    if (r == ROMA_SUCCESS)
        r = roma_gpu_timer_create(ctx, 1, &timer);
    if (r == ROMA_SUCCESS)
        r = roma_descriptor_set_create(ctx, &pipe, &type, 1, &set);
    if (r == ROMA_SUCCESS) {
        roma_descriptor_write_buffer(ctx, &set, ROMA_FILL_BINDING_OUTPUT, type, buffer.buffer);
        memset(buffer.mapped, 0xff, SELF_TEST_COUNT * sizeof(uint32_t));
    }
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    roma_fill_push push = {.count = SELF_TEST_COUNT, .value = 7u, .stride = 3u};
    if (r == ROMA_SUCCESS)
        r = roma_begin_one_shot(ctx, &cmd);
    if (r == ROMA_SUCCESS) {
        roma_gpu_timer_reset(timer, cmd);
        uint32_t scope = roma_gpu_timer_begin(timer, cmd, "self_test_fill");
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipe.pipeline);
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipe.layout, 0, 1, &set.set, 0, NULL);
        vkCmdPushConstants(cmd, pipe.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push, &push);
        vkCmdDispatch(cmd, (SELF_TEST_COUNT + ROMA_FILL_WORKGROUP_SIZE - 1) / ROMA_FILL_WORKGROUP_SIZE, 1, 1);
        roma_gpu_timer_end(timer, cmd, scope);
        roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                                VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
        r = roma_submit_one_shot(ctx, cmd);
    }
    if (r == ROMA_SUCCESS)
        r = roma_buffer_invalidate(ctx, &buffer);
    if (r == ROMA_SUCCESS) {
        const uint32_t *words = buffer.mapped;
        for (uint32_t i = 0; i < SELF_TEST_COUNT && r == ROMA_SUCCESS; ++i)
            if (words[i] != push.value + i * push.stride)
                r = roma_fail(&ctx->logger, ROMA_ERROR_VULKAN,
                              "self-test: word %u is %u, expected %u", i, words[i], push.value + i * push.stride);
    }
    if (r == ROMA_SUCCESS) {
        roma_gpu_timing timing;
        uint32_t count = 1;
        r = roma_gpu_timer_read(timer, &timing, &count);
        if (r == ROMA_SUCCESS && out_gpu_ms)
            *out_gpu_ms = timing.milliseconds;
    }
    roma_descriptor_set_destroy(ctx, &set);
    roma_gpu_timer_destroy(timer);
    roma_buffer_destroy(ctx, &buffer);
    roma_compute_pipeline_destroy(ctx, &pipe);
    return r;
}
