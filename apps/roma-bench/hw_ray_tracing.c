#include "hw_ray_tracing.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "app_common.h"
#include "frame.h"
#include "reference.h"
#include "roma/sampling.h"
#include "vulkan/upload.h"
#include "vulkan/vk_internal.h"

/* One timed submission: the step alone (trace or build) between two timestamps. Returns the
 * host-observed ms (submit to fence) and sets *gpu_ms from the timestamps. */
static double timed(roma_context *ctx, roma_hwrt *h, roma_gpu_timer *timer, const roma_bench_hwrt_desc *d, int step,
                    double *gpu_ms)
{
    VkCommandBuffer cmd;
    *gpu_ms = NAN;
    if (roma_begin_one_shot(ctx, &cmd) != ROMA_SUCCESS)
        return NAN;
    roma_gpu_timer_reset(timer, cmd);
    const uint32_t scope = roma_gpu_timer_begin(timer, cmd, "hwrt");
    if (step == 2) {
        roma_hwrt_record_build(h, cmd);
    } else {
        /* After earlier traces (ROMA's or the hardware's) that wrote the same hits. */
        roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_RAY_TRACING_SHADER_BIT_KHR,
                                VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_RAY_TRACING_SHADER_BIT_KHR,
                                VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
        roma_hwrt_record_trace(h, cmd, d->rays, d->hits, d->count, step);
    }
    roma_gpu_timer_end(timer, cmd, scope);
    const double ms = roma_bench_submit_ms(ctx, cmd, ROMA_SUCCESS);
    roma_gpu_timing t;
    uint32_t n = 1;
    if (roma_gpu_timer_read(timer, &t, &n) == ROMA_SUCCESS && n == 1)
        *gpu_ms = t.milliseconds;
    return ms;
}

/* The hits of the last trace, read back. */
static roma_result read_hits(roma_context *ctx, const roma_bench_hwrt_desc *d, roma_hit *out)
{
    roma_buffer rb = {0};
    const VkDeviceSize bytes = sizeof(roma_hit) * (VkDeviceSize)d->count;
    VkCommandBuffer cmd;
    roma_result r = roma_buffer_create(ctx, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, ROMA_MEMORY_READBACK, &rb);
    if (r == ROMA_SUCCESS)
        r = roma_begin_one_shot(ctx, &cmd);
    if (r == ROMA_SUCCESS) {
        roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_RAY_TRACING_SHADER_BIT_KHR, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                                VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
        vkCmdCopyBuffer(cmd, d->hits_buffer, rb.buffer, 1, &(VkBufferCopy){0, 0, bytes});
        roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                                VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
        r = roma_submit_one_shot(ctx, cmd);
    }
    if (r == ROMA_SUCCESS)
        r = roma_buffer_invalidate(ctx, &rb);
    if (r == ROMA_SUCCESS)
        memcpy(out, rb.mapped, (size_t)bytes);
    roma_buffer_destroy(ctx, &rb);
    return r;
}

