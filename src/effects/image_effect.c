/* The shared part of the public effects on G-buffer images (image_effect.h). */
#include "effects/image_effect.h"

#include <string.h>

#include "map/map_internal.h"
#include "util/log.h"

#define RECORDS_PER_SLOT 16u

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
    roma_specialization spec;
    roma_specialization_make(ctx, NULL, 0, &spec);
    if (r == ROMA_SUCCESS) {
        VkComputePipelineCreateInfo pi = {
            .sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO,
            .stage = {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
                      .stage = VK_SHADER_STAGE_COMPUTE_BIT,
                      .module = shader,
                      .pName = "main",
                      .pSpecializationInfo = &spec.info},
            .layout = e->layout};
        r = roma_vk_check(ctx, vkCreateComputePipelines(ctx->device, ctx->pipeline_cache, 1, &pi, ctx->allocator,
                                                        &e->pipeline),
                          "vkCreateComputePipelines");
    }
    if (shader)
        vkDestroyShaderModule(ctx->device, shader, ctx->allocator);
    const VkDescriptorPoolSize sizes[3] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, inputs},
                                           {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, outputs},
                                           {VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, 1}};
    if (r == ROMA_SUCCESS)
        r = roma_slot_sets_init(&e->sets, ctx, frames_in_flight, RECORDS_PER_SLOT, 1, sizes, 3);
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
    roma_slot_sets_free(&e->sets);
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
    if (slot >= e->sets.frames_in_flight)
        return roma_fail(&e->logger, ROMA_ERROR_INVALID_ARGUMENT, "%s: slot %u of %u", e->name, slot,
                         e->sets.frames_in_flight);
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
    return roma_slot_sets_same_frame(&e->sets, slot, e->frame);
}

roma_result roma_image_effect_dispatch(roma_image_effect *e, VkCommandBuffer cmd, uint32_t slot,
                                       const roma_map_info *info, const VkImageView *views, VkImageLayout input_layout,
                                       const void *push, uint32_t width, uint32_t height)
{
    roma_result r = roma_slot_sets_begin(&e->sets, &e->logger, e->name, slot, e->frame);
    VkImageLayout in_layouts[ROMA_IMAGE_EFFECT_MAX_IMAGES];
    for (uint32_t i = 0; i < e->inputs; ++i)
        in_layouts[i] = input_layout ? input_layout : VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    VkDescriptorSet set = VK_NULL_HANDLE;
    if (r == ROMA_SUCCESS)
        r = roma_slot_sets_write_images(&e->sets, slot, e->images_layout, e->sampler, views, in_layouts, e->inputs,
                                        e->inputs + e->outputs, &set);
    if (r != ROMA_SUCCESS)
        return r;
    roma_slot_sets_commit(&e->sets, slot);
    VkWriteDescriptorSet bom = {.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET,
                                .dstSet = set,
                                .dstBinding = e->inputs + e->outputs,
                                .descriptorCount = 1,
                                .descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER,
                                .pTexelBufferView = &info->bom_view};
    vkUpdateDescriptorSets(e->ctx->device, 1, &bom, 0, NULL);
    VkDescriptorSet sets[2] = {info->trace_set, set};
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, e->pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, e->layout, 0, 2, sets, 0, NULL);
    vkCmdPushConstants(cmd, e->layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, e->push_size, push);
    vkCmdDispatch(cmd, (width + 7) / 8, (height + 7) / 8, 1);
    return ROMA_SUCCESS;
}
