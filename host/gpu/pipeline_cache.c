#define _POSIX_C_SOURCE 200809L
#include "pipeline_cache.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "tempfile.h"
#include "vk_check.h"

/* Refuse to read files beyond this: a cache is a few megabytes at most. */
#define TP2_CACHE_MAX_BYTES (64u << 20)

/* A folder tp2 may keep its cache in: a real directory (not a link to
 * one), ours, and not writable by everyone, so nobody else can plant
 * files or links in it (XDG_CACHE_HOME=/tmp would otherwise allow that). */
static bool safe_folder(const char *dir)
{
    struct stat st;
    return lstat(dir, &st) == 0 && S_ISDIR(st.st_mode) && st.st_uid == geteuid() &&
           !(st.st_mode & S_IWOTH);
}

/* The cache file for this device, or NULL if no safe folder can be named.
 * The folder is created when missing. */
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
    /* Make both levels; errors show up in the check below. */
    char *slash = strrchr(dir, '/');
    *slash = '\0';
    mkdir(dir, 0755);
    *slash = '/';
    mkdir(dir, 0755);
    if (!safe_folder(dir))
        return NULL;
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

/* read(2) until n bytes or the end; the count read, or -1. */
static ssize_t read_full(int fd, unsigned char *data, size_t n)
{
    size_t got = 0;
    while (got < n) {
        ssize_t k = read(fd, data + got, n - got);
        if (k < 0 && errno == EINTR)
            continue;
        if (k < 0)
            return -1;
        if (k == 0)
            break;
        got += (size_t)k;
    }
    return (ssize_t)got;
}

/* The file's bytes in a new buffer, or NULL (with *n = 0). Only a regular
 * file of sane size is read: no link is followed (O_NOFOLLOW) and nothing
 * blocks (O_NONBLOCK: a FIFO opens at once and is then skipped). */
static unsigned char *read_file(const char *path, size_t *n)
{
    *n = 0;
    int fd = open(path, O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0)
        return NULL;
    struct stat st;
    unsigned char *data = NULL;
    if (fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && st.st_size > 0 &&
        (unsigned long long)st.st_size <= TP2_CACHE_MAX_BYTES &&
        (data = malloc((size_t)st.st_size)) &&
        read_full(fd, data, (size_t)st.st_size) == (ssize_t)st.st_size)
        *n = (size_t)st.st_size;
    close(fd);
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

/* Writes n bytes to a new temporary file (exclusive, mode 0600, in the
 * cache folder) and renames it over path, which replaces whatever is
 * there (a planted link is replaced, never followed); on any failure the
 * temporary file is removed. */
static void write_file(const char *path, const unsigned char *data, size_t n)
{
    const char *slash = strrchr(path, '/');
    size_t dir = (size_t)(slash - path) + 1;
    char *tmp = malloc(dir + sizeof ".pipelines-XXXXXX");
    if (!tmp)
        return;
    memcpy(tmp, path, dir);
    memcpy(tmp + dir, ".pipelines-XXXXXX", sizeof ".pipelines-XXXXXX");
    int fd = tempfile_create(tmp);
    if (fd >= 0) {
        bool ok = true;
        for (size_t done = 0; ok && done < n;) {
            ssize_t k = write(fd, data + done, n - done);
            ok = k > 0 || (k < 0 && errno == EINTR);
            done += k > 0 ? (size_t)k : 0;
        }
        if (close(fd) != 0 || !ok || rename(tmp, path) != 0)
            unlink(tmp);
        tempfile_forget(tmp);
    }
    free(tmp);
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
        vkGetPipelineCacheData(c->device, cache, &n, data) == VK_SUCCESS)
        write_file(path, data, n);
    free(data);
    free(path);
    vkDestroyPipelineCache(c->device, cache, NULL);
}
