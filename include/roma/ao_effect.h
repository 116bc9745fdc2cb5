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
 * image in GENERAL; after the pass, compute-shader storage writes to its own readers. The
 * map must have been built earlier in the queue (its build ends with a barrier that covers
 * every later command). Descriptor sets come from a pool per frame slot (16 records per
 * slot and frame). A record starts a new frame of its slot when its slot or the map's
 * build differs from the previous record's, and the slot's pool is reset then: the slot
 * rules of roma_map_frame_desc.slot apply (one build of the map per frame). */
#ifndef ROMA_AO_EFFECT_H
#define ROMA_AO_EFFECT_H

#include "roma/api.h"

#include <stdint.h>
#include <vulkan/vulkan.h>

#include "roma/context.h"
#include "roma/map.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Defaults, resolved in one place (roma_ao_settings_resolve). */
#define ROMA_DEFAULT_AO_SAMPLES 1u
/** AO rays start this many trace cells past their (offset) origin: the cells around a
 * surface hold the surface itself (docs/accuracy.md measures the choice). */
#define ROMA_DEFAULT_AO_SKIP_CELLS 1.6f

/** Per-record AO settings; the zero value is the default (roma_ao_settings_resolve). */
typedef struct roma_ao_settings {
    uint32_t samples;     /**< rays per pixel and frame; 0 = ROMA_DEFAULT_AO_SAMPLES */
    float radius;         /**< ray length, world units; 0 = unbounded */
    float offset_cells;   /**< origin offset along the geometric normal, trace cells; 0 = ROMA_DEFAULT_OFFSET_CELLS */
    float skip_cells;     /**< rays start this far past the origin, trace cells; 0 = ROMA_DEFAULT_AO_SKIP_CELLS,
                             negative = 0 */
    uint32_t seed; /**< sample sequences: the same seed as the reference gives the same rays */
    uint32_t frame;       /**< new directions every frame */
} roma_ao_settings;

/** The zero value's meaning, filled in (the one place defaults are resolved).
 * ROMA_ERROR_INVALID_ARGUMENT for NaN or infinite values or a negative radius. */
ROMA_API roma_result roma_ao_settings_resolve(const roma_ao_settings *in, roma_ao_settings *out);

/** Ambient occlusion on the engine's G-buffer images (opaque). Used by one thread at a time, like
 * its context.
 */
typedef struct roma_ao_effect roma_ao_effect;

/** Settings of roma_ao_effect_create; the zero value is the default. */
typedef struct roma_ao_effect_desc {
    uint32_t frames_in_flight; /**< [1, 8]; 0 = 2 */
    roma_logger logger;        /**< 0 = the context's */
} roma_ao_effect_desc;

/** Creates the AO effect (its pipeline comes from the context's shared cache). desc may be NULL
 * (defaults). ROMA_ERROR_INVALID_ARGUMENT for a NULL context or out, or frames_in_flight above
 * ROMA_MAX_FRAMES_IN_FLIGHT; out-of-memory and ROMA_ERROR_VULKAN failures leave *out NULL.
 */
ROMA_API roma_result roma_ao_effect_create(roma_context *context, const roma_ao_effect_desc *desc, roma_ao_effect **out);
/** Accepts NULL. The caller makes sure no submitted work still uses it. */
ROMA_API void roma_ao_effect_destroy(roma_ao_effect *effect);

/** The engine's images the AO effect reads and writes (views it owns, valid while recorded work
 * runs).
 */
typedef struct roma_ao_images {
    uint32_t width; /**< size of every image, pixels */
    uint32_t height; /**< size of every image, pixels */
    VkImageView position;         /**< sampled: xyz world position, w > 0 = geometry */
    VkImageView normal;           /**< sampled: shading normal */
    VkImageView geometric_normal; /**< sampled, optional (VK_NULL_HANDLE: the shading normal) */
    VkImageView output;           /**< storage, R32_SFLOAT, layout GENERAL */
    VkImageLayout input_layout;   /**< of the three inputs: SHADER_READ_ONLY_OPTIMAL (0 = that) or GENERAL */
} roma_ao_images;

ROMA_API roma_result roma_ao_effect_record(roma_ao_effect *effect, VkCommandBuffer cmd, uint32_t slot, const roma_map *map,
                                           const roma_ao_images *images, const roma_ao_settings *settings);

#ifdef __cplusplus
}
#endif

#endif /**< ROMA_AO_EFFECT_H */
