#include <string.h>

#include "vulkan/vk_internal.h"

#define MAX_STORAGE_BUFFERS 16

roma_result roma_compute_pipeline_create(roma_context *ctx, const char *module_name,
                                         uint32_t storage_buffer_count, uint32_t push_size,
                                         roma_compute_pipeline *out)
{
    VkDescriptorType types[MAX_STORAGE_BUFFERS];
    for (uint32_t i = 0; i < storage_buffer_count && i < MAX_STORAGE_BUFFERS; ++i)
        types[i] = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    return roma_compute_pipeline_create_typed(ctx, module_name, types, storage_buffer_count, push_size, out);
}

roma_result roma_compute_pipeline_create_typed(roma_context *ctx, const char *module_name,
                                               const VkDescriptorType *types, uint32_t binding_count,
                                               uint32_t push_size, roma_compute_pipeline *out)
{
    return roma_compute_pipeline_create_spec(ctx, module_name, types, binding_count, push_size, NULL, 0, out);
}

roma_result roma_compute_pipeline_create_spec(roma_context *ctx, const char *module_name,
                                              const VkDescriptorType *types, uint32_t binding_count,
                                              uint32_t push_size, const uint32_t *constants, uint32_t constant_count,
                                              roma_compute_pipeline *out)
{
    memset(out, 0, sizeof *out);
    if (binding_count > MAX_STORAGE_BUFFERS)
        return roma_fail(&ctx->logger, ROMA_ERROR_INVALID_ARGUMENT, "too many descriptors for %s", module_name);
    roma_result r = roma_descriptor_layout_create(ctx, types, binding_count, &out->set_layout);
    VkPushConstantRange push = {.stageFlags = VK_SHADER_STAGE_COMPUTE_BIT, .size = push_size};
    if (r == ROMA_SUCCESS) {
        VkPipelineLayoutCreateInfo layout_info = {
            .sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO,
            .setLayoutCount = 1,
            .pSetLayouts = &out->set_layout,
            .pushConstantRangeCount = push_size ? 1u : 0u,
            .pPushConstantRanges = &push,
        };
        r = roma_vk_check(ctx, vkCreatePipelineLayout(ctx->device, &layout_info, ctx->allocator, &out->layout),
                          "vkCreatePipelineLayout");
    }
    VkShaderModule shader = VK_NULL_HANDLE;
    if (r == ROMA_SUCCESS)
        r = roma_shader_module_create(ctx, module_name, &shader);
    VkSpecializationMapEntry entries[MAX_STORAGE_BUFFERS];
    for (uint32_t i = 0; i < constant_count && i < MAX_STORAGE_BUFFERS; ++i)
        entries[i] = (VkSpecializationMapEntry){i, i * 4, 4};
    VkSpecializationInfo spec = {constant_count < MAX_STORAGE_BUFFERS ? constant_count : MAX_STORAGE_BUFFERS,
                                 entries, 4 * (size_t)constant_count, constants};
    if (r == ROMA_SUCCESS) {
        VkComputePipelineCreateInfo info = {
            .sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO,
            .stage = {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
                      .stage = VK_SHADER_STAGE_COMPUTE_BIT,
                      .module = shader,
                      .pName = "main",
                      .pSpecializationInfo = constant_count ? &spec : NULL},
            .layout = out->layout,
        };
        r = roma_vk_check(ctx, vkCreateComputePipelines(ctx->device, VK_NULL_HANDLE, 1, &info, ctx->allocator, &out->pipeline),
                          "vkCreateComputePipelines");
    }
    if (shader)
        vkDestroyShaderModule(ctx->device, shader, ctx->allocator);
    if (r != ROMA_SUCCESS)
        roma_compute_pipeline_destroy(ctx, out);
    return r;
}

void roma_compute_pipeline_destroy(roma_context *ctx, roma_compute_pipeline *p)
{
    if (!ctx || !p)
        return;
    if (p->pipeline)
        vkDestroyPipeline(ctx->device, p->pipeline, ctx->allocator);
    if (p->layout)
        vkDestroyPipelineLayout(ctx->device, p->layout, ctx->allocator);
    if (p->set_layout)
        vkDestroyDescriptorSetLayout(ctx->device, p->set_layout, ctx->allocator);
    memset(p, 0, sizeof *p);
}
