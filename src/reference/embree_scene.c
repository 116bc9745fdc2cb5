/* Embree device and scene for the reference tracer, single-ray queries and
 * their multithreaded batch versions. */
#define _POSIX_C_SOURCE 200809L

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "reference_internal.h"
#include "util/log.h"

/* Upper bound on worker threads; far above any machine this runs on. */
#define ROMA_REF_MAX_THREADS 1024u
/* Rays per work item in the batch queries. */
#define ROMA_REF_BATCH_CHUNK 4096u

static const char *rtc_error_name(enum RTCError code)
{
    switch (code) {
    case RTC_ERROR_NONE: return "no error";
    case RTC_ERROR_UNKNOWN: return "unknown error";
    case RTC_ERROR_INVALID_ARGUMENT: return "invalid argument";
    case RTC_ERROR_INVALID_OPERATION: return "invalid operation";
    case RTC_ERROR_OUT_OF_MEMORY: return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU: return "unsupported CPU";
    case RTC_ERROR_CANCELLED: return "cancelled";
    }
    return "unrecognised error";
}

static roma_result rtc_error_result(enum RTCError code)
{
    switch (code) {
    case RTC_ERROR_NONE: return ROMA_SUCCESS;
    case RTC_ERROR_OUT_OF_MEMORY: return ROMA_ERROR_OUT_OF_HOST_MEMORY;
    case RTC_ERROR_UNSUPPORTED_CPU: return ROMA_ERROR_UNSUPPORTED;
    case RTC_ERROR_INVALID_ARGUMENT: return ROMA_ERROR_INVALID_SCENE;
    default: return ROMA_ERROR_INVALID_ARGUMENT;
    }
}

/* Embree reports errors here (any thread); user is the roma_ref, whose logger
 * is set before the device exists. */
static void on_embree_error(void *user, enum RTCError code, const char *message)
{
    const roma_ref *ref = user;
    roma_log_error(&ref->logger, rtc_error_result(code), "Embree: %s (%s)", message ? message : "",
                   rtc_error_name(code));
}

/* Returns ROMA_SUCCESS or logs `what` with the pending device error. */
static roma_result check_device(const roma_ref *ref, const char *what)
{
    enum RTCError code = rtcGetDeviceError(ref->device);
    if (code == RTC_ERROR_NONE)
        return ROMA_SUCCESS;
    return roma_fail(&ref->logger, rtc_error_result(code), "roma_ref_create: %s failed (%s)", what,
                     rtc_error_name(code));
}

static roma_result build_scene(roma_ref *ref)
{
    const roma_scene_view *v = &ref->view;
    char config[64];
    snprintf(config, sizeof config, "threads=%u,verbose=0", ref->thread_count);
    ref->device = rtcNewDevice(config);
    if (!ref->device) {
        enum RTCError code = rtcGetDeviceError(NULL);
        return roma_fail(&ref->logger, rtc_error_result(code),
                         "roma_ref_create: rtcNewDevice failed (%s)", rtc_error_name(code));
    }
    rtcSetDeviceErrorFunction(ref->device, on_embree_error, ref);

    ref->scene = rtcNewScene(ref->device);
    roma_result r = check_device(ref, "rtcNewScene");
    if (r != ROMA_SUCCESS || !ref->scene)
        return r != ROMA_SUCCESS ? r
                                 : roma_fail(&ref->logger, ROMA_ERROR_OUT_OF_HOST_MEMORY,
                                             "roma_ref_create: rtcNewScene failed");
    /* Robust traversal: watertight edges matter more than speed for ground truth. */
    rtcSetSceneFlags(ref->scene, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(ref->scene, RTC_BUILD_QUALITY_MEDIUM);

    RTCGeometry geom = rtcNewGeometry(ref->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    if (!geom) {
        r = check_device(ref, "rtcNewGeometry");
        return r != ROMA_SUCCESS ? r
                                 : roma_fail(&ref->logger, ROMA_ERROR_OUT_OF_HOST_MEMORY,
                                             "roma_ref_create: rtcNewGeometry failed");
    }
    /* Embree-owned copies: Embree pads them for its 16-byte vector loads, which
     * the scene's own arrays do not guarantee. */
    float *vb = rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                        3 * sizeof(float), v->vertex_count);
    uint32_t *ib = rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                           3 * sizeof(uint32_t), v->triangle_count);
    if (!vb || !ib) {
        rtcReleaseGeometry(geom);
        r = check_device(ref, "allocating the vertex/index buffers");
        return r != ROMA_SUCCESS ? r
                                 : roma_fail(&ref->logger, ROMA_ERROR_OUT_OF_HOST_MEMORY,
                                             "roma_ref_create: Embree buffer allocation failed");
    }
    memcpy(vb, v->positions, 3 * sizeof(float) * (size_t)v->vertex_count);
    memcpy(ib, v->indices, 3 * sizeof(uint32_t) * (size_t)v->triangle_count);
    rtcCommitGeometry(geom);
    rtcAttachGeometryByID(ref->scene, geom, 0);
    rtcReleaseGeometry(geom);
    r = check_device(ref, "creating the triangle geometry");
    if (r != ROMA_SUCCESS)
        return r;

    rtcCommitScene(ref->scene);
    return check_device(ref, "building the Embree BVH (rtcCommitScene)");
}

