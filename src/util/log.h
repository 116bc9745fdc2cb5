/* Internal logging helpers: printf-style messages to a roma_logger. */
#ifndef ROMA_UTIL_LOG_H
#define ROMA_UTIL_LOG_H

#include "roma/result.h"

#if defined(__GNUC__)
#define ROMA_PRINTF(fmt_index, first_arg) __attribute__((format(printf, fmt_index, first_arg)))
#else
#define ROMA_PRINTF(fmt_index, first_arg)
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* logger may be NULL or zeroed: warnings and errors then go to stderr. */
void roma_logf(const roma_logger *logger, roma_log_level level, const char *fmt, ...)
    ROMA_PRINTF(3, 4);

/* An error message with the code the failing call will return (when they are not one line). */
void roma_log_error(const roma_logger *logger, roma_result code, const char *fmt, ...) ROMA_PRINTF(3, 4);
/* Logs an error and returns `result`, for one-line failure paths. */
roma_result roma_fail(const roma_logger *logger, roma_result result, const char *fmt, ...)
    ROMA_PRINTF(3, 4);

#ifdef __cplusplus
}
#endif

#endif /* ROMA_UTIL_LOG_H */
