/* Point estimators of the reference tracer: AO, direct light, one-bounce
 * indirect light and many-lights visibility at one surface point.
 *
 * Random dimensions per (seed, pixel, sample), see reference.h:
 *   0, 1  AO direction                 5, 6  GI bounce direction
 *   2-4   direct: area-light sample    7-9   GI: area-light sample at the bounce hit
 * (area-light sample = triangle choice, then the two roma_triangle_sample uniforms). */
#include <string.h>

#include "reference_internal.h"
#include "roma/sampling.h"
#include "roma_shared.h"

enum {
    DIM_AO = 0,
    DIM_DIRECT_AREA = 2,
    DIM_GI_BOUNCE = 5,
    DIM_GI_AREA = 7
};

/* Shadow segments stop this fraction short of the target so that the light's
 * own surface (area lights) never occludes it. */
#define SEGMENT_SHORTEN 1e-4f

/* The segment from origin to target, stopped short (target: a point light or an area-light
 * sample): its unit direction and end; tmax 0 when they coincide (nothing can block it). */
static void segment_to(const float origin[3], const float target[3], roma_ref_segment *out)
{
    roma_ref_sub(target, origin, out->dir);
    float d = roma_ref_normalize(out->dir);
    out->tmax = d > 0.0f ? d * (1.0f - SEGMENT_SHORTEN) : 0.0f;
}

/* The segment to one punctual light, with the irradiance it adds when unblocked; 0 when the
 * light adds nothing at p (below the surface, outside its cone or range). */
static int punctual_segment(const roma_light *light, const float p[3], const float gn[3], const float n[3],
                            const float origin[3], roma_ref_segment *out)
{
    float l[3];
    float scale = light->intensity;
    if (light->type == ROMA_LIGHT_DIRECTIONAL) {
        l[0] = -light->direction[0];
        l[1] = -light->direction[1];
        l[2] = -light->direction[2];
        if (!(roma_ref_normalize(l) > 0.0f))
            return 0;
    } else {
        roma_ref_sub(light->position, p, l);
        float d = roma_ref_normalize(l);
        if (!(d > 0.0f))
            return 0;
        scale /= d * d;
        if (light->range > 0.0f) {
            /* glTF-recommended window: max(min(1 - (d/range)^4, 1), 0) / d^2. */
            float q = d / light->range;
            q *= q;
            scale *= fmaxf(fminf(1.0f - q * q, 1.0f), 0.0f);
        }
        if (light->type == ROMA_LIGHT_SPOT) {
            float sd[3] = {light->direction[0], light->direction[1], light->direction[2]};
            if (!(roma_ref_normalize(sd) > 0.0f))
                return 0;
            float outer = light->outer_cone_angle > 0.0f ? light->outer_cone_angle : ROMA_PI / 4.0f;
            float cos_outer = cosf(outer), cos_inner = cosf(light->inner_cone_angle);
            /* glTF KHR_lights_punctual smooth cone falloff. */
            float s = 1.0f / fmaxf(0.001f, cos_inner - cos_outer);
            float o = -cos_outer * s;
            float cd = -roma_ref_dot(l, sd);
            float a = fminf(fmaxf(cd * s + o, 0.0f), 1.0f);
            scale *= a * a;
        }
    }
    float cos_n = roma_ref_dot(n, l);
    if (!(scale > 0.0f) || cos_n <= 0.0f || roma_ref_dot(gn, l) <= 0.0f)
        return 0;
    memcpy(out->origin, origin, sizeof out->origin);
    if (light->type == ROMA_LIGHT_DIRECTIONAL) {
        memcpy(out->dir, l, sizeof out->dir);
        out->tmax = INFINITY;
    } else {
        segment_to(origin, light->position, out);
    }
    float factor = fminf(scale * cos_n, (float)ROMA_MAX_IRRADIANCE);
    for (int k = 0; k < 3; ++k)
        out->add[k] = fminf(factor * light->color[k], (float)ROMA_MAX_IRRADIANCE);
    out->area = 0;
    return 1;
}

/* Every shadow segment of the irradiance at p (normal n, geometric gn): to all punctual
 * lights, then area_samples area-light samples using samples [sample_base, +area_samples)
 * of dimensions dim .. dim + 2; fn gets each. */
