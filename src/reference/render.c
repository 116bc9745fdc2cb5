/* Reference images: one primary ray through each pixel centre, the point
 * estimators at the hit, rows handed out to a pthread worker pool. Every pixel
 * is a pure function of its inputs, so images do not depend on the threads. */
#define _POSIX_C_SOURCE 200809L

#include <pthread.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "reference_internal.h"
#include "util/log.h"

#define ROMA_REF_MAX_IMAGE_SIZE 16384u
#define ROMA_REF_DEFAULT_SPP 64u

/* --- Worker pool --- */

typedef struct pool {
    uint32_t count;
    roma_ref_task_fn fn;
    void *ctx;
    atomic_uint next;
    int track;     /* count finished items for progress */
    uint32_t done; /* guarded by mutex */
    pthread_mutex_t mutex;
    pthread_cond_t cond;
} pool;

static void *pool_worker(void *arg)
{
    pool *p = arg;
    for (;;) {
        unsigned item = atomic_fetch_add(&p->next, 1u);
        if (item >= p->count)
            break;
        p->fn(p->ctx, item);
        if (p->track) {
            pthread_mutex_lock(&p->mutex);
            ++p->done;
            pthread_cond_signal(&p->cond);
            pthread_mutex_unlock(&p->mutex);
        }
    }
    return NULL;
}

static void run_inline(uint32_t count, roma_ref_task_fn fn, void *ctx, roma_progress_fn progress,
                       void *user)
{
    for (uint32_t i = 0; i < count; ++i) {
        fn(ctx, i);
        if (progress)
            progress((float)(i + 1) / (float)count, user);
    }
}

void roma_ref_parallel_for(const roma_ref *ref, uint32_t count, roma_ref_task_fn fn, void *ctx,
                           roma_progress_fn progress, void *progress_user_data)
{
    if (count == 0)
        return;
    uint32_t threads = ref->thread_count < count ? ref->thread_count : count;
    pthread_t *tids = threads > 1 ? malloc(threads * sizeof *tids) : NULL;
    if (!tids) {
        run_inline(count, fn, ctx, progress, progress_user_data);
        return;
    }
    pool p;
    memset(&p, 0, sizeof p);
    p.count = count;
    p.fn = fn;
    p.ctx = ctx;
    atomic_init(&p.next, 0u);
    p.track = progress != NULL;
    if (pthread_mutex_init(&p.mutex, NULL) != 0) {
        free(tids);
        run_inline(count, fn, ctx, progress, progress_user_data);
        return;
    }
    if (pthread_cond_init(&p.cond, NULL) != 0) {
        pthread_mutex_destroy(&p.mutex);
        free(tids);
        run_inline(count, fn, ctx, progress, progress_user_data);
        return;
    }
    uint32_t started = 0;
    while (started < threads && pthread_create(&tids[started], NULL, pool_worker, &p) == 0)
        ++started;
    if (started < threads)
        roma_logf(&ref->logger, ROMA_LOG_WARNING,
                  "reference: started %u of %u worker threads; continuing with fewer", started,
                  threads);
    if (started == 0) {
        /* No thread could start: the caller does all the work. */
        run_inline(count, fn, ctx, progress, progress_user_data);
    } else if (progress) {
        /* Only this thread calls progress; workers just signal finished items. */
        uint32_t reported = 0;
        pthread_mutex_lock(&p.mutex);
        while (reported < count) {
            while (p.done == reported)
                pthread_cond_wait(&p.cond, &p.mutex);
            reported = p.done;
            pthread_mutex_unlock(&p.mutex);
            progress((float)reported / (float)count, progress_user_data);
            pthread_mutex_lock(&p.mutex);
        }
        pthread_mutex_unlock(&p.mutex);
    }
    for (uint32_t i = 0; i < started; ++i)
        pthread_join(tids[i], NULL);
    pthread_cond_destroy(&p.cond);
    pthread_mutex_destroy(&p.mutex);
    free(tids);
}

/* --- Image rendering --- */

