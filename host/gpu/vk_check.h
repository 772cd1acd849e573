/* vk_check.h: every Vulkan call is checked, always (no assert). */
#ifndef TP2_VK_CHECK_H
#define TP2_VK_CHECK_H

#include <vulkan/vulkan.h>

/* The enumerator's name, e.g. "VK_ERROR_OUT_OF_DEVICE_MEMORY". */
const char *vk_result_name(VkResult r);

/* Prints "tp2: CALL failed: NAME (FILE:LINE)" on stderr. */
void vk_report(const char *call, VkResult r, const char *file, int line);

/* Runs a call returning VkResult; on failure reports it and returns -1 from
 * the enclosing function (which must return int). */
#define TP2_VK_TRY(call)                                          \
    do {                                                          \
        VkResult tp2_r_ = (call);                                 \
        if (tp2_r_ != VK_SUCCESS) {                               \
            vk_report(#call, tp2_r_, __FILE__, __LINE__);         \
            return -1;                                            \
        }                                                         \
    } while (0)

#endif
