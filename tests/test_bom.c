/* BOM rasterization and the compute voxelizer against the exact CPU voxelizer
 * (tests/support/voxelize_cpu.c).
 *
 * For each scene and RES the grid is the cube around the scene bounds with a one
 * cell margin (optionally shifted by a fraction of a cell), rasterized on the
 * GPU in both modes, with and without ROMA_BOM_FLAG_CONSERVATIVE, and compared
 * cell by cell with the CPU:
 *  - missed: occupied on the CPU, not on the GPU (without the flag the GPU marks
 *    only columns whose pixel centre the triangle covers): bounded per scene and
 *    variant by the measured fraction plus a small margin;
 *  - extra: set on the GPU, not on the CPU: each must be within one cell
 *    (26-neighbourhood) of a CPU cell.
 * Also: zero-area triangles mark nothing, geometry outside the grid writes
 * nothing (and nothing past the BOM), two runs give identical bits. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "voxelize/bom_raster.h"
#include "voxelize/bom_voxelize.h"
#include "roma/builtin_scenes.h"
#include "roma/context.h"
#include "roma/gltf.h"
#include "roma/map.h"
#include "roma/scene.h"
#include "voxelize_cpu.h"
#include "vulkan/vk_internal.h"

/* Missed-cell bounds: the measured worst fraction + this (absolute) + 2 cells. */
#define MISS_MARGIN 0.01
#define GUARD_BYTES 4096u
/* The exact compute voxelization (measured, see run_case). */
#define EXACT_MAX_MISSED 2.0
#define EXACT_MAX_EXTRA 0.008

typedef struct geometry {
    const char *name;
    const float *positions; /* 3 per vertex */
    uint32_t vertex_count;
    const uint32_t *indices;
    uint32_t triangle_count;
    float bounds_min[3], bounds_max[3];
} geometry;

typedef struct gpu_geometry {
    roma_buffer positions, indices;
    uint32_t triangle_count;
} gpu_geometry;

typedef struct compare_stats {
    uint64_t cpu, gpu, missed, extra, extra_far;
} compare_stats;

static uint32_t popcount32(uint32_t v)
{
    uint32_t n = 0;
    for (; v; v &= v - 1)
        ++n;
    return n;
}

static uint64_t count_bits(const uint32_t *words, uint64_t n)
{
    uint64_t c = 0;
    for (uint64_t i = 0; i < n; ++i)
        c += popcount32(words[i]);
    return c;
}

static void geometry_bounds(geometry *g)
{
    for (int j = 0; j < 3; ++j) {
        g->bounds_min[j] = INFINITY;
        g->bounds_max[j] = -INFINITY;
    }
    for (uint32_t i = 0; i < 3 * g->triangle_count; ++i)
        for (int j = 0; j < 3; ++j) {
            float v = g->positions[3 * g->indices[i] + j];
            g->bounds_min[j] = fminf(g->bounds_min[j], v);
            g->bounds_max[j] = fmaxf(g->bounds_max[j], v);
        }
}

/* Cube around the bounds with one cell of margin, origin shifted by `shift` cells. */
static roma_voxel_grid make_grid(const geometry *g, uint32_t res, float shift)
{
    float extent = 0.0f, center[3];
    for (int j = 0; j < 3; ++j) {
        extent = fmaxf(extent, g->bounds_max[j] - g->bounds_min[j]);
        center[j] = 0.5f * (g->bounds_min[j] + g->bounds_max[j]);
    }
    if (extent <= 0.0f)
        extent = 1.0f;
    float cell = extent / (float)(res - 2);
    roma_voxel_grid grid = {.resolution = res, .inv_cell = 1.0f / cell};
    for (int j = 0; j < 3; ++j)
        grid.origin[j] = center[j] - 0.5f * (float)res * cell + shift * cell;
    return grid;
}

