/* BOM voxelization in compute (internal): the exact voxelization of the triangles,
 * the default way to build the base occupancy map on every device.
 *
 * A cell is occupied when the triangle overlaps its half-open box [k, k+1)^3 in grid
 * units (separating-axis test, 13 axes; shaders/include/roma_voxelize.glsl): the same
 * definition as the CPU voxelizer of the tests, which this matches up to float ties.
 * Zero-area triangles (sine of the edge angle below 1e-6) and triangles with NaN or Inf
 * corners mark nothing; geometry outside the grid writes nothing.
 *
 * Work is split so that triangle sizes do not serialise it: voxelize.comp runs one
 * invocation per triangle and marks small triangles itself; a triangle whose
 * footprint spans more than ROMA_VOXELIZE_INLINE_COLUMNS columns along its dominant
 * axis is queued as tiles of 8 x 8 columns, and voxelize_tiles.comp processes one tile
 * per invocation (indirect dispatch). When the queue is full, triangles are marked
 * inline: slower, the same bits. */
#ifndef ROMA_BOM_VOXELIZE_H
#define ROMA_BOM_VOXELIZE_H

#include <vulkan/vulkan.h>

#include "roma/context.h"
#include "roma_shared.h"
#include "vulkan/vk_internal.h"

typedef struct roma_bom_voxelizer roma_bom_voxelizer;

/* The voxelizer binds its buffers once (descriptors: on CPU devices they are much cheaper
 * than buffer-address loads): positions (float4 per vertex) and indices (uint x3 per
 * triangle) as storage buffers, bom (STORAGE and TRANSFER_DST usage, bom_bytes >=
 * RES^3 / 8). They must outlive the voxelizer. The tile queue is its own, sized for
 * resolution. */
roma_result roma_bom_voxelizer_create(roma_context *ctx, uint32_t resolution, VkBuffer positions, VkBuffer indices,
                                      VkBuffer bom, VkDeviceSize bom_bytes, roma_bom_voxelizer **out);
/* Accepts NULL. The caller makes sure no recorded use is still executing. */
void roma_bom_voxelizer_destroy(roma_bom_voxelizer *vox);

/* A run of consecutive triangles: first .. first + count - 1. */
typedef struct roma_triangle_run {
    uint32_t first, count;
} roma_triangle_run;

/* Records into cmd (outside any render pass):
 *  1. a barrier: earlier shader/transfer/indirect accesses of the BOM and the queue
 *     complete before they are cleared, and earlier transfer/compute writes
 *     (geometry uploads, skinning) are visible to the compute reads;
 *  2. the BOM cleared (vkCmdFillBuffer) and the queue header reset (vkCmdUpdateBuffer);
 *  3. voxelize.comp over the triangles, a barrier, voxelize_tiles.comp
 *     (vkCmdDispatchIndirect from the queue);
 *  4. a barrier making the BOM visible to compute-shader reads/writes and transfer reads.
 * grid is this frame's placement (dims.x must be the voxelizer's RES, dims.y RES / 32);
 * it travels in push constants. No triangles: the clear alone. Indices must be in range
 * for positions (not checked on the GPU).
 * One cascade level of a map (grid->level.x: its BOM slot in the buffer; the other slots are
 * kept): the triangles of at most ROMA_VOXELIZE_RUNS runs (one dispatch over them all), into
 * the slot cleared first when clear is set, else added to what it holds. */
roma_result roma_bom_voxelize_record_runs(roma_bom_voxelizer *vox, VkCommandBuffer cmd, const roma_grid_params *grid,
                                          const roma_triangle_run *runs, uint32_t run_count, int clear);
/* One run: triangles first .. first + count - 1. */
roma_result roma_bom_voxelize_record_level(roma_bom_voxelizer *vox, VkCommandBuffer cmd, const roma_grid_params *grid,
                                           uint32_t first, uint32_t count, int clear);
/* The grid's slot cleared and voxelized from triangles 0 .. triangle_count - 1. */
roma_result roma_bom_voxelize_record(roma_bom_voxelizer *vox, VkCommandBuffer cmd, const roma_grid_params *grid,
                                     uint32_t triangle_count);

#endif /* ROMA_BOM_VOXELIZE_H */
