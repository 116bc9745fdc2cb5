/* roma-bench --cascades: the build of cascade levels around a camera against one grid. */
#include "cascades.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "app_common.h"
#include "frame.h"
#include "roma/builtin_scenes.h"
#include "roma/map.h"
#include "vulkan/upload.h"
#include "vulkan/vk_internal.h"

#define SEED 7u

typedef struct cascade_case {
    const char *name;
    uint32_t levels; /* 1: one grid over the scene */
    int jitter, moving;
    int object;      /* the camera still, a dynamic object moving in front of it */
    int skinned;     /* the camera still, the object bent every frame: 1 by its mesh's positions
                        (roma_mesh_positions), 2 by the whole scene's (gpu_positions) */
} cascade_case;

/* Two poses of the object bent as a skinned character's would be (a shear growing with height
 * and a stretch), written on the GPU each frame by an engine: its own positions (local frame)
 * and the whole scene's (the level and the object placed at frame 0), device-local, 12 bytes
 * a vertex, as an animator's output. */
typedef struct skin_poses {
    roma_buffer mesh[2], whole[2];
    roma_box mesh_box[2], whole_box[2];
    uint32_t whole_vertices;
} skin_poses;

static void skin_poses_destroy(roma_context *ctx, skin_poses *p)
{
    for (int k = 0; k < 2; ++k) {
        roma_buffer_destroy(ctx, &p->mesh[k]);
        roma_buffer_destroy(ctx, &p->whole[k]);
    }
}

static roma_result skin_poses_create(roma_context *ctx, const roma_scene *level, const roma_scene *object,
                                     const float t[12], skin_poses *p)
{
    memset(p, 0, sizeof *p);
    roma_scene_view lv, ov;
    roma_scene_get_view(level, &lv);
    roma_scene_get_view(object, &ov);
    p->whole_vertices = lv.vertex_count + ov.vertex_count;
    float *mesh = malloc(12ull * ov.vertex_count), *whole = malloc(12ull * p->whole_vertices);
    roma_result r = mesh && whole ? ROMA_SUCCESS : ROMA_ERROR_OUT_OF_HOST_MEMORY;
    const VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;
    for (int k = 0; k < 2 && r == ROMA_SUCCESS; ++k) {
        for (int a = 0; a < 3; ++a) { /* the whole scene's box grows from the level's */
            p->mesh_box[k].min[a] = INFINITY;
            p->mesh_box[k].max[a] = -INFINITY;
            p->whole_box[k].min[a] = lv.bounds_min[a];
            p->whole_box[k].max[a] = lv.bounds_max[a];
        }
        memcpy(whole, lv.positions, 12ull * lv.vertex_count);
        const float bend = 0.1f * (float)(k + 1);
        for (uint32_t i = 0; i < ov.vertex_count; ++i) {
            const float *q = ov.positions + 3 * i;
            const float h = (q[1] - ov.bounds_min[1]) / (ov.bounds_max[1] - ov.bounds_min[1]);
            const float bent[3] = {q[0] + bend * h * (ov.bounds_max[0] - ov.bounds_min[0]), q[1] * (1.0f + 0.5f * bend),
                                   q[2]};
            for (int a = 0; a < 3; ++a) {
                const float *row = t + 4 * a;
                const float w = row[0] * bent[0] + row[1] * bent[1] + row[2] * bent[2] + row[3];
                mesh[3 * i + a] = bent[a];
                whole[3 * (lv.vertex_count + i) + a] = w;
                p->mesh_box[k].min[a] = fminf(p->mesh_box[k].min[a], bent[a]);
                p->mesh_box[k].max[a] = fmaxf(p->mesh_box[k].max[a], bent[a]);
                p->whole_box[k].min[a] = fminf(p->whole_box[k].min[a], w);
                p->whole_box[k].max[a] = fmaxf(p->whole_box[k].max[a], w);
            }
        }
        r = roma_buffer_create_filled(ctx, 12ull * ov.vertex_count, usage, mesh, &p->mesh[k]);
        if (r == ROMA_SUCCESS)
            r = roma_buffer_create_filled(ctx, 12ull * p->whole_vertices, usage, whole, &p->whole[k]);
    }
    free(mesh);
    free(whole);
    if (r != ROMA_SUCCESS)
        skin_poses_destroy(ctx, p);
    return r;
}

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