static roma_result upload_geometry(roma_context *ctx, const geometry *g, gpu_geometry *out)
{
    memset(out, 0, sizeof *out);
    const VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;
    roma_result r = roma_buffer_create(ctx, (VkDeviceSize)g->vertex_count * 16, usage, ROMA_MEMORY_UPLOAD,
                                       &out->positions);
    if (r == ROMA_SUCCESS)
        r = roma_buffer_create(ctx, (VkDeviceSize)g->triangle_count * 12, usage, ROMA_MEMORY_UPLOAD, &out->indices);
    if (r != ROMA_SUCCESS)
        return r;
    float *p = out->positions.mapped;
    for (uint32_t i = 0; i < g->vertex_count; ++i) {
        memcpy(p + 4 * i, g->positions + 3 * i, 3 * sizeof(float));
        p[4 * i + 3] = 1.0f;
    }
    memcpy(out->indices.mapped, g->indices, (size_t)g->triangle_count * 12);
    out->triangle_count = g->triangle_count;
    return ROMA_SUCCESS;
}

static void free_geometry(roma_context *ctx, gpu_geometry *g)
{
    roma_buffer_destroy(ctx, &g->positions);
    roma_buffer_destroy(ctx, &g->indices);
}

/* Rasterizes on the GPU and downloads the BOM into words. Checks the guard
 * bytes after the BOM are untouched. */
/* The variants compared: BOM mode and config.w flags. */
typedef struct variant {
    uint32_t mode; /* ROMA_BOM_MODE_* (raster modes) */
    uint32_t flags;
    const char *name;
    int compute;   /* the compute voxelizer (src/voxelize/bom_voxelize.h) instead of the raster */
} variant;

#define VARIANTS 5
static const variant variants[VARIANTS] = {
    {ROMA_BOM_MODE_UNION3, 0, "union3", 0},
    {ROMA_BOM_MODE_DOMINANT, 0, "dominant", 0},
    {ROMA_BOM_MODE_UNION3, ROMA_BOM_FLAG_CONSERVATIVE, "union3+cons", 0},
    {ROMA_BOM_MODE_DOMINANT, ROMA_BOM_FLAG_CONSERVATIVE, "dominant+cons", 0},
    {0, 0, "exact (compute)", 1},
};

