/* The GPU rotation and traces equal the plain C mirror bit for bit, on several
 * scenes, BOM modes and parameter sets, given the BOM the GPU built. The rotation
 * runs by scatter (occupied-cell list) unless the list overflows; a dense stack of
 * planes that fills more than the list (1/16 of the grid) checks the gather fallback.
 * The mirror counts what the un-snapped rays met in the walk, and the test asserts that
 * they reached each of its branches: a step of a wall found past a column's exit, a ray
 * blocked by the next column's search back, a ray blocked because that search left the map
 * (measured: 37,834, 656 and 46). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "trace/cpu_mirror.h"
#include "roma/builtin_scenes.h"
#include "roma/gltf.h"
#include "roma/map.h"
#include "map/map_internal.h"
#include "roma/sampling.h"

static void make_rays(const roma_map_info *info, uint32_t n, uint32_t seed, roma_ray *rays)
{
    float side = info->grid_cell * (float)info->resolution;
    for (uint32_t i = 0; i < n; ++i) {
        roma_ray *r = &rays[i];
        for (int a = 0; a < 3; ++a)
            r->origin[a] = info->grid_origin[a] + side * (roma_random(seed, i, 0, (uint32_t)a) * 1.2f - 0.1f);
        float z = 1.0f - 2.0f * roma_random(seed, i, 1, 0), phi = 2.0f * ROMA_PI * roma_random(seed, i, 1, 1);
        float s = sqrtf(fmaxf(0.0f, 1.0f - z * z));
        r->dir[0] = s * cosf(phi), r->dir[1] = s * sinf(phi), r->dir[2] = z;
        uint32_t kind = i % 8;
        /* Axis-aligned and unnormalised directions, clamped and open ranges. */
        if (kind == 1) { r->dir[0] = 0, r->dir[1] = 0, r->dir[2] = (i & 8) ? 1.0f : -1.0f; }
        if (kind == 2) { r->dir[0] = (i & 8) ? 3.0f : -3.0f, r->dir[1] = 0, r->dir[2] = 0; }
        r->tmin = kind == 3 ? 0.3f * side * roma_random(seed, i, 2, 0) : 0.0f;
        r->tmax = kind == 4 ? 0.2f * side : kind == 5 ? r->tmin : INFINITY;
    }
}

static int same_hit(roma_hit a, roma_hit b)
{
    return a.info == b.info && memcmp(&a.t, &b.t, sizeof a.t) == 0;
}

/* The same rays through roma_map_record_trace on buffers of the test's own, reached by
 * address (trace.comp reads the maps through roma_use_addresses): the hits must equal
 * roma_map_trace's (maps bound as descriptors) bit for bit. */
static uint32_t by_address_mismatches(roma_context *ctx, roma_map *map, roma_trace_mode mode, const roma_ray *rays,
                                      const roma_hit *expected, uint32_t n)
{
    const VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;
    roma_buffer ray_buf = {0}, hit_buf = {0};
    uint32_t mismatch = n;
    VkCommandBuffer cmd;
    if (roma_buffer_create(ctx, sizeof(roma_ray) * n, usage, ROMA_MEMORY_UPLOAD, &ray_buf) == ROMA_SUCCESS &&
        roma_buffer_create(ctx, sizeof(roma_hit) * n, usage, ROMA_MEMORY_READBACK, &hit_buf) == ROMA_SUCCESS &&
        roma_begin_one_shot(ctx, &cmd) == ROMA_SUCCESS) {
        memcpy(ray_buf.mapped, rays, sizeof(roma_ray) * n);
        roma_trace_desc desc = {.mode = mode, .max_steps = 8, .rays = ray_buf.address, .hits = hit_buf.address,
                                .ray_count = n};
        CHECK_RESULT(roma_map_record_trace(map, cmd, &desc, NULL), ROMA_SUCCESS);
        roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                                VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
        if (roma_submit_one_shot(ctx, cmd) == ROMA_SUCCESS && roma_buffer_invalidate(ctx, &hit_buf) == ROMA_SUCCESS) {
            const roma_hit *hits = hit_buf.mapped;
            mismatch = 0;
            for (uint32_t i = 0; i < n; ++i)
                mismatch += !same_hit(hits[i], expected[i]);
        }
    }
    roma_buffer_destroy(ctx, &ray_buf);
    roma_buffer_destroy(ctx, &hit_buf);
    return mismatch;
}

static const char *mode_name(roma_bom_mode mode)
{
    return mode == ROMA_BOM_EXACT ? "exact       " : mode == ROMA_BOM_UNION3 ? "union3      "
         : mode == ROMA_BOM_DOMINANT ? "dominant    " : "conservative";
}

/* Returns the number of occupied BOM cells; adds what the un-snapped rays met in the walk
 * to *walk_counts (may be NULL). */
