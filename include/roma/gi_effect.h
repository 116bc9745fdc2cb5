/** @file
 * libroma: one-bounce diffuse global illumination with ROMA rays on the engine's own
 * G-buffer images, recorded into the engine's command buffer.
 *
 * Per pixel, `samples` cosine-weighted bounce rays leave the surface (the reference
 * tracer's sample dimensions 5 and 6) as snapped closest-hit ROMA queries through the map;
 * the skipped start of each is walked exactly through the map's base occupancy map, so no
 * bounce passes a wall it starts next to. A hit is a voxel, not a surface: a surface grid
 * built from the map's triangles names the triangle there, whose albedo (from the scene
 * given to roma_gi_effect_set_scene) gives the light leaving the hit point: the direct
 * light there, from the punctual lights of the record (one un-snapped ROMA shadow ray each; directional
 * lights one snapped ray) and from the scene's emissive triangles (one sample per bounce,
 * dimensions 7-9), as the reference tracer computes it. The emission of a surface a
 * bounce hits is not added (it is direct light at the pixel).
 *
 * Inputs as for roma_light_effect (roma_light_images). Output: an RGBA32F storage image
 * the engine owns: rgb = the irradiance E (W/m^2 per channel) that reaches the surface
 * from one bounce off the scene; a = 0. Multiply by albedo / pi for the reflected
 * radiance of a diffuse surface. Pixels with w <= 0 get 0. Each record is one frame's
 * estimate; accumulate or filter over frames in the engine.
 *
 * Geometry: the bounce hits find their triangles where the map's last build put them. The
 * record rebuilds the surface grid (RES^3 cells over the map's volume, one invocation per
 * small triangle, one per 8 x 8 columns of a large one) whenever that build moved the
 * geometry or the box: new positions (host or GPU, so skinning and animation are followed),
 * instances added, removed or moved, another volume; a map whose geometry stands still costs
 * the grid once. The scene given to set_scene is the one the map was made from: its
 * triangles give the albedo (by index: the map's triangles start with the scene's; an
 * instance's triangles reflect nothing) and its emissive triangles the area lights at the
 * hit (where set_scene put them: call it again when they move). Its vertex normals shade the
 * hits while no build has given the map new positions; after that the hit triangle's face
 * normal does. Point and spot lights are lit by shadow rays; the reflective shadow maps of
 * the ROMA paper (the accuracy study's `--gi-punctual rsm`) need a rasterization of the light's view,
 * which is the engine's to make. Those shadow rays walk the map's rotated arrays with
 * bounded steps from each end (from the light's end past the empty cells in front of it,
 * up to 48 at RES 128, as far in metres at higher RES), and what lies beyond both walks
 * counts as open: a point or spot light outside a closed room can light its inside a little
 * (a GI mean of up to 2e-4 in the tests' closed rooms, where the lit default room's is 0.04;
 * docs/accuracy.md); keep such lights out of the record where that matters. Lights within
 * about two occupancy cells of a wall's far side pass it as roma_light_effect's do.
 *
 * Threads (roma/context.h): an effect is externally synchronised, used by one thread at a time;
 * records write only
 * into the command buffer they are given and never submit or wait. Frame slots: as
 * roma_ao_effect. */
#ifndef ROMA_GI_EFFECT_H
#define ROMA_GI_EFFECT_H

#include "roma/api.h"

#include <stdint.h>
#include <vulkan/vulkan.h>

#include "roma/context.h"
#include "roma/light_effect.h"
#include "roma/map.h"
#include "roma/scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Default bounce rays per pixel and frame. Defaults are resolved in one place
 * (roma_gi_settings_resolve). */
#define ROMA_DEFAULT_GI_SAMPLES 1u
/** Default resolution of the surface grid the bounce hits look their surface up in. */
#define ROMA_DEFAULT_GI_SURFACE_RESOLUTION 128u

