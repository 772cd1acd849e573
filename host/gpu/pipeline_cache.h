/* pipeline_cache.h: compiled pipelines kept on disk between runs.
 *
 * The cache lives in $XDG_CACHE_HOME/tp2/ (else ~/.cache/tp2/), one file
 * per device. A missing, corrupt or foreign file is ignored (Vulkan is
 * only ever given data whose header matches this device), and failures to
 * save are silent: the cache only saves time, it never changes output.
 * Nobody else can make tp2 write elsewhere or hang through it: the folder
 * is used only if it is a real directory of tp2's user that not everyone
 * may write to; only a regular file is read (no link followed, no FIFO
 * waited on); the new file is written to a temporary file created
 * exclusively (mode 0600) and renamed into place. */
#ifndef TP2_PIPELINE_CACHE_H
#define TP2_PIPELINE_CACHE_H

#include "vk_context.h"

/* Creates a pipeline cache seeded from disk when a valid file exists.
 * Returns 0, or -1 after a message. */
int pipeline_cache_load(const struct vkc *c, VkPipelineCache *cache);

/* Writes the cache's data back to disk (atomically) and destroys it. */
void pipeline_cache_save(const struct vkc *c, VkPipelineCache cache);

#endif
