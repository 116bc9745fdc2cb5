#include "vk_base.h"

#include <GLFW/glfw3.h>
#include <roma/context.h>

#include <cstdio>
#include <cstring>
#include <vector>

static VKAPI_ATTR VkBool32 VKAPI_CALL on_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                 VkDebugUtilsMessageTypeFlagsEXT, const VkDebugUtilsMessengerCallbackDataEXT *data,
                                                 void *user)
{
    if (severity & (VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT)) {
        ++static_cast<vk_base *>(user)->validation_messages;
        std::fprintf(stderr, "roma-viewer: validation: %s\n", data->pMessage);
    }
    return VK_FALSE;
}

static bool create_instance(vk_base &b, GLFWwindow *window, bool validation)
{
    std::vector<const char *> extensions;
    if (window) {
        uint32_t n = 0;
        const char **glfw = glfwGetRequiredInstanceExtensions(&n);
        extensions.assign(glfw, glfw + n);
    }
    if (validation)
        extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    roma_device_requirements req;
    roma_get_device_requirements(&req);
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "roma-viewer";
    app.apiVersion = req.api_version;
    const char *layer = "VK_LAYER_KHRONOS_validation";
    VkDebugUtilsMessengerCreateInfoEXT messenger{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    messenger.messageSeverity =
        VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT;
    // Correctness only: performance hints are not counted.
    messenger.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT;
    messenger.pfnUserCallback = on_message;
    messenger.pUserData = &b;
    VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    info.pApplicationInfo = &app;
    info.enabledLayerCount = validation ? 1u : 0u;
    info.ppEnabledLayerNames = &layer;
    info.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
    info.ppEnabledExtensionNames = extensions.data();
    if (vkCreateInstance(&info, nullptr, &b.instance) != VK_SUCCESS) {
        std::fprintf(stderr, "roma-viewer: cannot create a Vulkan 1.3 instance%s\n",
                     validation ? " with the validation layer (is vulkan-validationlayers installed?)" : "");
        return false;
    }
    if (validation) {
        auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(b.instance, "vkCreateDebugUtilsMessengerEXT"));
        if (!create || create(b.instance, &messenger, nullptr, &b.messenger) != VK_SUCCESS)
            return false;
    }
    if (window && glfwCreateWindowSurface(b.instance, window, nullptr, &b.surface) != VK_SUCCESS) {
        std::fprintf(stderr, "roma-viewer: cannot create a window surface\n");
        return false;
    }
    return true;
}

