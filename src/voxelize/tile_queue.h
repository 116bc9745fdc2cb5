/* The queue of tiles of large triangles (internal), shared by the BOM voxelizer
 * (voxelize.comp, voxelize_tiles.comp) and the GI pass's surface grid
 * (surface_cells.comp, surface_cells_tiles.comp): the first pass of each marks small
 * triangles itself and queues a large one as tiles of ROMA_VOXELIZE_TILE x
 * ROMA_VOXELIZE_TILE columns (roma_vox_queue_tiles in roma_voxelize.glsl), the second
 * processes one tile per invocation by an indirect dispatch, so that a few large
 * triangles do not serialise the pass. Layout: roma_voxelize_queue, then capacity uvec2
 * items, at ROMA_VOXELIZE_BINDING_QUEUE. */
#ifndef ROMA_VOXELIZE_TILE_QUEUE_H
#define ROMA_VOXELIZE_TILE_QUEUE_H

#include <vulkan/vulkan.h>

#include "roma_shared.h"
#include "vulkan/vk_internal.h"

typedef struct roma_tile_queue {
    roma_buffer buffer;
    uint32_t capacity; /* items; the push constants' config.y */
} roma_tile_queue;

/* Room for four tiles per column of one face of a RES grid (a grid-wide wall is (RES/8)^2
 * tiles); when it is full, the first pass does the rest inline. On failure *out is
 * zeroed. */
roma_result roma_tile_queue_create(roma_context *ctx, uint32_t resolution, roma_tile_queue *out);
/* Accepts a zeroed queue. */
void roma_tile_queue_destroy(roma_context *ctx, roma_tile_queue *queue);

/* Empties the queue (a transfer write): earlier reads of it (the last indirect dispatch)
 * must have completed, and the write be made visible to compute shaders, by the caller's
 * barriers around it. */
void roma_tile_queue_record_reset(const roma_tile_queue *queue, VkCommandBuffer cmd);

/* With the set and push constants of the two pipelines' shared layout bound: the first
 * pass over triangle_count triangles, the barrier that makes its queue visible to the
 * indirect dispatch and its writes to the second pass, and the second pass. The caller
 * orders what follows after the second pass's writes. */
void roma_tile_queue_record_passes(const roma_tile_queue *queue, VkCommandBuffer cmd, VkPipeline triangles,
                                   VkPipeline tiles, uint32_t triangle_count);

#endif /* ROMA_VOXELIZE_TILE_QUEUE_H */
