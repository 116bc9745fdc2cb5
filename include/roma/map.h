/** @file
 * libroma: the Ray-aligned Occupancy Map Array.
 *
 * A roma_map owns, on the GPU:
 *  - the base occupancy map (BOM): a RES^3 binary grid over a cube fitted to the
 *    scene, voxelized from the triangles every build. Texel (x, y) holds RES/32
 *    words; bit b of word w is cell z = 32 w + b (least significant bit = lowest z);
 *  - A x A ray-aligned occupancy maps, one per candidate direction, each the BOM
 *    resampled ("rotated") into a box whose z axis is the candidate direction;
 *  - the per-frame parameters (grid placement, candidate frames) in a buffer.
 *
 * Candidate directions are stratified over the hemisphere z >= 0 (world z) with
 * the equal-area concentric mapping and jittered inside their strata from
 * (seed, frame). A direction d with d.z < 0 uses the map of -d traced backwards,
 * so one map serves d and -d. Map selection is O(1): the stratum of a direction
 * is found by inverting the mapping.
 *
 * Each rotated map's box is the bounding box of the (jittered, margin-padded)
 * grid cube in the candidate's frame, so every map contains all geometry for
 * every direction. Its cells are not cubes: along each map axis the cell size is
 * that box extent / RES, between 1 and sqrt(3) times the BOM cell size
 * (1 for axis-aligned candidates, sqrt(3) at worst for cube diagonals).
 *
 * Tracing (roma/trace.glsl, the same code engines include):
 *  - snapped: the ray direction is replaced by its candidate; any-hit and
 *    closest-hit are one texel fetch plus bit masks, O(1);
 *  - un-snapped: the exact direction is walked through the selected map's texels
 *    with a 2D DDA of at most max_steps texels (default 8); rays that need more
 *    report a miss for the part not walked.
 * Closest-hit distance is the distance to the entry face of the first occupied
 * cell along the ray, clamped to tmin.
 *
 * Rays leaving a surface start offset along its normal by ROMA_DEFAULT_OFFSET_CELLS
 * (1.5, the paper's value) trace cells: a trace cell is the longest edge a rotated
 * cell can have (sqrt(3) BOM cells), so the origin clears the surface's own cells in
 * every map. Rotation samples the BOM twice per rotated cell along the map's z axis
 * (ROMA_ROTATE_SAMPLES) so that rays rarely step over one-cell-thick walls
 * (docs/accuracy.md: 0.1% of rays in a closed room, against 8.8% with one sample).
 *
 * Threads (roma/context.h): a map is externally synchronised, used by one thread at a time;
 * different maps may be used from different threads at once; record calls write only into the
 * command buffer they are given. */
#ifndef ROMA_MAP_H
#define ROMA_MAP_H

#include "roma/api.h"

/** Default ray-origin offset off the surface, in trace cells. */
#define ROMA_DEFAULT_OFFSET_CELLS 1.5f

#include <stdint.h>
#include <vulkan/vulkan.h>

#include "roma/context.h"
#include "roma/presets.h"
#include "roma/scene.h"
#include "roma/trace_types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** A ray-aligned occupancy map array and the scene geometry it is built from (opaque). Used by one
 * thread at a time (roma/context.h). */
typedef struct roma_map roma_map;

/** How the base occupancy map is voxelized. */
typedef enum roma_bom_mode {
    /** Default: the exact voxelization, in compute on every device: a cell is occupied
     * when a triangle overlaps it (separating-axis test), up to float ties. */
    ROMA_BOM_EXACT = 0,
    /** Rasterize along x, y and z at pixel centres, union (misses thin parts). */
    ROMA_BOM_UNION3,
    ROMA_BOM_DOMINANT,    /**< each triangle only along its dominant normal axis, pixel centres */
    /** Dominant axis rasterized conservatively (the projected triangle grown by half a
     * pixel, pixels it does not touch discarded): the exact voxelization through the
     * raster pipeline, for devices where that is faster (large triangles on a GPU). */
    ROMA_BOM_CONSERVATIVE
} roma_bom_mode;

/** Most frame slots any libroma object takes. */
#define ROMA_MAX_FRAMES_IN_FLIGHT 8

/** How an effect on the engine's G-buffer images (roma_ao_effect, roma_light_effect,
 * roma_gi_effect) covers them. */
