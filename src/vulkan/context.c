#include <stdlib.h>
#include <string.h>

#include "vulkan/loop_budget.h"
#include "vulkan/loop_guard.h"
#include "vulkan/vk_internal.h"

static VKAPI_ATTR VkBool32 VKAPI_CALL on_validation_message(
    VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT types,
    const VkDebugUtilsMessengerCallbackDataEXT *data, void *user)
{
    (void)types;
    roma_context *ctx = user;
    roma_log_level level = ROMA_LOG_DEBUG;
    if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) {
        level = ROMA_LOG_ERROR;
        atomic_fetch_add(&ctx->validation_errors, 1u);
    } else if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) {
        level = ROMA_LOG_WARNING;
    } else if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_INFO_BIT_EXT) {
        level = ROMA_LOG_INFO;
    }
    const char *text = data && data->pMessage ? data->pMessage : "(no message)";
    if (level == ROMA_LOG_ERROR)
        roma_log_error(&ctx->logger, ROMA_ERROR_VALIDATION, "vulkan validation: %s", text);
    else
        roma_logf(&ctx->logger, level, "vulkan validation: %s", text);
    return VK_FALSE;
}

static int env_flag(const char *name)
{
    const char *v = getenv(name);
    return v && *v && strcmp(v, "0") != 0;
}

/* The plan of split dispatches (loop_budget.h): CPU devices run llvmpipe's budget; the
 * environment's ROMA_LOOP_PLAN (a positive count) tests the split anywhere. */
static uint32_t loop_plan(const roma_context *ctx)
{
    const char *v = getenv("ROMA_LOOP_PLAN");
    if (v && *v) {
        char *end = NULL;
        unsigned long n = strtoul(v, &end, 10);
        if (end && !*end && n > 0 && n < UINT32_MAX) {
            roma_logf(&ctx->logger, ROMA_LOG_INFO, "libroma: ROMA_LOOP_PLAN: dispatches plan for %lu loop iterations", n);
            return (uint32_t)n;
        }
        roma_logf(&ctx->logger, ROMA_LOG_WARNING, "libroma: ROMA_LOOP_PLAN '%s' is not a positive count: ignored", v);
    }
    return ctx->properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU ? ROMA_LOOP_PLAN : UINT32_MAX;
}

static int has_instance_layer(const char *name)
{
    uint32_t count = 0;
    if (vkEnumerateInstanceLayerProperties(&count, NULL) != VK_SUCCESS || count == 0)
        return 0;
    VkLayerProperties *layers = calloc(count, sizeof *layers);
    if (!layers)
        return 0;
    int found = 0;
    if (vkEnumerateInstanceLayerProperties(&count, layers) == VK_SUCCESS)
        for (uint32_t i = 0; i < count && !found; ++i)
            found = strcmp(layers[i].layerName, name) == 0;
    free(layers);
    return found;
}

static VkDebugUtilsMessengerCreateInfoEXT messenger_info(roma_context *ctx)
{
    VkDebugUtilsMessengerCreateInfoEXT info = {
        .sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT,
        .messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                           VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT,
        .messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT,
        .pfnUserCallback = on_validation_message,
        .pUserData = ctx,
    };
    return info;
}

