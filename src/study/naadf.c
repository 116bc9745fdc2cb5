#include "study/naadf.h"
#include "study/study_shaders.h"

#include <stddef.h>
#include <string.h>

#include "roma_shared.h"

static const VkDescriptorType naadf_types[3] = {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                                                VK_DESCRIPTOR_TYPE_STORAGE_BUFFER};
static const char *const step_shaders[4] = {"naadf_blocks.comp", "naadf_chunk_blocks.comp", "naadf_chunks.comp",
                                            "naadf_voxels.comp"};

void roma_naadf_layout(uint32_t resolution, uint64_t *chunk_words, uint64_t *block_words, uint64_t *voxel_words,
                       uint64_t *row_words)
{
    const uint64_t n = resolution / 16, b = resolution / 4, r = resolution;
    *chunk_words = n * n * n;
    *block_words = b * b * b;
    *voxel_words = r * r * r / 2;
    *row_words = n * n;
}

static uint64_t total_words(uint32_t resolution)
{
    uint64_t c, b, v, r;
    roma_naadf_layout(resolution, &c, &b, &v, &r);
    return c + b + v + r;
}

roma_result roma_naadf_create(roma_context *ctx, VkBuffer bom, uint32_t resolution, roma_naadf *out)
{
    roma_study_shaders_use(ctx); /* its shaders are in the study table */
    if (!out)
        return ROMA_ERROR_INVALID_ARGUMENT;
    memset(out, 0, sizeof *out);
    if (!ctx || bom == VK_NULL_HANDLE || resolution < 32 || resolution > ROMA_NAADF_MAX_RESOLUTION ||
        resolution % 32)
        return ROMA_ERROR_INVALID_ARGUMENT;
    out->ctx = ctx;
    out->resolution = resolution;
    const uint64_t words = total_words(resolution);
    roma_result r = ROMA_SUCCESS;
    if (words > ctx->properties.limits.maxTexelBufferElements)
        r = roma_fail(&ctx->logger, ROMA_ERROR_UNSUPPORTED,
                      "NAADF: %llu words at RES %u exceed maxTexelBufferElements (%u)",
                      (unsigned long long)words, resolution, ctx->properties.limits.maxTexelBufferElements);
    /* The steps bind the whole buffer as a storage buffer. */
    if (r == ROMA_SUCCESS && words * sizeof(uint32_t) > ctx->properties.limits.maxStorageBufferRange)
        r = roma_fail(&ctx->logger, ROMA_ERROR_UNSUPPORTED,
                      "NAADF: %llu bytes at RES %u exceed maxStorageBufferRange (%u)",
                      (unsigned long long)(words * sizeof(uint32_t)), resolution,
                      ctx->properties.limits.maxStorageBufferRange);
    if (r == ROMA_SUCCESS)
        r = roma_buffer_create(ctx, words * sizeof(uint32_t),
                               VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                                   VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT,
                               ROMA_MEMORY_DEVICE, &out->cells);
    if (r == ROMA_SUCCESS)
        r = roma_buffer_view_create(ctx, out->cells.buffer, VK_FORMAT_R32_UINT, &out->cells_view);
    const uint64_t blocks = (uint64_t)(resolution / 4) * (resolution / 4) * (resolution / 4);
    if (r == ROMA_SUCCESS)
        r = roma_buffer_create(ctx, sizeof(roma_naadf_mixed_header) + 3 * blocks * sizeof(uint32_t),
                               VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                                   VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT,
                               ROMA_MEMORY_DEVICE, &out->mixed);
    for (int i = 0; i < 4 && r == ROMA_SUCCESS; ++i)
        r = roma_compute_pipeline_create_typed(ctx, step_shaders[i], naadf_types, 3, sizeof(roma_naadf_push),
                                               &out->steps[i]);
    if (r == ROMA_SUCCESS)
        r = roma_descriptor_set_create(ctx, &out->steps[0], naadf_types, 3, &out->set);
    if (r == ROMA_SUCCESS) {
        roma_descriptor_write_buffer(ctx, &out->set, ROMA_NAADF_BINDING_BOM, naadf_types[0], bom);
        roma_descriptor_write_buffer(ctx, &out->set, ROMA_NAADF_BINDING_CELLS, naadf_types[1], out->cells.buffer);
        roma_descriptor_write_buffer(ctx, &out->set, ROMA_NAADF_BINDING_MIXED, naadf_types[2], out->mixed.buffer);
    }
    if (r != ROMA_SUCCESS)
        roma_naadf_destroy(out);
    return r;
}

