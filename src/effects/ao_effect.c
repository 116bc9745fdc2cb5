/* roma_ao_effect: ambient occlusion from the engine's G-buffer images
 * (shaders/effects/ao_images.comp), sets from a per-slot pool. */
#include "roma/ao_effect.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "map/map_internal.h"
#include "roma_shared.h"
#include "util/log.h"
#include "vulkan/vk_internal.h"

#define SETS_PER_SLOT 16u

struct roma_ao_effect {
    roma_context *ctx;
    roma_logger logger;
    uint32_t frames_in_flight, last_slot, used[ROMA_MAX_FRAMES_IN_FLIGHT];
    VkSampler sampler;
    VkDescriptorSetLayout trace_layout, images_layout;
    VkPipelineLayout layout;
    VkPipeline pipeline;
    VkDescriptorPool pools[ROMA_MAX_FRAMES_IN_FLIGHT];
};

static const VkDescriptorType image_types[4] = {
    VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
    VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE};

roma_result roma_ao_settings_resolve(const roma_ao_settings *in, roma_ao_settings *out)
{
    roma_ao_settings s = in ? *in : (roma_ao_settings){0};
    if (out)
        memset(out, 0, sizeof *out);
    if (!out)
        return roma_fail(NULL, ROMA_ERROR_INVALID_ARGUMENT, "roma_ao_settings_resolve: out is NULL");
    if (!isfinite(s.radius) || s.radius < 0.0f || !isfinite(s.offset_cells) || s.offset_cells < 0.0f ||
        !isfinite(s.skip_cells))
        return roma_fail(NULL, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_ao_settings: radius and offset_cells must be finite and not negative, skip_cells finite");
    if (s.samples == 0)
        s.samples = ROMA_DEFAULT_AO_SAMPLES;
    if (s.offset_cells == 0.0f)
        s.offset_cells = ROMA_DEFAULT_OFFSET_CELLS;
    s.skip_cells = s.skip_cells < 0.0f ? 0.0f : s.skip_cells > 0.0f ? s.skip_cells : ROMA_DEFAULT_AO_SKIP_CELLS;
    *out = s;
    return ROMA_SUCCESS;
}

roma_result roma_ao_effect_create(roma_context *ctx, const roma_ao_effect_desc *desc_in, roma_ao_effect **out)
{
    roma_ao_effect_desc desc = desc_in ? *desc_in : (roma_ao_effect_desc){0};
    const roma_logger *log = desc.logger.fn ? &desc.logger : (ctx ? &ctx->logger : NULL);
    if (!out)
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT, "roma_ao_effect_create: out is NULL");
    *out = NULL;
    if (!ctx)
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT, "roma_ao_effect_create: context is NULL");
    if (desc.frames_in_flight == 0)
        desc.frames_in_flight = 2;
    if (desc.frames_in_flight > ROMA_MAX_FRAMES_IN_FLIGHT)
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT, "roma_ao_effect_create: frames_in_flight %u outside [1, %u]",
                         desc.frames_in_flight, ROMA_MAX_FRAMES_IN_FLIGHT);
    roma_ao_effect *e = calloc(1, sizeof *e);
    if (!e)
        return roma_fail(log, ROMA_ERROR_OUT_OF_HOST_MEMORY, "roma_ao_effect_create: out of host memory");
    e->ctx = ctx;
    e->logger = *log;
    e->frames_in_flight = desc.frames_in_flight;
    e->last_slot = UINT32_MAX;
    VkSamplerCreateInfo si = {.sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO,
                              .magFilter = VK_FILTER_NEAREST,
                              .minFilter = VK_FILTER_NEAREST,
                              .addressModeU = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
                              .addressModeV = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
                              .addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE};
    roma_result r = roma_vk_check(ctx, vkCreateSampler(ctx->device, &si, ctx->allocator, &e->sampler), "vkCreateSampler");
    if (r == ROMA_SUCCESS)
        r = roma_descriptor_layout_create(ctx, roma_trace_binding_types, ROMA_TRACE_BINDINGS, &e->trace_layout);
    if (r == ROMA_SUCCESS)
        r = roma_descriptor_layout_create(ctx, image_types, 4, &e->images_layout);
    if (r == ROMA_SUCCESS) {
        VkDescriptorSetLayout sets[2] = {e->trace_layout, e->images_layout};
        VkPushConstantRange push = {VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(roma_ao_push)};
        VkPipelineLayoutCreateInfo li = {.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO,
                                         .setLayoutCount = 2,
                                         .pSetLayouts = sets,
                                         .pushConstantRangeCount = 1,
                                         .pPushConstantRanges = &push};
        r = roma_vk_check(ctx, vkCreatePipelineLayout(ctx->device, &li, ctx->allocator, &e->layout),
                          "vkCreatePipelineLayout");
    }
    VkShaderModule module = VK_NULL_HANDLE;
    if (r == ROMA_SUCCESS)
        r = roma_shader_module_create(ctx, "ao_images.comp", &module);
    if (r == ROMA_SUCCESS) {
        VkComputePipelineCreateInfo pi = {
            .sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO,
            .stage = {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
                      .stage = VK_SHADER_STAGE_COMPUTE_BIT,
                      .module = module,
                      .pName = "main"},
            .layout = e->layout};
        r = roma_vk_check(ctx, vkCreateComputePipelines(ctx->device, ctx->pipeline_cache, 1, &pi, ctx->allocator,
                                                        &e->pipeline),
                          "vkCreateComputePipelines");
    }
    if (module)
        vkDestroyShaderModule(ctx->device, module, ctx->allocator);
    VkDescriptorPoolSize sizes[2] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 3 * SETS_PER_SLOT},
                                     {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, SETS_PER_SLOT}};
    VkDescriptorPoolCreateInfo poi = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO,
                                      .maxSets = SETS_PER_SLOT,
                                      .poolSizeCount = 2,
                                      .pPoolSizes = sizes};
    for (uint32_t s = 0; s < e->frames_in_flight && r == ROMA_SUCCESS; ++s)
        r = roma_vk_check(ctx, vkCreateDescriptorPool(ctx->device, &poi, ctx->allocator, &e->pools[s]),
                          "vkCreateDescriptorPool");
    if (r != ROMA_SUCCESS) {
        roma_ao_effect_destroy(e);
        return r;
    }
    *out = e;
    return ROMA_SUCCESS;
}

