/* Un-snapped rays do not pass a wall one cell thick, at any slant (C mirror of the GPU walk,
 * which test_roma_mirror holds bit-exact to it).
 *
 * A plane through the grid's centre, voxelized conservatively (every cell it touches, as the
 * compute voxelization), rotated into the maps; segments from one side to the other, both
 * ends 3 to 30 cells off the plane, walked without a step bound. The maps sample each column
 * along its centre, so the wall is a staircase whose steps shift from column to column; the
 * walk tests each column past the ray's exit and blocks a ray that leaves one step above
 * and enters the next below (include/roma/trace.glsl). Measured before that test, on the same
 * walls and segments: 489 of the 360,000 passed, up to 241 of 20,000 through one wall (A 4,
 * its normal along z); with it 28, at most 17 through one wall (A 2), none at A 4, 1 at A 8.
 * Testing past the exit over two texels instead of one let 9 pass, but blocked more of the
 * many lights' segments in the default room (test_light_passes: eps_s 0.0313 against 0.0285).
 * Segments parallel to the plane 3 cells off it must not be blocked: the test adds no
 * reach beside a surface. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "harness.h"
#include "rotate/directions.h"
#include "rotate/map_params.h"
#include "trace/cpu_mirror.h"

#define RES 64u
#define SEGMENTS 20000

/* Measured: at most 17 of 20,000 crossing segments pass; none of the parallel ones 3 cells
 * off is blocked (nor was one before the test past the exit). */
#define MAX_PASSING 20
#define MAX_BLOCKED_BESIDE 0

static uint32_t rng_state = 12345u;
static float uniform(void)
{
    rng_state = rng_state * 1664525u + 1013904223u;
    return (float)(rng_state >> 8) * (1.0f / 16777216.0f);
}

static float dot3(const float a[3], const float b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* A point of the box [-0.8, 0.8]^3 moved along n to signed distance d from the plane. */
static void point_at(const float n[3], float d, float p[3])
{
    for (int a = 0; a < 3; ++a)
        p[a] = -0.8f + 1.6f * uniform();
    float off = d - dot3(n, p);
    for (int a = 0; a < 3; ++a)
        p[a] += n[a] * off;
}

static int blocked(const roma_grid_params *grid, const roma_map_frame *frames, const uint32_t *maps,
                   const float p[3], const float q[3])
{
    float v[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
    float len = sqrtf(dot3(v, v));
    roma_ray r = {{p[0], p[1], p[2]}, 0.0f, {v[0] / len, v[1] / len, v[2] / len}, len};
    return (roma_cpu_trace(grid, frames, maps, &r, ROMA_TRACE_UNSNAPPED_ANY, 1u << 20, -1, 0).info & ROMA_HIT_FLAG) != 0;
}

static void wall(uint32_t angular, const float normal_in[3])
{
    const uint32_t words = RES / 32, maps_n = angular * angular;
    float len = sqrtf(dot3(normal_in, normal_in)), n[3] = {normal_in[0] / len, normal_in[1] / len, normal_in[2] / len};
    roma_grid_params grid;
    const float lo[3] = {-1, -1, -1}, hi[3] = {1, 1, 1}, jitter[3] = {0.1f, -0.2f, 0.3f};
    CHECK(roma_compute_grid(lo, hi, RES, angular, 1.0f, jitter, &grid));
    float *dirs = malloc(sizeof(float) * 3 * maps_n);
    roma_map_frame *frames = calloc(maps_n, sizeof *frames);
    uint32_t *bom = calloc((size_t)RES * RES * words, sizeof *bom);
    uint32_t *maps = calloc((size_t)maps_n * RES * RES * words, sizeof *maps);
    if (!dirs || !frames || !bom || !maps) {
        CHECK(!"out of memory");
        goto done;
    }
    roma_candidate_directions(angular, 7, 0, 1, dirs);
    for (uint32_t k = 0; k < maps_n; ++k)
        roma_compute_map_frame(&grid, &dirs[3 * k], &frames[k]);
    const float cell = grid.origin[3], half = 0.5f * cell * (fabsf(n[0]) + fabsf(n[1]) + fabsf(n[2]));
    for (uint32_t z = 0; z < RES; ++z)
        for (uint32_t y = 0; y < RES; ++y)
            for (uint32_t x = 0; x < RES; ++x) {
                float c[3] = {grid.origin[0] + ((float)x + 0.5f) * cell, grid.origin[1] + ((float)y + 0.5f) * cell,
                              grid.origin[2] + ((float)z + 0.5f) * cell};
                if (fabsf(dot3(n, c)) <= half)
                    bom[(y * RES + x) * words + (z >> 5)] |= 1u << (z & 31u);
            }
    roma_cpu_rotate(&grid, frames, bom, maps);
    int passing = 0, beside = 0;
    for (int i = 0; i < SEGMENTS; ++i) {
        float p[3], q[3];
        point_at(n, (3.0f + 27.0f * uniform()) * cell, p);
        point_at(n, -(3.0f + 27.0f * uniform()) * cell, q);
        passing += !blocked(&grid, frames, maps, p, q);
        point_at(n, 3.0f * cell, p);
        point_at(n, 3.0f * cell, q);
        beside += blocked(&grid, frames, maps, p, q);
    }
    printf("A %2u, wall normal (%5.2f %5.2f %5.2f): %d of %d crossing segments pass, %d of %d beside it blocked\n",
           angular, n[0], n[1], n[2], passing, SEGMENTS, beside, SEGMENTS);
    CHECK(passing <= MAX_PASSING);
    CHECK(beside <= MAX_BLOCKED_BESIDE);
done:
    free(dirs);
    free(frames);
    free(bom);
    free(maps);
}

int main(void)
{
    static const float normals[][3] = {{0, 0, 1}, {1, 2, 3}, {0.3f, 1, 0.1f}, {0.1f, 0.2f, 1}, {0.05f, 1, 0.6f},
                                       {1, 0.02f, 0.01f}};
    static const uint32_t angulars[] = {2, 4, 8};
    for (size_t a = 0; a < sizeof angulars / sizeof angulars[0]; ++a)
        for (size_t i = 0; i < sizeof normals / sizeof normals[0]; ++i)
            wall(angulars[a], normals[i]);
    return roma_test_finish("test_thin_walls");
}
