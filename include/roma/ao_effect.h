/** @file
 * libroma: ambient occlusion from the engine's own G-buffer, recorded into the engine's
 * command buffer (the first of the public effect passes).
 *
 * Inputs are the engine's images, read with texelFetch through a sampler libroma owns
 * (nearest, so any float format works): world position (xyz; w > 0 where there is
 * geometry), shading normal, and optionally the geometric normal (the shading normal
 * stands in for it when absent). Output: an R32_SFLOAT storage image the engine owns,
 * the unoccluded fraction of `samples` cosine-weighted rays per pixel, 1 where w <= 0.
 * Rays and samples are those of the reference tracer (roma_sampling.glsl: seed, pixel
 * index y * width + x, sample frame * samples + k), so results compare sample for sample.
 *
 * Synchronisation the caller records: its G-buffer writes made visible to compute-shader
 * sampled reads, with the input images in SHADER_READ_ONLY_OPTIMAL or GENERAL, the output
 * image in GENERAL; after the pass, compute-shader storage writes to its own readers (a
 * second record that writes the same image is such a reader). The
 * map must have been built earlier in the queue (its build ends with a barrier that covers
 * every later command). Descriptor sets come from a pool per frame slot (16 records per
 * slot and frame). A record starts a new frame of its slot when its slot or its
 * settings' frame differs from the previous record's, and the slot's pool is reset then:
 * the slot rules of roma_map_frame_desc.slot apply (the GPU has finished the slot's
 * previous frame). Count frames in settings.frame; records of one frame (several maps,
 * several images) keep the same frame. A record binds its own compute pipeline, descriptor
 * sets and push constants (as every effect's does): bind yours again afterwards.
 *
 * Threads (roma/context.h): an effect is externally synchronised, used by one thread at a time;
 * records write only
 * into the command buffer they are given and never submit or wait. */
#ifndef ROMA_AO_EFFECT_H
#define ROMA_AO_EFFECT_H

#include "roma/api.h"

#include <stdint.h>
#include <vulkan/vulkan.h>

#include "roma/context.h"
#include "roma/map.h"
#include "roma/pixel_list.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Default rays per pixel and frame. Defaults are resolved in one place
 * (roma_ao_settings_resolve). */
#define ROMA_DEFAULT_AO_SAMPLES 1u
/** AO rays start this many trace cells past their (offset) origin: the cells around a
 * surface hold the surface itself (docs/accuracy.md measures the choice). */
#define ROMA_DEFAULT_AO_SKIP_CELLS 1.6f

/** How an AO ray's skipped start is checked (roma_ao_settings.start). */
typedef enum roma_ao_start {
    /** Walked exactly through the map's base occupancy map: any occupied cell there blocks the
     * ray. No ray passes a wall it starts next to; a ray that only passes by another surface
     * within a cell (fins closer than the origin's offset, the band along the edge where two
     * walls meet) is blocked too (darker there). */
    ROMA_AO_START_VOXELS = 0,
    /** The same walk, and where it meets an occupied cell, the effect's surface grid decides
     * (which triangles lie in each of its cells, two per cell, over the map's volume): the ray
     * is blocked only when the straight segment from the surface point to where its ROMA query
     * begins crosses one of them. Closer to the reference on fine geometry; the check costs
     * time, and so does the grid's build, on the first record and again when the geometry
     * moves or another map is recorded (docs/accuracy.md measures both). Where more than two
     * triangles share a cell, the others are not seen there, and a few rays pass where walls
     * meet. The walk alone decides where the grid's cells are coarser than 1.5 of the map's
     * at the point (cascade levels finer than the grid, a surface_resolution below the map's
     * RES). One record per frame slot with this start. */
    ROMA_AO_START_SURFACES = 1,
} roma_ao_start;

/** How an AO ray is traced past its skipped start (roma_ao_settings.trace). */
typedef enum roma_ao_trace {
    /** One snapped ROMA query: constant time, along its stratum's candidate direction through
     * the rotated map. The voxels widen every surface by up to a cell, so AO comes out a few
     * percent darker than the reference (docs/accuracy.md). */
    ROMA_AO_TRACE_MAPS = 0,
    /** The ray itself walked through the effect's surface grid (which triangles lie in each
     * cell, over the map's volume): in a cell whose triangles the grid holds all of (two or
     * fewer), the ray is blocked only by crossing one of them; over each run of cells that hold
     * more, ROMA's rotated map decides (an un-snapped query along the ray over the run). The
     * walk begins at the surface point, so it covers the skipped start too, whatever `start`
     * says (where such a run begins within the skip, the check of ROMA_AO_START_SURFACES
     * decides there). Within 1% of the reference's mean AO on the room, the dragon and the
     * bunny, where the snapped query is 2-7% darker (less close where the grid's cells hold more
     * triangles: 2CylinderEngine's fins), at the cost of a walk over the ray's cells (time grows
     * with the radius; unbounded rays walk to the grid's edge): docs/accuracy.md measures both.
     * Where the grid's cells are coarser than 1.5 of the map's at the point (cascade levels
     * finer than the grid, a surface_resolution below the map's RES), the start's check and the
     * snapped query decide instead. One record per frame slot with this or
     * ROMA_AO_START_SURFACES. */
    ROMA_AO_TRACE_SURFACES = 1,
} roma_ao_trace;

