/* The Vulkan context: default creation with validation, info, the embedded-shader
 * self-test with a GPU timestamp, timers, device selection failures, external mode. */
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "roma/context.h"

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

    roma_test_context_finish(ctx);
    roma_context_destroy(NULL);
    return roma_test_finish("test_context");
}
