#include "study/hw_ray_tracing.h"
#include "study/study_shaders.h"

#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "util/log.h"
#include "vulkan/upload.h"
#include "vulkan/vk_internal.h"

static const char *const rt_extensions[3] = {VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME,
                                             VK_KHR_RAY_TRACING_PIPELINE_EXTENSION_NAME,
                                             VK_KHR_DEFERRED_HOST_OPERATIONS_EXTENSION_NAME};

struct roma_hwrt_device {
    VkInstance instance;
    VkDebugUtilsMessengerEXT messenger;
    VkPhysicalDevice physical_device;
    VkDevice device;
    VkQueue queue;
    uint32_t queue_family;
    roma_device_requirements req; /* its chain, extended, is what the device was created with */
    VkPhysicalDeviceAccelerationStructureFeaturesKHR as_features;
    VkPhysicalDeviceRayTracingPipelineFeaturesKHR rt_features;
    VkPhysicalDevicePipelineExecutablePropertiesFeaturesKHR statistics_features;
    int statistics; /* VK_KHR_pipeline_executable_properties enabled */
    roma_external_device external;
    unsigned validation_messages;
};

/* A ray-tracing pipeline of three groups (ray generation, miss, hit) and its shader binding
 * table. */
typedef struct hwrt_program {
    VkPipeline pipeline;
    roma_buffer sbt;
    VkStridedDeviceAddressRegionKHR raygen, miss, hit, callable;
} hwrt_program;

struct roma_hwrt {
    roma_context *ctx;
    PFN_vkCreateAccelerationStructureKHR create_as;
    PFN_vkDestroyAccelerationStructureKHR destroy_as;
    PFN_vkGetAccelerationStructureBuildSizesKHR build_sizes;
    PFN_vkGetAccelerationStructureDeviceAddressKHR as_address;
    PFN_vkCmdBuildAccelerationStructuresKHR cmd_build;
    PFN_vkCreateRayTracingPipelinesKHR create_pipelines;
    PFN_vkGetRayTracingShaderGroupHandlesKHR group_handles;
    PFN_vkCmdTraceRaysKHR cmd_trace;
    roma_buffer positions, indices, instance, blas_buffer, tlas_buffer, scratch;
    VkAccelerationStructureKHR blas, tlas;
    VkDeviceAddress scratch_address; /* aligned to minAccelerationStructureScratchOffsetAlignment */
    uint32_t vertex_count, triangle_count;
    VkDescriptorSetLayout set_layout;
    VkDescriptorPool pool;
    VkDescriptorSet set;
    VkPipelineLayout layout; /* both programs': the scene's structure, either push block */
    hwrt_program rays;       /* batches of roma_ray (hwrt_rays.rgen) */
    hwrt_program layers;     /* the stochastic depth map (hwrt_depth_layers.*) */
    VkPhysicalDeviceRayTracingPipelinePropertiesKHR rt; /* read once: launches and binding tables */
    uint32_t max_launch_width, max_launch_invocations;
};

typedef struct hwrt_push {
    VkDeviceAddress rays, hits; /* uvec2 in the shader */
    uint32_t count, closest, base;
} hwrt_push;

/* hwrt_depth_layers.rgen's push block (std430: the vec4s from byte 32). */
typedef struct hwrt_depth_push {
    VkDeviceAddress pixels, positions, indices;
    uint32_t pad[2];
    float eye[4], forward[4], right[4], up[4];
    uint32_t config[4];
} hwrt_depth_push;
_Static_assert(sizeof(hwrt_depth_push) == 112 && offsetof(hwrt_depth_push, eye) == 32 &&
                   offsetof(hwrt_depth_push, config) == 96,
               "hwrt_depth_layers.rgen's push block");

static void say(char *why, size_t size, const char *fmt, ...)
{
    if (!why || !size)
        return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(why, size, fmt, ap);
    va_end(ap);
}

static VKAPI_ATTR VkBool32 VKAPI_CALL on_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                 VkDebugUtilsMessageTypeFlagsEXT type,
                                                 const VkDebugUtilsMessengerCallbackDataEXT *data, void *user)
{
    roma_hwrt_device *d = user;
    (void)type;
    /* Errors count, as libroma's own validation counts them; warnings are shown. */
    if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT)
        ++d->validation_messages;
    fprintf(stderr, "hardware ray tracing, %s: %s\n",
            severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT ? "error" : "warning",
            data && data->pMessage ? data->pMessage : "?");
    return VK_FALSE;
}

/* Whether pd offers the extension `name`. */
static int has_extension(VkPhysicalDevice pd, const char *name)
{
    uint32_t n = 0;
    vkEnumerateDeviceExtensionProperties(pd, NULL, &n, NULL);
    VkExtensionProperties *props = calloc(n ? n : 1, sizeof *props);
    int found = 0;
    if (props && vkEnumerateDeviceExtensionProperties(pd, NULL, &n, props) >= 0)
        for (uint32_t i = 0; i < n && !found; ++i)
            found = strcmp(props[i].extensionName, name) == 0;
    free(props);
    return found;
}

static int has_extensions(VkPhysicalDevice pd, const char **missing)
{
    for (int e = 0; e < 3; ++e)
        if (!has_extension(pd, rt_extensions[e])) {
            *missing = rt_extensions[e];
            return 0;
        }
    return 1;
}

