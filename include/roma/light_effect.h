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
 * formulas are the reference tracer's. Synchronisation and slots: as roma_ao_effect. */
#ifndef ROMA_LIGHT_EFFECT_H
#define ROMA_LIGHT_EFFECT_H

#include "roma/api.h"

#include <stdint.h>
#include <vulkan/vulkan.h>

#include "roma/context.h"
#include "roma/map.h"
#include "roma/scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Defaults, resolved in one place (roma_light_settings_resolve). */
#define ROMA_DEFAULT_SHADOW_STEPS 8u        /**< the paper's un-snapped walk */
#define ROMA_DEFAULT_SHADOW_SKIP_CELLS 1.0f /**< shadow rays start one trace cell past their origin */
#define ROMA_DEFAULT_AREA_LIGHT_SAMPLES 4u  /**< area-light samples per pixel and frame */

/** Per-record light settings; the zero value is the default (roma_light_settings_resolve). */
typedef struct roma_light_settings {
    uint32_t max_steps;   /**< texels an un-snapped shadow ray walks; 0 = ROMA_DEFAULT_SHADOW_STEPS */
    float offset_cells;   /**< origin offset along the geometric normal, trace cells; 0 = ROMA_DEFAULT_OFFSET_CELLS */
    float skip_cells;     /**< 0 = ROMA_DEFAULT_SHADOW_SKIP_CELLS, negative = 0 */
    uint32_t area_samples; /**< area-light samples per pixel and frame; 0 = ROMA_DEFAULT_AREA_LIGHT_SAMPLES */
    uint32_t seed;         /**< area-light sample sequences, as roma_ao_settings */
    uint32_t frame;        /**< new area-light samples every frame */
} roma_light_settings;

/** The zero value's meaning filled in (the one place defaults are resolved). in may be NULL (all
 * defaults). ROMA_ERROR_INVALID_ARGUMENT for a NULL out or a negative or non-finite offset, or a
 * non-finite skip.
 */
ROMA_API roma_result roma_light_settings_resolve(const roma_light_settings *in, roma_light_settings *out);

/** Direct light with ROMA shadows on the engine's G-buffer images (opaque). Used by one thread at a
 * time, like its context.
 */
typedef struct roma_light_effect roma_light_effect;

/** Area lights: the emissive triangles of `scene` (materials with emission), sampled in
 * proportion to power x area as the reference tracer samples them; each sample is one
 * un-snapped shadow segment from the surface to a point on the emitter, and the output adds
 * their average to the punctual lights' irradiance. Replaces the previous set (NULL or a
 * scene without emitters removes it); a failure keeps it. The emitters are copied (the
 * scene may be destroyed afterwards) and stay where the scene puts them. Call it between
 * frames, when no submitted work of this effect is still running (it frees the old
 * buffers). ROMA_ERROR_INVALID_ARGUMENT for a NULL effect; out of memory errors. */
ROMA_API roma_result roma_light_effect_set_area_lights(roma_light_effect *effect, const roma_scene *scene);

/** Settings of roma_light_effect_create; the zero value is the default. */
typedef struct roma_light_effect_desc {
    uint32_t frames_in_flight; /**< [1, 8]; 0 = 2 */
    roma_logger logger;        /**< 0 = the context's */
} roma_light_effect_desc;

/** Creates the light effect. desc may be NULL (defaults). ROMA_ERROR_INVALID_ARGUMENT for a NULL
 * context or out, or frames_in_flight above ROMA_MAX_FRAMES_IN_FLIGHT; out-of-memory and
 * ROMA_ERROR_VULKAN failures leave *out NULL.
 */
ROMA_API roma_result roma_light_effect_create(roma_context *context, const roma_light_effect_desc *desc,
                                              roma_light_effect **out);
/** Accepts NULL. The caller makes sure no submitted work still uses it. */
ROMA_API void roma_light_effect_destroy(roma_light_effect *effect);

/** The engine's images the light effect reads and writes. */
typedef struct roma_light_images {
    uint32_t width; /**< size of every image, pixels */
    uint32_t height; /**< size of every image, pixels */
    VkImageView position; /**< sampled: xyz world position, w > 0 = geometry */
    VkImageView normal; /**< sampled: shading normal */
    VkImageView geometric_normal; /**< sampled, optional (VK_NULL_HANDLE: the shading normal) */
    VkImageView output;                             /**< storage, R32G32B32A32_SFLOAT, layout GENERAL */
    VkImageLayout input_layout; /**< of the three inputs: SHADER_READ_ONLY_OPTIMAL (0 = that) or GENERAL */
} roma_light_images;

/** The lights are copied into the slot's storage at record time (up to 65,536; lights
 * with zero intensity or colour are dropped, as the reference does). One record per frame:
 * a second record with the same slot and the same build of the map is refused
 * (ROMA_ERROR_INVALID_ARGUMENT). */
ROMA_API roma_result roma_light_effect_record(roma_light_effect *effect, VkCommandBuffer cmd, uint32_t slot,
                                              const roma_map *map, const roma_light_images *images, const roma_light *lights,
                                              uint32_t light_count, const roma_light_settings *settings);

#ifdef __cplusplus
}
#endif

#endif /**< ROMA_LIGHT_EFFECT_H */
