/* render_pipelines.c: each pass's SPIR-V (by precision and the kinds the
 * scene has, made exact or fused), specialized and made into pipelines;
 * the layouts they share and the finish pipeline, some made on threads of
 * their own. */
#define _POSIX_C_SOURCE 200809L
#include "renderer.h"

#include <stdio.h>
#include <stdlib.h>

#include "clock.h"
#include "test_hooks.h"
#include "finish_spv.h"
#include "gpu_layout.h"
#include "kinds.h"
#include "pipeline_cache.h"
#include "spirv_exact.h"
#include "spirv_soft_double.h"
#include "spirv_specialize.h"
#include "trace_double_basic_spv.h"
#include "trace_double_curved_spv.h"
#include "trace_double_spv.h"
#include "trace_float_basic_spv.h"
#include "trace_float_curved_spv.h"
#include "trace_float_spv.h"
#include "vk_check.h"

/* Whether shadow rays toward the arealight test the last sample's occluder
 * first (trace.comp): the image is the same either way, and the test hook
 * TP2_OCCLUDER_HINT=0 turns it off so that a test can show it. */
static bool occluder_hint(void)
{
    return !test_hooks()->no_occluder_hint;
}

/* The specialization constants of tp2_shared.h, indexed by id: booleans
 * (VkBool32) and ints are all 32-bit words. */
static void spec_values(const struct renderer *r, const struct tracer *t, int walk,
                        int32_t v[TP2_SPEC_COUNT], VkSpecializationMapEntry map[TP2_SPEC_COUNT])
{
    const struct scene_features *f = &r->features;
    v[TP2_SPEC_WALK] = walk;
    v[TP2_SPEC_SIGNATURES] = t->signatures;
    v[TP2_SPEC_PIXEL_LIST] = t->pixel_list;
    v[TP2_SPEC_REFLECT] = f->reflect;
    v[TP2_SPEC_REFRACT] = f->refract;
    v[TP2_SPEC_PIGMENTS] = f->pigments;
    v[TP2_SPEC_SHAPES] = f->shapes;
    v[TP2_SPEC_BOUNDED_SHAPE] = f->bounded_shape;
    v[TP2_SPEC_UNBOUNDED_SHAPE] = f->unbounded_shape;
    v[TP2_SPEC_FOG] = f->fog;
    v[TP2_SPEC_LENS] = f->lens;
    v[TP2_SPEC_AREA] = f->area;
    v[TP2_SPEC_STATS] = r->count_rays;
    v[TP2_SPEC_SAMPLES] = f->samples;
    v[TP2_SPEC_BVH] = f->bvh;
    v[TP2_SPEC_LOOP_GUARD] = r->loop_guard;
    v[TP2_SPEC_OCCLUDER_HINT] = occluder_hint();
    v[TP2_SPEC_SLABS] = (int32_t)r->slabs;
    v[TP2_SPEC_TWINS] = f->twins;
    v[TP2_SPEC_SCENE_SLOTS] = f->scene_slots;
    v[TP2_SPEC_SOFT_KEEP] = 0;
    for (uint32_t id = 0; id < TP2_SPEC_COUNT; id++)
        map[id] = (VkSpecializationMapEntry){id, id * sizeof(int32_t), sizeof(int32_t)};
}

/* The least tier (kinds.h, TP2_TIER_*: which SPIR-V build) that has every
 * kind the scene uses. */
static int kind_tier(const struct scene_features *f)
{
    int tier = TP2_TIER_BASIC;
#define TP2_TIER_OF_(NAME, keyword, id, kind_tier, flat)                      \
    if ((f->shapes >> id & 1) && TP2_TIER_##kind_tier > tier)                  \
        tier = TP2_TIER_##kind_tier;
    TP2_SHAPES(TP2_TIER_OF_)
#undef TP2_TIER_OF_
    return tier;
}

/* The SPIR-V builds (CMakeLists.txt), by precision (double: 1) and tier. */
static const struct {
    const uint32_t *code;
    size_t size;
} builds[2][TP2_TIERS] = {
    {{tp2_trace_float_basic, sizeof tp2_trace_float_basic},
     {tp2_trace_float, sizeof tp2_trace_float},
     {tp2_trace_float_curved, sizeof tp2_trace_float_curved}},
    {{tp2_trace_double_basic, sizeof tp2_trace_double_basic},
     {tp2_trace_double, sizeof tp2_trace_double},
     {tp2_trace_double_curved, sizeof tp2_trace_double_curved}},
};

/* The descriptor set layout and the pipeline layout. */
static int create_layouts(struct renderer *r)
{
    VkDescriptorSetLayoutBinding bindings[TP2_BINDING_COUNT];
    for (uint32_t i = 0; i < TP2_BINDING_COUNT; i++)
        bindings[i] = (VkDescriptorSetLayoutBinding){
            .binding = i,
            .descriptorType = binding_type(i),
            .descriptorCount = 1,
            .stageFlags = VK_SHADER_STAGE_COMPUTE_BIT,
        };
    VkDescriptorSetLayoutCreateInfo set_info = {
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO,
        .bindingCount = TP2_BINDING_COUNT,
        .pBindings = bindings,
    };
    TP2_VK_TRY(vkCreateDescriptorSetLayout(r->vk.device, &set_info, NULL,
                                           &r->set_layout));
    VkPushConstantRange push = {
        .stageFlags = VK_SHADER_STAGE_COMPUTE_BIT,
        .size = sizeof(struct gpu_tile),
    };
    VkPipelineLayoutCreateInfo layout_info = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO,
        .setLayoutCount = 1,
        .pSetLayouts = &r->set_layout,
        .pushConstantRangeCount = 1,
        .pPushConstantRanges = &push,
    };
    TP2_VK_TRY(vkCreatePipelineLayout(r->vk.device, &layout_info, NULL,
                                      &r->pipeline_layout));
    return 0;
}

