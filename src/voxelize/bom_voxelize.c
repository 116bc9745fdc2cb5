#include "voxelize/bom_voxelize.h"

#include <stdlib.h>
#include <string.h>

#include "voxelize/tile_queue.h"

struct roma_bom_voxelizer {
    roma_context *ctx;
    uint32_t resolution;
    roma_tile_queue queue;
    VkBuffer bom;
    VkDeviceSize bom_bytes;
    roma_compute_pipeline triangles, tiles; /* one set layout, the same bindings */
    roma_descriptor_set set;
};

static const VkDescriptorType binding_types[ROMA_VOXELIZE_BINDINGS] = {
    VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
    VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
};

roma_result roma_bom_voxelizer_create(roma_context *ctx, uint32_t resolution, VkBuffer positions, VkBuffer indices,
                                      VkBuffer bom, VkDeviceSize bom_bytes, roma_bom_voxelizer **out)
{
    if (!out)
        return ROMA_ERROR_INVALID_ARGUMENT;
    *out = NULL;
    if (!ctx)
        return ROMA_ERROR_INVALID_ARGUMENT;
    if (!positions || !indices || !bom)
        return roma_fail(&ctx->logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_bom_voxelizer_create: positions, indices and bom are required");
    const VkDeviceSize need = (VkDeviceSize)resolution * resolution * resolution / 8;
    if (bom_bytes < need || bom_bytes % 4 != 0)
        return roma_fail(&ctx->logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_bom_voxelizer_create: bom_bytes %llu (need a multiple of 4, at least %llu)",
                         (unsigned long long)bom_bytes, (unsigned long long)need);
    if (resolution < 32 || resolution > ROMA_MAX_RESOLUTION || resolution % 32 != 0)
        return roma_fail(&ctx->logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_bom_voxelizer_create: resolution %u is not a multiple of 32 in [32, %u]",
                         resolution, (unsigned)ROMA_MAX_RESOLUTION);
    roma_bom_voxelizer *v = calloc(1, sizeof *v);
    if (!v)
        return roma_fail(&ctx->logger, ROMA_ERROR_OUT_OF_HOST_MEMORY, "roma_bom_voxelizer_create: out of memory");
    v->ctx = ctx;
    v->resolution = resolution;
    v->bom = bom;
    v->bom_bytes = bom_bytes;
    roma_result r = roma_tile_queue_create(ctx, resolution, &v->queue);
    if (r == ROMA_SUCCESS)
        r = roma_compute_pipeline_create_typed(ctx, "voxelize.comp", binding_types, ROMA_VOXELIZE_BINDINGS,
                                               sizeof(roma_voxelize_push), &v->triangles);
    if (r == ROMA_SUCCESS)
        r = roma_compute_pipeline_create_typed(ctx, "voxelize_tiles.comp", binding_types, ROMA_VOXELIZE_BINDINGS,
                                               sizeof(roma_voxelize_push), &v->tiles);
    if (r == ROMA_SUCCESS)
        r = roma_descriptor_set_create(ctx, &v->triangles, binding_types, ROMA_VOXELIZE_BINDINGS, &v->set);
    if (r == ROMA_SUCCESS) {
        const VkBuffer buffers[ROMA_VOXELIZE_BINDINGS] = {positions, indices, bom, v->queue.buffer.buffer};
        for (uint32_t b = 0; b < ROMA_VOXELIZE_BINDINGS; ++b)
            roma_descriptor_write_buffer(ctx, &v->set, b, binding_types[b], buffers[b]);
    }
    if (r != ROMA_SUCCESS) {
        roma_bom_voxelizer_destroy(v);
        return r;
    }
    *out = v;
    return ROMA_SUCCESS;
}

void roma_bom_voxelizer_destroy(roma_bom_voxelizer *v)
{
    if (!v)
        return;
    roma_descriptor_set_destroy(v->ctx, &v->set);
    roma_compute_pipeline_destroy(v->ctx, &v->tiles);
    roma_compute_pipeline_destroy(v->ctx, &v->triangles);
    roma_tile_queue_destroy(v->ctx, &v->queue);
    free(v);
}

roma_result roma_bom_voxelize_record(roma_bom_voxelizer *v, VkCommandBuffer cmd, const roma_grid_params *grid,
                                     uint32_t triangles)
{
    return roma_bom_voxelize_record_level(v, cmd, grid, 0, triangles, 1);
}

roma_result roma_bom_voxelize_record_level(roma_bom_voxelizer *v, VkCommandBuffer cmd, const roma_grid_params *grid,
                                           uint32_t first, uint32_t triangles, int clear)
{
    const roma_triangle_run run = {first, triangles};
    return roma_bom_voxelize_record_runs(v, cmd, grid, &run, triangles ? 1u : 0u, clear);
}

roma_result roma_bom_voxelize_record_runs(roma_bom_voxelizer *v, VkCommandBuffer cmd, const roma_grid_params *grid,
                                          const roma_triangle_run *runs, uint32_t run_count, int clear)
{
    if (!v)
        return ROMA_ERROR_INVALID_ARGUMENT;
    roma_context *ctx = v->ctx;
    if (!cmd || !grid || (run_count && !runs))
        return roma_fail(&ctx->logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_bom_voxelize_record: cmd, grid and the runs are required");
    if (grid->dims[0] != v->resolution || grid->dims[1] != v->resolution / 32)
        return roma_fail(&ctx->logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_bom_voxelize_record: grid of RES %u (%u words), the voxelizer was made for %u",
                         grid->dims[0], grid->dims[1], v->resolution);
    const VkDeviceSize level_bytes = (VkDeviceSize)v->resolution * v->resolution * v->resolution / 8;
    if ((VkDeviceSize)grid->level[0] * level_bytes + level_bytes > v->bom_bytes)
        return roma_fail(&ctx->logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_bom_voxelize_record: level %u is outside the BOM buffer", grid->level[0]);
    if (run_count > ROMA_VOXELIZE_RUNS)
        return roma_fail(&ctx->logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_bom_voxelize_record: %u runs of triangles, at most %u", run_count,
                         (unsigned)ROMA_VOXELIZE_RUNS);
    roma_voxelize_push push = {.grid = *grid, .config = {0, v->queue.capacity, 0, 0}};
    for (uint32_t i = 0; i < run_count; ++i) {
        push.runs[i / 2][2 * (i % 2)] = runs[i].first;
        push.runs[i / 2][2 * (i % 2) + 1] = runs[i].count;
        push.config[0] += runs[i].count;
    }
    const uint32_t triangles = push.config[0];

    /* WAR/WAW against the previous build (voxelization, rotation, downloads, the
     * indirect read of the queue) and geometry written by transfers or compute. */
    roma_cmd_memory_barrier(cmd,
                            VK_PIPELINE_STAGE_2_TRANSFER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT |
                                VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT,
                            VK_ACCESS_2_TRANSFER_WRITE_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                            VK_PIPELINE_STAGE_2_TRANSFER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                            VK_ACCESS_2_TRANSFER_WRITE_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
    if (clear)
        vkCmdFillBuffer(cmd, v->bom, (VkDeviceSize)grid->level[0] * level_bytes, level_bytes, 0);
    roma_tile_queue_record_reset(&v->queue, cmd);
    roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                            VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                            VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    if (triangles) {
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, v->triangles.layout, 0, 1, &v->set.set, 0, NULL);
        vkCmdPushConstants(cmd, v->triangles.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push, &push);
        roma_tile_queue_record_passes(&v->queue, cmd, v->triangles.pipeline, v->tiles.pipeline, triangles);
    }
    roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                            VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT,
                            VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                            VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT |
                                VK_ACCESS_2_TRANSFER_READ_BIT);
    return ROMA_SUCCESS;
}
