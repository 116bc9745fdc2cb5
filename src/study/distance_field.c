#include "study/distance_field.h"
#include "study/study_shaders.h"

#include <string.h>

#include "roma_shared.h"

static const VkDescriptorType df_types[4] = {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                                             VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER};

roma_result roma_distance_field_create(roma_context *ctx, VkBuffer bom, uint32_t resolution,
                                       roma_distance_field *out)
{
    roma_study_shaders_use(ctx); /* its shaders are in the study table */
    if (!out)
        return ROMA_ERROR_INVALID_ARGUMENT;
    memset(out, 0, sizeof *out);
    /* Seeds pack 10 bits per axis; RES is a multiple of 32 (the BOM's words). */
    if (!ctx || bom == VK_NULL_HANDLE || resolution < 32 || resolution > 1024 || resolution % 32)
        return ROMA_ERROR_INVALID_ARGUMENT;
    out->ctx = ctx;
    out->resolution = resolution;
    const VkDeviceSize cells = (VkDeviceSize)resolution * resolution * resolution;
    const VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
    roma_result r = ROMA_SUCCESS;
    if (cells / 2 > ctx->properties.limits.maxTexelBufferElements)
        r = roma_fail(&ctx->logger, ROMA_ERROR_UNSUPPORTED,
                      "distance field: %llu words at RES %u exceed maxTexelBufferElements (%u)",
                      (unsigned long long)(cells / 2), resolution, ctx->properties.limits.maxTexelBufferElements);
    for (int i = 0; i < 2 && r == ROMA_SUCCESS; ++i)
        r = roma_buffer_create(ctx, cells * sizeof(uint32_t), usage, ROMA_MEMORY_DEVICE, &out->seed_buffers[i]);
    if (r == ROMA_SUCCESS)
        r = roma_buffer_create(ctx, cells / 2 * sizeof(uint32_t), usage | VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT,
                               ROMA_MEMORY_DEVICE, &out->distances);
    if (r == ROMA_SUCCESS)
        r = roma_buffer_view_create(ctx, out->distances.buffer, VK_FORMAT_R32_UINT, &out->distances_view);
    if (r == ROMA_SUCCESS)
        r = roma_compute_pipeline_create_typed(ctx, "df_seeds.comp", df_types, 4, sizeof(roma_df_push), &out->seeds);
    if (r == ROMA_SUCCESS)
        r = roma_compute_pipeline_create_typed(ctx, "df_jump.comp", df_types, 4, sizeof(roma_df_push), &out->jump);
    if (r == ROMA_SUCCESS)
        r = roma_compute_pipeline_create_typed(ctx, "df_distance.comp", df_types, 4, sizeof(roma_df_push),
                                               &out->distance);
    /* The three pipelines' layouts are defined identically: one pair of sets serves all. */
    for (int i = 0; i < 2 && r == ROMA_SUCCESS; ++i) {
        r = roma_descriptor_set_create(ctx, &out->jump, df_types, 4, &out->sets[i]);
        if (r != ROMA_SUCCESS)
            break;
        roma_descriptor_write_buffer(ctx, &out->sets[i], ROMA_DF_BINDING_BOM, df_types[0], bom);
        roma_descriptor_write_buffer(ctx, &out->sets[i], ROMA_DF_BINDING_SEEDS_IN, df_types[1],
                                     out->seed_buffers[i].buffer);
        roma_descriptor_write_buffer(ctx, &out->sets[i], ROMA_DF_BINDING_SEEDS_OUT, df_types[2],
                                     out->seed_buffers[1 - i].buffer);
        roma_descriptor_write_buffer(ctx, &out->sets[i], ROMA_DF_BINDING_DISTANCES, df_types[3],
                                     out->distances.buffer);
    }
    if (r != ROMA_SUCCESS)
        roma_distance_field_destroy(out);
    return r;
}

void roma_distance_field_destroy(roma_distance_field *field)
{
    if (!field)
        return;
    if (field->ctx) {
        for (int i = 0; i < 2; ++i) {
            roma_descriptor_set_destroy(field->ctx, &field->sets[i]);
            roma_buffer_destroy(field->ctx, &field->seed_buffers[i]);
        }
        if (field->distances_view)
            vkDestroyBufferView(field->ctx->device, field->distances_view, field->ctx->allocator);
        roma_buffer_destroy(field->ctx, &field->distances);
        roma_compute_pipeline_destroy(field->ctx, &field->seeds);
        roma_compute_pipeline_destroy(field->ctx, &field->jump);
        roma_compute_pipeline_destroy(field->ctx, &field->distance);
    }
    memset(field, 0, sizeof *field);
}

/* One pass over every cell (or, for the distances, every pair of cells) with set s. */
static void dispatch(roma_distance_field *f, VkCommandBuffer cmd, const roma_compute_pipeline *p, int s,
                     uint32_t step, uint64_t invocations)
{
    const uint32_t res = f->resolution;
    roma_df_push push = {.config = {res, step, res * res * res, 0}};
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p->pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p->layout, 0, 1, &f->sets[s].set, 0, NULL);
    vkCmdPushConstants(cmd, p->layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push, &push);
    roma_cmd_dispatch_linear(cmd, invocations, ROMA_DF_WORKGROUP_SIZE);
    roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                            VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                            VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT |
                                VK_ACCESS_2_SHADER_SAMPLED_READ_BIT | VK_ACCESS_2_TRANSFER_READ_BIT);
}

void roma_distance_field_record(roma_distance_field *f, VkCommandBuffer cmd)
{
    const uint64_t cells = (uint64_t)f->resolution * f->resolution * f->resolution;
    /* The BOM's build, and earlier reads of the buffers this build overwrites. */
    roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                            VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT |
                                VK_ACCESS_2_TRANSFER_WRITE_BIT | VK_ACCESS_2_TRANSFER_READ_BIT,
                            VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                            VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    int s = 0; /* the set whose "out" the last pass wrote is s; the next pass reads with 1 - s */
    dispatch(f, cmd, &f->seeds, s, 0, cells);
    for (uint32_t step = f->resolution / 2; step >= 1; step /= 2) {
        s = 1 - s;
        dispatch(f, cmd, &f->jump, s, step, cells);
    }
    dispatch(f, cmd, &f->distance, 1 - s, 0, cells / 2);
}

uint64_t roma_distance_field_bytes(const roma_distance_field *f, uint64_t *build_bytes)
{
    const uint64_t cells = (uint64_t)f->resolution * f->resolution * f->resolution;
    if (build_bytes)
        *build_bytes = 2 * cells * sizeof(uint32_t);
    return cells / 2 * sizeof(uint32_t);
}
