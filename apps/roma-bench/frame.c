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
#include "study/gbuffer.h"
#include "passes/pixel_list.h"
#include "effects/scene_buffers.h"
#include "reference.h"
#include "map/map_internal.h"
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

double roma_bench_embree_ao_ms(const roma_ref *ref, const roma_gbuffer_pixel *px, const uint32_t *covered,
                               uint32_t count, uint32_t spp, float radius, double *mean)
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
        /* A frame's build redoes the grid (new jitter): one the map keeps times nothing. */
        roma_map_info info;
        roma_map_get_info(map, &info);
        if (r == ROMA_SUCCESS && info.levels_rebuilt != info.levels) {
            fprintf(stderr, "roma-bench: frame %u's build kept %u of %u levels: not a dynamic frame\n", frame,
                    info.levels - info.levels_rebuilt, info.levels);
            r = ROMA_ERROR_INVALID_ARGUMENT;
        }
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

/* What both sides of a frame share: the scene's geometry, its G-buffer from the default camera
 * (rendered once) and the covered pixels. */
typedef struct frame_setup {
    roma_scene_buffers geo;
    roma_gbuffer *gb;
    roma_gbuffer_list list;
    roma_gbuffer_pixel *px;
    uint32_t *covered, count;
} frame_setup;

static void setup_destroy(roma_context *ctx, frame_setup *s)
{
    roma_gbuffer_list_destroy(&s->list);
    roma_gbuffer_destroy(s->gb);
    roma_scene_buffers_destroy(ctx, &s->geo);
    free(s->px);
    free(s->covered);
    memset(s, 0, sizeof *s);
}

static roma_result setup_create(roma_context *ctx, const roma_scene *scene, uint32_t w, uint32_t h, frame_setup *s)
{
    memset(s, 0, sizeof *s);
    s->px = malloc(sizeof *s->px * (size_t)w * h);
    s->covered = malloc(sizeof *s->covered * (size_t)w * h);
    roma_scene_view sv;
    roma_scene_get_view(scene, &sv);
    float diag = 0.0f;
    for (int a = 0; a < 3; ++a)
        diag += (sv.bounds_max[a] - sv.bounds_min[a]) * (sv.bounds_max[a] - sv.bounds_min[a]);
    roma_camera cam;
    roma_scene_default_camera(scene, (float)w / (float)h, &cam);
    roma_result r = ROMA_ERROR_OUT_OF_HOST_MEMORY;
    if (s->px && s->covered)
        r = roma_scene_buffers_create(ctx, scene, &s->geo);
    if (r == ROMA_SUCCESS)
        r = roma_gbuffer_create(ctx, w, h, &s->gb);
    if (r == ROMA_SUCCESS)
        r = roma_gbuffer_list_create(ctx, w, h, &s->list);
    VkCommandBuffer cmd;
    if (r == ROMA_SUCCESS)
        r = roma_begin_one_shot(ctx, &cmd);
    if (r == ROMA_SUCCESS) {
        roma_gbuffer_inputs gin = {
            .positions = s->geo.positions.address, .normals = s->geo.normals.address,
            .indices = s->geo.indices.address, .albedo = s->geo.albedo.address,
            .triangle_count = s->geo.triangle_count, .camera = cam, .previous_camera = cam,
            .near_plane = 1e-4f * sqrtf(diag),
        };
        r = roma_gbuffer_record(s->gb, cmd, &gin);
        if (r == ROMA_SUCCESS)
            r = roma_gbuffer_list_record(&s->list, cmd, roma_gbuffer_pixels_address(s->gb));
        roma_result sr = roma_submit_one_shot(ctx, cmd);
        if (r == ROMA_SUCCESS)
            r = sr;
    }
    if (r == ROMA_SUCCESS)
        r = roma_gbuffer_download(s->gb, s->px);
    if (r != ROMA_SUCCESS) {
        fprintf(stderr, "roma-bench: frame setup failed: %s\n", roma_result_string(r));
        setup_destroy(ctx, s);
        return r;
    }
    for (uint32_t i = 0; i < w * h; ++i)
        if (isfinite(s->px[i].position_t[3]))
            s->covered[s->count++] = i;
    return ROMA_SUCCESS;
}