static roma_result create_instance(roma_context *ctx)
{
    uint32_t loader_version = VK_API_VERSION_1_0;
    PFN_vkEnumerateInstanceVersion enumerate_version =
        (PFN_vkEnumerateInstanceVersion)vkGetInstanceProcAddr(NULL, "vkEnumerateInstanceVersion");
    if (enumerate_version)
        enumerate_version(&loader_version);
    if (loader_version < VK_API_VERSION_1_3)
        return roma_fail(&ctx->logger, ROMA_ERROR_NO_VULKAN,
                         "the Vulkan loader offers version %u.%u; libroma needs 1.3",
                         VK_API_VERSION_MAJOR(loader_version), VK_API_VERSION_MINOR(loader_version));

    const char *layers[1] = {"VK_LAYER_KHRONOS_validation"};
    const char *extensions[1] = {VK_EXT_DEBUG_UTILS_EXTENSION_NAME};
    if (ctx->validation_enabled && !has_instance_layer(layers[0]))
        return roma_fail(&ctx->logger, ROMA_ERROR_MISSING_FEATURE,
                         "validation was requested but VK_LAYER_KHRONOS_validation is not "
                         "installed (Debian package vulkan-validationlayers)");

    VkApplicationInfo app = {
        .sType = VK_STRUCTURE_TYPE_APPLICATION_INFO,
        .pApplicationName = "libroma",
        .pEngineName = "libroma",
        .engineVersion = VK_MAKE_API_VERSION(0, 0, 1, 0),
        .apiVersion = VK_API_VERSION_1_3,
    };
    VkDebugUtilsMessengerCreateInfoEXT debug = messenger_info(ctx);
    const VkValidationFeatureEnableEXT sync = VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
    VkValidationFeaturesEXT features = {
        .sType = VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT,
        .enabledValidationFeatureCount = 1,
        .pEnabledValidationFeatures = &sync,
    };
    /* The messenger info also covers instance create/destroy; the sync feature before it. */
    const void *chain = ctx->validation_enabled ? &debug : NULL;
    if (ctx->validation_enabled && (ctx->flags & ROMA_CONTEXT_SYNC_VALIDATION)) {
        features.pNext = &debug;
        chain = &features;
    }
    VkInstanceCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO,
        .pNext = chain,
        .pApplicationInfo = &app,
        .enabledLayerCount = ctx->validation_enabled ? 1u : 0u,
        .ppEnabledLayerNames = layers,
        .enabledExtensionCount = ctx->validation_enabled ? 1u : 0u,
        .ppEnabledExtensionNames = extensions,
    };
    VkResult vr = vkCreateInstance(&info, ctx->allocator, &ctx->instance);
    if (vr == VK_ERROR_INCOMPATIBLE_DRIVER || vr == VK_ERROR_INITIALIZATION_FAILED)
        return roma_fail(&ctx->logger, ROMA_ERROR_NO_VULKAN,
                         "vkCreateInstance failed (%s): no usable Vulkan driver is installed "
                         "(for a CPU fallback install mesa-vulkan-drivers)",
                         roma_vk_result_string(vr));
    roma_result r = roma_vk_check(ctx, vr, "vkCreateInstance");
    if (r != ROMA_SUCCESS)
        return r;
    if (ctx->validation_enabled) {
        PFN_vkCreateDebugUtilsMessengerEXT create_messenger =
            (PFN_vkCreateDebugUtilsMessengerEXT)vkGetInstanceProcAddr(
                ctx->instance, "vkCreateDebugUtilsMessengerEXT");
        if (!create_messenger)
            return roma_fail(&ctx->logger, ROMA_ERROR_MISSING_FEATURE,
                             "vkCreateDebugUtilsMessengerEXT is unavailable");
        r = roma_vk_check(ctx, create_messenger(ctx->instance, &debug, ctx->allocator, &ctx->messenger),
                          "vkCreateDebugUtilsMessengerEXT");
    }
    return r;
}

void roma_get_device_requirements(roma_device_requirements *out)
{
    if (!out)
        return;
    memset(out, 0, sizeof *out);
    out->api_version = VK_API_VERSION_1_3;
    out->features13 = (VkPhysicalDeviceVulkan13Features){
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES,
        .dynamicRendering = VK_TRUE,
        .synchronization2 = VK_TRUE,
    };
    out->features12 = (VkPhysicalDeviceVulkan12Features){
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES,
        .pNext = &out->features13,
        .hostQueryReset = VK_TRUE,
        .bufferDeviceAddress = VK_TRUE,
    };
    out->features = (VkPhysicalDeviceFeatures2){
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2,
        .pNext = &out->features12,
        .features = {.fragmentStoresAndAtomics = VK_TRUE},
    };
    out->queue_flags = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
}

