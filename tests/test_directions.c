/* Candidate mapping: round trips, O(1) stratum lookup, candidates inside their strata,
 * and the boundary directions (pole, horizon, axes, stratum edges, diagonals). */
#include <math.h>

#include "harness.h"
#include "rotate/directions.h"
#include "roma/sampling.h"
#include "trace/cpu_mirror.h"

static float angle_between(const float a[3], const float b[3])
{
    float d = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    return acosf(fminf(1.0f, fmaxf(-1.0f, d)));
}

/* Largest angle between the candidate and points of its stratum (dense boundary + interior sampling). */
static float stratum_radius(uint32_t angular, uint32_t k, const float cand[3])
{
    uint32_t sx = k % angular, sy = k / angular;
    float worst = 0.0f;
    const int n = 24;
    for (int i = 0; i <= n; ++i)
        for (int j = 0; j <= n; ++j) {
            float d[3];
            roma_square_to_hemisphere(((float)sx + (float)i / n) / angular, ((float)sy + (float)j / n) / angular, d);
            worst = fmaxf(worst, angle_between(d, cand));
        }
    return worst;
}

int main(void)
{
    /* Round trip square -> hemisphere -> square, and unit length. */
    double max_err = 0.0;
    for (int i = 0; i < 20000; ++i) {
        float u = roma_random(7, (uint32_t)i, 0, 0), v = roma_random(7, (uint32_t)i, 0, 1), d[3], u2, v2;
        roma_square_to_hemisphere(u, v, d);
        CHECK_NEAR(d[0] * d[0] + d[1] * d[1] + d[2] * d[2], 1.0, 1e-5);
        CHECK(d[2] >= 0.0f);
        roma_hemisphere_to_square(d, &u2, &v2);
        max_err = fmax(max_err, fmax(fabs(u - u2), fabs(v - v2)));
    }
    printf("square round trip: max error %.3g\n", max_err);
    CHECK(max_err < 2e-5);

    for (uint32_t angular = 1; angular <= 16; angular *= 2) {
        float cands[3 * 16 * 16];
        for (int jitter = 0; jitter < 2; ++jitter) {
            roma_candidate_directions(angular, 3, 11, jitter, cands);
            /* Each candidate selects its own map. */
            for (uint32_t k = 0; k < angular * angular; ++k) {
                int folded = 1;
                CHECK(roma_direction_to_map(cands + 3 * k, angular, &folded) == k);
                CHECK(folded == 0);
            }
        }
        /* Jitter at and beyond the ends of its range (roma_random gives [0, 1); the
         * clamp keeps [1e-4, 1 - 1e-4]) puts the candidate in its stratum, for every A. */
        const float ends[] = {0.0f, 1e-4f, 0.5f, 1.0f - 1e-4f, 0x1.fffffep-1f, 1.0f, -1.0f, 2.0f, NAN};
        const uint32_t n_ends = sizeof ends / sizeof ends[0];
        uint32_t outside = 0;
        for (uint32_t a = angular; a < 2 * angular && a <= 16; ++a)
            for (uint32_t k = 0; k < a * a; ++k)
                for (uint32_t i = 0; i < n_ends * n_ends; ++i) {
                    float d[3];
                    roma_stratum_candidate(a, k, ends[i % n_ends], ends[i / n_ends], d);
                    int folded = 1;
                    outside += !(roma_direction_to_map(d, a, &folded) == k && folded == 0);
                }
        CHECK(outside == 0);
        /* Random directions land in a stratum whose candidate is within its angular radius;
         * d and -d select the same map. */
        float radius[256];
        for (uint32_t k = 0; k < angular * angular; ++k)
            radius[k] = stratum_radius(angular, k, cands + 3 * k);
        float worst_ratio = 0.0f;
        for (int i = 0; i < 5000; ++i) {
            float local[3], n[3] = {0, 0, 1}, d[3];
            /* Uniform sphere directions. */
            float z = 1.0f - 2.0f * roma_random(5, (uint32_t)i, 1, 0), phi = 2.0f * ROMA_PI * roma_random(5, (uint32_t)i, 1, 1);
            float s = sqrtf(fmaxf(0.0f, 1.0f - z * z));
            local[0] = s * cosf(phi), local[1] = s * sinf(phi), local[2] = z;
            roma_local_to_world(n, local, d);
            int folded;
            uint32_t k = roma_direction_to_map(d, angular, &folded);
            CHECK(k < angular * angular);
            float up[3] = {folded ? -d[0] : d[0], folded ? -d[1] : d[1], folded ? -d[2] : d[2]};
            float a = angle_between(up, cands + 3 * k);
            worst_ratio = fmaxf(worst_ratio, a / radius[k]);
            float neg[3] = {-d[0], -d[1], -d[2]};
            int folded2;
            if (d[2] != 0.0f)
                CHECK(roma_direction_to_map(neg, angular, &folded2) == k && folded2 != folded);
        }
        printf("A=%u: worst angle / stratum radius = %.4f\n", angular, worst_ratio);
        CHECK(worst_ratio <= 1.0001f);
    }

    /* Boundary directions: never out of range, defined for zero and non-finite input. */
    const uint32_t A = 4;
    float specials[][3] = {{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0},
                           {1, 1, 0}, {1, -1, 0}, {-1, -1, 0}, {1, 1, 1}, {1e-30f, 0, 1}, {0, 1e-38f, -1},
                           {3e38f, 0, 0}, {0, 0, 0}, {NAN, 0, 1}, {INFINITY, 0, 0}};
    for (size_t i = 0; i < sizeof specials / sizeof specials[0]; ++i) {
        int folded;
        uint32_t k = roma_direction_to_map(specials[i], A, &folded);
        CHECK(k < A * A);
    }
    int folded;
    float pole[3] = {0, 0, 1}, south[3] = {0, 0, -1}, zero[3] = {0, 0, 0};
    /* The pole is the centre of the square: with A = 4, the stratum (2, 2). */
    CHECK(roma_direction_to_map(pole, A, &folded) == 2 * A + 2 && !folded);
    CHECK(roma_direction_to_map(south, A, &folded) == 2 * A + 2 && folded);
    CHECK(roma_direction_to_map(zero, A, &folded) == 0);
    /* Horizon directions map to the square's border strata. */
    for (int i = 0; i < 64; ++i) {
        float phi = 2.0f * ROMA_PI * (float)i / 64.0f, d[3] = {cosf(phi), sinf(phi), 0.0f};
        uint32_t k = roma_direction_to_map(d, A, &folded);
        uint32_t sx = k % A, sy = k / A;
        CHECK(sx == 0 || sy == 0 || sx == A - 1 || sy == A - 1);
    }
    /* The tests' tolerance for a device's map selection (ROMA_CPU_SELECTION_TOLERANCE): the
     * neighbour across the edge u = 1/4 (A = 4) is accepted within the tolerance of it, not
     * beyond it, and a stratum two away or another row never. */
    for (int side = -1; side <= 1; side += 2) {
        float near[3], far[3];
        roma_square_to_hemisphere(0.25f + (float)side * 0.5f * ROMA_CPU_SELECTION_TOLERANCE, 0.6f, near);
        roma_square_to_hemisphere(0.25f + (float)side * 2.0f * ROMA_CPU_SELECTION_TOLERANCE, 0.6f, far);
        const uint32_t mine = roma_direction_to_map(near, A, &folded), other = side < 0 ? mine + 1 : mine - 1;
        CHECK(mine == 2 * A + (side < 0 ? 0u : 1u));
        CHECK(roma_cpu_selection_may_differ(near, A, mine, NULL));
        CHECK(roma_cpu_selection_may_differ(near, A, other, NULL));
        CHECK(!roma_cpu_selection_may_differ(far, A, side < 0 ? roma_direction_to_map(far, A, &folded) + 1
                                                               : roma_direction_to_map(far, A, &folded) - 1, NULL));
        CHECK(!roma_cpu_selection_may_differ(near, A, mine + 2, NULL));
        CHECK(!roma_cpu_selection_may_differ(near, A, mine + A, NULL));
    }
    return roma_test_finish("test_directions");
}
