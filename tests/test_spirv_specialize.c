/* test_spirv_specialize.c: the shader with what its specialization
 * constants rule out taken away (spirv_specialize). On each of the six
 * embedded trace shaders, under constants of a sphere-and-plane scene, of
 * every kind at once, and the module's defaults: the result is valid
 * SPIR-V for Vulkan 1.1 (SPIRV-Tools' validator), removed words (more for
 * the small scene), every id it uses is defined in it, every call names a
 * function it keeps; code for a shape kind the scene lacks is gone, for
 * one it has kept. A probe shader (specialize_probe.comp) holds the
 * control flow the trace shaders may not: a switch, loops left early,
 * a continue construct of several blocks, OpPhis across ruled-out edges;
 * under each of its 12 sets of constants the result is valid and keeps
 * exactly the functions those constants can call. 60 random sets of
 * constants on the trace shaders give valid modules too. Malformed modules are
 * refused. (That each specialized shader renders the same image is
 * checked by effect_specialized_same_image, under the validation layer.) */
#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define SPV_ENABLE_UTILITY_CODE
#include <spirv/unified1/spirv.h>

#include "kinds.h"
#include "specialize_probe_spv.h"
#include "spirv_specialize.h"
#include "tp2_shared.h"
#include "trace_double_basic_spv.h"
#include "trace_double_curved_spv.h"
#include "trace_double_spv.h"
#include "trace_float_basic_spv.h"
#include "trace_float_curved_spv.h"
#include "trace_float_spv.h"
#include "unit.h"
#include "spirv_test.h"

/* SpvHasResultAndType's external definition is spirv_specialize.c's. */

enum { HEADER = 5 };

/* Constants of a scene of spheres and planes, solid pigments, no
 * reflection or refraction, under auto's float pass. */
static void small_scene(int32_t v[TP2_SPEC_COUNT])
{
    memset(v, 0, TP2_SPEC_COUNT * sizeof *v);
    v[TP2_SPEC_PIGMENTS] = 1 << TP2_PIGMENT_SOLID;
    v[TP2_SPEC_SHAPES] = 1 << TP2_SHAPE_SPHERE | 1 << TP2_SHAPE_PLANE;
    v[TP2_SPEC_BOUNDED_SHAPE] = TP2_SHAPE_SPHERE;
    v[TP2_SPEC_UNBOUNDED_SHAPE] = TP2_SHAPE_PLANE;
    v[TP2_SPEC_SAMPLES] = 1;
    v[TP2_SPEC_SIGNATURES] = 1;
    v[TP2_SPEC_SLABS] = 2;
}

/* Every kind and effect in use at once. */
static void everything(int32_t v[TP2_SPEC_COUNT])
{
    small_scene(v);
    v[TP2_SPEC_REFLECT] = v[TP2_SPEC_REFRACT] = 1;
    v[TP2_SPEC_PIGMENTS] = v[TP2_SPEC_SHAPES] = -1;
    v[TP2_SPEC_BOUNDED_SHAPE] = v[TP2_SPEC_UNBOUNDED_SHAPE] = -1;
    v[TP2_SPEC_FOG] = v[TP2_SPEC_LENS] = v[TP2_SPEC_AREA] = v[TP2_SPEC_STATS] = 1;
    v[TP2_SPEC_SAMPLES] = 4;
    v[TP2_SPEC_BVH] = v[TP2_SPEC_LOOP_GUARD] = v[TP2_SPEC_OCCLUDER_HINT] = 1;
}

static uint32_t result_of(const uint32_t *op)
{
    bool result = false, type = false;
    SpvHasResultAndType((SpvOp)(op[0] & 0xffffu), &result, &type);
    return result ? op[type ? 2 : 1] : 0;
}

/* Whether an OpName in the module starts with `name`. */
static bool named(const uint32_t *code, size_t words, const char *name)
{
    for (size_t at = HEADER; at < words; at += code[at] >> 16)
        if ((code[at] & 0xffffu) == SpvOpName &&
            strncmp((const char *)(code + at + 2), name, strlen(name)) == 0)
            return true;
    return false;
}

