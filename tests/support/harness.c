#include "harness.h"

#include <stdlib.h>
#include <string.h>

#include "roma/context.h"

int roma_test_failures = 0;

static void count(roma_test_log *log, roma_log_level level, roma_result code, const char *message)
{
    if (level == ROMA_LOG_ERROR)
        ++log->errors, log->last_code = code;
    if (level == ROMA_LOG_WARNING)
        ++log->warnings;
    snprintf(log->last, sizeof log->last, "%s", message);
}

static void record(roma_log_level level, roma_result code, const char *message, void *user)
{
    count(user, level, code, message);
    fprintf(stderr, "  [%s] %s\n", roma_log_level_string(level), message);
}

/* record, printing only validation messages (or everything with ROMA_TEST_VERBOSE set). */
static void record_quietly(roma_log_level level, roma_result code, const char *message, void *user)
{
    count(user, level, code, message);
    if (code == ROMA_ERROR_VALIDATION || getenv("ROMA_TEST_VERBOSE"))
        fprintf(stderr, "  [%s] %s\n", roma_log_level_string(level), message);
}

roma_logger roma_test_logger_quiet(roma_test_log *log)
{
    memset(log, 0, sizeof *log);
    roma_logger logger = {record_quietly, log};
    return logger;
}

roma_logger roma_test_logger(roma_test_log *log)
{
    memset(log, 0, sizeof *log);
    roma_logger logger = {record, log};
    return logger;
}

/* Validation errors of the harness's contexts, counted in the logger so that
 * errors raised while a context is destroyed (objects left alive) count too. */
static unsigned validation_errors;

static void count_validation(roma_log_level level, roma_result code, const char *message, void *user)
{
    (void)user;
    if (code == ROMA_ERROR_VALIDATION)
        ++validation_errors;
    if (level >= ROMA_LOG_WARNING)
        fprintf(stderr, "  [%s] %s\n", roma_log_level_string(level), message);
}

unsigned roma_test_sync_validation_flags(void)
{
    const char *plain = getenv("ROMA_TEST_PLAIN_VALIDATION");
    return plain && *plain && strcmp(plain, "0") != 0 ? ROMA_CONTEXT_VALIDATION : ROMA_CONTEXT_SYNC_VALIDATION;
}

roma_context *roma_test_context(void)
{
    return roma_test_context_flags(0);
}

roma_context *roma_test_context_flags(unsigned flags)
{
    roma_context_desc desc = {0};
    desc.flags = ROMA_CONTEXT_VALIDATION | flags;
    desc.logger.fn = count_validation;
    roma_context *ctx = NULL;
    roma_result r = roma_context_create(&desc, &ctx);
    if (r != ROMA_SUCCESS) {
        fprintf(stderr, "roma_context_create failed: %s\n", roma_result_string(r));
        ++roma_test_failures;
        return NULL;
    }
    return ctx;
}

void roma_test_context_finish(roma_context *ctx)
{
    if (!ctx)
        return;
    unsigned before = validation_errors;
    uint32_t counted = roma_context_validation_error_count(ctx);
    roma_context_destroy(ctx);
    if (counted || validation_errors) {
        fprintf(stderr, "%u Vulkan validation error(s), %u of them while destroying the context\n",
                validation_errors, validation_errors - before);
        ++roma_test_failures;
    }
}

int roma_test_scene_file(const char *file, char *buf, size_t size)
{
    const char *dir = getenv("ROMA_SCENES_DIR");
    snprintf(buf, size, "%s/%s", (dir && *dir) ? dir : ".", file);
    FILE *f = fopen(buf, "rb");
    if (!f) {
        fprintf(stderr, "scene file %s not found (ROMA_SCENES_DIR is the repository's scenes/)\n", buf);
        ++roma_test_failures;
        return 0;
    }
    fclose(f);
    return 1;
}

const char *roma_test_tmp_path(const char *name, char *buf, size_t size)
{
    const char *dir = getenv("ROMA_TEST_TMPDIR");
    snprintf(buf, size, "%s/%s", (dir && *dir) ? dir : "/tmp", name);
    return buf;
}

int roma_test_finish(const char *test_name)
{
    if (roma_test_failures) {
        fprintf(stderr, "%s: %d check(s) failed\n", test_name, roma_test_failures);
        return 1;
    }
    printf("%s: all checks passed\n", test_name);
    return 0;
}
