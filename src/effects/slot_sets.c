/* Per-slot descriptor pools of the effects (slot_sets.h). */
#include "effects/slot_sets.h"

#include <string.h>

#include "util/log.h"

#define MAX_IMAGES 8u

roma_result roma_slot_sets_init(roma_slot_sets *s, roma_context *ctx, uint32_t frames_in_flight,
                                uint32_t records_per_frame, uint32_t sets_per_record, const VkDescriptorPoolSize *sizes,
                                uint32_t size_count)
{
    memset(s, 0, sizeof *s);
    s->ctx = ctx;
    s->frames_in_flight = frames_in_flight;
    s->records_per_frame = records_per_frame;
    s->last_slot = UINT32_MAX;
    VkDescriptorPoolSize scaled[4];
    if (size_count > 4)
        return ROMA_ERROR_INVALID_ARGUMENT;
    for (uint32_t i = 0; i < size_count; ++i)
        scaled[i] = (VkDescriptorPoolSize){sizes[i].type, sizes[i].descriptorCount * records_per_frame};
    VkDescriptorPoolCreateInfo pi = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO,
                                     .maxSets = sets_per_record * records_per_frame,
                                     .poolSizeCount = size_count,
                                     .pPoolSizes = scaled};
    roma_result r = ROMA_SUCCESS;
    for (uint32_t i = 0; i < frames_in_flight && r == ROMA_SUCCESS; ++i)
        r = roma_vk_check(ctx, vkCreateDescriptorPool(ctx->device, &pi, ctx->allocator, &s->pools[i]),
                          "vkCreateDescriptorPool");
    if (r != ROMA_SUCCESS)
        roma_slot_sets_free(s);
    return r;
}

void roma_slot_sets_free(roma_slot_sets *s)
{
    if (s->ctx)
        for (uint32_t i = 0; i < ROMA_MAX_FRAMES_IN_FLIGHT; ++i)
            if (s->pools[i])
                vkDestroyDescriptorPool(s->ctx->device, s->pools[i], s->ctx->allocator);
    memset(s, 0, sizeof *s);
}

int roma_slot_sets_same_frame(const roma_slot_sets *s, uint32_t slot, uint32_t frame)
{
    return slot == s->last_slot && frame == s->last_frame && s->used[slot] > 0;
}

roma_result roma_slot_sets_begin(roma_slot_sets *s, const roma_logger *log, const char *name, uint32_t slot,
                                 uint32_t frame)
{
    if (slot >= s->frames_in_flight)
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT, "%s: slot %u of %u", name, slot, s->frames_in_flight);
    if (!roma_slot_sets_same_frame(s, slot, frame)) {
        vkResetDescriptorPool(s->ctx->device, s->pools[slot], 0);
        s->used[slot] = 0;
        s->last_slot = slot;
        s->last_frame = frame;
    }
    if (s->used[slot] == s->records_per_frame)
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT,
                         "%s: more than %u records in one frame of a slot (count frames in settings.frame)", name,
                         s->records_per_frame);
    return ROMA_SUCCESS;
}

void roma_slot_sets_commit(roma_slot_sets *s, uint32_t slot)
{
    ++s->used[slot];
}

roma_result roma_slot_sets_write_images(roma_slot_sets *s, uint32_t slot, VkDescriptorSetLayout layout,
                                        VkSampler sampler, const VkImageView *views, const VkImageLayout *layouts,
                                        uint32_t sampled, uint32_t count, VkDescriptorSet *out)
{
    if (count > MAX_IMAGES)
        return ROMA_ERROR_INVALID_ARGUMENT;
    VkDescriptorSetAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO,
                                      .descriptorPool = s->pools[slot],
                                      .descriptorSetCount = 1,
                                      .pSetLayouts = &layout};
    roma_result r = roma_vk_check(s->ctx, vkAllocateDescriptorSets(s->ctx->device, &ai, out),
                                  "vkAllocateDescriptorSets");
    if (r != ROMA_SUCCESS)
        return r;
    VkDescriptorImageInfo infos[MAX_IMAGES];
    VkWriteDescriptorSet writes[MAX_IMAGES];
    for (uint32_t i = 0; i < count; ++i) {
        int input = i < sampled;
        infos[i] = (VkDescriptorImageInfo){input ? sampler : VK_NULL_HANDLE, views[i],
                                           input ? layouts[i] : VK_IMAGE_LAYOUT_GENERAL};
        writes[i] = (VkWriteDescriptorSet){.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET,
                                           .dstSet = *out,
                                           .dstBinding = i,
                                           .descriptorCount = 1,
                                           .descriptorType = input ? VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER
                                                                   : VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
                                           .pImageInfo = &infos[i]};
    }
    vkUpdateDescriptorSets(s->ctx->device, count, writes, 0, NULL);
    return ROMA_SUCCESS;
}