int roma_bench_frame(roma_context *ctx, const roma_scene *scene, const roma_bench_frame_desc *d, FILE *csv)
{
    const uint32_t w = d->width, h = d->height, runs = d->runs ? d->runs : 5;
    frame_setup fs;
    roma_map *map = NULL;
    roma_ao_pass *ao = NULL;
    roma_buffer accum = {0};
    double *samples = malloc(sizeof(double) * runs * 5);
    int status = 1;
    roma_map_desc md = {.resolution = d->resolution, .angular = d->angular};
    roma_result r = setup_create(ctx, scene, w, h, &fs);
    if (r != ROMA_SUCCESS) {
        free(samples);
        return 1;
    }
    const roma_gbuffer_pixel *px = fs.px;
    const uint32_t *covered = fs.covered, count = fs.count;
    if (!samples)
        r = ROMA_ERROR_OUT_OF_HOST_MEMORY;
    if (r == ROMA_SUCCESS)
        r = roma_map_create(ctx, &md, scene, &map);
    if (r == ROMA_SUCCESS)
        r = roma_ao_pass_create(ctx, &ao);
    if (r == ROMA_SUCCESS)
        r = roma_buffer_create(ctx, 4ull * w * h, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                               VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                               ROMA_MEMORY_READBACK, &accum);
    if (r != ROMA_SUCCESS) {
        fprintf(stderr, "roma-bench: frame setup failed: %s\n", roma_result_string(r));
        goto done;
    }
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
            .gbuffer_pixels = roma_gbuffer_pixels_buffer(fs.gb), .width = w, .height = h, .map = &mi,
            .list = &fs.list, .offset = ROMA_DEFAULT_OFFSET_CELLS * mi.trace_cell, .radius = d->radius,
            .tmin = ROMA_DEFAULT_AO_SKIP_CELLS * mi.trace_cell, .spp = spp, .frame = 0, .seed = SEED, .accum = accum.buffer,
            .bom = mi.bom_view, /* the rays' start walked exactly, as every pass does */
        };
        double ref_mean = 0.0;
        for (uint32_t k = 0; k < runs; ++k) {
            /* frames 1 + 2k and 2 + 2k: each build a new jitter (frame 0 warmed the map) */
            samples[k] = roma_frame_ms(ctx, map, ao, &in, &accum, 1 + 2 * k, 1);
            samples[runs + k] = roma_frame_ms(ctx, map, ao, &in, &accum, 1 + 2 * k, 2);
            samples[2 * runs + k] = roma_frame_ms(ctx, map, ao, &in, &accum, 2 + 2 * k, 3);
            double t0 = roma_app_now_ms();
            roma_ref *ref = NULL;
            if (roma_ref_create(scene, NULL, &ref) != ROMA_SUCCESS) {
                status = 1;
                break;
            }
            samples[3 * runs + k] = roma_app_now_ms() - t0;
            samples[4 * runs + k] = roma_bench_embree_ao_ms(ref, px, covered, count, spp, d->radius, &ref_mean);
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
    setup_destroy(ctx, &fs);
    free(samples);
    return status;
}

/* One step of the build alone (ROMA_MAP_STEP_*), submit to fence. */
static double step_ms(roma_context *ctx, roma_map *map, uint32_t frame, uint32_t steps)
{
    VkCommandBuffer cmd;
    if (roma_begin_one_shot(ctx, &cmd) != ROMA_SUCCESS)
        return NAN;
    roma_map_frame_desc fd = {.frame = frame, .seed = SEED, .jitter_grid = 1, .jitter_directions = 1};
    return roma_bench_submit_ms(ctx, cmd, roma_map_record_steps(map, cmd, &fd, NULL, steps));
}

