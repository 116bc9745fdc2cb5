/* Cascade levels (roma_map_desc.cascades): nested grids around a focus, each RES^3 with its
 * own A x A maps, traced across by roma/trace.glsl.
 * - Placement: each level's cube holds the last's; with the grid unjittered its origin is a
 *   whole number of its own cells (the focus moved by less than a cell leaves it in place).
 * - Each level's BOM equals the exact CPU voxelizer's on that level's grid, and each
 *   level's maps the C mirror's rotation of it, word for word; on a scene larger than the
 *   levels too, where each level voxelizes only the triangles whose chunk touches it.
 * - Rays from everywhere (the finest level, between levels, outside every level, on the
 *   levels' faces), in every query mode: the GPU's hits equal roma_cpu_trace_levels', the
 *   mirror of the walk across levels, bit for bit (the level in info too); many of them end
 *   in a coarser level than the one they start in.
 * - One level traces as roma_cpu_trace does.
 * - A build keeps the levels whose placement, directions and geometry are unchanged, and what
 *   it keeps equals a new map's build of the same frame. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "map/map_internal.h"
#include "roma/builtin_scenes.h"
#include "roma/map.h"
#include "roma/sampling.h"
#include "trace/cpu_mirror.h"
#include "voxelize_cpu.h"
#include "vulkan/upload.h"

#define RES 64u
#define ANGULAR 4u
#define LEVELS 3u
#define N 4096u

static int same_hit(roma_hit a, roma_hit b)
{
    return a.info == b.info && memcmp(&a.t, &b.t, sizeof a.t) == 0;
}

static int inside(const roma_grid_params *g, const float p[3])
{
    const float side = (float)g->dims[0] * g->origin[3];
    return p[0] >= g->origin[0] && p[0] < g->origin[0] + side && p[1] >= g->origin[1] &&
           p[1] < g->origin[1] + side && p[2] >= g->origin[2] && p[2] < g->origin[2] + side;
}

/* Rays whose origins spread over the coarsest cube and beyond it; every fourth starts on a
 * face of a level's cube. */
static void make_rays(const roma_grid_params *grids, uint32_t seed, roma_ray *rays)
{
    const roma_grid_params *outer = &grids[LEVELS - 1];
    const float side = (float)outer->dims[0] * outer->origin[3];
    for (uint32_t i = 0; i < N; ++i) {
        roma_ray *r = &rays[i];
        const roma_grid_params *near = &grids[i % LEVELS];
        const float near_side = (float)near->dims[0] * near->origin[3];
        for (int a = 0; a < 3; ++a)
            r->origin[a] = i % 2 ? near->origin[a] + near_side * roma_random(seed, i, 0, (uint32_t)a)
                                 : outer->origin[a] + side * (roma_random(seed, i, 0, (uint32_t)a) * 1.2f - 0.1f);
        if (i % 4 == 3) /* on a face of the level's cube */
            r->origin[i / 4 % 3] = near->origin[i / 4 % 3] + (i & 32 ? near_side : 0.0f);
        const float z = 1.0f - 2.0f * roma_random(seed, i, 1, 0), phi = 6.2831853f * roma_random(seed, i, 1, 1);
        const float s = sqrtf(fmaxf(0.0f, 1.0f - z * z));
        r->dir[0] = s * cosf(phi), r->dir[1] = s * sinf(phi), r->dir[2] = z;
        if (i % 16 == 5) /* along an axis */
            r->dir[0] = 0.0f, r->dir[1] = 0.0f, r->dir[2] = i & 64 ? 2.0f : -2.0f;
        const uint32_t kind = i / 2 % 4;
        r->tmin = kind == 1 ? 0.2f * near_side * roma_random(seed, i, 2, 0) : 0.0f;
        r->tmax = kind == 2 ? 0.6f * near_side : kind == 3 ? 3.0f * near_side : INFINITY;
    }
}

/* A map of LEVELS levels at RES, A (NULL on failure, a check failed). */
static roma_map *cascaded_map(roma_context *ctx, const roma_scene *scene)
{
    roma_map *map = NULL;
    CHECK_RESULT(roma_map_create(ctx, &(roma_map_desc){.resolution = RES, .angular = ANGULAR, .cascades = LEVELS},
                                 scene, &map),
                 ROMA_SUCCESS);
    return map;
}

/* Returns the triangles the first build voxelized, its levels' summed (their runs:
 * src/map/level_runs.h); traces: also the traces across the levels. */
