/* render_bands.c: the image rendered band by band: each band's passes
 * submitted (walks going on across passes on CPU devices), its marked
 * pixels traced again under --precision mixed, finished on the device
 * and copied out, and the previous band handed to the writer meanwhile. */
#define _POSIX_C_SOURCE 200809L
#include "renderer.h"

#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "clock.h"
#include "gpu_layout.h"
#include "progress.h"
#include "retrace.h"
#include "test_hooks.h"
#include "vk_check.h"

/* Most slabs a dispatch is cut into: lavapipe runs at most 16 or 32
 * threads (by version); more slabs than threads still spread each
 * thread's run over the band. */
#define TP2_MAX_SLABS 32

/* Lavapipe hands each of its threads one contiguous run of a dispatch's
 * workgroups (lp_cs_tpool.c: workgroups / threads each), and a thread
 * that finishes its run early takes none of another's. Where the dear
 * pixels sit together (a glass object in one half of a band), one thread
 * traced most of the band while the other waited. So a dispatch has a
 * third dimension, one slab per thread: workgroup (x, y, z) traces
 * workgroup row y * slabs + z (trace.comp, group_place), and each
 * thread's run, a slab of z, holds every slabs-th row of the band,
 * spread over all of it. Lavapipe's threads are LP_NUM_THREADS or one
 * per CPU; GPUs give workgroups to whatever unit is free: one slab. The
 * test hook TP2_DISPATCH_SLABS sets the count. The
 * shader has it as a specialization constant: read from gl_NumWorkGroups
 * it made spheres.txt's float render 20% slower on lavapipe. */
/* Lavapipe's thread count: LP_NUM_THREADS where it is a whole number,
 * else one per CPU. */
static long lavapipe_threads(void)
{
    const char *env = getenv("LP_NUM_THREADS");
    char *end;
    long n = env && *env ? strtol(env, &end, 10) : 0;
    return env && *env && *end == '\0' ? n : sysconf(_SC_NPROCESSORS_ONLN);
}

uint32_t dispatch_slabs(const struct vkc *vk)
{
    long n = 1;
    if (vk->props.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU)
        n = lavapipe_threads();
    if (test_hooks()->dispatch_slabs_set)
        n = test_hooks()->dispatch_slabs;
    return n < 1 ? 1 : n > TP2_MAX_SLABS ? TP2_MAX_SLABS : (uint32_t)n;
}

/* Records a dispatch of `across` x `down` workgroups, in r->slabs slabs. */
static void dispatch_rows(struct renderer *r, uint32_t across, uint32_t down)
{
    vkCmdDispatch(r->cmd, across, (down + r->slabs - 1) / r->slabs, r->slabs);
}

/* What one pass of t covers: sample `sample` of the band of rows [y, y +
 * rows), and of the first `listed` pixels in the pixel list if t traces a
 * list. */
struct pass_area {
    int width, y, rows, sample;
    uint32_t listed;
};

/* Starts recording r's one command buffer afresh. */
static int begin_commands(struct renderer *r)
{
    VkCommandBufferBeginInfo begin = {
        .sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
        .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT,
    };
    TP2_VK_TRY(vkResetCommandBuffer(r->cmd, 0));
    TP2_VK_TRY(vkBeginCommandBuffer(r->cmd, &begin));
    return 0;
}

/* Ends the command buffer and submits it; r's fence signals when done. */
static int submit_commands(struct renderer *r)
{
    TP2_VK_TRY(vkEndCommandBuffer(r->cmd));
    VkSubmitInfo submit = {
        .sType = VK_STRUCTURE_TYPE_SUBMIT_INFO,
        .commandBufferCount = 1,
        .pCommandBuffers = &r->cmd,
    };
    TP2_VK_TRY(vkResetFences(r->vk.device, 1, &r->fence));
    TP2_VK_TRY(vkQueueSubmit(r->vk.queue, 1, &submit, r->fence));
    return 0;
}

