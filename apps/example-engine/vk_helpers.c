/* The example engine's Vulkan plumbing (vk_helpers.h). */
#include "vk_helpers.h"

#include <stdio.h>
#include <string.h>

static VKAPI_ATTR VkBool32 VKAPI_CALL on_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                 VkDebugUtilsMessageTypeFlagsEXT types,
                                                 const VkDebugUtilsMessengerCallbackDataEXT *data, void *user)
{
    (void)severity, (void)types;
    ((engine *)user)->validation_messages++;
    fprintf(stderr, "validation: %s\n", data->pMessage);
    return VK_FALSE;
}

static int create_instance(engine *e, int validation)
{
    VkApplicationInfo app = {.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO,
                             .pApplicationName = "example-engine",
                             .apiVersion = VK_API_VERSION_1_3};
    const char *layer = "VK_LAYER_KHRONOS_validation";
    const char *extension = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
    VkDebugUtilsMessengerCreateInfoEXT messenger = {
        .sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT,
        .messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT,
        .messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT,
        .pfnUserCallback = on_message,
        .pUserData = e};
    const VkValidationFeatureEnableEXT sync = VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
    VkValidationFeaturesEXT features = {.sType = VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT,
                                        .pNext = &messenger,
                                        .enabledValidationFeatureCount = 1,
                                        .pEnabledValidationFeatures = &sync};
    VkInstanceCreateInfo info = {.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO,
                                 .pNext = validation == 2 ? (const void *)&features
                                          : validation ? (const void *)&messenger : NULL,
                                 .pApplicationInfo = &app,
                                 .enabledLayerCount = validation ? 1u : 0u,
                                 .ppEnabledLayerNames = &layer,
                                 .enabledExtensionCount = validation ? 1u : 0u,
                                 .ppEnabledExtensionNames = &extension};
    if (vkCreateInstance(&info, NULL, &e->instance) != VK_SUCCESS) {
        fprintf(stderr, "example-engine: vkCreateInstance failed%s\n",
                validation ? " (is vulkan-validationlayers installed?)" : "");
        return 0;
    }
    if (validation) {
        PFN_vkCreateDebugUtilsMessengerEXT create =
            (PFN_vkCreateDebugUtilsMessengerEXT)vkGetInstanceProcAddr(e->instance, "vkCreateDebugUtilsMessengerEXT");
        if (!create || create(e->instance, &messenger, NULL, &e->messenger) != VK_SUCCESS)
            return 0;
    }
    return 1;
}

/* The first Vulkan 1.3 device with a graphics + compute queue that has timestamps, created
 * with exactly what libroma lists. */
static int create_device(engine *e, roma_device_requirements *req)
{
    uint32_t count = 8;
    VkPhysicalDevice devices[8];
    if (vkEnumeratePhysicalDevices(e->instance, &count, devices) < 0)
        return 0;
    roma_get_device_requirements(req);
    for (uint32_t d = 0; d < count && !e->physical; ++d) {
        VkPhysicalDeviceProperties props;
        vkGetPhysicalDeviceProperties(devices[d], &props);
        if (props.apiVersion < req->api_version)
            continue;
        uint32_t families = 16;
        VkQueueFamilyProperties fp[16];
        vkGetPhysicalDeviceQueueFamilyProperties(devices[d], &families, fp);
        for (uint32_t f = 0; f < families && !e->physical; ++f)
            if ((fp[f].queueFlags & req->queue_flags) == req->queue_flags && fp[f].timestampValidBits) {
                e->physical = devices[d];
                e->family = f;
            }
    }
    if (!e->physical) {
        fprintf(stderr, "example-engine: no Vulkan 1.3 device with a graphics + compute queue\n");
        return 0;
    }
    float priority = 1.0f;
    VkDeviceQueueCreateInfo queue = {.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO,
                                     .queueFamilyIndex = e->family,
                                     .queueCount = 1,
                                     .pQueuePriorities = &priority};
    VkDeviceCreateInfo info = {.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO,
                               .pNext = &req->features,
                               .queueCreateInfoCount = 1,
                               .pQueueCreateInfos = &queue,
                               .enabledExtensionCount = req->extension_count,
                               .ppEnabledExtensionNames = req->extensions};
    if (vkCreateDevice(e->physical, &info, NULL, &e->device) != VK_SUCCESS)
        return 0;
    vkGetDeviceQueue(e->device, e->family, 0, &e->queue);
    return 1;
}

int engine_create(engine *e, int validation, roma_device_requirements *req)
{
    return create_instance(e, validation) && create_device(e, req);
}

void engine_destroy(engine *e)
{
    if (e->device)
        vkDestroyDevice(e->device, NULL);
    if (e->messenger) {
        PFN_vkDestroyDebugUtilsMessengerEXT destroy =
            (PFN_vkDestroyDebugUtilsMessengerEXT)vkGetInstanceProcAddr(e->instance, "vkDestroyDebugUtilsMessengerEXT");
        if (destroy)
            destroy(e->instance, e->messenger, NULL);
    }
    if (e->instance)
        vkDestroyInstance(e->instance, NULL);
}

