/* libroma: direct light with ROMA shadows from point, spot and directional lights, on the
 * engine's own G-buffer images, recorded into the engine's command buffer.
 *
 * Inputs as for roma_ao_effect (world position with w > 0 where there is geometry,
 * shading normal, optional geometric normal; sampled). Output: an RGBA32F storage image
 * (layout GENERAL) the engine owns: rgb = the irradiance E (W/m^2 per colour channel) that
 * reaches the surface from the lights, each light's share counted when one un-snapped
 * shadow ray to it (at most max_steps texels) is free; a = 0. Multiply by albedo / pi for
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

/* Defaults, resolved in one place (roma_light_settings_resolve). */
#define ROMA_DEFAULT_SHADOW_STEPS 8u        /* the paper's un-snapped walk */
#define ROMA_DEFAULT_SHADOW_SKIP_CELLS 1.0f /* shadow rays start one trace cell past their origin */

typedef struct roma_light_settings {
    uint32_t max_steps;   /* texels an un-snapped shadow ray walks; 0 = ROMA_DEFAULT_SHADOW_STEPS */
    float offset_cells;   /* origin offset along the geometric normal, trace cells; 0 = ROMA_DEFAULT_OFFSET_CELLS */
    float skip_cells;     /* 0 = ROMA_DEFAULT_SHADOW_SKIP_CELLS, negative = 0 */
} roma_light_settings;

ROMA_API roma_result roma_light_settings_resolve(const roma_light_settings *in, roma_light_settings *out);

typedef struct roma_light_effect roma_light_effect;

typedef struct roma_light_effect_desc {
    uint32_t frames_in_flight; /* [1, 8]; 0 = 2 */
    roma_logger logger;        /* 0 = the context's */
} roma_light_effect_desc;

ROMA_API roma_result roma_light_effect_create(roma_context *context, const roma_light_effect_desc *desc,
                                              roma_light_effect **out);
ROMA_API void roma_light_effect_destroy(roma_light_effect *effect);

typedef struct roma_light_images {
    uint32_t width, height;
    VkImageView position, normal, geometric_normal; /* as roma_ao_images */
    VkImageView output;                             /* storage, R32G32B32A32_SFLOAT, layout GENERAL */
    VkImageLayout input_layout;
} roma_light_images;

/* The lights are copied into the slot's storage at record time (up to 65,536; lights
 * with zero intensity or colour are dropped, as the reference does). One record per frame:
 * a second record with the same slot and the same build of the map is refused
 * (ROMA_ERROR_INVALID_ARGUMENT). */
ROMA_API roma_result roma_light_effect_record(roma_light_effect *effect, VkCommandBuffer cmd, uint32_t slot,
                                              const roma_map *map, const roma_light_images *images, const roma_light *lights,
                                              uint32_t light_count, const roma_light_settings *settings);

#ifdef __cplusplus
}
#endif

#endif /* ROMA_LIGHT_EFFECT_H */