/* A queue family with graphics, compute and timestamps, or UINT32_MAX. */
static uint32_t pick_queue_family(VkPhysicalDevice pd)
{
    uint32_t n = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &n, NULL);
    VkQueueFamilyProperties props[16];
    n = n > 16 ? 16 : n;
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &n, props);
    for (uint32_t i = 0; i < n; ++i)
        if ((props[i].queueFlags & (VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT)) ==
                (VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT) &&
            props[i].timestampValidBits > 0)
            return i;
    return UINT32_MAX;
}

static int name_matches(const char *name, const char *filter)
{
    if (!filter || !*filter)
        return 1;
    const size_t fl = strlen(filter);
    for (const char *p = name; *p; ++p)
        if (strncasecmp(p, filter, fl) == 0)
            return 1;
    return 0;
}

/* The device to use: GPUs first, each with the extensions, the features and a queue. */
static roma_result pick_device(roma_hwrt_device *d, const char *device_name, char *why, size_t why_size)
{
    uint32_t n = 0;
    vkEnumeratePhysicalDevices(d->instance, &n, NULL);
    VkPhysicalDevice list[16];
    n = n > 16 ? 16 : n;
    if (n == 0 || vkEnumeratePhysicalDevices(d->instance, &n, list) < 0) {
        say(why, why_size, "no Vulkan device");
        return ROMA_ERROR_NO_VULKAN;
    }
    say(why, why_size, "no device matches \"%s\"", device_name ? device_name : "");
    for (int pass = 0; pass < 2; ++pass)
        for (uint32_t i = 0; i < n; ++i) {
            VkPhysicalDeviceProperties p;
            vkGetPhysicalDeviceProperties(list[i], &p);
            const int gpu = p.deviceType == VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU ||
                            p.deviceType == VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU;
            if ((pass == 0) != gpu || !name_matches(p.deviceName, device_name))
                continue;
            const char *missing = NULL;
            if (p.apiVersion < VK_API_VERSION_1_3) {
                say(why, why_size, "%s offers Vulkan %u.%u, not 1.3", p.deviceName, VK_API_VERSION_MAJOR(p.apiVersion),
                    VK_API_VERSION_MINOR(p.apiVersion));
                continue;
            }
            if (!has_extensions(list[i], &missing)) {
                say(why, why_size, "%s offers no %s", p.deviceName, missing);
                continue;
            }
            VkPhysicalDeviceRayTracingPipelineFeaturesKHR rt = {
                .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_TRACING_PIPELINE_FEATURES_KHR};
            VkPhysicalDeviceAccelerationStructureFeaturesKHR as = {
                .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR, .pNext = &rt};
            VkPhysicalDeviceVulkan13Features f13 = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES,
                                                    .pNext = &as};
            VkPhysicalDeviceVulkan12Features f12 = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES,
                                                    .pNext = &f13};
            VkPhysicalDeviceFeatures2 f = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, .pNext = &f12};
            vkGetPhysicalDeviceFeatures2(list[i], &f);
            const uint32_t family = pick_queue_family(list[i]);
            if (!as.accelerationStructure || !rt.rayTracingPipeline || !f12.bufferDeviceAddress ||
                !f12.hostQueryReset || !f13.dynamicRendering || !f13.synchronization2 ||
                !f.features.fragmentStoresAndAtomics || family == UINT32_MAX) {
                say(why, why_size, "%s lacks a feature or queue libroma or the ray-tracing pipeline needs",
                    p.deviceName);
                continue;
            }
            d->physical_device = list[i];
            d->queue_family = family;
            /* The trace ladder's pipeline statistics (registers, spills), where offered. */
            if (has_extension(list[i], VK_KHR_PIPELINE_EXECUTABLE_PROPERTIES_EXTENSION_NAME)) {
                VkPhysicalDevicePipelineExecutablePropertiesFeaturesKHR pe = {
                    .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PIPELINE_EXECUTABLE_PROPERTIES_FEATURES_KHR};
                VkPhysicalDeviceFeatures2 f2 = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, .pNext = &pe};
                vkGetPhysicalDeviceFeatures2(list[i], &f2);
                d->statistics = pe.pipelineExecutableInfo != VK_FALSE;
            }
            d->req.features.features.geometryShader = f.features.geometryShader;
            return ROMA_SUCCESS;
        }
    return ROMA_ERROR_MISSING_FEATURE;
}

static roma_result create_instance(roma_hwrt_device *d, int validation, char *why, size_t why_size)
{
    const char *layers[1] = {"VK_LAYER_KHRONOS_validation"};
    const char *extensions[1] = {VK_EXT_DEBUG_UTILS_EXTENSION_NAME};
    VkApplicationInfo app = {.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO,
                             .pApplicationName = "libroma hardware ray-tracing baseline",
                             .apiVersion = VK_API_VERSION_1_3};
    /* The same messenger for the instance's creation and destruction. */
    const VkDebugUtilsMessengerCreateInfoEXT m = {
        .sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT,
        .messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT,
        .messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT,
        .pfnUserCallback = on_message,
        .pUserData = d};
    VkInstanceCreateInfo info = {.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO,
                                 .pNext = validation ? &m : NULL,
                                 .pApplicationInfo = &app,
                                 .enabledLayerCount = validation ? 1u : 0u,
                                 .ppEnabledLayerNames = layers,
                                 .enabledExtensionCount = validation ? 1u : 0u,
                                 .ppEnabledExtensionNames = extensions};
    VkResult vr = vkCreateInstance(&info, NULL, &d->instance);
    if (vr != VK_SUCCESS) {
        say(why, why_size, "vkCreateInstance: %s%s", roma_vk_result_string(vr),
            validation ? " (with the validation layer)" : "");
        return vr == VK_ERROR_LAYER_NOT_PRESENT ? ROMA_ERROR_MISSING_FEATURE : ROMA_ERROR_NO_VULKAN;
    }
    if (validation) {
        PFN_vkCreateDebugUtilsMessengerEXT create_messenger =
            (PFN_vkCreateDebugUtilsMessengerEXT)vkGetInstanceProcAddr(d->instance, "vkCreateDebugUtilsMessengerEXT");
        if (!create_messenger || create_messenger(d->instance, &m, NULL, &d->messenger) != VK_SUCCESS) {
            say(why, why_size, "vkCreateDebugUtilsMessengerEXT failed");
            return ROMA_ERROR_MISSING_FEATURE;
        }
    }
    return ROMA_SUCCESS;
}

