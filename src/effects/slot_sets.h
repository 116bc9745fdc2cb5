/* Descriptor sets of the effects recorded every frame, from one pool per frame slot. A
 * record that starts a new frame of its slot (another slot or settings.frame than the
 * record before, or the slot's first) resets that slot's pool: by the slot rules the GPU is
 * done with the slot's previous frame. The records of one frame share its pool, up to
 * records_per_frame of them. */
#ifndef ROMA_EFFECTS_SLOT_SETS_H
#define ROMA_EFFECTS_SLOT_SETS_H

#include "roma/map.h" /* ROMA_MAX_FRAMES_IN_FLIGHT */
#include "vulkan/vk_internal.h"

typedef struct roma_slot_sets {
    roma_context *ctx;
    VkDescriptorPool pools[ROMA_MAX_FRAMES_IN_FLIGHT];
    uint32_t frames_in_flight, records_per_frame;
    uint32_t last_slot, last_frame, used[ROMA_MAX_FRAMES_IN_FLIGHT];
} roma_slot_sets;

/* Pools of sets_per_record * records_per_frame sets holding sizes[i].descriptorCount
 * descriptors of each type per record. On failure *s is zeroed. */
roma_result roma_slot_sets_init(roma_slot_sets *s, roma_context *ctx, uint32_t frames_in_flight,
                                uint32_t records_per_frame, uint32_t sets_per_record, const VkDescriptorPoolSize *sizes,
                                uint32_t size_count);
/* Accepts a zeroed one. */
void roma_slot_sets_free(roma_slot_sets *s);

/* Whether a record in slot for frame would continue the frame of the record before. */
int roma_slot_sets_same_frame(const roma_slot_sets *s, uint32_t slot, uint32_t frame);

/* Starts a record (slot < frames_in_flight): resets the slot's pool on a new frame; refuses
 * a record past records_per_frame (logged, naming `name`). */
roma_result roma_slot_sets_begin(roma_slot_sets *s, const roma_logger *log, const char *name, uint32_t slot,
                                 uint32_t frame);
/* Counts the record begun in slot once its sets are written (a failed one does not count). */
void roma_slot_sets_commit(roma_slot_sets *s, uint32_t slot);

/* A set of `layout` from the slot's pool with views[i] at binding i: the first `sampled`
 * through `sampler` in layouts[i], the rest storage images in GENERAL. */
roma_result roma_slot_sets_write_images(roma_slot_sets *s, uint32_t slot, VkDescriptorSetLayout layout,
                                        VkSampler sampler, const VkImageView *views, const VkImageLayout *layouts,
                                        uint32_t sampled, uint32_t count, VkDescriptorSet *out);

#endif /* ROMA_EFFECTS_SLOT_SETS_H */