void roma_ao_effect_destroy(roma_ao_effect *e)
{
    if (!e)
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
    free(e);
}

roma_result roma_ao_effect_record(roma_ao_effect *e, VkCommandBuffer cmd, uint32_t slot, const roma_map *map,
                                  const roma_ao_images *im, const roma_ao_settings *settings_in)
{
    if (!e || !cmd || !map || !im)
        return roma_fail(e ? &e->logger : NULL, ROMA_ERROR_INVALID_ARGUMENT, "roma_ao_effect_record: %s is NULL",
                         !e ? "effect" : !cmd ? "cmd" : !map ? "map" : "images");
    if (slot >= e->frames_in_flight)
        return roma_fail(&e->logger, ROMA_ERROR_INVALID_ARGUMENT, "roma_ao_effect_record: slot %u of %u", slot,
                         e->frames_in_flight);
    if (!im->width || !im->height || !im->position || !im->normal || !im->output)
        return roma_fail(&e->logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_ao_effect_record: width, height, position, normal and output are required");
    roma_ao_settings s;
    roma_result r = roma_ao_settings_resolve(settings_in, &s);
    if (r != ROMA_SUCCESS)
        return roma_fail(&e->logger, r, "roma_ao_effect_record: invalid settings");
    roma_map_info info;
    r = roma_map_get_info(map, &info);
    if (r != ROMA_SUCCESS)
        return r;
    if (!map->built)
        return roma_fail(&e->logger, ROMA_ERROR_NOT_READY, "roma_ao_effect_record: record a build of the map first");
    if (slot != e->last_slot) { /* a new frame in this slot: its last use has completed */
        vkResetDescriptorPool(e->ctx->device, e->pools[slot], 0);
        e->used[slot] = 0;
        e->last_slot = slot;
    }
    if (e->used[slot] == SETS_PER_SLOT)
        return roma_fail(&e->logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_ao_effect_record: more than %u records in one frame slot", SETS_PER_SLOT);
    VkDescriptorSet set;
    VkDescriptorSetAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO,
                                      .descriptorPool = e->pools[slot],
                                      .descriptorSetCount = 1,
                                      .pSetLayouts = &e->images_layout};
    r = roma_vk_check(e->ctx, vkAllocateDescriptorSets(e->ctx->device, &ai, &set), "vkAllocateDescriptorSets");
    if (r != ROMA_SUCCESS)
        return r;
    e->used[slot]++;
    VkImageLayout in_layout = im->input_layout ? im->input_layout : VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    VkDescriptorImageInfo infos[4] = {
        {e->sampler, im->position, in_layout},
        {e->sampler, im->normal, in_layout},
        {e->sampler, im->geometric_normal ? im->geometric_normal : im->normal, in_layout},
        {VK_NULL_HANDLE, im->output, VK_IMAGE_LAYOUT_GENERAL}};
    VkWriteDescriptorSet writes[4];
    for (uint32_t i = 0; i < 4; ++i)
        writes[i] = (VkWriteDescriptorSet){.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET,
                                           .dstSet = set,
                                           .dstBinding = i,
                                           .descriptorCount = 1,
                                           .descriptorType = image_types[i],
                                           .pImageInfo = &infos[i]};
    vkUpdateDescriptorSets(e->ctx->device, 4, writes, 0, NULL);
    roma_ao_push push = {.config = {im->width, im->height, s.samples, s.frame},
                         .config2 = {s.seed, 0, 0, 0},
                         .ray = {s.offset_cells * info.trace_cell, s.radius > 0.0f ? s.radius : INFINITY,
                                 s.skip_cells * info.trace_cell, 0.0f}};
    VkDescriptorSet sets[2] = {info.trace_set, set};
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, e->pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, e->layout, 0, 2, sets, 0, NULL);
    vkCmdPushConstants(cmd, e->layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push, &push);
    vkCmdDispatch(cmd, (im->width + 7) / 8, (im->height + 7) / 8, 1);
    return ROMA_SUCCESS;
}