roma_scene *roma_bench_level_with_object(const roma_scene *level, const roma_scene *object, const float t[12])
{
    roma_scene_view lv, ov;
    roma_scene_get_view(level, &lv);
    roma_scene_get_view(object, &ov);
    const uint32_t vertices = lv.vertex_count + ov.vertex_count, triangles = lv.triangle_count + ov.triangle_count;
    float *positions = malloc(sizeof(float) * 3 * vertices);
    uint32_t *indices = malloc(sizeof(uint32_t) * 3 * triangles);
    roma_scene *out = NULL;
    if (positions && indices) {
        memcpy(positions, lv.positions, sizeof(float) * 3 * lv.vertex_count);
        memcpy(indices, lv.indices, sizeof(uint32_t) * 3 * lv.triangle_count);
        for (uint32_t v = 0; v < ov.vertex_count; ++v)
            for (int a = 0; a < 3; ++a) {
                const float *p = ov.positions + 3 * v, *row = t + 4 * a;
                positions[3 * (lv.vertex_count + v) + a] = row[0] * p[0] + row[1] * p[1] + row[2] * p[2] + row[3];
            }
        for (uint32_t i = 0; i < 3 * ov.triangle_count; ++i)
            indices[3 * lv.triangle_count + i] = ov.indices[i] + lv.vertex_count;
        const roma_scene_desc sd = {.positions = positions, .vertex_count = vertices, .indices = indices,
                                    .triangle_count = triangles};
        if (roma_scene_create(&sd, &out) != ROMA_SUCCESS)
            out = NULL;
    }
    free(positions);
    free(indices);
    return out;
}

/* One run: frames builds of the case, the mean host-observed milliseconds a build, the mean
 * levels a build redid and the mean triangles it voxelized (its levels' summed). */
