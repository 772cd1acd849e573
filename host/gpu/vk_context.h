/* vk_context.h: the Vulkan instance, the chosen device and its queue. */
#ifndef TP2_VK_CONTEXT_H
#define TP2_VK_CONTEXT_H

#include <stdbool.h>
#include <stdio.h>
#include <vulkan/vulkan.h>

struct vkc;

struct vkc_options {
    int device_index; /* index from vkc_list_devices(), or -1: the best */
    bool need_float64; /* fail without shaderFloat64 */
    bool want_float64; /* enable shaderFloat64 where the device has it */
    bool validate; /* enable VK_LAYER_KHRONOS_validation and count messages */
    /* Called once the physical device is chosen and c->props and
     * c->float64 are set, before the logical device is created: a caller
     * may decide what to prepare beside the rest. NULL: none. */
    void (*chosen)(const struct vkc *c, void *user);
    void *chosen_user;
};

struct vkc {
    VkInstance instance;
    VkDebugUtilsMessengerEXT messenger;
    VkPhysicalDevice physical;
    VkPhysicalDeviceProperties props;
    VkPhysicalDeviceMemoryProperties memory;
    VkDevice device;
    VkQueue queue;
    uint32_t queue_family;
    bool float64; /* shaderFloat64 is enabled */
    /* On a CPU device with VK_EXT_external_memory_host: the alignment of
     * host memory it can read in place (vk_buffer_import); 0 elsewhere. */
    VkDeviceSize host_import;
    PFN_vkGetMemoryHostPointerPropertiesEXT host_pointer_properties;
};

/* Creates the instance and device. Returns 0, or -1 after printing one
 * "tp2: ..." line; vkc_destroy() is safe either way. */
int vkc_create(struct vkc *c, const struct vkc_options *opt);

/* Waits for the device, then destroys in reverse order; zeroes c. */
void vkc_destroy(struct vkc *c);

/* Prints "INDEX: NAME (TYPE)" per device, the default marked; 0 or -1. */
int vkc_list_devices(FILE *out);

/* Validation messages seen by any context since the program started. */
unsigned vkc_validation_message_count(void);

/* Index of a memory type with all of `want` among the bits of `allowed`,
 * preferring one that also has `prefer`; -1 if none. */
int vkc_memory_type(const struct vkc *c, uint32_t allowed,
                    VkMemoryPropertyFlags want, VkMemoryPropertyFlags prefer);

#endif