static roma_result run_gpu(roma_context *ctx, roma_bom_raster *raster, const gpu_geometry *geo,
                           const roma_voxel_grid *grid, variant var, uint32_t *words, double *out_ms)
{
    const uint32_t res = grid->resolution;
    const VkDeviceSize bom_bytes = (VkDeviceSize)res * res * res / 8;
    roma_buffer params = {0}, bom = {0}, readback = {0};
    roma_gpu_timer *timer = NULL;
    roma_bom_voxelizer *vox = NULL;
    roma_result r = roma_buffer_create(ctx, sizeof(roma_grid_params),
                                       VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT,
                                       ROMA_MEMORY_UPLOAD, &params);
    if (r == ROMA_SUCCESS)
        r = roma_buffer_create(ctx, bom_bytes + GUARD_BYTES,
                               VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT |
                                   VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                               ROMA_MEMORY_DEVICE, &bom);
    if (r == ROMA_SUCCESS)
        r = roma_buffer_create(ctx, bom_bytes + GUARD_BYTES, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                               ROMA_MEMORY_READBACK, &readback);
    if (r == ROMA_SUCCESS)
        r = roma_gpu_timer_create(ctx, 1, &timer);
    if (r == ROMA_SUCCESS && var.compute)
        r = roma_bom_voxelizer_create(ctx, res, geo->positions.buffer, geo->indices.buffer, bom.buffer, bom_bytes, &vox);
    roma_grid_params gp = {0};
    if (r == ROMA_SUCCESS) {
        gp = (roma_grid_params){
            .origin = {grid->origin[0], grid->origin[1], grid->origin[2], 1.0f / grid->inv_cell},
            .inv_cell = {grid->inv_cell, 0, 0, 0},
            .dims = {res, res / 32, 0, 0},
        };
        memcpy(params.mapped, &gp, sizeof gp);
    }
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    if (r == ROMA_SUCCESS)
        r = roma_begin_one_shot(ctx, &cmd);
    if (r == ROMA_SUCCESS) {
        /* Guard pattern everywhere; the raster clears only the BOM part. */
        vkCmdFillBuffer(cmd, bom.buffer, 0, VK_WHOLE_SIZE, 0xa5a5a5a5u);
        roma_bom_push push = {
            .positions = geo->positions.address,
            .indices = geo->indices.address,
            .bom = bom.address,
            .params = params.address,
            .config = {0, var.mode, geo->triangle_count, var.flags},
        };
        roma_gpu_timer_reset(timer, cmd);
        uint32_t scope = roma_gpu_timer_begin(timer, cmd, "bom");
        if (var.compute) {
            r = roma_bom_voxelize_record(vox, cmd, &gp, geo->triangle_count);
        } else {
            r = roma_bom_raster_record(raster, cmd, &push, bom.buffer, bom_bytes, res);
        }
        roma_gpu_timer_end(timer, cmd, scope);
        VkBufferCopy copy = {0, 0, bom_bytes + GUARD_BYTES};
        vkCmdCopyBuffer(cmd, bom.buffer, readback.buffer, 1, &copy);
        roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                                VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
        roma_result s = roma_submit_one_shot(ctx, cmd);
        if (r == ROMA_SUCCESS)
            r = s;
    }
    if (r == ROMA_SUCCESS)
        r = roma_buffer_invalidate(ctx, &readback);
    if (r == ROMA_SUCCESS) {
        memcpy(words, readback.mapped, bom_bytes);
        const uint32_t *guard = (const uint32_t *)((const char *)readback.mapped + bom_bytes);
        int intact = 1;
        for (uint32_t i = 0; i < GUARD_BYTES / 4; ++i)
            intact &= guard[i] == 0xa5a5a5a5u;
        CHECK(intact);
        roma_gpu_timing timing;
        uint32_t count = 1;
        if (roma_gpu_timer_read(timer, &timing, &count) == ROMA_SUCCESS && count == 1 && out_ms)
            *out_ms = timing.milliseconds;
    }
    roma_gpu_timer_destroy(timer);
    roma_bom_voxelizer_destroy(vox);
    roma_buffer_destroy(ctx, &readback);
    roma_buffer_destroy(ctx, &bom);
    roma_buffer_destroy(ctx, &params);
    return r;
}

static int cpu_near(const uint32_t *cpu, uint32_t res, int x, int y, int z)
{
    for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                int a = x + dx, b = y + dy, c = z + dz;
                if (a >= 0 && b >= 0 && c >= 0 && a < (int)res && b < (int)res && c < (int)res &&
                    roma_voxel_get(cpu, res, (uint32_t)a, (uint32_t)b, (uint32_t)c))
                    return 1;
            }
    return 0;
}

static compare_stats compare(const uint32_t *cpu, const uint32_t *gpu, uint32_t res)
{
    compare_stats s = {0};
    const uint32_t words = res / 32;
    for (uint32_t y = 0; y < res; ++y)
        for (uint32_t x = 0; x < res; ++x)
            for (uint32_t w = 0; w < words; ++w) {
                uint64_t i = ((uint64_t)y * res + x) * words + w;
                s.cpu += popcount32(cpu[i]);
                s.gpu += popcount32(gpu[i]);
                s.missed += popcount32(cpu[i] & ~gpu[i]);
                uint32_t extra = gpu[i] & ~cpu[i];
                s.extra += popcount32(extra);
                for (; extra; extra &= extra - 1) {
                    int z = (int)(32 * w) + __builtin_ctz(extra);
                    if (!cpu_near(cpu, res, (int)x, (int)y, z))
                        ++s.extra_far;
                }
            }
    return s;
}

typedef struct scene_case {
    geometry geo;
    float shift;               /* grid origin shift, cells */
    const uint32_t *res_list;
    double max_miss[VARIANTS]; /* measured worst missed fraction over res_list */
    int expect_empty;
    int must_not_vanish;       /* every variant marks something */
} scene_case;