roma_result roma_hwrt_device_create(const char *device_name, int validation, roma_hwrt_device **out, char *why,
                                    size_t why_size)
{
    say(why, why_size, "");
    if (!out)
        return ROMA_ERROR_INVALID_ARGUMENT;
    *out = NULL;
    roma_hwrt_device *d = calloc(1, sizeof *d);
    if (!d) {
        say(why, why_size, "out of host memory");
        return ROMA_ERROR_OUT_OF_HOST_MEMORY;
    }
    roma_get_device_requirements(&d->req);
    roma_result r = create_instance(d, validation, why, why_size);
    if (r == ROMA_SUCCESS)
        r = pick_device(d, device_name, why, why_size);
    if (r == ROMA_SUCCESS) {
        /* libroma's chain (features -> 1.2 -> 1.3), then the ray-tracing features. */
        d->rt_features = (VkPhysicalDeviceRayTracingPipelineFeaturesKHR){
            .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_TRACING_PIPELINE_FEATURES_KHR,
            .rayTracingPipeline = VK_TRUE};
        d->as_features = (VkPhysicalDeviceAccelerationStructureFeaturesKHR){
            .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR,
            .pNext = &d->rt_features,
            .accelerationStructure = VK_TRUE};
        d->req.features13.pNext = &d->as_features;
        d->statistics_features = (VkPhysicalDevicePipelineExecutablePropertiesFeaturesKHR){
            .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PIPELINE_EXECUTABLE_PROPERTIES_FEATURES_KHR,
            .pipelineExecutableInfo = VK_TRUE};
        if (d->statistics)
            d->rt_features.pNext = &d->statistics_features;
        const char **extensions = calloc(d->req.extension_count + 4, sizeof *extensions);
        uint32_t count = 0;
        for (uint32_t i = 0; extensions && i < d->req.extension_count; ++i)
            extensions[count++] = d->req.extensions[i];
        for (int i = 0; extensions && i < 3; ++i)
            extensions[count++] = rt_extensions[i];
        if (extensions && d->statistics)
            extensions[count++] = VK_KHR_PIPELINE_EXECUTABLE_PROPERTIES_EXTENSION_NAME;
        float priority = 1.0f;
        VkDeviceQueueCreateInfo queue = {.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO,
                                         .queueFamilyIndex = d->queue_family,
                                         .queueCount = 1,
                                         .pQueuePriorities = &priority};
        VkDeviceCreateInfo info = {.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO,
                                   .pNext = &d->req.features,
                                   .queueCreateInfoCount = 1,
                                   .pQueueCreateInfos = &queue,
                                   .enabledExtensionCount = count,
                                   .ppEnabledExtensionNames = extensions};
        VkResult vr = extensions ? vkCreateDevice(d->physical_device, &info, NULL, &d->device)
                                 : VK_ERROR_OUT_OF_HOST_MEMORY;
        free(extensions);
        if (vr != VK_SUCCESS) {
            say(why, why_size, "vkCreateDevice with the ray-tracing extensions: %s", roma_vk_result_string(vr));
            r = ROMA_ERROR_MISSING_FEATURE;
        }
    }
    if (r != ROMA_SUCCESS) {
        roma_hwrt_device_destroy(d);
        return r;
    }
    say(why, why_size, "");
    vkGetDeviceQueue(d->device, d->queue_family, 0, &d->queue);
    d->external = (roma_external_device){.instance = d->instance,
                                         .physical_device = d->physical_device,
                                         .device = d->device,
                                         .queue_family_index = d->queue_family,
                                         .queue = d->queue,
                                         .enabled_features = &d->req.features};
    *out = d;
    return ROMA_SUCCESS;
}

uint32_t roma_hwrt_device_destroy(roma_hwrt_device *d)
{
    if (!d)
        return 0;
    if (d->device) {
        /* Destruction only, never on a frame's path: the device's last work must be done. */
        vkDeviceWaitIdle(d->device);
        vkDestroyDevice(d->device, NULL);
    }
    if (d->messenger) {
        PFN_vkDestroyDebugUtilsMessengerEXT destroy_messenger =
            (PFN_vkDestroyDebugUtilsMessengerEXT)vkGetInstanceProcAddr(d->instance, "vkDestroyDebugUtilsMessengerEXT");
        if (destroy_messenger)
            destroy_messenger(d->instance, d->messenger, NULL);
    }
    if (d->instance)
        vkDestroyInstance(d->instance, NULL);
    const uint32_t messages = d->validation_messages;
    free(d);
    return messages;
}

const roma_external_device *roma_hwrt_device_external(const roma_hwrt_device *d)
{
    return d ? &d->external : NULL;
}

int roma_hwrt_device_has_pipeline_statistics(const roma_hwrt_device *d)
{
    return d && d->statistics;
}

static VkDeviceSize align_up(VkDeviceSize v, VkDeviceSize a)
{
    return a > 1 ? (v + a - 1) / a * a : v;
}

