/* The surface grid (roma_surface_grid in roma_shared.h): which triangle lies in each cell
 * of a grid over the geometry, so that a GI bounce ray's ROMA hit (a cell, not a triangle)
 * finds the albedo and normal of the surface it reached, and a shadow segment's end at its
 * light finds on which side of a wall in the light's cells the light lies. The grid is not
 * the BOM's: it does not jitter, and it is built with the exact voxelizer's overlap test
 * whenever the geometry it covers has moved. */
#ifndef ROMA_EFFECTS_SURFACE_CELLS_H
#define ROMA_EFFECTS_SURFACE_CELLS_H

#include "roma/map.h" /* ROMA_MAX_FRAMES_IN_FLIGHT */
#include "effects/light_data.h"
#include "roma_shared.h"
#include "voxelize/tile_queue.h"
#include "vulkan/vk_internal.h"

typedef struct roma_surface_cells {
    roma_context *ctx;
    /* Small triangles write their cells in the first; large ones are queued as tiles of
     * columns for the second (an indirect dispatch), as the BOM voxelizer does. */
    roma_compute_pipeline triangles, tiles;
    roma_tile_queue queue;
    /* One set per frame slot: a build in a slot rewrites that slot's set (the geometry's
     * buffers may have been replaced), which the slot rules make safe. */
    roma_descriptor_set sets[ROMA_MAX_FRAMES_IN_FLIGHT];
    roma_buffer cells;          /* one or two layers of RES^3 uint */
    roma_buffer third_cells;    /* the third layer, RES^3 uint, a buffer of its own (within the
                                   binding's range at RES 256); written through its address;
                                   with COUNTS, the blocks' flags after it, then the
                                   super-blocks' (ROMA_SURFACE_BLOCK, _SUPER) */
    uint32_t resolution, layers; /* ROMA_SURFACE_LAYERS_* */
    float origin[3], cell;      /* of the last build: corner of cell (0,0,0), cell size */
    uint64_t version;           /* the map geometry it holds (roma_surface_cells_follow; 0: none) */
} roma_surface_cells;

/* What a build reads: float4 positions per vertex, uint3 indices per triangle, and which of
 * the first emitter_triangles triangles are area lights (bits as roma_light_data's; 0: none),
 * ranked after the rest in a cell they share. */
typedef struct roma_surface_geometry {
    VkBuffer positions, indices;
    uint32_t triangle_count;
    VkDeviceAddress emitter_bits;
    uint32_t emitter_triangles;
} roma_surface_geometry;

/* A RES^3 grid (RES at most 256) with `layers` (ROMA_SURFACE_LAYERS_*): the lowest key in each
 * cell, and from TWO on the highest index of a triangle that is not an area light too (plus
 * one; 0: none), so that a cell two walls share (the halves of a quad along its diagonal, a
 * room's edge) shows both, also where a lamp shares it; with EMITTERS the lowest area light's
 * key too (ROMA_GBUFFER_NO_TRIANGLE: none), so that a GI bounce hit finds a lamp whose cells a
 * ceiling shares (the GI effect's grid); with COUNTS how many triangles overlap each cell, so
 * that an AO ray knows where the two layers hold all of a cell's triangles (the AO effect's).
 * On failure *out is zeroed. */
roma_result roma_surface_cells_create(roma_context *ctx, uint32_t resolution, uint32_t layers,
                                      roma_surface_cells *out);
/* Accepts a zeroed grid. */
void roma_surface_cells_destroy(roma_surface_cells *cells);

/* Places the grid around the box [bounds_min, bounds_max]: cubic cells over its largest
 * extent, a few percent of margin so that surfaces on the bounds lie inside. Empty or
 * non-finite bounds fail with ROMA_ERROR_INVALID_SCENE and keep the placement. */
roma_result roma_surface_cells_place(roma_surface_cells *cells, const float bounds_min[3], const float bounds_max[3]);

/* Records the build into cmd where the grid is placed: orders it after earlier reads of
 * the grid and its queue on the queue, clears it, writes every triangle into the cells it
 * overlaps and makes the writes visible to later compute shaders. The geometry's buffers are read when
 * cmd executes and must be written before (the map's build makes its positions visible
 * to compute shaders). A failed set allocation records nothing. */
roma_result roma_surface_cells_record(roma_surface_cells *cells, VkCommandBuffer cmd, uint32_t slot,
                                      const roma_surface_geometry *geometry);

/* Records a build of the grid (made at `resolution` with `layers` on first use) from the map's geometry,
 * with the scene's area lights of `emitters` (NULL: none; their copies recorded before), when
 * the grid holds another map's or an older build's (versions are unique in the context;
 * records nothing otherwise). A failure is logged as `name`'s, and the grid is built again
 * next time; so must it be when the caller drops cmd or sets other area lights (set version
 * to 0). */
roma_result roma_surface_cells_follow(roma_surface_cells *cells, roma_context *ctx, uint32_t resolution,
                                      uint32_t layers, VkCommandBuffer cmd, uint32_t slot, const roma_map *map,
                                      const roma_light_data *emitters, const roma_logger *log, const char *name);

/* What the shaders read of a grid that follows map (roma_surface_cells_follow). */
roma_surface_grid roma_surface_cells_view(const roma_surface_cells *cells, const roma_map *map);

/* roma_surface_cells_follow, then the grid's record (roma_surface_cells_view) written into the
 * slot's upload `record` (made on first use), for the caller's roma_upload_record: what an
 * effect whose passes read the grid by its record's address does each record. */
roma_result roma_surface_cells_follow_record(roma_surface_cells *cells, roma_upload *record, roma_context *ctx,
                                             uint32_t resolution, uint32_t layers, VkCommandBuffer cmd, uint32_t slot,
                                             const roma_map *map, const roma_light_data *emitters,
                                             const roma_logger *log, const char *name);

#endif /* ROMA_EFFECTS_SURFACE_CELLS_H */
