/* Internals shared by the reference tracer's translation units. */
#ifndef ROMA_REFERENCE_INTERNAL_H
#define ROMA_REFERENCE_INTERNAL_H

#include <embree3/rtcore.h>
#include <math.h>

#include "reference.h"
#include "scene/emitters.h"

struct roma_ref {
    roma_logger logger;
    roma_scene_view view;
    RTCDevice device;
    RTCScene scene;
    uint32_t thread_count; /* resolved, >= 1 */
    float offset_scale;    /* ROMA_REF_EPSILON * |bbox diagonal| */
    roma_emitter_table emitters; /* area lights */
};

/* Runs fn(ctx, item) for item in [0, count) on up to ref->thread_count threads
 * (an atomic counter hands out items). progress, when set, is called only from
 * the calling thread, with non-decreasing fractions ending at 1. */
typedef void (*roma_ref_task_fn)(void *ctx, uint32_t item);
void roma_ref_parallel_for(const roma_ref *ref, uint32_t count, roma_ref_task_fn fn, void *ctx,
                           roma_progress_fn progress, void *progress_user_data);

/* Albedo of a triangle's material. */
static inline const float *roma_ref_albedo(const roma_ref *ref, uint32_t triangle)
{
    static const float grey[3] = {0.8f, 0.8f, 0.8f};
    const roma_scene_view *v = &ref->view;
    uint32_t m = v->triangle_materials ? v->triangle_materials[triangle] : 0;
    return (v->materials && m < v->material_count) ? v->materials[m].base_color : grey;
}

static inline float roma_ref_dot(const float a[3], const float b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static inline void roma_ref_sub(const float a[3], const float b[3], float out[3])
{
    out[0] = a[0] - b[0];
    out[1] = a[1] - b[1];
    out[2] = a[2] - b[2];
}

static inline void roma_ref_cross(const float a[3], const float b[3], float out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

/* Normalises v in place; returns its former length (0 leaves v unchanged). */
static inline float roma_ref_normalize(float v[3])
{
    float len = sqrtf(roma_ref_dot(v, v));
    if (len > 0.0f && isfinite(len)) {
        float inv = 1.0f / len;
        v[0] *= inv;
        v[1] *= inv;
        v[2] *= inv;
    }
    return len;
}

#endif /* ROMA_REFERENCE_INTERNAL_H */