/** Per-record GI settings; the zero value is the default (roma_gi_settings_resolve). */
typedef struct roma_gi_settings {
    uint32_t samples; /**< bounce rays per pixel and frame; 0 = ROMA_DEFAULT_GI_SAMPLES */
    /** Origin offset along the geometric normal, trace cells, >= 0; 0 = ROMA_DEFAULT_OFFSET_CELLS
     * (for the bounce rays and the shadow rays at their hits). */
    float offset_cells;
    /** The ROMA query of a bounce ray starts this far past its origin, trace cells, the
     * part skipped walked exactly through the base occupancy map. 0 =
     * ROMA_DEFAULT_AO_SKIP_CELLS, negative = 0. */
    float skip_cells;
    /** The same for the shadow rays at a bounce hit (four skips walked exactly). 0 =
     * ROMA_DEFAULT_SHADOW_SKIP_CELLS, negative = 0. */
    float shadow_skip_cells;
    uint32_t max_steps; /**< texels a shadow ray at a hit walks; 0 = ROMA_DEFAULT_SHADOW_STEPS */
    uint32_t seed;      /**< sample sequences, as roma_ao_settings */
    uint32_t frame;     /**< the engine's frame counter: new directions, and a new frame of the slot */
    /** Trace one pixel of each 2 x 2 (2) or 4 x 4 (4) block, its place in the block new each
     * frame (all places in 4 or 16 frames), and fill the other pixels from the traced ones
     * around them on a matching surface (normals, plane): about 1/4 or 1/16 of the rays for
     * blur across a block, which accumulation over frames averages out (the error it costs:
     * docs/benchmark.md). 0 or 1 = every pixel traced; other values are refused. */
    uint32_t resolution_divisor;
} roma_gi_settings;

/** The zero value's meaning filled in (the one place defaults are resolved).
 *
 * @param in        the settings; NULL = the zero value (all defaults).
 * @param[out] out  the resolved settings; zeroed on failure. May equal in.
 * @return ROMA_SUCCESS; ROMA_ERROR_INVALID_ARGUMENT for a NULL out, a negative or
 *         non-finite offset, or a non-finite skip.
 * @par Threads
 * Any thread (pure). */
ROMA_API roma_result roma_gi_settings_resolve(const roma_gi_settings *in, roma_gi_settings *out);

/** One-bounce GI on the engine's G-buffer images (opaque). Used by one thread at a time
 * (roma/context.h). */
typedef struct roma_gi_effect roma_gi_effect;

/** Settings of roma_gi_effect_create; the zero value is the default. */
typedef struct roma_gi_effect_desc {
    uint32_t frames_in_flight;   /**< [1, 8]; 0 = 2 */
    roma_pixel_dispatch pixel_dispatch; /**< 0 = ROMA_PIXEL_DISPATCH_AUTO */
    /** Surface grid resolution, 32 to 256; 0 = ROMA_DEFAULT_GI_SURFACE_RESOLUTION. At least
     * the map's RES: a hit looks one grid cell around itself. The grid takes
     * 3 * resolution^3 * 4 bytes of device memory (its third layer: the area lights, which a
     * hit finds where they share cells with another surface). */
    uint32_t surface_resolution;
    roma_logger logger;          /**< 0 = the context's */
} roma_gi_effect_desc;

/** Creates the GI effect. Until roma_gi_effect_set_scene gives it surfaces, its output is 0.
 *
 * @param context   the context; must outlive the effect.
 * @param desc      settings; NULL = the zero value. Copied.
 * @param[out] out  the new effect; NULL on failure.
 * @return ROMA_SUCCESS; ROMA_ERROR_INVALID_ARGUMENT for a NULL context or out, frames_in_flight
 *         above ROMA_MAX_FRAMES_IN_FLIGHT, a surface resolution outside [32, 256] or a
 *         pixel_dispatch that is not a roma_pixel_dispatch;
 *         ROMA_ERROR_OUT_OF_HOST_MEMORY, or a Vulkan failure code (roma_result).
 * @par Threads
 * Any thread. */
ROMA_API roma_result roma_gi_effect_create(roma_context *context, const roma_gi_effect_desc *desc,
                                           roma_gi_effect **out);

/** Destroys the effect and its buffers.
 *
 * @param effect  the effect, or NULL (nothing is done). The caller makes sure no submitted
 *                work still uses it.
 * @par Threads
 * Any thread, the effect externally synchronised. */
