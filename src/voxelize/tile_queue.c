#include "voxelize/tile_queue.h"

#include <string.h>

roma_result roma_tile_queue_create(roma_context *ctx, uint32_t resolution, roma_tile_queue *out)
{
    memset(out, 0, sizeof *out);
    const uint32_t capacity = 4 * resolution * resolution;
    /* TRANSFER_SRC: the tests read the header back. */
    roma_result r = roma_buffer_create(ctx, sizeof(roma_voxelize_queue) + 8ull * capacity,
                                       VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT |
                                           VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                                           VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                       ROMA_MEMORY_DEVICE, &out->buffer);
    if (r == ROMA_SUCCESS)
        out->capacity = capacity;
    return r;
}

void roma_tile_queue_destroy(roma_context *ctx, roma_tile_queue *queue)
{
    roma_buffer_destroy(ctx, &queue->buffer);
    memset(queue, 0, sizeof *queue);
}

void roma_tile_queue_record_reset(const roma_tile_queue *queue, VkCommandBuffer cmd)
{
    const uint32_t header[4] = {0, 1, 1, 0}; /* no workgroups yet, y = z = 1, no items */
    vkCmdUpdateBuffer(cmd, queue->buffer.buffer, 0, sizeof header, header);
}

void roma_tile_queue_record_passes(const roma_tile_queue *queue, VkCommandBuffer cmd, VkPipeline triangles,
                                   VkPipeline tiles, uint32_t triangle_count)
{
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, triangles);
    roma_cmd_dispatch_linear(cmd, triangle_count, ROMA_VOXELIZE_WORKGROUP_SIZE);
    roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                            VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT,
                            VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT |
                                VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT);
    /* Same set layout and push range: the set and constants stay bound. */
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, tiles);
    vkCmdDispatchIndirect(cmd, queue->buffer.buffer, 0);
}
