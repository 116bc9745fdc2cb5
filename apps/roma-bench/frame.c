/* roma-bench --frame: what a dynamic AO frame costs, ROMA against Embree, host-observed
 * (submit to fence on the GPU side, wall clock on the CPU side), medians of runs. */
#include "frame.h"

#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app_common.h"
#include "passes/ao.h"
#include "passes/effect_render.h"
#include "passes/gbuffer.h"
#include "passes/pixel_list.h"
#include "passes/scene_buffers.h"
#include "reference.h"
#include "roma/map.h"
#include "vulkan/vk_internal.h"

#define SEED 7u

/* Embree AO at the covered G-buffer points, split over threads like the reference. */
typedef struct ao_job {
    const roma_ref *ref;
    const roma_gbuffer_pixel *px;
    const uint32_t *covered;
    uint32_t count, spp, thread, threads;
    float radius;
    double sum;
} ao_job;

static void *ao_worker(void *arg)
{
    ao_job *j = arg;
    for (uint32_t i = j->thread; i < j->count; i += j->threads) {
        const roma_gbuffer_pixel *p = &j->px[j->covered[i]];
        j->sum += roma_ref_ao_point(j->ref, p->position_t, p->geometric_normal, p->shading_normal, j->radius, j->spp,
                                    SEED, j->covered[i]);
    }
    return NULL;
}

static double embree_ao_ms(const roma_ref *ref, const roma_gbuffer_pixel *px, const uint32_t *covered, uint32_t count,
                           uint32_t spp, float radius, double *mean)
{
    long cores = sysconf(_SC_NPROCESSORS_ONLN);
    uint32_t threads = cores < 1 ? 1u : cores > 64 ? 64u : (uint32_t)cores;
    ao_job jobs[64];
    pthread_t tid[64];
    double t0 = roma_app_now_ms();
    for (uint32_t t = 0; t < threads; ++t) {
        jobs[t] = (ao_job){ref, px, covered, count, spp, t, threads, radius, 0.0};
        pthread_create(&tid[t], NULL, ao_worker, &jobs[t]);
    }
    double sum = 0.0;
    for (uint32_t t = 0; t < threads; ++t) {
        pthread_join(tid[t], NULL);
        sum += jobs[t].sum;
    }
    double ms = roma_app_now_ms() - t0;
    *mean = count ? sum / count : 0.0;
    return ms;
}

/* One submission of `what` (bit 0: map build, bit 1: AO pass), submit to fence. */
static double roma_frame_ms(roma_context *ctx, roma_map *map, roma_ao_pass *ao, const roma_ao_pass_inputs *in,
                            roma_buffer *accum, uint32_t frame, int what)
{
    VkCommandBuffer cmd;
    if (roma_begin_one_shot(ctx, &cmd) != ROMA_SUCCESS)
        return NAN;
    roma_result r = ROMA_SUCCESS;
    if (what & 1) {
        roma_map_frame_desc fd = {.frame = frame, .seed = SEED, .jitter_grid = 1, .jitter_directions = 1};
        r = roma_map_record_build(map, cmd, &fd, NULL);
    }
    if (r == ROMA_SUCCESS && (what & 2)) {
        vkCmdFillBuffer(cmd, accum->buffer, 0, VK_WHOLE_SIZE, 0);
        r = roma_ao_pass_record(ao, cmd, in);
    }
    return roma_bench_submit_ms(ctx, cmd, r);
}

double roma_bench_submit_ms(roma_context *ctx, VkCommandBuffer cmd, roma_result recorded)
{
    double t0 = roma_app_now_ms();
    roma_result s = roma_submit_one_shot(ctx, cmd);
    double ms = roma_app_now_ms() - t0;
    return recorded == ROMA_SUCCESS && s == ROMA_SUCCESS ? ms : NAN;
}