int roma_bench_hwrt(roma_context *ctx, const roma_scene *scene, roma_gpu_timer *timer, const roma_bench_hwrt_desc *d,
                    FILE *csv)
{
    static const char *const names[2] = {"hardware ray tracing any-hit", "hardware ray tracing closest-hit"};
    if (!d->device) {
        printf("| hardware ray tracing (VK_KHR_ray_tracing_pipeline) | skipped: %s | - | - | - | - |\n",
               d->why && *d->why ? d->why : "no device offers it");
        return 0;
    }
    roma_hwrt *h = NULL;
    roma_result r = roma_hwrt_create(ctx, d->device, scene, &h);
    if (r != ROMA_SUCCESS) {
        fprintf(stderr, "roma-bench: hardware ray tracing: %s\n", roma_result_string(r));
        return 1;
    }
    const uint32_t runs = d->runs ? d->runs : 5;
    double *samples = malloc(sizeof(double) * 2 * runs);
    roma_hit *hits = malloc(sizeof(roma_hit) * (size_t)d->count);
    int status = !samples || !hits;
    double build_ms[2] = {NAN, NAN};
    uint32_t agree[2] = {0, 0}, hits_found[2] = {0, 0};
    double t_error = 0.0;
    uint32_t t_compared = 0;
    for (int c = 0; c < 3 && !status; ++c) {
        double gpu;
        timed(ctx, h, timer, d, c, &gpu); /* warm-up */
        for (uint32_t k = 0; k < runs; ++k)
            samples[runs + k] = timed(ctx, h, timer, d, c, &samples[k]);
        const double ts = roma_app_median(samples, (int)runs), host = roma_app_median(samples + runs, (int)runs);
        if (c == 2) { /* the acceleration structures rebuilt, as every frame of a dynamic scene */
            build_ms[0] = ts, build_ms[1] = host;
            break;
        }
        if (read_hits(ctx, d, hits) != ROMA_SUCCESS) {
            status = 1;
            break;
        }
        for (uint32_t i = 0; i < d->count; ++i) {
            const int hw = (hits[i].info & ROMA_HIT_FLAG) != 0;
            const int em = c == 0 ? d->embree_occluded[i] != 0 : isfinite(d->embree_t[i]);
            agree[c] += hw == em;
            hits_found[c] += hw;
            if (c == 1 && hw && em) {
                t_error += fabs((double)hits[i].t - (double)d->embree_t[i]);
                ++t_compared;
            }
        }
        const double ms = d->cpu_device ? host : ts;
        const double base = d->embree_ms[c];
        printf("| %s | %.3f | %.2f | - | %.2f | %.2fx (vs %s) |\n", names[c], ts, host, d->count / ms / 1e3,
               base / ms, c == 1 ? "rtcIntersect" : "rtcOccluded");
        if (csv) {
            fprintf(csv, "trace,%s timestamp,0,0,%.6f,ms\n", names[c], ts);
            fprintf(csv, "trace,%s host,0,0,%.6f,ms\n", names[c], host);
        }
    }
    if (!status) {
        printf("\nhardware ray tracing: both acceleration structures rebuilt (a dynamic scene's frame) in %.3f ms "
               "(timestamps), %.2f ms host-observed; against Embree on the same rays: any-hit answers agree on "
               "%.4f%% (%u hits), closest-hit on %.4f%% (%u hits), mean |t - t_embree| %.3g over %u rays both hit\n",
               build_ms[0], build_ms[1], 100.0 * agree[0] / d->count, hits_found[0], 100.0 * agree[1] / d->count,
               hits_found[1], t_compared ? t_error / t_compared : 0.0, t_compared);
        if (csv) {
            fprintf(csv, "trace,hardware ray tracing build timestamp,0,0,%.6f,ms\n", build_ms[0]);
            fprintf(csv, "trace,hardware ray tracing any-hit agreement,0,0,%.6f,percent\n", 100.0 * agree[0] / d->count);
            fprintf(csv, "trace,hardware ray tracing closest-hit agreement,0,0,%.6f,percent\n",
                    100.0 * agree[1] / d->count);
        }
    }
    free(samples);
    free(hits);
    roma_hwrt_destroy(h);
    return status;
}

/* One submission: the structures rebuilt (what & 1) and the AO rays traced (what & 2). */
static double frame_ms(roma_context *ctx, roma_hwrt *h, VkDeviceAddress rays, VkDeviceAddress hits, uint32_t n,
                       int what)
{
    VkCommandBuffer cmd;
    if (roma_begin_one_shot(ctx, &cmd) != ROMA_SUCCESS)
        return NAN;
    if (what & 1)
        roma_hwrt_record_build(h, cmd);
    if (what & 2) {
        /* After the last submission's trace, which wrote the same hits. */
        roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_RAY_TRACING_SHADER_BIT_KHR, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                                VK_PIPELINE_STAGE_2_RAY_TRACING_SHADER_BIT_KHR, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
        roma_hwrt_record_trace(h, cmd, rays, hits, n, 0);
    }
    return roma_bench_submit_ms(ctx, cmd, ROMA_SUCCESS);
}