typedef enum roma_pixel_dispatch {
    /** The list on CPU devices, every pixel on GPUs: on lavapipe the list saves 30% of the AO
     * pass on a view that covers 23% of the screen, on an H100 it costs 35% (its pass and
     * barriers outweigh the idle lanes); docs/benchmark.md. */
    ROMA_PIXEL_DISPATCH_AUTO = 0,
    /** Each record lists the covered pixels (position w > 0) and traces them by an indirect
     * dispatch. */
    ROMA_PIXEL_DISPATCH_LIST = 1,
    /** One dispatch over every pixel; the lanes of uncovered pixels return at once. */
    ROMA_PIXEL_DISPATCH_EVERY_PIXEL = 2,
} roma_pixel_dispatch;

/** Settings of roma_map_create; the zero value is the default (RES 128, A 4, exact BOM). */
typedef struct roma_map_desc {
    uint32_t resolution;       /**< RES in {32, 64, 128, 256}; 0 = the preset's (128) */
    uint32_t angular;          /**< A in [1, 16]: A x A maps; 0 = the preset's (4) */
    roma_preset preset;        /**< RES and A where they are 0 (roma/presets.h); 0 = medium */
    roma_bom_mode bom_mode; /**< how the BOM is voxelized; 0 = ROMA_BOM_EXACT */
    float margin_cells;        /**< grid cube padding around the traced volume, cells, [0.5, RES/8]; 0 = 1 */
    uint32_t frames_in_flight; /**< frame slots for host-written positions, [1, 8]; 0 = 2 */
    roma_logger logger;        /**< 0 = the context's */
    /** Cascade levels K in [1, ROMA_MAX_LEVELS], with K x A x A at most 256; 0 = 1. Level 0
     * is a cube around roma_map_frame_desc.focus, each next level a cube of twice the edge
     * around it, each RES^3 cells with its own A x A maps: cells grow with the distance from
     * the focus (the camera). A ray is traced from the finest level that holds its origin
     * out through the coarser ones (roma/trace.glsl). The exact BOM mode only. */
    uint32_t cascades;
} roma_map_desc;

/** Creates a map for a scene: its buffers and pipelines (shared through the context).
 * The scene's topology (indices) and first positions are uploaded here: the one call
 * of a map that submits to the context's queue and waits (not a per-frame call).
 * The map is not built yet: record a build before tracing.
 * Supported volumes: the grid cube around the traced volume (the scene's bounds or
 * roma_map_frame_desc.volume) must lie within +-8.5e37 world units on every axis and
 * its cells be at least 1e-35 across (at RES 32, volumes at least ~3e-34 wide; at most
 * ~1.6e38 wide when centred on the origin); others are refused with
 * ROMA_ERROR_INVALID_SCENE.
 *
 * @param context  the context; must outlive the map.
 * @param desc     settings; NULL = the zero value (RES 128, A 4, exact BOM, 2 slots).
 * @param scene    the geometry (vertex count and triangles are fixed for the map's life);
 *                 copied: it may be destroyed after the call.
 * @param[out] out_map  the new map; NULL on failure.
 * @return ROMA_SUCCESS;
 *   ROMA_ERROR_INVALID_ARGUMENT: a NULL out_map, context or scene, a resolution other than
 *   32/64/128/256, A above 16, an unknown preset or bom_mode, frames_in_flight above 8, margin_cells
 *   outside [0.5, RES/8];
 *   ROMA_ERROR_INVALID_SCENE: scene bounds empty, not finite or outside the supported range;
 *   ROMA_ERROR_UNSUPPORTED: the maps of all levels exceed the device's maxTexelBufferElements
 *   (words) or maxStorageBufferRange (bytes; 128 MiB on lavapipe: RES 256 with at most 64 maps);
 *   ROMA_ERROR_OUT_OF_HOST_MEMORY, or a Vulkan failure code (roma_result).
 * @par Threads
 * Any thread; submits to the context's queue (roma_context_desc.queue_lock). */
ROMA_API roma_result roma_map_create(roma_context *context, const roma_map_desc *desc,
                                     const roma_scene *scene, roma_map **out_map);
/** Destroys a map, its meshes and instances, and every buffer and set it handed out
 * (roma_map_info handles are invalid afterwards).
 *
 * @param map  the map, or NULL (nothing is done). The caller makes sure no submitted work
 *             still uses the map (the blocking convenience calls below always finish theirs).
 * @par Threads
 * Any thread, the map externally synchronised. */
