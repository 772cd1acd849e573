/* no_fp64.c: VK_LAYER_TP2_no_fp64, a device without shaderFloat64 made
 * of one that has it (lavapipe), for tests. The feature reads VK_FALSE in
 * vkGetPhysicalDeviceFeatures and vkGetPhysicalDeviceFeatures2; a
 * vkCreateDevice that asks for it, and a vkCreateShaderModule whose
 * SPIR-V declares the Float64 capability, are refused with
 * VK_ERROR_FEATURE_NOT_PRESENT and a line on stderr. So a program that
 * runs under it used no double on the device, whatever its own checks
 * say. */
#include <stdbool.h>
#include <stdio.h>
#include <string.h>

#include "layer_chain.h"

const char layer_name[] = "VK_LAYER_TP2_no_fp64";

enum { SPIRV_HEADER_WORDS = 5, OP_CAPABILITY = 17, CAPABILITY_FLOAT64 = 10 };

static VKAPI_ATTR void VKAPI_CALL get_features(VkPhysicalDevice physical,
                                               VkPhysicalDeviceFeatures *features)
{
    layer_instance_of(physical)->get_features(physical, features);
    features->shaderFloat64 = VK_FALSE;
}

static VKAPI_ATTR void VKAPI_CALL get_features2(VkPhysicalDevice physical,
                                                VkPhysicalDeviceFeatures2 *features)
{
    layer_instance_of(physical)->get_features2(physical, features);
    features->features.shaderFloat64 = VK_FALSE;
}

/* Whether the module declares OpCapability Float64 (it may sit anywhere
 * in the capability section; a malformed module is the driver's to
 * refuse). */
static bool declares_float64(const uint32_t *code, size_t words)
{
    for (size_t at = SPIRV_HEADER_WORDS; at < words;) {
        uint32_t count = code[at] >> 16;
        if (count == 0 || count > words - at)
            return false;
        if ((code[at] & 0xffffu) == OP_CAPABILITY && count == 2 &&
            code[at + 1] == CAPABILITY_FLOAT64)
            return true;
        at += count;
    }
    return false;
}

static VKAPI_ATTR VkResult VKAPI_CALL create_shader_module(VkDevice device,
                                                          const VkShaderModuleCreateInfo *info,
                                                          const VkAllocationCallbacks *alloc,
                                                          VkShaderModule *module)
{
    if (declares_float64(info->pCode, info->codeSize / 4)) {
        fprintf(stderr, "%s: refused a shader module that declares Float64\n", layer_name);
        return VK_ERROR_FEATURE_NOT_PRESENT;
    }
    return layer_device_of(device)->create_shader_module(device, info, alloc, module);
}

PFN_vkVoidFunction layer_function(const char *name)
{
    if (strcmp(name, "vkGetPhysicalDeviceFeatures") == 0)
        return (PFN_vkVoidFunction)get_features;
    if (strcmp(name, "vkGetPhysicalDeviceFeatures2") == 0 ||
        strcmp(name, "vkGetPhysicalDeviceFeatures2KHR") == 0)
        return (PFN_vkVoidFunction)get_features2;
    if (strcmp(name, "vkCreateShaderModule") == 0)
        return (PFN_vkVoidFunction)create_shader_module;
    return NULL;
}

VkResult layer_device_info(VkPhysicalDevice physical, const VkDeviceCreateInfo *in,
                           VkDeviceCreateInfo *out, VkPhysicalDeviceFeatures *features)
{
    (void)physical, (void)features;
    bool asked = in->pEnabledFeatures && in->pEnabledFeatures->shaderFloat64;
    for (const VkBaseInStructure *s = in->pNext; s; s = s->pNext)
        if (s->sType == VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2)
            asked |= ((const VkPhysicalDeviceFeatures2 *)s)->features.shaderFloat64 != 0;
    if (asked) {
        fprintf(stderr, "%s: refused a device that asks for shaderFloat64\n", layer_name);
        return VK_ERROR_FEATURE_NOT_PRESENT;
    }
    *out = *in;
    return VK_SUCCESS;
}
