/* The shared part of the public effects on G-buffer images (image_effect.h). */
#include "effects/image_effect.h"

#include <string.h>

#include "map/map_internal.h"
#include "util/log.h"

#define SETS_PER_SLOT 16u

roma_result roma_nearest_sampler_create(roma_context *ctx, VkSampler *out)
{
    VkSamplerCreateInfo si = {.sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO,
                              .magFilter = VK_FILTER_NEAREST,
                              .minFilter = VK_FILTER_NEAREST,
                              .addressModeU = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
                              .addressModeV = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
                              .addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE};
    return roma_vk_check(ctx, vkCreateSampler(ctx->device, &si, ctx->allocator, out), "vkCreateSampler");
}

roma_result roma_image_effect_init(roma_image_effect *e, roma_context *ctx, const roma_logger *log, const char *name,
                                   const char *module, uint32_t inputs, uint32_t outputs, uint32_t push_size,
                                   uint32_t frames_in_flight)
{
    memset(e, 0, sizeof *e);
    e->ctx = ctx;
    e->logger = *log;
    e->name = name;
    e->frames_in_flight = frames_in_flight;
    e->last_slot = UINT32_MAX;
    e->inputs = inputs;
    e->outputs = outputs;
    e->push_size = push_size;
    VkDescriptorType types[ROMA_IMAGE_EFFECT_MAX_IMAGES + 1];
    for (uint32_t i = 0; i < inputs + outputs; ++i)
        types[i] = i < inputs ? VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER : VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    types[inputs + outputs] = VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER; /* the map's BOM (bom_view) */
    roma_result r = roma_nearest_sampler_create(ctx, &e->sampler);
    if (r == ROMA_SUCCESS)
        r = roma_descriptor_layout_create(ctx, roma_trace_binding_types, ROMA_TRACE_BINDINGS, &e->trace_layout);
    if (r == ROMA_SUCCESS)
        r = roma_descriptor_layout_create(ctx, types, inputs + outputs + 1, &e->images_layout);
    if (r == ROMA_SUCCESS) {
        VkDescriptorSetLayout sets[2] = {e->trace_layout, e->images_layout};
        VkPushConstantRange push = {VK_SHADER_STAGE_COMPUTE_BIT, 0, push_size};
        VkPipelineLayoutCreateInfo li = {.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO,
                                         .setLayoutCount = 2,
                                         .pSetLayouts = sets,
                                         .pushConstantRangeCount = 1,
                                         .pPushConstantRanges = &push};
        r = roma_vk_check(ctx, vkCreatePipelineLayout(ctx->device, &li, ctx->allocator, &e->layout),
                          "vkCreatePipelineLayout");
    }
    VkShaderModule shader = VK_NULL_HANDLE;
    if (r == ROMA_SUCCESS)
        r = roma_shader_module_create(ctx, module, &shader);
    if (r == ROMA_SUCCESS) {
        VkComputePipelineCreateInfo pi = {
            .sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO,
            .stage = {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
                      .stage = VK_SHADER_STAGE_COMPUTE_BIT,
                      .module = shader,
                      .pName = "main"},
            .layout = e->layout};
        r = roma_vk_check(ctx, vkCreateComputePipelines(ctx->device, ctx->pipeline_cache, 1, &pi, ctx->allocator,
                                                        &e->pipeline),
                          "vkCreateComputePipelines");
    }
    if (shader)
        vkDestroyShaderModule(ctx->device, shader, ctx->allocator);
    VkDescriptorPoolSize sizes[3] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, inputs * SETS_PER_SLOT},
                                     {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, outputs * SETS_PER_SLOT},
                                     {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, SETS_PER_SLOT}};
    VkDescriptorPoolCreateInfo poi = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO,
                                      .maxSets = SETS_PER_SLOT,
                                      .poolSizeCount = 3,
                                      .pPoolSizes = sizes};
    for (uint32_t s = 0; s < frames_in_flight && r == ROMA_SUCCESS; ++s)
        r = roma_vk_check(ctx, vkCreateDescriptorPool(ctx->device, &poi, ctx->allocator, &e->pools[s]),
                          "vkCreateDescriptorPool");
    if (r != ROMA_SUCCESS)
        roma_image_effect_free(e);
    return r;
}

