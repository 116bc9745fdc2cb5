#include "passes/pixel_list.h"
#include "study/study_shaders.h"

#include <string.h>

#include "roma_shared.h"
#include "util/log.h"

roma_result roma_gbuffer_list_create(roma_context *ctx, uint32_t width, uint32_t height, roma_gbuffer_list *out)
{
    roma_study_shaders_use(ctx); /* its shaders are in the study table */
    memset(out, 0, sizeof *out);
    if (!ctx || width == 0 || height == 0)
        return ROMA_ERROR_INVALID_ARGUMENT;
    /* The tracing passes read it as a texel buffer: 4 header words, then a word a pixel. */
    if (4ull + (uint64_t)width * height > ctx->properties.limits.maxTexelBufferElements)
        return roma_fail(&ctx->logger, ROMA_ERROR_UNSUPPORTED,
                         "roma_gbuffer_list_create: %ux%u pixels exceed this device's maxTexelBufferElements (%u)", width,
                         height, ctx->properties.limits.maxTexelBufferElements);
    out->ctx = ctx;
    out->width = width;
    out->height = height;
    roma_result r = roma_buffer_create(ctx, sizeof(roma_pixel_list_header) + 4ull * width * height,
                                       VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT |
                                           VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                                           VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT, /* read by the tracing passes */
                                       ROMA_MEMORY_DEVICE, &out->buffer);
    if (r == ROMA_SUCCESS)
        r = roma_compute_pipeline_create(ctx, "pixel_list.comp", 0, sizeof(roma_pixel_list_push), &out->build);
    if (r == ROMA_SUCCESS)
        r = roma_compute_pipeline_create(ctx, "pixel_list_args.comp", 0, sizeof(roma_pixel_list_push), &out->args);
    if (r != ROMA_SUCCESS)
        roma_gbuffer_list_destroy(out);
    return r;
}

void roma_gbuffer_list_destroy(roma_gbuffer_list *list)
{
    if (!list->ctx)
        return;
    roma_compute_pipeline_destroy(list->ctx, &list->args);
    roma_compute_pipeline_destroy(list->ctx, &list->build);
    roma_buffer_destroy(list->ctx, &list->buffer);
    memset(list, 0, sizeof *list);
}

roma_result roma_gbuffer_list_record(roma_gbuffer_list *list, VkCommandBuffer cmd, VkDeviceAddress gbuffer_pixels)
{
    if (!list->ctx || !cmd || !gbuffer_pixels)
        return ROMA_ERROR_INVALID_ARGUMENT;
    uint32_t gx = (list->width + ROMA_PIXEL_WORKGROUP_X - 1) / ROMA_PIXEL_WORKGROUP_X;
    uint32_t gy = (list->height + ROMA_PIXEL_WORKGROUP_Y - 1) / ROMA_PIXEL_WORKGROUP_Y;
    if (gx > 65535u || gy > 65535u)
        return roma_fail(&list->ctx->logger, ROMA_ERROR_INVALID_ARGUMENT, "pixel list: image %ux%u is too large",
                         list->width, list->height);
    roma_pixel_list_push push = {
        .pixels = gbuffer_pixels,
        .list = list->buffer.address,
        .config = {list->width, list->height, 0, 0},
    };
    /* The previous frame's passes read the list (indirect arguments, pixel indices). */
    roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT, 0,
                            VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    const roma_pixel_list_header header = {.dispatch = {0, 0, 1, 0}};
    vkCmdUpdateBuffer(cmd, list->buffer.buffer, 0, sizeof header, &header);
    /* The G-buffer (fragment or compute writes) and the reset header. */
    roma_cmd_memory_barrier(cmd,
                            VK_PIPELINE_STAGE_2_TRANSFER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT |
                                VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                            VK_ACCESS_2_TRANSFER_WRITE_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                            VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                            VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, list->build.pipeline);
    vkCmdPushConstants(cmd, list->build.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push, &push);
    vkCmdDispatch(cmd, gx, gy, 1);
    roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                            VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                            VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, list->args.pipeline);
    vkCmdPushConstants(cmd, list->args.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push, &push);
    vkCmdDispatch(cmd, 1, 1, 1);
    roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                            VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT,
                            VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT);
    return ROMA_SUCCESS;
}