static int run_case(roma_context *ctx, roma_map *map, const roma_bench_cascades_desc *d, const cascade_case *c,
                    const roma_scene *object, uint32_t instance, uint32_t mesh, const skin_poses *poses, float finest,
                    uint32_t first_frame, double *ms, double *rebuilt, double *voxelized)
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
        const int pose = (int)((first_frame + f) % 2u);
        const roma_mesh_positions posed = {.mesh = mesh, .gpu_positions = poses->mesh[pose].address,
                                           .bounds = poses->mesh_box[pose]};
        if (c->skinned == 1) {
            fd.mesh_positions = &posed;
            fd.mesh_position_count = 1;
        } else if (c->skinned == 2) {
            fd.gpu_positions = poses->whole[pose].address;
            fd.vertex_count = poses->whole_vertices;
            fd.volume = &poses->whole_box[pose];
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
    enum { CASES = 7, MAPS = 5 };
    const cascade_case cases[CASES] = {
        {"one grid, jittered", 1, 1, 1, 0, 0},
        {"levels along the path, jittered", d->levels, 1, 1, 0, 0},
        {"levels along the path, unjittered", d->levels, 0, 1, 0, 0},
        {"levels, camera still, unjittered", d->levels, 0, 0, 0, 0},
        {"levels, camera still, unjittered, an object moving", d->levels, 0, 0, 1, 0},
        {"levels, camera still, unjittered, the object skinned (its mesh's positions)", d->levels, 0, 0, 0, 1},
        {"levels, camera still, unjittered, the object skinned (the whole scene's positions)", d->levels, 0, 0, 0, 2},
    };
    /* One grid, the levels, the levels with the object as a dynamic instance (moving, then
     * skinned: two maps), and the levels of one scene holding both (its positions given whole). */
    roma_map *maps[MAPS] = {NULL, NULL, NULL, NULL, NULL};
    roma_scene *object = NULL, *with = NULL;
    uint32_t mesh[2] = {0, 0}, instance[2] = {0, 0};
    skin_poses poses;
    memset(&poses, 0, sizeof poses);
    float t0[12];
    double *samples = malloc(sizeof(double) * runs * 8);
    roma_result r = samples ? ROMA_SUCCESS : ROMA_ERROR_OUT_OF_HOST_MEMORY;
    if (r == ROMA_SUCCESS)
        r = roma_scene_create_builtin("cornell", NULL, &object);
    if (r == ROMA_SUCCESS) {
        roma_bench_object_transform(d, object, finest, 0, t0);
        with = roma_bench_level_with_object(scene, object, t0);
        r = with ? skin_poses_create(ctx, scene, object, t0, &poses) : ROMA_ERROR_OUT_OF_HOST_MEMORY;
    }
    for (int m = 0; m < MAPS && r == ROMA_SUCCESS; ++m) {
        const roma_map_desc md = {.resolution = d->resolution, .angular = 4, .cascades = m ? d->levels : 1};
        r = roma_map_create(ctx, &md, m == 4 ? with : scene, &maps[m]);
    }
    for (int m = 0; m < 2 && r == ROMA_SUCCESS; ++m) {
        r = roma_map_add_mesh(maps[2 + m], object, &mesh[m]);
        roma_instance_desc id = {.mesh = mesh[m], .flags = ROMA_INSTANCE_DYNAMIC};
        memcpy(id.transform, t0, sizeof t0);
        if (r == ROMA_SUCCESS)
            r = roma_map_add_instance(maps[2 + m], &id, &instance[m]);
    }
    if (r != ROMA_SUCCESS) {
        fprintf(stderr, "roma-bench: --cascades: setup failed: %s\n", roma_result_string(r));
        for (int m = 0; m < MAPS; ++m)
            roma_map_destroy(maps[m]);
        skin_poses_destroy(ctx, &poses);
        roma_scene_destroy(with);
        roma_scene_destroy(object);
        free(samples);
        return 1;
    }
    printf("\nThe build of %u cascade levels around the camera against one grid over the scene: RES %u, A 4, the\n"
           "finest level %.3g wide (30 cells to the AO radius %.3g), the camera moving towards its target\n"
           "by one finest cell (%.3g) a frame; milliseconds a build, host-observed (one submission, submit\n"
           "to fence), the mean of %u frames, medians of %u runs. The object: the built-in room shrunk to\n"
           "%.3g, %.3g in front of the camera, a dynamic instance moving sideways by a finest cell a frame;\n"
           "skinned: held at its start and bent into one of two poses a frame, the positions written on the\n"
           "GPU (device-local) and given as its mesh's (roma_mesh_positions) or as the whole scene's\n"
           "(gpu_positions: one scene of the level and the object, the route without meshes).\n\n"
           "| build | levels | ms a build | levels rebuilt a build | triangles voxelized a build | ratio to one grid |\n"
           "|---|---|---|---|---|---|\n",
           d->levels, d->resolution, (double)finest, (double)d->radius, (double)(finest / (float)d->resolution),
           d->frames, runs, (double)(finest / 6.0f), (double)(finest / 4.0f));
    int status = 0;
    double one_grid = NAN;
    for (int c = 0; c < CASES && status == 0; ++c) {
        roma_map *map = maps[cases[c].skinned ? 2 + cases[c].skinned : cases[c].object ? 2 : cases[c].levels > 1];
        const int m = cases[c].skinned == 1; /* which map's mesh and instance */
        /* A first build of the case's start, not timed: the levels then hold what the case
         * starts from (pipelines made, a still camera's levels built). */
        double warm_ms, warm_levels, warm_triangles;
        roma_bench_cascades_desc one = *d;
        one.frames = 1;
        if (!run_case(ctx, map, &one, &cases[c], object, instance[m], mesh[m], &poses, finest, 0, &warm_ms,
                      &warm_levels, &warm_triangles)) {
            status = 1;
            break;
        }
        for (uint32_t k = 0; k < runs; ++k)
            if (!run_case(ctx, map, d, &cases[c], object, instance[m], mesh[m], &poses, finest, 1 + k * d->frames,
                          &samples[k], &samples[runs + k], &samples[2 * runs + k])) {
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
    for (int m = 0; m < MAPS; ++m)
        roma_map_destroy(maps[m]);
    skin_poses_destroy(ctx, &poses);
    roma_scene_destroy(with);
    roma_scene_destroy(object);
    free(samples);
    return status;
}