typedef struct render_job {
    const roma_ref *ref;
    const roma_ref_render_desc *desc;
    roma_camera_frame frame;
    uint32_t spp;
    roma_ref_images *images;
} render_job;

static void render_row(void *ctx, uint32_t y)
{
    const render_job *job = ctx;
    const roma_ref_render_desc *d = job->desc;
    roma_ref_images *im = job->images;
    for (uint32_t x = 0; x < d->width; ++x) {
        uint32_t pixel = y * d->width + x;
        float org[3], dir[3];
        /* Pixel centre, no jitter: matches a rasterised G-buffer. */
        roma_camera_ray(&job->frame, (float)x + 0.5f, (float)y + 0.5f, org, dir);
        roma_ref_hit hit;
        if (!roma_ref_intersect(job->ref, org, dir, 0.0f, INFINITY, &hit)) {
            if (im->ao.pixels)
                im->ao.pixels[pixel] = 1.0f;
            continue;
        }
        im->coverage.pixels[pixel] = 1.0f;
        const float *p = hit.position, *gn = hit.geometric_normal, *n = hit.shading_normal;
        const float *albedo = roma_ref_albedo(job->ref, hit.triangle);
        if (im->ao.pixels)
            im->ao.pixels[pixel] =
                roma_ref_ao_point(job->ref, p, gn, n, d->ao_radius, job->spp, d->seed, pixel);
        if (im->direct.pixels)
            roma_ref_direct_point(job->ref, p, gn, n, albedo, job->spp, d->seed, pixel,
                                  &im->direct.pixels[3 * (size_t)pixel]);
        if (im->gi.pixels)
            roma_ref_indirect_point(job->ref, p, gn, n, albedo, job->spp, d->seed, pixel,
                                    &im->gi.pixels[3 * (size_t)pixel]);
        if (im->lights.pixels)
            im->lights.pixels[pixel] = (float)roma_ref_count_visible_lights(
                job->ref, p, gn, n, d->many_light_positions, d->many_light_count);
    }
}

/* --- G-buffer --- */

typedef struct gbuffer_job {
    const roma_ref *ref;
    roma_camera_frame frame;
    uint32_t width;
    const roma_ref_gbuffer *out;
} gbuffer_job;

static void gbuffer_row(void *ctx, uint32_t y)
{
    const gbuffer_job *job = ctx;
    const roma_ref_gbuffer *g = job->out;
    for (uint32_t x = 0; x < job->width; ++x) {
        const size_t i = (size_t)y * job->width + x;
        float org[3], dir[3];
        roma_camera_ray(&job->frame, (float)x + 0.5f, (float)y + 0.5f, org, dir);
        roma_ref_hit hit;
        const int covered = roma_ref_intersect(job->ref, org, dir, 0.0f, INFINITY, &hit);
        const float *albedo = covered ? roma_ref_albedo(job->ref, hit.triangle) : NULL;
        for (int c = 0; c < 3; ++c) {
            g->position[4 * i + c] = covered ? hit.position[c] : 0.0f;
            g->normal[4 * i + c] = covered ? hit.shading_normal[c] : 0.0f;
            g->geometric_normal[4 * i + c] = covered ? hit.geometric_normal[c] : 0.0f;
            g->albedo[3 * i + c] = covered ? albedo[c] : 0.0f;
        }
        g->position[4 * i + 3] = covered ? 1.0f : 0.0f;
        g->normal[4 * i + 3] = g->geometric_normal[4 * i + 3] = 0.0f;
    }
}