static void for_each_segment(const roma_ref *ref, const float p[3], const float gn[3], const float n[3],
                             uint32_t area_samples, uint32_t seed, uint32_t pixel, uint32_t sample_base, uint32_t dim,
                             roma_ref_segment_fn fn, void *user)
{
    float origin[3];
    roma_ref_offset_origin(ref, p, gn, origin);
    roma_ref_segment seg;
    for (uint32_t i = 0; i < ref->view.light_count; ++i)
        if (punctual_segment(&ref->view.lights[i], p, gn, n, origin, &seg))
            fn(user, &seg);
    if (ref->emitters.count == 0)
        return;
    for (uint32_t k = 0; k < area_samples; ++k) {
        uint32_t s = sample_base + k;
        const roma_emitter *e =
            &ref->emitters.emitters[roma_emitter_pick(&ref->emitters, roma_random(seed, pixel, s, dim))];
        float b1, b2;
        roma_triangle_sample(roma_random(seed, pixel, s, dim + 1),
                             roma_random(seed, pixel, s, dim + 2), &b1, &b2);
        float y[3], w[3];
        for (int c = 0; c < 3; ++c)
            y[c] = e->v0[c] + b1 * e->e1[c] + b2 * e->e2[c];
        roma_ref_sub(y, p, w);
        float d2 = roma_ref_dot(w, w);
        if (!(d2 > 0.0f))
            continue;
        roma_ref_normalize(w);
        float cos_x = roma_ref_dot(n, w);
        float cos_y = fabsf(roma_ref_dot(e->normal, w)); /* two-sided emitters */
        if (cos_x <= 0.0f || roma_ref_dot(gn, w) <= 0.0f || cos_y <= 0.0f)
            continue;
        memcpy(seg.origin, origin, sizeof seg.origin);
        segment_to(origin, y, &seg);
        float g = fminf(cos_x * cos_y / (d2 * e->pdf_area), (float)ROMA_MAX_IRRADIANCE);
        for (int c = 0; c < 3; ++c)
            seg.add[c] = fminf(e->emission[c] * g, (float)ROMA_MAX_IRRADIANCE);
        seg.area = 1;
        fn(user, &seg);
    }
}

void roma_ref_direct_segments(const roma_ref *ref, const float p[3], const float gn[3], const float n[3],
                              uint32_t spp, uint32_t seed, uint32_t pixel, roma_ref_segment_fn fn, void *user)
{
    if (ref && p && gn && n && fn)
        for_each_segment(ref, p, gn, n, spp ? spp : 1, seed, pixel, 0, DIM_DIRECT_AREA, fn, user);
}

/* Embree's answer for each segment of an irradiance: punctual lights added at once, area
 * samples summed apart (their mean is taken at the end). */
typedef struct traced_irradiance {
    const roma_ref *ref;
    double punctual[3], area[3];
} traced_irradiance;

static void trace_segment(void *user, const roma_ref_segment *s)
{
    traced_irradiance *t = user;
    if (s->tmax > 0.0f && roma_ref_occluded(t->ref, s->origin, s->dir, 0.0f, s->tmax))
        return;
    double *sum = s->area ? t->area : t->punctual;
    for (int c = 0; c < 3; ++c)
        sum[c] += (double)s->add[c];
}

/* Irradiance at p (normal n, geometric gn): all punctual lights exactly, plus
 * area_samples area-light samples using samples [sample_base, +area_samples) of
 * dimensions dim .. dim + 2. Emission of p's own surface is not included. */
static void irradiance(const roma_ref *ref, const float p[3], const float gn[3], const float n[3],
                       uint32_t area_samples, uint32_t seed, uint32_t pixel, uint32_t sample_base,
                       uint32_t dim, double E[3])
{
    traced_irradiance t = {.ref = ref};
    for_each_segment(ref, p, gn, n, area_samples, seed, pixel, sample_base, dim, trace_segment, &t);
    for (int c = 0; c < 3; ++c)
        E[c] = t.punctual[c] + (area_samples ? t.area[c] / (double)area_samples : 0.0);
}

/* Cosine-weighted direction around n for (seed, pixel, s, dim .. dim + 1). */
static void cosine_direction(const float n[3], uint32_t seed, uint32_t pixel, uint32_t s,
                             uint32_t dim, float out[3])
{
    float local[3];
    roma_cosine_hemisphere(roma_random(seed, pixel, s, dim), roma_random(seed, pixel, s, dim + 1),
                           local);
    roma_local_to_world(n, local, out);
}

int roma_ref_ao_ray(const roma_ref *ref, const float p[3], const float gn[3], const float n[3], float radius,
                    uint32_t seed, uint32_t pixel, uint32_t sample, float origin[3], float dir[3], float *tmax)
{
    roma_ref_offset_origin(ref, p, gn, origin);
    cosine_direction(n, seed, pixel, sample, DIM_AO, dir);
    *tmax = (radius > 0.0f) ? radius : INFINITY; /* also maps NaN to unbounded */
    /* Directions below the geometric surface (possible when n != gn) are occluded. */
    return !(roma_ref_dot(dir, gn) <= 0.0f); /* a NaN product is traced, as before */
}