/* Pass t's code rewritten by `pass` (spirv_exact, spirv_soft_double),
 * which t then owns. Returns the pass's count of sites, or (size_t)-1
 * after saying `doing` failed (out of memory: the embedded builds are
 * what the passes are tested on). */
static size_t rewrite(struct tracer *t,
                      uint32_t *(*pass)(const uint32_t *, size_t, size_t *, size_t *),
                      const char *doing)
{
    size_t words = 0, sites = 0;
    uint32_t *code = pass(t->code, t->words, &words, &sites);
    if (!code) {
        fprintf(stderr, "tp2: out of memory %s\n", doing);
        return (size_t)-1;
    }
    free(t->rewritten);
    t->rewritten = code;
    t->code = code;
    t->words = words;
    return sites;
}

/* Each pass's SPIR-V, of its precision and the kinds the scene needs. */
static int choose_code(struct renderer *r)
{
    int tier = kind_tier(&r->features);
    struct tracer *passes[2];
    for (int k = 0, n = tracers(r, passes); k < n; k++) {
        struct tracer *t = passes[k];
        t->code = builds[t->use_double][tier].code;
        t->words = builds[t->use_double][tier].size / sizeof *t->code;
        if (t->use_double &&
            rewrite(t, t->soft ? spirv_soft_double : spirv_exact,
                    t->soft ? "putting software double in the shader"
                            : "making the double shader exact") == (size_t)-1)
            return -1;
    }
    return 0;
}

/* Pass t's shader module for a pipeline with the specialization constants
 * `values`: its code without what they rule out (spirv_specialize.h; a
 * pipeline made 1.5-3 times faster on lavapipe, docs/decisions.md),
 * or as it is where that fails or under the test hook TP2_SPECIALIZE=0. */
static VkResult create_module(const struct renderer *r, const struct tracer *t,
                              const int32_t values[TP2_SPEC_COUNT], VkShaderModule *module)
{
    size_t words = t->words;
    uint32_t *specialized = test_hooks()->no_specialize
                                ? NULL
                                : spirv_specialize(t->code, t->words, values, TP2_SPEC_COUNT,
                                                   &words);
    VkShaderModuleCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO,
        .codeSize = (specialized ? words : t->words) * sizeof *t->code,
        .pCode = specialized ? specialized : t->code,
    };
    VkResult made = vkCreateShaderModule(r->vk.device, &info, NULL, module);
    free(specialized);
    return made;
}

/* A compute pipeline of module's main with the given constants. */
static VkComputePipelineCreateInfo pipeline_info(const struct renderer *r, VkShaderModule module,
                                                 const VkSpecializationInfo *spec)
{
    return (VkComputePipelineCreateInfo){
        .sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO,
        .stage = {
            .sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
            .stage = VK_SHADER_STAGE_COMPUTE_BIT,
            .module = module,
            .pName = "main",
            .pSpecializationInfo = spec,
        },
        .layout = r->pipeline_layout,
    };
}

/* Makes pass t's pipeline for walks of kind `walk` (TP2_WALK_*), through
 * a pipeline cache of its own, so that two threads may each make one. */
static int make_pipeline(struct renderer *r, struct tracer *t, int walk)
{
    int32_t values[TP2_SPEC_COUNT];
    VkSpecializationMapEntry map[TP2_SPEC_COUNT];
    spec_values(r, t, walk, values, map);
    VkSpecializationInfo spec = {
        .mapEntryCount = TP2_SPEC_COUNT,
        .pMapEntries = map,
        .dataSize = sizeof values,
        .pData = values,
    };
    VkShaderModule module = VK_NULL_HANDLE;
    VkResult made = create_module(r, t, values, &module);
    if (made != VK_SUCCESS) {
        vk_report("vkCreateShaderModule", made, __FILE__, __LINE__);
        return -1;
    }
    VkComputePipelineCreateInfo info = pipeline_info(r, module, &spec);
    VkPipelineCache cache = VK_NULL_HANDLE;
    if (pipeline_cache_load(&r->vk, &cache) != 0) {
        vkDestroyShaderModule(r->vk.device, module, NULL);
        return -1;
    }
    made = vkCreateComputePipelines(r->vk.device, cache, 1, &info, NULL, &t->pipelines[walk]);
    pipeline_cache_save(&r->vk, cache);
    vkDestroyShaderModule(r->vk.device, module, NULL); /* the pipeline keeps what it needs */
    if (made != VK_SUCCESS) {
        t->pipelines[walk] = VK_NULL_HANDLE;
        vk_report("vkCreateComputePipelines", made, __FILE__, __LINE__);
        return -1;
    }
    return 0;
}

