/* test_spirv_fused.c: the rewrite with which VK_LAYER_TP2_fused
 * (tests/layers) makes shaders round as a device that fuses multiply-adds
 * (spirv_fused.h). On each of the six embedded trace shaders: operations
 * are rewritten, the result is a well-formed module that declares Float64
 * once and defines every id once (SSA), its id bound covers every id,
 * and a second pass finds nothing left to fuse; SPIRV-Tools' validator
 * accepts the two curved builds' results (the other builds' code is part
 * of theirs; 0.2 s a module; the validation layer, above the fused layer,
 * sees only tp2's own modules). Operations decorated NoContraction (GLSL
 * `precise`) are left alone: with every sum, difference and dot product
 * so decorated, or every product and dot product, nothing is fused.
 * Malformed modules are refused.
 * (That rewritten shaders render is checked under the layer by
 * effect_mixed_same_when_fused.) */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "spirv_fused.h"
#include "trace_double_basic_spv.h"
#include "trace_double_curved_spv.h"
#include "trace_double_spv.h"
#include "trace_float_basic_spv.h"
#include "trace_float_curved_spv.h"
#include "trace_float_spv.h"
#include "unit.h"
#include "spirv_test.h"

enum {
    HEADER = 5,
    OP_CAPABILITY = 17,
    FLOAT64 = 10,
    OP_DECORATE = 71,
    NO_CONTRACTION = 42,
};

/* A copy of the module with every result of the opcodes `ops` (0-ended)
 * decorated NoContraction, before its first OpDecorate; *words its
 * length. */
static uint32_t *decorated(const uint32_t *code, size_t n, const uint32_t *ops, size_t *words)
{
    uint32_t *out = malloc((n * 2) * sizeof *out);
    size_t o = HEADER, first = 0;
    memcpy(out, code, HEADER * sizeof *out);
    for (size_t at = HEADER; at < n; at += code[at] >> 16)
        if ((code[at] & 0xffffu) == OP_DECORATE && !first)
            first = at;
    for (size_t at = HEADER; at < n; at += code[at] >> 16) {
        if (at == first)
            for (size_t k = HEADER; k < n; k += code[k] >> 16)
                for (const uint32_t *op = ops; *op; op++)
                    if ((code[k] & 0xffffu) == *op) {
                        out[o++] = (3u << 16) | OP_DECORATE;
                        out[o++] = code[k + 2];
                        out[o++] = NO_CONTRACTION;
                    }
        memcpy(out + o, code + at, (code[at] >> 16) * sizeof *out);
        o += code[at] >> 16;
    }
    *words = o;
    return out;
}

/* Nothing of the module is fused once `ops`' results are NoContraction. */
static void check_precise_kept(const char *what, const uint32_t *code, size_t bytes,
                               const uint32_t *ops)
{
    size_t words, out_words, sites = 99;
    uint32_t *precise = decorated(code, bytes / 4, ops, &words);
    uint32_t *out = spirv_fused(precise, words, &out_words, &sites);
    expect(out && sites == 0, "%s NoContraction: %zu operations fused", what, sites);
    free(out);
    free(precise);
}

/* Opcodes that define a result id in word 2 (with a type in word 1), or
 * in word 1 (types, imports, labels): enough of the grammar to find
 * every definition in tp2's shaders. */
static int defined_id(const uint32_t *op)
{
    uint32_t code = op[0] & 0xffffu, count = op[0] >> 16;
    if (code == 11 || (code >= 19 && code <= 33) || code == 248 || code == 73)
        return count >= 2 ? (int)op[1] : -1; /* import, types, label, group */
    if (code == 12 || (code >= 41 && code <= 52) || code == 54 || code == 55 ||
        code == 57 || code == 59 || code == 60 || code == 61 || (code >= 65 && code <= 70) ||
        (code >= 77 && code <= 83) || (code >= 109 && code <= 205) || code == 227 ||
        (code >= 229 && code <= 242) || code == 245)
        return count >= 3 ? (int)op[2] : -1;
    return -1;
}

static void check_shader(const char *name, const uint32_t *code, size_t bytes, bool validate)
{
    size_t words = bytes / 4, out_words = 0, sites = 0;
    uint32_t *out = spirv_fused(code, words, &out_words, &sites);
    expect(out != NULL, "%s: rewritten", name);
    if (!out)
        return;
    expect(sites > 0, "%s: %zu operations fused", name, sites);
    expect(out_words > words, "%s: grew from %zu to %zu words", name, words, out_words);
    uint32_t bound = out[3];
    expect(bound > code[3], "%s: id bound %u > %u", name, bound, code[3]);
    unsigned char *seen = calloc(bound, 1);
    int float64 = 0, twice = 0, beyond = 0, broken = 0;
    for (size_t at = HEADER; at < out_words;) {
        uint32_t count = out[at] >> 16;
        if (count == 0 || count > out_words - at) {
            broken = 1;
            break;
        }
        if ((out[at] & 0xffffu) == OP_CAPABILITY && out[at + 1] == FLOAT64)
            float64++;
        int id = defined_id(&out[at]);
        if (id >= (int)bound)
            beyond++;
        else if (id >= 0 && seen[id]++)
            twice++;
        at += count;
    }
    free(seen);
    expect(!broken, "%s: every instruction's word count fits", name);
    expect(float64 == 1, "%s: Float64 declared once (%d)", name, float64);
    expect(twice == 0, "%s: %d ids defined twice", name, twice);
    expect(beyond == 0, "%s: %d ids past the bound", name, beyond);
    if (validate)
        expect(spirv_valid(name, out, out_words), "%s: valid SPIR-V", name);
    size_t again_words = 0, again = 99;
    uint32_t *second = spirv_fused(out, out_words, &again_words, &again);
    expect(second && again == 0, "%s: a second pass fuses %zu more", name, again);
    free(second);
    free(out);
}

int main(void)
{
    check_shader("float", tp2_trace_float, sizeof tp2_trace_float, false);
    check_shader("float curved", tp2_trace_float_curved, sizeof tp2_trace_float_curved, true);
    check_shader("double", tp2_trace_double, sizeof tp2_trace_double, false);
    check_shader("double curved", tp2_trace_double_curved, sizeof tp2_trace_double_curved,
                 true);
    check_shader("float basic", tp2_trace_float_basic, sizeof tp2_trace_float_basic, false);
    check_shader("double basic", tp2_trace_double_basic, sizeof tp2_trace_double_basic, false);
    check_precise_kept("sums and dot products", tp2_trace_float_curved,
                       sizeof tp2_trace_float_curved, (const uint32_t[]){129, 131, 148, 0});
    check_precise_kept("products and dot products", tp2_trace_float_curved,
                       sizeof tp2_trace_float_curved, (const uint32_t[]){133, 142, 148, 0});
    spirv_check_refused(spirv_fused, tp2_trace_float, sizeof tp2_trace_float);
    return unit_report();
}