ROMA_API void roma_gi_effect_destroy(roma_gi_effect *effect);

/** The materials of the surfaces bounce rays light: the scene the map was made from (each
 * triangle's material albedo, the vertex normals) and its emissive triangles as area
 * lights, copied to the GPU. Where the triangles are comes from the map at each record.
 * Replaces the previous scene (NULL removes it); a failure keeps it. Call it between
 * frames, when no submitted work of this effect is still running. The data goes to
 * device-local memory: written directly where the host can map it (CPU and integrated
 * devices, GPUs with a resizable BAR), else the materials by a copy submitted to the
 * context's queue and waited for, as roma_map_create's upload, and the area lights by a copy
 * the next record records ahead of the pass.
 *
 * @param effect  the effect.
 * @param scene   the scene, or NULL; nothing of it is kept.
 * @return ROMA_SUCCESS; ROMA_ERROR_INVALID_ARGUMENT for a NULL effect; ROMA_ERROR_INVALID_SCENE
 *         for a scene without triangles; ROMA_ERROR_OUT_OF_HOST_MEMORY, or a Vulkan failure
 *         code (roma_result).
 * @par Threads
 * Any thread, the effect externally synchronised; submits to the context's queue
 * (roma_context_desc.queue_lock); the scene may be
 * read by other threads meanwhile. */
ROMA_API roma_result roma_gi_effect_set_scene(roma_gi_effect *effect, const roma_scene *scene);

/** Records the GI pass into cmd: when the map's geometry changed since the grid was built
 * (see above), the surface grid's build (a barrier after earlier compute reads, a fill,
 * one compute dispatch, a barrier), then the pass over the images or the list of their
 * covered pixels, as roma_ao_effect_record (uncovered pixels get 0; samples, and the lights
 * lit at each bounce hit, split across dispatches where a device limits the loop iterations
 * of one shader invocation).
 * Submit the command buffers of an effect in the order they were recorded. The lights
 * are copied into the slot's storage at record time (up to 65,536; as
 * roma_light_effect_record). One record per frame slot and settings frame. Synchronisation
 * as roma_ao_effect: the map's build and the images' writes must be made visible to
 * compute shader reads first; the output is written by the compute stage.
 *
 * @param effect       the effect.
 * @param cmd          a command buffer of the context's queue family, recording.
 * @param slot         the engine's frame slot, below the effect's frames_in_flight.
 * @param map          a map with a build recorded earlier on the queue; it and the image views
 *                     must outlive the recorded work.
 * @param images       the images (as roma_light_effect's); copied.
 * @param lights       light_count punctual lights, copied; may be NULL when light_count is 0.
 * @param light_count  lights, at most 65,536.
 * @param settings     NULL = the zero value (defaults, roma_gi_settings_resolve).
 * @return ROMA_SUCCESS;
 *   ROMA_ERROR_INVALID_ARGUMENT: a NULL effect, cmd, map or images, NULL lights with
 *   light_count > 0, a zero width or height, images too large (as roma_ao_effect_record),
 *   no position, normal or output view, more than 65,536 lights, a light of unknown type or
 *   with a NaN or infinite value, settings roma_gi_settings_resolve rejects, a slot not below frames_in_flight, a second record
 *   in one slot and frame;
 *   ROMA_ERROR_NOT_READY: no build of the map recorded yet;
 *   a Vulkan failure code (roma_result) for the slot's buffers or descriptor sets, or the
 *   surface grid's first allocation (RES^3 x 4 bytes, and RES^2 x 32 bytes for its build's queue of
 *   tiles).
 * @par Threads
 * Any thread, the effect externally synchronised; the map it reads is not changed meanwhile (other
 * calls may read it); cmd externally synchronised. Never submits or waits. */
ROMA_API roma_result roma_gi_effect_record(roma_gi_effect *effect, VkCommandBuffer cmd, uint32_t slot,
                                           const roma_map *map, const roma_light_images *images,
                                           const roma_light *lights, uint32_t light_count,
                                           const roma_gi_settings *settings);

#ifdef __cplusplus
}
#endif

#endif /* ROMA_GI_EFFECT_H */
