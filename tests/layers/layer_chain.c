#include "layer_chain.h"

#include <pthread.h>
#include <string.h>

#define LAYER_EXPORT __attribute__((visibility("default")))

/* The loader's dispatch table pointer, first in every dispatchable
 * object: the same for an instance and its physical devices. */
static void *key_of(const void *dispatchable)
{
    return *(void *const *)dispatchable;
}

static pthread_mutex_t lock = PTHREAD_MUTEX_INITIALIZER;
static struct {
    void *key;
    struct layer_instance next;
} instances[LAYER_MAX_OBJECTS];
static struct {
    void *key;
    struct layer_device next;
} devices[LAYER_MAX_OBJECTS];

const struct layer_instance *layer_instance_of(const void *dispatchable)
{
    void *key = key_of(dispatchable);
    const struct layer_instance *found = NULL;
    pthread_mutex_lock(&lock);
    for (int i = 0; i < LAYER_MAX_OBJECTS && !found; i++)
        if (instances[i].key == key)
            found = &instances[i].next;
    pthread_mutex_unlock(&lock);
    return found;
}

const struct layer_device *layer_device_of(VkDevice device)
{
    void *key = key_of(device);
    const struct layer_device *found = NULL;
    pthread_mutex_lock(&lock);
    for (int i = 0; i < LAYER_MAX_OBJECTS && !found; i++)
        if (devices[i].key == key)
            found = &devices[i].next;
    pthread_mutex_unlock(&lock);
    return found;
}

/* The loader's link for this layer in a create info's pNext chain. */
static void *link_info(const void *next, VkStructureType type)
{
    for (const VkBaseInStructure *s = next; s; s = s->pNext)
        if (s->sType == type && ((const VkLayerInstanceCreateInfo *)s)->function ==
                                    VK_LAYER_LINK_INFO)
            return (void *)s;
    return NULL;
}

static VKAPI_ATTR VkResult VKAPI_CALL create_instance(const VkInstanceCreateInfo *info,
                                                      const VkAllocationCallbacks *alloc,
                                                      VkInstance *instance)
{
    VkLayerInstanceCreateInfo *chain =
        link_info(info->pNext, VK_STRUCTURE_TYPE_LOADER_INSTANCE_CREATE_INFO);
    if (!chain)
        return VK_ERROR_INITIALIZATION_FAILED;
    PFN_vkGetInstanceProcAddr gipa = chain->u.pLayerInfo->pfnNextGetInstanceProcAddr;
    chain->u.pLayerInfo = chain->u.pLayerInfo->pNext; /* the next layer's link */
    PFN_vkCreateInstance next_create = (PFN_vkCreateInstance)gipa(NULL, "vkCreateInstance");
    VkResult r = next_create(info, alloc, instance);
    if (r != VK_SUCCESS)
        return r;
    /* resolved now: asked later, the loader's end of the chain answers
     * with the top of the chain */
    struct layer_instance next = {
        gipa,
        (PFN_vkDestroyInstance)gipa(*instance, "vkDestroyInstance"),
        (PFN_vkGetPhysicalDeviceFeatures)gipa(*instance, "vkGetPhysicalDeviceFeatures"),
        (PFN_vkGetPhysicalDeviceFeatures2)gipa(*instance, "vkGetPhysicalDeviceFeatures2"),
    };
    int i = 0;
    pthread_mutex_lock(&lock);
    while (i < LAYER_MAX_OBJECTS && instances[i].key)
        i++;
    if (i < LAYER_MAX_OBJECTS)
        instances[i].key = key_of(*instance), instances[i].next = next;
    pthread_mutex_unlock(&lock);
    if (i == LAYER_MAX_OBJECTS) {
        ((PFN_vkDestroyInstance)gipa(*instance, "vkDestroyInstance"))(*instance, alloc);
        return VK_ERROR_OUT_OF_HOST_MEMORY;
    }
    return VK_SUCCESS;
}

static VKAPI_ATTR void VKAPI_CALL destroy_instance(VkInstance instance,
                                                  const VkAllocationCallbacks *alloc)
{
    if (!instance)
        return;
    const struct layer_instance *next = layer_instance_of(instance);
    if (!next)
        return;
    PFN_vkDestroyInstance destroy = next->destroy;
    void *key = key_of(instance);
    destroy(instance, alloc);
    pthread_mutex_lock(&lock);
    for (int i = 0; i < LAYER_MAX_OBJECTS; i++)
        if (instances[i].key == key)
            instances[i].key = NULL;
    pthread_mutex_unlock(&lock);
}

