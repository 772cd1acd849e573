/* fused.c: VK_LAYER_TP2_fused, a device whose compiler fuses
 * multiply-adds, made of one that never does (lavapipe), for tests. Every
 * shader module is rewritten by spirv_fused (spirv_fused.h) before the
 * driver sees it, and one line on stderr says how many operations each
 * had fused. The rewrite computes in double, so vkCreateDevice turns
 * shaderFloat64 on below the program (which need not ask for it), and
 * refuses a device that lacks it. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "layer_chain.h"
#include "spirv_fused.h"

const char layer_name[] = "VK_LAYER_TP2_fused";

static VKAPI_ATTR VkResult VKAPI_CALL create_shader_module(VkDevice device,
                                                          const VkShaderModuleCreateInfo *info,
                                                          const VkAllocationCallbacks *alloc,
                                                          VkShaderModule *module)
{
    size_t words = 0, sites = 0;
    uint32_t *code = spirv_fused(info->pCode, info->codeSize / 4, &words, &sites);
    if (!code) {
        fprintf(stderr, "%s: could not rewrite a shader module\n", layer_name);
        return VK_ERROR_OUT_OF_HOST_MEMORY;
    }
    fprintf(stderr, "%s: %zu operations fused in a module of %zu words\n", layer_name, sites,
            info->codeSize / 4);
    VkShaderModuleCreateInfo down = *info;
    down.pCode = code;
    down.codeSize = words * sizeof *code;
    VkResult r = layer_device_of(device)->create_shader_module(device, &down, alloc, module);
    free(code);
    return r;
}

PFN_vkVoidFunction layer_function(const char *name)
{
    if (strcmp(name, "vkCreateShaderModule") == 0)
        return (PFN_vkVoidFunction)create_shader_module;
    return NULL;
}

VkResult layer_device_info(VkPhysicalDevice physical, const VkDeviceCreateInfo *in,
                           VkDeviceCreateInfo *out, VkPhysicalDeviceFeatures *features)
{
    VkPhysicalDeviceFeatures have;
    layer_instance_of(physical)->get_features(physical, &have);
    if (!have.shaderFloat64) {
        fprintf(stderr, "%s: the device has no shaderFloat64, which the rewrite needs\n",
                layer_name);
        return VK_ERROR_FEATURE_NOT_PRESENT;
    }
    for (const VkBaseInStructure *s = in->pNext; s; s = s->pNext)
        if (s->sType == VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2 &&
            !((const VkPhysicalDeviceFeatures2 *)s)->features.shaderFloat64) {
            /* kept simple: tp2 asks through pEnabledFeatures */
            fprintf(stderr, "%s: VkPhysicalDeviceFeatures2 in vkCreateDevice is not "
                            "supported\n", layer_name);
            return VK_ERROR_FEATURE_NOT_PRESENT;
        }
    *out = *in;
    if (in->pEnabledFeatures)
        *features = *in->pEnabledFeatures;
    else
        memset(features, 0, sizeof *features);
    features->shaderFloat64 = VK_TRUE;
    for (const VkBaseInStructure *s = in->pNext; s; s = s->pNext)
        if (s->sType == VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2)
            return VK_SUCCESS; /* asks for it already */
    out->pEnabledFeatures = features;
    return VK_SUCCESS;
}
