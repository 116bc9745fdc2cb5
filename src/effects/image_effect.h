/* What every public effect on the engine's G-buffer images shares: a compute pipeline
 * whose set 0 is a map's trace set and set 1 the engine's images (sampled inputs through
 * a nearest sampler, then storage outputs) followed by the map's BOM (a uniform texel buffer, for
 * the exact walk of the rays' start), sets allocated from a pool per frame slot. */
#ifndef ROMA_EFFECTS_IMAGE_EFFECT_H
#define ROMA_EFFECTS_IMAGE_EFFECT_H

#include "effects/slot_sets.h"
#include "roma/map.h"
#include "vulkan/vk_internal.h"

#define ROMA_IMAGE_EFFECT_MAX_IMAGES 8

typedef struct roma_image_effect {
    roma_context *ctx;
    roma_logger logger;
    const char *name; /* for messages: "roma_ao_effect_record" */
    uint32_t frame; /* the settings' frame of this record */
    uint32_t inputs, outputs, push_size;
    VkSampler sampler;
    VkDescriptorSetLayout trace_layout, images_layout;
    VkPipelineLayout layout;
    VkPipeline pipeline;
    roma_slot_sets sets; /* set 1 of each record */
} roma_image_effect;

/* The nearest, clamp-to-edge sampler through which the effects read the engine's images
 * (texelFetch: any float format works). */
roma_result roma_nearest_sampler_create(roma_context *ctx, VkSampler *out);

roma_result roma_image_effect_init(roma_image_effect *e, roma_context *ctx, const roma_logger *log, const char *name,
                                   const char *module, uint32_t inputs, uint32_t outputs, uint32_t push_size,
                                   uint32_t frames_in_flight);
void roma_image_effect_free(roma_image_effect *e);

/* A record starts a new frame of its slot when the slot or the settings' frame changed since
 * the previous record (the slot rules: the GPU is done with the slot's previous frame): the
 * slot's pool is reset then. Records of one frame (several maps) share its pool.
 * roma_image_effect_same_frame says whether this record continues one. */
int roma_image_effect_same_frame(const roma_image_effect *e, uint32_t slot);

/* Checks slot and map, allocates and writes set 1 (views: inputs then outputs; a NULL
 * input view is replaced by fallback[i] when given), binds, pushes and dispatches
 * ceil(width / 8) x ceil(height / 8). The map's info is returned for the push. */
roma_result roma_image_effect_begin(roma_image_effect *e, uint32_t slot, uint32_t frame, const roma_map *map,
                                    roma_map_info *info);
roma_result roma_image_effect_dispatch(roma_image_effect *e, VkCommandBuffer cmd, uint32_t slot,
                                       const roma_map_info *info, const VkImageView *views, VkImageLayout input_layout,
                                       const void *push, uint32_t width, uint32_t height);

#endif /* ROMA_EFFECTS_IMAGE_EFFECT_H */
