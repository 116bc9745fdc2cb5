/* roma-bench --cascades: the build of cascade levels around a camera against one grid. */
#include "cascades.h"

#include <math.h>
#include <stdlib.h>

#include "app_common.h"
#include "frame.h"
#include "roma/map.h"
#include "vulkan/vk_internal.h"

#define SEED 7u

typedef struct cascade_case {
    const char *name;
    uint32_t levels; /* 1: one grid over the scene */
    int jitter, moving;
} cascade_case;

/* One run: frames builds of the case, the mean host-observed milliseconds a build and the mean
 * levels a build redid. */
static int run_case(roma_context *ctx, roma_map *map, const roma_bench_cascades_desc *d, const cascade_case *c,
                    float finest, uint32_t first_frame, double *ms, double *rebuilt)
{
    float eye[3], way[3], length = 0.0f;
    for (int a = 0; a < 3; ++a) {
        eye[a] = d->camera.eye[a];
        way[a] = d->camera.target[a] - d->camera.eye[a];
        length += way[a] * way[a];
    }
    length = sqrtf(length);
    const float step = finest / (float)d->resolution; /* one finest cell a frame */
    double total = 0.0, levels = 0.0;
    for (uint32_t f = 0; f < d->frames; ++f) {
        float focus[3];
        for (int a = 0; a < 3; ++a)
            focus[a] = eye[a] + (c->moving && length > 0.0f ? way[a] / length * step * (float)f : 0.0f);
        roma_map_frame_desc fd = {.frame = first_frame + f, .seed = SEED, .jitter_grid = c->jitter,
                                  .jitter_directions = c->jitter};
        if (c->levels > 1) {
            fd.focus = focus;
            fd.finest_extent = finest;
        }
        VkCommandBuffer cmd;
        if (roma_begin_one_shot(ctx, &cmd) != ROMA_SUCCESS)
            return 0;
        const double t = roma_bench_submit_ms(ctx, cmd, roma_map_record_build(map, cmd, &fd, NULL));
        if (!isfinite(t))
            return 0;
        roma_map_info info;
        roma_map_get_info(map, &info);
        total += t;
        levels += info.levels_rebuilt;
    }
    *ms = total / d->frames;
    *rebuilt = levels / d->frames;
    return 1;
}

int roma_bench_cascades(roma_context *ctx, const roma_scene *scene, const roma_bench_cascades_desc *d, FILE *csv)
{
    const uint32_t runs = d->runs ? d->runs : 5;
    const float finest = roma_app_finest_extent(d->resolution, d->radius);
    if (!(finest > 0.0f) || d->levels < 2 || d->frames == 0) {
        fprintf(stderr, "roma-bench: --cascades needs a positive, finite --ao-radius, K >= 2 and frames\n");
        return 1;
    }
    const cascade_case cases[4] = {
        {"one grid, jittered", 1, 1, 1},
        {"levels along the path, jittered", d->levels, 1, 1},
        {"levels along the path, unjittered", d->levels, 0, 1},
        {"levels, camera still, unjittered", d->levels, 0, 0},
    };
    roma_map *maps[2] = {NULL, NULL};
    double *samples = malloc(sizeof(double) * runs * 8);
    roma_result r = samples ? ROMA_SUCCESS : ROMA_ERROR_OUT_OF_HOST_MEMORY;
    for (int m = 0; m < 2 && r == ROMA_SUCCESS; ++m) {
        const roma_map_desc md = {.resolution = d->resolution, .angular = 4, .cascades = m ? d->levels : 1};
        r = roma_map_create(ctx, &md, scene, &maps[m]);
    }
    if (r != ROMA_SUCCESS) {
        fprintf(stderr, "roma-bench: --cascades: setup failed: %s\n", roma_result_string(r));
        roma_map_destroy(maps[0]);
        roma_map_destroy(maps[1]);
        free(samples);
        return 1;
    }
    printf("\nThe build of %u cascade levels around the camera against one grid over the scene: RES %u, A 4, the\n"
           "finest level %.3g wide (30 cells to the AO radius %.3g), the camera moving towards its target\n"
           "by one finest cell (%.3g) a frame; milliseconds a build, host-observed (one submission, submit\n"
           "to fence), the mean of %u frames, medians of %u runs.\n\n"
           "| build | levels | ms a build | levels rebuilt a build | ratio to one grid |\n|---|---|---|---|---|\n",
           d->levels, d->resolution, (double)finest, (double)d->radius, (double)(finest / (float)d->resolution),
           d->frames, runs);
    int status = 0;
    double one_grid = NAN;
    for (int c = 0; c < 4 && status == 0; ++c) {
        roma_map *map = maps[cases[c].levels > 1];
        /* A first build of the case's start, not timed: the levels then hold what the case
         * starts from (pipelines made, a still camera's levels built). */
        double warm_ms, warm_levels;
        roma_bench_cascades_desc one = *d;
        one.frames = 1;
        if (!run_case(ctx, map, &one, &cases[c], finest, 0, &warm_ms, &warm_levels)) {
            status = 1;
            break;
        }
        for (uint32_t k = 0; k < runs; ++k)
            if (!run_case(ctx, map, d, &cases[c], finest, 1 + k * d->frames, &samples[k], &samples[runs + k])) {
                status = 1;
                break;
            }
        if (status)
            break;
        const double ms = roma_app_median(samples, (int)runs);
        const double levels = roma_app_median(samples + runs, (int)runs);
        if (c == 0)
            one_grid = ms;
        printf("| %s | %u | %.2f | %.2f | %.2fx |\n", cases[c].name, cases[c].levels, ms, levels, ms / one_grid);
        if (csv)
            fprintf(csv, "cascades,%s,%u,4,%.6f,ms\n", cases[c].name, d->resolution, ms);
    }
    if (status)
        fprintf(stderr, "roma-bench: --cascades: a build failed\n");
    roma_map_destroy(maps[0]);
    roma_map_destroy(maps[1]);
    free(samples);
    return status;
}