/* The geometry of the bottom level (the scene's indexed triangles) or the top level (one
 * instance), and its build info. Opaque (the batch rays run no any-hit shader); the depth
 * map's rays make it non-opaque, and its reservoir counts each surface once (no duplicate
 * any-hit calls: a constraint on the build the batch rays share, which a driver may pay for
 * in build or trace time; the baseline's figures are with it). */
static VkAccelerationStructureGeometryKHR level_geometry(const roma_hwrt *h, int top)
{
    VkAccelerationStructureGeometryKHR g = {
        .sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR,
        .flags = VK_GEOMETRY_OPAQUE_BIT_KHR | VK_GEOMETRY_NO_DUPLICATE_ANY_HIT_INVOCATION_BIT_KHR};
    if (top) {
        g.geometryType = VK_GEOMETRY_TYPE_INSTANCES_KHR;
        g.geometry.instances = (VkAccelerationStructureGeometryInstancesDataKHR){
            .sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_INSTANCES_DATA_KHR,
            .data.deviceAddress = h->instance.address};
    } else {
        g.geometryType = VK_GEOMETRY_TYPE_TRIANGLES_KHR;
        g.geometry.triangles = (VkAccelerationStructureGeometryTrianglesDataKHR){
            .sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_TRIANGLES_DATA_KHR,
            .vertexFormat = VK_FORMAT_R32G32B32_SFLOAT,
            .vertexData.deviceAddress = h->positions.address,
            .vertexStride = 12,
            .maxVertex = h->vertex_count ? h->vertex_count - 1 : 0,
            .indexType = VK_INDEX_TYPE_UINT32,
            .indexData.deviceAddress = h->indices.address};
    }
    return g;
}

static VkAccelerationStructureBuildGeometryInfoKHR level_build(const roma_hwrt *h, int top,
                                                               const VkAccelerationStructureGeometryKHR *g)
{
    return (VkAccelerationStructureBuildGeometryInfoKHR){
        .sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_GEOMETRY_INFO_KHR,
        .type = top ? VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR : VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR,
        /* Rebuilt every frame, as a dynamic scene's is: a fast build. */
        .flags = VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_BUILD_BIT_KHR,
        .mode = VK_BUILD_ACCELERATION_STRUCTURE_MODE_BUILD_KHR,
        .dstAccelerationStructure = top ? h->tlas : h->blas,
        .geometryCount = 1,
        .pGeometries = g,
        .scratchData.deviceAddress = h->scratch_address};
}

static roma_result create_level(roma_hwrt *h, int top, VkDeviceSize *scratch_size)
{
    VkAccelerationStructureGeometryKHR g = level_geometry(h, top);
    VkAccelerationStructureBuildGeometryInfoKHR b = level_build(h, top, &g);
    const uint32_t primitives = top ? 1u : h->triangle_count;
    VkAccelerationStructureBuildSizesInfoKHR sizes = {.sType =
                                                          VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_SIZES_INFO_KHR};
    h->build_sizes(h->ctx->device, VK_ACCELERATION_STRUCTURE_BUILD_TYPE_DEVICE_KHR, &b, &primitives, &sizes);
    roma_buffer *buf = top ? &h->tlas_buffer : &h->blas_buffer;
    roma_result r = roma_buffer_create(h->ctx, sizes.accelerationStructureSize,
                                       VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_STORAGE_BIT_KHR |
                                           VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT,
                                       ROMA_MEMORY_DEVICE, buf);
    if (r != ROMA_SUCCESS)
        return r;
    VkAccelerationStructureCreateInfoKHR info = {
        .sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_CREATE_INFO_KHR,
        .buffer = buf->buffer,
        .size = sizes.accelerationStructureSize,
        .type = b.type};
    r = roma_vk_check(h->ctx, h->create_as(h->ctx->device, &info, h->ctx->allocator, top ? &h->tlas : &h->blas),
                      "vkCreateAccelerationStructureKHR");
    if (*scratch_size < sizes.buildScratchSize)
        *scratch_size = sizes.buildScratchSize;
    return r;
}

void roma_hwrt_record_build(roma_hwrt *h, VkCommandBuffer cmd)
{
    /* After earlier traces that read the structures being rebuilt (a frame's trace, then the
     * next frame's build). */
    roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_RAY_TRACING_SHADER_BIT_KHR, 0,
                            VK_PIPELINE_STAGE_2_ACCELERATION_STRUCTURE_BUILD_BIT_KHR, 0);
    for (int top = 0; top < 2; ++top) {
        VkAccelerationStructureGeometryKHR g = level_geometry(h, top);
        VkAccelerationStructureBuildGeometryInfoKHR b = level_build(h, top, &g);
        VkAccelerationStructureBuildRangeInfoKHR range = {.primitiveCount = top ? 1u : h->triangle_count};
        const VkAccelerationStructureBuildRangeInfoKHR *ranges = &range;
        h->cmd_build(cmd, 1, &b, &ranges);
        /* The top level reads the bottom one, and both share the scratch buffer. */
        roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_ACCELERATION_STRUCTURE_BUILD_BIT_KHR,
                                VK_ACCESS_2_ACCELERATION_STRUCTURE_WRITE_BIT_KHR,
                                top ? VK_PIPELINE_STAGE_2_RAY_TRACING_SHADER_BIT_KHR |
                                          VK_PIPELINE_STAGE_2_ACCELERATION_STRUCTURE_BUILD_BIT_KHR
                                    : VK_PIPELINE_STAGE_2_ACCELERATION_STRUCTURE_BUILD_BIT_KHR,
                                VK_ACCESS_2_ACCELERATION_STRUCTURE_READ_BIT_KHR |
                                    VK_ACCESS_2_ACCELERATION_STRUCTURE_WRITE_BIT_KHR);
    }
}

