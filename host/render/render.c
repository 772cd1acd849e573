/* render.c: one image of a scene (render_scene): the device made and the
 * scene packed on threads of their own, the passes planned for what the
 * device has and what fits it, the buffers and descriptors, then the
 * bands (render_bands.c) with the pipelines of render_pipelines.c. */
#define _POSIX_C_SOURCE 200809L
#include "renderer.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "big_alloc.h"
#include "clock.h"
#include "gpu_layout.h"
#include "scene_pack.h"
#include "test_hooks.h"
#include "vk_check.h"

/* Camera samples per submission on a GPU: bounds the work of one
 * submission so that a watchdog never sees a long dispatch. */
#define TP2_TILE_SAMPLES (256 * 256)

/* Submissions per image on a CPU device (lavapipe): no watchdog there, and
 * each dispatch ends with threads idling on its slowest workgroups, so few
 * big ones are faster (measured: 1920 x 1080 refraction.txt 15-35% faster
 * in one dispatch than in 40); eight still let the progress bar move. */
#define TP2_CPU_TILES 8

/* Camera samples from which auto makes its retrace pipeline at the start
 * rather than when a band first marks a pixel. On lavapipe that compile
 * takes 0.04-0.12 s; beside the band pass's it costs 12-20 ms of wall
 * time (2 CPUs: it slows the other) and saves all of it where a pixel is
 * marked. At 1920 x 1080 all 20 bench scenes (showpiece aside) marked
 * some, at 400 x 300 9 of 36 scenes and corpus files marked none. The
 * test hook of that name replaces it (test_hooks.h). */
#define TP2_EAGER_RETRACE (1 << 20)

static double eager_retrace_samples(void)
{
    const struct test_hooks *h = test_hooks();
    return h->eager_retrace_set ? h->eager_retrace : TP2_EAGER_RETRACE;
}

/* Largest band buffer in bytes: whole images no longer have to fit one
 * storage buffer (lavapipe's limit, 128 MiB, stopped at about 3840 x 2160),
 * and host memory stays bounded whatever the image size. 32 MiB is two
 * million pixels, far more than a band needs to keep a device busy. */
#define TP2_BAND_BYTES (32u << 20)

/* Walks that go on in a next pass, on CPU devices (TP2_CANARY_STEPS): the
 * walk buffers hold this many (16k walks are 2 MB of Walks and 8.6 / 17 MB
 * of rays in float / double); more than this many unfinished walks at once
 * start again after these are done. */
#define TP2_WALK_CAPACITY 16384

/* Rays a walk traces in its first pass on CPU devices: most pixel samples
 * need far fewer. A pass that lavapipe cuts short is run again with half
 * as many, and later passes keep the smaller number. */
#define TP2_CPU_PASS_RAYS 256

/* The stats buffer: rays counted in 64 bits as (low, high) pairs of uints,
 * then the TP2_COUNTER_*s. */
#define TP2_STATS_WORDS (2 * TP2_STAT_COUNT + TP2_COUNTER_COUNT)
#define TP2_STATS_BYTES (TP2_STATS_WORDS * sizeof(uint32_t))

/* The band buffer's byte limit on this device: TP2_BAND_BYTES, or less
 * where the device's storage-buffer range is smaller. The test hook
 * TP2_BAND_BYTES may lower it, so that tests can render small
 * images in many bands (below one band of TP2_GROUP_Y rows, bands have
 * TP2_GROUP_Y rows). */
static VkDeviceSize band_bytes_max(const struct vkc *vk)
{
    VkDeviceSize range = vk->props.limits.maxStorageBufferRange;
    VkDeviceSize max = range < TP2_BAND_BYTES ? range : TP2_BAND_BYTES;
    return hook_lowered(test_hooks()->band_bytes, max);
}

/* The input bindings whose layout depends on the precision (layout.glsl's
 * rvec4s): there the retrace pass reads the double scene's buffers. */
static bool by_precision(int binding)
{
    return binding == TP2_BINDING_FRAME || binding == TP2_BINDING_LIGHTS ||
           binding == TP2_BINDING_PIGMENTS || binding == TP2_BINDING_OBJECTS ||
           binding == TP2_BINDING_EXTRA;
}

/* A device buffer holding input buffer i of p. A CPU device that can
 * import host memory reads a big one (big_alloc's, 2 MiB-aligned) where it
 * lies (vk_buffer_import): a million spheres under auto copied 0.2-0.7 s
 * of them. Otherwise it is copied; a CPU device's memory is the host's,
 * untouched until this copy, and as huge pages filling it takes a page
 * fault per 2 MiB instead of per 4 KiB (that million: 0.67 s of copies
 * became 0.05-0.28 s). */