int buffer_create(const engine *e, VkDeviceSize size, int host_visible, buffer *out)
{
    memset(out, 0, sizeof *out);
    VkBufferCreateInfo info = {.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO,
                               .size = size,
                               .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                        VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT |
                                        VK_BUFFER_USAGE_TRANSFER_DST_BIT};
    if (vkCreateBuffer(e->device, &info, NULL, &out->buffer) != VK_SUCCESS)
        return 0;
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(e->device, out->buffer, &req);
    VkPhysicalDeviceMemoryProperties props;
    vkGetPhysicalDeviceMemoryProperties(e->physical, &props);
    VkMemoryPropertyFlags want = host_visible
                                     ? VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT
                                     : VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
    uint32_t type = UINT32_MAX;
    for (uint32_t i = 0; i < props.memoryTypeCount && type == UINT32_MAX; ++i)
        if ((req.memoryTypeBits & (1u << i)) && (props.memoryTypes[i].propertyFlags & want) == want)
            type = i;
    VkMemoryAllocateFlagsInfo flags = {.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO,
                                       .flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT};
    VkMemoryAllocateInfo alloc = {.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO,
                                  .pNext = &flags,
                                  .allocationSize = req.size,
                                  .memoryTypeIndex = type};
    if (type == UINT32_MAX || vkAllocateMemory(e->device, &alloc, NULL, &out->memory) != VK_SUCCESS ||
        vkBindBufferMemory(e->device, out->buffer, out->memory, 0) != VK_SUCCESS)
        return 0;
    if (host_visible && vkMapMemory(e->device, out->memory, 0, VK_WHOLE_SIZE, 0, &out->mapped) != VK_SUCCESS)
        return 0;
    VkBufferDeviceAddressInfo at = {.sType = VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO, .buffer = out->buffer};
    out->address = vkGetBufferDeviceAddress(e->device, &at);
    return 1;
}

void buffer_destroy(const engine *e, buffer *b)
{
    if (b->buffer)
        vkDestroyBuffer(e->device, b->buffer, NULL);
    if (b->memory)
        vkFreeMemory(e->device, b->memory, NULL);
}

int image_create(const engine *e, uint32_t width, uint32_t height, VkFormat format, VkImageUsageFlags usage,
                 image *out)
{
    memset(out, 0, sizeof *out);
    VkImageCreateInfo ii = {.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO, .imageType = VK_IMAGE_TYPE_2D,
                            .format = format, .extent = {width, height, 1}, .mipLevels = 1, .arrayLayers = 1,
                            .samples = VK_SAMPLE_COUNT_1_BIT, .tiling = VK_IMAGE_TILING_OPTIMAL, .usage = usage};
    if (vkCreateImage(e->device, &ii, NULL, &out->image) != VK_SUCCESS)
        return 0;
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(e->device, out->image, &req);
    VkPhysicalDeviceMemoryProperties props;
    vkGetPhysicalDeviceMemoryProperties(e->physical, &props);
    uint32_t type = UINT32_MAX;
    for (uint32_t i = 0; i < props.memoryTypeCount && type == UINT32_MAX; ++i)
        if (req.memoryTypeBits & (1u << i))
            type = i;
    VkMemoryAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, .allocationSize = req.size,
                               .memoryTypeIndex = type};
    if (vkAllocateMemory(e->device, &ai, NULL, &out->memory) != VK_SUCCESS ||
        vkBindImageMemory(e->device, out->image, out->memory, 0) != VK_SUCCESS)
        return 0;
    VkImageViewCreateInfo vi = {.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO, .image = out->image,
                                .viewType = VK_IMAGE_VIEW_TYPE_2D, .format = format,
                                .subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1}};
    return vkCreateImageView(e->device, &vi, NULL, &out->view) == VK_SUCCESS;
}

void image_destroy(const engine *e, image *im)
{
    if (im->view)
        vkDestroyImageView(e->device, im->view, NULL);
    if (im->image)
        vkDestroyImage(e->device, im->image, NULL);
    if (im->memory)
        vkFreeMemory(e->device, im->memory, NULL);
}

