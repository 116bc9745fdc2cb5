/* Graphics pipelines of libroma's raster passes. They all pull vertices by buffer
 * address (no vertex input), draw two-sided triangle lists with dynamic viewport
 * and scissor, single-sampled, and write no colour attachment: their outputs are
 * storage buffers, plus an optional depth attachment. */
#include <stdlib.h>

#include "vulkan/shader_table.h"
#include "vulkan/spirv_rounding.h"
#include "vulkan/vk_internal.h"

roma_result roma_shader_module_create(roma_context *ctx, const char *name, VkShaderModule *out)
{
    *out = VK_NULL_HANDLE;
    const roma_spirv_module *m = roma_find_spirv(ctx, name);
    if (!m)
        return roma_fail(&ctx->logger, ROMA_ERROR_INVALID_ARGUMENT, "no embedded shader named %s", name);
    VkShaderModuleCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO,
        .codeSize = m->size,
        .pCode = m->code,
    };
    uint32_t *rte = NULL;
    size_t rte_words = 0;
    if (ctx->rounding_rte) { /* round to nearest even, as the trace's mirror assumes (spirv_rounding.h) */
        const int patched = roma_spirv_declare_rte(m->code, m->size / 4, &rte, &rte_words);
        if (patched <= 0)
            return roma_fail(&ctx->logger, patched < 0 ? ROMA_ERROR_OUT_OF_HOST_MEMORY : ROMA_ERROR_UNSUPPORTED,
                             "shader %s: could not declare RoundingModeRTE (%s)", name,
                             patched < 0 ? "out of memory" : "a module it cannot patch");
        info.codeSize = 4 * rte_words;
        info.pCode = rte;
    }
    roma_result r = roma_vk_check(ctx, vkCreateShaderModule(ctx->device, &info, ctx->allocator, out),
                                  "vkCreateShaderModule");
    free(rte);
    return r;
}

roma_result roma_push_layout_create(roma_context *ctx, VkShaderStageFlags stages, uint32_t push_size,
                                    VkPipelineLayout *out)
{
    VkPushConstantRange push = {.stageFlags = stages, .size = push_size};
    VkPipelineLayoutCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO,
        .pushConstantRangeCount = push_size ? 1u : 0u,
        .pPushConstantRanges = &push,
    };
    return roma_vk_check(ctx, vkCreatePipelineLayout(ctx->device, &info, ctx->allocator, out), "vkCreatePipelineLayout");
}

roma_result roma_graphics_pipeline_create(roma_context *ctx, const roma_graphics_pipeline_desc *d, VkPipeline *out)
{
    roma_specialization spec;
    roma_specialization_make(ctx, d->frag_name, NULL, 0, 0, &spec);
    VkPipelineShaderStageCreateInfo stages[2] = {
        {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
         .stage = VK_SHADER_STAGE_VERTEX_BIT, .module = d->vert, .pName = "main"},
        {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
         .stage = VK_SHADER_STAGE_FRAGMENT_BIT, .module = d->frag, .pName = "main",
         .pSpecializationInfo = &spec.info},
    };
    VkPipelineVertexInputStateCreateInfo vertex_input = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
    VkPipelineInputAssemblyStateCreateInfo assembly = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO,
        .topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST,
    };
    /* Viewport and scissor are dynamic: one pipeline serves every resolution. */
    VkPipelineViewportStateCreateInfo viewport = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO,
        .viewportCount = 1,
        .scissorCount = 1,
    };
    /* Surfaces are two-sided: no culling. */
    VkPipelineRasterizationStateCreateInfo raster = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO,
        .polygonMode = VK_POLYGON_MODE_FILL,
        .cullMode = VK_CULL_MODE_NONE,
        .frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE,
        .lineWidth = 1.0f,
    };
    VkPipelineMultisampleStateCreateInfo multisample = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO,
        .rasterizationSamples = VK_SAMPLE_COUNT_1_BIT,
    };
    VkPipelineDepthStencilStateCreateInfo depth = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO,
        .depthTestEnable = d->depth_format != VK_FORMAT_UNDEFINED,
        .depthWriteEnable = d->depth_write ? VK_TRUE : VK_FALSE,
        .depthCompareOp = d->depth_compare,
    };
    VkPipelineColorBlendStateCreateInfo blend = {.sType = VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
    VkDynamicState dynamic_states[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
    VkPipelineDynamicStateCreateInfo dynamic = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO,
        .dynamicStateCount = 2,
        .pDynamicStates = dynamic_states,
    };
    VkPipelineRenderingCreateInfo rendering = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO,
        .depthAttachmentFormat = d->depth_format,
    };
    VkGraphicsPipelineCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO,
        .pNext = &rendering,
        .stageCount = d->frag ? 2u : 1u,
        .pStages = stages,
        .pVertexInputState = &vertex_input,
        .pInputAssemblyState = &assembly,
        .pViewportState = &viewport,
        .pRasterizationState = &raster,
        .pMultisampleState = &multisample,
        .pDepthStencilState = d->depth_format != VK_FORMAT_UNDEFINED ? &depth : NULL,
        .pColorBlendState = &blend,
        .pDynamicState = &dynamic,
        .layout = d->layout,
    };
    return roma_vk_check(ctx, vkCreateGraphicsPipelines(ctx->device, ctx->pipeline_cache, 1, &info, ctx->allocator, out),
                         d->label ? d->label : "vkCreateGraphicsPipelines");
}
