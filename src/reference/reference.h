/* libroma reference tracer: ground truth rendered on the CPU with Embree.
 *
 * Lives in its own target (roma_reference) so that engines linking libroma
 * never pull in Embree. Used by roma-render --tracer embree, the tests and the
 * benchmark. Deterministic: every estimate is a pure function of the scene,
 * the inputs and the seed (roma/sampling.h), whatever the thread count.
 *
 * Shading model (shared with the ROMA passes): two-sided Lambertian surfaces;
 * the shading normal is the interpolated vertex normal, flipped to the side of
 * the geometric normal that faces the incoming ray; secondary rays start at
 * the hit point offset by ROMA_REF_EPSILON * scene extent along the geometric
 * normal (facing side). Sampled directions that go below the geometric surface
 * (dot(dir, gn) <= 0, possible when the shading normal is tilted) contribute
 * nothing: an occluded AO sample, a zero GI sample, an unlit light sample.
 * Shadow rays towards a point (point/spot light, area-light sample, many-lights
 * position) are segments from the offset origin that stop 1e-4 of their length
 * short of the point; directional shadow rays are unbounded.
 *
 * Random numbers: roma_random(seed, pixel, sample, dimension), pixel = y * width + x
 * in images (the caller's value in the point estimators), dimensions:
 *   0, 1  AO direction (roma_cosine_hemisphere around the shading normal)
 *   2     direct: area-light triangle choice (CDF over area * luminance(emission))
 *   3, 4  direct: point on it, roma_triangle_sample -> y = v0 + b1 (v1 - v0) + b2 (v2 - v0)
 *   5, 6  GI: bounce direction (roma_cosine_hemisphere around the shading normal)
 *   7-9   GI: area-light sample at the bounce hit (as 2-4)
 * The point estimators treat spp = 0 as 1. */
#ifndef ROMA_REFERENCE_H
#define ROMA_REFERENCE_H

#include <stdint.h>

#include "roma/camera.h"
#include "roma/effects.h"
#include "roma/image.h"
#include "roma/result.h"
#include "roma/scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Relative ray offset (times the scene's bounding-box diagonal). */
#define ROMA_REF_EPSILON 1e-5f

typedef struct roma_ref roma_ref;

typedef struct roma_ref_desc {
    uint32_t thread_count; /* 0 = number of online CPUs */
    roma_logger logger;
} roma_ref_desc;

/* Builds the Embree scene. The roma_scene must outlive the roma_ref. */
roma_result roma_ref_create(const roma_scene *scene, const roma_ref_desc *desc, roma_ref **out_ref);
void roma_ref_destroy(roma_ref *ref);

typedef struct roma_ref_hit {
    float t;
    uint32_t triangle;
    float position[3];
    float geometric_normal[3]; /* unit, facing the ray origin */
    float shading_normal[3];   /* unit, same side as geometric_normal */
} roma_ref_hit;

/* Closest hit in (tmin, tmax); returns 1 and fills hit, or 0. dir need not be unit. */
int roma_ref_intersect(const roma_ref *ref, const float org[3], const float dir[3], float tmin,
                       float tmax, roma_ref_hit *out_hit);
/* 1 when anything is hit in (tmin, tmax). */
int roma_ref_occluded(const roma_ref *ref, const float org[3], const float dir[3], float tmin,
                      float tmax);
/* Batch versions over n rays (3 floats per origin/direction), multithreaded.
 * tmins/tmaxs may be NULL (0 and INFINITY for every ray). */
void roma_ref_occluded_batch(const roma_ref *ref, uint32_t n, const float *orgs, const float *dirs,
                             const float *tmins, const float *tmaxs, uint8_t *out_hit);
void roma_ref_intersect_batch(const roma_ref *ref, uint32_t n, const float *orgs, const float *dirs,
                              const float *tmins, const float *tmaxs, float *out_t /* INFINITY = miss */);

/* Offset origin for secondary rays leaving a surface point along geometric normal gn. */
void roma_ref_offset_origin(const roma_ref *ref, const float p[3], const float gn[3], float out[3]);

/* --- Point estimators (the building blocks of the images; tests call them directly) --- */

/* Sample `sample` of the AO at p (roma_ref_ao_point's rays, for tracers that trace them
 * elsewhere): the offset origin, the cosine-weighted unit direction and the ray's end, radius
 * (<= 0, NaN: INFINITY); the ray starts at t = 0. Returns 0 where the direction lies below the
 * geometric surface (n != gn): that sample counts as occluded, untraced. */
int roma_ref_ao_ray(const roma_ref *ref, const float p[3], const float gn[3], const float n[3], float radius,
                    uint32_t seed, uint32_t pixel, uint32_t sample, float origin[3], float dir[3], float *tmax);

/* AO visibility at p with normal n: cosine-weighted, spp samples, rays of length
 * radius (<= 0 or INFINITY = unbounded). Samples use (seed, pixel, sample index). */
float roma_ref_ao_point(const roma_ref *ref, const float p[3], const float gn[3], const float n[3],
                        float radius, uint32_t spp, uint32_t seed, uint32_t pixel);