/* Checks the module's structure; returns false (and reports) if broken. */
static bool check_module(const char *what, const uint32_t *out, size_t words)
{
    expect(spirv_valid(what, out, words), "%s: valid SPIR-V", what);
    uint32_t bound = out[3];
    unsigned char *defined = calloc(bound, 1), *function = calloc(bound, 1);
    bool ok = defined && function;
    for (size_t at = HEADER; ok && at < words;) {
        uint32_t count = out[at] >> 16;
        if (count == 0 || count > words - at) {
            ok = false;
            break;
        }
        uint32_t id = result_of(out + at);
        if (id >= bound || (id && defined[id]))
            ok = false;
        else if (id)
            defined[id] = 1;
        if ((out[at] & 0xffffu) == SpvOpFunction)
            function[id] = 1;
        at += count;
    }
    expect(ok, "%s: well formed, ids defined once below the bound", what);
    int undefined = 0, bad_calls = 0, bad_blocks = 0, in_block = 0;
    for (size_t at = HEADER; ok && at < words; at += out[at] >> 16) {
        uint32_t op = out[at] & 0xffffu, count = out[at] >> 16;
        if ((op == SpvOpName || op == SpvOpDecorate) && !defined[out[at + 1]])
            undefined++;
        if (op == SpvOpFunctionCall && !function[out[at + 3]])
            bad_calls++;
        if (op == SpvOpBranch && !defined[out[at + 1]])
            undefined++;
        if (op == SpvOpBranchConditional && (!defined[out[at + 2]] || !defined[out[at + 3]]))
            undefined++;
        if (op == SpvOpPhi)
            for (uint32_t w = 3; w + 1 < count; w += 2)
                undefined += !defined[out[at + w]] || !defined[out[at + w + 1]];
        if (op == SpvOpLabel)
            bad_blocks += in_block, in_block = 1;
        if (op == SpvOpBranch || op == SpvOpBranchConditional || op == SpvOpSwitch ||
            op == SpvOpReturn || op == SpvOpReturnValue || op == SpvOpUnreachable)
            bad_blocks += !in_block, in_block = 0;
    }
    expect(undefined == 0, "%s: %d uses of ids it no longer defines", what, undefined);
    expect(bad_calls == 0, "%s: %d calls of functions it dropped", what, bad_calls);
    expect(bad_blocks == 0, "%s: %d blocks without one terminator", what, bad_blocks);
    free(defined);
    free(function);
    return ok;
}

static void check_shader(const char *name, const uint32_t *code, size_t bytes, bool curved)
{
    size_t words = bytes / 4;
    int32_t small[TP2_SPEC_COUNT], all[TP2_SPEC_COUNT];
    small_scene(small);
    everything(all);
    size_t removed_small = 0, removed_all = 0, out_words = 0;
    uint32_t *out = spirv_specialize(code, words, small, TP2_SPEC_COUNT, &out_words);
    removed_small = out && out_words < words ? words - out_words : 0;
    expect(out != NULL, "%s: specialized for spheres and planes", name);
    if (out && check_module(name, out, out_words)) {
        expect(removed_small > words / 8, "%s: only %zu of %zu words removed", name,
               removed_small, words);
        expect(named(code, words, "hit_sphere") && named(out, out_words, "hit_sphere"),
               "%s: the sphere's test kept", name);
        if (curved)
            expect(named(code, words, "hit_torus") && !named(out, out_words, "hit_torus"),
                   "%s: the torus's test, unused, removed", name);
    }
    free(out);
    out = spirv_specialize(code, words, all, TP2_SPEC_COUNT, &out_words);
    removed_all = out && out_words < words ? words - out_words : 0;
    expect(out != NULL, "%s: specialized for everything", name);
    if (out && check_module(name, out, out_words) && curved)
        expect(named(out, out_words, "hit_torus"), "%s: the torus's test kept", name);
    free(out);
    expect(removed_all < removed_small, "%s: everything removed %zu words, one scene %zu",
           name, removed_all, removed_small);
    out = spirv_specialize(code, words, NULL, 0, &out_words);
    expect(out != NULL && check_module(name, out, out_words),
           "%s: specialized with the module's own defaults", name);
    free(out);
}

