// roma-viewer: the window's swapchain (FIFO, B8G8R8A8_UNORM where offered), the render
// pass the interface is drawn with on top of the picture, and their framebuffers.
#pragma once

#include "vk_base.h"

#include <vector>

struct swapchain {
    VkSwapchainKHR handle = VK_NULL_HANDLE;
    VkFormat format = VK_FORMAT_UNDEFINED;
    VkColorSpaceKHR color_space = VK_COLOR_SPACE_SRGB_NONLINEAR_KHR;
    VkExtent2D extent{};
    uint32_t min_image_count = 2;
    std::vector<VkImage> images;
    std::vector<VkImageView> views;
    std::vector<VkFramebuffer> framebuffers;
    std::vector<VkSemaphore> rendered; // one per image: presentation waits on it
    VkRenderPass ui_pass = VK_NULL_HANDLE;
};

// (Re)creates for the window's framebuffer size; the device must be idle. false with a
// zero extent means a minimised window: try again later.
bool swapchain_create(const vk_base &b, swapchain &s, uint32_t width, uint32_t height);
void swapchain_destroy(const vk_base &b, swapchain &s);
