/* The NAADF baseline of the accuracy study (src/study/naadf.h):
 *
 * - the hierarchy the GPU builds from a BOM against one built on the CPU from the same BOM
 *   read back: every chunk's and block's state and box, every voxel of every mixed block,
 *   word for word (the boxes grown in the same order, so equal, not only valid); and every
 *   box checked empty on the BOM itself, within its bounds (a box over an occupied cell
 *   would let rays through it);
 * - the traversal against the exact walk of the same BOM (ROMA_AO_METHOD_VOXEL_DDA), on the
 *   same rays and samples, both through the public AO pass (study/study_ao.h): AO images equal but for rays through a cell's edge or corner,
 *   where either may take the other side (measured: none differ).
 * Scenes: the built-in room (rotated blocks), the blinds (thin slats) and the plates, at
 * RES 64 and 128. Closed rooms stay dark through it as through the exact walk
 * (test_closed_rooms). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "study/naadf.h"
#include "harness.h"
#include "public_render.h"
#include "reference.h"
#include "roma/builtin_scenes.h"
#include "roma/map.h"
#include "roma_shared.h"

#define MAX_DIFFERING_PIXELS 0 /* AO pixels where the traversal and the exact walk differ: measured 0 */

/* A layer's occupancy on the CPU: a byte a cell, (y * n + x) * n + z. */
typedef struct cpu_grid {
    int n;
    const uint8_t *occupied;
} cpu_grid;

static int grid_occupied(const cpu_grid *g, int x, int y, int z) { return g->occupied[((y * g->n) + x) * g->n + z]; }

/* A slice of the box lo..hi with coordinate k on `axis` holds no occupied cell. */
static int slice_empty(const cpu_grid *g, int axis, int k, const int lo[3], const int hi[3])
{
    int a[3] = {lo[0], lo[1], lo[2]}, b[3] = {hi[0], hi[1], hi[2]};
    a[axis] = b[axis] = k;
    for (int y = a[1]; y <= b[1]; ++y)
        for (int x = a[0]; x <= b[0]; ++x)
            for (int z = a[2]; z <= b[2]; ++z)
                if (grid_occupied(g, x, y, z))
                    return 0;
    return 1;
}

/* The paper's growth, as shaders/include/roma_naadf.glsl does it: +x, -x, +y, -y, +z, -z in
 * turn, within bmin..bmax and maxd. Returns the packed distances. */
static uint32_t grow(const cpu_grid *g, const int c[3], const int bmin[3], const int bmax[3], int maxd, uint32_t bits,
                     uint32_t shift)
{
    int lo[3] = {c[0], c[1], c[2]}, hi[3] = {c[0], c[1], c[2]};
    for (int grew = 1; grew;) {
        grew = 0;
        for (int a = 0; a < 3; ++a) {
            if (hi[a] < bmax[a] && hi[a] - c[a] < maxd && slice_empty(g, a, hi[a] + 1, lo, hi))
                hi[a] += 1, grew = 1;
            if (lo[a] > bmin[a] && c[a] - lo[a] < maxd && slice_empty(g, a, lo[a] - 1, lo, hi))
                lo[a] -= 1, grew = 1;
        }
    }
    uint32_t w = 0;
    for (int a = 0; a < 3; ++a)
        w |= ((uint32_t)(hi[a] - c[a]) << (shift + 2 * a * bits)) |
             ((uint32_t)(c[a] - lo[a]) << (shift + (2 * a + 1) * bits));
    return w;
}

static uint32_t cube_index(int x, int y, int z, uint32_t n)
{
    return ((uint32_t)y * n + (uint32_t)x) * n + (uint32_t)z;
}

