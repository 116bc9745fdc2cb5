/* Data the host writes and shaders read every frame or every trace. The shaders read
 * device-local memory: the host writes into it directly where that memory is host-visible
 * (CPU and integrated devices such as lavapipe, GPUs with a resizable BAR), and elsewhere into
 * a host-visible staging twin whose copy is recorded ahead of the readers, so that a
 * discrete GPU never reads it across the bus per ray. */
#ifndef ROMA_VULKAN_UPLOAD_H
#define ROMA_VULKAN_UPLOAD_H

#include "vulkan/vk_internal.h"

typedef struct roma_upload {
    roma_buffer device;   /* what the shaders read (TRANSFER_DST added to its usage) */
    roma_buffer staging;  /* absent where device is mapped */
    VkDeviceSize pending; /* bytes written into staging and not copied yet */
} roma_upload;

/* usage: the device buffer's. On failure *out is zeroed. */
roma_result roma_upload_create(roma_context *ctx, VkDeviceSize size, VkBufferUsageFlags usage, roma_upload *out);
/* Accepts a zeroed one. */
void roma_upload_destroy(roma_context *ctx, roma_upload *u);
/* Where the host writes the first `bytes` (at most the size); they wait for
 * roma_upload_record where they went to the staging twin. */
void *roma_upload_write(roma_upload *u, VkDeviceSize bytes);
/* Records the copy of what waits in the staging twin and a barrier that makes it visible to
 * dst_stage's dst_access; records nothing when nothing waits. The caller orders the copy
 * after earlier readers of the device buffer (the slot rules, or a buffer of its own). What
 * waits keeps waiting, recorded again by the next record, until roma_upload_done: a record
 * that fails after this leaves the caller to drop its command buffer. */
void roma_upload_record(const roma_upload *u, VkCommandBuffer cmd, VkPipelineStageFlags2 dst_stage,
                        VkAccessFlags2 dst_access);
/* The record that copied it succeeded: nothing waits. */
void roma_upload_done(roma_upload *u);

/* Set-up data: a device-local buffer holding `size` bytes of data when this returns, written
 * directly where it is mapped, else copied from a staging buffer by one submission to the
 * context's queue that this waits for (a set-up call's, not a frame's). usage: the buffer's
 * (TRANSFER_DST added). On failure *out is zeroed. */
roma_result roma_buffer_create_filled(roma_context *ctx, VkDeviceSize size, VkBufferUsageFlags usage,
                                      const void *data, roma_buffer *out);

#endif /* ROMA_VULKAN_UPLOAD_H */