ROMA_API void roma_map_destroy(roma_map *map);

/** An axis-aligned box in world space. */
typedef struct roma_box {
    float min[3]; /**< lowest corner */
    float max[3]; /**< highest corner */
} roma_box;

/** This frame's positions of a mesh added to the map (roma_map_add_mesh), written on the GPU by
 * the caller: a skinned character or a deforming object among static geometry. Every instance of
 * the mesh takes them, in its own place; the rest of the map is not rebuilt for them, as for a
 * dynamic instance that moved. */
typedef struct roma_mesh_positions {
    uint32_t mesh; /**< from roma_map_add_mesh; its instances must all be ROMA_INSTANCE_DYNAMIC */
    /** The mesh's vertex_count positions in its local frame: 3 floats at
     * gpu_positions + i * gpu_position_stride, read by a compute pass of the build. */
    VkDeviceAddress gpu_positions;
    uint32_t gpu_position_stride; /**< bytes between vertices, a multiple of 4; 0 = 12 */
    /** A box (local frame) holding every position: the host cannot see them, and a level
     * voxelizes and restores only what the instances' boxes touch (roma_animator_output.bounds
     * for an animator's positions). Kept for later builds that give no new positions. */
    roma_box bounds;
} roma_mesh_positions;

/** What one build uses: its slot, jitter, volume and new positions; the zero value builds from
 * the last positions in slot 0 (levels already built from the same are kept:
 * roma_map_info.levels_rebuilt).
 */
typedef struct roma_map_frame_desc {
    uint32_t frame;        /**< frame counter: drives the jitter */
    uint32_t seed; /**< with frame: the jitter sequence */
    int jitter_grid;       /**< non-zero: sub-cell offset of the grid origin per frame */
    int jitter_directions; /**< non-zero: candidates jittered inside their strata (else centres) */
    /** The engine's frame slot, in [0, frames_in_flight): host data of this build goes to
     * storage of this slot. The caller makes sure the GPU finished the last command
     * buffer recorded with the same slot (its own per-frame fence) before recording. */
    uint32_t slot;
    /** The box the grid is fitted to (plus margin_cells); geometry outside it is not
     * traced. NULL: the bounds of the last host positions (the scene's at first) and of
     * the instances. */
    const roma_box *volume;
    /** New vertex positions for this build (the map's vertex count, vertex_count must
     * equal it), from either:
     *  - host memory: 3 floats per vertex, copied at record time into the slot's
     *    staging and from there by the GPU (vkCmdCopyBuffer);
     *  - the caller's GPU memory (a skinning or animation pass): 3 floats at
     *    gpu_positions + i * gpu_position_stride (bytes, multiple of 4, 0 = 12), read
     *    by a compute pass; volume is then required (the host cannot see the bounds).
     * Neither: the positions of the previous build stay. */
    const float *positions;
    VkDeviceAddress gpu_positions; /**< the caller's positions by address (0: none) */
    uint32_t gpu_position_stride; /**< bytes between vertices, a multiple of 4; 0 = 12 */
    uint32_t vertex_count; /**< with positions or gpu_positions: the map's vertex count */
    /** New positions of added meshes (mesh_position_count entries, one per mesh at most),
     * gathered before the instances are placed; meshes not listed keep theirs. NULL: none. */
    const roma_mesh_positions *mesh_positions;
    uint32_t mesh_position_count; /**< entries in mesh_positions */
    /** A map of several cascade levels: the point they centre on this frame (3 floats: the
     * camera's position); each level's centre snaps to its own cells, so that static
     * geometry does not shimmer as the point moves. NULL: the traced volume's centre. */
    const float *focus;
    /** A map of several cascade levels: the edge of the finest level's cube (world units,
     * before margin_cells); 0: the coarsest level holds the whole traced volume wherever the
     * focus is: its edge is the volume's longest edge for a focus at the centre, and for a
     * focus off it that of the cube around the focus that holds the volume, rounded up to a
     * quarter octave of the longest edge (so that the cells keep their size while the focus
     * moves between steps; a focus that crosses a step, as any move off the exact centre
     * does, changes every level, and one that goes back and forth across it changes them each
     * time); the finest's is that / 2^(K-1). Geometry outside the coarsest level is not
     * traced. */
    float finest_extent;
} roma_map_frame_desc;