void roma_image_effect_free(roma_image_effect *e)
{
    if (!e->ctx)
        return;
    VkDevice dev = e->ctx->device;
    const VkAllocationCallbacks *a = e->ctx->allocator;
    for (uint32_t s = 0; s < ROMA_MAX_FRAMES_IN_FLIGHT; ++s)
        if (e->pools[s])
            vkDestroyDescriptorPool(dev, e->pools[s], a);
    if (e->pipeline)
        vkDestroyPipeline(dev, e->pipeline, a);
    if (e->layout)
        vkDestroyPipelineLayout(dev, e->layout, a);
    if (e->images_layout)
        vkDestroyDescriptorSetLayout(dev, e->images_layout, a);
    if (e->trace_layout)
        vkDestroyDescriptorSetLayout(dev, e->trace_layout, a);
    if (e->sampler)
        vkDestroySampler(dev, e->sampler, a);
    memset(e, 0, sizeof *e);
}

roma_result roma_image_effect_begin(roma_image_effect *e, uint32_t slot, uint32_t frame, const roma_map *map,
                                    roma_map_info *info)
{
    if (slot >= e->frames_in_flight)
        return roma_fail(&e->logger, ROMA_ERROR_INVALID_ARGUMENT, "%s: slot %u of %u", e->name, slot,
                         e->frames_in_flight);
    roma_result r = roma_map_get_info(map, info);
    if (r != ROMA_SUCCESS)
        return r;
    if (!map->built)
        return roma_fail(&e->logger, ROMA_ERROR_NOT_READY, "%s: record a build of the map first", e->name);
    e->frame = frame;
    return ROMA_SUCCESS;
}

int roma_image_effect_same_frame(const roma_image_effect *e, uint32_t slot)
{
    return slot == e->last_slot && e->frame == e->last_frame && e->used[slot] > 0;
}

roma_result roma_image_effect_dispatch(roma_image_effect *e, VkCommandBuffer cmd, uint32_t slot,
                                       const roma_map_info *info, const VkImageView *views, VkImageLayout input_layout,
                                       const void *push, uint32_t width, uint32_t height)
{
    if (!roma_image_effect_same_frame(e, slot)) { /* a new frame in this slot: its last use has completed */
        vkResetDescriptorPool(e->ctx->device, e->pools[slot], 0);
        e->used[slot] = 0;
        e->last_slot = slot;
        e->last_frame = e->frame;
    }
    if (e->used[slot] == SETS_PER_SLOT)
        return roma_fail(&e->logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "%s: more than %u records in one frame of a slot (count frames in settings.frame)",
                         e->name, SETS_PER_SLOT);
    VkDescriptorSet set;
    VkDescriptorSetAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO,
                                      .descriptorPool = e->pools[slot],
                                      .descriptorSetCount = 1,
                                      .pSetLayouts = &e->images_layout};
    roma_result r = roma_vk_check(e->ctx, vkAllocateDescriptorSets(e->ctx->device, &ai, &set),
                                  "vkAllocateDescriptorSets");
    if (r != ROMA_SUCCESS)
        return r;
    e->used[slot]++;
    VkImageLayout in_layout = input_layout ? input_layout : VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    VkDescriptorImageInfo infos[ROMA_IMAGE_EFFECT_MAX_IMAGES];
    VkWriteDescriptorSet writes[ROMA_IMAGE_EFFECT_MAX_IMAGES + 1];
    for (uint32_t i = 0; i < e->inputs + e->outputs; ++i) {
        int input = i < e->inputs;
        infos[i] = (VkDescriptorImageInfo){input ? e->sampler : VK_NULL_HANDLE, views[i],
                                           input ? in_layout : VK_IMAGE_LAYOUT_GENERAL};
        writes[i] = (VkWriteDescriptorSet){.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET,
                                           .dstSet = set,
                                           .dstBinding = i,
                                           .descriptorCount = 1,
                                           .descriptorType = input ? VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER
                                                                   : VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
                                           .pImageInfo = &infos[i]};
    }
    const uint32_t n = e->inputs + e->outputs;
    writes[n] = (VkWriteDescriptorSet){.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET,
                                       .dstSet = set,
                                       .dstBinding = n,
                                       .descriptorCount = 1,
                                       .descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER,
                                       .pTexelBufferView = &info->bom_view};
    vkUpdateDescriptorSets(e->ctx->device, n + 1, writes, 0, NULL);
    VkDescriptorSet sets[2] = {info->trace_set, set};
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, e->pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, e->layout, 0, 2, sets, 0, NULL);
    vkCmdPushConstants(cmd, e->layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, e->push_size, push);
    vkCmdDispatch(cmd, (width + 7) / 8, (height + 7) / 8, 1);
    return ROMA_SUCCESS;
}
