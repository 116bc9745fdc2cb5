/* Every result code has its own message; unknown values are reported as such. */
#include <string.h>

#include "harness.h"
#include "roma/result.h"

int main(void)
{
    for (int a = 0; a < ROMA_RESULT_COUNT_; ++a) {
        const char *sa = roma_result_string((roma_result)a);
        CHECK(sa != NULL && strcmp(sa, "unknown roma_result") != 0);
        for (int b = 0; b < a; ++b)
            CHECK(strcmp(sa, roma_result_string((roma_result)b)) != 0);
    }
    CHECK(strcmp(roma_result_string(ROMA_RESULT_COUNT_), "unknown roma_result") == 0);
    CHECK(strcmp(roma_result_string((roma_result)-1), "unknown roma_result") == 0);
    CHECK(strcmp(roma_log_level_string(ROMA_LOG_ERROR), "error") == 0);
    return roma_test_finish("test_result");
}