static uint64_t check_cascades(roma_context *ctx, const roma_scene *scene, int traces)
{
    uint64_t voxelized = 0;
    roma_scene_view v;
    roma_scene_get_view(scene, &v);
    roma_map *map = cascaded_map(ctx, scene);
    if (!map)
        return 0;
    /* A focus near the floor and a wall, so that every level holds some of them; the finest
     * cube a sixth of the room. */
    float focus[3], longest = 0.0f;
    for (int a = 0; a < 3; ++a) {
        focus[a] = v.bounds_min[a] + (v.bounds_max[a] - v.bounds_min[a]) * (a == 0 ? 0.06f : a == 1 ? 0.05f : 0.55f);
        longest = fmaxf(longest, v.bounds_max[a] - v.bounds_min[a]);
    }
    roma_map_frame_desc frame = {.frame = 3, .seed = 9, .jitter_directions = 1, .focus = focus,
                                 .finest_extent = longest / 6.0f};
    CHECK_RESULT(roma_map_build(map, &frame, NULL), ROMA_SUCCESS);
    roma_map_info info;
    roma_map_get_info(map, &info);
    voxelized = info.triangles_voxelized;
    CHECK(info.levels == LEVELS);
    uint32_t levels = 0;
    const roma_grid_params *grids;
    const roma_map_frame *frames;
    roma_map_get_level_params(map, &levels, &grids, &frames);
    CHECK(levels == LEVELS);

    /* Placement: nested cubes, origins on their own cells; a focus on a corner of the coarsest
     * cells, moved by a tenth of the finest cell, leaves every level where it was. */
    const float coarse = grids[LEVELS - 1].origin[3];
    for (int a = 0; a < 3; ++a)
        focus[a] = roundf(focus[a] / coarse) * coarse;
    CHECK_RESULT(roma_map_build(map, &frame, NULL), ROMA_SUCCESS);
    roma_grid_params first[LEVELS];
    memcpy(first, grids, sizeof first);
    for (uint32_t l = 0; l < LEVELS; ++l) {
        const roma_grid_params *g = &grids[l];
        CHECK(g->level[0] == l && g->level[1] == LEVELS && g->level[2] == l * ANGULAR * ANGULAR);
        for (int a = 0; a < 3; ++a) {
            const double cells = (double)g->origin[a] / g->origin[3];
            CHECK(fabs(cells - floor(cells + 0.5)) < 1e-3);
        }
        if (l > 0) {
            const float *lo = grids[l - 1].origin, side = (float)RES * grids[l - 1].origin[3];
            const float hi[3] = {lo[0] + side * 0.999f, lo[1] + side * 0.999f, lo[2] + side * 0.999f};
            CHECK(inside(g, lo) && inside(g, hi));
            CHECK(fabsf(g->origin[3] / grids[l - 1].origin[3] - 2.0f) < 1e-5f);
        }
    }
    for (int a = 0; a < 3; ++a)
        focus[a] += 0.1f * first[0].origin[3];
    CHECK_RESULT(roma_map_build(map, &frame, NULL), ROMA_SUCCESS);
    CHECK(memcmp(first, grids, sizeof first) == 0);

    /* Each level's BOM against the exact CPU voxelizer, its maps against the mirror. */
    const uint64_t texel_words = (uint64_t)RES * RES * (RES / 32), map_words = texel_words * ANGULAR * ANGULAR;
    uint32_t *bom = malloc(4 * texel_words * LEVELS), *maps = malloc(4 * map_words * LEVELS);
    uint32_t *cpu = malloc(4 * texel_words), *mirror = malloc(4 * map_words);
    if (!bom || !maps || !cpu || !mirror) {
        CHECK(!"out of memory");
        goto done;
    }
    CHECK_RESULT(roma_map_download_bom(map, bom, texel_words * LEVELS), ROMA_SUCCESS);
    CHECK_RESULT(roma_map_download_maps(map, maps, map_words * LEVELS), ROMA_SUCCESS);
    for (uint32_t l = 0; l < LEVELS; ++l) {
        const roma_grid_params *g = &grids[l];
        const roma_voxel_grid vg = {{g->origin[0], g->origin[1], g->origin[2]}, g->inv_cell[0], RES};
        const uint64_t cells = roma_voxelize_cpu(&vg, v.positions, 3, v.indices, v.triangle_count, cpu);
        uint64_t bom_diff = 0, map_diff = 0;
        for (uint64_t i = 0; i < texel_words; ++i)
            bom_diff += bom[l * texel_words + i] != cpu[i];
        roma_cpu_rotate(g, frames + g->level[2], bom + l * texel_words, mirror);
        for (uint64_t i = 0; i < map_words; ++i)
            map_diff += maps[g->level[3] + i] != mirror[i];
        printf("level %u: cell %.4g, %llu BOM cells (%llu words differ from the CPU voxelizer), %llu map words "
               "differ from the mirror\n", l, (double)g->origin[3], (unsigned long long)cells,
               (unsigned long long)bom_diff, (unsigned long long)map_diff);
        CHECK(cells > 0 && bom_diff == 0 && map_diff == 0);
    }

    if (!traces)
        goto done;
    /* Traces across the levels against the mirror. */
    static roma_ray rays[N];
    static roma_hit gpu[N];
    make_rays(grids, 17, rays);
    for (int m = 0; m < 4; ++m) {
        CHECK_RESULT(roma_map_trace(map, (roma_trace_mode)m, 8, rays, N, gpu, NULL), ROMA_SUCCESS);
        uint32_t mismatch = 0, selection = 0, off_edge = 0, hits = 0, crossed = 0;
        for (uint32_t i = 0; i < N; ++i) {
            const roma_hit cpu_hit = roma_cpu_trace_levels(LEVELS, grids, frames, maps, &rays[i], (roma_trace_mode)m, 8,
                                                           -1, 0);
            int folded;
            const uint32_t k = roma_cpu_select_map(rays[i].dir, ANGULAR, &folded);
            uint32_t start = LEVELS - 1;
            for (uint32_t l = 0; l + 1 < LEVELS; ++l)
                if (inside(&grids[l], rays[i].origin)) {
                    start = l;
                    break;
                }
            hits += gpu[i].info & 1u;
            crossed += ROMA_HIT_LEVEL(gpu[i].info) > start;
            if (!same_hit(cpu_hit, gpu[i])) {
                /* Map selection may round apart on a stratum edge, within what Vulkan lets atan
                 * and sqrt round (ROMA_CPU_SELECTION_TOLERANCE): then the mirror is off too. */
                if (k != ROMA_HIT_MAP(gpu[i].info)) {
                    ++selection;
                    off_edge += !roma_cpu_selection_may_differ(rays[i].dir, ANGULAR, ROMA_HIT_MAP(gpu[i].info), NULL);
                    continue;
                }
                if (mismatch < 3)
                    fprintf(stderr, "  mode %d ray %u: gpu (%.9g, %#x) cpu (%.9g, %#x)\n", m, i, gpu[i].t,
                            gpu[i].info, cpu_hit.t, cpu_hit.info);
                ++mismatch;
            }
        }
        printf("  mode %d: %u/%u hits, %u ended in a coarser level than they began, %u mismatches, %u selection "
               "differences (%u off a stratum edge)\n", m, hits, N, crossed, mismatch, selection, off_edge);
        CHECK(mismatch == 0);
        CHECK(off_edge == 0);
        CHECK(hits > N / 10 && crossed > N / 10);
    }
    /* One level: the levels' walk is the single grid's trace. */
    uint32_t single_diff = 0;
    for (uint32_t i = 0; i < N; ++i)
        for (int m = 0; m < 4; ++m) {
            roma_grid_params g0 = grids[0];
            g0.level[1] = 1;
            const roma_hit walked = roma_cpu_trace_levels(1, &g0, frames, maps, &rays[i], (roma_trace_mode)m, 8, -1, 0);
            single_diff += !same_hit(walked, roma_cpu_trace(&g0, frames, maps, &rays[i], (roma_trace_mode)m, 8, -1, 0));
        }
    CHECK(single_diff == 0);

    /* Rays that are not traced are the plain miss (t = INFINITY, info 0) across levels too, on
     * the device and in the mirror: a NaN tmax in a coarser level's cube found hits (the levels'
     * min() dropped the NaN; fuzz_trace), and the level bits must not say where the origin was. */
    {
        const roma_grid_params *outer = &grids[LEVELS - 1];
        float p[3];
        for (int a = 0; a < 3; ++a)
            p[a] = outer->origin[a] + 0.3f * outer->origin[3] * (float)outer->dims[0];
        const roma_ray bad[5] = {{{p[0], p[1], p[2]}, 0.0f, {0.0f, 0.0f, 1.0f}, NAN},
                                 {{p[0], p[1], p[2]}, NAN, {1.0f, 0.0f, 0.0f}, INFINITY},
                                 {{p[0], p[1], p[2]}, 2.0f, {0.0f, -1.0f, 0.0f}, 1.0f},
                                 {{p[0], NAN, p[2]}, 0.0f, {0.6f, 0.8f, 0.0f}, INFINITY},
                                 {{p[0], p[1], p[2]}, 0.0f, {0.0f, 0.0f, 0.0f}, INFINITY}};
        roma_hit out[5];
        uint32_t not_plain = 0;
        for (int m = 0; m < 4; ++m) {
            CHECK_RESULT(roma_map_trace(map, (roma_trace_mode)m, 8, bad, 5, out, NULL), ROMA_SUCCESS);
            for (int i = 0; i < 5; ++i) {
                const roma_hit cpu_hit = roma_cpu_trace_levels(LEVELS, grids, frames, maps, &bad[i], (roma_trace_mode)m,
                                                               8, -1, 0);
                not_plain += !(out[i].t == INFINITY && out[i].info == 0u) + !(cpu_hit.t == INFINITY && cpu_hit.info == 0u);
            }
        }
        printf("untraced rays across levels: %u of 40 answers not the plain miss\n", not_plain);
        CHECK(not_plain == 0);
    }
done:
    free(bom);
    free(maps);
    free(cpu);
    free(mirror);
    roma_map_destroy(map);
    return voxelized;
}

