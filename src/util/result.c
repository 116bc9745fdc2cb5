#include "roma/result.h"

const char *roma_result_string(roma_result result)
{
    switch (result) {
    case ROMA_SUCCESS: return "success";
    case ROMA_ERROR_INVALID_ARGUMENT: return "invalid argument";
    case ROMA_ERROR_OUT_OF_HOST_MEMORY: return "out of host memory";
    case ROMA_ERROR_OUT_OF_DEVICE_MEMORY: return "out of device memory";
    case ROMA_ERROR_NO_VULKAN: return "no Vulkan loader or driver";
    case ROMA_ERROR_NO_DEVICE: return "no suitable Vulkan device";
    case ROMA_ERROR_MISSING_FEATURE: return "device lacks a required feature";
    case ROMA_ERROR_VULKAN: return "Vulkan error";
    case ROMA_ERROR_DEVICE_LOST: return "device lost";
    case ROMA_ERROR_FILE_NOT_FOUND: return "file not found";
    case ROMA_ERROR_IO: return "I/O error";
    case ROMA_ERROR_PARSE: return "malformed file";
    case ROMA_ERROR_INVALID_SCENE: return "invalid scene data";
    case ROMA_ERROR_EMPTY_SCENE: return "empty scene";
    case ROMA_ERROR_UNSUPPORTED: return "unsupported";
    case ROMA_ERROR_NOT_READY: return "not ready";
    case ROMA_ERROR_VALIDATION: return "Vulkan validation message";
    case ROMA_RESULT_COUNT_: break;
    }
    return "unknown roma_result";
}

const char *roma_log_level_string(roma_log_level level)
{
    switch (level) {
    case ROMA_LOG_DEBUG: return "debug";
    case ROMA_LOG_INFO: return "info";
    case ROMA_LOG_WARNING: return "warning";
    case ROMA_LOG_ERROR: return "error";
    }
    return "unknown";
}
