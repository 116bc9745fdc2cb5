#include "swapchain.h"

#include <algorithm>
#include <cstdio>

static void destroy_images(const vk_base &b, swapchain &s)
{
    for (VkFramebuffer f : s.framebuffers)
        vkDestroyFramebuffer(b.device, f, nullptr);
    for (VkImageView v : s.views)
        vkDestroyImageView(b.device, v, nullptr);
    for (VkSemaphore sem : s.rendered)
        vkDestroySemaphore(b.device, sem, nullptr);
    s.framebuffers.clear();
    s.views.clear();
    s.rendered.clear();
    s.images.clear();
}

static bool create_ui_pass(const vk_base &b, swapchain &s)
{
    // The picture is blitted in first (TRANSFER_DST); the interface is drawn over it.
    VkAttachmentDescription a{};
    a.format = s.format;
    a.samples = VK_SAMPLE_COUNT_1_BIT;
    a.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
    a.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    a.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    a.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    a.initialLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    a.finalLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
    VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkSubpassDescription sub{};
    sub.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    sub.colorAttachmentCount = 1;
    sub.pColorAttachments = &ref;
    VkSubpassDependency dep{};
    dep.srcSubpass = VK_SUBPASS_EXTERNAL;
    dep.dstSubpass = 0;
    dep.srcStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
    dep.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    dep.dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    dep.dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    VkRenderPassCreateInfo rp{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
    rp.attachmentCount = 1;
    rp.pAttachments = &a;
    rp.subpassCount = 1;
    rp.pSubpasses = &sub;
    rp.dependencyCount = 1;
    rp.pDependencies = &dep;
    return vkCreateRenderPass(b.device, &rp, nullptr, &s.ui_pass) == VK_SUCCESS;
}

bool swapchain_create(const vk_base &b, swapchain &s, uint32_t width, uint32_t height)
{
    VkSurfaceCapabilitiesKHR caps;
    if (vkGetPhysicalDeviceSurfaceCapabilitiesKHR(b.physical, b.surface, &caps) != VK_SUCCESS)
        return false;
    VkExtent2D extent = caps.currentExtent;
    if (extent.width == UINT32_MAX)
        extent = {std::clamp(width, caps.minImageExtent.width, caps.maxImageExtent.width),
                  std::clamp(height, caps.minImageExtent.height, caps.maxImageExtent.height)};
    if (extent.width == 0 || extent.height == 0)
        return false; // minimised
    if (!s.ui_pass || s.format == VK_FORMAT_UNDEFINED) {
        uint32_t n = 0;
        vkGetPhysicalDeviceSurfaceFormatsKHR(b.physical, b.surface, &n, nullptr);
        std::vector<VkSurfaceFormatKHR> formats(n);
        vkGetPhysicalDeviceSurfaceFormatsKHR(b.physical, b.surface, &n, formats.data());
        if (formats.empty())
            return false;
        // UNORM: the picture is sRGB-encoded already, and the interface's colours too.
        VkSurfaceFormatKHR chosen = formats[0];
        bool unorm = false;
        for (const VkSurfaceFormatKHR &f : formats)
            if (!unorm && (f.format == VK_FORMAT_B8G8R8A8_UNORM || f.format == VK_FORMAT_R8G8B8A8_UNORM))
                chosen = f, unorm = true;
        if (!unorm)
            std::fprintf(stderr, "roma-viewer: the window offers no 8-bit UNORM format; colours may look off\n");
        s.format = chosen.format;
        s.color_space = chosen.colorSpace;
        if (!create_ui_pass(b, s))
            return false;
    }
    // The picture is blitted into the swapchain image.
    if (!(caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_DST_BIT)) {
        std::fprintf(stderr, "roma-viewer: the window's images cannot be written by a transfer (blit)\n");
        return false;
    }
    VkSwapchainKHR old = s.handle;
    destroy_images(b, s);
    s.min_image_count = std::max(2u, caps.minImageCount);
    VkSwapchainCreateInfoKHR ci{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
    ci.surface = b.surface;
    ci.minImageCount = caps.maxImageCount ? std::min(s.min_image_count + 1, caps.maxImageCount) : s.min_image_count + 1;
    ci.imageFormat = s.format;
    ci.imageColorSpace = s.color_space;
    ci.imageExtent = extent;
    ci.imageArrayLayers = 1;
    ci.imageUsage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    ci.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
    ci.preTransform = caps.currentTransform;
    ci.compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
    ci.presentMode = VK_PRESENT_MODE_FIFO_KHR; // always there; no tearing
    ci.clipped = VK_TRUE;
    ci.oldSwapchain = old;
    VkResult r = vkCreateSwapchainKHR(b.device, &ci, nullptr, &s.handle);
    if (old)
        vkDestroySwapchainKHR(b.device, old, nullptr);
    if (r != VK_SUCCESS) {
        s.handle = VK_NULL_HANDLE;
        return false;
    }
    s.extent = extent;
    uint32_t n = 0;
    vkGetSwapchainImagesKHR(b.device, s.handle, &n, nullptr);
    s.images.resize(n);
    vkGetSwapchainImagesKHR(b.device, s.handle, &n, s.images.data());
    for (VkImage img : s.images) {
        VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
        vi.image = img;
        vi.viewType = VK_IMAGE_VIEW_TYPE_2D;
        vi.format = s.format;
        vi.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        VkImageView view = VK_NULL_HANDLE;
        if (vkCreateImageView(b.device, &vi, nullptr, &view) != VK_SUCCESS)
            return false;
        s.views.push_back(view);
        VkFramebufferCreateInfo fi{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
        fi.renderPass = s.ui_pass;
        fi.attachmentCount = 1;
        fi.pAttachments = &view;
        fi.width = extent.width;
        fi.height = extent.height;
        fi.layers = 1;
        VkFramebuffer fb = VK_NULL_HANDLE;
        if (vkCreateFramebuffer(b.device, &fi, nullptr, &fb) != VK_SUCCESS)
            return false;
        s.framebuffers.push_back(fb);
        VkSemaphoreCreateInfo si{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
        VkSemaphore sem = VK_NULL_HANDLE;
        if (vkCreateSemaphore(b.device, &si, nullptr, &sem) != VK_SUCCESS)
            return false;
        s.rendered.push_back(sem);
    }
    return true;
}

void swapchain_destroy(const vk_base &b, swapchain &s)
{
    destroy_images(b, s);
    if (s.handle)
        vkDestroySwapchainKHR(b.device, s.handle, nullptr);
    if (s.ui_pass)
        vkDestroyRenderPass(b.device, s.ui_pass, nullptr);
    s = swapchain{};
}
