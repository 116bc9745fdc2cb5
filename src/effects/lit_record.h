/* What the two effects that read the record's lights (roma_light_effect, roma_gi_effect)
 * share at the start of a record: the checks of their arguments, the frame slot (one
 * record per slot and frame: the lights live in one buffer per slot) and the upload of the
 * lights into that buffer. */
#ifndef ROMA_EFFECTS_LIT_RECORD_H
#define ROMA_EFFECTS_LIT_RECORD_H

#include "effects/image_effect.h"
#include "roma/light_effect.h"
#include "vulkan/upload.h"

/* Lights one record takes at most. */
#define ROMA_LIT_MAX_LIGHTS 65536u

/* The arguments' checks (name: "roma_light_effect_record" and the like, for messages). The
 * effect e may be NULL (then the error is logged without its logger). */
roma_result roma_lit_record_check(const roma_image_effect *e, const char *name, VkCommandBuffer cmd,
                                  const roma_map *map, const roma_light_images *im, const roma_light *lights,
                                  uint32_t light_count);

/* roma_image_effect_begin, refusing a second record in the slot's frame. */
roma_result roma_lit_record_begin(roma_image_effect *e, const char *name, uint32_t slot, uint32_t frame,
                                  const roma_map *map, const roma_light_images *im, uint32_t resolution_divisor,
                                  roma_map_info *info);

/* Makes buf, a slot's storage buffer the shaders reach by address and the host writes
 * (vulkan/upload.h: record its copy before the dispatch), hold at least `bytes`: grown (made
 * anew) when smaller; the slot's previous use has completed (the slot rules). */
roma_result roma_lit_slot_buffer(roma_context *ctx, roma_upload *buf, VkDeviceSize bytes);

/* Packs the lights (dropped ones, without intensity or colour, shift the rest) into buf,
 * grown when too small (the slot's previous use has completed: the slot rules); the caller
 * records buf's upload.
 * exact_count: how many of the first lights are exact (roma_light_settings); out_exact: how
 * many of the packed ones they became (all when exact_count exceeds the list). */
roma_result roma_lit_record_pack(roma_context *ctx, roma_upload *buf, const roma_light *lights, uint32_t light_count,
                                 uint32_t exact_count, uint32_t *out_packed, uint32_t *out_exact);

#endif /* ROMA_EFFECTS_LIT_RECORD_H */
