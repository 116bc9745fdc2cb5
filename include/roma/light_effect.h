/** @file
 * libroma: direct light with ROMA shadows from point, spot and directional lights and from
 * area lights (emissive triangles, roma_light_effect_set_area_lights), on the engine's own
 * G-buffer images, recorded into the engine's command buffer.
 *
 * Inputs as for roma_ao_effect (world position with w > 0 where there is geometry,
 * shading normal, optional geometric normal; sampled). Output: an RGBA32F storage image
 * (layout GENERAL) the engine owns: rgb = the irradiance E (W/m^2 per colour channel) that
 * reaches the surface from the lights, each light's share counted when one un-snapped
 * shadow ray to it (at most max_steps texels) is free, plus the area lights' estimate over
 * area_samples samples; a = 0. Multiply by albedo / pi for
 * the reflected radiance of a diffuse surface. Pixels with w <= 0 get 0. The lights'
 * units and windows are glTF KHR_lights_punctual's, as in roma_scene (intensity in cd for
 * point and spot lights, lux for directional ones; range windows; spot cones); their
 * formulas are the reference tracer's. Synchronisation and slots: as roma_ao_effect.
 *
 * Walls: a shadow ray's end at its light is walked through the map's occupancy, so a light
 * outside a closed room stays out. A light closer than about two occupancy cells to the far
 * side of a wall (one cell for an area light parallel to an axis-aligned wall) lies in the
 * same cells as the wall and cannot be told from a light mounted on it: it lights through
 * that wall (docs/accuracy.md, "Lights just outside a wall"); keep such lights two cells out.
 *
 * Many lights: with roma_light_settings.lights_per_frame each pixel traces a fixed number of
 * the lights per frame (a random run of them, scaled to an unbiased estimate), so thousands of
 * lights cost per frame what a few do and the engine's accumulation over frames converges to
 * the all-lights image; key lights can stay exact (exact_light_count).
 *
 * Threads (roma/context.h): an effect is externally synchronised, used by one thread at a time;
 * records write only
 * into the command buffer they are given and never submit or wait. */
#ifndef ROMA_LIGHT_EFFECT_H
#define ROMA_LIGHT_EFFECT_H

#include "roma/api.h"

#include <stdint.h>
#include <vulkan/vulkan.h>

#include "roma/context.h"
#include "roma/map.h"
#include "roma/pixel_list.h"
#include "roma/scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Default texels an un-snapped shadow ray walks: the paper's walk. Defaults are resolved in
 * one place (roma_light_settings_resolve). */
#define ROMA_DEFAULT_SHADOW_STEPS 8u
#define ROMA_DEFAULT_SHADOW_SKIP_CELLS 1.0f /**< shadow rays start one trace cell past their origin */
#define ROMA_DEFAULT_AREA_LIGHT_SAMPLES 4u  /**< area-light samples per pixel and frame */
/** Default resolution of the surface grid that tells on which side of a wall a light in the
 * wall's voxels lies. */
#define ROMA_DEFAULT_LIGHT_SURFACE_RESOLUTION 128u

/** What roma_light_effect writes. */
typedef enum roma_light_output {
    /** Shadowed irradiance from every light (RGB). */
    ROMA_LIGHT_OUTPUT_IRRADIANCE = 0,
    /** In x, how many of the punctual lights face the shading normal and reach the point
     * unshadowed (the many-lights visibility of the constant-time intersection paper, and the
     * reference's roma_ref_count_visible_lights); with lights_per_frame, the unbiased estimate
     * of that count. A light counts by its position (a directional one by its direction)
     * alone: spot cones, range windows and intensity are not looked at. Area lights are not
     * counted; y and z are 0. */
    ROMA_LIGHT_OUTPUT_VISIBLE_COUNT = 1,
} roma_light_output;