int roma_bench_growth(roma_context *ctx, const roma_scene *scene, const roma_bench_frame_desc *d, const uint32_t *res,
                      int res_count, roma_bench_growth_row *rows)
{
    const uint32_t w = d->width, h = d->height, runs = d->runs ? d->runs : 5;
    frame_setup fs;
    if (setup_create(ctx, scene, w, h, &fs) != ROMA_SUCCESS)
        return 1;
    double *samples = malloc(sizeof(double) * runs * 3);
    roma_buffer accum = {0};
    roma_ao_pass *ao = NULL;
    roma_result r = samples ? roma_ao_pass_create(ctx, &ao) : ROMA_ERROR_OUT_OF_HOST_MEMORY;
    if (r == ROMA_SUCCESS)
        r = roma_buffer_create(ctx, 4ull * w * h, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                               VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                               ROMA_MEMORY_READBACK, &accum);
    /* Embree's side does not depend on RES: measured once for the scene. */
    double bvh_ms = NAN, embree_ms = NAN, mean = 0.0;
    for (uint32_t k = 0; r == ROMA_SUCCESS && k < runs; ++k) {
        double t0 = roma_app_now_ms();
        roma_ref *ref = NULL;
        r = roma_ref_create(scene, NULL, &ref);
        samples[k] = roma_app_now_ms() - t0;
        if (r == ROMA_SUCCESS)
            samples[runs + k] = roma_bench_embree_ao_ms(ref, fs.px, fs.covered, fs.count, 1, d->radius, &mean);
        roma_ref_destroy(ref);
    }
    if (r == ROMA_SUCCESS) {
        bvh_ms = roma_app_median(samples, (int)runs);
        embree_ms = roma_app_median(samples + runs, (int)runs);
    }
    roma_scene_view sv;
    roma_scene_get_view(scene, &sv);
    for (int i = 0; i < res_count && r == ROMA_SUCCESS; ++i) {
        roma_map *map = NULL;
        roma_map_desc md = {.resolution = res[i], .angular = d->angular};
        r = roma_map_create(ctx, &md, scene, &map);
        if (r != ROMA_SUCCESS)
            break;
        roma_map_info mi;
        roma_map_frame_desc warm = {.frame = 0, .seed = SEED, .jitter_grid = 1, .jitter_directions = 1};
        roma_map_build(map, &warm, NULL);
        roma_map_get_info(map, &mi);
        roma_ao_pass_inputs in = {
            .gbuffer_pixels = roma_gbuffer_pixels_buffer(fs.gb), .width = w, .height = h, .map = &mi,
            .list = &fs.list, .offset = ROMA_DEFAULT_OFFSET_CELLS * mi.trace_cell, .radius = d->radius,
            .tmin = ROMA_DEFAULT_AO_SKIP_CELLS * mi.trace_cell, .spp = 1, .seed = SEED, .accum = accum.buffer,
            .bom = mi.bom_view,
        };
        roma_frame_ms(ctx, map, ao, &in, &accum, 0, 2); /* the AO pipeline's first use, untimed */
        for (uint32_t k = 0; k < runs; ++k) {
            samples[k] = step_ms(ctx, map, k, ROMA_MAP_STEP_VOXELIZE);
            samples[runs + k] = step_ms(ctx, map, k, ROMA_MAP_STEP_ROTATE);
            samples[2 * runs + k] = roma_frame_ms(ctx, map, ao, &in, &accum, k, 2);
        }
        rows[i] = (roma_bench_growth_row){
            .triangles = sv.triangle_count, .resolution = res[i], .covered = fs.count,
            .voxelize_ms = roma_app_median(samples, (int)runs), .rotate_ms = roma_app_median(samples + runs, (int)runs),
            .ao_ms = roma_app_median(samples + 2 * runs, (int)runs), .bvh_ms = bvh_ms, .embree_ao_ms = embree_ms,
        };
        roma_map_destroy(map);
    }
    if (r != ROMA_SUCCESS)
        fprintf(stderr, "roma-bench: growth measurement failed: %s\n", roma_result_string(r));
    roma_buffer_destroy(ctx, &accum);
    roma_ao_pass_destroy(ao);
    setup_destroy(ctx, &fs);
    free(samples);
    return r == ROMA_SUCCESS ? 0 : 1;
}