static VKAPI_ATTR VkResult VKAPI_CALL create_device(VkPhysicalDevice physical,
                                                    const VkDeviceCreateInfo *info,
                                                    const VkAllocationCallbacks *alloc,
                                                    VkDevice *device)
{
    VkLayerDeviceCreateInfo *chain =
        link_info(info->pNext, VK_STRUCTURE_TYPE_LOADER_DEVICE_CREATE_INFO);
    if (!chain)
        return VK_ERROR_INITIALIZATION_FAILED;
    VkDeviceCreateInfo down;
    VkPhysicalDeviceFeatures features;
    VkResult r = layer_device_info(physical, info, &down, &features);
    if (r != VK_SUCCESS)
        return r;
    PFN_vkGetInstanceProcAddr gipa = chain->u.pLayerInfo->pfnNextGetInstanceProcAddr;
    PFN_vkGetDeviceProcAddr gdpa = chain->u.pLayerInfo->pfnNextGetDeviceProcAddr;
    chain->u.pLayerInfo = chain->u.pLayerInfo->pNext;
    PFN_vkCreateDevice next_create = (PFN_vkCreateDevice)gipa(NULL, "vkCreateDevice");
    r = next_create(physical, &down, alloc, device);
    if (r != VK_SUCCESS)
        return r;
    struct layer_device next = {
        gdpa, (PFN_vkDestroyDevice)gdpa(*device, "vkDestroyDevice"),
        (PFN_vkCreateShaderModule)gdpa(*device, "vkCreateShaderModule")};
    int i = 0;
    pthread_mutex_lock(&lock);
    while (i < LAYER_MAX_OBJECTS && devices[i].key)
        i++;
    if (i < LAYER_MAX_OBJECTS)
        devices[i].key = key_of(*device), devices[i].next = next;
    pthread_mutex_unlock(&lock);
    if (i == LAYER_MAX_OBJECTS) {
        ((PFN_vkDestroyDevice)gdpa(*device, "vkDestroyDevice"))(*device, alloc);
        return VK_ERROR_OUT_OF_HOST_MEMORY;
    }
    return VK_SUCCESS;
}

static VKAPI_ATTR void VKAPI_CALL destroy_device(VkDevice device,
                                                const VkAllocationCallbacks *alloc)
{
    if (!device)
        return;
    const struct layer_device *next = layer_device_of(device);
    if (!next)
        return;
    PFN_vkDestroyDevice destroy = next->destroy;
    void *key = key_of(device);
    destroy(device, alloc);
    pthread_mutex_lock(&lock);
    for (int i = 0; i < LAYER_MAX_OBJECTS; i++)
        if (devices[i].key == key)
            devices[i].key = NULL;
    pthread_mutex_unlock(&lock);
}

static VKAPI_ATTR PFN_vkVoidFunction VKAPI_CALL get_device_proc_addr(VkDevice device,
                                                                      const char *name);

/* This layer's function of that name, whether instance or device level. */
static PFN_vkVoidFunction own(const char *name)
{
    static const struct {
        const char *name;
        PFN_vkVoidFunction fn;
    } chain[] = {
        {"vkCreateInstance", (PFN_vkVoidFunction)create_instance},
        {"vkDestroyInstance", (PFN_vkVoidFunction)destroy_instance},
        {"vkCreateDevice", (PFN_vkVoidFunction)create_device},
        {"vkDestroyDevice", (PFN_vkVoidFunction)destroy_device},
        {"vkGetDeviceProcAddr", (PFN_vkVoidFunction)get_device_proc_addr},
    };
    for (size_t i = 0; i < sizeof chain / sizeof chain[0]; i++)
        if (strcmp(chain[i].name, name) == 0)
            return chain[i].fn;
    return layer_function(name);
}

/* The ProcAddr functions are static, and the loader is given these, not
 * the exported names: a reference to an exported vkGetInstanceProcAddr
 * would bind to the loader's own (libvulkan's comes first). */
static VKAPI_ATTR PFN_vkVoidFunction VKAPI_CALL get_instance_proc_addr(VkInstance instance,
                                                                        const char *name)
{
    if (strcmp(name, "vkGetInstanceProcAddr") == 0)
        return (PFN_vkVoidFunction)get_instance_proc_addr;
    PFN_vkVoidFunction fn = own(name);
    if (fn)
        return fn;
    const struct layer_instance *next = instance ? layer_instance_of(instance) : NULL;
    return next ? next->next_gipa(instance, name) : NULL;
}

static VKAPI_ATTR PFN_vkVoidFunction VKAPI_CALL get_device_proc_addr(VkDevice device,
                                                                      const char *name)
{
    PFN_vkVoidFunction fn = own(name);
    if (fn)
        return fn;
    const struct layer_device *next = device ? layer_device_of(device) : NULL;
    return next ? next->next_gdpa(device, name) : NULL;
}

LAYER_EXPORT VKAPI_ATTR VkResult VKAPI_CALL
vkNegotiateLoaderLayerInterfaceVersion(VkNegotiateLayerInterface *v)
{
    if (!v || v->sType != LAYER_NEGOTIATE_INTERFACE_STRUCT)
        return VK_ERROR_INITIALIZATION_FAILED;
    if (v->loaderLayerInterfaceVersion > 2)
        v->loaderLayerInterfaceVersion = 2;
    v->pfnGetInstanceProcAddr = get_instance_proc_addr;
    v->pfnGetDeviceProcAddr = get_device_proc_addr;
    v->pfnGetPhysicalDeviceProcAddr = NULL;
    return VK_SUCCESS;
}