/** Per-record AO settings; the zero value is the default (roma_ao_settings_resolve). */
typedef struct roma_ao_settings {
    uint32_t samples;     /**< rays per pixel and frame; 0 = ROMA_DEFAULT_AO_SAMPLES */
    float radius;         /**< ray length, world units; 0 = unbounded */
    /** Origin offset along the geometric normal, trace cells, >= 0; 0 = ROMA_DEFAULT_OFFSET_CELLS.
     * Below about 1 trace cell the exact walk of the skipped start meets the cells of the
     * surface itself and blocks most rays (darker, not leaking). */
    float offset_cells;
    /** The ROMA query of a ray starts this far past the origin, trace cells; the part skipped
     * is walked exactly through the map's base occupancy map instead, so that no ray passes
     * a wall it starts next to. 0 = ROMA_DEFAULT_AO_SKIP_CELLS,
     * negative = 0. */
    float skip_cells;
    uint32_t seed; /**< sample sequences: the same seed as the reference gives the same rays */
    uint32_t frame;       /**< the engine's frame counter: new directions, and a new frame of the slot */
    /** Trace one pixel of each 2 x 2 (2) or 4 x 4 (4) block, its place in the block new each
     * frame (all places in 4 or 16 frames), and fill the other pixels from the traced ones
     * around them on a matching surface (normals, plane): about 1/4 or 1/16 of the rays for
     * blur across a block, which accumulation over frames averages out (the error it costs:
     * docs/benchmark.md). 0 or 1 = every pixel traced; other values are refused. */
    uint32_t resolution_divisor;
    roma_ao_start start; /**< how the skipped start is checked; 0 = ROMA_AO_START_VOXELS */
    roma_ao_trace trace; /**< how the ray past its start is traced; 0 = ROMA_AO_TRACE_MAPS */
} roma_ao_settings;

/** The zero value's meaning, filled in (the one place defaults are resolved).
 *
 * @param in        the settings; NULL = the zero value (all defaults).
 * @param[out] out  the resolved settings; zeroed on failure. May equal in.
 * @return ROMA_SUCCESS; ROMA_ERROR_INVALID_ARGUMENT for a NULL out, NaN or infinite values,
 *         a negative radius or offset_cells, a resolution_divisor other than 0, 1, 2 or 4, a
 *         start that is not a roma_ao_start, a trace that is not a roma_ao_trace.
 * @par Threads
 * Any thread (pure). */
ROMA_API roma_result roma_ao_settings_resolve(const roma_ao_settings *in, roma_ao_settings *out);

/** Ambient occlusion on the engine's G-buffer images (opaque). Used by one thread at a time
 * (roma/context.h). */
typedef struct roma_ao_effect roma_ao_effect;

/** Settings of roma_ao_effect_create; the zero value is the default. */
typedef struct roma_ao_effect_desc {
    uint32_t frames_in_flight; /**< [1, 8]; 0 = 2 */
    roma_pixel_dispatch pixel_dispatch; /**< 0 = ROMA_PIXEL_DISPATCH_AUTO */
    roma_logger logger;        /**< 0 = the context's */
    /** Resolution of the surface grid of ROMA_AO_START_SURFACES and ROMA_AO_TRACE_SURFACES
     * (which triangles lie in each of its cells, two, and how many, over the map's volume), 32
     * to 256; 0 = the RES of the map the first record with either traces (32 at least). Made by
     * that record: (3 * resolution^3 + ceil(resolution / 4)^3 + ceil(resolution / 16)^3) * 4 bytes
     * of device memory. */
    uint32_t surface_resolution;
} roma_ao_effect_desc;

/** Creates the AO effect: its sampler, pipeline (through the context's pipeline cache) and a
 * descriptor pool per frame slot.
 *
 * @param context   the context; must outlive the effect.
 * @param desc      settings; NULL = the zero value (2 slots, the context's logger). Copied.
 * @param[out] out  the new effect; NULL on failure.
 * @return ROMA_SUCCESS; ROMA_ERROR_INVALID_ARGUMENT for a NULL context or out,
 *         frames_in_flight above ROMA_MAX_FRAMES_IN_FLIGHT, a pixel_dispatch that is not a
 *         roma_pixel_dispatch or a surface_resolution outside [32, 256];
 *         ROMA_ERROR_OUT_OF_HOST_MEMORY, or a Vulkan failure code (roma_result).
 * @par Threads
 * Any thread. */