/** Records the build of this frame into cmd (a command buffer of the context's queue
 * family, outside a render pass).
 *
 * What it records: the frame parameters (vkCmdUpdateBuffer: they travel
 * in the command buffer, so builds may be recorded for any number of frames in
 * flight), new positions if given, BOM clear + voxelization + rotation. It never
 * submits or waits. Synchronisation it records itself:
 *  - first, a barrier after every earlier command of the queue (ALL_COMMANDS): earlier
 *    reads of the map (traces from any stage, downloads) finish before it is rewritten,
 *    and earlier writes of gpu_positions (transfer or shader stages) are visible;
 *  - last, a barrier making the maps and parameters visible to every later command
 *    (ALL_COMMANDS, MEMORY_READ): a caller tracing from a fragment or compute shader
 *    afterwards, in this command buffer or a later one on this queue, needs no barrier
 *    of its own. (On another queue: the caller's semaphore and queue transfer.)
 * timer may be NULL; otherwise scopes "bom" and "rotate" are added (every timer passed
 * to a map must come from a context on the map's VkDevice: ROMA_ERROR_INVALID_ARGUMENT
 * otherwise). A failed call records nothing the map depends on and keeps the previous
 * positions.
 *
 * @param map    the map.
 * @param cmd    a command buffer of the context's queue family, recording; the map must
 *               outlive its execution.
 * @param frame  this build's settings; NULL = the zero value (slot 0, no jitter, the last
 *               positions). Host positions are copied during the call; gpu_positions must
 *               hold the positions when cmd executes.
 * @param timer  may be NULL; otherwise scopes "bom" and "rotate" are added (not reset).
 * @return ROMA_SUCCESS;
 *   ROMA_ERROR_INVALID_ARGUMENT: a NULL map or cmd, a timer of another VkDevice, a slot
 *   not below frames_in_flight, both positions and gpu_positions, a vertex_count other than
 *   the map's, a gpu_position_stride not a multiple of 4 or below 12, gpu_positions not
 *   4-byte aligned or without volume, more than 16 GiB of gpu_positions (vertex_count x
 *   stride), a volume with min above max (or NaN); in mesh_positions (NULL with a count, an
 *   unknown or removed mesh, a mesh listed twice or with a static instance, a zero, unaligned
 *   or oversized gpu_positions, a bad stride, bounds with min above max or not finite);
 *   ROMA_ERROR_INVALID_SCENE: non-finite host positions, or the volume (or bounds) outside
 *   the range roma_map_create supports;
 *   ROMA_ERROR_OUT_OF_HOST_MEMORY, or a Vulkan failure code (roma_result) from the
 *   buffers made on first use of a slot or after instances changed.
 * @par Threads
 * Any thread, the map externally synchronised; cmd externally synchronised. Never submits or
 * waits. Binds its own
 * pipelines, descriptor sets and push constants: bind yours again afterwards. */
ROMA_API roma_result roma_map_record_build(roma_map *map, VkCommandBuffer cmd,
                                           const roma_map_frame_desc *frame, roma_gpu_timer *timer);

/** Convenience: records a build (roma_map_record_build) into a command buffer of its own,
 * submits it to the context's queue and waits.
 *
 * @param map    the map.
 * @param frame  as for roma_map_record_build; NULL = the zero value.
 * @param timer  may be NULL; otherwise it is reset and gets the scopes "bom" and "rotate".
 * @return ROMA_SUCCESS; ROMA_ERROR_INVALID_ARGUMENT for a NULL map; otherwise the codes of
 *         roma_map_record_build, or a Vulkan failure code (roma_result) of the submission.
 * @par Threads
 * Any thread, the map externally synchronised; submits to the context's queue
 * (roma_context_desc.queue_lock). */
ROMA_API roma_result roma_map_build(roma_map *map, const roma_map_frame_desc *frame,
                                    roma_gpu_timer *timer);

