/* The surface grid of the GI pass (roma_gi_scene in roma_shared.h): which triangle
 * lies in each cell of a grid over the scene, so that a bounce ray's ROMA hit (a
 * cell, not a triangle) finds the albedo and normal of the surface it reached.
 * The grid is not the BOM's: it stands still (no per-frame jitter) and is built
 * once per scene with the exact voxelizer's overlap test. */
#ifndef ROMA_PASSES_SURFACE_CELLS_H
#define ROMA_PASSES_SURFACE_CELLS_H

#include "passes/scene_buffers.h"
#include "vulkan/vk_internal.h"

typedef struct roma_surface_cells {
    roma_context *ctx;
    roma_compute_pipeline pipeline;
    roma_descriptor_set set;
    roma_buffer cells;          /* RES^3 uint */
    uint32_t resolution;
    float origin[3], cell;      /* corner of cell (0,0,0), cell size */
    uint32_t triangle_count;
} roma_surface_cells;

/* A RES^3 grid around the scene bounds over the geometry's positions and indices
 * (which must outlive it). On failure *out is zeroed. */
roma_result roma_surface_cells_create(roma_context *ctx, const roma_scene_buffers *geometry, const float bounds_min[3],
                                      const float bounds_max[3], uint32_t resolution, roma_surface_cells *out);
/* Accepts a zeroed grid. */
void roma_surface_cells_destroy(roma_surface_cells *cells);

/* Clears the grid and writes every triangle into the cells it overlaps; makes the
 * writes visible to later compute shaders. Reads the geometry's buffers (host writes
 * before the submission). */
void roma_surface_cells_record(roma_surface_cells *cells, VkCommandBuffer cmd);

#endif /* ROMA_PASSES_SURFACE_CELLS_H */