static int upload(const struct renderer *r, const struct packed_scene *p, int i,
                  struct vk_buffer *b)
{
    int imported = vk_buffer_import(&r->vk, p->data[i], p->size[i],
                                    big_alloc_capacity(p->size[i]), b);
    if (imported <= 0)
        return imported;
    if (vk_buffer_create(&r->vk, p->size[i], false, b) != 0)
        return -1;
    if (r->vk.props.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU)
        big_advise(b->mapped, p->size[i]);
    memcpy(b->mapped, p->data[i], p->size[i]);
    return 0;
}

/* The scene's buffers, filled (and the double scene's, when retracing);
 * the band buffer (band_rows rows of width), its host copy, the stats
 * buffer, the walks' buffers (on CPU devices; one element elsewhere, where
 * walks finish in their first pass), and when retracing the signatures
 * (of the band and the row after it) and the pixel list. */
static int create_buffers(struct renderer *r, const struct packed_scene *p,
                          const struct packed_scene *twin, int width)
{
    for (int i = 0; i < TP2_INPUT_BUFFERS; i++)
        if (upload(r, p, i, &r->buffers[i]) != 0 ||
            (retracing(r) && by_precision(i) && upload(r, twin, i, &r->twin[i]) != 0))
            return -1;
    VkDeviceSize pixels = (VkDeviceSize)r->band_rows * width;
    VkDeviceSize walks = (VkDeviceSize)r->walk_capacity;
    VkDeviceSize ray = r->band.use_double || retracing(r) ? sizeof(struct gpu_walk_ray_d)
                                                         : sizeof(struct gpu_walk_ray_f);
    VkDeviceSize words = sizeof(uint32_t);
    /* The band's running sums stay on the device; only the output buffer,
     * what the file needs, is read back (finish.comp). */
    if (vk_buffer_create(&r->vk, pixels * TP2_PIXEL_BYTES, false,
                         &r->buffers[TP2_BINDING_IMAGE]) != 0 ||
        vk_buffer_create(&r->vk, pixels * output_bytes(r), true,
                         &r->buffers[TP2_BINDING_OUTPUT]) != 0 ||
        vk_buffer_create(&r->vk, TP2_STATS_BYTES, true, &r->buffers[TP2_BINDING_STATS]) != 0 ||
        vk_buffer_create(&r->vk, (r->loop_guard ? pixels + width : 1) * words, false,
                         &r->buffers[TP2_BINDING_STARTED]) != 0 ||
        vk_buffer_create(&r->vk, walks * sizeof(struct gpu_walk), false,
                         &r->buffers[TP2_BINDING_WALKS]) != 0 ||
        vk_buffer_create(&r->vk, walks * TP2_WALK_RAYS * ray, false,
                         &r->buffers[TP2_BINDING_WALK_RAYS]) != 0 ||
        vk_buffer_create(&r->vk, (retracing(r) ? pixels + width : 1) * words, true,
                         &r->buffers[TP2_BINDING_SIGNATURES]) != 0 ||
        vk_buffer_create(&r->vk, (retracing(r) ? pixels : 1) * words, false,
                         &r->buffers[TP2_BINDING_PIXEL_LIST]) != 0)
        return -1;
    memset(r->buffers[TP2_BINDING_STATS].mapped, 0, TP2_STATS_BYTES);
    r->host_band = malloc((size_t)(pixels * output_bytes(r)));
    r->last_signatures = retracing(r) ? malloc((size_t)width * sizeof(uint32_t)) : NULL;
    if (!r->host_band || (retracing(r) && !r->last_signatures)) {
        fputs("tp2: out of memory for a band of the image\n", stderr);
        return -1;
    }
    return 0;
}

static void read_ray_counts(const uint32_t *words, uint64_t rays[TP2_STAT_COUNT])
{
    for (int i = 0; i < TP2_STAT_COUNT; i++)
        rays[i] = (uint64_t)words[2 * i + 1] << 32 | words[2 * i];
}

/* Says so when a pixel sample needed more than lavapipe allows one
 * invocation even one ray at a time (TP2_CANARY_STEPS): the image is
 * still written, but the user must know. */
static void warn_loop_limit(const struct vkc *vk, const uint32_t *words)
{
    uint32_t samples = words[2 * TP2_STAT_COUNT + TP2_COUNTER_LOST];
    if (samples > 0)
        fprintf(stderr, "tp2: warning: %u pixel sample%s needed more than '%s' lets one "
                        "shader invocation do (65535 loop iterations) for a single ray, "
                        "so %s wrong; render on a GPU\n",
                samples, samples == 1 ? "" : "s", vk->props.deviceName,
                samples == 1 ? "it is" : "they are");
}