static uint64_t check_scene(roma_context *ctx, roma_scene *scene, const char *name, uint32_t res,
                            uint32_t angular, roma_bom_mode mode, roma_cpu_walk_counts *walk_counts)
{
    roma_map_desc desc = {.resolution = res, .angular = angular, .bom_mode = mode};
    roma_map *map = NULL;
    CHECK_RESULT(roma_map_create(ctx, &desc, scene, &map), ROMA_SUCCESS);
    if (!map)
        return 0;
    roma_map_frame_desc frame = {.frame = 5, .seed = 9, .jitter_grid = 1, .jitter_directions = 1};
    CHECK_RESULT(roma_map_build(map, &frame, NULL), ROMA_SUCCESS);
    roma_map_info info;
    roma_map_get_info(map, &info);
    uint64_t texel_words = (uint64_t)res * res * (res / 32);
    uint32_t *bom = malloc(texel_words * 4), *maps = malloc(texel_words * 4 * info.map_count),
             *mirror = malloc(texel_words * 4 * info.map_count);
    CHECK_RESULT(roma_map_download_bom(map, bom, texel_words), ROMA_SUCCESS);
    CHECK_RESULT(roma_map_download_maps(map, maps, texel_words * info.map_count), ROMA_SUCCESS);
    roma_grid_params grid;
    const roma_map_frame *frames;
    roma_map_get_frame_params(map, &grid, &frames);
    roma_cpu_rotate(&grid, frames, bom, mirror);
    uint64_t diff = 0, occupied = 0, bom_cells = 0;
    for (uint64_t i = 0; i < texel_words; ++i)
        bom_cells += (uint64_t)__builtin_popcount(bom[i]);
    for (uint64_t i = 0; i < texel_words * info.map_count; ++i) {
        diff += maps[i] != mirror[i];
        occupied += __builtin_popcount(maps[i]);
    }
    printf("%-10s RES %3u A %2u %s: %llu BOM cells, %llu occupied cells over %u maps, %llu words differ "
           "from the mirror\n", name, res, angular, mode_name(mode), (unsigned long long)bom_cells,
           (unsigned long long)occupied, info.map_count, (unsigned long long)diff);
    CHECK(diff == 0);
    CHECK(occupied > 0);

    enum { N = 4096 };
    static roma_ray rays[N];
    static roma_hit gpu[N];
    make_rays(&info, N, res + angular, rays);
    for (int m = 0; m < 4; ++m) {
        CHECK_RESULT(roma_map_trace(map, (roma_trace_mode)m, 8, rays, N, gpu, NULL), ROMA_SUCCESS);
        uint32_t mismatch = 0, selection = 0, off_edge = 0, hits = 0;
        float widest = 0.0f;
        for (uint32_t i = 0; i < N; ++i) {
            int folded;
            uint32_t k = roma_cpu_select_map(rays[i].dir, angular, &folded);
            /* Selection may differ only on a stratum edge, within what Vulkan lets atan and sqrt
             * round (ROMA_CPU_SELECTION_TOLERANCE); the fold never. */
            float distance = 0.0f;
            if (k != ROMA_HIT_MAP(gpu[i].info)) {
                ++selection;
                off_edge += !roma_cpu_selection_may_differ(rays[i].dir, angular, ROMA_HIT_MAP(gpu[i].info), &distance);
                widest = fmaxf(widest, distance);
            }
            off_edge += (int)((gpu[i].info >> 16) & 1u) != folded;
            roma_hit cpu = roma_cpu_trace_counted(&grid, frames, maps, &rays[i], (roma_trace_mode)m, 8,
                                                  (int)ROMA_HIT_MAP(gpu[i].info), (gpu[i].info >> 16) & 1,
                                                  walk_counts);
            hits += gpu[i].info & 1;
            if (!same_hit(cpu, gpu[i])) {
                if (mismatch < 3)
                    fprintf(stderr, "  mode %d ray %u: gpu (%.9g, %#x) cpu (%.9g, %#x)\n", m, i, gpu[i].t,
                            gpu[i].info, cpu.t, cpu.info);
                ++mismatch;
            }
        }
        uint32_t by_address = by_address_mismatches(ctx, map, (roma_trace_mode)m, rays, gpu, N);
        printf("    mode %d: %u/%u hits, %u trace mismatches, %u selection differences (at most %.3g of the square "
               "from an edge; %u off one), %u by-address differences\n", m, hits, N, mismatch, selection,
               (double)widest, off_edge, by_address);
        CHECK(mismatch == 0);
        CHECK(by_address == 0);
        CHECK(off_edge == 0);
        CHECK(hits > 0 && hits < N);
    }
    free(bom);
    free(maps);
    free(mirror);
    roma_map_destroy(map);
    return bom_cells;
}