/** Per-record light settings; the zero value is the default (roma_light_settings_resolve). */
typedef struct roma_light_settings {
    uint32_t max_steps;   /**< texels an un-snapped shadow ray walks; 0 = ROMA_DEFAULT_SHADOW_STEPS */
    /** Origin offset along the geometric normal, trace cells, >= 0; 0 = ROMA_DEFAULT_OFFSET_CELLS.
     * Below about 1 trace cell the exact walk of the skipped start meets the cells of the
     * surface itself and blocks most rays (darker, not leaking). */
    float offset_cells;
    /** The ROMA query of a shadow ray starts this far past the origin, trace cells; four times
     * that is walked exactly through the map's base occupancy map first, so that no ray passes
     * a wall it starts next to. 0 = ROMA_DEFAULT_SHADOW_SKIP_CELLS, negative = 0. */
    float skip_cells;
    /** Area-light samples per pixel and frame; 0 = ROMA_DEFAULT_AREA_LIGHT_SAMPLES. */
    uint32_t area_samples;
    uint32_t seed;         /**< area-light sample sequences and the many lights' choice, as roma_ao_settings */
    /** The engine's frame counter: new area-light samples, a new choice of the many lights
     * (lights_per_frame: with a constant frame each pixel keeps the same lights and the mean
     * over frames never reaches the all-lights image), and a new frame of the slot. */
    uint32_t frame;
    /** Many lights: 0 = every punctual light is traced every frame. Otherwise each pixel traces
     * this many of the lights after the first exact_light_count (a run of consecutive lights
     * from a random start, new each frame), and scales their sum by (lights after the first
     * exact_light_count) / lights_per_frame: every light is traced with the same probability,
     * so the mean over frames is the all-lights image, at a cost per pixel that does not grow
     * with the number of lights. Values at or above the number of those lights trace them all. */
    uint32_t lights_per_frame;
    /** With lights_per_frame: the first exact_light_count lights (an engine's key lights) are
     * traced every frame and not sampled. Ignored when lights_per_frame is 0. */
    uint32_t exact_light_count;
    /** Trace one pixel of each 2 x 2 (2) or 4 x 4 (4) block, its place in the block new each
     * frame (all places in 4 or 16 frames), and fill the other pixels from the traced ones
     * around them on a matching surface (normals, plane): about 1/4 or 1/16 of the rays for
     * blur across a block, which accumulation over frames averages out (the error it costs:
     * docs/benchmark.md). 0 or 1 = every pixel traced; other values are refused. */
    uint32_t resolution_divisor;
    roma_light_output output; /**< 0 = ROMA_LIGHT_OUTPUT_IRRADIANCE */
} roma_light_settings;

/** The zero value's meaning filled in (the one place defaults are resolved).
 *
 * @param in        the settings; NULL = the zero value (all defaults).
 * @param[out] out  the resolved settings; zeroed on failure. May equal in.
 * @return ROMA_SUCCESS; ROMA_ERROR_INVALID_ARGUMENT for a NULL out or a negative or non-finite
 *         offset, or a non-finite skip.
 * @par Threads
 * Any thread (pure). */
ROMA_API roma_result roma_light_settings_resolve(const roma_light_settings *in, roma_light_settings *out);

/** Direct light with ROMA shadows on the engine's G-buffer images (opaque). Used by one thread at a
 * time (roma/context.h). */
typedef struct roma_light_effect roma_light_effect;

/** Area lights: the emissive triangles of `scene` (materials with emission), sampled in
 * proportion to power x area as the reference tracer samples them; each sample is one
 * un-snapped shadow segment from the surface to a point on the emitter, and the output adds
 * their average to the punctual lights' irradiance. Replaces the previous set (NULL or a
 * scene without emitters removes it); a failure keeps it. The emitters are copied (the
 * scene may be destroyed afterwards) and stay where the scene puts them. Call it between
 * frames, when no submitted work of this effect is still running (it frees the old
 * buffers).
 *
 * @param effect  the effect.
 * @param scene   the scene whose emissive triangles become the area lights; NULL removes them.
 * @return ROMA_SUCCESS; ROMA_ERROR_INVALID_ARGUMENT for a NULL effect;
 *         ROMA_ERROR_OUT_OF_HOST_MEMORY, or a Vulkan failure code (roma_result) for the buffers.
 * @par Threads
 * Any thread, the effect externally synchronised; the scene may be read by other threads
 * meanwhile. */
ROMA_API roma_result roma_light_effect_set_area_lights(roma_light_effect *effect, const roma_scene *scene);

/** Settings of roma_light_effect_create; the zero value is the default. */
typedef struct roma_light_effect_desc {
    uint32_t frames_in_flight; /**< [1, 8]; 0 = 2 */
    roma_pixel_dispatch pixel_dispatch; /**< 0 = ROMA_PIXEL_DISPATCH_AUTO */
    /** Resolution of the surface grid, 32 to 256; 0 = ROMA_DEFAULT_LIGHT_SURFACE_RESOLUTION.
     * A point, spot or area light within a voxel of a wall lies in the wall's voxels, on
     * either side of it as far as the map shows; the grid (2 RES^3 uints, rebuilt from the
     * map's triangles whenever they move) tells which. At least the map's RES. */
    uint32_t surface_resolution;
    roma_logger logger;        /**< 0 = the context's */
} roma_light_effect_desc;