int roma_bench_frame(roma_context *ctx, const roma_scene *scene, const roma_bench_frame_desc *d, FILE *csv)
{
    const uint32_t w = d->width, h = d->height, runs = d->runs ? d->runs : 5;
    roma_scene_buffers geo = {0};
    roma_gbuffer *gb = NULL;
    roma_pixel_list list = {0};
    roma_map *map = NULL;
    roma_ao_pass *ao = NULL;
    roma_buffer accum = {0};
    roma_gbuffer_pixel *px = malloc(sizeof *px * (size_t)w * h);
    uint32_t *covered = malloc(sizeof *covered * (size_t)w * h);
    double *samples = malloc(sizeof(double) * runs * 5);
    int status = 1;
    roma_scene_view sv;
    roma_scene_get_view(scene, &sv);
    float diag = 0.0f;
    for (int a = 0; a < 3; ++a)
        diag += (sv.bounds_max[a] - sv.bounds_min[a]) * (sv.bounds_max[a] - sv.bounds_min[a]);
    roma_camera cam;
    roma_scene_default_camera(scene, (float)w / (float)h, &cam);
    roma_map_desc md = {.resolution = d->resolution, .angular = d->angular};
    roma_result r = px && covered && samples ? roma_scene_buffers_create(ctx, scene, &geo) : ROMA_ERROR_OUT_OF_HOST_MEMORY;
    if (r == ROMA_SUCCESS)
        r = roma_gbuffer_create(ctx, w, h, &gb);
    if (r == ROMA_SUCCESS)
        r = roma_pixel_list_create(ctx, w, h, &list);
    if (r == ROMA_SUCCESS)
        r = roma_map_create(ctx, &md, scene, &map);
    if (r == ROMA_SUCCESS)
        r = roma_ao_pass_create(ctx, &ao);
    if (r == ROMA_SUCCESS)
        r = roma_buffer_create(ctx, 4ull * w * h, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                               VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                               ROMA_MEMORY_READBACK, &accum);
    /* The G-buffer and its covered-pixel list, once: both sides need them. */
    VkCommandBuffer cmd;
    if (r == ROMA_SUCCESS)
        r = roma_begin_one_shot(ctx, &cmd);
    if (r == ROMA_SUCCESS) {
        roma_gbuffer_inputs gin = {
            .positions = geo.positions.address, .normals = geo.normals.address, .indices = geo.indices.address,
            .albedo = geo.albedo.address, .triangle_count = geo.triangle_count, .camera = cam,
            .previous_camera = cam, .near_plane = 1e-4f * sqrtf(diag),
        };
        r = roma_gbuffer_record(gb, cmd, &gin);
        if (r == ROMA_SUCCESS)
            r = roma_pixel_list_record(&list, cmd, roma_gbuffer_pixels_address(gb));
        roma_result s = roma_submit_one_shot(ctx, cmd);
        if (r == ROMA_SUCCESS)
            r = s;
    }
    if (r == ROMA_SUCCESS)
        r = roma_gbuffer_download(gb, px);
    if (r != ROMA_SUCCESS) {
        fprintf(stderr, "roma-bench: frame setup failed: %s\n", roma_result_string(r));
        goto done;
    }
    uint32_t count = 0;
    for (uint32_t i = 0; i < w * h; ++i)
        if (isfinite(px[i].position_t[3]))
            covered[count++] = i;
    roma_map_info mi;
    roma_map_frame_desc warm = {.frame = 0, .seed = SEED, .jitter_grid = 1, .jitter_directions = 1};
    roma_map_build(map, &warm, NULL);
    roma_map_get_info(map, &mi);
    printf("\nDynamic AO frame, %ux%u (%u pixels, %u covered), RES %u, A %u, AO radius %s; medians of %u runs.\n"
           "ROMA: one submission, host-observed; Embree: wall clock, all cores, same points and samples.\n\n"
           "| spp | ROMA build ms | ROMA AO ms | ROMA frame ms | Embree BVH ms | Embree AO ms | Embree frame ms "
           "| ROMA speed-up | AO mean ROMA / Embree |\n|---|---|---|---|---|---|---|---|---|\n",
           w, h, w * h, count, d->resolution, d->angular, d->radius > 0.0f ? "bounded" : "unbounded", runs);
    static const uint32_t spps[2] = {1, 4};
    status = 0;
    for (int si = 0; si < 2; ++si) {
        const uint32_t spp = spps[si];
        roma_ao_pass_inputs in = {
            .gbuffer_pixels = roma_gbuffer_pixels_buffer(gb), .width = w, .height = h, .map = &mi,
            .list = &list, .offset = ROMA_DEFAULT_OFFSET_CELLS * mi.trace_cell, .radius = d->radius,
            .tmin = ROMA_DEFAULT_AO_SKIP_CELLS * mi.trace_cell, .spp = spp, .frame = 0, .seed = SEED, .accum = accum.buffer,
            .bom = mi.bom_view, /* the rays' start walked exactly, as every pass does */
        };
        double ref_mean = 0.0;
        for (uint32_t k = 0; k < runs; ++k) {
            samples[k] = roma_frame_ms(ctx, map, ao, &in, &accum, k, 1);
            samples[runs + k] = roma_frame_ms(ctx, map, ao, &in, &accum, k, 2);
            samples[2 * runs + k] = roma_frame_ms(ctx, map, ao, &in, &accum, k, 3);
            double t0 = roma_app_now_ms();
            roma_ref *ref = NULL;
            if (roma_ref_create(scene, NULL, &ref) != ROMA_SUCCESS) {
                status = 1;
                break;
            }
            samples[3 * runs + k] = roma_app_now_ms() - t0;
            samples[4 * runs + k] = embree_ao_ms(ref, px, covered, count, spp, d->radius, &ref_mean);
            roma_ref_destroy(ref);
        }
        /* The last frame's ROMA AO, for the mean beside the reference's. */
        roma_buffer_invalidate(ctx, &accum);
        double open = 0.0;
        for (uint32_t i = 0; i < count; ++i)
            open += ((const uint32_t *)accum.mapped)[covered[i]];
        double roma_mean = count ? open / ((double)count * spp) : 0.0;
        double med[5];
        for (int c = 0; c < 5; ++c)
            med[c] = roma_app_median(samples + c * runs, (int)runs);
        double embree_frame = med[3] + med[4];
        printf("| %u | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2fx | %.3f / %.3f |\n", spp, med[0], med[1], med[2],
               med[3], med[4], embree_frame, embree_frame / med[2], roma_mean, ref_mean);
        if (csv) {
            static const char *names[5] = {"roma_build", "roma_ao", "roma_frame", "embree_bvh", "embree_ao"};
            for (int c = 0; c < 5; ++c)
                fprintf(csv, "frame,%s spp %u,%u,%u,%.6f,ms\n", names[c], spp, d->resolution, d->angular, med[c]);
        }
    }
done:
    roma_buffer_destroy(ctx, &accum);
    roma_ao_pass_destroy(ao);
    roma_map_destroy(map);
    roma_pixel_list_destroy(&list);
    roma_gbuffer_destroy(gb);
    roma_scene_buffers_destroy(ctx, &geo);
    free(px);
    free(covered);
    free(samples);
    return status;
}
