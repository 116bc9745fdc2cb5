#include "passes/ao.h"

#include <math.h>
#include <stdlib.h>

#include "roma_shared.h"
#include "vulkan/vk_internal.h"

struct roma_ao_pass {
    roma_context *ctx;
    roma_compute_pipeline pipeline;
};

roma_result roma_ao_pass_create(roma_context *ctx, roma_ao_pass **out)
{
    if (!out)
        return ROMA_ERROR_INVALID_ARGUMENT;
    *out = NULL;
    if (!ctx)
        return ROMA_ERROR_INVALID_ARGUMENT;
    roma_ao_pass *pass = calloc(1, sizeof *pass);
    if (!pass)
        return roma_fail(&ctx->logger, ROMA_ERROR_OUT_OF_HOST_MEMORY, "roma_ao_pass_create: out of memory");
    pass->ctx = ctx;
    roma_result r = roma_compute_pipeline_create(ctx, "ao.comp", 0, sizeof(roma_ao_push), &pass->pipeline);
    if (r != ROMA_SUCCESS) {
        roma_ao_pass_destroy(pass);
        return r;
    }
    *out = pass;
    return ROMA_SUCCESS;
}

void roma_ao_pass_destroy(roma_ao_pass *pass)
{
    if (!pass)
        return;
    roma_compute_pipeline_destroy(pass->ctx, &pass->pipeline);
    free(pass);
}

roma_result roma_ao_pass_record(roma_ao_pass *pass, VkCommandBuffer cmd, const roma_ao_pass_inputs *in)
{
    if (!pass || !cmd || !in)
        return ROMA_ERROR_INVALID_ARGUMENT;
    if (!in->gbuffer_pixels || !in->maps_address || !in->params_address || !in->accum)
        return roma_fail(&pass->ctx->logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_ao_pass_record: G-buffer, map and accumulation addresses are required");
    if (in->width == 0 || in->height == 0 || !(in->offset >= 0.0f) || !isfinite(in->offset))
        return roma_fail(&pass->ctx->logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_ao_pass_record: empty image or invalid offset");
    /* One pass per pixel: each dimension's workgroup count must stay within 65535. */
    uint32_t gx = (in->width + ROMA_AO_WORKGROUP_X - 1) / ROMA_AO_WORKGROUP_X;
    uint32_t gy = (in->height + ROMA_AO_WORKGROUP_Y - 1) / ROMA_AO_WORKGROUP_Y;
    if (gx > 65535u || gy > 65535u)
        return roma_fail(&pass->ctx->logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_ao_pass_record: image %ux%u too large", in->width, in->height);
    if (in->spp == 0)
        return ROMA_SUCCESS;
    roma_ao_push push = {
        .pixels = in->gbuffer_pixels,
        .maps = in->maps_address,
        .params = in->params_address,
        .accum = in->accum,
        .config = {in->width, in->height, in->spp, in->frame},
        .config2 = {in->seed, 0, 0, 0},
        .ray = {in->offset, in->radius > 0.0f ? in->radius : INFINITY, 0.0f, 0.0f},
    };
    /* G-buffer (fragment/compute), map build (compute) and the accum clear (transfer). */
    roma_cmd_memory_barrier(cmd,
                            VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT |
                                VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                            VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT,
                            VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                            VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pass->pipeline.pipeline);
    vkCmdPushConstants(cmd, pass->pipeline.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push, &push);
    vkCmdDispatch(cmd, gx, gy, 1);
    /* Accumulated counts feed the next frame's pass and downloads. */
    roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                            VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                            VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT |
                                VK_ACCESS_2_TRANSFER_READ_BIT);
    return ROMA_SUCCESS;
}
