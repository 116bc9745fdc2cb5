#include "roma/bom_raster.h"

#include <stdlib.h>
#include <string.h>

#include "roma/map.h"
#include "vulkan/shader_table.h"
#include "vulkan/vk_internal.h"

struct roma_bom_raster {
    roma_context *ctx;
    VkPipelineLayout layout;
    VkPipeline pipeline;
};

static roma_result create_module(roma_context *ctx, const char *name, VkShaderModule *out)
{
    *out = VK_NULL_HANDLE;
    const roma_spirv_module *m = roma_find_spirv(name);
    if (!m)
        return roma_fail(&ctx->logger, ROMA_ERROR_INVALID_ARGUMENT, "no embedded shader named %s", name);
    VkShaderModuleCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO,
        .codeSize = m->size,
        .pCode = m->code,
    };
    return roma_vk_check(ctx, vkCreateShaderModule(ctx->device, &info, NULL, out), "vkCreateShaderModule");
}

static roma_result create_pipeline(roma_bom_raster *r)
{
    roma_context *ctx = r->ctx;
    VkPushConstantRange push = {
        .stageFlags = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT,
        .size = sizeof(roma_bom_push),
    };
    VkPipelineLayoutCreateInfo layout_info = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO,
        .pushConstantRangeCount = 1,
        .pPushConstantRanges = &push,
    };
    roma_result res = roma_vk_check(ctx, vkCreatePipelineLayout(ctx->device, &layout_info, NULL, &r->layout),
                                    "vkCreatePipelineLayout");
    VkShaderModule vert = VK_NULL_HANDLE, frag = VK_NULL_HANDLE;
    if (res == ROMA_SUCCESS)
        res = create_module(ctx, "bom.vert", &vert);
    if (res == ROMA_SUCCESS)
        res = create_module(ctx, "bom.frag", &frag);
    if (res == ROMA_SUCCESS) {
        VkPipelineShaderStageCreateInfo stages[2] = {
            {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
             .stage = VK_SHADER_STAGE_VERTEX_BIT, .module = vert, .pName = "main"},
            {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
             .stage = VK_SHADER_STAGE_FRAGMENT_BIT, .module = frag, .pName = "main"},
        };
        /* Vertex pulling: no vertex buffers. */
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
        /* Both windings, and depth never clipped (the VS writes z = 0.5). */
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
        VkPipelineColorBlendStateCreateInfo blend = {
            .sType = VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO,
        };
        VkDynamicState dynamic_states[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
        VkPipelineDynamicStateCreateInfo dynamic = {
            .sType = VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO,
            .dynamicStateCount = 2,
            .pDynamicStates = dynamic_states,
        };
        /* No attachments at all: the only output is the atomics into the BOM. */
        VkPipelineRenderingCreateInfo rendering = {
            .sType = VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO,
        };
        VkGraphicsPipelineCreateInfo info = {
            .sType = VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO,
            .pNext = &rendering,
            .stageCount = 2,
            .pStages = stages,
            .pVertexInputState = &vertex_input,
            .pInputAssemblyState = &assembly,
            .pViewportState = &viewport,
            .pRasterizationState = &raster,
            .pMultisampleState = &multisample,
            .pColorBlendState = &blend,
            .pDynamicState = &dynamic,
            .layout = r->layout,
        };
        res = roma_vk_check(ctx, vkCreateGraphicsPipelines(ctx->device, VK_NULL_HANDLE, 1, &info, NULL, &r->pipeline),
                            "vkCreateGraphicsPipelines (BOM)");
    }
    if (vert)
        vkDestroyShaderModule(ctx->device, vert, NULL);
    if (frag)
        vkDestroyShaderModule(ctx->device, frag, NULL);
    return res;
}

roma_result roma_bom_raster_create(roma_context *ctx, roma_bom_raster **out)
{
    if (!out)
        return ROMA_ERROR_INVALID_ARGUMENT;
    *out = NULL;
    if (!ctx)
        return ROMA_ERROR_INVALID_ARGUMENT;
    roma_bom_raster *r = calloc(1, sizeof *r);
    if (!r)
        return roma_fail(&ctx->logger, ROMA_ERROR_OUT_OF_HOST_MEMORY, "roma_bom_raster_create: out of memory");
    r->ctx = ctx;
    roma_result res = create_pipeline(r);
    if (res != ROMA_SUCCESS) {
        roma_bom_raster_destroy(r);
        return res;
    }
    *out = r;
    return ROMA_SUCCESS;
}