static double total_gpu_ms[VARIANTS];

static void run_case(roma_context *ctx, roma_bom_raster *raster, const scene_case *sc)
{
    gpu_geometry gg;
    roma_result r = upload_geometry(ctx, &sc->geo, &gg);
    CHECK_RESULT(r, ROMA_SUCCESS);
    if (r != ROMA_SUCCESS) {
        free_geometry(ctx, &gg);
        return;
    }
    for (const uint32_t *res = sc->res_list; *res; ++res) {
        roma_voxel_grid grid = make_grid(&sc->geo, *res, sc->shift);
        size_t nwords = (size_t)*res * *res * *res / 32;
        uint32_t *cpu = malloc(nwords * 4), *gpu = malloc(nwords * 4);
        CHECK(cpu && gpu);
        if (!cpu || !gpu) {
            free(cpu);
            free(gpu);
            break;
        }
        roma_voxelize_cpu(&grid, sc->geo.positions, 3, sc->geo.indices, sc->geo.triangle_count, cpu);
        compare_stats st[VARIANTS];
        double ms[VARIANTS] = {0};
        for (int v = 0; v < VARIANTS; ++v) {
            r = run_gpu(ctx, raster, &gg, &grid, variants[v], gpu, &ms[v]);
            CHECK_RESULT(r, ROMA_SUCCESS);
            st[v] = compare(cpu, gpu, *res);
            total_gpu_ms[v] += ms[v];
            if (sc->expect_empty) {
                CHECK(st[v].cpu == 0);
                CHECK(st[v].gpu == 0);
            } else {
                CHECK(st[v].cpu > 0);
            }
            if (!sc->expect_empty && (sc->must_not_vanish || (variants[v].flags & ROMA_BOM_FLAG_CONSERVATIVE)))
                CHECK(st[v].gpu > 0);
            CHECK(st[v].extra_far == 0);
            /* Measured bound, plus MISS_MARGIN and two cells (tiny scenes). The exact
             * compute voxelization gets no margin: it may miss only float ties (measured:
             * 2 cells, where the sliver passes through a grid vertex), and its extra cells
             * are the ones the triangle touches within float error (all measured within
             * 1e-5 cells of touching; at most 0.75% of the cells of one tilted triangle). */
            double allowed = variants[v].compute ? EXACT_MAX_MISSED
                                                 : (sc->max_miss[v] + MISS_MARGIN) * (double)st[v].cpu + 2.0;
            if (variants[v].compute && !((double)st[v].extra <= EXACT_MAX_EXTRA * (double)st[v].cpu + 2.0)) {
                fprintf(stderr, "%s RES %u %s: %llu extra cells of %llu\n", sc->geo.name, *res, variants[v].name,
                        (unsigned long long)st[v].extra, (unsigned long long)st[v].cpu);
                ++roma_test_failures;
            }
            if (!((double)st[v].missed <= allowed)) {
                fprintf(stderr, "%s RES %u %s: %llu of %llu cells missed, bound %.0f\n", sc->geo.name, *res,
                        variants[v].name, (unsigned long long)st[v].missed, (unsigned long long)st[v].cpu, allowed);
                ++roma_test_failures;
            }
        }
        double c = st[0].cpu ? (double)st[0].cpu : 1.0;
        printf("| %-14s | %3u | %6llu |", sc->geo.name, *res, (unsigned long long)st[0].cpu);
        for (int v = 0; v < VARIANTS; ++v)
            printf(" %.4f %.4f %6.1f |", st[v].missed / c, st[v].extra / c, ms[v]);
        printf("\n");
        for (int v = 0; v < VARIANTS; ++v)
            if (st[v].extra_far)
                printf("    %s: %llu extra cells farther than one cell\n", variants[v].name,
                       (unsigned long long)st[v].extra_far);
        free(cpu);
        free(gpu);
    }
    free_geometry(ctx, &gg);
}

/* Outside the grid: shift the grid by more than RES cells along one axis at a
 * time (and all three): nothing may be written. */