/* SCATTERED^3 small triangles on a 1 m lattice, in slabs of constant z (256 triangles, a
 * chunk of level_runs.h, each) laid out in bit-reversed order: a level's cube touches
 * slabs spread over the triangle order, so that its runs are several and merge. */
#define SCATTERED 16u
static roma_scene *scattered_scene(void)
{
    const uint32_t n = SCATTERED * SCATTERED * SCATTERED;
    float *positions = malloc(sizeof(float) * 9 * n);
    uint32_t *indices = malloc(sizeof(uint32_t) * 3 * n);
    roma_scene *scene = NULL;
    if (positions && indices) {
        for (uint32_t t = 0; t < n; ++t) {
            const uint32_t slab = t / (SCATTERED * SCATTERED), in = t % (SCATTERED * SCATTERED);
            const uint32_t z = ((slab & 1u) << 3) | ((slab & 2u) << 1) | ((slab & 4u) >> 1) | ((slab & 8u) >> 3);
            const float c[3] = {(float)(in % SCATTERED), (float)(in / SCATTERED), (float)z};
            const float corner[3][3] = {{0.0f, 0.0f, 0.0f}, {0.3f, 0.05f, 0.1f}, {0.05f, 0.3f, 0.2f}};
            for (int k = 0; k < 3; ++k)
                for (int a = 0; a < 3; ++a)
                    positions[9 * t + 3 * k + a] = c[a] + corner[k][a];
            indices[3 * t] = 3 * t, indices[3 * t + 1] = 3 * t + 1, indices[3 * t + 2] = 3 * t + 2;
        }
        const roma_scene_desc d = {.positions = positions, .vertex_count = 3 * n, .indices = indices,
                                   .triangle_count = n, .name = "scattered"};
        CHECK_RESULT(roma_scene_create(&d, &scene), ROMA_SUCCESS);
    }
    free(positions);
    free(indices);
    return scene;
}

/* The maps and BOM of every level, downloaded (words: RES^3/32 per level, then the maps). */
static int download_all(roma_map *map, uint32_t *bom, uint32_t *maps)
{
    const uint64_t texel_words = (uint64_t)RES * RES * (RES / 32), map_words = texel_words * ANGULAR * ANGULAR;
    return roma_map_download_bom(map, bom, texel_words * LEVELS) == ROMA_SUCCESS &&
           roma_map_download_maps(map, maps, map_words * LEVELS) == ROMA_SUCCESS;
}

/* Reuse: a build keeps each level whose placement, directions and geometry are unchanged, and
 * what it keeps and rebuilds is word for word what a new map's first build of the same frame
 * holds: the same frame again rebuilds nothing; a focus moved by a few finest cells rebuilds
 * the levels that moved, not the others; jittered directions rotate every level again; new
 * positions (the same ones) rebuild every level. */