/* Only CPU devices (lavapipe) cut long shader loops short. */
static bool needs_loop_guard(const struct vkc *vk)
{
    return vk->props.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
}

/* Pass t's descriptor set: every binding the band pass's buffer, but where
 * the retrace pass reads the double scene's (by_precision). */
static int write_descriptors(struct renderer *r, struct tracer *t)
{
    VkDescriptorSetAllocateInfo alloc = {
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO,
        .descriptorPool = r->pool,
        .descriptorSetCount = 1,
        .pSetLayouts = &r->set_layout,
    };
    TP2_VK_TRY(vkAllocateDescriptorSets(r->vk.device, &alloc, &t->set));
    VkDescriptorBufferInfo infos[TP2_BINDING_COUNT];
    VkWriteDescriptorSet writes[TP2_BINDING_COUNT];
    for (uint32_t i = 0; i < TP2_BINDING_COUNT; i++) {
        bool twin = t == &r->retrace && by_precision((int)i);
        VkBuffer buffer = twin ? r->twin[i].buffer : r->buffers[i].buffer;
        infos[i] = (VkDescriptorBufferInfo){
            .buffer = buffer,
            .range = VK_WHOLE_SIZE,
        };
        writes[i] = (VkWriteDescriptorSet){
            .sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET,
            .dstSet = t->set,
            .dstBinding = i,
            .descriptorCount = 1,
            .descriptorType = binding_type(i),
        };
        if (binding_type(i) == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER) {
            writes[i].pBufferInfo = &infos[i];
            continue;
        }
        VkBufferViewCreateInfo view_info = {
            .sType = VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO,
            .buffer = buffer,
            .format = VK_FORMAT_R32G32B32A32_UINT, /* bits, reinterpreted in GLSL */
            .range = VK_WHOLE_SIZE,
        };
        TP2_VK_TRY(vkCreateBufferView(r->vk.device, &view_info, NULL, &t->views[i]));
        writes[i].pTexelBufferView = &t->views[i];
    }
    vkUpdateDescriptorSets(r->vk.device, TP2_BINDING_COUNT, writes, 0, NULL);
    return 0;
}

