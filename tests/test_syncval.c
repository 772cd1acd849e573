/* test_syncval.c: --validate turns on synchronization validation too.
 *
 * Through a context made by vkc_create with validation on, two writes of
 * one buffer (vkCmdFillBuffer twice) are submitted, first with a barrier
 * between them (nothing may be reported), then without one: the layer
 * must report SYNC-HAZARD-WRITE-AFTER-WRITE, which it does only when
 * VkValidationFeaturesEXT reached it. Prints "N passed, M failed" last. */
#define _POSIX_C_SOURCE 200809L
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "vk_check.h"
#include "vk_context.h"

#include "unit.h"

/* Records and runs fill, [barrier,] fill on buf; 0 or -1. */
static int run_fills(const struct vkc *c, VkBuffer buf, bool barrier)
{
    VkCommandPoolCreateInfo pool_info = {
        .sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
        .queueFamilyIndex = c->queue_family,
    };
    VkCommandPool pool;
    TP2_VK_TRY(vkCreateCommandPool(c->device, &pool_info, NULL, &pool));
    VkCommandBufferAllocateInfo alloc = {
        .sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
        .commandPool = pool,
        .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
        .commandBufferCount = 1,
    };
    VkCommandBuffer cmd;
    VkFence fence;
    VkFenceCreateInfo fence_info = {.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkCommandBufferBeginInfo begin = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    VkMemoryBarrier mb = {
        .sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
        .srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT,
        .dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT,
    };
    VkSubmitInfo submit = {
        .sType = VK_STRUCTURE_TYPE_SUBMIT_INFO,
        .commandBufferCount = 1,
        .pCommandBuffers = &cmd,
    };
    int rc = -1;
    if (vkAllocateCommandBuffers(c->device, &alloc, &cmd) == VK_SUCCESS &&
        vkCreateFence(c->device, &fence_info, NULL, &fence) == VK_SUCCESS) {
        vkBeginCommandBuffer(cmd, &begin);
        vkCmdFillBuffer(cmd, buf, 0, VK_WHOLE_SIZE, 1);
        if (barrier)
            vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT,
                                 VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1, &mb, 0, NULL, 0, NULL);
        vkCmdFillBuffer(cmd, buf, 0, VK_WHOLE_SIZE, 2);
        vkEndCommandBuffer(cmd);
        if (vkQueueSubmit(c->queue, 1, &submit, fence) == VK_SUCCESS &&
            vkWaitForFences(c->device, 1, &fence, VK_TRUE, UINT64_MAX) == VK_SUCCESS)
            rc = 0;
        vkDestroyFence(c->device, fence, NULL);
    }
    vkDestroyCommandPool(c->device, pool, NULL);
    return rc;
}

/* A small buffer the transfer queue may fill, bound to any memory. */
static int make_buffer(const struct vkc *c, VkBuffer *buf, VkDeviceMemory *mem)
{
    VkBufferCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO,
        .size = 4096,
        .usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT,
    };
    TP2_VK_TRY(vkCreateBuffer(c->device, &info, NULL, buf));
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(c->device, *buf, &req);
    VkMemoryAllocateInfo alloc = {
        .sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO,
        .allocationSize = req.size,
        .memoryTypeIndex = (uint32_t)vkc_memory_type(c, req.memoryTypeBits, 0, 0),
    };
    TP2_VK_TRY(vkAllocateMemory(c->device, &alloc, NULL, mem));
    TP2_VK_TRY(vkBindBufferMemory(c->device, *buf, *mem, 0));
    return 0;
}

/* What the layer printed to stderr while f ran on c and buf. */
static char *stderr_of(const struct vkc *c, VkBuffer buf, bool barrier, int *rc)
{
    char path[] = "/tmp/tp2-syncval-XXXXXX";
    int fd = mkstemp(path);
    fflush(stderr);
    int saved = dup(2);
    dup2(fd, 2);
    *rc = run_fills(c, buf, barrier);
    fflush(stderr);
    dup2(saved, 2);
    close(saved);
    char *text = calloc(1, 65536);
    if (text)
        pread(fd, text, 65535, 0);
    close(fd);
    unlink(path);
    return text;
}

int main(void)
{
    struct vkc c;
    struct vkc_options opt = {.device_index = -1, .validate = true};
    CHECK(vkc_create(&c, &opt) == 0);
    VkBuffer buf = VK_NULL_HANDLE;
    VkDeviceMemory mem = VK_NULL_HANDLE;
    if (c.device && make_buffer(&c, &buf, &mem) == 0) {
        int rc;
        char *text = stderr_of(&c, buf, true, &rc);
        CHECK(rc == 0 && vkc_validation_message_count() == 0);
        expect(text && text[0] == '\0', "synchronized fills: nothing reported, got %s",
               text ? text : "?");
        free(text);
        text = stderr_of(&c, buf, false, &rc);
        CHECK(rc == 0 && vkc_validation_message_count() > 0);
        expect(text && strstr(text, "SYNC-HAZARD-WRITE-AFTER-WRITE"),
               "unsynchronized fills: a hazard reported, got %s", text ? text : "?");
        free(text);
    } else {
        CHECK(!"a buffer to fill");
    }
    if (c.device) {
        vkDestroyBuffer(c.device, buf, NULL);
        vkFreeMemory(c.device, mem, NULL);
    }
    vkc_destroy(&c);
    return unit_report();
}