/* --- Objects: meshes and their instances ---
 *
 * Besides the scene it was made with, a map voxelizes instances of meshes added to it,
 * each with its own transform. A moving instance costs its transform: the next build
 * transforms the mesh's vertices on the GPU (one dispatch per dynamic instance); a
 * static instance is transformed once, at the first build after it was added. Adding or
 * removing changes which triangles the next build voxelizes; the host work happens in
 * these calls and in the next roma_map_record_build, which uploads new meshes through
 * the command buffer. Nothing here submits or waits: buffers that an added or removed
 * instance replaces are released frames_in_flight builds later (so record at most one
 * build of a map per frame slot, as roma_map_frame_desc.slot says).
 * Hits do not report an object: the maps hold one occupancy bit per cell, shared by
 * everything in it; a caller that needs the object finds it from the hit point.
 * Transforms are row-major 3x4: world = M[0..2][0..2] * local + M[.][3].
 * With the exact BOM, a build keeps what is static apart from the dynamic instances (a copy of
 * each level's static BOM and maps, roma_map_info.static_copy_bytes, made for a level that stays
 * where it was): when only dynamic instances moved, it restores a level's static part where they
 * were and voxelizes and rotates their triangles alone, in the levels they were or are in. A
 * level that moved or has new directions (jitter) is built whole, as without them. A mesh whose
 * vertices move on the GPU (a skinned character in a level) is added the same way, with dynamic
 * instances, and given its positions in the builds that change them
 * (roma_map_frame_desc.mesh_positions): only the levels its instances touch are redone. */

#define ROMA_INSTANCE_DYNAMIC 1u /**< roma_instance_desc.flags: its transform may change */

/** Adds a mesh from a scene's triangles (its positions are the local frame; materials,
 * lights and animation data are ignored). Nothing is drawn until an instance uses it; the
 * next build uploads it (through its command buffer).
 *
 * @param map            the map.
 * @param mesh           the mesh's scene; copied: it may be destroyed afterwards.
 * @param[out] out_mesh  the mesh id for roma_instance_desc.mesh (ids are not reused);
 *                       UINT32_MAX on failure.
 * @return ROMA_SUCCESS; ROMA_ERROR_INVALID_ARGUMENT for a NULL argument;
 *         ROMA_ERROR_OUT_OF_HOST_MEMORY, or a Vulkan failure code (roma_result) for its buffers.
 * @par Threads
 * Any thread, the map externally synchronised. */
ROMA_API roma_result roma_map_add_mesh(roma_map *map, const roma_scene *mesh, uint32_t *out_mesh);
/** Removes a mesh; its buffers are freed once frames_in_flight later builds were recorded.
 *
 * @param map   the map.
 * @param mesh  an id from roma_map_add_mesh.
 * @return ROMA_SUCCESS; ROMA_ERROR_INVALID_ARGUMENT for a NULL map, an unknown or removed
 *         mesh, or while instances of it remain; ROMA_ERROR_OUT_OF_HOST_MEMORY.
 * @par Threads
 * Any thread, the map externally synchronised. */
ROMA_API roma_result roma_map_remove_mesh(roma_map *map, uint32_t mesh);

/** An instance of a mesh added to a map. */
typedef struct roma_instance_desc {
    uint32_t mesh;         /**< from roma_map_add_mesh */
    float transform[12];   /**< row-major 3x4, local -> world; all zero = identity */
    uint32_t flags;        /**< ROMA_INSTANCE_DYNAMIC */
} roma_instance_desc;

/** Adds an instance of a mesh (roma_map_add_mesh) at desc->transform; it is voxelized
 * from the next build.
 *
 * @param map                the map.
 * @param desc               the instance; copied (an all-zero transform is the identity).
 * @param[out] out_instance  the instance id (ids are not reused); UINT32_MAX on failure.
 * @return ROMA_SUCCESS; ROMA_ERROR_INVALID_ARGUMENT (NULL arguments, an unknown mesh, unknown
 *         flag bits, a non-finite transform, more geometry than a map holds);
 *         ROMA_ERROR_OUT_OF_HOST_MEMORY.
 * @par Threads
 * Any thread, the map externally synchronised. */
ROMA_API roma_result roma_map_add_instance(roma_map *map, const roma_instance_desc *desc, uint32_t *out_instance);
/** Removes an instance from the next build on (its storage is freed once frames_in_flight later
 * builds have been recorded).
 *
 * @param map       the map.
 * @param instance  an id from roma_map_add_instance.
 * @return ROMA_SUCCESS; ROMA_ERROR_INVALID_ARGUMENT for a NULL map or an unknown or removed
 *         instance.
 * @par Threads
 * Any thread, the map externally synchronised. */
ROMA_API roma_result roma_map_remove_instance(roma_map *map, uint32_t instance);
/** Moves a dynamic instance; takes effect at the next build.
 *
 * @param map        the map.
 * @param instance   an instance added with ROMA_INSTANCE_DYNAMIC.
 * @param transform  row-major 3x4, local -> world, copied; all zero = identity, as in
 *                   roma_instance_desc.
 * @return ROMA_SUCCESS; ROMA_ERROR_INVALID_ARGUMENT for NULL arguments, an unknown or static
 *         instance, or a non-finite transform (the old one stays).
 * @par Threads
 * Any thread, the map externally synchronised. */