/* A descriptor set per pass. */
static int create_descriptors(struct renderer *r)
{
    struct tracer *passes[2];
    int n = tracers(r, passes);
    VkDescriptorPoolSize sizes[2] = {
        {.type = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
        {.type = VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER},
    };
    for (uint32_t i = 0; i < TP2_BINDING_COUNT; i++)
        sizes[binding_type(i) == sizes[1].type].descriptorCount += (uint32_t)n;
    VkDescriptorPoolCreateInfo pool_info = {
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO,
        .maxSets = (uint32_t)n,
        .poolSizeCount = 2,
        .pPoolSizes = sizes,
    };
    TP2_VK_TRY(vkCreateDescriptorPool(r->vk.device, &pool_info, NULL, &r->pool));
    for (int k = 0; k < n; k++)
        if (write_descriptors(r, passes[k]) != 0)
            return -1;
    return 0;
}

static int create_commands(struct renderer *r)
{
    VkCommandPoolCreateInfo pool_info = {
        .sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
        .flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT,
        .queueFamilyIndex = r->vk.queue_family,
    };
    TP2_VK_TRY(vkCreateCommandPool(r->vk.device, &pool_info, NULL,
                                   &r->command_pool));
    VkCommandBufferAllocateInfo alloc = {
        .sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
        .commandPool = r->command_pool,
        .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
        .commandBufferCount = 1,
    };
    TP2_VK_TRY(vkAllocateCommandBuffers(r->vk.device, &alloc, &r->cmd));
    VkFenceCreateInfo fence_info = {.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    TP2_VK_TRY(vkCreateFence(r->vk.device, &fence_info, NULL, &r->fence));
    return 0;
}

/* Rows per band: a multiple of the workgroup's height (so a band's last
 * workgroups never write past it), about TP2_TILE_SAMPLES pixels on a GPU
 * and a TP2_CPU_TILES-th of all the samples on a CPU (so the whole image
 * once there are that many samples per pixel), but never more than
 * TP2_BAND_BYTES: that bounds memory whatever the image size. */
static int band_rows(const struct vkc *vk, int width, int height, int samples)
{
    double budget = TP2_TILE_SAMPLES;
    if (vk->props.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU)
        budget = fmax(budget, (double)width * height * samples / TP2_CPU_TILES);
    int rows = (int)ceil(budget / width);
    rows += (TP2_GROUP_Y - rows % TP2_GROUP_Y) % TP2_GROUP_Y;
    int fit = (int)(band_bytes_max(vk) / ((VkDeviceSize)width * TP2_PIXEL_BYTES));
    fit -= fit % TP2_GROUP_Y;
    if (fit < TP2_GROUP_Y) /* only where TP2_BAND_BYTES asks for less */
        fit = TP2_GROUP_Y;
    if (rows > fit)
        rows = fit;
    return rows < height ? rows : height;
}

static void renderer_destroy(struct renderer *r)
{
    VkDevice d = r->vk.device;
    join_side(r, &r->finishing);
    join_side(r, &r->retrace_making);
    if (d) {
        vkDeviceWaitIdle(d);
        vkDestroyFence(d, r->fence, NULL);
        vkDestroyCommandPool(d, r->command_pool, NULL);
        vkDestroyDescriptorPool(d, r->pool, NULL);
        for (int i = 0; i < TP2_BINDING_COUNT; i++) {
            vkDestroyBufferView(d, r->band.views[i], NULL);
            vkDestroyBufferView(d, r->retrace.views[i], NULL);
        }
        unmake_passes(r);
        vkDestroyPipeline(d, r->finish, NULL);
        vkDestroyShaderModule(d, r->finish_shader, NULL);
        vkDestroyPipelineLayout(d, r->pipeline_layout, NULL);
        vkDestroyDescriptorSetLayout(d, r->set_layout, NULL);
        for (int i = TP2_BINDING_COUNT - 1; i >= 0; i--)
            vk_buffer_destroy(&r->vk, &r->buffers[i]);
        for (int i = TP2_INPUT_BUFFERS - 1; i >= 0; i--)
            vk_buffer_destroy(&r->vk, &r->twin[i]);
    }
    vkc_destroy(&r->vk);
    free(r->host_band);
    free(r->last_signatures);
}

/* Rays per walk per pass to begin with: TP2_CPU_PASS_RAYS on CPU devices,
 * a whole tree elsewhere. The test hook TP2_PASS_RAYS sets it
 * on CPU devices and has walks start in passes at once (not after a cut
 * whole-tree pass), so that tests can make walks go on across passes. */
static int pass_rays(bool loop_guard, bool *walking)
{
    long v = test_hooks()->pass_rays;
    *walking = false;
    if (!loop_guard)
        return TP2_MAX_RAYS;
    if (v > 0 && v <= TP2_MAX_RAYS) {
        *walking = true;
        return (int)v;
    }
    return TP2_CPU_PASS_RAYS;
}

/* Even the smallest band (TP2_GROUP_Y rows) must fit the band limit; with
 * Vulkan's least maxStorageBufferRange (128 MiB) every width up to 32768
 * does. */
static int check_band_fits(const struct vkc *vk, int width)
{
    VkDeviceSize bytes = (VkDeviceSize)width * TP2_GROUP_Y * TP2_PIXEL_BYTES;
    VkDeviceSize range = vk->props.limits.maxStorageBufferRange;
    if (bytes > (range < TP2_BAND_BYTES ? range : TP2_BAND_BYTES)) {
        fprintf(stderr, "tp2: image too wide for device '%s' (%d rows of %d "
                        "pixels need %llu bytes, its storage-buffer limit is %u)\n",
                vk->props.deviceName, TP2_GROUP_Y, width, (unsigned long long)bytes,
                vk->props.limits.maxStorageBufferRange);
        return -1;
    }
    return 0;
}

/* The device's storage-buffer range; the test hook
 * TP2_STORAGE_RANGE may lower it, so that tests can reach the limit with
 * small scenes. */
static VkDeviceSize storage_range(const struct vkc *vk)
{
    VkDeviceSize range = vk->props.limits.maxStorageBufferRange;
    return hook_lowered(test_hooks()->storage_range, range);
}

/* The device's texel-buffer limit, in texels; TP2_TEXEL_ELEMENTS may lower
 * it, as TP2_STORAGE_RANGE the storage range. */
static VkDeviceSize texel_elements(const struct vkc *vk)
{
    VkDeviceSize max = vk->props.limits.maxTexelBufferElements;
    return hook_lowered(test_hooks()->texel_elements, max);
}

/* Every scene buffer must fit its binding (a storage buffer's range, a
 * texel buffer's element count), or the shader would read past what it
 * is given. Says which does not unless quiet. */
static int check_scene_fits(const struct vkc *vk, const struct packed_scene *p,
                            bool use_double, bool quiet)
{
    static const char *const what[TP2_INPUT_BUFFERS] = {
        [TP2_BINDING_FRAME] = "camera and settings", [TP2_BINDING_LIGHTS] = "lights",
        [TP2_BINDING_PIGMENTS] = "pigments", [TP2_BINDING_FINISHES] = "finishes",
        [TP2_BINDING_OBJECTS] = "objects",   [TP2_BINDING_BVH] = "BVH nodes",
        [TP2_BINDING_EXTRA] = "polyhedron faces and quadrics",
        [TP2_BINDING_TEXELS] = "texture texels",
    };
    VkDeviceSize range = storage_range(vk), texels = texel_elements(vk);
    for (int i = 0; i < TP2_INPUT_BUFFERS; i++) {
        if (binding_type((uint32_t)i) == VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER) {
            if (p->size[i] / TP2_TEXEL_BYTES <= texels)
                continue;
            if (quiet)
                return -1;
            fprintf(stderr, "tp2: scene too large for device '%s': its %s need %llu "
                            "texels of %d bytes, and one texel buffer holds at most %llu%s\n",
                    vk->props.deviceName, what[i],
                    (unsigned long long)(p->size[i] / TP2_TEXEL_BYTES), TP2_TEXEL_BYTES,
                    (unsigned long long)texels,
                    use_double ? " (--precision float makes them smaller)" : "");
            return -1;
        }
        if (p->size[i] > range) {
            if (quiet)
                return -1;
            fprintf(stderr, "tp2: scene too large for device '%s': its %s need %llu "
                            "bytes, and one storage buffer holds at most %llu%s\n",
                    vk->props.deviceName, what[i], (unsigned long long)p->size[i],
                    (unsigned long long)range,
                    use_double ? " (--precision float makes most of them smaller)" : "");
            return -1;
        }
    }
    return 0;
}

/* The passes this device runs and how: under --precision mixed (and
 * auto but on a CPU device: render_scene, auto_on_device) a float pass
 * that records signatures and a retrace pass in double, where the double
 * scene fits the device (twin_fits); in software double
 * (shaders/soft_double.glsl) where it has no shaderFloat64. */
static void plan_passes(struct renderer *r, const struct render_options *opt,
                        const struct scene_features *f, bool twin_fits)
{
    r->features = *f;
    r->count_rays = opt->count_rays;
    r->bytes = opt->bytes;
    r->loop_guard = needs_loop_guard(&r->vk);
    r->slabs = dispatch_slabs(&r->vk);
    r->band = (struct tracer){.use_double = opt->use_double,
                              .signatures = opt->retrace && twin_fits};
    r->retrace = (struct tracer){.use_double = true, .pixel_list = true,
                                 .soft = !r->vk.float64};
    r->band.pass_rays = pass_rays(r->loop_guard, &r->band.walking);
    r->retrace.pass_rays = pass_rays(r->loop_guard, &r->retrace.walking);
    r->walk_capacity = r->loop_guard ? TP2_WALK_CAPACITY : 1;
    r->eager_retrace = retracing(r) && (double)opt->width * opt->height * f->samples >=
                                           eager_retrace_samples();
}

/* Vulkan instance and device creation on a thread of its own, so that it
 * runs while the scene is packed and its BVH built (on lavapipe 0.03-0.09
 * s, on a discrete GPU's driver 0.15 s or more). What auto needs to
 * choose (auto_on_device) is known before the logical device is made
 * (vkc_options.chosen): packing waits for that alone. */
struct device_job {
    struct vkc *vk;
    struct vkc_options opt;
    int rc;
    double seconds;
    pthread_mutex_t lock;
    pthread_cond_t changed;
    bool chosen;       /* the facts below are known (or creation failed) */
    bool cpu, float64; /* a CPU device; shaderFloat64 enabled */
};

/* Tells wait_chosen the device is known (c: its facts), or that creation
 * ended (c NULL: the facts stay as they are, false if it failed first). */
static void announce_chosen(struct device_job *job, const struct vkc *c)
{
    pthread_mutex_lock(&job->lock);
    if (c) {
        job->cpu = c->props.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
        job->float64 = c->float64;
    }
    job->chosen = true;
    pthread_cond_broadcast(&job->changed);
    pthread_mutex_unlock(&job->lock);
}

static void device_chosen(const struct vkc *c, void *user)
{
    announce_chosen(user, c);
}

static void *create_device(void *arg)
{
    struct device_job *job = arg;
    double t0 = clock_seconds();
    job->rc = vkc_create(job->vk, &job->opt);
    job->seconds = clock_seconds() - t0;
    announce_chosen(job, NULL);
    return NULL;
}

/* Waits until the device job knows its device (or has failed). */
static void wait_chosen(struct device_job *job)
{
    pthread_mutex_lock(&job->lock);
    while (!job->chosen)
        pthread_cond_wait(&job->changed, &job->lock);
    pthread_mutex_unlock(&job->lock);
}

/* Packing on a thread of its own too, so that this thread makes the band
 * pass's pipeline (on lavapipe 0.04-0.18 s, by the kinds it has; a GPU's
 * driver takes longer for one its cache lacks) as soon as the device is
 * made and packing knows the scene's features (pack_options.
 * features_known), beside the BVH's build. Made here, not on the device's
 * thread: on lavapipe that made small scenes' runs 5-7% slower (measured
 * side by side, cause not found). */
struct pack_job {
    const struct scene *s;
    struct pack_options opt;
    struct packed_scene *packed, *twin;
    pthread_mutex_t lock;
    pthread_cond_t changed;
    bool known; /* features holds the scene's (a copy: packed is the
                 * packing thread's until joined, and freed on failure) */
    bool done;  /* rc and finished are set */
    struct scene_features features;
    int rc;
    double finished; /* clock_seconds() when packing was done */
};

static void features_known(const struct scene_features *f, void *user)
{
    struct pack_job *job = user;
    pthread_mutex_lock(&job->lock);
    job->features = *f;
    job->known = true;
    pthread_cond_signal(&job->changed);
    pthread_mutex_unlock(&job->lock);
}

static void *pack(void *arg)
{
    struct pack_job *job = arg;
    int rc = scene_pack(job->s, &job->opt, job->packed, job->twin);
    pthread_mutex_lock(&job->lock);
    job->rc = rc;
    job->finished = clock_seconds();
    job->done = true;
    pthread_cond_signal(&job->changed);
    pthread_mutex_unlock(&job->lock);
    return NULL;
}

/* Waits until packing knows the scene's features or is done; returns
 * whether the features are known. */
static bool wait_features(struct pack_job *job)
{
    pthread_mutex_lock(&job->lock);
    while (!job->known && !job->done)
        pthread_cond_wait(&job->changed, &job->lock);
    bool known = job->known;
    pthread_mutex_unlock(&job->lock);
    return known;
}

static bool pack_done(struct pack_job *job)
{
    pthread_mutex_lock(&job->lock);
    bool done = job->done;
    pthread_mutex_unlock(&job->lock);
    return done;
}

/* What --stats says of the precision: the one used, or mixed's passes;
 * why auto or mixed (asked) chose another, where they did. */
static void describe_precision(const struct renderer *r, const struct render_options *asked,
                               const char *why, struct render_stats *st)
{
    const char *name = asked->double_on_cpu ? "auto" : "mixed";
    const char *used = r->band.use_double ? "double" : "float";
    if (retracing(r))
        snprintf(st->precision, sizeof st->precision,
                 "%s (float, then pixels on decision boundaries again in %sdouble)", name,
                 r->retrace.soft ? "software " : "");
    else if (why)
        snprintf(st->precision, sizeof st->precision, "%s (%s: %s)", used, name, why);
    else
        snprintf(st->precision, sizeof st->precision, "%s", used);
    st->retracing = retracing(r);
    st->retrace_soft = retracing(r) && r->retrace.soft;
}

/* Auto on a CPU device is double throughout, with the default's pruning
 * (docs/decisions.md, "--precision auto against float"): there a
 * double lane costs about two float lanes (half as many fit a SIMD
 * register), not the tens of times of most GPUs, and mixed's bookkeeping
 * for its retrace costs about as much; the image is then the exact
 * model's but for pruning. Decided once the device is chosen, before the
 * scene is packed, so that only the double scene is packed (a million
 * spheres: 2.9 s end to end when both were). Returns the options to
 * render with. */
static struct render_options auto_on_device(const struct render_options *asked,
                                            const struct device_job *device)
{
    struct render_options o = *asked;
    if (asked->double_on_cpu && device->float64 && device->cpu) {
        o.use_double = true;
        o.retrace = false;
    }
    return o;
}

/* Says that packing (or packing again in float) ran out of memory. */
static void packing_failed(const struct scene *s)
{
    fprintf(stderr, "tp2: out of memory packing the scene's %zu objects for the device\n",
            s->nobjects);
}

/* The device job for the options asked. Double asked for needs
 * shaderFloat64; auto and mixed want it (float without it), and so does a
 * scene that needs double, refused with its position by
 * check_double_needed on a device without it. */
static void device_job_init(struct device_job *job, struct vkc *vk,
                            const struct render_options *asked)
{
    *job = (struct device_job){
        .vk = vk,
        .opt = {
            .device_index = asked->device_index,
            .need_float64 = asked->use_double && !asked->double_where,
            .want_float64 = asked->use_double || asked->retrace,
            .validate = asked->validate,
            .chosen = device_chosen,
            .chosen_user = job,
        },
        .lock = PTHREAD_MUTEX_INITIALIZER,
        .changed = PTHREAD_COND_INITIALIZER,
    };
}

/* The packing job for the options chosen: the double twin only where
 * mixed retraces. */
static void pack_job_init(struct pack_job *job, const struct scene *s,
                          const struct render_options *opt, struct packed_scene *packed,
                          struct packed_scene *twin)
{
    *job = (struct pack_job){
        .s = s,
        .opt = {
            .width = opt->width,
            .height = opt->height,
            .use_double = opt->use_double,
            .samples = opt->samples,
            .bvh_min = opt->bvh_min,
            .bailout = opt->bailout,
            .features_known = features_known,
            .user = job,
        },
        .packed = packed,
        .twin = opt->retrace ? twin : NULL,
        .lock = PTHREAD_MUTEX_INITIALIZER,
        .changed = PTHREAD_COND_INITIALIZER,
    };
}

/* A scene that needs double (opt->double_where says where) on a device
 * without it is refused; on one with it, said unless quiet. */
static int check_double_needed(const struct render_options *opt, const struct vkc *vk)
{
    if (!opt->double_where)
        return 0;
    if (!vk->float64) {
        fprintf(stderr, "%s: error: %s, and device '%s' has no shaderFloat64 to render "
                        "it in double; choose another with --device (lavapipe has it)\n",
                opt->double_where, opt->double_what, vk->props.deviceName);
        return -1;
    }
    if (!opt->quiet)
        fprintf(stderr, "%s: note: %s: rendering in double precision\n", opt->double_where,
                opt->double_what);
    return 0;
}

/* When render_scene's steps began or ended (clock_seconds()), for the
 * phases --stats reports. */
struct phase_times {
    double pack_start;         /* packing began */
    double make_start, made;   /* the early pipelines were made (early only) */
    double packed;             /* packing was done */
    double plan_start, planned; /* the plan after packing (and any remaking) */
    double buffers_made, commands_made;
};

/* Fills stats from a finished render: what the scene and its buffers
 * held, the rays counted, and the phases' seconds. Pipelines made on the
 * way (the retrace's, made lazily) count as pipeline, not render. */
static void record_stats(struct render_stats *st, const struct renderer *r,
                         const struct packed_scene *packed, const struct device_job *device,
                         bool early, const struct phase_times *t)
{
    for (int i = 0; i < TP2_INPUT_BUFFERS; i++) {
        st->in_place += r->buffers[i].imported ? r->buffers[i].size : 0;
        st->in_place += r->twin[i].imported ? r->twin[i].size : 0;
    }
    read_ray_counts(r->buffers[TP2_BINDING_STATS].mapped, st->rays);
    st->pass_rays = r->band.pass_rays;
    st->device = device->seconds;
    st->pipeline_beside = early ? t->made - t->make_start : 0;
    st->bvh = packed->bvh_time;
    st->bounded = packed->bounded;
    st->unbounded = packed->unbounded;
    st->has_bvh = packed->features.bvh;
    st->upload = (t->packed - t->pack_start - packed->bvh_time) + (t->buffers_made - t->planned);
    /* What the early pipelines kept waiting once packing was done (early
     * only when packing outlasted the device), then what was made after. */
    double waited = early && t->made > t->packed ? t->made - t->packed : 0;
    st->pipeline = waited + (t->planned - t->plan_start) + (t->commands_made - t->buffers_made) +
                   r->pipeline_time;
    st->render -= r->pipeline_time;
}

int render_scene(const struct scene *s, const struct render_options *asked,
                 render_rows_fn on_rows, void *user, struct render_stats *stats)
{
    struct renderer r = {0};
    struct packed_scene packed = {0}, twin = {0};
    struct device_job device;
    struct pack_job packing;
    struct phase_times t = {0};
    int rc = -1;
    memset(stats, 0, sizeof *stats);
    device_job_init(&device, &r.vk, asked);
    pthread_t device_thread, pack_thread;
    bool device_threaded = pthread_create(&device_thread, NULL, create_device, &device) == 0;
    if (!device_threaded)
        create_device(&device);
    /* Under auto which device it is decides what is packed; the logical
     * device is made beside packing all the same. */
    double t_choose = clock_seconds();
    if (asked->double_on_cpu)
        wait_chosen(&device);
    stats->device_choice = asked->double_on_cpu ? clock_seconds() - t_choose : 0;
    struct render_options o = auto_on_device(asked, &device);
    const struct render_options *opt = &o;
    bool cpu_double = o.use_double && !asked->use_double;
    const char *why = NULL; /* why auto or mixed is not what they say (--stats) */
    pack_job_init(&packing, s, opt, &packed, &twin);
    t.pack_start = clock_seconds();
    bool pack_threaded = pthread_create(&pack_thread, NULL, pack, &packing) == 0;
    if (!pack_threaded)
        pack(&packing);
    bool known = wait_features(&packing);
    if (device_threaded)
        pthread_join(device_thread, NULL);
    /* Where packing goes on (a large scene), the pipelines are made now,
     * beside it, planned as if the double scene fits the device (checked
     * once it is packed, below); else after the buffers, as a small
     * scene's render starts 2-5% faster on lavapipe when its buffers are
     * not made just before it. TP2_EARLY_PIPELINES=1 makes them now
     * whatever the scene (tests). A scene that needs double on a device
     * without it is refused below. */
    bool early = known && device.rc == 0 && (!opt->use_double || r.vk.float64) &&
                 (!pack_done(&packing) || test_hooks()->early_pipelines);
    int made_rc = 0;
    t.make_start = clock_seconds();
    if (early) {
        plan_passes(&r, opt, &packing.features, true);
        made_rc = make_pipelines(&r);
    }
    t.made = clock_seconds();
    if (pack_threaded)
        pthread_join(pack_thread, NULL);
    t.packed = packing.finished;
    if (device.rc != 0 || check_band_fits(&r.vk, opt->width) != 0 ||
        check_double_needed(opt, &r.vk) != 0)
        goto done;
    snprintf(stats->device_name, sizeof stats->device_name, "%s", r.vk.props.deviceName);
    if (packing.rc != 0) {
        packing_failed(s);
        goto done;
    }
    if (made_rc == 0 && cpu_double && check_scene_fits(&r.vk, &packed, true, true) != 0) {
        /* auto's double scene does not fit: float alone, packed now */
        why = "the double scene does not fit the device";
        cpu_double = o.use_double = false;
        packing.opt.use_double = false;
        packed_scene_free(&packed);
        if (scene_pack(s, &packing.opt, &packed, NULL) != 0) {
            packing_failed(s);
            goto done;
        }
        if (early) { /* made for double: made again */
            unmake_passes(&r);
            plan_passes(&r, opt, &packed.features, false);
            made_rc = make_passes(&r);
        }
    }
    if (made_rc != 0 || check_scene_fits(&r.vk, &packed, opt->use_double, false) != 0)
        goto done;
    bool twin_fits = opt->retrace && check_scene_fits(&r.vk, &twin, true, true) == 0;
    if (cpu_double)
        why = "a CPU device, where double costs no more than mixed";
    else if (opt->retrace && !twin_fits)
        why = "the double scene does not fit the device";
    t.plan_start = clock_seconds();
    if (!early) {
        plan_passes(&r, opt, &packed.features, twin_fits);
    } else if (!twin_fits && retracing(&r)) { /* planned as if it fit: plan again */
        unmake_passes(&r);
        plan_passes(&r, opt, &packed.features, false);
        if (make_passes(&r) != 0)
            goto done;
    }
    t.planned = clock_seconds();
    describe_precision(&r, asked, why, stats);
    r.band_rows = band_rows(&r.vk, opt->width, opt->height, packed.features.samples);
    if (create_buffers(&r, &packed, &twin, opt->width) != 0)
        goto done;
    t.buffers_made = clock_seconds();
    if ((!early && make_pipelines(&r) != 0) || create_descriptors(&r) != 0 ||
        create_commands(&r) != 0)
        goto done;
    t.commands_made = clock_seconds();
    r.pipeline_time = 0; /* counted in the phases above */
    if (run_bands(&r, opt->width, opt->height, packed.features.samples, opt->progress,
                  on_rows, user, stats) != 0)
        goto done;
    warn_loop_limit(&r.vk, r.buffers[TP2_BINDING_STATS].mapped);
    record_stats(stats, &r, &packed, &device, early, &t);
    rc = 0;
done:
    renderer_destroy(&r);
    packed_scene_free(&packed);
    packed_scene_free(&twin);
    return rc;
}