/* Records and submits one pass of t (TP2_WALK_*) of the area's walks: a
 * whole-tree or start dispatch covers the band (and the row after it,
 * for its signatures) or the listed pixels, a continue one the `walks`
 * saved walks. `clear`: the sample's first pass, which clears the band's
 * started flags first. */
static int submit_pass(struct renderer *r, struct tracer *t, const struct pass_area *a,
                       int kind, uint32_t walks, bool clear)
{
    struct gpu_tile push = {{0, a->y}, a->sample, t->pass_rays, r->walk_capacity,
                             t->pass_rays == 1, a->rows, (int32_t)a->listed};
    if (need_pipeline(r, t, kind) != 0)
        return -1;
    if (begin_commands(r) != 0)
        return -1;
    if (clear && r->loop_guard) {
        vkCmdFillBuffer(r->cmd, r->buffers[TP2_BINDING_STARTED].buffer, 0, VK_WHOLE_SIZE, 0);
        VkMemoryBarrier cleared = {
            .sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
            .srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT,
            .dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT,
        };
        vkCmdPipelineBarrier(r->cmd, VK_PIPELINE_STAGE_TRANSFER_BIT,
                             VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1, &cleared, 0, NULL,
                             0, NULL);
    }
    vkCmdBindPipeline(r->cmd, VK_PIPELINE_BIND_POINT_COMPUTE, t->pipelines[kind]);
    vkCmdBindDescriptorSets(r->cmd, VK_PIPELINE_BIND_POINT_COMPUTE,
                            r->pipeline_layout, 0, 1, &t->set, 0, NULL);
    vkCmdPushConstants(r->cmd, r->pipeline_layout, VK_SHADER_STAGE_COMPUTE_BIT,
                       0, sizeof push, &push);
    uint32_t group = TP2_GROUP_X * TP2_GROUP_Y;
    uint32_t rows = (uint32_t)(a->rows + t->signatures);
    if (kind == TP2_WALK_CONTINUE)
        dispatch_rows(r, 1, (walks + group - 1) / group);
    else if (t->pixel_list)
        dispatch_rows(r, 1, (a->listed + group - 1) / group);
    else
        dispatch_rows(r, (uint32_t)(a->width + TP2_GROUP_X - 1) / TP2_GROUP_X,
                      (rows + TP2_GROUP_Y - 1) / TP2_GROUP_Y);
    /* Make the shader's writes visible to the next pass, which adds to the
     * pixels, goes on with the walks and clears the started flags, and to
     * the host's reads after the fence. */
    VkMemoryBarrier barrier = {
        .sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
        .srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT,
        .dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT |
                         VK_ACCESS_HOST_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT,
    };
    vkCmdPipelineBarrier(r->cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                         VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_HOST_BIT |
                             VK_PIPELINE_STAGE_TRANSFER_BIT,
                         0, 1, &barrier, 0, NULL, 0, NULL);
    return submit_commands(r);
}

static int wait_pass(struct renderer *r)
{
    TP2_VK_TRY(vkWaitForFences(r->vk.device, 1, &r->fence, VK_TRUE, UINT64_MAX));
    return 0;
}

/* The band the host holds (copied out of device memory), and how many of
 * its rows the writer has had. */
struct host_band {
    int y, rows, done;
};

/* Hands rows [done, upto) of the host's band to on_rows; 0 or -1. */
static int hand_on(struct renderer *r, struct host_band *b, int upto, int width,
                   render_rows_fn on_rows, void *user, double *time)
{
    if (upto <= b->done)
        return 0;
    double t0 = clock_seconds();
    int rc = on_rows(user, r->host_band + (size_t)b->done * width * output_bytes(r),
                     b->y + b->done, upto - b->done);
    *time += clock_seconds() - t0;
    b->done = upto;
    return rc;
}

/* What the host writes while a band's first pass renders: rows of the
 * band it holds, up to `upto`. */