void roma_bom_raster_destroy(roma_bom_raster *r)
{
    if (!r)
        return;
    if (r->pipeline)
        vkDestroyPipeline(r->ctx->device, r->pipeline, NULL);
    if (r->layout)
        vkDestroyPipelineLayout(r->ctx->device, r->layout, NULL);
    free(r);
}

roma_result roma_bom_raster_record(roma_bom_raster *r, VkCommandBuffer cmd, const roma_bom_push *push,
                                   VkBuffer bom_buffer, VkDeviceSize bom_bytes, uint32_t resolution)
{
    if (!r)
        return ROMA_ERROR_INVALID_ARGUMENT;
    roma_context *ctx = r->ctx;
    if (!cmd || !push || !bom_buffer)
        return roma_fail(&ctx->logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_bom_raster_record: cmd, push and bom_buffer are required");
    if (resolution < 32 || resolution > ROMA_MAX_RESOLUTION || resolution % 32 != 0)
        return roma_fail(&ctx->logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_bom_raster_record: resolution %u is not a multiple of 32 in [32, %u]",
                         resolution, (unsigned)ROMA_MAX_RESOLUTION);
    const VkDeviceSize need = (VkDeviceSize)resolution * resolution * resolution / 8;
    if (bom_bytes < need || bom_bytes % 4 != 0)
        return roma_fail(&ctx->logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_bom_raster_record: bom_bytes %llu (need a multiple of 4, at least %llu)",
                         (unsigned long long)bom_bytes, (unsigned long long)need);
    const uint32_t triangles = push->config[2];
    if (triangles > UINT32_MAX / 3)
        return roma_fail(&ctx->logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_bom_raster_record: %u triangles exceed one draw", triangles);
    if (triangles && (!push->positions || !push->indices || !push->bom || !push->params))
        return roma_fail(&ctx->logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_bom_raster_record: a buffer address is zero");
    if (push->config[3] & ~ROMA_BOM_FLAG_CONSERVATIVE)
        return roma_fail(&ctx->logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_bom_raster_record: unknown flags 0x%x", push->config[3]);
    if (push->config[1] != ROMA_BOM_MODE_UNION3 && push->config[1] != ROMA_BOM_MODE_DOMINANT)
        return roma_fail(&ctx->logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_bom_raster_record: unknown BOM mode %u", push->config[1]);

    /* WAR/WAW against the previous build's raster, rotation and downloads, and
     * geometry written by transfers or compute (uploads, skinning) made visible. */
    roma_cmd_memory_barrier(cmd,
                   VK_PIPELINE_STAGE_2_TRANSFER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT |
                       VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                   VK_ACCESS_2_TRANSFER_WRITE_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                   VK_PIPELINE_STAGE_2_TRANSFER_BIT | VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT |
                       VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                   VK_ACCESS_2_TRANSFER_WRITE_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
    vkCmdFillBuffer(cmd, bom_buffer, 0, bom_bytes, 0);
    /* Atomics read and write. */
    roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                   VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                   VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);

    if (triangles) {
        VkRenderingInfo rendering = {
            .sType = VK_STRUCTURE_TYPE_RENDERING_INFO,
            .renderArea = {{0, 0}, {resolution, resolution}},
            .layerCount = 1,
        };
        vkCmdBeginRendering(cmd, &rendering);
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, r->pipeline);
        VkViewport viewport = {0.0f, 0.0f, (float)resolution, (float)resolution, 0.0f, 1.0f};
        VkRect2D scissor = {{0, 0}, {resolution, resolution}};
        vkCmdSetViewport(cmd, 0, 1, &viewport);
        vkCmdSetScissor(cmd, 0, 1, &scissor);
        roma_bom_push p = *push;
        /* All three draws in both modes: in DOMINANT the vertex shader drops a
         * triangle from the draws of its non-dominant axes (no CPU sorting). */
        for (uint32_t axis = 0; axis < 3; ++axis) {
            p.config[0] = axis;
            vkCmdPushConstants(cmd, r->layout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                               sizeof p, &p);
            vkCmdDraw(cmd, 3 * triangles, 1, 0, 0);
        }
        vkCmdEndRendering(cmd);
    }

    roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                   VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT,
                   VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                   VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT |
                       VK_ACCESS_2_TRANSFER_READ_BIT);
    return ROMA_SUCCESS;
}