static void check_outside(roma_context *ctx, roma_bom_raster *raster, const geometry *geo)
{
    gpu_geometry gg;
    CHECK_RESULT(upload_geometry(ctx, geo, &gg), ROMA_SUCCESS);
    const uint32_t res = 32;
    uint32_t *gpu = malloc((size_t)res * res * res / 8);
    CHECK(gpu != NULL);
    for (int axis = 0; axis < 4 && gpu; ++axis)
        for (int side = -1; side <= 1; side += 2)
            for (int v = 0; v < VARIANTS; ++v) {
                roma_voxel_grid grid = make_grid(geo, res, 0.0f);
                for (int j = 0; j < 3; ++j)
                    if (axis == 3 || axis == j)
                        grid.origin[j] += (float)side * (float)(res + 1) / grid.inv_cell;
                CHECK_RESULT(run_gpu(ctx, raster, &gg, &grid, variants[v], gpu, NULL), ROMA_SUCCESS);
                uint64_t n = count_bits(gpu, (uint64_t)res * res * res / 32);
                if (n) {
                    fprintf(stderr, "outside grid (axis %d side %d, %s): %llu cells set\n", axis, side,
                            variants[v].name, (unsigned long long)n);
                    ++roma_test_failures;
                }
            }
    free(gpu);
    free_geometry(ctx, &gg);
}

/* Bits identical across two runs (atomicOr order must not matter). */
static void check_repeatable(roma_context *ctx, roma_bom_raster *raster, const geometry *geo, uint32_t res)
{
    gpu_geometry gg;
    CHECK_RESULT(upload_geometry(ctx, geo, &gg), ROMA_SUCCESS);
    size_t bytes = (size_t)res * res * res / 8;
    uint32_t *a = malloc(bytes), *b = malloc(bytes);
    CHECK(a && b);
    roma_voxel_grid grid = make_grid(geo, res, 0.25f);
    for (int v = 0; v < VARIANTS && a && b; ++v) {
        CHECK_RESULT(run_gpu(ctx, raster, &gg, &grid, variants[v], a, NULL), ROMA_SUCCESS);
        CHECK_RESULT(run_gpu(ctx, raster, &gg, &grid, variants[v], b, NULL), ROMA_SUCCESS);
        CHECK(memcmp(a, b, bytes) == 0);
    }
    free(a);
    free(b);
    free_geometry(ctx, &gg);
}