struct writing {
    struct host_band *held;
    int upto, width;
    render_rows_fn on_rows;
    void *user;
    double *time;
};

/* Runs pass t over area a to the end: every pixel's walk starts in a
 * first pass; on a CPU device those that did not finish go on in further
 * passes, and a pass that lavapipe cut short runs again with half the rays
 * per walk (TP2_CANARY_STEPS). While the first pass renders, the host
 * writes (w, if not NULL). *passes counts the passes. */
static int render_band_sample(struct renderer *r, struct tracer *t, const struct pass_area *a,
                              const struct writing *w, uint32_t *passes)
{
    uint32_t *count = (uint32_t *)r->buffers[TP2_BINDING_STATS].mapped + 2 * TP2_STAT_COUNT;
    int kind = t->walking ? TP2_WALK_START : TP2_WALK_WHOLE;
    bool first = true;
    bool waiting = false; /* walks found no room: their pixels start again */
    count[TP2_COUNTER_WALKS] = 0;
    for (;;) {
        count[TP2_COUNTER_CUT] = count[TP2_COUNTER_UNFINISHED] = count[TP2_COUNTER_WAITING] = 0;
        uint32_t walks = count[TP2_COUNTER_WALKS];
        if (walks > (uint32_t)r->walk_capacity)
            walks = (uint32_t)r->walk_capacity;
        if (submit_pass(r, t, a, kind, walks, first) != 0 ||
            (first && w && hand_on(r, w->held, w->upto, w->width, w->on_rows, w->user, w->time) != 0) ||
            wait_pass(r) != 0)
            return -1;
        first = false;
        ++*passes;
        if (kind == TP2_WALK_WHOLE) { /* cut trees: in walks from now on */
            if (count[TP2_COUNTER_CUT] == 0)
                return 0;
            t->walking = true;
            kind = TP2_WALK_START;
            continue;
        }
        if (count[TP2_COUNTER_CUT] > 0 && t->pass_rays > 1) {
            t->pass_rays /= 2; /* the same pass again: cut walks are as they were */
            continue;
        }
        if (kind == TP2_WALK_START)
            waiting = count[TP2_COUNTER_WAITING] > 0;
        if (count[TP2_COUNTER_WALKS] > 0 &&
            (kind == TP2_WALK_START || count[TP2_COUNTER_UNFINISHED] > 0)) {
            kind = TP2_WALK_CONTINUE;
        } else if (waiting) { /* every saved walk is done: room for the rest */
            kind = TP2_WALK_START;
            count[TP2_COUNTER_WALKS] = 0;
        } else {
            return 0;
        }
    }
}

/* Under --precision auto, after the band's float pass: marks the pixels
 * whose decisions differ from a neighbour's (retrace.c), the row before
 * the band (kept from the last band) and the row after it (traced for
 * its signatures) included, and traces them again, every sample, in
 * double. */
static int retrace_band(struct renderer *r, int width, int height, int y, int rows,
                        int samples, struct render_stats *st)
{
    double t0 = clock_seconds(), made0 = r->pipeline_time;
    const uint32_t *sig = r->buffers[TP2_BINDING_SIGNATURES].mapped;
    const uint32_t *after = y + rows < height ? sig + (size_t)rows * width : NULL;
    size_t listed = retrace_mark(y > 0 ? r->last_signatures : NULL, sig, after, width, rows,
                                 r->buffers[TP2_BINDING_PIXEL_LIST].mapped);
    memcpy(r->last_signatures, sig + (size_t)(rows - 1) * width, (size_t)width * sizeof *sig);
    st->retraced += listed;
    if (listed > 0 && join_side(r, &r->retrace_making) != 0)
        return -1;
    for (int s = 0; s < samples && listed > 0; s++) {
        struct pass_area a = {width, y, rows, s, (uint32_t)listed};
        if (render_band_sample(r, &r->retrace, &a, NULL, &st->passes) != 0)
            return -1;
    }
    /* pipelines made or waited for here count as such, as in render */
    st->retrace += clock_seconds() - t0 - (r->pipeline_time - made0);
    return 0;
}

