/* The covered-pixel list of the public effects (an effect's own, image_effect.c, and the
 * frame's shared one, pixel_list.c): per frame slot a device buffer of a
 * roma_pixel_list_header (the indirect dispatch's arguments) and the pixels ((y << 16) | x),
 * grown with the images, and the recording of its two passes (roma_image_list_build.glsl). */
#ifndef ROMA_EFFECTS_COVERED_LIST_H
#define ROMA_EFFECTS_COVERED_LIST_H

#include "roma/map.h" /* ROMA_MAX_FRAMES_IN_FLIGHT */
#include "roma_shared.h"
#include "vulkan/vk_internal.h"

#define ROMA_COVERED_LIST_RETIRED 16u

typedef struct roma_covered_lists {
    roma_buffer lists[ROMA_MAX_FRAMES_IN_FLIGHT];
    /* Lists a larger record of the same frame outgrew: earlier records may still read them
     * until the slot's next frame. */
    roma_buffer retired[ROMA_MAX_FRAMES_IN_FLIGHT][ROMA_COVERED_LIST_RETIRED];
    uint32_t retired_count[ROMA_MAX_FRAMES_IN_FLIGHT];
} roma_covered_lists;

/* The slot's list holds `pixels` entries; a new frame of the slot (same_frame 0) first frees
 * the lists its previous frame outgrew (the slot rules: the GPU is done with them). name:
 * the record's, for messages. */
roma_result roma_covered_lists_reserve(roma_covered_lists *l, roma_context *ctx, const roma_logger *log,
                                       const char *name, uint32_t slot, int same_frame, uint64_t pixels);
void roma_covered_lists_free(roma_covered_lists *l, roma_context *ctx);

/* Records into list, with layout's sets bound by the caller: after earlier readers and writers
 * of the list, its header reset, the list pass of `pipeline` over groups_x x groups_y
 * workgroups with push, its count turned into the indirect arguments, and a barrier that
 * makes both visible to compute shaders and indirect dispatches. */
void roma_covered_list_record(VkCommandBuffer cmd, VkBuffer list, VkPipeline pipeline, VkPipelineLayout layout,
                              roma_image_list_push push, uint32_t groups_x, uint32_t groups_y);

#endif /* ROMA_EFFECTS_COVERED_LIST_H */
