/* The tools' device-local images (app_image.h). */
#include "app_image.h"

#include <string.h>

void app_image_destroy(roma_context *ctx, app_image *im)
{
    VkDevice dev = ctx ? roma_context_device(ctx) : VK_NULL_HANDLE;
    if (dev && im->view)
        vkDestroyImageView(dev, im->view, NULL);
    if (dev && im->image)
        vkDestroyImage(dev, im->image, NULL);
    if (dev && im->memory)
        vkFreeMemory(dev, im->memory, NULL);
    memset(im, 0, sizeof *im);
}

roma_result app_image_create(roma_context *ctx, uint32_t width, uint32_t height, VkFormat format,
                             VkImageUsageFlags usage, app_image *out)
{
    memset(out, 0, sizeof *out);
    VkDevice dev = roma_context_device(ctx);
    const VkImageCreateInfo ii = {.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO, .imageType = VK_IMAGE_TYPE_2D,
                                  .format = format, .extent = {width, height, 1}, .mipLevels = 1, .arrayLayers = 1,
                                  .samples = VK_SAMPLE_COUNT_1_BIT, .tiling = VK_IMAGE_TILING_OPTIMAL, .usage = usage,
                                  .initialLayout = VK_IMAGE_LAYOUT_UNDEFINED};
    if (vkCreateImage(dev, &ii, NULL, &out->image) != VK_SUCCESS) {
        out->image = VK_NULL_HANDLE;
        return ROMA_ERROR_OUT_OF_DEVICE_MEMORY;
    }
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(dev, out->image, &req);
    VkPhysicalDeviceMemoryProperties mp;
    vkGetPhysicalDeviceMemoryProperties(roma_context_physical_device(ctx), &mp);
    uint32_t type = UINT32_MAX;
    for (uint32_t i = 0; i < mp.memoryTypeCount && type == UINT32_MAX; ++i)
        if ((req.memoryTypeBits & (1u << i)) && (mp.memoryTypes[i].propertyFlags & VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT))
            type = i;
    const VkMemoryAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, .allocationSize = req.size,
                                     .memoryTypeIndex = type};
    roma_result r = type == UINT32_MAX ? ROMA_ERROR_MISSING_FEATURE : ROMA_SUCCESS;
    if (r == ROMA_SUCCESS && vkAllocateMemory(dev, &ai, NULL, &out->memory) != VK_SUCCESS) {
        out->memory = VK_NULL_HANDLE;
        r = ROMA_ERROR_OUT_OF_DEVICE_MEMORY;
    }
    if (r == ROMA_SUCCESS && vkBindImageMemory(dev, out->image, out->memory, 0) != VK_SUCCESS)
        r = ROMA_ERROR_VULKAN;
    out->bytes = req.size;
    const VkImageViewCreateInfo vi = {.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO, .image = out->image,
                                      .viewType = VK_IMAGE_VIEW_TYPE_2D, .format = format,
                                      .subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1}};
    if (r == ROMA_SUCCESS && vkCreateImageView(dev, &vi, NULL, &out->view) != VK_SUCCESS) {
        out->view = VK_NULL_HANDLE;
        r = ROMA_ERROR_VULKAN;
    }
    if (r != ROMA_SUCCESS)
        app_image_destroy(ctx, out);
    return r;
}

void app_image_barrier(VkCommandBuffer cmd, VkImage image, VkImageLayout from, VkImageLayout to,
                       VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access, VkPipelineStageFlags2 dst_stage,
                       VkAccessFlags2 dst_access)
{
    const VkImageMemoryBarrier2 b = {.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2, .srcStageMask = src_stage,
                                     .srcAccessMask = src_access, .dstStageMask = dst_stage,
                                     .dstAccessMask = dst_access, .oldLayout = from, .newLayout = to,
                                     .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                                     .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED, .image = image,
                                     .subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1}};
    const VkDependencyInfo dep = {.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO, .imageMemoryBarrierCount = 1,
                                  .pImageMemoryBarriers = &b};
    vkCmdPipelineBarrier2(cmd, &dep);
}