/* The finished band's first `pixels` pixels into the output buffer as the
 * file needs them (finish.comp), waited for. */
static int finish_band(struct renderer *r, int pixels)
{
    struct gpu_tile push = {.list_length = pixels};
    if (begin_commands(r) != 0)
        return -1;
    vkCmdBindPipeline(r->cmd, VK_PIPELINE_BIND_POINT_COMPUTE, r->finish);
    vkCmdBindDescriptorSets(r->cmd, VK_PIPELINE_BIND_POINT_COMPUTE, r->pipeline_layout, 0, 1,
                            &r->band.set, 0, NULL);
    vkCmdPushConstants(r->cmd, r->pipeline_layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push,
                       &push);
    vkCmdDispatch(r->cmd, ((uint32_t)pixels + TP2_FINISH_GROUP - 1) / TP2_FINISH_GROUP, 1, 1);
    /* The host reads the output after the fence; the next band's first
     * pass overwrites the pixels only after this read them. */
    VkMemoryBarrier barrier = {
        .sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
        .srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_SHADER_READ_BIT,
        .dstAccessMask = VK_ACCESS_HOST_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT,
    };
    vkCmdPipelineBarrier(r->cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                         VK_PIPELINE_STAGE_HOST_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1,
                         &barrier, 0, NULL, 0, NULL);
    return submit_commands(r) != 0 ? -1 : wait_pass(r);
}

/* Renders every sample of every pixel, band by band, one dispatch per band
 * and sample, each adding its sample's share to the pixels. One sample per
 * dispatch also keeps each invocation's work bounded: lavapipe ends a
 * shader invocation's loops after 65535 iterations in all (gallivm's
 * LP_MAX_TGSI_LOOP_ITERATIONS), which 64 samples of a glass scene in one
 * invocation overran, silently. While the device renders a band, the host
 * writes the previous one, a share after each submission. */
int run_bands(struct renderer *r, int width, int height, int samples,
              bool show_progress, render_rows_fn on_rows, void *user,
              struct render_stats *st)
{
    struct progress bar;
    progress_start(&bar, show_progress);
    int rows = r->band_rows;
    int bands = (height + rows - 1) / rows;
    st->bands = bands;
    st->band_rows = rows;
    struct host_band held = {0, 0, 0};
    double t0 = clock_seconds();
    int rc = 0;
    for (int band = 0; band < bands && rc == 0; band++) {
        int y = band * rows, n = height - y < rows ? height - y : rows;
        for (int s = 0; s < samples && rc == 0; s++) {
            struct writing w = {&held, (int)((int64_t)held.rows * (s + 1) / samples), width,
                                on_rows, user, &st->write};
            struct pass_area a = {width, y, n, s, 0};
            rc = render_band_sample(r, &r->band, &a, &w, &st->passes);
            progress_update(&bar, (double)(band * samples + s + 1) / ((double)samples * bands));
        }
        if (rc == 0 && retracing(r))
            rc = retrace_band(r, width, height, y, n, samples, st);
        if (rc == 0 && join_side(r, &r->finishing) != 0)
            rc = -1;
        if (rc == 0) { /* the device may reuse its buffers once this is copied */
            double t1 = clock_seconds();
            rc = finish_band(r, n * width);
            if (rc == 0)
                memcpy(r->host_band, r->buffers[TP2_BINDING_OUTPUT].mapped,
                       (size_t)n * width * output_bytes(r));
            st->readback += clock_seconds() - t1;
            held = (struct host_band){y, n, 0};
        }
    }
    if (rc == 0)
        rc = hand_on(r, &held, held.rows, width, on_rows, user, &st->write);
    st->render = clock_seconds() - t0 - st->readback - st->write;
    progress_finish(&bar);
    return rc;
}