bool vk_base_create(vk_base &b, GLFWwindow *window, bool validation, const char *device_name)
{
    if (!create_instance(b, window, validation))
        return false;
    roma_device_requirements &req = b.requirements;
    roma_get_device_requirements(&req);
    uint32_t count = 0;
    vkEnumeratePhysicalDevices(b.instance, &count, nullptr);
    std::vector<VkPhysicalDevice> devices(count);
    vkEnumeratePhysicalDevices(b.instance, &count, devices.data());
    // A discrete or integrated GPU first, then anything (lavapipe), as libroma chooses.
    for (int pass = 0; pass < 2 && !b.physical; ++pass) {
        for (VkPhysicalDevice d : devices) {
            VkPhysicalDeviceProperties p;
            vkGetPhysicalDeviceProperties(d, &p);
            bool gpu = p.deviceType == VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU ||
                       p.deviceType == VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU;
            if (p.apiVersion < req.api_version || (pass == 0 && !gpu && !device_name))
                continue;
            if (device_name && !std::strstr(p.deviceName, device_name))
                continue;
            uint32_t nf = 0;
            vkGetPhysicalDeviceQueueFamilyProperties(d, &nf, nullptr);
            std::vector<VkQueueFamilyProperties> fp(nf);
            vkGetPhysicalDeviceQueueFamilyProperties(d, &nf, fp.data());
            for (uint32_t f = 0; f < nf && !b.physical; ++f) {
                VkBool32 present = VK_TRUE;
                if (b.surface)
                    vkGetPhysicalDeviceSurfaceSupportKHR(d, f, b.surface, &present);
                if ((fp[f].queueFlags & req.queue_flags) == req.queue_flags && fp[f].timestampValidBits && present) {
                    b.physical = d;
                    b.family = f;
                    b.properties = p;
                }
            }
            if (b.physical)
                break;
        }
    }
    if (!b.physical) {
        std::fprintf(stderr, "roma-viewer: no Vulkan 1.3 device%s%s with a graphics + compute queue%s\n",
                     device_name ? " named *" : "", device_name ? device_name : "",
                     b.surface ? " that can present to the window" : "");
        return false;
    }
    vkGetPhysicalDeviceMemoryProperties(b.physical, &b.memory);
    float priority = 1.0f;
    VkDeviceQueueCreateInfo queue{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queue.queueFamilyIndex = b.family;
    queue.queueCount = 1;
    queue.pQueuePriorities = &priority;
    std::vector<const char *> extensions(req.extensions, req.extensions + req.extension_count);
    if (b.surface)
        extensions.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
    VkDeviceCreateInfo info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    info.pNext = &req.features; // the chain: features -> 1.2 -> 1.3
    info.queueCreateInfoCount = 1;
    info.pQueueCreateInfos = &queue;
    info.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
    info.ppEnabledExtensionNames = extensions.data();
    if (vkCreateDevice(b.physical, &info, nullptr, &b.device) != VK_SUCCESS) {
        std::fprintf(stderr, "roma-viewer: cannot create the device on %s\n", b.properties.deviceName);
        return false;
    }
    vkGetDeviceQueue(b.device, b.family, 0, &b.queue);
    return true;
}

void vk_base_destroy(vk_base &b)
{
    if (b.device)
        vkDestroyDevice(b.device, nullptr);
    if (b.surface)
        vkDestroySurfaceKHR(b.instance, b.surface, nullptr);
    if (b.messenger) {
        auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(b.instance, "vkDestroyDebugUtilsMessengerEXT"));
        if (destroy)
            destroy(b.instance, b.messenger, nullptr);
    }
    if (b.instance)
        vkDestroyInstance(b.instance, nullptr);
    b.device = VK_NULL_HANDLE;
    b.surface = VK_NULL_HANDLE;
    b.messenger = VK_NULL_HANDLE;
    b.instance = VK_NULL_HANDLE;
}

static uint32_t memory_type(const vk_base &b, uint32_t bits, VkMemoryPropertyFlags want)
{
    for (uint32_t i = 0; i < b.memory.memoryTypeCount; ++i)
        if ((bits & (1u << i)) && (b.memory.memoryTypes[i].propertyFlags & want) == want)
            return i;
    return UINT32_MAX;
}