int roma_bench_hwrt_rays(roma_context *ctx, roma_hwrt *h, const roma_ray *rays, uint32_t n, uint32_t runs,
                         roma_hit *hits, double ms[3])
{
    runs = runs ? runs : 1;
    double *samples = malloc(sizeof(double) * 3 * runs);
    roma_buffer ray_buf = {0}, hit_buf = {0};
    int status = !samples ||
                 roma_buffer_create_filled(ctx, sizeof(roma_ray) * (VkDeviceSize)(n ? n : 1),
                                           VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT,
                                           rays, &ray_buf) != ROMA_SUCCESS ||
                 roma_buffer_create(ctx, sizeof(roma_hit) * (VkDeviceSize)(n ? n : 1),
                                    VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT |
                                        VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                    ROMA_MEMORY_DEVICE, &hit_buf) != ROMA_SUCCESS;
    if (!status)
        frame_ms(ctx, h, ray_buf.address, hit_buf.address, n, 3); /* warm-up */
    for (uint32_t k = 0; k < runs && !status; ++k) {
        samples[k] = frame_ms(ctx, h, ray_buf.address, hit_buf.address, n, 1);
        samples[runs + k] = frame_ms(ctx, h, ray_buf.address, hit_buf.address, n, 2);
        samples[2 * runs + k] = frame_ms(ctx, h, ray_buf.address, hit_buf.address, n, 3);
        status = !isfinite(samples[k] + samples[runs + k] + samples[2 * runs + k]);
    }
    const roma_bench_hwrt_desc rd = {.hits_buffer = hit_buf.buffer, .count = n};
    if (!status && n)
        status = read_hits(ctx, &rd, hits) != ROMA_SUCCESS;
    for (int c = 0; c < 3 && !status; ++c)
        ms[c] = roma_app_median(samples + c * runs, (int)runs);
    roma_buffer_destroy(ctx, &ray_buf);
    roma_buffer_destroy(ctx, &hit_buf);
    free(samples);
    return status;
}

/* The rays of d's points, made by `make` (the reference's AO samples or light segments; 0:
 * none for that one), each with the index of its point. */
typedef int (*ray_maker)(const roma_ref *ref, const roma_gbuffer_pixel *p, uint32_t pixel, uint32_t k,
                         const void *user, roma_ray *out);

static int ao_ray(const roma_ref *ref, const roma_gbuffer_pixel *p, uint32_t pixel, uint32_t k, const void *user,
                  roma_ray *r)
{
    const roma_bench_hwrt_ao_desc *d = user;
    r->tmin = 0.0f;
    return roma_ref_ao_ray(ref, p->position_t, p->geometric_normal, p->shading_normal, d->radius, d->seed, pixel, k,
                           r->origin, r->dir, &r->tmax);
}

static int light_ray(const roma_ref *ref, const roma_gbuffer_pixel *p, uint32_t pixel, uint32_t k, const void *user,
                     roma_ray *r)
{
    (void)pixel;
    const roma_bench_hwrt_lights_desc *d = user;
    r->tmin = 0.0f;
    return roma_ref_light_segment(ref, p->position_t, p->geometric_normal, p->shading_normal,
                                  &d->light_positions[3 * (size_t)k], r->origin, r->dir, &r->tmax);
}

/* out[i]: the share of point i's `per_point` rays that miss (rays `make` declines count as
 * blocked), traced after both structures are rebuilt. */
static int open_share(roma_context *ctx, roma_hwrt *h, const roma_ref *ref, const roma_gbuffer_pixel *px,
                      const uint32_t *covered, uint32_t count, uint32_t per_point, ray_maker make, const void *user,
                      uint32_t runs, float *out, double ms[3], uint32_t *ray_count)
{
    const size_t wanted = (size_t)count * per_point, max_rays = wanted > 0 ? wanted : 1;
    if (max_rays > ROMA_BENCH_HWRT_MAX_RAYS) {
        fprintf(stderr, "roma-bench: %zu hardware rays are more than a batch takes (%u)\n", max_rays,
                ROMA_BENCH_HWRT_MAX_RAYS);
        return 1;
    }
    roma_ray *rays = malloc(sizeof *rays * max_rays);
    uint32_t *owner = malloc(sizeof *owner * max_rays);
    roma_hit *hits = malloc(sizeof *hits * max_rays);
    int status = !rays || !owner || !hits;
    uint32_t n = 0;
    for (uint32_t i = 0; i < count && !status; ++i) {
        const uint32_t pixel = covered ? covered[i] : i;
        for (uint32_t k = 0; k < per_point; ++k)
            if (make(ref, &px[pixel], pixel, k, user, &rays[n]))
                owner[n++] = i;
    }
    if (!status)
        status = roma_bench_hwrt_rays(ctx, h, rays, n, runs, hits, ms);
    for (uint32_t i = 0; i < count && !status; ++i)
        out[i] = 0.0f;
    for (uint32_t r = 0; r < n && !status; ++r)
        out[owner[r]] += (hits[r].info & ROMA_HIT_FLAG) ? 0.0f : 1.0f / (float)per_point;
    *ray_count = n;
    free(rays);
    free(owner);
    free(hits);
    return status;
}

