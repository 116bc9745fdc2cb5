/* Images and host staging for tests of the effects on an engine's images (gpu_images.h). */
#include "gpu_images.h"

#include <string.h>

#include "harness.h"

uint32_t roma_test_memory_type(VkPhysicalDevice pd, uint32_t bits, VkMemoryPropertyFlags want)
{
    VkPhysicalDeviceMemoryProperties p;
    vkGetPhysicalDeviceMemoryProperties(pd, &p);
    for (uint32_t i = 0; i < p.memoryTypeCount; ++i)
        if ((bits & (1u << i)) && (p.memoryTypes[i].propertyFlags & want) == want)
            return i;
    return 0;
}

/* pNext: NULL, or a VkMemoryAllocateFlagsInfo (device addresses). */
static VkDeviceMemory allocate_with(roma_context *ctx, const VkMemoryRequirements *req, VkMemoryPropertyFlags want,
                                    const void *pNext)
{
    VkMemoryAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, .pNext = pNext,
                               .allocationSize = req->size,
                               .memoryTypeIndex = roma_test_memory_type(roma_context_physical_device(ctx),
                                                                        req->memoryTypeBits, want)};
    VkDeviceMemory memory = VK_NULL_HANDLE;
    CHECK(vkAllocateMemory(roma_context_device(ctx), &ai, NULL, &memory) == VK_SUCCESS);
    return memory;
}

static VkDeviceMemory allocate(roma_context *ctx, const VkMemoryRequirements *req, VkMemoryPropertyFlags want)
{
    return allocate_with(ctx, req, want, NULL);
}

void roma_test_image_create(roma_context *ctx, uint32_t width, uint32_t height, VkFormat format,
                            VkImageUsageFlags usage, roma_test_image *out)
{
    memset(out, 0, sizeof *out);
    VkDevice dev = roma_context_device(ctx);
    VkImageCreateInfo ii = {.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO, .imageType = VK_IMAGE_TYPE_2D,
                            .format = format, .extent = {width, height, 1}, .mipLevels = 1, .arrayLayers = 1,
                            .samples = VK_SAMPLE_COUNT_1_BIT, .tiling = VK_IMAGE_TILING_OPTIMAL, .usage = usage,
                            .initialLayout = VK_IMAGE_LAYOUT_UNDEFINED};
    CHECK(vkCreateImage(dev, &ii, NULL, &out->image) == VK_SUCCESS);
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(dev, out->image, &req);
    out->memory = allocate(ctx, &req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    CHECK(vkBindImageMemory(dev, out->image, out->memory, 0) == VK_SUCCESS);
    VkImageViewCreateInfo vi = {.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO, .image = out->image,
                                .viewType = VK_IMAGE_VIEW_TYPE_2D, .format = format,
                                .subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1}};
    CHECK(vkCreateImageView(dev, &vi, NULL, &out->view) == VK_SUCCESS);
}

void roma_test_image_destroy(VkDevice dev, roma_test_image *image)
{
    vkDestroyImageView(dev, image->view, NULL);
    vkDestroyImage(dev, image->image, NULL);
    vkFreeMemory(dev, image->memory, NULL);
    memset(image, 0, sizeof *image);
}

void roma_test_layout_barrier(VkCommandBuffer cmd, VkImage image, VkImageLayout from, VkImageLayout to,
                              VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access,
                              VkPipelineStageFlags2 dst_stage, VkAccessFlags2 dst_access)
{
    VkImageMemoryBarrier2 b = {.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2, .srcStageMask = src_stage,
                               .srcAccessMask = src_access, .dstStageMask = dst_stage, .dstAccessMask = dst_access,
                               .oldLayout = from, .newLayout = to, .image = image,
                               .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                               .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                               .subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1}};
    VkDependencyInfo d = {.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO, .imageMemoryBarrierCount = 1,
                          .pImageMemoryBarriers = &b};
    vkCmdPipelineBarrier2(cmd, &d);
}

void roma_test_submit_and_wait(roma_context *ctx, VkCommandBuffer cmd)
{
    VkMemoryBarrier2 to_host = {.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER_2,
                                .srcStageMask = VK_PIPELINE_STAGE_2_COPY_BIT,
                                .srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT,
                                .dstStageMask = VK_PIPELINE_STAGE_2_HOST_BIT,
                                .dstAccessMask = VK_ACCESS_2_HOST_READ_BIT};
    VkDependencyInfo dep = {.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO, .memoryBarrierCount = 1,
                            .pMemoryBarriers = &to_host};
    vkCmdPipelineBarrier2(cmd, &dep);
    vkEndCommandBuffer(cmd);
    VkSubmitInfo si = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO, .commandBufferCount = 1, .pCommandBuffers = &cmd};
    CHECK(vkQueueSubmit(roma_context_queue(ctx), 1, &si, VK_NULL_HANDLE) == VK_SUCCESS);
    vkQueueWaitIdle(roma_context_queue(ctx));
}

/* A host-visible, coherent buffer of the given usage, bound and mapped; allocate_flags: NULL or
 * a VkMemoryAllocateFlagsInfo. */
static void create_mapped(roma_context *ctx, VkDeviceSize bytes, VkBufferUsageFlags usage, const void *allocate_flags,
                          VkBuffer *buffer, VkDeviceMemory *memory, void **mapped)
{
    VkDevice dev = roma_context_device(ctx);
    VkBufferCreateInfo bi = {.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO, .size = bytes, .usage = usage};
    CHECK(vkCreateBuffer(dev, &bi, NULL, buffer) == VK_SUCCESS);
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(dev, *buffer, &req);
    *memory = allocate_with(ctx, &req, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT,
                            allocate_flags);
    CHECK(vkBindBufferMemory(dev, *buffer, *memory, 0) == VK_SUCCESS);
    CHECK(vkMapMemory(dev, *memory, 0, VK_WHOLE_SIZE, 0, mapped) == VK_SUCCESS);
}

void roma_test_staging_create(roma_context *ctx, VkDeviceSize bytes, roma_test_staging *out)
{
    memset(out, 0, sizeof *out);
    create_mapped(ctx, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, NULL, &out->buffer,
                  &out->memory, &out->mapped);
}

void roma_test_staging_destroy(VkDevice dev, roma_test_staging *staging)
{
    vkDestroyBuffer(dev, staging->buffer, NULL);
    vkFreeMemory(dev, staging->memory, NULL);
    memset(staging, 0, sizeof *staging);
}

void roma_test_host_buffer_create(roma_context *ctx, VkDeviceSize bytes, roma_test_host_buffer *out)
{
    memset(out, 0, sizeof *out);
    VkMemoryAllocateFlagsInfo flags = {.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO,
                                       .flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT};
    create_mapped(ctx, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT, &flags,
                  &out->buffer, &out->memory, &out->mapped);
    VkBufferDeviceAddressInfo at = {.sType = VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO, .buffer = out->buffer};
    out->address = vkGetBufferDeviceAddress(roma_context_device(ctx), &at);
}

void roma_test_host_buffer_destroy(VkDevice dev, roma_test_host_buffer *buffer)
{
    if (buffer->buffer)
        vkDestroyBuffer(dev, buffer->buffer, NULL);
    if (buffer->memory)
        vkFreeMemory(dev, buffer->memory, NULL);
    memset(buffer, 0, sizeof *buffer);
}
