/* roma-bench --cascades: the build of cascade levels around a camera against one grid. */
#include "cascades.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "app_common.h"
#include "frame.h"
#include "roma/builtin_scenes.h"
#include "roma/map.h"
#include "vulkan/vk_internal.h"

#define SEED 7u

typedef struct cascade_case {
    const char *name;
    uint32_t levels; /* 1: one grid over the scene */
    int jitter, moving;
    int object;      /* the camera still, a dynamic object moving in front of it */
} cascade_case;

void roma_bench_object_transform(const roma_bench_cascades_desc *d, const roma_scene *object, float finest,
                                 uint32_t f, float t[12])
{
    roma_scene_view v;
    roma_scene_get_view(object, &v);
    float way[3], length = 0.0f, longest = 0.0f;
    for (int a = 0; a < 3; ++a) {
        way[a] = d->camera.target[a] - d->camera.eye[a];
        length += way[a] * way[a];
        longest = fmaxf(longest, v.bounds_max[a] - v.bounds_min[a]);
    }
    length = sqrtf(length);
    const float s = finest / 6.0f / longest, ahead = finest / 4.0f, step = finest / (float)d->resolution;
    /* sideways: the horizontal perpendicular of the view direction */
    float side[3] = {-way[2], 0.0f, way[0]}, sl = sqrtf(way[0] * way[0] + way[2] * way[2]);
    memset(t, 0, 12 * sizeof *t);
    for (int a = 0; a < 3; ++a) {
        const float centre = 0.5f * (v.bounds_min[a] + v.bounds_max[a]);
        t[5 * a] = s;
        t[4 * a + 3] = d->camera.eye[a] + (length > 0.0f ? way[a] / length * ahead : 0.0f) +
                       (sl > 0.0f ? side[a] / sl * step * (float)(f % 16u) : 0.0f) - s * centre;
    }
}

/* One run: frames builds of the case, the mean host-observed milliseconds a build, the mean
 * levels a build redid and the mean triangles it voxelized (its levels' summed). */