static void check_reuse(roma_context *ctx, const roma_scene *scene)
{
    roma_scene_view v;
    roma_scene_get_view(scene, &v);
    const roma_map_desc desc = {.resolution = RES, .angular = ANGULAR, .cascades = LEVELS};
    roma_map *map = NULL;
    CHECK_RESULT(roma_map_create(ctx, &desc, scene, &map), ROMA_SUCCESS);
    const uint64_t texel_words = (uint64_t)RES * RES * (RES / 32), map_words = texel_words * ANGULAR * ANGULAR;
    uint32_t *bom = malloc(4 * texel_words * LEVELS), *maps = malloc(4 * map_words * LEVELS);
    uint32_t *bom2 = malloc(4 * texel_words * LEVELS), *maps2 = malloc(4 * map_words * LEVELS);
    if (!map || !bom || !maps || !bom2 || !maps2) {
        CHECK(map && "out of memory");
        goto done;
    }
    float focus[3], longest = 0.0f;
    for (int a = 0; a < 3; ++a) {
        focus[a] = v.bounds_min[a] + (v.bounds_max[a] - v.bounds_min[a]) * (a == 0 ? 0.06f : a == 1 ? 0.05f : 0.55f);
        longest = fmaxf(longest, v.bounds_max[a] - v.bounds_min[a]);
    }
    roma_map_frame_desc frame = {.frame = 1, .seed = 9, .focus = focus, .finest_extent = longest / 6.0f};
    roma_map_info info;
    CHECK_RESULT(roma_map_build(map, &frame, NULL), ROMA_SUCCESS);
    roma_map_get_info(map, &info);
    CHECK(info.levels_rebuilt == LEVELS);
    CHECK(info.static_copy_bytes == 0); /* no dynamic instance */
    CHECK_RESULT(roma_map_build(map, &frame, NULL), ROMA_SUCCESS);
    roma_map_get_info(map, &info);
    CHECK(info.levels_rebuilt == 0);

    /* The focus moved along x by k finest cells, for the first k that moves some levels and
     * not all. */
    uint32_t levels = 0;
    const roma_grid_params *grids;
    const roma_map_frame *frames;
    roma_map_get_level_params(map, &levels, &grids, &frames);
    const float finest_cell = grids[0].origin[3];
    uint32_t moved = 0, rebuilt = 0;
    int k = 0;
    while (++k <= 8 && (moved == 0 || moved == LEVELS)) {
        roma_grid_params before[LEVELS];
        memcpy(before, grids, sizeof before);
        focus[0] += finest_cell;
        CHECK_RESULT(roma_map_build(map, &frame, NULL), ROMA_SUCCESS);
        roma_map_get_info(map, &info);
        moved = 0;
        for (uint32_t l = 0; l < LEVELS; ++l)
            moved += memcmp(&before[l], &grids[l], sizeof before[l]) != 0;
        rebuilt = info.levels_rebuilt;
    }
    printf("reuse: the focus moved by %d finest cells: %u of %u levels moved, %u rebuilt\n", k - 1, moved, LEVELS,
           rebuilt);
    CHECK(moved > 0 && moved < LEVELS);
    CHECK(rebuilt == moved);
    roma_map *fresh = NULL;
    CHECK_RESULT(roma_map_create(ctx, &desc, scene, &fresh), ROMA_SUCCESS);
    CHECK_RESULT(roma_map_build(fresh, &frame, NULL), ROMA_SUCCESS);
    CHECK(download_all(map, bom, maps) && download_all(fresh, bom2, maps2));
    CHECK(memcmp(bom, bom2, 4 * texel_words * LEVELS) == 0);
    CHECK(memcmp(maps, maps2, 4 * map_words * LEVELS) == 0);

    /* Jittered directions: every level's maps rotated again from the kept BOM. */
    frame.jitter_directions = 1;
    frame.frame = 2;
    CHECK_RESULT(roma_map_build(map, &frame, NULL), ROMA_SUCCESS);
    roma_map_get_info(map, &info);
    CHECK(info.levels_rebuilt == LEVELS);
    CHECK_RESULT(roma_map_build(fresh, &frame, NULL), ROMA_SUCCESS);
    CHECK(download_all(map, bom, maps) && download_all(fresh, bom2, maps2));
    CHECK(memcmp(maps, maps2, 4 * map_words * LEVELS) == 0);

    /* New positions, the same ones: every level rebuilt. */
    frame.positions = v.positions;
    frame.vertex_count = v.vertex_count;
    CHECK_RESULT(roma_map_build(map, &frame, NULL), ROMA_SUCCESS);
    roma_map_get_info(map, &info);
    CHECK(info.levels_rebuilt == LEVELS);
    roma_map_destroy(fresh);
done:
    free(bom);
    free(maps);
    free(bom2);
    free(maps2);
    roma_map_destroy(map);
}

/* A new map of the scene with the mesh as a static instance at `transform`, built from frame:
 * what a map with it dynamic must hold word for word. */
static int fresh_equal_mesh(roma_context *ctx, const roma_scene *scene, const roma_scene *mesh_scene,
                            const roma_map_desc *desc, const roma_map_frame_desc *frame, const float transform[12],
                            const uint32_t *bom, const uint32_t *maps, uint32_t *bom2, uint32_t *maps2)
{
    const uint64_t texel_words = (uint64_t)RES * RES * (RES / 32), map_words = texel_words * ANGULAR * ANGULAR;
    roma_map *fresh = NULL;
    uint32_t mesh = 0, instance = 0;
    roma_map_frame_desc plain = *frame; /* the fresh map's mesh holds the positions from its start */
    plain.mesh_positions = NULL;
    plain.mesh_position_count = 0;
    int same = roma_map_create(ctx, desc, scene, &fresh) == ROMA_SUCCESS &&
               roma_map_add_mesh(fresh, mesh_scene, &mesh) == ROMA_SUCCESS;
    roma_instance_desc d = {.mesh = mesh};
    memcpy(d.transform, transform, sizeof d.transform);
    same = same && roma_map_add_instance(fresh, &d, &instance) == ROMA_SUCCESS &&
           roma_map_build(fresh, &plain, NULL) == ROMA_SUCCESS && download_all(fresh, bom2, maps2) &&
           memcmp(bom, bom2, 4 * texel_words * LEVELS) == 0 && memcmp(maps, maps2, 4 * map_words * LEVELS) == 0;
    roma_map_destroy(fresh);
    return same;
}