/* The descriptor set of the scene's top level and the pipeline layout both programs share
 * (their push blocks in one range, as large as the larger). */
static roma_result create_layout(roma_hwrt *h)
{
    roma_context *ctx = h->ctx;
    VkDescriptorSetLayoutBinding binding = {.binding = 0,
                                            .descriptorType = VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR,
                                            .descriptorCount = 1,
                                            .stageFlags = VK_SHADER_STAGE_RAYGEN_BIT_KHR};
    VkDescriptorSetLayoutCreateInfo set_info = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO,
                                                .bindingCount = 1,
                                                .pBindings = &binding};
    roma_result r = roma_vk_check(ctx, vkCreateDescriptorSetLayout(ctx->device, &set_info, ctx->allocator, &h->set_layout),
                                  "vkCreateDescriptorSetLayout");
    VkPushConstantRange push = {.stageFlags = VK_SHADER_STAGE_RAYGEN_BIT_KHR,
                                .size = sizeof(hwrt_depth_push) > sizeof(hwrt_push) ? sizeof(hwrt_depth_push)
                                                                                     : sizeof(hwrt_push)};
    VkPipelineLayoutCreateInfo layout_info = {.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO,
                                              .setLayoutCount = 1,
                                              .pSetLayouts = &h->set_layout,
                                              .pushConstantRangeCount = 1,
                                              .pPushConstantRanges = &push};
    if (r == ROMA_SUCCESS)
        r = roma_vk_check(ctx, vkCreatePipelineLayout(ctx->device, &layout_info, ctx->allocator, &h->layout),
                          "vkCreatePipelineLayout");
    VkDescriptorPoolSize size = {.type = VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR, .descriptorCount = 1};
    VkDescriptorPoolCreateInfo pool_info = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO,
                                            .maxSets = 1,
                                            .poolSizeCount = 1,
                                            .pPoolSizes = &size};
    if (r == ROMA_SUCCESS)
        r = roma_vk_check(ctx, vkCreateDescriptorPool(ctx->device, &pool_info, ctx->allocator, &h->pool),
                          "vkCreateDescriptorPool");
    VkDescriptorSetAllocateInfo alloc = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO,
                                         .descriptorPool = h->pool,
                                         .descriptorSetCount = 1,
                                         .pSetLayouts = &h->set_layout};
    if (r == ROMA_SUCCESS)
        r = roma_vk_check(ctx, vkAllocateDescriptorSets(ctx->device, &alloc, &h->set), "vkAllocateDescriptorSets");
    if (r != ROMA_SUCCESS)
        return r;
    VkWriteDescriptorSetAccelerationStructureKHR as_write = {
        .sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET_ACCELERATION_STRUCTURE_KHR,
        .accelerationStructureCount = 1,
        .pAccelerationStructures = &h->tlas};
    VkWriteDescriptorSet write = {.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET,
                                  .pNext = &as_write,
                                  .dstSet = h->set,
                                  .descriptorCount = 1,
                                  .descriptorType = VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR};
    vkUpdateDescriptorSets(ctx->device, 1, &write, 0, NULL);

    /* One invocation per ray, in rows no wider than the device launches along x. */
    h->rt = (VkPhysicalDeviceRayTracingPipelinePropertiesKHR){
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_TRACING_PIPELINE_PROPERTIES_KHR};
    VkPhysicalDeviceProperties2 props = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, .pNext = &h->rt};
    vkGetPhysicalDeviceProperties2(ctx->physical_device, &props);
    h->rt.pNext = NULL;
    const VkPhysicalDeviceRayTracingPipelinePropertiesKHR rt = h->rt;
    h->max_launch_invocations = rt.maxRayDispatchInvocationCount ? rt.maxRayDispatchInvocationCount : 1u;
    h->max_launch_width = rt.maxRayDispatchInvocationCount < 65536u ? rt.maxRayDispatchInvocationCount : 65536u;
    if (h->max_launch_width > ctx->properties.limits.maxComputeWorkGroupCount[0])
        h->max_launch_width = ctx->properties.limits.maxComputeWorkGroupCount[0];
    if (h->max_launch_width == 0)
        h->max_launch_width = 1;
    return ROMA_SUCCESS;
}

/* A program of names[0] (ray generation), names[1] (miss) and names[2], the hit group's
 * closest-hit shader, or its any-hit shader when any_hit is non-zero. */
