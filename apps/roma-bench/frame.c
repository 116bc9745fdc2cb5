/* roma-bench's dynamic AO frame (and --growth): what a dynamic AO frame costs, ROMA against
 * Embree, host-observed (submit to fence on the GPU side, wall clock on the CPU side), medians
 * of runs. roma-bench plays the engine: it owns the G-buffer images (the reference's primary
 * rays, uploaded once), lists their covered pixels once (roma_pixel_list) and records the
 * map's build and the public AO effect (roma_ao_effect) into its own command buffers. */
#include "frame.h"

#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app_common.h"
#include "app_image.h"
#include "hw_ray_tracing.h"
#include "map/map_internal.h" /* roma_map_record_steps: a build step alone (--growth) */
#include "reference.h"
#include "roma/ao_effect.h"
#include "roma/map.h"
#include "roma/pixel_list.h"
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

/* What both sides of a frame share: the G-buffer of the scene's default camera (the
 * reference's primary rays through the pixel centres, the points Embree shades), uploaded once
 * into the engine's images, the AO effect's output image, the covered pixels listed once in
 * each of the effect's two slots, and the same points for Embree's side. */
#define SLOTS 2u


typedef struct frame_setup {
    roma_context *ctx;
    uint32_t width, height;
    app_image in[3], out; /* position, shading normal, geometric normal; the AO (R32F) */
    roma_buffer readback;   /* the output's copy, for the mean AO */
    roma_pixel_list *list;  /* the covered pixels, listed in each slot */
    roma_ao_effect *ao;
    uint32_t records;       /* AO records so far: their slot alternates */
    roma_gbuffer_pixel *px; /* Embree's points */
    uint32_t *covered, count;
} frame_setup;

static void setup_destroy(frame_setup *s)
{
    if (s->ctx) {
        for (int i = 0; i < 3; ++i)
            app_image_destroy(s->ctx, &s->in[i]);
        app_image_destroy(s->ctx, &s->out);
        roma_buffer_destroy(s->ctx, &s->readback);
    }
    roma_pixel_list_destroy(s->list);
    roma_ao_effect_destroy(s->ao);
    free(s->px);
    free(s->covered);
    memset(s, 0, sizeof *s);
}