/* Pass t's pipeline for walks of kind `walk`, made when first needed:
 * most scenes only ever need TP2_WALK_WHOLE. */
int need_pipeline(struct renderer *r, struct tracer *t, int walk)
{
    if (t->pipelines[walk])
        return 0;
    double t0 = clock_seconds();
    int rc = make_pipeline(r, t, walk);
    r->pipeline_time += clock_seconds() - t0;
    return rc;
}

/* The finish pipeline (finish.comp), for 8-bit values or floats. */
static int create_finish(struct renderer *r)
{
    VkShaderModuleCreateInfo module_info = {
        .sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO,
        .codeSize = sizeof tp2_finish,
        .pCode = tp2_finish,
    };
    TP2_VK_TRY(vkCreateShaderModule(r->vk.device, &module_info, NULL, &r->finish_shader));
    VkBool32 bytes = r->bytes;
    VkSpecializationMapEntry entry = {TP2_FINISH_SPEC_BYTES, 0, sizeof bytes};
    VkSpecializationInfo spec = {
        .mapEntryCount = 1,
        .pMapEntries = &entry,
        .dataSize = sizeof bytes,
        .pData = &bytes,
    };
    VkComputePipelineCreateInfo info = pipeline_info(r, r->finish_shader, &spec);
    TP2_VK_TRY(vkCreateComputePipelines(r->vk.device, VK_NULL_HANDLE, 1, &info, NULL,
                                        &r->finish));
    return 0;
}

/* What is compiled on threads of its own, beside the band pass's much
 * longer compile and its first band's float pass: the finish pipeline (on
 * lavapipe it would add 8-10 ms to every start), and under auto, for
 * images of TP2_EAGER_RETRACE samples or more, the retrace pass's, which
 * is otherwise made in the middle of the first band that needs it. Each
 * is waited for where it is first needed. */
static void *finish_job(void *arg)
{
    struct side_make *m = arg;
    m->rc = create_finish(m->r);
    return NULL;
}

static void *retrace_job(void *arg)
{
    struct side_make *m = arg;
    m->rc = make_pipeline(m->r, &m->r->retrace, TP2_WALK_WHOLE);
    return NULL;
}

static void side_job(struct renderer *r, struct side_make *m, void *(*job)(void *))
{
    m->r = r;
    m->running = pthread_create(&m->thread, NULL, job, m) == 0;
    if (!m->running)
        job(m);
}

/* Waits for m's job if it still runs; a wait counts as pipeline time.
 * Returns the job's status (0 for one never started). */
int join_side(struct renderer *r, struct side_make *m)
{
    if (m->running) {
        double t0 = clock_seconds();
        pthread_join(m->thread, NULL);
        m->running = false;
        r->pipeline_time += clock_seconds() - t0;
    }
    return m->rc;
}

/* The passes' pipelines (and fused code), destroyed (make_passes undone,
 * to plan again or at the end). */
void unmake_passes(struct renderer *r)
{
    join_side(r, &r->retrace_making);
    struct tracer *passes[2] = {&r->band, &r->retrace};
    for (int p = 0; p < 2; p++) {
        for (int k = 0; k < TP2_WALK_KINDS; k++) {
            vkDestroyPipeline(r->vk.device, passes[p]->pipelines[k], NULL);
            passes[p]->pipelines[k] = VK_NULL_HANDLE;
        }
        free(passes[p]->rewritten);
        passes[p]->rewritten = NULL;
    }
}

/* The passes' code and the band pass's pipeline. The retrace
 * pass's pipelines, like the walks', are made when first needed (a scene
 * where no pixel needs double never makes them), but for a large image
 * (eager_retrace) its first one is made now, on a thread of its own
 * (side_job). */
int make_passes(struct renderer *r)
{
    if (choose_code(r) != 0)
        return -1;
    if (r->eager_retrace)
        side_job(r, &r->retrace_making, retrace_job);
    return need_pipeline(r, &r->band, TP2_WALK_WHOLE);
}

/* The layouts, the finish pipeline (on a thread of its own) and the
 * passes'. */
int make_pipelines(struct renderer *r)
{
    if (create_layouts(r) != 0)
        return -1;
    side_job(r, &r->finishing, finish_job);
    return make_passes(r);
}
