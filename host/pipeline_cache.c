#define _POSIX_C_SOURCE 200809L
#include "pipeline_cache.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "vk_check.h"

/* Refuse to read files beyond this: a cache is a few megabytes at most. */
#define TP2_CACHE_MAX_BYTES (256u << 20)

/* The cache file for this device, or NULL if no folder can be named. The
 * folder is created when missing. */
static char *cache_path(const struct vkc *c)
{
    const char *xdg = getenv("XDG_CACHE_HOME");
    const char *home = getenv("HOME");
    char dir[4096];
    if (xdg && xdg[0] == '/')
        snprintf(dir, sizeof dir, "%s/tp2", xdg);
    else if (home && home[0] == '/')
        snprintf(dir, sizeof dir, "%s/.cache/tp2", home);
    else
        return NULL;
    /* Make both levels; errors show up when the file is opened. */
    char *slash = strrchr(dir, '/');
    *slash = '\0';
    mkdir(dir, 0755);
    *slash = '/';
    mkdir(dir, 0755);
    size_t n = strlen(dir) + 64;
    char *path = malloc(n);
    if (path)
        snprintf(path, n, "%s/pipelines-%08x-%08x.bin", dir,
                 c->props.vendorID, c->props.deviceID);
    return path;
}

/* True if data starts with a header describing this very device and
 * driver build (VkPipelineCacheHeaderVersionOne). */
static bool header_matches(const struct vkc *c, const unsigned char *data, size_t n)
{
    VkPipelineCacheHeaderVersionOne h;
    if (n < sizeof h)
        return false;
    memcpy(&h, data, sizeof h);
    return h.headerSize >= sizeof h && h.headerSize <= n &&
           h.headerVersion == VK_PIPELINE_CACHE_HEADER_VERSION_ONE &&
           h.vendorID == c->props.vendorID && h.deviceID == c->props.deviceID &&
           memcmp(h.pipelineCacheUUID, c->props.pipelineCacheUUID, VK_UUID_SIZE) == 0;
}

/* The file's bytes in a new buffer, or NULL (with *n = 0). */
static unsigned char *read_file(const char *path, size_t *n)
{
    *n = 0;
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    unsigned char *data = NULL;
    long size = -1;
    if (fseek(f, 0, SEEK_END) == 0 && (size = ftell(f)) > 0 &&
        (unsigned long)size <= TP2_CACHE_MAX_BYTES && fseek(f, 0, SEEK_SET) == 0 &&
        (data = malloc((size_t)size)) && fread(data, 1, (size_t)size, f) == (size_t)size)
        *n = (size_t)size;
    fclose(f);
    if (*n == 0) {
        free(data);
        data = NULL;
    }
    return data;
}

int pipeline_cache_load(const struct vkc *c, VkPipelineCache *cache)
{
    char *path = cache_path(c);
    size_t n = 0;
    unsigned char *data = path ? read_file(path, &n) : NULL;
    bool valid = data && header_matches(c, data, n);
    VkPipelineCacheCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO,
        .initialDataSize = valid ? n : 0,
        .pInitialData = valid ? data : NULL,
    };
    VkResult r = vkCreatePipelineCache(c->device, &info, NULL, cache);
    if (r != VK_SUCCESS && valid) { /* the driver disliked it: start empty */
        info.initialDataSize = 0;
        info.pInitialData = NULL;
        r = vkCreatePipelineCache(c->device, &info, NULL, cache);
    }
    free(data);
    free(path);
    TP2_VK_TRY(r);
    return 0;
}

void pipeline_cache_save(const struct vkc *c, VkPipelineCache cache)
{
    if (!cache)
        return;
    size_t n = 0;
    char *path = cache_path(c);
    unsigned char *data = NULL;
    if (path && vkGetPipelineCacheData(c->device, cache, &n, NULL) == VK_SUCCESS &&
        n > 0 && (data = malloc(n)) &&
        vkGetPipelineCacheData(c->device, cache, &n, data) == VK_SUCCESS) {
        size_t len = strlen(path) + 16;
        char *tmp = malloc(len);
        if (tmp) {
            snprintf(tmp, len, "%s.%ld", path, (long)getpid());
            FILE *f = fopen(tmp, "wb");
            bool ok = f && fwrite(data, 1, n, f) == n;
            if (f && fclose(f) != 0)
                ok = false;
            if (!ok || rename(tmp, path) != 0)
                remove(tmp);
            free(tmp);
        }
    }
    free(data);
    free(path);
    vkDestroyPipelineCache(c->device, cache, NULL);
}