static roma_result create_device(roma_context *ctx)
{
    float priority = 1.0f;
    VkDeviceQueueCreateInfo queue = {
        .sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO,
        .queueFamilyIndex = ctx->queue_family,
        .queueCount = 1,
        .pQueuePriorities = &priority,
    };
    roma_device_requirements req;
    roma_get_device_requirements(&req);
    req.features.features.geometryShader = ctx->has_geometry_shader ? VK_TRUE : VK_FALSE;
    VkDeviceCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO,
        .pNext = &req.features,
        .queueCreateInfoCount = 1,
        .pQueueCreateInfos = &queue,
        .enabledExtensionCount = req.extension_count,
        .ppEnabledExtensionNames = req.extensions,
    };
    VkResult vr = vkCreateDevice(ctx->physical_device, &info, ctx->allocator, &ctx->device);
    if (vr == VK_ERROR_OUT_OF_DEVICE_MEMORY)
        return roma_fail(&ctx->logger, ROMA_ERROR_OUT_OF_DEVICE_MEMORY, "vkCreateDevice: out of device memory");
    roma_result r = roma_vk_check(ctx, vr, "vkCreateDevice");
    if (r == ROMA_SUCCESS)
        vkGetDeviceQueue(ctx->device, ctx->queue_family, 0, &ctx->queue);
    return r;
}

/* The features a caller's device was created with, gathered from its pNext chain
 * (the Vulkan 1.2/1.3 structs or the single-feature structs they absorbed). */
typedef struct enabled_features {
    VkBool32 dynamic_rendering, synchronization2, host_query_reset, buffer_device_address;
    VkBool32 fragment_stores_and_atomics, geometry_shader;
} enabled_features;

static enabled_features read_enabled(const VkPhysicalDeviceFeatures2 *chain)
{
    enabled_features e = {0};
    e.fragment_stores_and_atomics = chain->features.fragmentStoresAndAtomics;
    e.geometry_shader = chain->features.geometryShader;
    for (const VkBaseInStructure *s = chain->pNext; s; s = s->pNext) {
        switch (s->sType) {
        case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES: {
            const VkPhysicalDeviceVulkan12Features *f = (const void *)s;
            e.host_query_reset |= f->hostQueryReset;
            e.buffer_device_address |= f->bufferDeviceAddress;
            break;
        }
        case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES: {
            const VkPhysicalDeviceVulkan13Features *f = (const void *)s;
            e.dynamic_rendering |= f->dynamicRendering;
            e.synchronization2 |= f->synchronization2;
            break;
        }
        case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_HOST_QUERY_RESET_FEATURES:
            e.host_query_reset |= ((const VkPhysicalDeviceHostQueryResetFeatures *)(const void *)s)->hostQueryReset;
            break;
        case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_BUFFER_DEVICE_ADDRESS_FEATURES:
            e.buffer_device_address |=
                ((const VkPhysicalDeviceBufferDeviceAddressFeatures *)(const void *)s)->bufferDeviceAddress;
            break;
        case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DYNAMIC_RENDERING_FEATURES:
            e.dynamic_rendering |=
                ((const VkPhysicalDeviceDynamicRenderingFeatures *)(const void *)s)->dynamicRendering;
            break;
        case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SYNCHRONIZATION_2_FEATURES:
            e.synchronization2 |=
                ((const VkPhysicalDeviceSynchronization2Features *)(const void *)s)->synchronization2;
            break;
        default:
            break;
        }
    }
    return e;
}