static int run_case(roma_context *ctx, roma_map *map, const roma_bench_cascades_desc *d, const cascade_case *c,
                    const roma_scene *object, uint32_t instance, float finest, uint32_t first_frame, double *ms,
                    double *rebuilt, double *voxelized)
{
    float eye[3], way[3], length = 0.0f;
    for (int a = 0; a < 3; ++a) {
        eye[a] = d->camera.eye[a];
        way[a] = d->camera.target[a] - d->camera.eye[a];
        length += way[a] * way[a];
    }
    length = sqrtf(length);
    const float step = finest / (float)d->resolution; /* one finest cell a frame */
    double total = 0.0, levels = 0.0, triangles = 0.0;
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
        if (c->object) {
            float t[12];
            roma_bench_object_transform(d, object, finest, first_frame + f, t);
            if (roma_map_set_instance_transform(map, instance, t) != ROMA_SUCCESS)
                return 0;
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
        triangles += (double)info.triangles_voxelized;
    }
    *ms = total / d->frames;
    *rebuilt = levels / d->frames;
    *voxelized = triangles / d->frames;
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
    enum { CASES = 5 };
    const cascade_case cases[CASES] = {
        {"one grid, jittered", 1, 1, 1, 0},
        {"levels along the path, jittered", d->levels, 1, 1, 0},
        {"levels along the path, unjittered", d->levels, 0, 1, 0},
        {"levels, camera still, unjittered", d->levels, 0, 0, 0},
        {"levels, camera still, unjittered, an object moving", d->levels, 0, 0, 1},
    };
    /* One grid, the levels, and the levels with the object as a dynamic instance. */
    roma_map *maps[3] = {NULL, NULL, NULL};
    roma_scene *object = NULL;
    uint32_t mesh = 0, instance = 0;
    double *samples = malloc(sizeof(double) * runs * 8);
    roma_result r = samples ? ROMA_SUCCESS : ROMA_ERROR_OUT_OF_HOST_MEMORY;
    for (int m = 0; m < 3 && r == ROMA_SUCCESS; ++m) {
        const roma_map_desc md = {.resolution = d->resolution, .angular = 4, .cascades = m ? d->levels : 1};
        r = roma_map_create(ctx, &md, scene, &maps[m]);
    }
    if (r == ROMA_SUCCESS)
        r = roma_scene_create_builtin("cornell", NULL, &object);
    if (r == ROMA_SUCCESS)
        r = roma_map_add_mesh(maps[2], object, &mesh);
    if (r == ROMA_SUCCESS) {
        roma_instance_desc id = {.mesh = mesh, .flags = ROMA_INSTANCE_DYNAMIC};
        roma_bench_object_transform(d, object, finest, 0, id.transform);
        r = roma_map_add_instance(maps[2], &id, &instance);
    }
    if (r != ROMA_SUCCESS) {
        fprintf(stderr, "roma-bench: --cascades: setup failed: %s\n", roma_result_string(r));
        for (int m = 0; m < 3; ++m)
            roma_map_destroy(maps[m]);
        roma_scene_destroy(object);
        free(samples);
        return 1;
    }
    printf("\nThe build of %u cascade levels around the camera against one grid over the scene: RES %u, A 4, the\n"
           "finest level %.3g wide (30 cells to the AO radius %.3g), the camera moving towards its target\n"
           "by one finest cell (%.3g) a frame; milliseconds a build, host-observed (one submission, submit\n"
           "to fence), the mean of %u frames, medians of %u runs. The object: the built-in room shrunk to\n"
           "%.3g, %.3g in front of the camera, a dynamic instance moving sideways by a finest cell a frame.\n\n"
           "| build | levels | ms a build | levels rebuilt a build | triangles voxelized a build | ratio to one grid |\n"
           "|---|---|---|---|---|---|\n",
           d->levels, d->resolution, (double)finest, (double)d->radius, (double)(finest / (float)d->resolution),
           d->frames, runs, (double)(finest / 6.0f), (double)(finest / 4.0f));
    int status = 0;
    double one_grid = NAN;
    for (int c = 0; c < CASES && status == 0; ++c) {
        roma_map *map = maps[cases[c].object ? 2 : cases[c].levels > 1];
        /* A first build of the case's start, not timed: the levels then hold what the case
         * starts from (pipelines made, a still camera's levels built). */
        double warm_ms, warm_levels, warm_triangles;
        roma_bench_cascades_desc one = *d;
        one.frames = 1;
        if (!run_case(ctx, map, &one, &cases[c], object, instance, finest, 0, &warm_ms, &warm_levels, &warm_triangles)) {
            status = 1;
            break;
        }
        for (uint32_t k = 0; k < runs; ++k)
            if (!run_case(ctx, map, d, &cases[c], object, instance, finest, 1 + k * d->frames, &samples[k],
                          &samples[runs + k], &samples[2 * runs + k])) {
                status = 1;
                break;
            }
        if (status)
            break;
        const double ms = roma_app_median(samples, (int)runs);
        const double levels = roma_app_median(samples + runs, (int)runs);
        const double triangles = roma_app_median(samples + 2 * runs, (int)runs);
        if (c == 0)
            one_grid = ms;
        printf("| %s | %u | %.2f | %.2f | %.0f | %.2fx |\n", cases[c].name, cases[c].levels, ms, levels, triangles,
               ms / one_grid);
        if (csv)
            fprintf(csv, "cascades,%s,%u,4,%.6f,ms\n", cases[c].name, d->resolution, ms);
    }
    if (status)
        fprintf(stderr, "roma-bench: --cascades: a build failed\n");
    for (int m = 0; m < 3; ++m)
        roma_map_destroy(maps[m]);
    roma_scene_destroy(object);
    free(samples);
    return status;
}
