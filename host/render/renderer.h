/* renderer.h: what render.c, render_pipelines.c and render_bands.c share:
 * the renderer (one image's device objects) and its passes. Not for other
 * modules: render.h is the API. */
#ifndef TP2_RENDERER_H
#define TP2_RENDERER_H

#include <pthread.h>
#include <stdbool.h>
#include <stdint.h>

#include "render.h"
#include "scene_pack.h"
#include "tp2_shared.h"
#include "vk_buffer.h"
#include "vk_context.h"

/* Bytes of one pixel in the band buffer: an RGBA32F vec4. */
#define TP2_PIXEL_BYTES (4 * sizeof(float))

/* One kind of pass: its shader, its pipelines and the descriptor set they
 * read. The band pass traces every pixel of a band, in the precision
 * chosen (under --precision auto in float, recording signatures); the
 * retrace pass, under auto only, traces the listed pixels in double. */
struct tracer {
    bool use_double, signatures, pixel_list;
    bool soft; /* its doubles in software (the device has no shaderFloat64) */
    const uint32_t *code; /* its SPIR-V: a build of CMakeLists.txt's, or rewritten */
    size_t words;
    uint32_t *rewritten; /* owned: the double build made exact, or fused (choose_code) */
    VkPipeline pipelines[TP2_WALK_KINDS]; /* by TP2_WALK_*, made when needed */
    VkDescriptorSet set;
    VkBufferView views[TP2_BINDING_COUNT]; /* its texel buffers' */
    bool walking;  /* a whole-tree pass was cut: walks go in passes */
    int pass_rays; /* rays a walk traces per pass */
};

/* A pipeline made on a thread of its own (side_job), waited for where it
 * is first needed (join_side). */
struct side_make {
    pthread_t thread;
    bool running;
    int rc;
    struct renderer *r;
};

/* One image's device objects: the device, buffers, layouts, the passes,
 * the finish pipeline, the command buffer, and the host's copy of the
 * last band. */
struct renderer {
    struct vkc vk;
    struct vk_buffer buffers[TP2_BINDING_COUNT];
    struct vk_buffer twin[TP2_INPUT_BUFFERS]; /* the retrace pass's double scene */
    VkDescriptorSetLayout set_layout;
    VkPipelineLayout pipeline_layout;
    struct tracer band, retrace; /* retrace in use where band.signatures */
    struct scene_features features;
    bool count_rays;
    double pipeline_time; /* seconds spent making pipelines */
    VkDescriptorPool pool;
    VkCommandPool command_pool;
    VkCommandBuffer cmd;
    VkFence fence;
    int band_rows;    /* rows per band; the band buffer holds this many */
    bool bytes;       /* the file takes 8-bit values (render_options.bytes) */
    VkShaderModule finish_shader; /* finish.comp: the band as the file needs it */
    VkPipeline finish;
    struct side_make finishing, retrace_making; /* pipelines made beside (side_job) */
    bool eager_retrace; /* make the retrace pipeline beside the band's */
    unsigned char *host_band; /* the last finished band, copied out for the writer */
    uint32_t *last_signatures; /* the previous band's last row's (retracing) */
    bool loop_guard;  /* a CPU device: walks run in passes (TP2_CANARY_STEPS) */
    uint32_t slabs;   /* a dispatch's slabs of workgroup rows (dispatch_slabs) */
    int walk_capacity;
};

/* Whether --precision mixed's (or auto's) retrace is on: the band pass
 * records signatures exactly then. */
static inline bool retracing(const struct renderer *r)
{
    return r->band.signatures;
}

/* Bytes per pixel the output buffer and the host's band hold: one RGBA8
 * word, or four floats (finish.comp). */
static inline VkDeviceSize output_bytes(const struct renderer *r)
{
    return r->bytes ? sizeof(uint32_t) : TP2_PIXEL_BYTES;
}

/* How the shader reads binding i (tp2_shared.h): TP2_TEXEL_BINDINGS as
 * texels, the rest as storage buffers. */
static inline VkDescriptorType binding_type(uint32_t i)
{
    return TP2_TEXEL_BINDINGS >> i & 1u ? VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER
                                        : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
}

/* The passes in use, in passes; returns how many. */
static inline int tracers(struct renderer *r, struct tracer *passes[2])
{
    passes[0] = &r->band;
    passes[1] = &r->retrace;
    return retracing(r) ? 2 : 1;
}

/* render_pipelines.c: each pass's SPIR-V and pipelines, the layouts and
 * the finish pipeline. Each returns 0, or -1 after printing a message. */

/* The layouts, the finish pipeline (beside, on a thread) and the passes'. */
int make_pipelines(struct renderer *r);
/* The passes' code and the band pass's first pipeline. */
int make_passes(struct renderer *r);
/* make_passes undone: to plan again, or at the end. */
void unmake_passes(struct renderer *r);
/* Pass t's pipeline for walks of kind walk (TP2_WALK_*), made if new. */
int need_pipeline(struct renderer *r, struct tracer *t, int walk);
/* Waits for a pipeline made beside; its status. */
int join_side(struct renderer *r, struct side_make *m);

/* render_bands.c: the bands of rows traced (and retraced), finished and
 * handed to the writer. */

/* Slabs a dispatch's workgroup rows are cut into: one per lavapipe thread. */
uint32_t dispatch_slabs(const struct vkc *vk);
/* Every sample of every pixel, band by band, rows handed to on_rows;
 * fills st's band, pass, render, readback, write and retrace figures. */
int run_bands(struct renderer *r, int width, int height, int samples,
              bool show_progress, render_rows_fn on_rows, void *user,
              struct render_stats *st);

#endif