roma_result roma_ref_create(const roma_scene *scene, const roma_ref_desc *desc, roma_ref **out_ref)
{
    const roma_logger *logger = desc ? &desc->logger : NULL;
    if (out_ref)
        *out_ref = NULL;
    if (!scene || !out_ref)
        return roma_fail(logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_ref_create: scene and out_ref must not be NULL");
    roma_ref *ref = calloc(1, sizeof *ref);
    if (!ref)
        return roma_fail(logger, ROMA_ERROR_OUT_OF_HOST_MEMORY, "roma_ref_create: out of memory");
    if (logger)
        ref->logger = *logger;

    roma_result r = roma_scene_get_view(scene, &ref->view);
    if (r != ROMA_SUCCESS) {
        roma_ref_destroy(ref);
        return roma_fail(logger, r, "roma_ref_create: could not read the scene (%s)",
                         roma_result_string(r));
    }
    if (!ref->view.positions || !ref->view.indices || ref->view.triangle_count == 0) {
        roma_ref_destroy(ref);
        return roma_fail(logger, ROMA_ERROR_EMPTY_SCENE, "roma_ref_create: the scene has no triangles");
    }

    uint32_t threads = desc ? desc->thread_count : 0;
    if (threads == 0) {
        long online = sysconf(_SC_NPROCESSORS_ONLN);
        threads = online > 0 ? (uint32_t)online : 1u;
    }
    ref->thread_count = threads < ROMA_REF_MAX_THREADS ? threads : ROMA_REF_MAX_THREADS;

    float diag[3];
    roma_ref_sub(ref->view.bounds_max, ref->view.bounds_min, diag);
    float extent = sqrtf(roma_ref_dot(diag, diag));
    /* A degenerate (single point) scene still needs a non-zero offset. */
    ref->offset_scale = ROMA_REF_EPSILON * (extent > 0.0f && isfinite(extent) ? extent : 1.0f);

    r = build_scene(ref);
    if (r == ROMA_SUCCESS)
        r = roma_emitter_table_build(&ref->view, &ref->logger, &ref->emitters);
    if (r != ROMA_SUCCESS) {
        roma_ref_destroy(ref);
        return r;
    }
    roma_logf(&ref->logger, ROMA_LOG_DEBUG,
              "reference: %u triangles, %u area-light triangles, %u punctual lights, %u threads",
              ref->view.triangle_count, ref->emitters.count, ref->view.light_count,
              ref->thread_count);
    *out_ref = ref;
    return ROMA_SUCCESS;
}

void roma_ref_destroy(roma_ref *ref)
{
    if (!ref)
        return;
    if (ref->scene)
        rtcReleaseScene(ref->scene);
    if (ref->device)
        rtcReleaseDevice(ref->device);
    roma_emitter_table_free(&ref->emitters);
    free(ref);
}

static void init_ray(struct RTCRay *ray, const float org[3], const float dir[3], float tmin,
                     float tmax)
{
    ray->org_x = org[0];
    ray->org_y = org[1];
    ray->org_z = org[2];
    ray->tnear = tmin;
    ray->dir_x = dir[0];
    ray->dir_y = dir[1];
    ray->dir_z = dir[2];
    ray->time = 0.0f;
    ray->tfar = tmax;
    ray->mask = 0xFFFFFFFFu;
    ray->id = 0;
    ray->flags = 0;
}

/* Fills the hit record from Embree's barycentrics (u, v weight vertices 1, 2). */
static void fill_hit(const roma_ref *ref, const struct RTCRayHit *rh, const float dir[3],
                     roma_ref_hit *hit)
{
    const roma_scene_view *v = &ref->view;
    uint32_t tri = rh->hit.primID;
    const uint32_t *idx = &v->indices[3 * (size_t)tri];
    const float *p0 = &v->positions[3 * (size_t)idx[0]];
    const float *p1 = &v->positions[3 * (size_t)idx[1]];
    const float *p2 = &v->positions[3 * (size_t)idx[2]];
    float u = rh->hit.u, w = rh->hit.v, b0 = 1.0f - u - w;

    hit->t = rh->ray.tfar;
    hit->triangle = tri;
    /* Interpolating the vertices keeps the point on the triangle's plane even
     * for long rays, where org + t * dir drifts. */
    for (int k = 0; k < 3; ++k)
        hit->position[k] = b0 * p0[k] + u * p1[k] + w * p2[k];

    float e1[3], e2[3], gn[3];
    roma_ref_sub(p1, p0, e1);
    roma_ref_sub(p2, p0, e2);
    roma_ref_cross(e1, e2, gn);
    if (!(roma_ref_normalize(gn) > 0.0f)) {
        /* Only reachable for a sliver Embree still hit: face the ray. */
        gn[0] = -dir[0];
        gn[1] = -dir[1];
        gn[2] = -dir[2];
        roma_ref_normalize(gn);
    }
    if (roma_ref_dot(gn, dir) > 0.0f) {
        gn[0] = -gn[0];
        gn[1] = -gn[1];
        gn[2] = -gn[2];
    }
    memcpy(hit->geometric_normal, gn, sizeof gn);

    float sn[3] = {gn[0], gn[1], gn[2]};
    if (v->normals) {
        const float *n0 = &v->normals[3 * (size_t)idx[0]];
        const float *n1 = &v->normals[3 * (size_t)idx[1]];
        const float *n2 = &v->normals[3 * (size_t)idx[2]];
        float n[3];
        for (int k = 0; k < 3; ++k)
            n[k] = b0 * n0[k] + u * n1[k] + w * n2[k];
        float len = roma_ref_normalize(n);
        if (len > 1e-12f && isfinite(len))
            memcpy(sn, n, sizeof sn);
    }
    if (roma_ref_dot(sn, gn) < 0.0f) {
        sn[0] = -sn[0];
        sn[1] = -sn[1];
        sn[2] = -sn[2];
    }
    memcpy(hit->shading_normal, sn, sizeof sn);
}

int roma_ref_intersect(const roma_ref *ref, const float org[3], const float dir[3], float tmin,
                       float tmax, roma_ref_hit *out_hit)
{
    if (!ref || !org || !dir)
        return 0;
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    struct RTCRayHit rh;
    init_ray(&rh.ray, org, dir, tmin, tmax);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(ref->scene, &ctx, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID)
        return 0;
    if (out_hit)
        fill_hit(ref, &rh, dir, out_hit);
    return 1;
}

int roma_ref_occluded(const roma_ref *ref, const float org[3], const float dir[3], float tmin,
                      float tmax)
{
    if (!ref || !org || !dir)
        return 0;
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    struct RTCRay ray;
    init_ray(&ray, org, dir, tmin, tmax);
    rtcOccluded1(ref->scene, &ctx, &ray);
    /* Embree sets tfar to -inf on a hit. */
    return ray.tfar < 0.0f && isinf(ray.tfar);
}

void roma_ref_offset_origin(const roma_ref *ref, const float p[3], const float gn[3], float out[3])
{
    float s = ref ? ref->offset_scale : 0.0f;
    for (int k = 0; k < 3; ++k)
        out[k] = p[k] + gn[k] * s;
}

/* --- Batches: chunks of rays handed out to the worker pool. --- */

typedef struct batch_job {
    const roma_ref *ref;
    uint32_t n;
    const float *orgs, *dirs, *tmins, *tmaxs;
    uint8_t *out_hit;
    float *out_t;
} batch_job;

static void batch_chunk(void *ctx, uint32_t item)
{
    const batch_job *job = ctx;
    uint32_t begin = item * ROMA_REF_BATCH_CHUNK;
    uint32_t end = job->n - begin < ROMA_REF_BATCH_CHUNK ? job->n : begin + ROMA_REF_BATCH_CHUNK;
    for (uint32_t i = begin; i < end; ++i) {
        const float *o = &job->orgs[3 * (size_t)i], *d = &job->dirs[3 * (size_t)i];
        float tmin = job->tmins ? job->tmins[i] : 0.0f;
        float tmax = job->tmaxs ? job->tmaxs[i] : INFINITY;
        if (job->out_hit) {
            job->out_hit[i] = (uint8_t)roma_ref_occluded(job->ref, o, d, tmin, tmax);
        } else {
            roma_ref_hit hit;
            job->out_t[i] = roma_ref_intersect(job->ref, o, d, tmin, tmax, &hit) ? hit.t : INFINITY;
        }
    }
}

static void run_batch(batch_job *job)
{
    uint32_t chunks = (uint32_t)(((uint64_t)job->n + ROMA_REF_BATCH_CHUNK - 1) / ROMA_REF_BATCH_CHUNK);
    roma_ref_parallel_for(job->ref, chunks, batch_chunk, job, NULL, NULL);
}

void roma_ref_occluded_batch(const roma_ref *ref, uint32_t n, const float *orgs, const float *dirs,
                             const float *tmins, const float *tmaxs, uint8_t *out_hit)
{
    if (!ref || n == 0 || !out_hit)
        return;
    if (!orgs || !dirs) {
        roma_log_error(&ref->logger, ROMA_ERROR_INVALID_ARGUMENT, "roma_ref_occluded_batch: NULL ray arrays");
        memset(out_hit, 0, n);
        return;
    }
    batch_job job = {ref, n, orgs, dirs, tmins, tmaxs, out_hit, NULL};
    run_batch(&job);
}

void roma_ref_intersect_batch(const roma_ref *ref, uint32_t n, const float *orgs, const float *dirs,
                              const float *tmins, const float *tmaxs, float *out_t)
{
    if (!ref || n == 0 || !out_t)
        return;
    if (!orgs || !dirs) {
        roma_log_error(&ref->logger, ROMA_ERROR_INVALID_ARGUMENT, "roma_ref_intersect_batch: NULL ray arrays");
        for (uint32_t i = 0; i < n; ++i)
            out_t[i] = INFINITY;
        return;
    }
    batch_job job = {ref, n, orgs, dirs, tmins, tmaxs, NULL, out_t};
    run_batch(&job);
}