roma_result roma_ref_render_gbuffer(const roma_ref *ref, const roma_camera *camera, uint32_t width, uint32_t height,
                                    const roma_ref_gbuffer *out)
{
    const roma_logger *logger = ref ? &ref->logger : NULL;
    if (!ref || !camera || !out || !out->position || !out->normal || !out->geometric_normal || !out->albedo)
        return roma_fail(logger, ROMA_ERROR_INVALID_ARGUMENT, "roma_ref_render_gbuffer: NULL argument");
    gbuffer_job job = {.ref = ref, .width = width, .out = out};
    if (width < 1 || height < 1 || !roma_camera_make_frame(camera, width, height, &job.frame))
        return roma_fail(logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_ref_render_gbuffer: empty image or degenerate camera");
    roma_ref_parallel_for(ref, height, gbuffer_row, &job, NULL, NULL);
    return ROMA_SUCCESS;
}

static roma_result alloc_image(const roma_ref *ref, roma_image *image, const roma_ref_render_desc *d,
                               uint32_t channels, const char *name)
{
    roma_result r = roma_image_alloc(image, d->width, d->height, channels);
    if (r != ROMA_SUCCESS)
        return roma_fail(&ref->logger, r, "roma_ref_render: cannot allocate the %ux%u %s image (%s)",
                         d->width, d->height, name, roma_result_string(r));
    return ROMA_SUCCESS;
}

roma_result roma_ref_render(const roma_ref *ref, const roma_ref_render_desc *desc,
                            roma_ref_images *out_images)
{
    const roma_logger *logger = ref ? &ref->logger : NULL;
    if (out_images)
        memset(out_images, 0, sizeof *out_images);
    if (!ref || !desc || !out_images)
        return roma_fail(logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_ref_render: ref, desc and out_images must not be NULL");
    if (desc->width < 1 || desc->width > ROMA_REF_MAX_IMAGE_SIZE || desc->height < 1 ||
        desc->height > ROMA_REF_MAX_IMAGE_SIZE)
        return roma_fail(logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_ref_render: image size %ux%u is outside 1..%u", desc->width,
                         desc->height, ROMA_REF_MAX_IMAGE_SIZE);
    const uint32_t known = ROMA_EFFECT_AO | ROMA_EFFECT_DIRECT | ROMA_EFFECT_GI | ROMA_EFFECT_LIGHTS;
    if (desc->effects & ~known)
        return roma_fail(logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_ref_render: unknown effect bits 0x%x", desc->effects & ~known);
    if ((desc->effects & ROMA_EFFECT_LIGHTS) && !desc->many_light_positions)
        return roma_fail(logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_ref_render: ROMA_EFFECT_LIGHTS needs many_light_positions");
    if (isnan(desc->ao_radius))
        return roma_fail(logger, ROMA_ERROR_INVALID_ARGUMENT, "roma_ref_render: ao_radius is NaN");

    render_job job;
    memset(&job, 0, sizeof job);
    if (!roma_camera_make_frame(&desc->camera, desc->width, desc->height, &job.frame))
        return roma_fail(logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_ref_render: degenerate camera (eye == target, up parallel to the "
                         "view direction, or non-finite values)");
    job.ref = ref;
    job.desc = desc;
    job.spp = desc->spp ? desc->spp : ROMA_REF_DEFAULT_SPP;
    job.images = out_images;

    roma_result r = alloc_image(ref, &out_images->coverage, desc, 1, "coverage");
    if (r == ROMA_SUCCESS && (desc->effects & ROMA_EFFECT_AO))
        r = alloc_image(ref, &out_images->ao, desc, 1, "AO");
    if (r == ROMA_SUCCESS && (desc->effects & ROMA_EFFECT_DIRECT))
        r = alloc_image(ref, &out_images->direct, desc, 3, "direct");
    if (r == ROMA_SUCCESS && (desc->effects & ROMA_EFFECT_GI))
        r = alloc_image(ref, &out_images->gi, desc, 3, "GI");
    if (r == ROMA_SUCCESS && (desc->effects & ROMA_EFFECT_LIGHTS))
        r = alloc_image(ref, &out_images->lights, desc, 1, "lights");
    if (r != ROMA_SUCCESS) {
        roma_ref_images_free(out_images);
        return r;
    }

    roma_ref_parallel_for(ref, desc->height, render_row, &job, desc->progress,
                          desc->progress_user_data);
    return ROMA_SUCCESS;
}

void roma_ref_images_free(roma_ref_images *images)
{
    if (!images)
        return;
    roma_image_free(&images->ao);
    roma_image_free(&images->direct);
    roma_image_free(&images->gi);
    roma_image_free(&images->lights);
    roma_image_free(&images->coverage);
}