ROMA_API roma_result roma_ao_effect_create(roma_context *context, const roma_ao_effect_desc *desc, roma_ao_effect **out);
/** Destroys the effect.
 *
 * @param effect  the effect, or NULL (nothing is done). The caller makes sure no submitted
 *                work still uses it.
 * @par Threads
 * Any thread, the effect externally synchronised. */
ROMA_API void roma_ao_effect_destroy(roma_ao_effect *effect);

/** The engine's images the AO effect reads and writes (views it owns, valid while recorded work
 * runs). Usage: the three inputs VK_IMAGE_USAGE_SAMPLED_BIT, any float format (read with
 * texelFetch through a nearest sampler libroma owns); the output VK_IMAGE_USAGE_STORAGE_BIT.
 * Before the record: the inputs' writes made visible to compute-shader sampled reads, the
 * inputs in input_layout, the output in GENERAL. After it: a barrier from compute-shader
 * storage writes to the output's readers (another record that writes the same image is one). */
typedef struct roma_ao_images {
    uint32_t width; /**< size of every image, pixels */
    uint32_t height; /**< size of every image, pixels */
    VkImageView position;         /**< sampled: xyz world position, w > 0 = geometry */
    VkImageView normal;           /**< sampled: shading normal */
    VkImageView geometric_normal; /**< sampled, optional (VK_NULL_HANDLE: the shading normal) */
    VkImageView output;           /**< storage, R32_SFLOAT, layout GENERAL */
    VkImageLayout input_layout;   /**< of the three inputs: SHADER_READ_ONLY_OPTIMAL (0 = that) or GENERAL */
    /** Optional: the frame's covered pixels, recorded earlier in this slot for images of this
     * size, on the effect's context (roma/pixel_list.h; a list of another slot, size or
     * context is refused). The effect traces them alone, whatever its pixel_dispatch, and
     * writes no other pixel (at a resolution divisor: see roma/pixel_list.h). NULL: the
     * effect covers the images as its pixel_dispatch says. */
    const roma_pixel_list *pixels;
} roma_ao_images;

/** Records the AO pass into cmd, tracing snapped any-hit rays through the map: one compute
 * dispatch of 8 x 8 pixel groups over the images (1 where position w <= 0) or, with the
 * desc's pixel_dispatch resolved to ROMA_PIXEL_DISPATCH_LIST, a list of the covered pixels
 * (that dispatch, which writes the 1s), then an indirect dispatch over the list, with
 * barriers between them; the slot's list is allocated by its first record and when the
 * images grow. See the file comment for the synchronisation the caller records and the slot
 * rules. Any number of samples: on a device that limits the loop iterations of one shader
 * invocation (lavapipe: 65,535) the samples are traced in as many dispatches as that takes,
 * each adding to the output after a barrier (docs/robustness.md); elsewhere in one. With
 * ROMA_AO_START_SURFACES or ROMA_AO_TRACE_SURFACES the first such record (which also makes that
 * pass's pipeline) and each after the map's geometry moved, or with another map, record the
 * surface grid's build before the pass.
 *
 * @param effect    the effect.
 * @param cmd       a command buffer of the context's queue family, recording.
 * @param slot      the engine's frame slot, below the effect's frames_in_flight.
 * @param map       a map with a build recorded earlier on the queue; it and the image views
 *                  must outlive the recorded work.
 * @param images    the images; copied.
 * @param settings  NULL = the zero value (defaults, roma_ao_settings_resolve).
 * @return ROMA_SUCCESS;
 *   ROMA_ERROR_INVALID_ARGUMENT: a NULL effect, cmd, map or images, a zero width or height,
 *   a width or height above 65,536 (the list packs x and y in 16 bits each), a listed record
 *   whose list of width x height pixels exceeds the device's maxStorageBufferRange, no
 *   position, normal or output view, settings roma_ao_settings_resolve rejects, a slot not below
 *   frames_in_flight, more than 16 records in one slot and frame;
 *   ROMA_ERROR_NOT_READY: no build of the map recorded yet;
 *   with ROMA_AO_START_SURFACES or ROMA_AO_TRACE_SURFACES, a second such record in the slot's
 *   frame;
 *   ROMA_ERROR_INVALID_SCENE: with either, a map whose volume is empty;
 *   ROMA_ERROR_OUT_OF_HOST_MEMORY, or a Vulkan failure code (roma_result) when the descriptor
 *   set, the slot's list or, with either, that pass's pipeline or the surface grid cannot be
 *   made.
 * @par Threads
 * Any thread, the effect externally synchronised; the map it reads is not changed meanwhile (other
 * calls may read it); cmd externally synchronised. Never submits or waits. */
ROMA_API roma_result roma_ao_effect_record(roma_ao_effect *effect, VkCommandBuffer cmd, uint32_t slot, const roma_map *map,
                                           const roma_ao_images *images, const roma_ao_settings *settings);

#ifdef __cplusplus
}
#endif

#endif /* ROMA_AO_EFFECT_H */