/* Builds the map and the hierarchy and reads back the BOM and the cells. */
static int build(roma_context *ctx, const roma_scene *scene, uint32_t res, uint32_t **bom, uint32_t **cells)
{
    roma_map *map = NULL;
    roma_map_desc md = {.resolution = res, .angular = 1};
    roma_naadf nf = {0};
    roma_buffer rb_bom = {0}, rb_cells = {0};
    const uint64_t bom_bytes = (uint64_t)res * res * res / 8;
    int ok = 0;
    roma_map_info info;
    CHECK_RESULT(roma_map_create(ctx, &md, scene, &map), ROMA_SUCCESS);
    if (!map)
        return 0;
    CHECK_RESULT(roma_map_get_info(map, &info), ROMA_SUCCESS);
    CHECK_RESULT(roma_naadf_create(ctx, info.bom_buffer, res, &nf), ROMA_SUCCESS);
    const uint64_t cell_bytes = nf.ctx ? roma_naadf_bytes(&nf, NULL) : 0;
    CHECK_RESULT(roma_buffer_create(ctx, bom_bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, ROMA_MEMORY_READBACK, &rb_bom),
                 ROMA_SUCCESS);
    if (cell_bytes)
        CHECK_RESULT(roma_buffer_create(ctx, cell_bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, ROMA_MEMORY_READBACK,
                                        &rb_cells),
                     ROMA_SUCCESS);
    VkCommandBuffer cmd;
    if (nf.ctx && rb_bom.buffer && rb_cells.buffer && roma_begin_one_shot(ctx, &cmd) == ROMA_SUCCESS) {
        roma_map_frame_desc frame = {0};
        CHECK_RESULT(roma_map_record_build(map, cmd, &frame, NULL), ROMA_SUCCESS);
        /* Twice: the second build starts from the first one's cells, as every frame after the first. */
        roma_naadf_record(&nf, cmd);
        roma_naadf_record(&nf, cmd);
        VkBufferCopy c_bom = {0, 0, bom_bytes}, c_cells = {0, 0, cell_bytes};
        vkCmdCopyBuffer(cmd, info.bom_buffer, rb_bom.buffer, 1, &c_bom);
        vkCmdCopyBuffer(cmd, nf.cells.buffer, rb_cells.buffer, 1, &c_cells);
        roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                                VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
        CHECK_RESULT(roma_submit_one_shot(ctx, cmd), ROMA_SUCCESS);
        roma_buffer_invalidate(ctx, &rb_bom);
        roma_buffer_invalidate(ctx, &rb_cells);
        *bom = malloc(bom_bytes);
        *cells = malloc(cell_bytes);
        if (*bom && *cells) {
            memcpy(*bom, rb_bom.mapped, bom_bytes);
            memcpy(*cells, rb_cells.mapped, cell_bytes);
            ok = 1;
        }
    }
    roma_buffer_destroy(ctx, &rb_bom);
    roma_buffer_destroy(ctx, &rb_cells);
    roma_naadf_destroy(&nf);
    roma_map_destroy(map);
    return ok;
}

/* Every word of the GPU's hierarchy against the CPU's from the same BOM. */
static void test_structure(roma_context *ctx, const char *name, const roma_scene *scene, uint32_t res)
{
    uint32_t *bom = NULL, *cells = NULL;
    if (!build(ctx, scene, res, &bom, &cells))
        return;
    uint64_t chunk_words, block_words, voxel_words, row_words;
    roma_naadf_layout(res, &chunk_words, &block_words, &voxel_words, &row_words);
    const int n = (int)res, nc = n / 16, nb = n / 4;
    /* Occupied voxels; occupied and full counts of blocks and chunks. */
    uint8_t *vox = calloc((size_t)n * n * n, 1), *bocc = calloc((size_t)nb * nb * nb, 1),
            *cocc = calloc((size_t)nc * nc * nc, 1);
    uint32_t *bcount = calloc((size_t)nb * nb * nb, sizeof *bcount);
    uint32_t *ccount = calloc((size_t)nc * nc * nc, sizeof *ccount);
    CHECK(vox && bocc && cocc && bcount && ccount);
    if (!vox || !bocc || !cocc || !bcount || !ccount) {
        free(vox), free(bocc), free(cocc), free(bcount), free(ccount), free(bom), free(cells);
        return;
    }
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x)
            for (int z = 0; z < n; ++z) {
                uint32_t i = cube_index(x, y, z, res);
                if (!((bom[i >> 5] >> (i & 31)) & 1u))
                    continue;
                vox[i] = 1;
                bocc[cube_index(x / 4, y / 4, z / 4, (uint32_t)nb)] = 1;
                ++bcount[cube_index(x / 4, y / 4, z / 4, (uint32_t)nb)];
                cocc[cube_index(x / 16, y / 16, z / 16, (uint32_t)nc)] = 1;
                ++ccount[cube_index(x / 16, y / 16, z / 16, (uint32_t)nc)];
            }
    uint64_t wrong = 0, counted[3] = {0, 0, 0}, mixed_blocks = 0;
    /* Chunks: boxes over the chunk grid, at most 31 a direction. */
    cpu_grid cg = {nc, cocc}, bg = {nb, bocc}, vg = {n, vox};
    for (int y = 0; y < nc; ++y)
        for (int x = 0; x < nc; ++x)
            for (int z = 0; z < nc; ++z) {
                uint32_t c = ccount[cube_index(x, y, z, (uint32_t)nc)];
                uint32_t want = c == 0 ? ROMA_NAADF_EMPTY : c == 16 * 16 * 16 ? ROMA_NAADF_FULL : ROMA_NAADF_MIXED;
                ++counted[want];
                if (want == ROMA_NAADF_EMPTY)
                    want |= grow(&cg, (int[3]){x, y, z}, (int[3]){0, 0, 0}, (int[3]){nc - 1, nc - 1, nc - 1},
                                 ROMA_NAADF_CHUNK_MAX_DISTANCE, 5, 2);
                wrong += cells[cube_index(x, y, z, (uint32_t)nc)] != want;
            }
    /* Blocks: boxes within their chunk; voxels of mixed blocks: boxes within their block. */
    for (int y = 0; y < nb; ++y)
        for (int x = 0; x < nb; ++x)
            for (int z = 0; z < nb; ++z) {
                uint32_t c = bcount[cube_index(x, y, z, (uint32_t)nb)];
                uint32_t want = c == 0 ? ROMA_NAADF_EMPTY : c == 64 ? ROMA_NAADF_FULL : ROMA_NAADF_MIXED;
                if (want == ROMA_NAADF_EMPTY) {
                    int lo[3] = {x & ~3, y & ~3, z & ~3}, hi[3] = {lo[0] + 3, lo[1] + 3, lo[2] + 3};
                    want |= grow(&bg, (int[3]){x, y, z}, lo, hi, 3, 2, 2);
                }
                wrong += cells[chunk_words + cube_index(x, y, z, (uint32_t)nb)] != want;
                if ((want & 3u) != ROMA_NAADF_MIXED)
                    continue;
                ++mixed_blocks;
                int lo[3] = {4 * x, 4 * y, 4 * z}, hi[3] = {lo[0] + 3, lo[1] + 3, lo[2] + 3};
                for (int j = 0; j < 4; ++j)
                    for (int i = 0; i < 4; ++i)
                        for (int k = 0; k < 4; ++k) {
                            int v[3] = {lo[0] + i, lo[1] + j, lo[2] + k};
                            uint32_t at = cube_index(v[0], v[1], v[2], res);
                            uint32_t want_v = vox[at] ? 1u : grow(&vg, v, lo, hi, 3, 2, 1);
                            uint32_t word = cells[chunk_words + block_words + (at >> 1)];
                            uint32_t got = (word >> ((at & 1u) * 16u)) & 0xffffu;
                            wrong += got != want_v;
                        }
            }
    printf("%-7s RES %3u: chunks %llu empty, %llu full, %llu mixed; %llu mixed blocks; "
           "%llu words differ from the CPU's\n",
           name, res, (unsigned long long)counted[0], (unsigned long long)counted[1], (unsigned long long)counted[2],
           (unsigned long long)mixed_blocks, (unsigned long long)wrong);
    CHECK(wrong == 0);
    CHECK(mixed_blocks > 0);
    free(vox);
    free(bocc);
    free(cocc);
    free(bcount);
    free(ccount);
    free(bom);
    free(cells);
}