int roma_bench_hwrt_ao(roma_context *ctx, roma_hwrt *h, const roma_ref *ref, const roma_bench_hwrt_ao_desc *d,
                       float *ao, double ms[3], uint32_t *ray_count)
{
    return open_share(ctx, h, ref, d->px, d->covered, d->count, d->spp ? d->spp : 1, ao_ray, d, d->runs, ao, ms,
                      ray_count);
}

int roma_bench_hwrt_lights(roma_context *ctx, roma_hwrt *h, const roma_ref *ref, const roma_bench_hwrt_lights_desc *d,
                           float *share, double ms[3], uint32_t *ray_count)
{
    return open_share(ctx, h, ref, d->px, d->covered, d->count, d->light_count, light_ray, d, d->runs, share, ms,
                      ray_count);
}

/* The segments of the points for one trace (roma_ref_direct_segments' callback), in two
 * passes: the first counts the segments to trace (rays NULL), the second fills the rays with
 * their point and what each adds. A segment nothing can block (at its light) is added at
 * once, in the second pass. */
typedef struct direct_batch {
    roma_ray *rays;
    uint32_t *owner;
    float *add; /* 3 a ray */
    uint8_t *area;
    uint64_t n;
    uint32_t point;
    double *punctual, *area_sum; /* 3 a point */
} direct_batch;

static void collect_segment(void *user, const roma_ref_segment *s)
{
    direct_batch *b = user;
    if (!(s->tmax > 0.0f)) { /* at the light: seen */
        double *sum = s->area ? b->area_sum : b->punctual;
        for (int c = 0; c < 3 && b->rays; ++c)
            sum[3 * (size_t)b->point + c] += (double)s->add[c];
        return;
    }
    if (b->rays) {
        roma_ray *r = &b->rays[b->n];
        memcpy(r->origin, s->origin, sizeof r->origin);
        memcpy(r->dir, s->dir, sizeof r->dir);
        r->tmin = 0.0f;
        r->tmax = s->tmax;
        b->owner[b->n] = b->point;
        memcpy(&b->add[3 * (size_t)b->n], s->add, sizeof s->add);
        b->area[b->n] = (uint8_t)s->area;
    }
    ++b->n;
}

static void collect_segments(const roma_ref *ref, const roma_bench_hwrt_direct_desc *d, uint32_t spp, direct_batch *b)
{
    b->n = 0;
    for (uint32_t i = 0; i < d->count; ++i) {
        const uint32_t pixel = d->covered ? d->covered[i] : i;
        const roma_gbuffer_pixel *p = &d->px[pixel];
        b->point = i;
        roma_ref_direct_segments(ref, p->position_t, p->geometric_normal, p->shading_normal, spp, d->seed, pixel,
                                 collect_segment, b);
    }
}