static roma_result create_program(roma_hwrt *h, const char *const names[3], int any_hit, hwrt_program *out)
{
    roma_context *ctx = h->ctx;
    const VkShaderStageFlagBits stages[3] = {
        VK_SHADER_STAGE_RAYGEN_BIT_KHR, VK_SHADER_STAGE_MISS_BIT_KHR,
        any_hit ? VK_SHADER_STAGE_ANY_HIT_BIT_KHR : VK_SHADER_STAGE_CLOSEST_HIT_BIT_KHR};
    VkShaderModule modules[3] = {VK_NULL_HANDLE, VK_NULL_HANDLE, VK_NULL_HANDLE};
    VkPipelineShaderStageCreateInfo stage_info[3];
    roma_result r = ROMA_SUCCESS;
    for (int i = 0; i < 3 && r == ROMA_SUCCESS; ++i) {
        r = roma_shader_module_create(ctx, names[i], &modules[i]);
        stage_info[i] = (VkPipelineShaderStageCreateInfo){.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
                                                          .stage = stages[i],
                                                          .module = modules[i],
                                                          .pName = "main"};
    }
    VkRayTracingShaderGroupCreateInfoKHR groups[3];
    for (uint32_t i = 0; i < 3; ++i)
        groups[i] = (VkRayTracingShaderGroupCreateInfoKHR){
            .sType = VK_STRUCTURE_TYPE_RAY_TRACING_SHADER_GROUP_CREATE_INFO_KHR,
            .type = i < 2 ? VK_RAY_TRACING_SHADER_GROUP_TYPE_GENERAL_KHR
                          : VK_RAY_TRACING_SHADER_GROUP_TYPE_TRIANGLES_HIT_GROUP_KHR,
            .generalShader = i < 2 ? i : VK_SHADER_UNUSED_KHR,
            .closestHitShader = i == 2 && !any_hit ? i : VK_SHADER_UNUSED_KHR,
            .anyHitShader = i == 2 && any_hit ? i : VK_SHADER_UNUSED_KHR,
            .intersectionShader = VK_SHADER_UNUSED_KHR};
    VkRayTracingPipelineCreateInfoKHR info = {.sType = VK_STRUCTURE_TYPE_RAY_TRACING_PIPELINE_CREATE_INFO_KHR,
                                              .stageCount = 3,
                                              .pStages = stage_info,
                                              .groupCount = 3,
                                              .pGroups = groups,
                                              .maxPipelineRayRecursionDepth = 1,
                                              .layout = h->layout};
    if (r == ROMA_SUCCESS)
        r = roma_vk_check(ctx, h->create_pipelines(ctx->device, VK_NULL_HANDLE, ctx->pipeline_cache, 1, &info,
                                                   ctx->allocator, &out->pipeline),
                          "vkCreateRayTracingPipelinesKHR");
    for (int i = 0; i < 3; ++i)
        if (modules[i])
            vkDestroyShaderModule(ctx->device, modules[i], ctx->allocator);
    if (r != ROMA_SUCCESS)
        return r;

    /* The shader binding table: ray generation, miss and hit group, each region at the
     * base alignment (the ray generation region's stride equals its size). */
    const VkPhysicalDeviceRayTracingPipelinePropertiesKHR rt = h->rt; /* create_layout read it */
    const VkDeviceSize handle = rt.shaderGroupHandleSize;
    const VkDeviceSize stride = align_up(handle, rt.shaderGroupHandleAlignment);
    const VkDeviceSize region = align_up(stride, rt.shaderGroupBaseAlignment);
    uint8_t handles[3 * 64];
    if (handle == 0 || handle > 64)
        return roma_fail(&ctx->logger, ROMA_ERROR_MISSING_FEATURE, "shaderGroupHandleSize %u unexpected",
                         rt.shaderGroupHandleSize);
    r = roma_vk_check(ctx, h->group_handles(ctx->device, out->pipeline, 0, 3, (size_t)(3 * handle), handles),
                      "vkGetRayTracingShaderGroupHandlesKHR");
    if (r != ROMA_SUCCESS)
        return r;
    const VkDeviceSize base = rt.shaderGroupBaseAlignment ? rt.shaderGroupBaseAlignment : 1;
    uint8_t *table = calloc(1, (size_t)(3 * region + base));
    if (!table)
        return ROMA_ERROR_OUT_OF_HOST_MEMORY;
    /* The buffer's address is aligned to its memory's alignment, which need not reach the base
     * alignment: the table starts at the first aligned byte of a buffer one alignment larger. */
    r = roma_buffer_create(ctx, 3 * region + base,
                           VK_BUFFER_USAGE_SHADER_BINDING_TABLE_BIT_KHR | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT |
                               VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                           ROMA_MEMORY_DEVICE, &out->sbt);
    if (r == ROMA_SUCCESS) {
        const VkDeviceAddress start = align_up(out->sbt.address, base);
        const size_t offset = (size_t)(start - out->sbt.address);
        for (int i = 0; i < 3; ++i)
            memcpy(table + offset + i * region, handles + i * handle, (size_t)handle);
        VkCommandBuffer cmd;
        roma_buffer staging = {0};
        r = roma_buffer_create(ctx, 3 * region + base, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, ROMA_MEMORY_UPLOAD, &staging);
        if (r == ROMA_SUCCESS) {
            memcpy(staging.mapped, table, (size_t)(3 * region + base));
            r = roma_begin_one_shot(ctx, &cmd);
            if (r == ROMA_SUCCESS) {
                vkCmdCopyBuffer(cmd, staging.buffer, out->sbt.buffer, 1, &(VkBufferCopy){0, 0, 3 * region + base});
                roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                                        VK_PIPELINE_STAGE_2_RAY_TRACING_SHADER_BIT_KHR,
                                        VK_ACCESS_2_SHADER_READ_BIT);
                r = roma_submit_one_shot(ctx, cmd);
            }
            roma_buffer_destroy(ctx, &staging);
        }
        out->raygen = (VkStridedDeviceAddressRegionKHR){start, region, region};
        out->miss = (VkStridedDeviceAddressRegionKHR){start + region, stride, stride};
        out->hit = (VkStridedDeviceAddressRegionKHR){start + 2 * region, stride, stride};
        out->callable = (VkStridedDeviceAddressRegionKHR){0, 0, 0};
    }
    free(table);
    return r;
}

static void destroy_program(roma_context *ctx, hwrt_program *p)
{
    if (p->pipeline)
        vkDestroyPipeline(ctx->device, p->pipeline, ctx->allocator);
    roma_buffer_destroy(ctx, &p->sbt);
}

