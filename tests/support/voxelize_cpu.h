/* Exact CPU voxelizer: the reference the GPU BOM is compared with.
 *
 * Same grid and word layout as the BOM (include/roma/map.h): cell (x, y, z)
 * is bit z & 31 of word (y * RES + x) * (RES / 32) + z / 32.
 *
 * A cell is occupied when the triangle intersects its box. Boundary rule: each
 * cell owns the half-open box [k, k+1)^3 in grid coordinates (the same floor
 * convention as the GPU), so a triangle lying exactly on a cell face belongs to
 * the cell above the face only and no surface vanishes. The test is the
 * separating-axis test of Akenine-Moeller in double precision against the
 * closed box [k, k+1-1e-9]^3, i.e. touching counts as overlap except on the
 * upper faces. Coordinates are taken relative to the box corner (exact), and
 * the box's projections are built from its corners, so that a triangle lying on
 * a face compares equal values rather than rounded centre +- radius ones.
 *
 * Grid coordinates are computed in float exactly as the GPU does,
 * g = (p - origin) * inv_cell, so corners on cell faces land on them in both.
 * Zero-area triangles (|e1 x e2|^2 <= 1e-12 |e1|^2 |e2|^2, the GPU's rule) mark
 * nothing. */
#ifndef ROMA_TEST_VOXELIZE_CPU_H
#define ROMA_TEST_VOXELIZE_CPU_H

#include <stdint.h>

typedef struct roma_voxel_grid {
    float origin[3];   /* corner of cell (0,0,0) */
    float inv_cell;    /* 1 / cell size */
    uint32_t resolution; /* RES, a multiple of 32 */
} roma_voxel_grid;

/* Sets the bits of every cell the triangles overlap in words (RES^3 / 32
 * words, cleared first). positions: stride floats per vertex, xyz first.
 * Returns the number of occupied cells. */
uint64_t roma_voxelize_cpu(const roma_voxel_grid *grid, const float *positions, uint32_t stride,
                           const uint32_t *indices, uint32_t triangle_count, uint32_t *words);

/* Triangle / closed cube [box_min, box_min + box_size] overlap (separating
 * axes, double precision; touching counts). */
int roma_tri_box_overlap(const double box_min[3], double box_size, const double v0[3], const double v1[3],
                         const double v2[3]);

static inline uint64_t roma_voxel_word(uint32_t res, uint32_t x, uint32_t y, uint32_t z)
{
    return ((uint64_t)y * res + x) * (res / 32) + z / 32;
}

static inline int roma_voxel_get(const uint32_t *words, uint32_t res, uint32_t x, uint32_t y, uint32_t z)
{
    return (int)((words[roma_voxel_word(res, x, y, z)] >> (z & 31u)) & 1u);
}

#endif /* ROMA_TEST_VOXELIZE_CPU_H */