int roma_bench_hwrt_direct(roma_context *ctx, roma_hwrt *h, const roma_ref *ref, const roma_bench_hwrt_direct_desc *d,
                           float *rgb, double ms[3], uint32_t *ray_count)
{
    const uint32_t spp = d->spp ? d->spp : 1;
    direct_batch b = {0};
    collect_segments(ref, d, spp, &b); /* the count */
    *ray_count = b.n > UINT32_MAX ? UINT32_MAX : (uint32_t)b.n;
    if (b.n > ROMA_BENCH_HWRT_MAX_RAYS) {
        fprintf(stderr, "roma-bench: %llu hardware rays of the direct light are more than a batch takes (%u)\n",
                (unsigned long long)b.n, ROMA_BENCH_HWRT_MAX_RAYS);
        return 1;
    }
    const size_t rays = b.n ? (size_t)b.n : 1, points = 3 * (size_t)(d->count ? d->count : 1);
    b.rays = malloc(sizeof *b.rays * rays);
    b.owner = malloc(sizeof *b.owner * rays);
    b.add = malloc(sizeof *b.add * 3 * rays);
    b.area = malloc(rays);
    b.punctual = calloc(points, sizeof(double));
    b.area_sum = calloc(points, sizeof(double));
    roma_hit *hits = malloc(sizeof *hits * rays);
    int status = !b.rays || !b.owner || !b.add || !b.area || !b.punctual || !b.area_sum || !hits;
    if (!status)
        collect_segments(ref, d, spp, &b); /* the same segments, filled */
    if (!status && b.n == 0) /* nothing to trace: every segment was at its light */
        ms[0] = ms[1] = ms[2] = 0.0;
    else if (!status)
        status = roma_bench_hwrt_rays(ctx, h, b.rays, (uint32_t)b.n, d->runs, hits, ms);
    for (uint64_t r = 0; r < b.n && !status; ++r) {
        if (hits[r].info & ROMA_HIT_FLAG)
            continue;
        double *sum = b.area[r] ? b.area_sum : b.punctual;
        for (int c = 0; c < 3; ++c)
            sum[3 * (size_t)b.owner[r] + c] += (double)b.add[3 * (size_t)r + c];
    }
    for (uint32_t i = 0; i < d->count && !status; ++i) {
        const roma_gbuffer_pixel *p = &d->px[d->covered ? d->covered[i] : i];
        for (int c = 0; c < 3; ++c) /* as roma_ref_direct_point: albedo / pi * irradiance */
            rgb[3 * (size_t)i + c] = (float)(p->albedo[c] / ROMA_PI *
                                             (b.punctual[3 * (size_t)i + c] + b.area_sum[3 * (size_t)i + c] / spp));
    }
    free(b.rays);
    free(b.owner);
    free(b.add);
    free(b.area);
    free(b.punctual);
    free(b.area_sum);
    free(hits);
    return status;
}

int roma_bench_hwrt_frame(roma_context *ctx, const roma_scene *scene, const roma_bench_hwrt_frame_desc *d, FILE *csv)
{
    if (!d->device) {
        printf("\nhardware ray tracing frame: skipped: %s\n", d->why && *d->why ? d->why : "no device offers it");
        return 0;
    }
    roma_ref *ref = NULL;
    roma_hwrt *h = NULL;
    float *ao = malloc(sizeof *ao * (d->count ? d->count : 1));
    int status = !ao || roma_ref_create(scene, NULL, &ref) != ROMA_SUCCESS ||
                 roma_hwrt_create(ctx, d->device, scene, &h) != ROMA_SUCCESS;
    if (!status)
        printf("\nThe same frame through hardware ray tracing: both acceleration structures rebuilt, then the AO rays "
               "of Embree's points and samples (made on the host from the reference's sequences and uploaded, "
               "untimed; samples below the geometric surface count as occluded, as Embree's), any hit; "
               "host-observed, medians of %u runs.\n\n| spp, hardware | rays | build ms | AO ms | frame ms | AO mean |\n"
               "|---|---|---|---|---|---|\n",
               d->runs);
    static const uint32_t spps[2] = {1, 4};
    for (int si = 0; si < 2 && !status; ++si) {
        const roma_bench_hwrt_ao_desc ad = {.px = d->px, .covered = d->covered, .count = d->count, .spp = spps[si],
                                            .radius = d->radius, .seed = d->seed, .runs = d->runs};
        double med[3], sum = 0.0;
        uint32_t n = 0;
        status = roma_bench_hwrt_ao(ctx, h, ref, &ad, ao, med, &n);
        if (status)
            break;
        for (uint32_t i = 0; i < d->count; ++i)
            sum += ao[i];
        printf("| %u (hardware) | %u | %.3f | %.3f | %.3f | %.3f |\n", spps[si], n, med[0], med[1], med[2],
               d->count ? sum / d->count : 0.0);
        if (csv) {
            static const char *names[3] = {"hwrt_build", "hwrt_ao", "hwrt_frame"};
            for (int c = 0; c < 3; ++c)
                fprintf(csv, "frame,%s spp %u,0,0,%.6f,ms\n", names[c], spps[si], med[c]);
        }
    }
    if (status)
        fprintf(stderr, "roma-bench: the hardware ray-tracing frame failed\n");
    roma_hwrt_destroy(h);
    roma_ref_destroy(ref);
    free(ao);
    return status;
}