/* Sets of constants no scene may give (a fixed seed): every result valid. */
static void check_random_constants(void)
{
    static const struct {
        const uint32_t *code;
        size_t bytes;
    } builds[] = {
        {tp2_trace_float_basic, sizeof tp2_trace_float_basic},
        {tp2_trace_float, sizeof tp2_trace_float},
        {tp2_trace_float_curved, sizeof tp2_trace_float_curved},
        {tp2_trace_double_basic, sizeof tp2_trace_double_basic},
        {tp2_trace_double, sizeof tp2_trace_double},
        {tp2_trace_double_curved, sizeof tp2_trace_double_curved},
    };
    uint32_t seed = 12345;
    int invalid = 0;
    for (int round = 0; round < 60; round++) {
        int32_t v[TP2_SPEC_COUNT];
        for (int i = 0; i < TP2_SPEC_COUNT; i++) {
            seed = seed * 1664525u + 1013904223u;
            v[i] = (int32_t)(seed >> 20) % 40 - 2; /* booleans, kinds, -1, masks */
        }
        size_t k = (size_t)round % 6, out_words = 0;
        uint32_t *out = spirv_specialize(builds[k].code, builds[k].bytes / 4, v, TP2_SPEC_COUNT,
                                         &out_words);
        invalid += !out || !spirv_valid("random constants", out, out_words);
        free(out);
    }
    expect(invalid == 0, "%d of 60 random sets of constants gave no valid module", invalid);
}

/* The probe under A, B, K: valid, and its functions kept where the
 * constants can call them, gone where they cannot. */
static void check_probe(void)
{
    size_t words = sizeof tp2_specialize_probe / 4;
    expect(spirv_valid("probe", tp2_specialize_probe, words), "the probe itself is valid");
    for (int a = 0; a < 2; a++)
        for (int b = 0; b < 2; b++)
            for (int k = 1; k <= 3; k++) {
                int32_t v[3] = {a, b, k};
                size_t out_words = 0;
                char what[64];
                snprintf(what, sizeof what, "probe A=%d B=%d K=%d", a, b, k);
                uint32_t *out = spirv_specialize(tp2_specialize_probe, words, v, 3, &out_words);
                expect(out != NULL, "%s: specialized", what);
                if (!out || !check_module(what, out, out_words)) {
                    free(out);
                    continue;
                }
                expect(named(out, out_words, "only_if_a(") == (a == 1), "%s: only_if_a", what);
                expect(named(out, out_words, "only_if_not_a("), "%s: only_if_not_a", what);
                expect(named(out, out_words, "only_if_k2(") == (k == 2), "%s: only_if_k2",
                       what);
                expect(named(out, out_words, "only_if_b(") == (b == 1), "%s: only_if_b", what);
                expect(out_words < words, "%s: nothing removed", what);
                free(out);
            }
}

static void refuses_malformed(void)
{
    size_t words = sizeof tp2_trace_float_basic / 4, out_words = 0;
    uint32_t *copy = malloc(words * sizeof *copy);
    int32_t v[TP2_SPEC_COUNT];
    small_scene(v);
    memcpy(copy, tp2_trace_float_basic, words * sizeof *copy);
    copy[0] = 0;
    CHECK(spirv_specialize(copy, words, v, TP2_SPEC_COUNT, &out_words) == NULL);
    memcpy(copy, tp2_trace_float_basic, words * sizeof *copy);
    CHECK(spirv_specialize(copy, words - 1, v, TP2_SPEC_COUNT, &out_words) == NULL);
    CHECK(spirv_specialize(copy, 3, v, TP2_SPEC_COUNT, &out_words) == NULL);
    copy[HEADER] = 0; /* a zero word count */
    CHECK(spirv_specialize(copy, words, v, TP2_SPEC_COUNT, &out_words) == NULL);
    memcpy(copy, tp2_trace_float_basic, words * sizeof *copy);
    copy[3] = 2; /* an id bound below the ids used */
    CHECK(spirv_specialize(copy, words, v, TP2_SPEC_COUNT, &out_words) == NULL);
    free(copy);
}

int main(void)
{
    check_shader("float basic", tp2_trace_float_basic, sizeof tp2_trace_float_basic, false);
    check_shader("float", tp2_trace_float, sizeof tp2_trace_float, false);
    check_shader("float curved", tp2_trace_float_curved, sizeof tp2_trace_float_curved, true);
    check_shader("double basic", tp2_trace_double_basic, sizeof tp2_trace_double_basic, false);
    check_shader("double", tp2_trace_double, sizeof tp2_trace_double, false);
    check_shader("double curved", tp2_trace_double_curved, sizeof tp2_trace_double_curved,
                 true);
    check_random_constants();
    check_probe();
    refuses_malformed();
    return unit_report();
}
