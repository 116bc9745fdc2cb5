/** @file
 * libroma: result codes and logging.
 *
 * Every fallible call returns a roma_result. Details go to the caller's log
 * callback (roma_logger); the library never exits, aborts or asserts on bad
 * input or on a Vulkan failure. The functions here are pure: any thread, any time. */
#ifndef ROMA_RESULT_H
#define ROMA_RESULT_H

#include "roma/api.h"

#ifdef __cplusplus
extern "C" {
#endif

/** What a call returns: ROMA_SUCCESS or the reason it failed (roma_result_string names it).
 *
 * Vulkan failures map as follows; "a Vulkan failure code" in a function's result list means
 * one of these: VK_ERROR_OUT_OF_HOST_MEMORY -> ROMA_ERROR_OUT_OF_HOST_MEMORY;
 * VK_ERROR_OUT_OF_DEVICE_MEMORY, an allocation larger than the device allows or one past
 * roma_context_desc.device_memory_budget -> ROMA_ERROR_OUT_OF_DEVICE_MEMORY;
 * VK_ERROR_DEVICE_LOST -> ROMA_ERROR_DEVICE_LOST; a missing feature, extension, layer or
 * memory type -> ROMA_ERROR_MISSING_FEATURE; any other VkResult -> ROMA_ERROR_VULKAN. */
typedef enum roma_result {
    ROMA_SUCCESS = 0,               /**< the call did what it says */
    ROMA_ERROR_INVALID_ARGUMENT,    /**< NULL handle, out-of-range value, inconsistent desc */
    ROMA_ERROR_OUT_OF_HOST_MEMORY,  /**< a host allocation failed (malloc or VK_ERROR_OUT_OF_HOST_MEMORY) */
    ROMA_ERROR_OUT_OF_DEVICE_MEMORY, /**< device memory exhausted, or the context's memory budget */
    ROMA_ERROR_NO_VULKAN,           /**< no Vulkan loader or driver could be initialised */
    ROMA_ERROR_NO_DEVICE,           /**< no physical device matches the requirements */
    ROMA_ERROR_MISSING_FEATURE,     /**< the device lacks a required feature or extension */
    ROMA_ERROR_VULKAN,              /**< any other Vulkan failure */
    ROMA_ERROR_DEVICE_LOST,         /**< VK_ERROR_DEVICE_LOST: the device must be recreated */
    ROMA_ERROR_FILE_NOT_FOUND,      /**< the path (or an external file it names) does not exist */
    ROMA_ERROR_IO,                  /**< read/write failed on an existing path */
    ROMA_ERROR_PARSE,               /**< malformed file: JSON, GLB container, PFM header */
    ROMA_ERROR_INVALID_SCENE,       /**< well-formed file with unusable data (NaN, bad indices) */
    ROMA_ERROR_EMPTY_SCENE,         /**< no triangle with non-zero area */
    ROMA_ERROR_UNSUPPORTED,         /**< e.g. a required glTF extension libroma cannot decode */
    ROMA_ERROR_NOT_READY,           /**< results asked for before the GPU produced them */
    ROMA_ERROR_VALIDATION,          /**< a Vulkan validation-layer message (logged, never returned) */
    ROMA_RESULT_COUNT_              /**< number of codes (not a result) */
} roma_result;

/** A short English name of a result code, for messages.
 *
 * @param result  any value; values outside the enum are allowed.
 * @return a static string, never NULL; "unknown roma_result" for values outside the enum.
 * @par Threads
 * Any thread. */
ROMA_API const char *roma_result_string(roma_result result);

/** Severity of a logged message. */
typedef enum roma_log_level {
    ROMA_LOG_DEBUG = 0, /**< details for libroma's developers (counts, choices) */
    ROMA_LOG_INFO,      /**< one-off facts (the device chosen) */
    ROMA_LOG_WARNING,   /**< input accepted with a change (a replaced normal, an ignored feature) */
    ROMA_LOG_ERROR      /**< the reason a call fails, or a validation-layer error */
} roma_log_level;

/** The name of a log level.
 *
 * @param level  any value; values outside the enum are allowed.
 * @return a static string: "debug", "info", "warning" or "error"; "unknown" otherwise.
 * @par Threads
 * Any thread. */
ROMA_API const char *roma_log_level_string(roma_log_level level);

/** A log callback.
 *
 * code: for an error, the roma_result the failing call returns (ROMA_ERROR_VALIDATION for
 * a validation-layer message); ROMA_SUCCESS for debug, info and warning messages. Callers
 * can act on the code; the message is for people. message is valid only during the call.
 * The callback runs on the thread of the libroma call that logs (validation-layer messages:
 * inside the Vulkan call that raised them). */
typedef void (*roma_log_fn)(roma_log_level level, roma_result code, const char *message, void *user_data);

/** Where messages go. Zero value: warnings and errors go to stderr. Set fn to route them
 * elsewhere. Objects copy the struct: user_data must outlive every object given it. */
typedef struct roma_logger {
    roma_log_fn fn; /**< called for each message; NULL: the default (stderr, warnings and errors) */
    void *user_data; /**< passed to fn */
} roma_logger;

#ifdef __cplusplus
}
#endif

#endif /* ROMA_RESULT_H */
