#include "voxelize/bom_raster.h"

#include <stdlib.h>
#include <string.h>

#include "roma/map.h"
#include "vulkan/vk_internal.h"

struct roma_bom_raster {
    roma_context *ctx;
    VkPipelineLayout layout;
    VkPipeline pipeline;
};

static roma_result create_pipeline(roma_bom_raster *r)
{
    roma_context *ctx = r->ctx;
    VkShaderModule vert = VK_NULL_HANDLE, frag = VK_NULL_HANDLE;
    roma_result res = roma_push_layout_create(ctx, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT,
                                              sizeof(roma_bom_push), &r->layout);
    if (res == ROMA_SUCCESS)
        res = roma_shader_module_create(ctx, "bom.vert", &vert);
    if (res == ROMA_SUCCESS)
        res = roma_shader_module_create(ctx, "bom.frag", &frag);
    /* No attachments at all: the only output is the atomics into the BOM; the vertex
     * shader writes z = 0.5, so nothing is depth-clipped. */
    roma_graphics_pipeline_desc desc = {
        .vert = vert, .frag = frag, .frag_name = "bom.frag", .layout = r->layout, .depth_format = VK_FORMAT_UNDEFINED,
        .label = "vkCreateGraphicsPipelines (BOM)",
    };
    if (res == ROMA_SUCCESS)
        res = roma_graphics_pipeline_create(ctx, &desc, &r->pipeline);
    if (vert)
        vkDestroyShaderModule(ctx->device, vert, ctx->allocator);
    if (frag)
        vkDestroyShaderModule(ctx->device, frag, ctx->allocator);
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
        vkDestroyPipeline(r->ctx->device, r->pipeline, r->ctx->allocator);
    if (r->layout)
        vkDestroyPipelineLayout(r->ctx->device, r->layout, r->ctx->allocator);
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