static void check_arguments(roma_context *ctx, roma_bom_raster *raster)
{
    roma_buffer bom = {0};
    CHECK_RESULT(roma_buffer_create(ctx, 32 * 32 * 32 / 8, VK_BUFFER_USAGE_TRANSFER_DST_BIT, ROMA_MEMORY_DEVICE, &bom),
                 ROMA_SUCCESS);
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    CHECK_RESULT(roma_begin_one_shot(ctx, &cmd), ROMA_SUCCESS);
    roma_bom_push push = {.config = {0, ROMA_BOM_MODE_UNION3, 0, 0}};
    fprintf(stderr, "expected argument errors follow:\n");
    CHECK_RESULT(roma_bom_raster_record(raster, cmd, &push, bom.buffer, bom.size, 48), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(roma_bom_raster_record(raster, cmd, &push, bom.buffer, bom.size - 4, 32),
                 ROMA_ERROR_INVALID_ARGUMENT);
    push.config[2] = 1; /* triangles but no addresses */
    CHECK_RESULT(roma_bom_raster_record(raster, cmd, &push, bom.buffer, bom.size, 32), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(roma_bom_raster_record(NULL, cmd, &push, bom.buffer, bom.size, 32), ROMA_ERROR_INVALID_ARGUMENT);
    push.config[2] = 0;
    push.config[3] = 2; /* unknown flag */
    CHECK_RESULT(roma_bom_raster_record(raster, cmd, &push, bom.buffer, bom.size, 32), ROMA_ERROR_INVALID_ARGUMENT);
    push.config[3] = 0;
    /* Zero triangles: a valid clear. */
    CHECK_RESULT(roma_bom_raster_record(raster, cmd, &push, bom.buffer, bom.size, 32), ROMA_SUCCESS);
    CHECK_RESULT(roma_submit_one_shot(ctx, cmd), ROMA_SUCCESS);
    roma_buffer_destroy(ctx, &bom);
    roma_bom_raster_destroy(NULL);
}

static geometry from_scene(const roma_scene *scene, const char *name)
{
    roma_scene_view v;
    geometry g = {0};
    if (roma_scene_get_view(scene, &v) != ROMA_SUCCESS)
        return g;
    g.name = name;
    g.positions = v.positions;
    g.vertex_count = v.vertex_count;
    g.indices = v.indices;
    g.triangle_count = v.triangle_count;
    geometry_bounds(&g);
    return g;
}

static geometry raw(const char *name, const float *positions, uint32_t vertex_count, const uint32_t *indices,
                    uint32_t triangle_count)
{
    geometry g = {name, positions, vertex_count, indices, triangle_count, {0}, {0}};
    geometry_bounds(&g);
    return g;
}

int main(void)
{
    roma_context *ctx = roma_test_context();
    if (!ctx)
        return roma_test_finish("test_bom");
    roma_bom_raster *raster = NULL;
    CHECK_RESULT(roma_bom_raster_create(ctx, &raster), ROMA_SUCCESS);
    if (!raster) {
        roma_test_context_finish(ctx);
        return roma_test_finish("test_bom");
    }
    check_arguments(ctx, raster);

    static const float tilted_p[] = {0.1f, 0.2f, 0.3f, 0.9f, 0.35f, 0.5f, 0.4f, 0.85f, 0.95f};
    /* In the plane y = 0.5: at the centre of the cube, so on a cell face (shift 0)
     * or mid-cell (shift 0.5). */
    static const float plane_p[] = {0.0f, 0.5f, 0.0f, 1.0f, 0.5f, 0.2f, 0.3f, 0.5f, 0.9f};
    /* Long and thin: about 0.002 wide for 1.4 long (0.2 cells wide at RES 128). */
    static const float sliver_p[] = {0.013f, 0.021f, 0.007f, 1.017f, 0.813f, 0.589f, 0.3139f, 0.2571f, 0.1829f};
    /* Collinear, and a repeated vertex. */
    static const float degenerate_p[] = {0.0f, 0.0f, 0.0f, 0.5f, 0.25f, 1.0f, 1.0f, 0.5f, 2.0f, 0.3f, 0.7f, 0.1f};
    static const uint32_t tri_i[] = {0, 1, 2};
    static const uint32_t degenerate_i[] = {0, 1, 2, 3, 3, 1};

    static const uint32_t res_std[] = {32, 64, 128, 0};
    static const uint32_t res_big[] = {32, 64, 128, 256, 0};

    roma_scene *cornell = NULL, *blinds = NULL, *bunny = NULL, *spot = NULL;
    CHECK_RESULT(roma_scene_create_builtin("cornell", NULL, &cornell), ROMA_SUCCESS);
    CHECK_RESULT(roma_scene_create_builtin("blinds", NULL, &blinds), ROMA_SUCCESS);
    char path[1024];
    if (roma_test_scene_file("bunny.glb", path, sizeof path))
        CHECK_RESULT(roma_scene_load_gltf(path, NULL, &bunny), ROMA_SUCCESS);
    else
        printf("bunny.glb absent: skipped\n");
    if (roma_test_scene_file("spot.glb", path, sizeof path))
        CHECK_RESULT(roma_scene_load_gltf(path, NULL, &spot), ROMA_SUCCESS);
    else
        printf("spot.glb absent: skipped\n");

    /* max_miss: the worst missed fraction over the RES list, measured on lavapipe
     * (Mesa 22.3.6); each run may miss MISS_MARGIN (1 %) + 2 cells more. Order:
     * union3, dominant, union3+cons, dominant+cons. Without conservative
     * rasterization the misses are cells that the surface crosses without covering a
     * pixel centre in any draw (edges, thin parts); union3 misses fewer than dominant
     * everywhere. With it the misses are float ties (the sliver passes through a
     * grid vertex). */
    scene_case cases[20];
    int n = 0;
    if (cornell)
        cases[n++] = (scene_case){from_scene(cornell, "cornell"), 0.0f, res_big, {0.0319, 0.0364, 0, 0, 0}, 0, 0};
    /* Grid shifted by 10.3 cells each way: the scene sticks out of the grid on the
     * low (+10.3) or high (-10.3) side of every axis; cut off, not wrapped. */
    if (cornell)
        cases[n++] = (scene_case){from_scene(cornell, "cornell_low"), 10.3f, res_std, {0.0083, 0.0138, 0, 0, 0}, 0, 1};
    if (cornell)
        cases[n++] = (scene_case){from_scene(cornell, "cornell_high"), -10.3f, res_std, {0.0193, 0.0348, 0, 0, 0}, 0, 1};
    if (blinds)
        cases[n++] = (scene_case){from_scene(blinds, "blinds"), 0.0f, res_std, {0.2371, 0.2371, 0, 0, 0}, 0, 0};
    cases[n++] = (scene_case){raw("tilted", tilted_p, 3, tri_i, 1), 0.0f, res_big, {0.0547, 0.0975, 0, 0, 0}, 0, 1};
    cases[n++] = (scene_case){raw("plane_on_face", plane_p, 3, tri_i, 1), 0.0f, res_std,
                              {0.1310, 0.1310, 0, 0, 0}, 0, 1};
    cases[n++] = (scene_case){raw("plane_mid_cell", plane_p, 3, tri_i, 1), 0.5f, res_std,
                              {0.1330, 0.1330, 0, 0, 0}, 0, 1};
    cases[n++] = (scene_case){raw("sliver", sliver_p, 3, tri_i, 1), 0.0f, res_std, {0.9595, 0.9595, 0, 0.0270, 0}, 0, 0};
    cases[n++] = (scene_case){raw("degenerate", degenerate_p, 4, degenerate_i, 2), 0.0f, res_std, {0, 0, 0, 0, 0}, 1, 0};
    if (spot)
        cases[n++] = (scene_case){from_scene(spot, "spot"), 0.0f, res_std, {0.1642, 0.2069, 0, 0, 0}, 0, 1};
    if (bunny)
        cases[n++] = (scene_case){from_scene(bunny, "bunny"), 0.0f, res_std, {0.3411, 0.3864, 0, 0, 0}, 0, 1};

    printf("per variant: missed and extra cells as fractions of the CPU cells, GPU ms (raster: clear + 3 draws; "
           "compute: lavapipe's timestamps do not cover dispatches)\n| scene          | RES |  cells |");
    for (int v = 0; v < VARIANTS; ++v)
        printf(" %-20s |", variants[v].name);
    printf("\n");
    for (int i = 0; i < n; ++i)
        run_case(ctx, raster, &cases[i]);
    printf("total GPU ms:");
    for (int v = 0; v < VARIANTS; ++v)
        printf(" %s %.1f", variants[v].name, total_gpu_ms[v]);
    printf("\n");

    geometry tilted = raw("tilted", tilted_p, 3, tri_i, 1);
    check_outside(ctx, raster, &tilted);
    if (cornell) {
        geometry g = from_scene(cornell, "cornell");
        check_outside(ctx, raster, &g);
        check_repeatable(ctx, raster, &g, 64);
    }
    if (bunny) {
        geometry g = from_scene(bunny, "bunny");
        check_repeatable(ctx, raster, &g, 64);
    }

    roma_scene_destroy(cornell);
    roma_scene_destroy(blinds);
    roma_scene_destroy(bunny);
    roma_scene_destroy(spot);
    roma_bom_raster_destroy(raster);
    roma_test_context_finish(ctx);
    return roma_test_finish("test_bom");
}