/* planes parallel quads one unit apart, tilted so that each crosses many cells. */
static roma_scene *dense_planes(uint32_t planes)
{
    float *p = malloc(sizeof(float) * 12 * planes);
    uint32_t *idx = malloc(sizeof(uint32_t) * 6 * planes);
    roma_scene *scene = NULL;
    if (p && idx) {
        for (uint32_t i = 0; i < planes; ++i) {
            float z = (float)i, corners[4][3] = {{0, 0, z}, {32, 0, z + 3}, {32, 32, z + 5}, {0, 32, z + 2}};
            memcpy(p + 12 * i, corners, sizeof corners);
            const uint32_t q[6] = {4 * i, 4 * i + 1, 4 * i + 2, 4 * i, 4 * i + 2, 4 * i + 3};
            memcpy(idx + 6 * i, q, sizeof q);
        }
        roma_scene_desc d = {.positions = p, .vertex_count = 4 * planes, .indices = idx,
                             .triangle_count = 2 * planes, .name = "dense"};
        CHECK_RESULT(roma_scene_create(&d, &scene), ROMA_SUCCESS);
    }
    free(p);
    free(idx);
    return scene;
}

int main(void)
{
    roma_context *ctx = roma_test_context();
    if (!ctx)
        return roma_test_finish("test_roma_mirror");
    roma_scene *cornell = NULL, *blinds = NULL, *spot = NULL;
    /* What the un-snapped rays of every case met in the walk, so the test shows it compared the
     * GPU with the mirror on each of the walk's branches. */
    roma_cpu_walk_counts walk_counts = {0, 0, 0};
    CHECK_RESULT(roma_scene_create_builtin("cornell", NULL, &cornell), ROMA_SUCCESS);
    CHECK_RESULT(roma_scene_create_builtin("blinds", NULL, &blinds), ROMA_SUCCESS);
    check_scene(ctx, cornell, "cornell", 32, 2, ROMA_BOM_UNION3, &walk_counts);
    check_scene(ctx, cornell, "cornell", 64, 3, ROMA_BOM_EXACT, &walk_counts);
    check_scene(ctx, blinds, "blinds", 128, 4, ROMA_BOM_EXACT, &walk_counts);
    /* Every other BOM cell occupied: the cell list (RES^3 / 16) overflows and the
     * gather rotates instead. */
    roma_scene *dense = dense_planes(32);
    if (dense) {
        uint64_t cells = check_scene(ctx, dense, "dense", 32, 2, ROMA_BOM_EXACT, &walk_counts);
        CHECK(cells > 32 * 32 * 32 / 16);
        roma_scene_destroy(dense);
    }
    check_scene(ctx, cornell, "cornell", 64, 4, ROMA_BOM_DOMINANT, &walk_counts);
    check_scene(ctx, blinds, "blinds", 128, 3, ROMA_BOM_CONSERVATIVE, &walk_counts);
    /* 81 maps at RES 128: more than 65535 workgroups, so the 2D dispatch path runs. */
    check_scene(ctx, cornell, "cornell", 128, 9, ROMA_BOM_CONSERVATIVE, &walk_counts);
    char path[1024];
    if (roma_test_scene_file("spot.glb", path, sizeof path) &&
        roma_scene_load_gltf(path, NULL, &spot) == ROMA_SUCCESS)
        check_scene(ctx, spot, "spot", 64, 8, ROMA_BOM_CONSERVATIVE, &walk_counts);
    else
        printf("spot.glb not available: skipping that case\n");
    /* Every branch of the un-snapped walk met by rays the GPU answered as the mirror did. */
    printf("un-snapped walks: %llu steps ahead past a column's exit, %llu rays blocked by the search back, "
           "%llu by a search back leaving the map\n", (unsigned long long)walk_counts.steps_ahead,
           (unsigned long long)walk_counts.back_hits, (unsigned long long)walk_counts.unseen_hits);
    CHECK(walk_counts.steps_ahead > 0);
    CHECK(walk_counts.back_hits > 0);
    CHECK(walk_counts.unseen_hits > 0);

    /* The corrected division and square root (roma_div, roma_sqrt), which GPUs trace with, on
     * this device too: from products and sums rounded to nearest they must give IEEE's
     * quotients and roots, the mirror's, bit for bit. */
    roma_context *corrected = roma_test_context_flags(ROMA_CONTEXT_CORRECTED_DIVISION);
    if (corrected) {
        roma_context_info info;
        roma_context_get_info(corrected, &info);
        printf("corrected division (%s by default on this device):\n",
               info.device_type == VK_PHYSICAL_DEVICE_TYPE_CPU ? "off" : "on");
        CHECK(info.corrected_division == VK_TRUE);
        check_scene(corrected, cornell, "cornell", 64, 3, ROMA_BOM_EXACT, NULL);
        check_scene(corrected, blinds, "blinds", 128, 4, ROMA_BOM_EXACT, NULL);
        roma_test_context_finish(corrected);
    }
    roma_scene_destroy(cornell);
    roma_scene_destroy(blinds);
    roma_scene_destroy(spot);
    roma_test_context_finish(ctx);
    return roma_test_finish("test_roma_mirror");
}