/* AO through the hierarchy against the exact walk of the BOM, same rays and samples. */
static void test_traversal(roma_context *ctx, const char *name, const roma_scene *scene, uint32_t res, float radius)
{
    enum { W = 64, H = 48 };
    roma_scene_view v;
    roma_scene_get_view(scene, &v);
    roma_camera cam = v.camera;
    if (!v.has_camera)
        roma_scene_default_camera(scene, (float)W / (float)H, &cam);
    effect_api_result img[2];
    memset(img, 0, sizeof img);
    const roma_ao_method methods[2] = {ROMA_AO_METHOD_VOXEL_DDA, ROMA_AO_METHOD_NAADF};
    roma_ref *ref = NULL; /* the G-buffer's primary rays */
    CHECK_RESULT(roma_ref_create(scene, NULL, &ref), ROMA_SUCCESS);
    for (int m = 0; m < 2 && ref; ++m) {
        const effect_api_desc d = {.camera = cam, .width = W, .height = H, .spp = 16, .frames = 2, .seed = 3,
                                   .ao_radius = radius, .ao_method = methods[m],
                                   .options = {.effects = ROMA_EFFECT_AO, .resolution = res}};
        CHECK_RESULT(roma_test_public_render(ctx, scene, ref, &d, &img[m], NULL), ROMA_SUCCESS);
    }
    roma_ref_destroy(ref);
    if (img[0].ao.pixels && img[1].ao.pixels) {
        uint32_t differ = 0;
        float worst = 0.0f;
        for (uint32_t i = 0; i < W * H; ++i) {
            float e = fabsf(img[0].ao.pixels[i] - img[1].ao.pixels[i]);
            differ += e > 0.0f;
            worst = fmaxf(worst, e);
        }
        printf("%-7s RES %3u radius %s: AO through NAADF differs from the exact walk in %u of %u pixels "
               "(largest %.4f)\n",
               name, res, radius > 0.0f ? "0.5" : "inf", differ, W * H, worst);
        CHECK(differ <= MAX_DIFFERING_PIXELS);
    }
    effect_api_result_free(&img[0]);
    effect_api_result_free(&img[1]);
}

int main(void)
{
    roma_context *ctx = roma_test_context();
    if (!ctx)
        return roma_test_finish("test_naadf");
    const char *names[] = {"cornell", "blinds", "plates"};
    for (int s = 0; s < 3; ++s) {
        roma_scene *scene = NULL;
        CHECK_RESULT(roma_scene_create_builtin(names[s], NULL, &scene), ROMA_SUCCESS);
        if (!scene)
            continue;
        test_structure(ctx, names[s], scene, 64);
        test_structure(ctx, names[s], scene, 128);
        test_traversal(ctx, names[s], scene, 128, 0.0f);
        test_traversal(ctx, names[s], scene, 64, 0.5f);
        roma_scene_destroy(scene);
    }
    /* Bad arguments: a clear refusal and a zeroed hierarchy. */
    roma_naadf nf;
    CHECK_RESULT(roma_naadf_create(ctx, VK_NULL_HANDLE, 128, &nf), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK(nf.ctx == NULL);
    roma_naadf_destroy(&nf);
    roma_context_destroy(ctx);
    return roma_test_finish("test_naadf");
}
