#include "vk_buffer.h"

#include <string.h>

#include "vk_check.h"

int vk_buffer_create(const struct vkc *c, VkDeviceSize size, bool readback,
                     struct vk_buffer *b)
{
    memset(b, 0, sizeof *b);
    b->size = size;
    VkBufferCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO,
        .size = size,
        /* Texel: objects and BVH nodes are read through texel views. */
        .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                 VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT,
        .sharingMode = VK_SHARING_MODE_EXCLUSIVE,
    };
    TP2_VK_TRY(vkCreateBuffer(c->device, &info, NULL, &b->buffer));
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(c->device, b->buffer, &req);
    VkMemoryPropertyFlags want = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                 VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    VkMemoryPropertyFlags prefer = readback ? VK_MEMORY_PROPERTY_HOST_CACHED_BIT
                                            : VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
    int type = vkc_memory_type(c, req.memoryTypeBits, want, prefer);
    if (type < 0) {
        fputs("tp2: the device has no host-visible coherent memory\n", stderr);
        return -1;
    }
    VkMemoryAllocateInfo alloc = {
        .sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO,
        .allocationSize = req.size,
        .memoryTypeIndex = (uint32_t)type,
    };
    TP2_VK_TRY(vkAllocateMemory(c->device, &alloc, NULL, &b->memory));
    TP2_VK_TRY(vkBindBufferMemory(c->device, b->buffer, b->memory, 0));
    TP2_VK_TRY(vkMapMemory(c->device, b->memory, 0, VK_WHOLE_SIZE, 0, &b->mapped));
    return 0;
}

void vk_buffer_destroy(const struct vkc *c, struct vk_buffer *b)
{
    if (b->mapped)
        vkUnmapMemory(c->device, b->memory);
    if (b->buffer)
        vkDestroyBuffer(c->device, b->buffer, NULL);
    if (b->memory)
        vkFreeMemory(c->device, b->memory, NULL);
    memset(b, 0, sizeof *b);
}