static roma_result create_pipelines(roma_hwrt *h)
{
    static const char *const rays[3] = {"hwrt_rays.rgen", "hwrt_miss.rmiss", "hwrt_hit.rchit"};
    static const char *const layers[3] = {"hwrt_depth_layers.rgen", "hwrt_depth_layers.rmiss",
                                          "hwrt_depth_layers.rahit"};
    roma_result r = create_layout(h);
    if (r == ROMA_SUCCESS)
        r = create_program(h, rays, 0, &h->rays);
    if (r == ROMA_SUCCESS)
        r = create_program(h, layers, 1, &h->layers);
    return r;
}

#define DEVICE_FN(h, field, type, name) ((h)->field = (type)vkGetDeviceProcAddr((h)->ctx->device, name))

roma_result roma_hwrt_create(roma_context *ctx, const roma_hwrt_device *dev, const roma_scene *scene, roma_hwrt **out)
{
    roma_study_shaders_use(ctx); /* its shaders are in the study table */
    if (!out)
        return ROMA_ERROR_INVALID_ARGUMENT;
    *out = NULL;
    roma_scene_view view;
    if (!ctx || !dev || ctx->device != dev->device || roma_scene_get_view(scene, &view) != ROMA_SUCCESS)
        return ROMA_ERROR_INVALID_ARGUMENT;
    roma_hwrt *h = calloc(1, sizeof *h);
    if (!h)
        return ROMA_ERROR_OUT_OF_HOST_MEMORY;
    h->ctx = ctx;
    DEVICE_FN(h, create_as, PFN_vkCreateAccelerationStructureKHR, "vkCreateAccelerationStructureKHR");
    DEVICE_FN(h, destroy_as, PFN_vkDestroyAccelerationStructureKHR, "vkDestroyAccelerationStructureKHR");
    DEVICE_FN(h, build_sizes, PFN_vkGetAccelerationStructureBuildSizesKHR, "vkGetAccelerationStructureBuildSizesKHR");
    DEVICE_FN(h, as_address, PFN_vkGetAccelerationStructureDeviceAddressKHR,
              "vkGetAccelerationStructureDeviceAddressKHR");
    DEVICE_FN(h, cmd_build, PFN_vkCmdBuildAccelerationStructuresKHR, "vkCmdBuildAccelerationStructuresKHR");
    DEVICE_FN(h, create_pipelines, PFN_vkCreateRayTracingPipelinesKHR, "vkCreateRayTracingPipelinesKHR");
    DEVICE_FN(h, group_handles, PFN_vkGetRayTracingShaderGroupHandlesKHR, "vkGetRayTracingShaderGroupHandlesKHR");
    DEVICE_FN(h, cmd_trace, PFN_vkCmdTraceRaysKHR, "vkCmdTraceRaysKHR");
    roma_result r = ROMA_SUCCESS;
    if (!h->create_as || !h->destroy_as || !h->build_sizes || !h->as_address || !h->cmd_build ||
        !h->create_pipelines || !h->group_handles || !h->cmd_trace)
        r = roma_fail(&ctx->logger, ROMA_ERROR_MISSING_FEATURE, "the device has no ray-tracing entry points");
    h->vertex_count = view.vertex_count;
    h->triangle_count = view.triangle_count;
    const VkBufferUsageFlags input =
        VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT |
        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT; /* the depth map's ray generation reads the triangles */
    static const float no_vertex[3] = {0.0f, 0.0f, 0.0f};
    static const uint32_t no_triangle[3] = {0u, 0u, 0u};
    if (r == ROMA_SUCCESS)
        r = roma_buffer_create_filled(ctx, 12 * (VkDeviceSize)(view.vertex_count ? view.vertex_count : 1), input,
                                      view.vertex_count ? (const void *)view.positions : no_vertex, &h->positions);
    if (r == ROMA_SUCCESS)
        r = roma_buffer_create_filled(ctx, 12 * (VkDeviceSize)(view.triangle_count ? view.triangle_count : 1), input,
                                      view.triangle_count ? (const void *)view.indices : no_triangle, &h->indices);
    VkDeviceSize scratch_size = 0;
    if (r == ROMA_SUCCESS)
        r = create_level(h, 0, &scratch_size);
    if (r == ROMA_SUCCESS) {
        VkAccelerationStructureDeviceAddressInfoKHR ai = {
            .sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_DEVICE_ADDRESS_INFO_KHR, .accelerationStructure = h->blas};
        VkAccelerationStructureInstanceKHR instance = {
            .transform.matrix = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}},
            .mask = 0xff,
            .flags = VK_GEOMETRY_INSTANCE_TRIANGLE_FACING_CULL_DISABLE_BIT_KHR,
            .accelerationStructureReference = h->as_address(ctx->device, &ai)};
        r = roma_buffer_create_filled(ctx, sizeof instance, input, &instance, &h->instance);
    }
    if (r == ROMA_SUCCESS)
        r = create_level(h, 1, &scratch_size);
    VkPhysicalDeviceAccelerationStructurePropertiesKHR asp = {
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_PROPERTIES_KHR};
    VkPhysicalDeviceProperties2 props = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, .pNext = &asp};
    vkGetPhysicalDeviceProperties2(ctx->physical_device, &props);
    const VkDeviceSize scratch_align =
        asp.minAccelerationStructureScratchOffsetAlignment ? asp.minAccelerationStructureScratchOffsetAlignment : 1;
    if (r == ROMA_SUCCESS)
        r = roma_buffer_create(ctx, scratch_size + scratch_align,
                               VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT,
                               ROMA_MEMORY_DEVICE, &h->scratch);
    if (r == ROMA_SUCCESS) {
        h->scratch_address = align_up(h->scratch.address, scratch_align);
        VkCommandBuffer cmd;
        r = roma_begin_one_shot(ctx, &cmd);
        if (r == ROMA_SUCCESS) {
            roma_hwrt_record_build(h, cmd);
            r = roma_submit_one_shot(ctx, cmd);
        }
    }
    if (r == ROMA_SUCCESS)
        r = create_pipelines(h);
    if (r != ROMA_SUCCESS) {
        roma_hwrt_destroy(h);
        return r;
    }
    *out = h;
    return ROMA_SUCCESS;
}

