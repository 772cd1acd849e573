/* layer_chain.h: the plumbing that a small Vulkan layer of the tests
 * shares (layer_chain.c): the loader's negotiation, vkCreateInstance and
 * vkCreateDevice linked to the next layer down (VK_LAYER_LINK_INFO in
 * pCreateInfo->pNext), and each instance's and device's next functions
 * kept by dispatch key. Everything a layer does not take is the next
 * layer's own function, so a layer intercepts only what it changes.
 *
 * A layer built on it defines layer_name, layer_function and
 * layer_device_info (below). tp2 makes few instances and devices, one at a
 * time; up to LAYER_MAX_OBJECTS of each may live at once. */
#ifndef TP2_LAYER_CHAIN_H
#define TP2_LAYER_CHAIN_H

#include <vulkan/vk_layer.h>
#include <vulkan/vulkan.h>

#define LAYER_MAX_OBJECTS 16

/* What a layer calls below itself, for one instance. */
struct layer_instance {
    PFN_vkGetInstanceProcAddr next_gipa;
    PFN_vkDestroyInstance destroy;
    PFN_vkGetPhysicalDeviceFeatures get_features;
    PFN_vkGetPhysicalDeviceFeatures2 get_features2;
};

/* ... and for one device. */
struct layer_device {
    PFN_vkGetDeviceProcAddr next_gdpa;
    PFN_vkDestroyDevice destroy;
    PFN_vkCreateShaderModule create_shader_module;
};

/* The next functions of the instance a VkInstance or VkPhysicalDevice
 * belongs to, and of a VkDevice (NULL: not made through this layer). */
const struct layer_instance *layer_instance_of(const void *dispatchable);
const struct layer_device *layer_device_of(VkDevice device);

/* Defined by each layer: its name (the manifest's), for its messages. */
extern const char layer_name[];

/* Defined by each layer: its own function of that Vulkan name, other than
 * vkCreateInstance, vkDestroyInstance, vkCreateDevice, vkDestroyDevice and
 * the ProcAddr functions; NULL where it leaves that one to the next. */
PFN_vkVoidFunction layer_function(const char *name);

/* Defined by each layer: *out, the create info that vkCreateDevice passes
 * down (a copy of *in; *features is room for a changed copy of
 * pEnabledFeatures). VK_SUCCESS, or the error that refuses the device. */
VkResult layer_device_info(VkPhysicalDevice physical, const VkDeviceCreateInfo *in,
                           VkDeviceCreateInfo *out, VkPhysicalDeviceFeatures *features);

#endif
