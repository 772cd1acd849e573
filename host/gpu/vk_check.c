#include "vk_check.h"

#include <stdio.h>
#include <string.h>

const char *vk_result_name(VkResult r)
{
    switch (r) {
#define TP2_NAME(x) case x: return #x;
    TP2_NAME(VK_SUCCESS)
    TP2_NAME(VK_NOT_READY)
    TP2_NAME(VK_TIMEOUT)
    TP2_NAME(VK_EVENT_SET)
    TP2_NAME(VK_EVENT_RESET)
    TP2_NAME(VK_INCOMPLETE)
    TP2_NAME(VK_ERROR_OUT_OF_HOST_MEMORY)
    TP2_NAME(VK_ERROR_OUT_OF_DEVICE_MEMORY)
    TP2_NAME(VK_ERROR_INITIALIZATION_FAILED)
    TP2_NAME(VK_ERROR_DEVICE_LOST)
    TP2_NAME(VK_ERROR_MEMORY_MAP_FAILED)
    TP2_NAME(VK_ERROR_LAYER_NOT_PRESENT)
    TP2_NAME(VK_ERROR_EXTENSION_NOT_PRESENT)
    TP2_NAME(VK_ERROR_FEATURE_NOT_PRESENT)
    TP2_NAME(VK_ERROR_INCOMPATIBLE_DRIVER)
    TP2_NAME(VK_ERROR_TOO_MANY_OBJECTS)
    TP2_NAME(VK_ERROR_FORMAT_NOT_SUPPORTED)
    TP2_NAME(VK_ERROR_FRAGMENTED_POOL)
    TP2_NAME(VK_ERROR_UNKNOWN)
    TP2_NAME(VK_ERROR_OUT_OF_POOL_MEMORY)
    TP2_NAME(VK_ERROR_INVALID_EXTERNAL_HANDLE)
    TP2_NAME(VK_ERROR_FRAGMENTATION)
    TP2_NAME(VK_ERROR_INVALID_OPAQUE_CAPTURE_ADDRESS)
    TP2_NAME(VK_PIPELINE_COMPILE_REQUIRED)
#undef TP2_NAME
    default: return "unknown VkResult";
    }
}

void vk_report(const char *call, VkResult r, const char *file, int line)
{
    /* Name the function, not its argument list. */
    size_t n = strcspn(call, "(");
    fprintf(stderr, "tp2: %.*s failed: %s (%s:%d)\n", (int)n, call,
            vk_result_name(r), file, line);
}
