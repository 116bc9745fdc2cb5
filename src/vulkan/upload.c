/* Data the host writes and shaders read (upload.h). */
#include "vulkan/upload.h"

#include <string.h>

roma_result roma_upload_create(roma_context *ctx, VkDeviceSize size, VkBufferUsageFlags usage, roma_upload *out)
{
    memset(out, 0, sizeof *out);
    usage |= VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    /* Device-local and mapped where the device has it; a small mappable heap (a BAR without
     * resizing) that is full falls back to plain device memory and staging. */
    roma_result r = roma_buffer_create(ctx, size, usage, ROMA_MEMORY_DEVICE_MAPPED, &out->device);
    if (r != ROMA_SUCCESS)
        r = roma_buffer_create(ctx, size, usage, ROMA_MEMORY_DEVICE, &out->device);
    if (r == ROMA_SUCCESS && !out->device.mapped)
        r = roma_buffer_create(ctx, size, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, ROMA_MEMORY_UPLOAD, &out->staging);
    if (r != ROMA_SUCCESS)
        roma_upload_destroy(ctx, out);
    return r;
}

void roma_upload_destroy(roma_context *ctx, roma_upload *u)
{
    roma_buffer_destroy(ctx, &u->device);
    roma_buffer_destroy(ctx, &u->staging);
    u->pending = 0;
}

void *roma_upload_write(roma_upload *u, VkDeviceSize bytes)
{
    if (u->device.mapped)
        return u->device.mapped;
    if (bytes > u->pending)
        u->pending = bytes;
    return u->staging.mapped;
}

void roma_upload_record(const roma_upload *u, VkCommandBuffer cmd, VkPipelineStageFlags2 dst_stage,
                        VkAccessFlags2 dst_access)
{
    if (!u->pending || !u->staging.buffer)
        return;
    /* After every earlier read of the device buffer (an execution dependency; the data they
     * read is replaced). */
    roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, 0, VK_PIPELINE_STAGE_2_COPY_BIT, 0);
    const VkBufferCopy copy = {0, 0, u->pending};
    vkCmdCopyBuffer(cmd, u->staging.buffer, u->device.buffer, 1, &copy);
    roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, dst_stage, dst_access);
}

void roma_upload_done(roma_upload *u)
{
    u->pending = 0;
}

roma_result roma_buffer_create_filled(roma_context *ctx, VkDeviceSize size, VkBufferUsageFlags usage,
                                      const void *data, roma_buffer *out)
{
    roma_upload u;
    roma_result r = roma_upload_create(ctx, size, usage, &u);
    if (r != ROMA_SUCCESS) {
        memset(out, 0, sizeof *out);
        return r;
    }
    memcpy(roma_upload_write(&u, size), data, (size_t)size);
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    if (u.pending) {
        r = roma_begin_one_shot(ctx, &cmd);
        if (r == ROMA_SUCCESS) {
            roma_upload_record(&u, cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_READ_BIT);
            r = roma_submit_one_shot(ctx, cmd);
        }
    }
    roma_buffer_destroy(ctx, &u.staging);
    *out = u.device;
    if (r != ROMA_SUCCESS)
        roma_buffer_destroy(ctx, out);
    return r;
}
