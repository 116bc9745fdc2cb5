/* The Vulkan context: default creation with validation, info, the embedded-shader
 * self-test with a GPU timestamp, timers, device selection failures, external mode. */
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "roma/context.h"

/* Allocation callbacks that count what is live: libroma must route the instance, the
 * device and every object through them, and free all of it. A header before each block
 * keeps its size and the offset back to the malloc'd pointer. */
typedef struct alloc_count {
    long live, total;
} alloc_count;

static void *VKAPI_CALL count_alloc(void *user, size_t size, size_t align, VkSystemAllocationScope scope)
{
    (void)scope;
    if (align < 16)
        align = 16;
    unsigned char *raw = malloc(size + align + 16);
    if (!raw)
        return NULL;
    unsigned char *p = raw + 16;
    p += (align - (uintptr_t)p % align) % align;
    size_t off = (size_t)(p - raw);
    memcpy(p - 16, &size, sizeof size);
    memcpy(p - 8, &off, sizeof off);
    ((alloc_count *)user)->live++, ((alloc_count *)user)->total++;
    return p;
}

static void VKAPI_CALL count_free(void *user, void *mem)
{
    if (!mem)
        return;
    size_t off;
    memcpy(&off, (unsigned char *)mem - 8, sizeof off);
    free((unsigned char *)mem - off);
    ((alloc_count *)user)->live--;
}

static void *VKAPI_CALL count_realloc(void *user, void *old, size_t size, size_t align, VkSystemAllocationScope scope)
{
    if (!old)
        return count_alloc(user, size, align, scope);
    if (size == 0) {
        count_free(user, old);
        return NULL;
    }
    void *p = count_alloc(user, size, align, scope);
    if (p) {
        size_t old_size;
        memcpy(&old_size, (unsigned char *)old - 16, sizeof old_size);
        memcpy(p, old, old_size < size ? old_size : size);
        count_free(user, old);
    }
    return p;
}

/* A device on the context's physical device made the way an engine might forget to:
 * without bufferDeviceAddress. libroma must refuse it by name, not fail later with
 * validation errors. */
