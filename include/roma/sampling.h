/** @file
 * libroma: deterministic sample sequences shared by the reference tracer and
 * the GPU passes (shaders/include/roma_sampling.glsl mirrors this file), so
 * that ROMA and Embree can be compared on the same rays.
 *
 * Every random number is a pure function of (seed, pixel, sample, dimension):
 * no state, any order, any thread. Header-only (static inline). */
#ifndef ROMA_SAMPLING_H
#define ROMA_SAMPLING_H

#include <math.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** pi as a float. */
#define ROMA_PI 3.14159265358979323846f

/** A 32-bit integer hash with good avalanche ("lowbias32" constants).
 *
 * @param x  the value to hash.
 * @return the hash of x.
 * @par Threads
 * Any thread (pure). */
static inline uint32_t roma_hash_u32(uint32_t x)
{
    x ^= x >> 16;
    x *= 0x7feb352dU;
    x ^= x >> 15;
    x *= 0x846ca68bU;
    x ^= x >> 16;
    return x;
}

/** Uniform float in [0, 1) with 24 bits of precision.
 *
 * @param x  random bits; the top 24 are used.
 * @return (x >> 8) / 2^24, in [0, 1).
 * @par Threads
 * Any thread (pure). */
static inline float roma_u32_to_unit_float(uint32_t x)
{
    return (float)(x >> 8) * (1.0f / 16777216.0f);
}

/** Random number for (seed, pixel, sample, dimension).
 *
 * @param seed       the sequence (roma_ao_settings.seed and the like).
 * @param pixel      pixel index, y * width + x.
 * @param sample     sample index (frame * samples + k in the effects).
 * @param dimension  which number of the sample (each use has its own).
 * @return a uniform float in [0, 1), the same on the host and in roma_sampling.glsl.
 * @par Threads
 * Any thread (pure). */
static inline float roma_random(uint32_t seed, uint32_t pixel, uint32_t sample, uint32_t dimension)
{
    uint32_t h = roma_hash_u32(seed ^ 0x9e3779b9U);
    h = roma_hash_u32(h ^ pixel);
    h = roma_hash_u32(h ^ (sample * 0x632be5abU));
    h = roma_hash_u32(h ^ (dimension * 0x85ebca6bU));
    return roma_u32_to_unit_float(h);
}

/** Concentric (Shirley-Chiu) map from the unit square to the unit disk.
 *
 * @param u       first uniform, [0, 1].
 * @param v       second uniform, [0, 1].
 * @param[out] x  disk x, [-1, 1].
 * @param[out] y  disk y, [-1, 1].
 * @par Threads
 * Any thread (pure). */
static inline void roma_concentric_disk(float u, float v, float *x, float *y)
{
    float a = 2.0f * u - 1.0f, b = 2.0f * v - 1.0f;
    if (a == 0.0f && b == 0.0f) {
        *x = 0.0f;
        *y = 0.0f;
        return;
    }
    float r, phi;
    if (fabsf(a) > fabsf(b)) {
        r = a;
        phi = (ROMA_PI / 4.0f) * (b / a);
    } else {
        r = b;
        phi = (ROMA_PI / 2.0f) - (ROMA_PI / 4.0f) * (a / b);
    }
    *x = r * cosf(phi);
    *y = r * sinf(phi);
}

/** Cosine-weighted direction in the local frame where +z is the normal; pdf = cos/pi.
 *
 * @param u         first uniform, [0, 1].
 * @param v         second uniform, [0, 1].
 * @param[out] dir  unit direction with z >= 0 (roma_local_to_world turns it to world space).
 * @par Threads
 * Any thread (pure). */
static inline void roma_cosine_hemisphere(float u, float v, float dir[3])
{
    float x, y;
    roma_concentric_disk(u, v, &x, &y);
    float z2 = 1.0f - x * x - y * y;
    dir[0] = x;
    dir[1] = y;
    dir[2] = z2 > 0.0f ? sqrtf(z2) : 0.0f;
}

/** Orthonormal basis (t, b, n) around unit n, continuous except at n.z = -1 boundary
 * (Duff et al. 2017, "Building an orthonormal basis, revisited").
 *
 * @param n       unit normal.
 * @param[out] t  first tangent, unit.
 * @param[out] b  second tangent, unit.
 * @par Threads
 * Any thread (pure). */
static inline void roma_basis(const float n[3], float t[3], float b[3])
{
    float sign = n[2] >= 0.0f ? 1.0f : -1.0f;
    float a = -1.0f / (sign + n[2]);
    float c = n[0] * n[1] * a;
    t[0] = 1.0f + sign * n[0] * n[0] * a;
    t[1] = sign * c;
    t[2] = -sign * n[0];
    b[0] = c;
    b[1] = sign + n[1] * n[1] * a;
    b[2] = -n[1];
}

/** Local direction -> world direction around unit normal n (the frame of roma_basis).
 *
 * @param n         unit normal: the local +z.
 * @param local     direction in the local frame.
 * @param[out] out  world direction; must not alias n or local.
 * @par Threads
 * Any thread (pure). */
static inline void roma_local_to_world(const float n[3], const float local[3], float out[3])
{
    float t[3], b[3];
    roma_basis(n, t, b);
    for (int i = 0; i < 3; ++i)
        out[i] = t[i] * local[0] + b[i] * local[1] + n[i] * local[2];
}

/** Uniform point on a triangle (barycentrics from two uniforms, square-root method): the point
 * is v0 + b1 (v1 - v0) + b2 (v2 - v0).
 *
 * @param u        first uniform, [0, 1].
 * @param v        second uniform, [0, 1].
 * @param[out] b1  weight of edge v1 - v0.
 * @param[out] b2  weight of edge v2 - v0.
 * @par Threads
 * Any thread (pure). */
static inline void roma_triangle_sample(float u, float v, float *b1, float *b2)
{
    float su = sqrtf(u);
    *b1 = 1.0f - su;
    *b2 = v * su;
}

/** Point-light positions for the many-lights effect: count positions, uniformly
 * in the box [bmin, bmax] shrunk by 2% per side, from seed. out: 3 floats per light.
 *
 * @param bmin      lowest corner of the box.
 * @param bmax      highest corner of the box.
 * @param count     lights; 0 writes nothing.
 * @param seed      the sequence.
 * @param[out] out  3 * count floats.
 * @par Threads
 * Any thread (pure). */
static inline void roma_many_lights_positions(const float bmin[3], const float bmax[3],
                                              uint32_t count, uint32_t seed, float *out)
{
    for (uint32_t i = 0; i < count; ++i)
        for (uint32_t k = 0; k < 3; ++k) {
            float ext = bmax[k] - bmin[k];
            float u = roma_random(seed, i, 0x4c49u, k); /* 'LI' */
            out[3 * i + k] = bmin[k] + ext * (0.02f + 0.96f * u);
        }
}

#ifdef __cplusplus
}
#endif

#endif /* ROMA_SAMPLING_H */