static roma_result create_submit_objects(roma_context *ctx)
{
    VkCommandPoolCreateInfo pool = {
        .sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
        .flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT,
        .queueFamilyIndex = ctx->queue_family,
    };
    roma_result r = roma_vk_check(ctx, vkCreateCommandPool(ctx->device, &pool, ctx->allocator, &ctx->command_pool),
                                  "vkCreateCommandPool");
    if (r != ROMA_SUCCESS)
        return r;
    VkFenceCreateInfo fence = {.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    r = roma_vk_check(ctx, vkCreateFence(ctx->device, &fence, ctx->allocator, &ctx->fence), "vkCreateFence");
    VkPipelineCacheCreateInfo cache = {.sType = VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO};
    if (r == ROMA_SUCCESS)
        r = roma_vk_check(ctx, vkCreatePipelineCache(ctx->device, &cache, ctx->allocator, &ctx->pipeline_cache),
                          "vkCreatePipelineCache");
    return r;
}

static roma_result adopt_external(roma_context *ctx, const roma_external_device *ext)
{
    if (!ext->instance || !ext->physical_device || !ext->device || !ext->queue)
        return roma_fail(&ctx->logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_context_desc.external: instance, physical_device, device and queue "
                         "must all be set");
    ctx->instance = ext->instance;
    ctx->physical_device = ext->physical_device;
    ctx->device = ext->device;
    ctx->queue = ext->queue;
    ctx->queue_family = ext->queue_family_index;
    uint32_t family_count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(ext->physical_device, &family_count, NULL);
    if (ext->queue_family_index >= family_count)
        return roma_fail(&ctx->logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "external queue family %u does not exist (the device has %u)",
                         ext->queue_family_index, family_count);
    VkQueueFamilyProperties families[64];
    uint32_t listed = family_count < 64 ? family_count : 64;
    vkGetPhysicalDeviceQueueFamilyProperties(ext->physical_device, &listed, families);
    const VkQueueFlags need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
    if (ext->queue_family_index < listed && ((families[ext->queue_family_index].queueFlags & need) != need ||
                                             families[ext->queue_family_index].timestampValidBits == 0))
        return roma_fail(&ctx->logger, ROMA_ERROR_MISSING_FEATURE,
                         "external queue family %u lacks graphics, compute or timestamps", ext->queue_family_index);
    if (!ext->enabled_features || ext->enabled_features->sType != VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2)
        return roma_fail(&ctx->logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_context_desc.external.enabled_features must point to the VkPhysicalDeviceFeatures2 "
                         "the device was created with (roma_get_device_requirements lists what to enable)");
    roma_result r = roma_check_device_support(ctx, ext->physical_device, NULL);
    if (r != ROMA_SUCCESS)
        return r;
    /* Offered is not enabled: what the caller enabled decides. */
    enabled_features e = read_enabled(ext->enabled_features);
    const char *missing = !e.dynamic_rendering             ? "dynamicRendering"
                          : !e.synchronization2            ? "synchronization2"
                          : !e.host_query_reset            ? "hostQueryReset"
                          : !e.buffer_device_address       ? "bufferDeviceAddress"
                          : !e.fragment_stores_and_atomics ? "fragmentStoresAndAtomics"
                                                           : NULL;
    if (missing)
        return roma_fail(&ctx->logger, ROMA_ERROR_MISSING_FEATURE,
                         "the caller's device was created without %s, which libroma needs "
                         "(roma_get_device_requirements)", missing);
    ctx->has_geometry_shader = e.geometry_shader != VK_FALSE;
    return ROMA_SUCCESS;
}

roma_result roma_context_create(const roma_context_desc *desc, roma_context **out_context)
{
    if (!out_context)
        return roma_fail(desc ? &desc->logger : NULL, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_context_create: out_context is NULL");
    *out_context = NULL;
    roma_context_desc defaults = {0};
    if (!desc)
        desc = &defaults;
    const uint32_t known_flags = ROMA_CONTEXT_VALIDATION | ROMA_CONTEXT_REQUIRE_GPU | ROMA_CONTEXT_SYNC_VALIDATION |
                                 ROMA_CONTEXT_CORRECTED_DIVISION;
    if (desc->flags & ~known_flags)
        return roma_fail(&desc->logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_context_create: unknown flags 0x%x", desc->flags & ~known_flags);
    roma_context *ctx = calloc(1, sizeof *ctx);
    if (ctx && !roma_mutex_init(&ctx->lock, 0)) {
        free(ctx);
        ctx = NULL;
    }
    if (ctx && !roma_mutex_init(&ctx->memory_lock, 0)) {
        roma_mutex_destroy(&ctx->lock);
        free(ctx);
        ctx = NULL;
    }
    if (ctx && !roma_mutex_init(&ctx->submit_lock, 1)) {
        roma_mutex_destroy(&ctx->lock);
        roma_mutex_destroy(&ctx->memory_lock);
        free(ctx);
        ctx = NULL;
    }
    if (!ctx)
        return roma_fail(&desc->logger, ROMA_ERROR_OUT_OF_HOST_MEMORY, "roma_context_create: out of memory");
    ctx->queue_lock = desc->queue_lock;
    ctx->logger = desc->logger;
    ctx->flags = desc->flags;
    ctx->allocator = desc->allocation_callbacks;
    ctx->memory_budget = desc->device_memory_budget;
    atomic_init(&ctx->validation_errors, 0u);
    atomic_init(&ctx->queue_submits, 0u);
    atomic_init(&ctx->queue_waits, 0u);
    atomic_init(&ctx->geometry_versions, 0u);
    atomic_init(&ctx->study_modules, NULL);

    roma_result r;
    if (desc->external) {
        r = adopt_external(ctx, desc->external);
    } else {
        ctx->owns_device = 1;
        ctx->validation_enabled =
            (desc->flags & (ROMA_CONTEXT_VALIDATION | ROMA_CONTEXT_SYNC_VALIDATION)) || env_flag("ROMA_VALIDATION");
        const char *name = desc->device_name ? desc->device_name : getenv("ROMA_DEVICE");
        roma_device_choice choice = {0};
        r = create_instance(ctx);
        if (r == ROMA_SUCCESS)
            r = roma_select_device(ctx, name, (desc->flags & ROMA_CONTEXT_REQUIRE_GPU) != 0, &choice);
        if (r == ROMA_SUCCESS) {
            ctx->physical_device = choice.physical_device;
            ctx->queue_family = choice.queue_family;
            r = roma_check_device_support(ctx, ctx->physical_device, &ctx->has_geometry_shader);
        }
        if (r == ROMA_SUCCESS)
            r = create_device(ctx);
    }
    if (r == ROMA_SUCCESS) {
        vkGetPhysicalDeviceProperties(ctx->physical_device, &ctx->properties);
        ctx->corrected_division = ctx->properties.deviceType != VK_PHYSICAL_DEVICE_TYPE_CPU ||
                                  (ctx->flags & ROMA_CONTEXT_CORRECTED_DIVISION) != 0;
        VkPhysicalDeviceFloatControlsProperties float_controls = {
            .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FLOAT_CONTROLS_PROPERTIES};
        VkPhysicalDeviceMaintenance3Properties m3 = {
            .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_3_PROPERTIES, .pNext = &float_controls};
        VkPhysicalDeviceProperties2 p2 = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, .pNext = &m3};
        vkGetPhysicalDeviceProperties2(ctx->physical_device, &p2);
        ctx->max_allocation_size = m3.maxMemoryAllocationSize;
        ctx->rounding_rte = float_controls.shaderRoundingModeRTEFloat32 && !env_flag("ROMA_NO_ROUNDING_MODE");
        vkGetPhysicalDeviceMemoryProperties(ctx->physical_device, &ctx->memory_properties);
        r = create_submit_objects(ctx);
    }
    if (r == ROMA_SUCCESS) {
        ctx->force_staging = env_flag("ROMA_FORCE_STAGING");
        ctx->loop_plan = loop_plan(ctx);
        r = roma_loop_guard_create(ctx);
    }
    if (r != ROMA_SUCCESS) {
        roma_context_destroy(ctx);
        return r;
    }
    roma_logf(&ctx->logger, ROMA_LOG_INFO, "libroma: using %s (Vulkan %u.%u)%s",
              ctx->properties.deviceName, VK_API_VERSION_MAJOR(ctx->properties.apiVersion),
              VK_API_VERSION_MINOR(ctx->properties.apiVersion),
              ctx->validation_enabled ? " with validation" : "");
    *out_context = ctx;
    return ROMA_SUCCESS;
}

void roma_context_destroy(roma_context *ctx)
{
    if (!ctx)
        return;
    if (ctx->device) {
        /* On the caller's device nothing of ours is pending: every libroma submission (creation,
         * blocking convenience calls) waits on its fence before returning, and the queue is the
         * engine's to synchronise (a failed create must not wait on it either). */
        if (ctx->owns_device)
            vkDeviceWaitIdle(ctx->device);
        roma_loop_guard_destroy(ctx); /* reports what the last work ran past the guard */
        roma_shared_pipelines_destroy(ctx);
        if (ctx->pipeline_cache)
            vkDestroyPipelineCache(ctx->device, ctx->pipeline_cache, ctx->allocator);
        if (ctx->fence)
            vkDestroyFence(ctx->device, ctx->fence, ctx->allocator);
        if (ctx->command_pool)
            vkDestroyCommandPool(ctx->device, ctx->command_pool, ctx->allocator);
    }
    if (ctx->owns_device) {
        if (ctx->device)
            vkDestroyDevice(ctx->device, ctx->allocator);
        if (ctx->messenger) {
            PFN_vkDestroyDebugUtilsMessengerEXT destroy_messenger =
                (PFN_vkDestroyDebugUtilsMessengerEXT)vkGetInstanceProcAddr(
                    ctx->instance, "vkDestroyDebugUtilsMessengerEXT");
            if (destroy_messenger)
                destroy_messenger(ctx->instance, ctx->messenger, ctx->allocator);
        }
        if (ctx->instance)
            vkDestroyInstance(ctx->instance, ctx->allocator);
    }
    roma_mutex_destroy(&ctx->lock);
    roma_mutex_destroy(&ctx->memory_lock);
    roma_mutex_destroy(&ctx->submit_lock);
    free(ctx);
}

roma_result roma_context_get_info(const roma_context *ctx, roma_context_info *out)
{
    if (out)
        memset(out, 0, sizeof *out);
    if (!ctx || !out)
        return roma_fail(ctx ? &ctx->logger : NULL, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_context_get_info: %s is NULL", ctx ? "out_info" : "context");
    memcpy(out->device_name, ctx->properties.deviceName, sizeof out->device_name);
    out->device_type = ctx->properties.deviceType;
    out->corrected_division = ctx->corrected_division ? VK_TRUE : VK_FALSE;
    out->rounding_mode_rte = ctx->rounding_rte ? VK_TRUE : VK_FALSE;
    out->api_version = ctx->properties.apiVersion;
    out->driver_version = ctx->properties.driverVersion;
    out->timestamp_period_ns = ctx->properties.limits.timestampPeriod;
    roma_mutex_lock(&((roma_context *)ctx)->memory_lock);
    out->device_memory_in_use = ctx->memory_in_use;
    roma_mutex_unlock(&((roma_context *)ctx)->memory_lock);
    roma_mutex_lock(&((roma_context *)ctx)->lock);
    out->pipelines_compiled = ctx->pipeline_count;
    roma_mutex_unlock(&((roma_context *)ctx)->lock);
    out->device_memory_budget = ctx->memory_budget;
    out->max_allocation_size = ctx->max_allocation_size;
    out->validation_enabled = ctx->validation_enabled;
    out->owns_device = ctx->owns_device;
    out->queue_submits = ctx->queue_submits;
    out->queue_waits = ctx->queue_waits;
    return ROMA_SUCCESS;
}

uint32_t roma_context_validation_error_count(const roma_context *ctx)
{
    roma_loop_guard_check(ctx);
    return ctx ? atomic_load(&((roma_context *)ctx)->validation_errors) : 0u;
}

VkInstance roma_context_instance(const roma_context *ctx) { return ctx ? ctx->instance : VK_NULL_HANDLE; }
VkPhysicalDevice roma_context_physical_device(const roma_context *ctx) { return ctx ? ctx->physical_device : VK_NULL_HANDLE; }
VkDevice roma_context_device(const roma_context *ctx) { return ctx ? ctx->device : VK_NULL_HANDLE; }
VkQueue roma_context_queue(const roma_context *ctx) { return ctx ? ctx->queue : VK_NULL_HANDLE; }
uint32_t roma_context_queue_family(const roma_context *ctx) { return ctx ? ctx->queue_family : UINT32_MAX; }