void roma_naadf_destroy(roma_naadf *naadf)
{
    if (!naadf)
        return;
    if (naadf->ctx) {
        roma_descriptor_set_destroy(naadf->ctx, &naadf->set);
        if (naadf->cells_view)
            vkDestroyBufferView(naadf->ctx->device, naadf->cells_view, naadf->ctx->allocator);
        roma_buffer_destroy(naadf->ctx, &naadf->cells);
        roma_buffer_destroy(naadf->ctx, &naadf->mixed);
        for (int i = 0; i < 4; ++i)
            roma_compute_pipeline_destroy(naadf->ctx, &naadf->steps[i]);
    }
    memset(naadf, 0, sizeof *naadf);
}

/* Earlier writes (the BOM's build, the previous step, the clears) visible to this step's
 * reads and writes (step 4's indirect dispatch included), and earlier reads done before its
 * writes. */
static void barrier(VkCommandBuffer cmd)
{
    const VkPipelineStageFlags2 stages = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT |
                                         VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT;
    roma_cmd_memory_barrier(cmd, stages,
                            VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT, stages,
                            VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT |
                                VK_ACCESS_2_SHADER_SAMPLED_READ_BIT | VK_ACCESS_2_TRANSFER_READ_BIT |
                                VK_ACCESS_2_TRANSFER_WRITE_BIT | VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT);
}

static void bind(roma_naadf *f, VkCommandBuffer cmd, const roma_compute_pipeline *p, uint32_t count)
{
    const uint32_t res = f->resolution;
    roma_naadf_push push = {.config = {res, res / 16, res / 4, count}};
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p->pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p->layout, 0, 1, &f->set.set, 0, NULL);
    vkCmdPushConstants(cmd, p->layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push, &push);
}

void roma_naadf_record(roma_naadf *f, VkCommandBuffer cmd)
{
    uint64_t chunks, blocks, voxels, rows;
    roma_naadf_layout(f->resolution, &chunks, &blocks, &voxels, &rows);
    barrier(cmd);
    vkCmdFillBuffer(cmd, f->cells.buffer, (chunks + blocks + voxels) * sizeof(uint32_t), rows * sizeof(uint32_t), 0);
    vkCmdFillBuffer(cmd, f->mixed.buffer, 0, sizeof(uint32_t), 0); /* no mixed block listed yet */
    barrier(cmd);
    bind(f, cmd, &f->steps[0], (uint32_t)blocks);
    roma_cmd_dispatch_linear(cmd, blocks, ROMA_NAADF_WORKGROUP_SIZE);
    barrier(cmd);
    bind(f, cmd, &f->steps[1], (uint32_t)chunks);
    roma_cmd_dispatch_linear(cmd, chunks, 1); /* a workgroup a chunk */
    barrier(cmd);
    bind(f, cmd, &f->steps[2], (uint32_t)chunks);
    roma_cmd_dispatch_linear(cmd, chunks, ROMA_NAADF_WORKGROUP_SIZE);
    bind(f, cmd, &f->steps[3], 0); /* steps 3 and 4 write apart: no barrier between them */
    vkCmdDispatchIndirect(cmd, f->mixed.buffer, offsetof(roma_naadf_mixed_header, groups_x));
    barrier(cmd);
}

uint64_t roma_naadf_bytes(const roma_naadf *f, uint64_t *build_bytes)
{
    if (build_bytes)
        *build_bytes = f->mixed.size + (uint64_t)(f->resolution / 16) * (f->resolution / 16) * sizeof(uint32_t);
    return total_words(f->resolution) * sizeof(uint32_t);
}