/** Creates the light effect (no area lights until roma_light_effect_set_area_lights).
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
ROMA_API roma_result roma_light_effect_create(roma_context *context, const roma_light_effect_desc *desc,
                                              roma_light_effect **out);
/** Destroys the effect and its light buffers.
 *
 * @param effect  the effect, or NULL (nothing is done). The caller makes sure no submitted
 *                work still uses it.
 * @par Threads
 * Any thread, the effect externally synchronised. */
ROMA_API void roma_light_effect_destroy(roma_light_effect *effect);

/** The engine's images the light effect reads and writes: usage and barriers as
 * roma_ao_images says (inputs sampled, the output a storage image in GENERAL). */
typedef struct roma_light_images {
    uint32_t width; /**< size of every image, pixels */
    uint32_t height; /**< size of every image, pixels */
    VkImageView position; /**< sampled: xyz world position, w > 0 = geometry */
    VkImageView normal; /**< sampled: shading normal */
    VkImageView geometric_normal; /**< sampled, optional (VK_NULL_HANDLE: the shading normal) */
    VkImageView output; /**< storage, R32G32B32A32_SFLOAT, layout GENERAL */
    VkImageLayout input_layout; /**< of the three inputs: SHADER_READ_ONLY_OPTIMAL (0 = that) or GENERAL */
    /** Optional: the frame's covered pixels, as roma_ao_images.pixels (the effect writes no
     * other pixel). */
    const roma_pixel_list *pixels;
} roma_light_images;

/** Records the direct-light pass into cmd: over the images or the list of their covered
 * pixels, as roma_ao_effect_record (uncovered pixels get 0).
 * The lights are copied into the slot's storage at record time (up to 65,536; lights
 * with zero intensity or colour are dropped, as the reference does). One record per frame:
 * a second record with the same slot and the same settings frame is refused
 * (ROMA_ERROR_INVALID_ARGUMENT). Frames and slots: as roma_ao_effect (count frames in
 * settings.frame). Any max_steps (a walk leaves the map within 2 RES texels) and area-light
 * samples; where a device limits the loop iterations of one shader invocation the lights and
 * samples are split across dispatches, as roma_ao_effect_record's samples.
 *
 * @param effect       the effect.
 * @param cmd          a command buffer of the context's queue family, recording.
 * @param slot         the engine's frame slot, below the effect's frames_in_flight.
 * @param map          a map with a build recorded earlier on the queue; it and the image views
 *                     must outlive the recorded work.
 * @param images       the images; copied.
 * @param lights       light_count punctual lights, copied; may be NULL when light_count is 0
 *                     (then only the area lights shine).
 * @param light_count  lights, at most 65,536.
 * @param settings     NULL = the zero value (defaults, roma_light_settings_resolve).
 * @return ROMA_SUCCESS;
 *   ROMA_ERROR_INVALID_ARGUMENT: a NULL effect, cmd, map or images, NULL lights with
 *   light_count > 0, a zero width or height, images too large (as roma_ao_effect_record),
 *   no position, normal or output view, more than 65,536 lights, a light of unknown type or
 *   with a NaN or infinite value, settings roma_light_settings_resolve rejects, a slot not below frames_in_flight, a second record
 *   in one slot and frame;
 *   ROMA_ERROR_NOT_READY: no build of the map recorded yet;
 *   a Vulkan failure code (roma_result) for the slot's light buffer, pixel list or descriptor set.
 * @par Threads
 * Any thread, the effect externally synchronised; the map it reads is not changed meanwhile (other
 * calls may read it); cmd externally synchronised. Never submits or waits. */
ROMA_API roma_result roma_light_effect_record(roma_light_effect *effect, VkCommandBuffer cmd, uint32_t slot,
                                              const roma_map *map, const roma_light_images *images, const roma_light *lights,
                                              uint32_t light_count, const roma_light_settings *settings);

#ifdef __cplusplus
}
#endif

#endif /* ROMA_LIGHT_EFFECT_H */