bool vk_buffer_create(const vk_base &b, VkDeviceSize size, VkBufferUsageFlags usage, bool host_visible,
                      vk_buffer &out)
{
    out = vk_buffer{};
    out.size = size;
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = size;
    info.usage = usage | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;
    if (vkCreateBuffer(b.device, &info, nullptr, &out.buffer) != VK_SUCCESS)
        return false;
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(b.device, out.buffer, &req);
    uint32_t type = memory_type(b, req.memoryTypeBits,
                                host_visible ? VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT
                                             : VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    VkMemoryAllocateFlagsInfo flags{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO};
    flags.flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT;
    VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    alloc.pNext = &flags;
    alloc.allocationSize = req.size;
    alloc.memoryTypeIndex = type;
    if (type == UINT32_MAX || vkAllocateMemory(b.device, &alloc, nullptr, &out.memory) != VK_SUCCESS ||
        vkBindBufferMemory(b.device, out.buffer, out.memory, 0) != VK_SUCCESS) {
        vk_buffer_destroy(b, out);
        return false;
    }
    if (host_visible && vkMapMemory(b.device, out.memory, 0, VK_WHOLE_SIZE, 0, &out.mapped) != VK_SUCCESS) {
        vk_buffer_destroy(b, out);
        return false;
    }
    VkBufferDeviceAddressInfo at{VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO};
    at.buffer = out.buffer;
    out.address = vkGetBufferDeviceAddress(b.device, &at);
    return true;
}

void vk_buffer_destroy(const vk_base &b, vk_buffer &buf)
{
    if (buf.buffer)
        vkDestroyBuffer(b.device, buf.buffer, nullptr);
    if (buf.memory)
        vkFreeMemory(b.device, buf.memory, nullptr);
    buf = vk_buffer{};
}

bool vk_image_create(const vk_base &b, uint32_t width, uint32_t height, VkFormat format, VkImageUsageFlags usage,
                     vk_image &out)
{
    out = vk_image{};
    out.format = format;
    VkImageCreateInfo ii{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    ii.imageType = VK_IMAGE_TYPE_2D;
    ii.format = format;
    ii.extent = {width, height, 1};
    ii.mipLevels = 1;
    ii.arrayLayers = 1;
    ii.samples = VK_SAMPLE_COUNT_1_BIT;
    ii.tiling = VK_IMAGE_TILING_OPTIMAL;
    ii.usage = usage;
    if (vkCreateImage(b.device, &ii, nullptr, &out.image) != VK_SUCCESS)
        return false;
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(b.device, out.image, &req);
    VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    alloc.allocationSize = req.size;
    alloc.memoryTypeIndex = memory_type(b, req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    bool depth = format == VK_FORMAT_D32_SFLOAT;
    VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    vi.viewType = VK_IMAGE_VIEW_TYPE_2D;
    vi.format = format;
    vi.subresourceRange = {static_cast<VkImageAspectFlags>(depth ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT),
                           0, 1, 0, 1};
    if (alloc.memoryTypeIndex == UINT32_MAX || vkAllocateMemory(b.device, &alloc, nullptr, &out.memory) != VK_SUCCESS ||
        vkBindImageMemory(b.device, out.image, out.memory, 0) != VK_SUCCESS) {
        vk_image_destroy(b, out);
        return false;
    }
    vi.image = out.image;
    if (vkCreateImageView(b.device, &vi, nullptr, &out.view) != VK_SUCCESS) {
        vk_image_destroy(b, out);
        return false;
    }
    return true;
}

void vk_image_destroy(const vk_base &b, vk_image &img)
{
    if (img.view)
        vkDestroyImageView(b.device, img.view, nullptr);
    if (img.image)
        vkDestroyImage(b.device, img.image, nullptr);
    if (img.memory)
        vkFreeMemory(b.device, img.memory, nullptr);
    img = vk_image{};
}

void vk_image_barrier(VkCommandBuffer cmd, VkImage image, VkImageLayout from, VkImageLayout to,
                      VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access, VkPipelineStageFlags2 dst_stage,
                      VkAccessFlags2 dst_access, VkImageAspectFlags aspect)
{
    VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    b.srcStageMask = src_stage;
    b.srcAccessMask = src_access;
    b.dstStageMask = dst_stage;
    b.dstAccessMask = dst_access;
    b.oldLayout = from;
    b.newLayout = to;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image;
    b.subresourceRange = {aspect, 0, 1, 0, 1};
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.imageMemoryBarrierCount = 1;
    dep.pImageMemoryBarriers = &b;
    vkCmdPipelineBarrier2(cmd, &dep);
}

VkShaderModule vk_shader_module(const vk_base &b, const uint32_t *code, size_t bytes)
{
    VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    info.codeSize = bytes;
    info.pCode = code;
    VkShaderModule m = VK_NULL_HANDLE;
    vkCreateShaderModule(b.device, &info, nullptr, &m);
    return m;
}

bool vk_submit_now(const vk_base &b, VkCommandPool pool, void (*record)(VkCommandBuffer, void *), void *user)
{
    VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    ai.commandPool = pool;
    ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    ai.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    if (vkAllocateCommandBuffers(b.device, &ai, &cmd) != VK_SUCCESS)
        return false;
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    bool ok = vkBeginCommandBuffer(cmd, &bi) == VK_SUCCESS;
    if (ok)
        record(cmd, user);
    ok = ok && vkEndCommandBuffer(cmd) == VK_SUCCESS;
    VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    si.commandBufferCount = 1;
    si.pCommandBuffers = &cmd;
    ok = ok && vkQueueSubmit(b.queue, 1, &si, VK_NULL_HANDLE) == VK_SUCCESS && vkQueueWaitIdle(b.queue) == VK_SUCCESS;
    vkFreeCommandBuffers(b.device, pool, 1, &cmd);
    return ok;
}
