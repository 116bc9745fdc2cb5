/* With no Vulkan driver visible (the loader pointed at a missing ICD manifest),
 * context creation fails with a result code and a message, never a crash. */
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "roma/context.h"

int main(void)
{
    setenv("VK_ICD_FILENAMES", "/nonexistent/roma-no-driver.json", 1);
    setenv("VK_DRIVER_FILES", "/nonexistent/roma-no-driver.json", 1);
    roma_test_log log;
    roma_context_desc desc = {.logger = roma_test_logger(&log)};
    roma_context *ctx = (roma_context *)1;
    roma_result r = roma_context_create(&desc, &ctx);
    printf("result: %s\n", roma_result_string(r));
    CHECK(r == ROMA_ERROR_NO_VULKAN || r == ROMA_ERROR_NO_DEVICE);
    CHECK(ctx == NULL);
    /* With validation on, the loader's own complaints come through the logger
     * first; the library's message, naming the cause, comes last. */
    CHECK(log.errors >= 1 && strstr(log.last, "driver") != NULL);
    return roma_test_finish("test_no_driver");
}
