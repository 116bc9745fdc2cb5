/* The harness relies on the validation error count to fail tests: prove that a
 * deliberate misuse is counted (and that the count is per context). */
#include "harness.h"
#include "roma/context.h"

int main(void)
{
    roma_test_log log;
    roma_context_desc desc = {.flags = ROMA_CONTEXT_VALIDATION, .logger = roma_test_logger(&log)};
    roma_context *ctx = NULL;
    CHECK_RESULT(roma_context_create(&desc, &ctx), ROMA_SUCCESS);
    if (!ctx)
        return roma_test_finish("test_validation_catches");
    roma_context *clean = roma_test_context();
    CHECK(roma_context_validation_error_count(ctx) == 0);

    /* size 0 violates VUID-VkBufferCreateInfo-size-00912. */
    VkBufferCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO,
        .size = 0,
        .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
    };
    VkBuffer buffer = VK_NULL_HANDLE;
    VkResult vr = vkCreateBuffer(roma_context_device(ctx), &info, NULL, &buffer);
    if (vr == VK_SUCCESS && buffer)
        vkDestroyBuffer(roma_context_device(ctx), buffer, NULL);
    printf("validation errors after misuse: %u\n", roma_context_validation_error_count(ctx));
    CHECK(roma_context_validation_error_count(ctx) >= 1);
    CHECK(log.errors >= 1);
    roma_context_destroy(ctx);
    roma_test_context_finish(clean); /* the other context saw nothing */
    return roma_test_finish("test_validation_catches");
}