ROMA_API roma_result roma_map_set_instance_transform(roma_map *map, uint32_t instance, const float transform[12]);

/** Sizes, grid placement and the handles for tracing from the caller's shaders (roma_map_get_info). */
typedef struct roma_map_info {
    uint32_t resolution; /**< RES */
    uint32_t angular; /**< A */
    uint32_t map_count; /**< A x A (per cascade level) */
    uint32_t words_per_texel; /**< RES / 32 */
    /** The finest cascade level's grid: the world position of its BOM cell (0,0,0)'s corner
     * this frame (the other levels' are in the parameters, roma_grid_params). */
    float grid_origin[3];
    float grid_cell;           /**< world size of a BOM cell */
    float trace_cell;          /**< grid_cell * sqrt(3): the longest edge a rotated cell can have;
                                  the unit of ray-origin offsets (see roma_offset_origin) */
    uint64_t bom_bytes; /**< device memory of the BOM */
    uint64_t maps_bytes; /**< device memory of the A x A maps */
    uint64_t params_bytes; /**< device memory of the frame parameters */
    uint64_t geometry_bytes; /**< device memory of positions, indices and instances */
    /** For roma/trace.glsl in the caller's shaders (valid until the map is destroyed).
     * By address (roma_use_addresses): the A x A maps. */
    VkDeviceAddress maps_address;
    VkDeviceAddress params_address; /**< the frame parameters (roma_use_addresses) */
    /** Through descriptors (roma/trace_descriptors.glsl): the maps as a uniform texel
     * buffer (maps_view, R32_UINT) and the parameters as a uniform buffer, or the set
     * libroma wrote for them, for a pipeline layout whose set ROMA_TRACE_SET is
     * trace_set_layout (or defined identically). The set is never rewritten.
     * maps_buffer: the A x A maps. */
    VkBuffer maps_buffer;
    VkBuffer params_buffer; /**< the parameters as a uniform buffer */
    VkBufferView maps_view; /**< the maps as an R32_UINT uniform texel buffer */
    VkDescriptorSet trace_set; /**< a set holding maps_view and params_buffer */
    /** trace_set's layout, for the compute stage only: a fragment (or other) shader binds a set
     * of its own with the same two bindings (roma/trace_descriptors.glsl), written with
     * maps_view and params_buffer, or traces by address. */
    VkDescriptorSetLayout trace_set_layout;
    /** The base occupancy map of this frame (storage buffer; layout in roma/ray_start.glsl),
     * for the exact walk of a ray's skipped start that keeps rays from passing a wall they
     * start next to: its address (roma_use_ray_start), the buffer, and an R32_UINT uniform
     * texel view of it, for shaders that bind it (on CPU devices texel fetches are several
     * times faster than storage-buffer loads at varying indices). Written by each build,
     * like the maps. */
    VkDeviceAddress bom_address;
    VkBuffer bom_buffer; /**< the same BOM as a buffer */
    VkBufferView bom_view; /**< the same BOM as an R32_UINT uniform texel buffer */
    uint32_t levels; /**< cascade levels (roma_map_desc.cascades); the buffers hold level after level */
    /** Levels the last build voxelized and rotated again. A level whose placement, candidate
     * directions and geometry are those it was last built from keeps its BOM and maps: with
     * jitter_grid and jitter_directions off, static geometry (no new positions, instances
     * unchanged, the same volume) and a focus that leaves the level's snapped cube where it
     * was, a build rebuilds nothing. Dynamic instances moving over static geometry (the exact
     * BOM, no new positions) or deforming (roma_mesh_positions) redo only the levels whose cube
     * they were or are in, and those from a copy of the level's static part plus the dynamic
     * triangles alone. */
    uint32_t levels_rebuilt;
    /** Device memory of those copies of the static part (each level's BOM and maps), made by
     * the first build with a dynamic instance; 0 before. */
    uint64_t static_copy_bytes;
    /** Triangles the last build voxelized, summed over the levels it rebuilt: each level takes
     * those whose bounds touch its cube (the scene's in chunks of 256 with their boxes at the
     * last host positions, every chunk after GPU positions; an instance by its mesh's box
     * where it is), so that a level's cost follows what lies in it. Dynamic instances added to
     * a level's static part are not counted. */
    uint64_t triangles_voxelized;
} roma_map_info;

