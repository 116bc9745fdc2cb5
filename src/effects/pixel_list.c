/* roma_pixel_list: the covered pixels of a frame's G-buffer, listed once for every effect of
 * the frame (shaders/effects/covered_pixels.comp, the effects' own list pass without its
 * output). */
#include "roma/pixel_list.h"

#include <stdlib.h>
#include <string.h>

#include "effects/covered_list.h"
#include "effects/image_effect.h"
#include "effects/pixel_list_internal.h"
#include "effects/slot_sets.h"
#include "roma/map.h"
#include "roma_shared.h"
#include "util/log.h"

#define RECORDS_PER_FRAME 4u

struct roma_pixel_list {
    roma_context *ctx;
    roma_logger logger;
    VkSampler sampler;
    VkDescriptorSetLayout set_layout;
    VkPipelineLayout layout;
    VkPipeline pipeline;
    roma_slot_sets sets;
    roma_covered_lists lists;
    uint32_t listed[ROMA_MAX_FRAMES_IN_FLIGHT][2]; /* the images' size of the slot's last record */
};

roma_result roma_pixel_list_create(roma_context *ctx, const roma_pixel_list_desc *desc_in, roma_pixel_list **out)
{
    roma_pixel_list_desc desc = desc_in ? *desc_in : (roma_pixel_list_desc){0};
    const roma_logger *log = desc.logger.fn ? &desc.logger : (ctx ? &ctx->logger : NULL);
    if (!out)
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT, "roma_pixel_list_create: out is NULL");
    *out = NULL;
    if (!ctx)
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT, "roma_pixel_list_create: context is NULL");
    if (desc.frames_in_flight == 0)
        desc.frames_in_flight = 2;
    if (desc.frames_in_flight > ROMA_MAX_FRAMES_IN_FLIGHT)
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT, "roma_pixel_list_create: frames_in_flight %u outside [1, %u]",
                         desc.frames_in_flight, ROMA_MAX_FRAMES_IN_FLIGHT);
    roma_pixel_list *l = calloc(1, sizeof *l);
    if (!l)
        return roma_fail(log, ROMA_ERROR_OUT_OF_HOST_MEMORY, "roma_pixel_list_create: out of host memory");
    l->ctx = ctx;
    l->logger = *log;
    const VkDescriptorType types[2] = {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER};
    roma_result r = roma_nearest_sampler_create(ctx, &l->sampler);
    if (r == ROMA_SUCCESS)
        r = roma_descriptor_layout_create(ctx, types, 2, &l->set_layout);
    if (r == ROMA_SUCCESS) {
        VkPushConstantRange push = {VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(roma_image_list_push)};
        VkPipelineLayoutCreateInfo li = {.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO,
                                         .setLayoutCount = 1,
                                         .pSetLayouts = &l->set_layout,
                                         .pushConstantRangeCount = 1,
                                         .pPushConstantRanges = &push};
        r = roma_vk_check(ctx, vkCreatePipelineLayout(ctx->device, &li, ctx->allocator, &l->layout),
                          "vkCreatePipelineLayout");
    }
    if (r == ROMA_SUCCESS)
        r = roma_compute_pipeline_make(ctx, "covered_pixels.comp", l->layout, NULL, 0, &l->pipeline);
    const VkDescriptorPoolSize sizes[2] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1},
                                           {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1}};
    if (r == ROMA_SUCCESS)
        r = roma_slot_sets_init(&l->sets, ctx, desc.frames_in_flight, RECORDS_PER_FRAME, 1, sizes, 2);
    if (r != ROMA_SUCCESS) {
        roma_pixel_list_destroy(l);
        return roma_fail(log, r, "roma_pixel_list_create: its pipeline or descriptor pools");
    }
    *out = l;
    return ROMA_SUCCESS;
}

void roma_pixel_list_destroy(roma_pixel_list *l)
{
    if (!l)
        return;
    VkDevice dev = l->ctx->device;
    const VkAllocationCallbacks *a = l->ctx->allocator;
    roma_slot_sets_free(&l->sets);
    roma_covered_lists_free(&l->lists, l->ctx);
    if (l->pipeline)
        vkDestroyPipeline(dev, l->pipeline, a);
    if (l->layout)
        vkDestroyPipelineLayout(dev, l->layout, a);
    if (l->set_layout)
        vkDestroyDescriptorSetLayout(dev, l->set_layout, a);
    if (l->sampler)
        vkDestroySampler(dev, l->sampler, a);
    free(l);
}

