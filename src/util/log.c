#include "util/log.h"

#include <stdarg.h>
#include <stdio.h>

static void vlog(const roma_logger *logger, roma_log_level level, roma_result code, const char *fmt, va_list args)
{
    char message[1024];
    vsnprintf(message, sizeof message, fmt, args);
    if (logger && logger->fn) {
        logger->fn(level, code, message, logger->user_data);
    } else if (level >= ROMA_LOG_WARNING) {
        fprintf(stderr, "libroma %s: %s\n", roma_log_level_string(level), message);
    }
}

void roma_logf(const roma_logger *logger, roma_log_level level, const char *fmt, ...)
{
    va_list args;
    va_start(args, fmt);
    vlog(logger, level, ROMA_SUCCESS, fmt, args);
    va_end(args);
}

void roma_log_error(const roma_logger *logger, roma_result code, const char *fmt, ...)
{
    va_list args;
    va_start(args, fmt);
    vlog(logger, ROMA_LOG_ERROR, code, fmt, args);
    va_end(args);
}

roma_result roma_fail(const roma_logger *logger, roma_result result, const char *fmt, ...)
{
    va_list args;
    va_start(args, fmt);
    vlog(logger, ROMA_LOG_ERROR, result, fmt, args);
    va_end(args);
    return result;
}