/** The map's sizes, grid and trace handles, as of the last recorded build.
 *
 * With frames in flight, the grid (grid_origin, grid_cell, trace_cell) and levels_rebuilt are
 * those of the build recorded last, not of the one a frame slot's commands will see: read the
 * info right after recording a slot's build and keep it with that slot. The handles (maps,
 * parameters, BOM) stay the same for the map's life; geometry_bytes follows the instances.
 *
 * @param map            the map.
 * @param[out] out_info  the information; zeroed on failure. Its handles belong to the map and
 *                       stay valid until roma_map_destroy.
 * @return ROMA_SUCCESS; ROMA_ERROR_INVALID_ARGUMENT for NULL arguments.
 * @par Threads
 * Any thread, the map externally synchronised. */
ROMA_API roma_result roma_map_get_info(const roma_map *map, roma_map_info *out_info);

/** Candidate direction of map k as of the last recorded build.
 *
 * @param map           the map.
 * @param k             the map index, below A x A.
 * @param[out] out_dir  the unit direction (z >= 0); zero on failure.
 * @return ROMA_SUCCESS; ROMA_ERROR_INVALID_ARGUMENT for NULL arguments or k >= A x A;
 *         ROMA_ERROR_NOT_READY before the first build was recorded.
 * @par Threads
 * Any thread, the map externally synchronised. */
ROMA_API roma_result roma_map_candidate(const roma_map *map, uint32_t k, float out_dir[3]);

/* --- Queries --- */

/** Matches struct roma_ray in roma/trace.glsl (std430, 32 bytes).
 * Defined for every bit pattern (docs/robustness.md):
 *  - dir need not be unit: any finite non-zero vector, however large or small, traces
 *    as its unit vector (d and d * 2^k give the same bits while no component crosses
 *    FLT_MIN). Components, and their ratios to the largest one, below FLT_MIN count
 *    as zero, as GPUs may flush them. A zero, NaN or infinite dir is a miss;
 *  - an origin with a NaN or infinite component, or NaN bounds, or tmin > tmax: a miss;
 *  - tmin may be negative or -INFINITY, tmax INFINITY; tmin = tmax tests the cells
 *    holding that one point;
 *  - origins outside the grid are traced: un-snapped rays are clipped to the grid;
 *    a snapped ray misses unless its line along the candidate crosses the grid.
 * Invalid rays report map 0, not folded. */
typedef struct roma_ray {
    float origin[3]; /**< world space */
    float tmin; /**< hits before tmin along the ray are ignored */
    float dir[3];          /**< need not be unit; t is a world-space distance along dir/|dir| */
    float tmax;            /**< INFINITY allowed */
} roma_ray;

/** Matches struct roma_hit in roma/trace.glsl (8 bytes). */
typedef struct roma_hit {
    float t;               /**< closest-hit distance (world units), INFINITY on a miss or for any-hit */
    uint32_t info;         /**< ROMA_HIT_FLAG, ROMA_HIT_MAP(info), ROMA_HIT_FOLDED (roma/trace_types.h) */
} roma_hit;


/** How a batch of rays is traced. */
typedef enum roma_trace_mode {
    ROMA_TRACE_SNAPPED_ANY = 0,   /**< direction snapped to its candidate, any hit (one fetch) */
    ROMA_TRACE_SNAPPED_CLOSEST,   /**< direction snapped to its candidate, closest hit (one fetch) */
    ROMA_TRACE_UNSNAPPED_ANY,     /**< exact direction walked (at most max_steps texels), any hit */
    ROMA_TRACE_UNSNAPPED_CLOSEST  /**< exact direction walked (at most max_steps texels), closest hit */
} roma_trace_mode;

/** A batch of rays traced by roma_map_record_trace on the caller's buffers. */
typedef struct roma_trace_desc {
    roma_trace_mode mode; /**< snapped or un-snapped, any or closest hit */
    uint32_t max_steps;      /**< un-snapped only; 0 = 8 */
    VkDeviceAddress rays;    /**< ray_count roma_ray (buffer with SHADER_DEVICE_ADDRESS usage) */
    VkDeviceAddress hits;    /**< ray_count roma_hit */
    uint32_t ray_count; /**< rays and hits; 0 records nothing */
} roma_trace_desc;