float roma_ref_ao_point(const roma_ref *ref, const float p[3], const float gn[3], const float n[3],
                        float radius, uint32_t spp, uint32_t seed, uint32_t pixel)
{
    if (!ref || !p || !gn || !n)
        return 1.0f;
    if (spp == 0)
        spp = 1;
    uint32_t open = 0;
    for (uint32_t s = 0; s < spp; ++s) {
        float origin[3], dir[3], tmax;
        if (roma_ref_ao_ray(ref, p, gn, n, radius, seed, pixel, s, origin, dir, &tmax) &&
            !roma_ref_occluded(ref, origin, dir, 0.0f, tmax))
            ++open;
    }
    return (float)((double)open / (double)spp);
}

void roma_ref_direct_point(const roma_ref *ref, const float p[3], const float gn[3],
                           const float n[3], const float albedo[3], uint32_t spp, uint32_t seed,
                           uint32_t pixel, float out_rgb[3])
{
    if (!out_rgb)
        return;
    out_rgb[0] = out_rgb[1] = out_rgb[2] = 0.0f;
    if (!ref || !p || !gn || !n || !albedo)
        return;
    double E[3];
    irradiance(ref, p, gn, n, spp ? spp : 1, seed, pixel, 0, DIM_DIRECT_AREA, E);
    for (int c = 0; c < 3; ++c)
        out_rgb[c] = (float)(albedo[c] / ROMA_PI * E[c]);
}

void roma_ref_indirect_point(const roma_ref *ref, const float p[3], const float gn[3],
                             const float n[3], const float albedo[3], uint32_t spp, uint32_t seed,
                             uint32_t pixel, float out_rgb[3])
{
    if (!out_rgb)
        return;
    out_rgb[0] = out_rgb[1] = out_rgb[2] = 0.0f;
    if (!ref || !p || !gn || !n || !albedo)
        return;
    if (spp == 0)
        spp = 1;
    float origin[3];
    roma_ref_offset_origin(ref, p, gn, origin);
    double acc[3] = {0.0, 0.0, 0.0};
    for (uint32_t s = 0; s < spp; ++s) {
        float w[3];
        cosine_direction(n, seed, pixel, s, DIM_GI_BOUNCE, w);
        if (roma_ref_dot(w, gn) <= 0.0f)
            continue;
        roma_ref_hit hit;
        if (!roma_ref_intersect(ref, origin, w, 0.0f, INFINITY, &hit))
            continue;
        const float *albedo_y = roma_ref_albedo(ref, hit.triangle);
        if (albedo_y[0] <= 0.0f && albedo_y[1] <= 0.0f && albedo_y[2] <= 0.0f)
            continue;
        double E[3];
        irradiance(ref, hit.position, hit.geometric_normal, hit.shading_normal, 1, seed, pixel, s,
                   DIM_GI_AREA, E);
        /* Cosine sampling: L_x = albedo_x/pi * L_y * cos / (cos/pi) = albedo_x * L_y,
         * with L_y = albedo_y/pi * E_y (reflected direct light only). */
        for (int c = 0; c < 3; ++c)
            acc[c] += (double)albedo_y[c] / ROMA_PI * E[c];
    }
    for (int c = 0; c < 3; ++c)
        out_rgb[c] = (float)(albedo[c] * acc[c] / (double)spp);
}

int roma_ref_light_segment(const roma_ref *ref, const float p[3], const float gn[3], const float n[3],
                           const float light[3], float origin[3], float dir[3], float *tmax)
{
    roma_ref_offset_origin(ref, p, gn, origin);
    float l[3];
    roma_ref_sub(light, p, l);
    /* Lights behind the shading hemisphere do not count. */
    if (roma_ref_dot(n, l) <= 0.0f)
        return 0;
    roma_ref_sub(light, origin, dir);
    const float d = roma_ref_normalize(dir);
    *tmax = d > 0.0f ? d * (1.0f - SEGMENT_SHORTEN) : 0.0f; /* a light at the origin is seen */
    return 1;
}

uint32_t roma_ref_count_visible_lights(const roma_ref *ref, const float p[3], const float gn[3],
                                       const float n[3], const float *light_positions,
                                       uint32_t light_count)
{
    if (!ref || !p || !gn || !n || !light_positions)
        return 0;
    uint32_t visible = 0;
    for (uint32_t i = 0; i < light_count; ++i) {
        float origin[3], dir[3], tmax;
        if (roma_ref_light_segment(ref, p, gn, n, &light_positions[3 * (size_t)i], origin, dir, &tmax) &&
            !(tmax > 0.0f && roma_ref_occluded(ref, origin, dir, 0.0f, tmax)))
            ++visible;
    }
    return visible;
}
