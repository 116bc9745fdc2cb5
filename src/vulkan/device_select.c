#include <ctype.h>
#include <stdlib.h>
#include <string.h>

#include "roma_shared.h"
#include "vulkan/vk_internal.h"

static int contains_ignore_case(const char *haystack, const char *needle)
{
    size_t n = strlen(needle);
    for (const char *h = haystack; *h; ++h) {
        size_t i = 0;
        while (i < n && h[i] && tolower((unsigned char)h[i]) == tolower((unsigned char)needle[i]))
            ++i;
        if (i == n)
            return 1;
    }
    return n == 0;
}

/* Graphics + compute queue family with timestamps, or UINT32_MAX. */
static uint32_t find_queue_family(VkPhysicalDevice pd)
{
    uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &count, NULL);
    VkQueueFamilyProperties *families = calloc(count ? count : 1, sizeof *families);
    if (!families)
        return UINT32_MAX;
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &count, families);
    uint32_t found = UINT32_MAX;
    const VkQueueFlags need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
    for (uint32_t i = 0; i < count && found == UINT32_MAX; ++i)
        if ((families[i].queueFlags & need) == need && families[i].timestampValidBits > 0)
            found = i;
    free(families);
    return found;
}

roma_result roma_check_device_support(const roma_context *ctx, VkPhysicalDevice pd,
                                      int *out_has_geometry_shader)
{
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(pd, &props);
    if (props.apiVersion < VK_API_VERSION_1_3)
        return roma_fail(&ctx->logger, ROMA_ERROR_MISSING_FEATURE,
                         "%s supports Vulkan %u.%u; libroma needs 1.3", props.deviceName,
                         VK_API_VERSION_MAJOR(props.apiVersion), VK_API_VERSION_MINOR(props.apiVersion));
    VkPhysicalDeviceVulkan13Features f13 = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    VkPhysicalDeviceVulkan12Features f12 = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES,
                                            .pNext = &f13};
    VkPhysicalDeviceFeatures2 features = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, .pNext = &f12};
    vkGetPhysicalDeviceFeatures2(pd, &features);
    const char *missing = !f13.dynamicRendering                       ? "dynamicRendering"
                          : !f13.synchronization2                     ? "synchronization2"
                          : !f12.hostQueryReset                       ? "hostQueryReset"
                          : !f12.bufferDeviceAddress                  ? "bufferDeviceAddress"
                          : !features.features.fragmentStoresAndAtomics ? "fragmentStoresAndAtomics"
                          : !props.limits.timestampComputeAndGraphics ? "timestampComputeAndGraphics"
                                                                      : NULL;
    if (missing)
        return roma_fail(&ctx->logger, ROMA_ERROR_MISSING_FEATURE, "%s lacks the feature %s",
                         props.deviceName, missing);
    /* The occupied-cell list aggregates its atomics per subgroup (occupied_cells.comp). */
    VkPhysicalDeviceSubgroupProperties subgroup = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
    VkPhysicalDeviceProperties2 props2 = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, .pNext = &subgroup};
    vkGetPhysicalDeviceProperties2(pd, &props2);
    const VkSubgroupFeatureFlags ops = VK_SUBGROUP_FEATURE_BASIC_BIT | VK_SUBGROUP_FEATURE_ARITHMETIC_BIT |
                                       VK_SUBGROUP_FEATURE_BALLOT_BIT;
    if ((subgroup.supportedOperations & ops) != ops || !(subgroup.supportedStages & VK_SHADER_STAGE_COMPUTE_BIT))
        return roma_fail(&ctx->logger, ROMA_ERROR_MISSING_FEATURE,
                         "%s lacks subgroup arithmetic and ballot operations in compute shaders", props.deviceName);
    /* The rotation reads every map's frame from one uniform block (roma_rotate.glsl). */
    if (props.limits.maxUniformBufferRange < ROMA_PARAMS_BLOCK_BYTES)
        return roma_fail(&ctx->logger, ROMA_ERROR_MISSING_FEATURE,
                         "%s: maxUniformBufferRange %u is below the %u bytes libroma's parameters need",
                         props.deviceName, props.limits.maxUniformBufferRange, (unsigned)ROMA_PARAMS_BLOCK_BYTES);
    if (out_has_geometry_shader)
        *out_has_geometry_shader = features.features.geometryShader != VK_FALSE;
    return ROMA_SUCCESS;
}

static int type_rank(VkPhysicalDeviceType type)
{
    switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 4;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 3;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return 1;
    default: return 0;
    }
}

roma_result roma_select_device(const roma_context *ctx, const char *name_filter, int require_gpu,
                               roma_device_choice *out)
{
    uint32_t count = 0;
    VkResult vr = vkEnumeratePhysicalDevices(ctx->instance, &count, NULL);
    if (vr != VK_SUCCESS)
        return roma_vk_check(ctx, vr, "vkEnumeratePhysicalDevices");
    if (count == 0)
        return roma_fail(&ctx->logger, ROMA_ERROR_NO_DEVICE,
                         "no Vulkan device found (for a CPU fallback install mesa-vulkan-drivers)");
    VkPhysicalDevice *devices = calloc(count, sizeof *devices);
    if (!devices)
        return ROMA_ERROR_OUT_OF_HOST_MEMORY;
    vr = vkEnumeratePhysicalDevices(ctx->instance, &count, devices);
    if (vr != VK_SUCCESS && vr != VK_INCOMPLETE) {
        free(devices);
        return roma_vk_check(ctx, vr, "vkEnumeratePhysicalDevices");
    }
    int best_rank = -1;
    for (uint32_t i = 0; i < count; ++i) {
        VkPhysicalDeviceProperties props;
        vkGetPhysicalDeviceProperties(devices[i], &props);
        const char *skip = NULL;
        uint32_t family = find_queue_family(devices[i]);
        int rank = type_rank(props.deviceType);
        if (name_filter && *name_filter && !contains_ignore_case(props.deviceName, name_filter))
            skip = "its name does not match the requested device";
        else if (require_gpu && props.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU)
            skip = "it is a CPU implementation and a GPU is required";
        else if (family == UINT32_MAX)
            skip = "no queue family offers graphics, compute and timestamps";
        else if (roma_check_device_support(ctx, devices[i], NULL) != ROMA_SUCCESS)
            skip = "it lacks a required feature";
        roma_logf(&ctx->logger, ROMA_LOG_DEBUG, "device %u: %s%s%s", i, props.deviceName,
                  skip ? " skipped: " : " usable", skip ? skip : "");
        if (!skip && rank > best_rank) {
            best_rank = rank;
            out->physical_device = devices[i];
            out->queue_family = family;
        }
    }
    free(devices);
    if (best_rank < 0)
        return roma_fail(&ctx->logger, ROMA_ERROR_NO_DEVICE,
                         "no suitable Vulkan device%s%s%s", name_filter && *name_filter ? " matches '" : "",
                         name_filter && *name_filter ? name_filter : "", name_filter && *name_filter ? "'" : "");
    return ROMA_SUCCESS;
}