int pipeline_create(const engine *e, const char *name, uint32_t push_size, VkDescriptorSetLayout set_layout,
                           VkPipelineLayout *layout, VkPipeline *pipeline)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", EXAMPLE_SPV_DIR, name);
    FILE *f = fopen(path, "rb");
    if (!f) {
        fprintf(stderr, "example-engine: cannot open %s\n", path);
        return 0;
    }
    static uint32_t code[65536];
    size_t bytes = fread(code, 1, sizeof code, f);
    fclose(f);
    VkShaderModuleCreateInfo mi = {.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO, .codeSize = bytes,
                                   .pCode = code};
    VkShaderModule module;
    if (vkCreateShaderModule(e->device, &mi, NULL, &module) != VK_SUCCESS)
        return 0;
    VkPushConstantRange range = {VK_SHADER_STAGE_COMPUTE_BIT, 0, push_size};
    VkPipelineLayoutCreateInfo li = {.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO,
                                     .setLayoutCount = set_layout ? 1u : 0u,
                                     .pSetLayouts = &set_layout,
                                     .pushConstantRangeCount = 1,
                                     .pPushConstantRanges = &range};
    /* roma/trace.glsl's division rule, as libroma's own pipelines have it
     * (roma_context_info.corrected_division); shaders that do not include it ignore it. */
    VkBool32 corrected = e->corrected_division;
    VkSpecializationMapEntry entry = {ROMA_CORRECTED_DIVISION_CONSTANT_ID, 0, sizeof corrected};
    VkSpecializationInfo spec = {1, &entry, sizeof corrected, &corrected};
    VkComputePipelineCreateInfo pi = {
        .sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO,
        .stage = {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
                  .stage = VK_SHADER_STAGE_COMPUTE_BIT,
                  .module = module,
                  .pName = "main",
                  .pSpecializationInfo = &spec}};
    int ok = vkCreatePipelineLayout(e->device, &li, NULL, layout) == VK_SUCCESS;
    pi.layout = *layout;
    ok = ok && vkCreateComputePipelines(e->device, VK_NULL_HANDLE, 1, &pi, NULL, pipeline) == VK_SUCCESS;
    vkDestroyShaderModule(e->device, module, NULL);
    return ok;
}

int storage_image_set_create(const engine *e, uint32_t count, const VkImageView *views, VkDescriptorSetLayout *layout,
                             VkDescriptorPool *pool, VkDescriptorSet *set)
{
    VkDescriptorSetLayoutBinding b[4];
    VkDescriptorImageInfo ii[4];
    VkWriteDescriptorSet w[4];
    if (count > 4)
        return 0;
    for (uint32_t i = 0; i < count; ++i)
        b[i] = (VkDescriptorSetLayoutBinding){i, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, VK_SHADER_STAGE_COMPUTE_BIT,
                                              NULL};
    VkDescriptorSetLayoutCreateInfo sli = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO,
                                           .bindingCount = count, .pBindings = b};
    VkDescriptorPoolSize size = {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, count};
    VkDescriptorPoolCreateInfo dpi = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO, .maxSets = 1,
                                      .poolSizeCount = 1, .pPoolSizes = &size};
    if (vkCreateDescriptorSetLayout(e->device, &sli, NULL, layout) != VK_SUCCESS ||
        vkCreateDescriptorPool(e->device, &dpi, NULL, pool) != VK_SUCCESS)
        return 0;
    VkDescriptorSetAllocateInfo dai = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO,
                                       .descriptorPool = *pool, .descriptorSetCount = 1, .pSetLayouts = layout};
    if (vkAllocateDescriptorSets(e->device, &dai, set) != VK_SUCCESS)
        return 0;
    for (uint32_t i = 0; i < count; ++i) {
        ii[i] = (VkDescriptorImageInfo){VK_NULL_HANDLE, views[i], VK_IMAGE_LAYOUT_GENERAL};
        w[i] = (VkWriteDescriptorSet){.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, .dstSet = *set,
                                      .dstBinding = i, .descriptorCount = 1,
                                      .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, .pImageInfo = &ii[i]};
    }
    vkUpdateDescriptorSets(e->device, count, w, 0, NULL);
    return 1;
}

int images_to_general(const engine *e, VkCommandBuffer cmd, uint32_t count, const VkImage *images)
{
    VkImageMemoryBarrier2 to_general[8];
    if (count > 8)
        return 0;
    VkCommandBufferBeginInfo once = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                     .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
    vkBeginCommandBuffer(cmd, &once);
    for (uint32_t i = 0; i < count; ++i)
        to_general[i] = (VkImageMemoryBarrier2){
            .sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2, .dstStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
            .dstAccessMask = VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, .oldLayout = VK_IMAGE_LAYOUT_UNDEFINED,
            .newLayout = VK_IMAGE_LAYOUT_GENERAL, .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
            .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED, .image = images[i],
            .subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1}};
    VkDependencyInfo dep = {.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO, .imageMemoryBarrierCount = count,
                            .pImageMemoryBarriers = to_general};
    vkCmdPipelineBarrier2(cmd, &dep);
    vkEndCommandBuffer(cmd);
    VkSubmitInfo si = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO, .commandBufferCount = 1, .pCommandBuffers = &cmd};
    return vkQueueSubmit(e->queue, 1, &si, VK_NULL_HANDLE) == VK_SUCCESS && vkQueueWaitIdle(e->queue) == VK_SUCCESS;
}

void memory_barrier(VkCommandBuffer cmd, VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access,
                           VkPipelineStageFlags2 dst_stage, VkAccessFlags2 dst_access)
{
    VkMemoryBarrier2 b = {.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER_2, .srcStageMask = src_stage,
                          .srcAccessMask = src_access, .dstStageMask = dst_stage, .dstAccessMask = dst_access};
    VkDependencyInfo d = {.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO, .memoryBarrierCount = 1, .pMemoryBarriers = &b};
    vkCmdPipelineBarrier2(cmd, &d);
}

