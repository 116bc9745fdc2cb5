/* A device-local 2D image with its view, and the barrier that changes its layout: what the
 * tools that play an engine (roma-bench's frames) make their G-buffer and output images of. */
#ifndef ROMA_APPS_APP_IMAGE_H
#define ROMA_APPS_APP_IMAGE_H

#include "roma/context.h"

typedef struct app_image {
    VkImage image;
    VkDeviceMemory memory;
    VkImageView view;
    VkDeviceSize bytes; /* its memory's size */
} app_image;

/* One level, one layer, optimal tiling; on failure nothing stays made. */
roma_result app_image_create(roma_context *ctx, uint32_t width, uint32_t height, VkFormat format,
                             VkImageUsageFlags usage, app_image *out);
/* Accepts a zeroed image. */
void app_image_destroy(roma_context *ctx, app_image *image);

/* One image barrier (synchronization2), colour aspect, the whole image. */
void app_image_barrier(VkCommandBuffer cmd, VkImage image, VkImageLayout from, VkImageLayout to,
                       VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access, VkPipelineStageFlags2 dst_stage,
                       VkAccessFlags2 dst_access);

#endif /* ROMA_APPS_APP_IMAGE_H */