roma_result roma_pixel_list_record(roma_pixel_list *l, VkCommandBuffer cmd, uint32_t slot,
                                   const roma_pixel_list_images *im)
{
    if (!l || !cmd || !im)
        return roma_fail(l ? &l->logger : NULL, ROMA_ERROR_INVALID_ARGUMENT, "roma_pixel_list_record: %s is NULL",
                         !l ? "list" : !cmd ? "cmd" : "images");
    if (!im->width || !im->height || !im->position)
        return roma_fail(&l->logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_pixel_list_record: width, height and position are required");
    const uint32_t most = 65536u; /* the list holds (y << 16) | x (roma_image_list.glsl) */
    const uint64_t bytes = sizeof(roma_pixel_list_header) + 4ull * im->width * im->height;
    if (im->width > most || im->height > most || bytes > l->ctx->properties.limits.maxStorageBufferRange)
        return roma_fail(&l->logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_pixel_list_record: images of %ux%u: at most %u pixels along each axis and a list of at "
                         "most maxStorageBufferRange (%u bytes; this one: %llu)",
                         im->width, im->height, most, l->ctx->properties.limits.maxStorageBufferRange,
                         (unsigned long long)bytes);
    if (slot >= l->sets.frames_in_flight)
        return roma_fail(&l->logger, ROMA_ERROR_INVALID_ARGUMENT, "roma_pixel_list_record: slot %u of %u", slot,
                         l->sets.frames_in_flight);
    int same_frame = roma_slot_sets_same_frame(&l->sets, slot, im->frame);
    /* Refuses a record past RECORDS_PER_FRAME (the descriptor pool's size). */
    roma_result r = roma_slot_sets_begin(&l->sets, &l->logger, "roma_pixel_list_record", slot, im->frame);
    if (r == ROMA_SUCCESS)
        r = roma_covered_lists_reserve(&l->lists, l->ctx, &l->logger, "roma_pixel_list_record", slot, same_frame,
                                       (uint64_t)im->width * im->height);
    VkDescriptorSet set = VK_NULL_HANDLE;
    const VkImageLayout layout = im->input_layout ? im->input_layout : VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    if (r == ROMA_SUCCESS)
        r = roma_slot_sets_write_images(&l->sets, slot, l->set_layout, l->sampler, &im->position, &layout, 1, 1,
                                        &set);
    if (r != ROMA_SUCCESS)
        return r;
    roma_slot_sets_commit(&l->sets, slot);
    const roma_buffer *list = &l->lists.lists[slot];
    VkDescriptorBufferInfo list_info = {list->buffer, 0, VK_WHOLE_SIZE};
    VkWriteDescriptorSet write = {.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET,
                                  .dstSet = set,
                                  .dstBinding = 1,
                                  .descriptorCount = 1,
                                  .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                                  .pBufferInfo = &list_info};
    vkUpdateDescriptorSets(l->ctx->device, 1, &write, 0, NULL);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, l->layout, 0, 1, &set, 0, NULL);
    roma_covered_list_record(cmd, list->buffer, l->pipeline, l->layout,
                             (roma_image_list_push){.config = {im->width, im->height, 0, 0}}, (im->width + 7) / 8,
                             (im->height + 7) / 8);
    l->listed[slot][0] = im->width;
    l->listed[slot][1] = im->height;
    return ROMA_SUCCESS;
}

roma_result roma_pixel_list_slot_buffer(const roma_pixel_list *l, const roma_context *ctx, const roma_logger *log,
                                        const char *name, uint32_t slot, uint32_t width, uint32_t height,
                                        VkBuffer *out)
{
    *out = VK_NULL_HANDLE;
    if (l->ctx != ctx)
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT, "%s: images.pixels was made on another context", name);
    if (slot >= l->sets.frames_in_flight || !l->lists.lists[slot].buffer)
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT,
                         "%s: images.pixels holds no list of slot %u (record roma_pixel_list_record first)", name, slot);
    if (l->listed[slot][0] != width || l->listed[slot][1] != height)
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT,
                         "%s: images.pixels lists %ux%u pixels in slot %u, the images are %ux%u", name,
                         l->listed[slot][0], l->listed[slot][1], slot, width, height);
    *out = l->lists.lists[slot].buffer;
    return ROMA_SUCCESS;
}