static roma_result setup_create(roma_context *ctx, const roma_scene *scene, uint32_t w, uint32_t h, frame_setup *s)
{
    memset(s, 0, sizeof *s);
    s->ctx = ctx;
    s->width = w;
    s->height = h;
    const size_t n = (size_t)w * h;
    s->px = calloc(n, sizeof *s->px);
    s->covered = malloc(sizeof *s->covered * n);
    float *albedo = malloc(sizeof(float) * 3 * n);
    roma_buffer staging = {0};
    roma_ref *ref = NULL;
    roma_camera cam;
    roma_scene_default_camera(scene, (float)w / (float)h, &cam);
    roma_result r = s->px && s->covered && albedo ? ROMA_SUCCESS : ROMA_ERROR_OUT_OF_HOST_MEMORY;
    /* The G-buffer: the reference's primary rays, straight into the upload buffer (one plane an image). */
    if (r == ROMA_SUCCESS)
        r = roma_buffer_create(ctx, 48ull * n, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, ROMA_MEMORY_UPLOAD, &staging);
    if (r == ROMA_SUCCESS)
        r = roma_ref_create(scene, NULL, &ref);
    float *host = staging.mapped;
    if (r == ROMA_SUCCESS)
        r = roma_ref_render_gbuffer(ref, &cam, w, h, &(roma_ref_gbuffer){host, host + 4 * n, host + 8 * n, albedo});
    roma_ref_destroy(ref);
    for (size_t p = 0; p < n && r == ROMA_SUCCESS; ++p) {
        const int hit = host[4 * p + 3] > 0.0f;
        for (int a = 0; a < 3; ++a) {
            s->px[p].position_t[a] = host[4 * p + a];
            s->px[p].shading_normal[a] = host[4 * (n + p) + a];
            s->px[p].geometric_normal[a] = host[4 * (2 * n + p) + a];
        }
        s->px[p].position_t[3] = hit ? 1.0f : INFINITY;
        if (hit)
            s->covered[s->count++] = (uint32_t)p;
    }
    const VkImageUsageFlags in_usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    for (int i = 0; i < 3 && r == ROMA_SUCCESS; ++i)
        r = app_image_create(ctx, w, h, VK_FORMAT_R32G32B32A32_SFLOAT, in_usage, &s->in[i]);
    if (r == ROMA_SUCCESS)
        r = app_image_create(ctx, w, h, VK_FORMAT_R32_SFLOAT,
                         VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, &s->out);
    if (r == ROMA_SUCCESS)
        r = roma_buffer_create(ctx, 4ull * n, VK_BUFFER_USAGE_TRANSFER_DST_BIT, ROMA_MEMORY_READBACK, &s->readback);
    if (r == ROMA_SUCCESS)
        r = roma_pixel_list_create(ctx, &(roma_pixel_list_desc){.frames_in_flight = SLOTS}, &s->list);
    if (r == ROMA_SUCCESS)
        r = roma_ao_effect_create(ctx, &(roma_ao_effect_desc){.frames_in_flight = SLOTS}, &s->ao);
    /* The upload, the output to GENERAL and the list of each slot: once, untimed. */
    VkCommandBuffer cmd;
    if (r == ROMA_SUCCESS)
        r = roma_begin_one_shot(ctx, &cmd);
    if (r == ROMA_SUCCESS) {
        for (int i = 0; i < 3; ++i) {
            app_image_barrier(cmd, s->in[i].image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                   VK_PIPELINE_STAGE_2_NONE, 0, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
            const VkBufferImageCopy copy = {.bufferOffset = 16ull * n * (VkDeviceSize)i,
                                            .imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                                            .imageExtent = {w, h, 1}};
            vkCmdCopyBufferToImage(cmd, staging.buffer, s->in[i].image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                                   &copy);
            app_image_barrier(cmd, s->in[i].image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                   VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT,
                   VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                   VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
        }
        app_image_barrier(cmd, s->out.image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_NONE, 0,
               VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
        for (uint32_t slot = 0; slot < SLOTS && r == ROMA_SUCCESS; ++slot) {
            const roma_pixel_list_images li = {.width = w, .height = h, .position = s->in[0].view};
            r = roma_pixel_list_record(s->list, cmd, slot, &li);
        }
        roma_result sr = roma_submit_one_shot(ctx, cmd);
        if (r == ROMA_SUCCESS)
            r = sr;
    }
    roma_buffer_destroy(ctx, &staging);
    free(albedo);
    if (r != ROMA_SUCCESS) {
        fprintf(stderr, "roma-bench: frame setup failed: %s\n", roma_result_string(r));
        setup_destroy(s);
    }
    return r;
}

/* One submission of `what` (bit 0: map build, bit 1: the AO effect over the listed pixels),
 * submit to fence. The records alternate between the effect's two slots, each listed once:
 * every record starts a new frame of its slot, whatever settings->frame (the samples). */
static double roma_frame_ms(frame_setup *s, roma_map *map, const roma_ao_settings *settings, uint32_t frame, int what)
{
    VkCommandBuffer cmd;
    if (roma_begin_one_shot(s->ctx, &cmd) != ROMA_SUCCESS)
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
        const roma_ao_images images = {.width = s->width, .height = s->height, .position = s->in[0].view,
                                       .normal = s->in[1].view, .geometric_normal = s->in[2].view,
                                       .output = s->out.view, .pixels = s->list};
        r = roma_ao_effect_record(s->ao, cmd, s->records++ % SLOTS, map, &images, settings);
        /* the next record (or the copy for the mean) after this one's writes */
        app_image_barrier(cmd, s->out.image, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_GENERAL,
               VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
               VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_COPY_BIT,
               VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT |
                   VK_ACCESS_2_TRANSFER_READ_BIT);
    }
    return roma_bench_submit_ms(s->ctx, cmd, r);
}

/* The mean of the last AO record's output over the covered pixels (a copy, untimed). */
static roma_result roma_mean_ao(frame_setup *s, double *mean)
{
    VkCommandBuffer cmd;
    roma_result r = roma_begin_one_shot(s->ctx, &cmd);
    if (r != ROMA_SUCCESS)
        return r;
    app_image_barrier(cmd, s->out.image, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
           VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_COPY_BIT,
           VK_ACCESS_2_TRANSFER_READ_BIT);
    const VkBufferImageCopy copy = {.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                                    .imageExtent = {s->width, s->height, 1}};
    vkCmdCopyImageToBuffer(cmd, s->out.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, s->readback.buffer, 1, &copy);
    app_image_barrier(cmd, s->out.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL,
           VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
           VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                            VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
    r = roma_submit_one_shot(s->ctx, cmd);
    if (r == ROMA_SUCCESS)
        r = roma_buffer_invalidate(s->ctx, &s->readback);
    double sum = 0.0;
    for (uint32_t i = 0; i < s->count && r == ROMA_SUCCESS; ++i)
        sum += ((const float *)s->readback.mapped)[s->covered[i]];
    *mean = s->count ? sum / s->count : 0.0;
    return r;
}

double roma_bench_submit_ms(roma_context *ctx, VkCommandBuffer cmd, roma_result recorded)
{
    double t0 = roma_app_now_ms();
    roma_result s = roma_submit_one_shot(ctx, cmd);
    double ms = roma_app_now_ms() - t0;
    return recorded == ROMA_SUCCESS && s == ROMA_SUCCESS ? ms : NAN;
}

/* The AO settings of d: the public defaults (offset, skipped start walked exactly through the
 * BOM), d's radius (<= 0: unbounded), seed 7, samples frame 0's (those Embree draws). */
static roma_ao_settings ao_settings(const roma_bench_frame_desc *d, uint32_t spp)
{
    return (roma_ao_settings){.samples = spp, .radius = d->radius > 0.0f && isfinite(d->radius) ? d->radius : 0.0f,
                              .seed = SEED, .frame = 0, .start = d->ao_start, .trace = d->ao_trace};
}

int roma_bench_frame(roma_context *ctx, const roma_scene *scene, const roma_bench_frame_desc *d, FILE *csv)
{
    const uint32_t w = d->width, h = d->height, runs = d->runs ? d->runs : 5;
    frame_setup fs;
    roma_map *map = NULL;
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
    if (r != ROMA_SUCCESS) {
        fprintf(stderr, "roma-bench: frame setup failed: %s\n", roma_result_string(r));
        goto done;
    }
    roma_map_info mi;
    roma_map_frame_desc warm = {.frame = 0, .seed = SEED, .jitter_grid = 1, .jitter_directions = 1};
    roma_map_build(map, &warm, NULL);
    roma_map_get_info(map, &mi);
    printf("\nDynamic AO frame, %ux%u (%u pixels, %u covered), RES %u, A %u, AO radius %s%s; medians of %u runs.\n"
           "ROMA: one submission, host-observed, the public AO effect over the covered pixels (listed once);\n"
           "Embree: wall clock, all cores, same points and samples. G-buffer: the reference's primary rays,\n"
           "uploaded once, counted by neither side.\n\n"
           "| spp | ROMA build ms | ROMA AO ms | ROMA frame ms | Embree BVH ms | Embree AO ms | Embree frame ms "
           "| ROMA speed-up | AO mean ROMA / Embree |\n|---|---|---|---|---|---|---|---|---|\n",
           w, h, w * h, count, d->resolution, d->angular, d->radius > 0.0f ? "bounded" : "unbounded",
           d->ao_trace == ROMA_AO_TRACE_SURFACES   ? ", rays through the surface grid"
           : d->ao_start == ROMA_AO_START_SURFACES ? ", start through the surface grid"
                                                   : "",
           runs);
    static const uint32_t spps[2] = {1, 4};
    status = 0;
    for (int si = 0; si < 2 && status == 0; ++si) {
        const uint32_t spp = spps[si];
        const roma_ao_settings settings = ao_settings(d, spp);
        double ref_mean = 0.0;
        for (uint32_t k = 0; k < runs; ++k) {
            /* frames 1 + 2k and 2 + 2k: each build a new jitter (frame 0 warmed the map) */
            samples[k] = roma_frame_ms(&fs, map, &settings, 1 + 2 * k, 1);
            samples[runs + k] = roma_frame_ms(&fs, map, &settings, 1 + 2 * k, 2);
            samples[2 * runs + k] = roma_frame_ms(&fs, map, &settings, 2 + 2 * k, 3);
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
        double roma_mean = 0.0;
        if (status == 0 && roma_mean_ao(&fs, &roma_mean) != ROMA_SUCCESS)
            status = 1;
        if (status != 0)
            break;
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
    if (status == 0) {
        const roma_bench_hwrt_frame_desc hd = {.device = d->hwrt, .why = d->hwrt_why, .px = px, .covered = covered,
                                               .count = count, .radius = d->radius, .seed = SEED, .runs = runs};
        status = roma_bench_hwrt_frame(ctx, scene, &hd, csv);
    }
done:
    roma_map_destroy(map);
    setup_destroy(&fs);
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
    roma_result r = samples ? ROMA_SUCCESS : ROMA_ERROR_OUT_OF_HOST_MEMORY;
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
        roma_map_frame_desc warm = {.frame = 0, .seed = SEED, .jitter_grid = 1, .jitter_directions = 1};
        roma_map_build(map, &warm, NULL);
        roma_ao_settings settings = ao_settings(d, 1);
        /* the AO pipeline's first use (at this map's cascade variant), untimed */
        if (isnan(roma_frame_ms(&fs, map, &settings, 0, 2)))
            r = ROMA_ERROR_VULKAN;
        for (uint32_t k = 0; k < runs && r == ROMA_SUCCESS; ++k) {
            samples[k] = step_ms(ctx, map, k, ROMA_MAP_STEP_VOXELIZE);
            samples[runs + k] = step_ms(ctx, map, k, ROMA_MAP_STEP_ROTATE);
            settings.frame = k;
            samples[2 * runs + k] = roma_frame_ms(&fs, map, &settings, k, 2);
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
    setup_destroy(&fs);
    free(samples);
    return r == ROMA_SUCCESS ? 0 : 1;
}