/** Records a trace of caller buffers after the build (same command buffer or a
 * later one): one compute dispatch. The caller synchronises its own writes to rays and
 * reads of hits; libroma adds the barrier between its build and the trace.
 *
 * @param map    the map; built (a build recorded) before.
 * @param cmd    a command buffer of the context's queue family, recording.
 * @param desc   the batch; copied. The rays and hits buffers must stay alive until cmd completes.
 * @param timer  may be NULL; otherwise the scope "trace" is added (not reset).
 * @return ROMA_SUCCESS; ROMA_ERROR_INVALID_ARGUMENT for a NULL map, cmd or desc, zero rays or
 *         hits addresses with ray_count > 0, an unknown mode, a timer of another VkDevice;
 *         ROMA_ERROR_NOT_READY when no build was recorded yet (ray_count > 0); a Vulkan failure
 *         code (roma_result) when a mode's pipeline is made, on its first use.
 * @par Threads
 * Any thread, the map externally synchronised; cmd externally synchronised. Never submits or
 * waits. */
ROMA_API roma_result roma_map_record_trace(roma_map *map, VkCommandBuffer cmd, const roma_trace_desc *desc,
                                           roma_gpu_timer *timer);

/** Convenience for CPU callers: uploads rays, traces, downloads hits (blocking). The host
 * staging buffers grow to the largest batch and are kept (a cache; dropped on a failure).
 *
 * @param map        the map; built before.
 * @param mode       how to trace.
 * @param max_steps  un-snapped modes: texels walked at most; 0 = 8.
 * @param rays       ray_count rays, copied; may be NULL when ray_count is 0.
 * @param ray_count  rays to trace; 0 does nothing and succeeds.
 * @param[out] out_hits  ray_count hits; may be NULL when ray_count is 0.
 * @param timer      may be NULL; otherwise it is reset and gets the scope "trace".
 * @return ROMA_SUCCESS; ROMA_ERROR_INVALID_ARGUMENT for a NULL map, NULL rays or out_hits with
 *         ray_count > 0, an unknown mode, a timer of another VkDevice, more rays than half the
 *         device's maxTexelBufferElements (2^26 on lavapipe and NVIDIA: split the batch);
 *         ROMA_ERROR_NOT_READY before the first build; a Vulkan failure code (roma_result).
 * @par Threads
 * Any thread, the map externally synchronised; submits to the context's queue
 * (roma_context_desc.queue_lock). */
ROMA_API roma_result roma_map_trace(roma_map *map, roma_trace_mode mode, uint32_t max_steps,
                                    const roma_ray *rays, uint32_t ray_count, roma_hit *out_hits,
                                    roma_gpu_timer *timer);

/** Downloads the BOM (RES*RES*RES/32 words), as left by the work submitted to the context's
 * queue before this call (blocking: submits a copy and waits).
 *
 * @param map              the map.
 * @param[out] out_words   word_count words, the BOM texel by texel (see the file comment).
 * @param word_count       must be exactly RES*RES*RES/32.
 * @return ROMA_SUCCESS; ROMA_ERROR_INVALID_ARGUMENT for NULL arguments or another word_count;
 *         ROMA_ERROR_NOT_READY before the first build; a Vulkan failure code (roma_result).
 * @par Threads
 * Any thread, the map externally synchronised; submits to the context's queue
 * (roma_context_desc.queue_lock). */
ROMA_API roma_result roma_map_download_bom(roma_map *map, uint32_t *out_words, uint64_t word_count);
/** Downloads all maps (map_count*RES*RES*RES/32 words, map after map), like
 * roma_map_download_bom.
 *
 * @param map              the map.
 * @param[out] out_words   word_count words.
 * @param word_count       must be exactly map_count*RES*RES*RES/32.
 * @return ROMA_SUCCESS; ROMA_ERROR_INVALID_ARGUMENT for NULL arguments or another word_count;
 *         ROMA_ERROR_NOT_READY before the first build; a Vulkan failure code (roma_result).
 * @par Threads
 * Any thread, the map externally synchronised; submits to the context's queue
 * (roma_context_desc.queue_lock). */
ROMA_API roma_result roma_map_download_maps(roma_map *map, uint32_t *out_words, uint64_t word_count);

#ifdef __cplusplus
}
#endif

#endif /* ROMA_MAP_H */