static int fresh_equal(roma_context *ctx, const roma_scene *scene, const roma_map_desc *desc,
                       const roma_map_frame_desc *frame, const float transform[12], const uint32_t *bom,
                       const uint32_t *maps, uint32_t *bom2, uint32_t *maps2)
{
    return fresh_equal_mesh(ctx, scene, scene, desc, frame, transform, bom, maps, bom2, maps2);
}

/* A dynamic instance over static geometry: a build keeps each level's static part and adds the
 * instance where it is (or restores the level where it was), and the result is word for word a
 * new map's with the instance static at the same place: near the camera (every level holds
 * it), moved far (the levels it left and entered redone), moved again far from the finest
 * levels (those kept), and still (nothing redone). */
static void check_dynamic(roma_context *ctx, const roma_scene *scene)
{
    roma_scene_view v;
    roma_scene_get_view(scene, &v);
    const roma_map_desc desc = {.resolution = RES, .angular = ANGULAR, .cascades = LEVELS};
    const uint64_t texel_words = (uint64_t)RES * RES * (RES / 32), map_words = texel_words * ANGULAR * ANGULAR;
    uint32_t *bom = malloc(4 * texel_words * LEVELS), *maps = malloc(4 * map_words * LEVELS);
    uint32_t *bom2 = malloc(4 * texel_words * LEVELS), *maps2 = malloc(4 * map_words * LEVELS);
    roma_map *map = NULL;
    CHECK_RESULT(roma_map_create(ctx, &desc, scene, &map), ROMA_SUCCESS);
    uint32_t mesh = 0, instance = 0;
    if (!map || !bom || !maps || !bom2 || !maps2 || roma_map_add_mesh(map, scene, &mesh) != ROMA_SUCCESS) {
        CHECK(map && "out of memory");
        goto done;
    }
    float focus[3], longest = 0.0f;
    for (int a = 0; a < 3; ++a) {
        focus[a] = v.bounds_min[a] + (v.bounds_max[a] - v.bounds_min[a]) * (a == 0 ? 0.3f : a == 1 ? 0.3f : 0.4f);
        longest = fmaxf(longest, v.bounds_max[a] - v.bounds_min[a]);
    }
    const roma_map_frame_desc frame = {.frame = 1, .seed = 9, .focus = focus, .finest_extent = longest / 6.0f};
    /* The room shrunk to 6% of its size, at the focus; then 0.25 of the room's size away
     * along z (outside the two finest cubes, inside the coarsest); then a little further. */
    const float s = 0.06f;
    float t[12] = {s, 0, 0, focus[0], 0, s, 0, focus[1], 0, 0, s, focus[2]};
    roma_instance_desc d = {.mesh = mesh, .flags = ROMA_INSTANCE_DYNAMIC};
    memcpy(d.transform, t, sizeof t);
    CHECK_RESULT(roma_map_add_instance(map, &d, &instance), ROMA_SUCCESS);
    roma_map_info info;
    const float moves[3] = {0.0f, 0.25f * longest, 0.03f * longest};
    uint32_t rebuilt[4] = {0};
    for (int step = 0; step < 4; ++step) {
        if (step > 0 && step < 3) {
            t[11] += moves[step];
            CHECK_RESULT(roma_map_set_instance_transform(map, instance, t), ROMA_SUCCESS);
        }
        CHECK_RESULT(roma_map_build(map, &frame, NULL), ROMA_SUCCESS);
        roma_map_get_info(map, &info);
        rebuilt[step] = info.levels_rebuilt;
        CHECK(info.static_copy_bytes == 4 * (texel_words + map_words) * LEVELS);
        CHECK(download_all(map, bom, maps));
        const int same = fresh_equal(ctx, scene, &desc, &frame, t, bom, maps, bom2, maps2);
        CHECK(same);
        if (!same)
            printf("dynamic: step %d differs from a new map's build\n", step);
    }
    /* Jittered, every level moves each frame: built from every triangle, with the instance. */
    roma_map_frame_desc jittered = frame;
    jittered.jitter_grid = jittered.jitter_directions = 1;
    for (int f = 0; f < 2; ++f) {
        jittered.frame = 10 + (uint32_t)f;
        t[3] += 0.01f * longest;
        CHECK_RESULT(roma_map_set_instance_transform(map, instance, t), ROMA_SUCCESS);
        CHECK_RESULT(roma_map_build(map, &jittered, NULL), ROMA_SUCCESS);
        roma_map_get_info(map, &info);
        CHECK(info.levels_rebuilt == LEVELS);
        CHECK(download_all(map, bom, maps) && fresh_equal(ctx, scene, &desc, &jittered, t, bom, maps, bom2, maps2));
    }
    /* Back to the still frame: a static part built again, then only what moved. */
    CHECK_RESULT(roma_map_build(map, &frame, NULL), ROMA_SUCCESS);
    t[3] += 0.01f * longest;
    CHECK_RESULT(roma_map_set_instance_transform(map, instance, t), ROMA_SUCCESS);
    CHECK_RESULT(roma_map_build(map, &frame, NULL), ROMA_SUCCESS);
    CHECK(download_all(map, bom, maps) && fresh_equal(ctx, scene, &desc, &frame, t, bom, maps, bom2, maps2));
    printf("dynamic instance: levels redone at the first build %u, moved far %u, moved again %u, still %u (of %u)\n",
           rebuilt[0], rebuilt[1], rebuilt[2], rebuilt[3], LEVELS);
    CHECK(rebuilt[0] == LEVELS && rebuilt[1] == LEVELS);
    CHECK(rebuilt[2] > 0 && rebuilt[2] < LEVELS); /* the finest level neither held it nor holds it */
    CHECK(rebuilt[3] == 0);
done:
    free(bom);
    free(maps);
    free(bom2);
    free(maps2);
    roma_map_destroy(map);
}