void roma_hwrt_destroy(roma_hwrt *h)
{
    if (!h)
        return;
    roma_context *ctx = h->ctx;
    destroy_program(ctx, &h->rays);
    destroy_program(ctx, &h->layers);
    if (h->layout)
        vkDestroyPipelineLayout(ctx->device, h->layout, ctx->allocator);
    if (h->pool)
        vkDestroyDescriptorPool(ctx->device, h->pool, ctx->allocator);
    if (h->set_layout)
        vkDestroyDescriptorSetLayout(ctx->device, h->set_layout, ctx->allocator);
    if (h->tlas)
        h->destroy_as(ctx->device, h->tlas, ctx->allocator);
    if (h->blas)
        h->destroy_as(ctx->device, h->blas, ctx->allocator);
    roma_buffer *buffers[6] = {&h->positions, &h->indices, &h->instance, &h->blas_buffer, &h->tlas_buffer,
                               &h->scratch};
    for (int i = 0; i < 6; ++i)
        roma_buffer_destroy(ctx, buffers[i]);
    free(h);
}

void roma_hwrt_record_trace(roma_hwrt *h, VkCommandBuffer cmd, VkDeviceAddress rays, VkDeviceAddress hits,
                            uint32_t count, int closest)
{
    if (!h || count == 0)
        return;
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR, h->rays.pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR, h->layout, 0, 1, &h->set, 0, NULL);
    /* Launches of whole rows, each within the device's invocations per launch. */
    const uint32_t width = count < h->max_launch_width ? count : h->max_launch_width;
    const uint64_t rows_per_launch = h->max_launch_invocations / width ? h->max_launch_invocations / width : 1;
    for (uint64_t base = 0; base < count; base += rows_per_launch * width) {
        const uint64_t left = count - base;
        const uint64_t rows = (left + width - 1) / width;
        hwrt_push push = {.rays = rays, .hits = hits, .count = count, .closest = closest ? 1u : 0u,
                          .base = (uint32_t)base};
        vkCmdPushConstants(cmd, h->layout, VK_SHADER_STAGE_RAYGEN_BIT_KHR, 0, sizeof push, &push);
        h->cmd_trace(cmd, &h->rays.raygen, &h->rays.miss, &h->rays.hit, &h->rays.callable, width,
                     (uint32_t)(rows < rows_per_launch ? rows : rows_per_launch), 1);
    }
}

int roma_hwrt_depth_layers_fit(const roma_hwrt *h, uint32_t width, uint32_t height)
{
    const VkPhysicalDeviceLimits *l = h ? &h->ctx->properties.limits : NULL;
    return h && width && height && width <= h->max_launch_width &&
           (uint64_t)width * height <= h->max_launch_invocations &&
           (uint64_t)height <= (uint64_t)l->maxComputeWorkGroupCount[1] * l->maxComputeWorkGroupSize[1];
}

roma_result roma_hwrt_record_depth_layers(roma_hwrt *h, VkCommandBuffer cmd, const roma_camera *camera,
                                          float near_plane, VkDeviceAddress pixels, uint32_t width, uint32_t height,
                                          uint32_t layers, uint32_t seed)
{
    roma_camera_frame cam;
    if (!h || !cmd || !camera || !pixels || layers == 0 || layers > ROMA_HWRT_MAX_DEPTH_LAYERS ||
        !(near_plane > 0.0f) || !roma_camera_make_frame(camera, width, height, &cam))
        return ROMA_ERROR_INVALID_ARGUMENT;
    if (!roma_hwrt_depth_layers_fit(h, width, height))
        return roma_fail(&h->ctx->logger, ROMA_ERROR_UNSUPPORTED,
                         "roma_hwrt_record_depth_layers: %ux%u pixels are more than one launch takes", width, height);
    /* The pixel scale of roma_ssao.glsl's projection, so both map a point to the same pixel. */
    const float sx = 0.5f * (float)width / (cam.tan_half_fovy * cam.aspect);
    const float sy = 0.5f * (float)height / cam.tan_half_fovy;
    hwrt_depth_push push = {.pixels = pixels, .positions = h->positions.address, .indices = h->indices.address,
                            .config = {width, height, layers, seed}};
    for (int k = 0; k < 3; ++k) {
        push.eye[k] = cam.origin[k];
        push.forward[k] = cam.forward[k];
        push.right[k] = cam.right[k] * sx;
        push.up[k] = cam.up[k] * sy;
    }
    push.eye[3] = near_plane;
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR, h->layers.pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR, h->layout, 0, 1, &h->set, 0, NULL);
    vkCmdPushConstants(cmd, h->layout, VK_SHADER_STAGE_RAYGEN_BIT_KHR, 0, sizeof push, &push);
    h->cmd_trace(cmd, &h->layers.raygen, &h->layers.miss, &h->layers.hit, &h->layers.callable, width, height, 1);
    return ROMA_SUCCESS;
}