static void test_missing_feature(roma_context *ctx)
{
    roma_device_requirements req;
    roma_get_device_requirements(&req);
    req.features12.bufferDeviceAddress = VK_FALSE;
    float priority = 1.0f;
    VkDeviceQueueCreateInfo queue = {.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO,
                                     .queueFamilyIndex = roma_context_queue_family(ctx),
                                     .queueCount = 1,
                                     .pQueuePriorities = &priority};
    VkDeviceCreateInfo info = {.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO,
                               .pNext = &req.features,
                               .queueCreateInfoCount = 1,
                               .pQueueCreateInfos = &queue};
    VkDevice device = VK_NULL_HANDLE;
    CHECK(vkCreateDevice(roma_context_physical_device(ctx), &info, NULL, &device) == VK_SUCCESS);
    if (!device)
        return;
    VkQueue q;
    vkGetDeviceQueue(device, roma_context_queue_family(ctx), 0, &q);
    roma_external_device ext = {roma_context_instance(ctx), roma_context_physical_device(ctx), device,
                                roma_context_queue_family(ctx), q, &req.features};
    roma_test_log log;
    roma_context_desc desc = {.external = &ext, .logger = roma_test_logger(&log)};
    roma_context *c = (roma_context *)1;
    CHECK_RESULT(roma_context_create(&desc, &c), ROMA_ERROR_MISSING_FEATURE);
    CHECK(c == NULL && log.errors == 1 && strstr(log.last, "bufferDeviceAddress") != NULL);
    /* The same device, the features not said: refused as a bad argument. */
    ext.enabled_features = NULL;
    CHECK_RESULT(roma_context_create(&desc, &c), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK(c == NULL && strstr(log.last, "enabled_features") != NULL);
    vkDestroyDevice(device, NULL);
}

/* Own device with allocation callbacks: used, and everything given back. */
static void test_allocation_callbacks(void)
{
    alloc_count count = {0, 0};
    VkAllocationCallbacks callbacks = {.pUserData = &count,
                                       .pfnAllocation = count_alloc,
                                       .pfnReallocation = count_realloc,
                                       .pfnFree = count_free};
    roma_context_desc desc = {.flags = ROMA_CONTEXT_VALIDATION, .allocation_callbacks = &callbacks};
    roma_context *c = NULL;
    CHECK_RESULT(roma_context_create(&desc, &c), ROMA_SUCCESS);
    CHECK_RESULT(roma_context_self_test(c, NULL), ROMA_SUCCESS);
    long during = count.total;
    roma_context_destroy(c);
    printf("allocation callbacks: %ld allocations, %ld live after destroy\n", during, count.live);
    CHECK(during > 0 && count.live == 0);
}

int main(void)
{
    roma_context *ctx = roma_test_context();
    if (!ctx)
        return roma_test_finish("test_context");
    roma_context_info info;
    CHECK_RESULT(roma_context_get_info(ctx, &info), ROMA_SUCCESS);
    printf("device: %s, Vulkan %u.%u, timestamp period %.3f ns\n", info.device_name,
           VK_API_VERSION_MAJOR(info.api_version), VK_API_VERSION_MINOR(info.api_version),
           info.timestamp_period_ns);
    CHECK(info.validation_enabled == 1);
    CHECK(info.owns_device == 1);
    CHECK(info.api_version >= VK_API_VERSION_1_3);
    /* The trace's division correction needs a fused fma, which CPU devices (lavapipe) may split:
     * off there, on every GPU (roma/trace_types.h). */
    CHECK(info.corrected_division == (info.device_type != VK_PHYSICAL_DEVICE_TYPE_CPU));
    CHECK(roma_context_device(ctx) != VK_NULL_HANDLE);
    CHECK_RESULT(roma_context_get_info(NULL, &info), ROMA_ERROR_INVALID_ARGUMENT);

    double ms = -1.0;
    CHECK_RESULT(roma_context_self_test(ctx, &ms), ROMA_SUCCESS);
    printf("self-test dispatch: %.4f ms\n", ms);
    CHECK(ms >= 0.0 && ms < 10000.0);

    /* Timer misuse and limits. */
    roma_gpu_timer *timer = NULL;
    CHECK_RESULT(roma_gpu_timer_create(ctx, 0, &timer), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK(timer == NULL);
    CHECK_RESULT(roma_gpu_timer_create(ctx, 2, &timer), ROMA_SUCCESS);
    uint32_t count = 0;
    CHECK_RESULT(roma_gpu_timer_read(timer, NULL, &count), ROMA_SUCCESS);
    CHECK(count == 0);
    roma_gpu_timer_destroy(timer);
    roma_gpu_timer_destroy(NULL);

    /* A device name nobody has: a clear error, no context. */
    roma_test_log log;
    roma_context_desc desc = {.flags = ROMA_CONTEXT_VALIDATION, .device_name = "no-such-device-xyz",
                              .logger = roma_test_logger(&log)};
    roma_context *none = (roma_context *)1;
    CHECK_RESULT(roma_context_create(&desc, &none), ROMA_ERROR_NO_DEVICE);
    CHECK(none == NULL);
    CHECK(log.errors == 1 && strstr(log.last, "no-such-device-xyz") != NULL);
    CHECK_RESULT(roma_context_create(&desc, NULL), ROMA_ERROR_INVALID_ARGUMENT);

    /* Adopt the first context's device: a second context on the caller's handles. */
    roma_external_device ext = {
        .instance = roma_context_instance(ctx),
        .physical_device = roma_context_physical_device(ctx),
        .device = roma_context_device(ctx),
        .queue_family_index = roma_context_queue_family(ctx),
        .queue = roma_context_queue(ctx),
    };
    roma_device_requirements req;
    roma_get_device_requirements(&req);
    CHECK(req.api_version == VK_API_VERSION_1_3 && req.features.pNext == &req.features12 &&
          req.features12.pNext == &req.features13 && req.features12.bufferDeviceAddress);
    ext.enabled_features = &req.features;
    roma_context_desc ext_desc = {.external = &ext};
    roma_context *adopted = NULL;
    CHECK_RESULT(roma_context_create(&ext_desc, &adopted), ROMA_SUCCESS);
    if (adopted) {
        CHECK_RESULT(roma_context_get_info(adopted, &info), ROMA_SUCCESS);
        CHECK(info.owns_device == 0);
        CHECK_RESULT(roma_context_self_test(adopted, NULL), ROMA_SUCCESS);
        roma_context_destroy(adopted); /* must leave the caller's device alive */
    }
    CHECK_RESULT(roma_context_self_test(ctx, NULL), ROMA_SUCCESS);
    ext.queue_family_index = 999;
    CHECK_RESULT(roma_context_create(&ext_desc, &adopted), ROMA_ERROR_INVALID_ARGUMENT);
    ext.device = VK_NULL_HANDLE;
    CHECK_RESULT(roma_context_create(&ext_desc, &adopted), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK(adopted == NULL);

    test_missing_feature(ctx);
    test_allocation_callbacks();
    roma_test_context_finish(ctx);
    roma_context_destroy(NULL);
    return roma_test_finish("test_context");
}