/* The room's positions bent as a skinned character's would be, at step k: a shear growing
 * with height and a bulge, different at every step. */
static void bend(const roma_scene_view *v, int k, float *out, float bmin[3], float bmax[3])
{
    for (int a = 0; a < 3; ++a)
        bmin[a] = INFINITY, bmax[a] = -INFINITY;
    for (uint32_t i = 0; i < v->vertex_count; ++i) {
        const float *p = v->positions + 3 * (size_t)i;
        const float h = (p[1] - v->bounds_min[1]) / (v->bounds_max[1] - v->bounds_min[1]);
        float q[3] = {p[0] + 0.15f * (float)k * h * (v->bounds_max[0] - v->bounds_min[0]),
                      p[1] * (1.0f + 0.1f * (float)k), p[2] * (1.0f - 0.05f * (float)k * h)};
        for (int a = 0; a < 3; ++a) {
            out[3 * (size_t)i + a] = q[a];
            bmin[a] = fminf(bmin[a], q[a]);
            bmax[a] = fmaxf(bmax[a], q[a]);
        }
    }
}

/* A mesh whose positions the caller writes on the GPU (roma_mesh_positions: a skinned character
 * in a level), as a dynamic instance over the static room in cascade levels: every build is
 * word for word a new map's with the bent mesh static at the same place; bending it redoes the
 * levels it is in from their static copies (once they are kept, no static triangle is
 * voxelized again); a build
 * without new positions keeps everything. Refused: a static instance of such a mesh, a mesh
 * listed twice, unknown meshes, NULL arrays, bad bounds and addresses (nothing changes). */
