// roma-viewer: the viewer's own Vulkan instance and device (created with what
// roma_get_device_requirements lists, plus the swapchain when there is a window), and the
// small buffer and image helpers of its passes.
#pragma once

#include <roma/context.h>
#include <vulkan/vulkan.h>

#include <cstdint>

struct GLFWwindow;

struct vk_base {
    VkInstance instance = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
    VkSurfaceKHR surface = VK_NULL_HANDLE;
    VkPhysicalDevice physical = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    uint32_t family = 0;
    VkQueue queue = VK_NULL_HANDLE;
    // What the device was created with (requirements.features chains to its 1.2 and 1.3
    // structs inside the same object: a vk_base is not copied once created).
    roma_device_requirements requirements{};
    VkPhysicalDeviceProperties properties{};
    VkPhysicalDeviceMemoryProperties memory{};
    uint32_t validation_messages = 0;     // errors and warnings of the validation layer
};

// window: NULL = headless (no surface, no swapchain extension).
bool vk_base_create(vk_base &b, GLFWwindow *window, bool validation, const char *device_name);
void vk_base_destroy(vk_base &b);

struct vk_buffer {
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkDeviceAddress address = 0;
    void *mapped = nullptr;
    VkDeviceSize size = 0;
};
bool vk_buffer_create(const vk_base &b, VkDeviceSize size, VkBufferUsageFlags usage, bool host_visible,
                      vk_buffer &out);
void vk_buffer_destroy(const vk_base &b, vk_buffer &buf);

struct vk_image {
    VkImage image = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;
    VkFormat format = VK_FORMAT_UNDEFINED;
};
bool vk_image_create(const vk_base &b, uint32_t width, uint32_t height, VkFormat format, VkImageUsageFlags usage,
                     vk_image &out);
void vk_image_destroy(const vk_base &b, vk_image &img);

// One image layout transition with a full memory dependency between the given stages.
void vk_image_barrier(VkCommandBuffer cmd, VkImage image, VkImageLayout from, VkImageLayout to,
                      VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access, VkPipelineStageFlags2 dst_stage,
                      VkAccessFlags2 dst_access, VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT);

VkShaderModule vk_shader_module(const vk_base &b, const uint32_t *code, size_t bytes);

// Records into a one-time command buffer, submits and waits (set-up work only).
bool vk_submit_now(const vk_base &b, VkCommandPool pool, void (*record)(VkCommandBuffer, void *), void *user);