/* Direct radiance leaving p towards the viewer: albedo/pi * irradiance from all
 * punctual lights (hard shadows, glTF spot cone and range windows) and area
 * lights (spp light samples, emitters two-sided). RGB out. This is reflected
 * light only: the emission of p's own surface is not included (an emitter shows
 * its lit albedo; add emission when composing). */
void roma_ref_direct_point(const roma_ref *ref, const float p[3], const float gn[3],
                           const float n[3], const float albedo[3], uint32_t spp, uint32_t seed,
                           uint32_t pixel, float out_rgb[3]);

/* One shadow segment of roma_ref_direct_point's estimate, for tracers that trace it elsewhere:
 * from the offset origin along the unit dir to tmax (INFINITY: a directional light; 0: the
 * target is the origin, nothing can block it), and the irradiance it adds when nothing blocks
 * it (area: an area-light sample, whose adds are averaged over the samples). */
typedef struct roma_ref_segment {
    float origin[3], dir[3], tmax;
    float add[3];
    int area;
} roma_ref_segment;
typedef void (*roma_ref_segment_fn)(void *user, const roma_ref_segment *segment);

/* Calls fn for every shadow segment of roma_ref_direct_point(ref, p, gn, n, albedo, spp, seed,
 * pixel): the punctual lights that reach p, then the area-light samples that do. The direct
 * radiance is albedo / pi * (the unblocked punctual adds + the unblocked area adds / spp). */
void roma_ref_direct_segments(const roma_ref *ref, const float p[3], const float gn[3], const float n[3],
                              uint32_t spp, uint32_t seed, uint32_t pixel, roma_ref_segment_fn fn, void *user);

/* One-bounce indirect radiance leaving p: cosine-sampled bounce rays, at the
 * bounce hit y the reflected direct radiance albedo_y/pi * E_y (next-event
 * estimation: all punctual lights + 1 area-light sample); the emission of y is
 * excluded (it is direct light at p). Estimator per sample: albedo * L(y). */
void roma_ref_indirect_point(const roma_ref *ref, const float p[3], const float gn[3],
                             const float n[3], const float albedo[3], uint32_t spp, uint32_t seed,
                             uint32_t pixel, float out_rgb[3]);

/* The shadow segment from p to one point light (roma_ref_count_visible_lights' ray, for tracers
 * that trace it elsewhere): the offset origin, the unit direction to the light and the
 * segment's end, shortened as the reference's (0 for a light at the origin: seen). Returns 0
 * where the light lies behind the shading hemisphere: it does not count, untraced. */
int roma_ref_light_segment(const roma_ref *ref, const float p[3], const float gn[3], const float n[3],
                           const float light[3], float origin[3], float dir[3], float *tmax);

/* Number of light positions (3 floats each) visible from p: segment from the
 * offset origin; positions with dot(n, L - p) <= 0 count as not visible. */
uint32_t roma_ref_count_visible_lights(const roma_ref *ref, const float p[3], const float gn[3],
                                       const float n[3], const float *light_positions,
                                       uint32_t light_count);

/* --- Images (effects: ROMA_EFFECT_* of roma/effects.h) --- */

typedef void (*roma_progress_fn)(float fraction, void *user_data);

typedef struct roma_ref_render_desc {
    roma_camera camera;
    uint32_t width, height;
    uint32_t effects;         /* ROMA_EFFECT_* bits */
    uint32_t spp;             /* samples per pixel for AO, area lights and GI; 0 = 64 */
    float ao_radius;          /* <= 0 = unbounded */
    uint32_t seed;
    const float *many_light_positions; /* required for ROMA_EFFECT_LIGHTS */
    uint32_t many_light_count;
    roma_progress_fn progress;
    void *progress_user_data;
} roma_ref_render_desc;

/* Output images; each requested effect is allocated by the call, the others stay zeroed.
 * ao: 1 channel visibility (background 1); direct, gi: RGB radiance (background 0);
 * lights: 1 channel count of visible lights (background 0);
 * coverage: 1 channel, 1 where the primary ray hit geometry (always filled). */
typedef struct roma_ref_images {
    roma_image ao, direct, gi, lights, coverage;
} roma_ref_images;

roma_result roma_ref_render(const roma_ref *ref, const roma_ref_render_desc *desc,
                            roma_ref_images *out_images);
void roma_ref_images_free(roma_ref_images *images);

/* A G-buffer of the primary rays the images shade (pixel centres), for renderers that shade
 * the reference's points themselves; caller-allocated, width * height entries each: position
 * (xyz, w = 1 where the ray hit, 0 elsewhere), shading and geometric normal (xyz facing the
 * eye, w = 0), albedo (rgb: the triangle's base colour, grey 0.8 without a material; 0 where
 * nothing was hit). Multithreaded like the images. */
typedef struct roma_ref_gbuffer {
    float *position, *normal, *geometric_normal; /* 4 floats a pixel */
    float *albedo;                               /* 3 floats a pixel */
} roma_ref_gbuffer;

roma_result roma_ref_render_gbuffer(const roma_ref *ref, const roma_camera *camera, uint32_t width, uint32_t height,
                                    const roma_ref_gbuffer *out);

#ifdef __cplusplus
}
#endif

#endif /* ROMA_REFERENCE_H */
