/* The covered-pixel list's buffers and passes (covered_list.h). */
#include "effects/covered_list.h"

#include "util/log.h"

roma_result roma_covered_lists_reserve(roma_covered_lists *l, roma_context *ctx, const roma_logger *log,
                                       const char *name, uint32_t slot, int same_frame, uint64_t pixels)
{
    if (!same_frame) {
        for (uint32_t i = 0; i < l->retired_count[slot]; ++i)
            roma_buffer_destroy(ctx, &l->retired[slot][i]);
        l->retired_count[slot] = 0;
    }
    VkDeviceSize size = sizeof(roma_pixel_list_header) + 4ull * (pixels ? pixels : 1u);
    if (l->lists[slot].buffer && l->lists[slot].size >= size)
        return ROMA_SUCCESS;
    if (l->retired_count[slot] == ROMA_COVERED_LIST_RETIRED)
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT, "%s: more than %u records in one frame of slot %u", name,
                         ROMA_COVERED_LIST_RETIRED, slot);
    roma_buffer grown;
    roma_result r = roma_buffer_create(ctx, size,
                                       VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT |
                                           VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                       ROMA_MEMORY_DEVICE, &grown);
    if (r != ROMA_SUCCESS)
        return roma_fail(log, r, "%s: the covered-pixel list of %llu pixels", name, (unsigned long long)pixels);
    if (l->lists[slot].buffer)
        l->retired[slot][l->retired_count[slot]++] = l->lists[slot];
    l->lists[slot] = grown;
    return ROMA_SUCCESS;
}

void roma_covered_lists_free(roma_covered_lists *l, roma_context *ctx)
{
    for (uint32_t slot = 0; slot < ROMA_MAX_FRAMES_IN_FLIGHT; ++slot) {
        roma_buffer_destroy(ctx, &l->lists[slot]);
        for (uint32_t i = 0; i < l->retired_count[slot]; ++i)
            roma_buffer_destroy(ctx, &l->retired[slot][i]);
        l->retired_count[slot] = 0;
    }
}

void roma_covered_list_record(VkCommandBuffer cmd, VkBuffer list, VkPipeline pipeline, VkPipelineLayout layout,
                              roma_image_list_push push, uint32_t groups_x, uint32_t groups_y)
{
    /* Records before read the list (indirect arguments, pixel indices), wrote it, or wrote
     * the output this pass writes the background into. */
    roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT,
                            VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT |
                                VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                            VK_PIPELINE_STAGE_2_TRANSFER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                            VK_ACCESS_2_TRANSFER_WRITE_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    const roma_pixel_list_header header = {.dispatch = {0, 0, 1, 0}};
    vkCmdUpdateBuffer(cmd, list, 0, sizeof header, &header);
    roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                            VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                            VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    push.config[2] = 0;
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
    vkCmdPushConstants(cmd, layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push, &push);
    vkCmdDispatch(cmd, groups_x, groups_y, 1);
    /* The list for its arguments; the background before the effect writes the same image. */
    roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                            VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                            VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    push.config[2] = 1; /* the count into the indirect arguments */
    vkCmdPushConstants(cmd, layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push, &push);
    vkCmdDispatch(cmd, 1, 1, 1);
    roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                            VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT,
                            VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT);
}
