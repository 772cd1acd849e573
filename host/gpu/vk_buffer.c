#include "vk_buffer.h"

#include <stdint.h>
#include <string.h>

#include "vk_check.h"

/* Texel: objects and BVH nodes are read through texel views. */
static const VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                        VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                                        VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT;

/* An unbound buffer of `size` bytes (next: its create info's chain) and
 * what memory it needs. */
static int create_buffer(const struct vkc *c, VkDeviceSize size, const void *next,
                         struct vk_buffer *b, VkMemoryRequirements *req)
{
    memset(b, 0, sizeof *b);
    b->size = size;
    VkBufferCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO,
        .pNext = next,
        .size = size,
        .usage = usage,
        .sharingMode = VK_SHARING_MODE_EXCLUSIVE,
    };
    TP2_VK_TRY(vkCreateBuffer(c->device, &info, NULL, &b->buffer));
    vkGetBufferMemoryRequirements(c->device, b->buffer, req);
    return 0;
}

/* Allocates `bytes` of memory type `type` (next: the allocation's chain)
 * and binds b to it. */
static int bind_memory(const struct vkc *c, struct vk_buffer *b, int type, VkDeviceSize bytes,
                       const void *next)
{
    VkMemoryAllocateInfo alloc = {
        .sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO,
        .pNext = next,
        .allocationSize = bytes,
        .memoryTypeIndex = (uint32_t)type,
    };
    TP2_VK_TRY(vkAllocateMemory(c->device, &alloc, NULL, &b->memory));
    TP2_VK_TRY(vkBindBufferMemory(c->device, b->buffer, b->memory, 0));
    return 0;
}

int vk_buffer_create(const struct vkc *c, VkDeviceSize size, bool readback,
                     struct vk_buffer *b)
{
    VkMemoryRequirements req;
    if (create_buffer(c, size, NULL, b, &req) != 0)
        return -1;
    VkMemoryPropertyFlags want = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                 VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    VkMemoryPropertyFlags prefer = readback ? VK_MEMORY_PROPERTY_HOST_CACHED_BIT
                                            : VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
    int type = vkc_memory_type(c, req.memoryTypeBits, want, prefer);
    if (type < 0) {
        fputs("tp2: the device has no host-visible coherent memory\n", stderr);
        return -1;
    }
    if (bind_memory(c, b, type, req.size, NULL) != 0)
        return -1;
    TP2_VK_TRY(vkMapMemory(c->device, b->memory, 0, VK_WHOLE_SIZE, 0, &b->mapped));
    return 0;
}

int vk_buffer_import(const struct vkc *c, void *host, VkDeviceSize size,
                     VkDeviceSize capacity, struct vk_buffer *b)
{
    const VkExternalMemoryHandleTypeFlagBits handle =
        VK_EXTERNAL_MEMORY_HANDLE_TYPE_HOST_ALLOCATION_BIT_EXT;
    VkDeviceSize align = c->host_import;
    if (!align || capacity == 0 || capacity % align != 0 || (uintptr_t)host % align != 0)
        return 1;
    VkPhysicalDeviceExternalBufferInfo query = {
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_EXTERNAL_BUFFER_INFO,
        .usage = usage,
        .handleType = handle,
    };
    VkExternalBufferProperties can = {.sType = VK_STRUCTURE_TYPE_EXTERNAL_BUFFER_PROPERTIES};
    vkGetPhysicalDeviceExternalBufferProperties(c->physical, &query, &can);
    if (!(can.externalMemoryProperties.externalMemoryFeatures &
          VK_EXTERNAL_MEMORY_FEATURE_IMPORTABLE_BIT))
        return 1;
    VkExternalMemoryBufferCreateInfo external = {
        .sType = VK_STRUCTURE_TYPE_EXTERNAL_MEMORY_BUFFER_CREATE_INFO,
        .handleTypes = handle,
    };
    VkMemoryRequirements req;
    if (create_buffer(c, size, &external, b, &req) != 0)
        return -1;
    VkMemoryHostPointerPropertiesEXT host_props = {
        .sType = VK_STRUCTURE_TYPE_MEMORY_HOST_POINTER_PROPERTIES_EXT,
    };
    TP2_VK_TRY(c->host_pointer_properties(c->device, handle, host, &host_props));
    int type = vkc_memory_type(c, req.memoryTypeBits & host_props.memoryTypeBits, 0,
                               VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    if (type < 0 || req.size > capacity) {
        fputs("tp2: the device cannot read the scene from host memory\n", stderr);
        return -1;
    }
    VkImportMemoryHostPointerInfoEXT import = {
        .sType = VK_STRUCTURE_TYPE_IMPORT_MEMORY_HOST_POINTER_INFO_EXT,
        .handleType = handle,
        .pHostPointer = host,
    };
    if (bind_memory(c, b, type, capacity, &import) != 0)
        return -1;
    b->mapped = host;
    b->imported = true;
    return 0;
}

void vk_buffer_destroy(const struct vkc *c, struct vk_buffer *b)
{
    if (b->mapped && !b->imported)
        vkUnmapMemory(c->device, b->memory);
    if (b->buffer)
        vkDestroyBuffer(c->device, b->buffer, NULL);
    if (b->memory)
        vkFreeMemory(c->device, b->memory, NULL);
    memset(b, 0, sizeof *b);
}