static void check_mesh_positions(roma_context *ctx, const roma_scene *scene)
{
    roma_scene_view v;
    roma_scene_get_view(scene, &v);
    const roma_map_desc desc = {.resolution = RES, .angular = ANGULAR, .cascades = LEVELS};
    const uint64_t texel_words = (uint64_t)RES * RES * (RES / 32), map_words = texel_words * ANGULAR * ANGULAR;
    const uint32_t stride = 20; /* 5 floats a vertex: a stride other than 12 */
    uint32_t *bom = malloc(4 * texel_words * LEVELS), *maps = malloc(4 * map_words * LEVELS);
    uint32_t *bom2 = malloc(4 * texel_words * LEVELS), *maps2 = malloc(4 * map_words * LEVELS);
    float *bent = malloc(12ull * v.vertex_count), *strided = calloc(v.vertex_count, stride);
    roma_buffer gpu[3] = {{0}};
    roma_map *map = NULL;
    uint32_t mesh = 0, instance = 0, other = 0;
    CHECK_RESULT(roma_map_create(ctx, &desc, scene, &map), ROMA_SUCCESS);
    if (!map || !bom || !maps || !bom2 || !maps2 || !bent || !strided ||
        roma_map_add_mesh(map, scene, &mesh) != ROMA_SUCCESS || roma_map_add_mesh(map, scene, &other) != ROMA_SUCCESS) {
        CHECK(map && "out of memory");
        goto done;
    }
    float focus[3], longest = 0.0f;
    for (int a = 0; a < 3; ++a) {
        focus[a] = v.bounds_min[a] + (v.bounds_max[a] - v.bounds_min[a]) * (a == 2 ? 0.4f : 0.3f);
        longest = fmaxf(longest, v.bounds_max[a] - v.bounds_min[a]);
    }
    const float s = 0.06f;
    const float t[12] = {s, 0, 0, focus[0], 0, s, 0, focus[1], 0, 0, s, focus[2]};
    roma_instance_desc d = {.mesh = mesh, .flags = ROMA_INSTANCE_DYNAMIC};
    memcpy(d.transform, t, sizeof t);
    CHECK_RESULT(roma_map_add_instance(map, &d, &instance), ROMA_SUCCESS);
    /* Three poses in the caller's device-local buffers (as an animator's). */
    roma_box boxes[3];
    for (int k = 0; k < 3; ++k) {
        bend(&v, k + 1, bent, boxes[k].min, boxes[k].max);
        for (uint32_t i = 0; i < v.vertex_count; ++i)
            memcpy((char *)strided + (size_t)i * stride, bent + 3 * (size_t)i, 12);
        CHECK_RESULT(roma_buffer_create_filled(ctx, (VkDeviceSize)v.vertex_count * stride,
                                               VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                                   VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT,
                                               strided, &gpu[k]),
                     ROMA_SUCCESS);
    }
    roma_map_frame_desc frame = {.frame = 1, .seed = 9, .focus = focus, .finest_extent = longest / 6.0f};
    roma_map_info info;
    uint32_t rebuilt[4];
    uint64_t voxelized[4];
    /* Posed at the first build, bent again, bent again, then still. */
    for (int k = 0; k < 4; ++k) {
        const int pose = k < 3 ? k : 2;
        roma_mesh_positions given = {.mesh = mesh, .gpu_positions = gpu[pose].address,
                                     .gpu_position_stride = stride, .bounds = boxes[pose]};
        frame.mesh_positions = k < 3 ? &given : NULL;
        frame.mesh_position_count = k < 3 ? 1 : 0;
        CHECK_RESULT(roma_map_build(map, &frame, NULL), ROMA_SUCCESS);
        roma_map_get_info(map, &info);
        rebuilt[k] = info.levels_rebuilt;
        voxelized[k] = info.triangles_voxelized;
        bend(&v, pose + 1, bent, boxes[pose].min, boxes[pose].max);
        roma_scene *posed = NULL;
        CHECK_RESULT(roma_scene_create(&(roma_scene_desc){.positions = bent, .vertex_count = v.vertex_count,
                                                          .indices = v.indices, .triangle_count = v.triangle_count},
                                       &posed),
                     ROMA_SUCCESS);
        const int same = posed && download_all(map, bom, maps) &&
                         fresh_equal_mesh(ctx, scene, posed, &desc, &frame, t, bom, maps, bom2, maps2);
        CHECK(same);
        if (!same)
            printf("mesh positions: build %d differs from a new map's with the posed mesh\n", k);
        roma_scene_destroy(posed);
    }
    printf("mesh positions: levels redone %u, %u, %u, still %u (of %u); triangles voxelized %llu, %llu, %llu, %llu\n",
           rebuilt[0], rebuilt[1], rebuilt[2], rebuilt[3], LEVELS, (unsigned long long)voxelized[0],
           (unsigned long long)voxelized[1], (unsigned long long)voxelized[2], (unsigned long long)voxelized[3]);
    CHECK(rebuilt[0] == LEVELS && voxelized[0] > 0);
    /* At the focus, in every level. The second build voxelizes the static part alone once, to
     * keep it (the first built every triangle together); from the third on it is kept. */
    CHECK(rebuilt[1] == LEVELS && voxelized[1] > 0);
    CHECK(rebuilt[2] == LEVELS && voxelized[2] == 0);
    CHECK(rebuilt[3] == 0);

    /* Refused, and the map as it was: a build after them keeps everything. */
    const roma_mesh_positions good = {.mesh = mesh, .gpu_positions = gpu[0].address, .bounds = boxes[0]};
    roma_mesh_positions bad[2] = {good, good};
    const struct {
        const char *what;
        roma_mesh_positions first;
        uint32_t count;
    } refusals[] = {
        {"no mesh 99", {.mesh = 99, .gpu_positions = good.gpu_positions, .bounds = good.bounds}, 1},
        {"address 0", {.mesh = mesh, .bounds = good.bounds}, 1},
        {"unaligned", {.mesh = mesh, .gpu_positions = good.gpu_positions + 2, .bounds = good.bounds}, 1},
        {"stride 8", {.mesh = mesh, .gpu_positions = good.gpu_positions, .gpu_position_stride = 8, .bounds = good.bounds}, 1},
        {"min above max", {.mesh = mesh, .gpu_positions = good.gpu_positions, .bounds = {{1, 0, 0}, {0, 1, 1}}}, 1},
        {"NaN bounds", {.mesh = mesh, .gpu_positions = good.gpu_positions, .bounds = {{NAN, 0, 0}, {1, 1, 1}}}, 1},
        {"twice", good, 2},
    };
    for (size_t i = 0; i < sizeof refusals / sizeof refusals[0]; ++i) {
        bad[0] = refusals[i].first;
        frame.mesh_positions = bad;
        frame.mesh_position_count = refusals[i].count;
        const roma_result r = roma_map_build(map, &frame, NULL);
        CHECK(r == ROMA_ERROR_INVALID_ARGUMENT);
        if (r != ROMA_ERROR_INVALID_ARGUMENT)
            printf("mesh positions: '%s' not refused (%d)\n", refusals[i].what, (int)r);
    }
    frame.mesh_positions = NULL;
    frame.mesh_position_count = 1;
    CHECK_RESULT(roma_map_build(map, &frame, NULL), ROMA_ERROR_INVALID_ARGUMENT);
    /* A static instance of a mesh given positions would stay in the static part as it was. */
    uint32_t fixed = 0;
    CHECK_RESULT(roma_map_add_instance(map, &(roma_instance_desc){.mesh = other}, &fixed), ROMA_SUCCESS);
    const roma_mesh_positions of_other = {.mesh = other, .gpu_positions = gpu[0].address, .bounds = boxes[0]};
    frame.mesh_positions = &of_other;
    CHECK_RESULT(roma_map_build(map, &frame, NULL), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(roma_map_remove_instance(map, fixed), ROMA_SUCCESS);
    frame.mesh_positions = NULL;
    frame.mesh_position_count = 0;
    CHECK_RESULT(roma_map_build(map, &frame, NULL), ROMA_SUCCESS); /* the instance removed: a new layout */
    /* Positions of a mesh no instance uses change nothing traced: nothing is redone. */
    frame.mesh_positions = &of_other;
    frame.mesh_position_count = 1;
    CHECK_RESULT(roma_map_build(map, &frame, NULL), ROMA_SUCCESS);
    roma_map_get_info(map, &info);
    CHECK(info.levels_rebuilt == 0);
    frame.mesh_positions = NULL;
    frame.mesh_position_count = 0;
    CHECK_RESULT(roma_map_build(map, &frame, NULL), ROMA_SUCCESS);
    CHECK(download_all(map, bom, maps) && fresh_equal_mesh(ctx, scene, scene, &desc, &frame, t, bom, maps, bom2, maps2) == 0);
    {
        roma_scene *posed = NULL;
        bend(&v, 3, bent, boxes[2].min, boxes[2].max);
        CHECK_RESULT(roma_scene_create(&(roma_scene_desc){.positions = bent, .vertex_count = v.vertex_count,
                                                          .indices = v.indices, .triangle_count = v.triangle_count},
                                       &posed),
                     ROMA_SUCCESS);
        CHECK(posed && fresh_equal_mesh(ctx, scene, posed, &desc, &frame, t, bom, maps, bom2, maps2));
        roma_scene_destroy(posed);
    }
done:
    for (int k = 0; k < 3; ++k)
        roma_buffer_destroy(ctx, &gpu[k]);
    free(bent);
    free(strided);
    free(bom);
    free(maps);
    free(bom2);
    free(maps2);
    roma_map_destroy(map);
}

/* Without a finest edge, the coarsest level holds the whole volume wherever the focus is: at
 * the volume's centre (the longest edge, as before), off it, or outside it (a camera looking at
 * an object from afar: before, the coarsest cube around it was as wide as the volume and missed
 * most of it). */
static void check_default_extent(roma_context *ctx, const roma_scene *scene)
{
    roma_scene_view v;
    roma_scene_get_view(scene, &v);
    roma_map *map = cascaded_map(ctx, scene);
    if (!map)
        return;
    float longest = 0.0f;
    for (int a = 0; a < 3; ++a)
        longest = fmaxf(longest, v.bounds_max[a] - v.bounds_min[a]);
    /* where: the focus at the volume's centre plus where * its size */
    static const float where[3][3] = {{0.0f, 0.0f, 0.0f}, {0.3f, -0.2f, 0.1f}, {2.0f, 0.5f, 1.6f}};
    float coarse_edge[3] = {0.0f, 0.0f, 0.0f};
    for (int w = 0; w < 3; ++w) {
        float focus[3], reach = 0.0f;
        for (int a = 0; a < 3; ++a) {
            const float size = v.bounds_max[a] - v.bounds_min[a];
            focus[a] = 0.5f * (v.bounds_min[a] + v.bounds_max[a]) + where[w][a] * size;
            reach = fmaxf(reach, fmaxf(focus[a] - v.bounds_min[a], v.bounds_max[a] - focus[a]));
        }
        const roma_map_frame_desc frame = {.frame = 1, .seed = 9, .focus = focus};
        CHECK_RESULT(roma_map_build(map, &frame, NULL), ROMA_SUCCESS);
        uint32_t levels = 0;
        const roma_grid_params *grids;
        const roma_map_frame *frames;
        roma_map_get_level_params(map, &levels, &grids, &frames);
        if (levels != LEVELS)
            break;
        const roma_grid_params *g = &grids[LEVELS - 1];
        int holds = 1;
        for (int a = 0; a < 3; ++a)
            holds &= g->origin[a] <= v.bounds_min[a] &&
                     g->origin[a] + g->origin[3] * (float)g->dims[0] >= v.bounds_max[a];
        coarse_edge[w] = g->origin[3] * (float)g->dims[0];
        printf("default extent, focus %d: coarsest cube %.3f wide (volume %.3f, reach %.3f), holds the volume: %d\n",
               w, (double)coarse_edge[w], (double)longest, (double)reach, holds);
        CHECK(holds);
        /* No wider than the cube around the focus that holds the volume, rounded up to a
         * quarter octave (2^0.25), with the margin. */
        CHECK(coarse_edge[w] <= 2.0f * reach * 1.19f * 1.1f);
        /* Off the centre, a focus moved by a tenth of the coarsest cell along the axis that sets
         * its reach (z here) keeps the cell size: static geometry stays in its cells (with an
         * edge that followed the reach, every move would change it). At the centre any such
         * move crosses a step (the edge grows by 2^0.25), as said in map.h. */
        const float cell = g->origin[3];
        if (w > 0) {
            focus[2] += 0.1f * cell;
            CHECK_RESULT(roma_map_build(map, &frame, NULL), ROMA_SUCCESS);
            roma_map_get_level_params(map, &levels, &grids, &frames);
            CHECK(grids[LEVELS - 1].origin[3] == cell &&
                  fabsf(grids[0].origin[3] * (float)(1u << (LEVELS - 1)) - cell) <= 1e-5f * cell);
        }
    }
    /* The focus at the centre: the cube as wide as before the change (the longest edge). */
    CHECK(coarse_edge[0] <= 1.1f * longest);
    roma_map_destroy(map);
}

int main(void)
{
    roma_context *ctx = roma_test_context();
    if (!ctx)
        return roma_test_finish("test_cascades");
    roma_scene *scene = NULL;
    CHECK_RESULT(roma_scene_create_builtin("cornell", NULL, &scene), ROMA_SUCCESS);
    if (scene) {
        roma_scene_view v;
        roma_scene_get_view(scene, &v);
        /* The room is one chunk that touches every level. */
        CHECK(check_cascades(ctx, scene, 1) == (uint64_t)LEVELS * v.triangle_count);
        check_reuse(ctx, scene);
        check_dynamic(ctx, scene);
        check_mesh_positions(ctx, scene);
        check_default_extent(ctx, scene);
    }
    /* Levels over part of a larger scene voxelize the chunks that touch them, and their BOM is
     * still the CPU voxelizer's of every triangle. */
    roma_scene *scattered = scattered_scene();
    if (scattered) {
        const uint64_t all = (uint64_t)LEVELS * SCATTERED * SCATTERED * SCATTERED;
        const uint64_t voxelized = check_cascades(ctx, scattered, 0);
        printf("scattered: %llu of %llu triangles voxelized over the %u levels\n", (unsigned long long)voxelized,
               (unsigned long long)all, LEVELS);
        /* Measured: 5,120 (20 slabs over the 3 levels); every level of every triangle: 12,288. */
        CHECK(voxelized > 0 && voxelized <= 5120);
        roma_scene_destroy(scattered);
    }
    /* Refused: too many levels, too many maps, a raster BOM mode with levels. */
    roma_map *bad = NULL;
    CHECK_RESULT(roma_map_create(ctx, &(roma_map_desc){.cascades = ROMA_MAX_LEVELS + 1}, scene, &bad),
                 ROMA_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(roma_map_create(ctx, &(roma_map_desc){.angular = 8, .cascades = 5}, scene, &bad),
                 ROMA_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(roma_map_create(ctx, &(roma_map_desc){.cascades = 2, .bom_mode = ROMA_BOM_UNION3}, scene, &bad),
                 ROMA_ERROR_INVALID_ARGUMENT);
    CHECK(bad == NULL);
    roma_scene_destroy(scene);
    roma_test_context_finish(ctx);
    return roma_test_finish("test_cascades");
}
