/* vk_buffer.h: host-visible storage buffers, mapped for their lifetime. */
#ifndef TP2_VK_BUFFER_H
#define TP2_VK_BUFFER_H

#include "vk_context.h"

struct vk_buffer {
    VkBuffer buffer;
    VkDeviceMemory memory;
    void *mapped;
    VkDeviceSize size;
    bool imported; /* mapped is host memory the device reads in place */
};

/* Creates a storage buffer of `size` bytes, mapped and coherent; `readback`
 * prefers cached memory (the host reads it), otherwise device-local memory
 * (the shader reads it). Returns 0 or -1 after a message. */
int vk_buffer_create(const struct vkc *c, VkDeviceSize size, bool readback,
                     struct vk_buffer *b);

/* A buffer of `size` bytes that the device reads from host memory in
 * place: `host` owns `capacity` bytes (at least `size`) and must outlive
 * the buffer. Returns 0; 1 if the device cannot import it (c->host_import
 * is 0, capacity is 0, or host or capacity is not a multiple of it, or the
 * device refuses such a buffer): then copy it; or -1 after a message. */
int vk_buffer_import(const struct vkc *c, void *host, VkDeviceSize size,
                     VkDeviceSize capacity, struct vk_buffer *b);

/* Unmaps and frees; safe on a zeroed buffer. */
void vk_buffer_destroy(const struct vkc *c, struct vk_buffer *b);

#endif
