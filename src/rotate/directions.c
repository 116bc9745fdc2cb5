#include "rotate/directions.h"

#include <float.h>
#include <math.h>

#include "roma/sampling.h"

void roma_square_to_hemisphere(float u, float v, float out[3])
{
    float x, y;
    roma_concentric_disk(u, v, &x, &y);
    float r2 = x * x + y * y;
    /* Equal-area lift of the disk to the hemisphere: z = 1 - r^2. */
    float s = sqrtf(fmaxf(0.0f, 2.0f - r2));
    out[0] = x * s;
    out[1] = y * s;
    out[2] = 1.0f - r2;
}

void roma_hemisphere_to_square(const float d[3], float *u, float *v)
{
    /* Back to the disk: (x, y) / sqrt(1 + z), stable near the pole. */
    float k = 1.0f / sqrtf(1.0f + fmaxf(d[2], 0.0f));
    float x = d[0] * k, y = d[1] * k;
    float r = sqrtf(x * x + y * y);
    float a = 0.0f, b = 0.0f;
    if (r > 0.0f) {
        const float four_over_pi = 4.0f / ROMA_PI;
        float theta = atan2f(y, x);
        if (theta < -ROMA_PI / 4.0f)
            theta += 2.0f * ROMA_PI; /* now in [-pi/4, 7pi/4) */
        if (theta < ROMA_PI / 4.0f) {
            a = r;
            b = r * theta * four_over_pi;
        } else if (theta < 3.0f * ROMA_PI / 4.0f) {
            b = r;
            a = r * (ROMA_PI / 2.0f - theta) * four_over_pi;
        } else if (theta < 5.0f * ROMA_PI / 4.0f) {
            a = -r;
            b = -r * (theta - ROMA_PI) * four_over_pi;
        } else {
            b = -r;
            a = -r * (ROMA_PI / 2.0f - (theta - ROMA_PI)) * four_over_pi;
        }
    }
    *u = fminf(fmaxf(0.5f * (a + 1.0f), 0.0f), 1.0f);
    *v = fminf(fmaxf(0.5f * (b + 1.0f), 0.0f), 1.0f);
}

int roma_unit_direction(const float d[3], float unit[3])
{
    unit[0] = unit[1] = unit[2] = 0.0f;
    float f[3];
    for (int i = 0; i < 3; ++i) {
        if (!isfinite(d[i]))
            return 0;
        f[i] = fabsf(d[i]) < FLT_MIN ? 0.0f : d[i];
    }
    float m = fmaxf(fmaxf(fabsf(f[0]), fabsf(f[1])), fabsf(f[2]));
    if (!(m > 0.0f))
        return 0;
    float s[3];
    for (int i = 0; i < 3; ++i) {
        s[i] = f[i] / m;
        s[i] = fabsf(s[i]) < FLT_MIN ? 0.0f : s[i]; /* as roma_unit_direction in GLSL */
    }
    float len = sqrtf(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
    float inv_len = 1.0f / len;
    for (int i = 0; i < 3; ++i)
        unit[i] = s[i] * inv_len;
    return 1;
}

uint32_t roma_unit_direction_to_map(const float unit[3], uint32_t angular, int *folded)
{
    int fold = unit[2] < 0.0f;
    if (folded)
        *folded = fold;
    if (angular == 0)
        return 0;
    float up[3] = {fold ? -unit[0] : unit[0], fold ? -unit[1] : unit[1], fold ? -unit[2] : unit[2]};
    float u, v;
    roma_hemisphere_to_square(up, &u, &v);
    uint32_t sx = (uint32_t)fminf(u * (float)angular, (float)(angular - 1));
    uint32_t sy = (uint32_t)fminf(v * (float)angular, (float)(angular - 1));
    return sy * angular + sx;
}

uint32_t roma_direction_to_map(const float d[3], uint32_t angular, int *folded)
{
    float unit[3];
    if (!roma_unit_direction(d, unit)) {
        if (folded)
            *folded = 0;
        return 0;
    }
    return roma_unit_direction_to_map(unit, angular, folded);
}

void roma_stratum_candidate(uint32_t angular, uint32_t k, float ju, float jv, float out_dir[3])
{
    /* Strictly inside the stratum: on its edge, float rounding could select a neighbour.
     * fmaxf/fminf also turn a NaN jitter into the edge of the range. */
    ju = fminf(fmaxf(ju, 1e-4f), 1.0f - 1e-4f);
    jv = fminf(fmaxf(jv, 1e-4f), 1.0f - 1e-4f);
    roma_square_to_hemisphere(((float)(k % angular) + ju) / (float)angular,
                              ((float)(k / angular) + jv) / (float)angular, out_dir);
}

void roma_candidate_directions(uint32_t angular, uint32_t seed, uint32_t frame, int jitter,
                               float *out)
{
    for (uint32_t k = 0; k < angular * angular; ++k) {
        float ju = jitter ? roma_random(seed, k, frame, 0) : 0.5f;
        float jv = jitter ? roma_random(seed, k, frame, 1) : 0.5f;
        roma_stratum_candidate(angular, k, ju, jv, out + 3 * k);
    }
}
