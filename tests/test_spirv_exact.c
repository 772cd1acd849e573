/* test_spirv_exact.c: the double build's geometry evaluated as written
 * (shaders/real.glsl, host/gpu/spirv_exact.h). On each of the six embedded
 * trace shaders, after spirv_exact: the module is valid SPIR-V (SPIRV-Tools'
 * validator), every 64-bit arithmetic result is decorated NoContraction
 * exactly once and no other result is, and a second pass adds nothing. On
 * the three double builds: something was decorated, and no 64-bit value
 * comes from an operation whose rounding a driver chooses (OpDot, or a
 * GLSL.std.450 instruction other than those that round exactly or once:
 * normalize, length, mix, fma, inversesqrt ... are written out in
 * real.glsl instead). Malformed modules, and one without a decoration to
 * put the new ones after, are refused. */
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <spirv/unified1/GLSL.std.450.h>
#include <spirv/unified1/spirv.h>

#include "spirv_exact.h"
#include "trace_double_basic_spv.h"
#include "trace_double_curved_spv.h"
#include "trace_double_spv.h"
#include "trace_float_basic_spv.h"
#include "trace_float_curved_spv.h"
#include "trace_float_spv.h"
#include "unit.h"
#include "spirv_test.h"

/* The arithmetic whose 64-bit results must be decorated: written out
 * here, not taken from spirv_exact.c, so that a pass that forgot one
 * fails. */
static bool arithmetic(uint32_t op)
{
    static const uint32_t ops[] = {
        SpvOpFNegate, SpvOpFAdd, SpvOpFSub, SpvOpFMul, SpvOpFDiv, SpvOpFRem, SpvOpFMod,
        SpvOpVectorTimesScalar, SpvOpMatrixTimesScalar, SpvOpVectorTimesMatrix,
        SpvOpMatrixTimesVector, SpvOpMatrixTimesMatrix, SpvOpOuterProduct, SpvOpDot};
    for (size_t i = 0; i < sizeof ops / sizeof ops[0]; i++)
        if (ops[i] == op)
            return true;
    return false;
}

/* GLSL.std.450 instructions a 64-bit value may come from: exact (abs,
 * floor, min, clamp, packing ...) or one correctly rounded step (sqrt). */
static bool exact_builtin(uint32_t inst)
{
    static const uint32_t ok[] = {
        GLSLstd450Round, GLSLstd450RoundEven, GLSLstd450Trunc, GLSLstd450FAbs,
        GLSLstd450FSign, GLSLstd450Floor, GLSLstd450Ceil, GLSLstd450Fract, GLSLstd450Sqrt,
        GLSLstd450FMin, GLSLstd450FMax, GLSLstd450FClamp, GLSLstd450Step,
        GLSLstd450PackDouble2x32, GLSLstd450UnpackDouble2x32, GLSLstd450NMin,
        GLSLstd450NMax, GLSLstd450NClamp};
    for (size_t i = 0; i < sizeof ok / sizeof ok[0]; i++)
        if (ok[i] == inst)
            return true;
    return false;
}

/* What check_module counts. */
struct census {
    size_t wide_arithmetic; /* 64-bit arithmetic results */
    size_t undecorated;     /* of those, not decorated NoContraction */
    size_t twice;           /* results decorated more than once */
    size_t narrow_marked;   /* decorated results that are not 64-bit arithmetic */
    size_t driver_rounded;  /* 64-bit OpDot or inexact GLSL.std.450 results */
};

static struct census check_module(const uint32_t *code, size_t words)
{
    struct census c = {0};
    uint32_t bound = code[3];
    bool *wide = calloc(bound, 1), *wide_result = calloc(bound, 1);
    unsigned *marks = calloc(bound, sizeof *marks);
    uint32_t glsl = 0;
    if (!wide || !wide_result || !marks) {
        c.undecorated = 1;
        goto done;
    }
    for (size_t at = SPIRV_TEST_HEADER; at < words; at += code[at] >> 16) {
        const uint32_t *w = &code[at];
        uint32_t op = w[0] & 0xffffu, n = w[0] >> 16;
        if (op == SpvOpExtInstImport && strcmp((const char *)&w[2], "GLSL.std.450") == 0)
            glsl = w[1];
        if (op == SpvOpDecorate && n == 3 && w[2] == SpvDecorationNoContraction)
            marks[w[1]]++;
        if (op == SpvOpTypeFloat && w[2] == 64)
            wide[w[1]] = true;
        if ((op == SpvOpTypeVector || op == SpvOpTypeMatrix) && wide[w[2]])
            wide[w[1]] = true;
        if (arithmetic(op) && wide[w[1]]) {
            wide_result[w[2]] = true;
            c.wide_arithmetic++;
        }
        if (op == SpvOpDot && wide[w[1]])
            c.driver_rounded++;
        if (op == SpvOpExtInst && n >= 5 && w[3] == glsl && wide[w[1]] && !exact_builtin(w[4]))
            c.driver_rounded++;
    }
    for (uint32_t id = 0; id < bound; id++) {
        c.undecorated += wide_result[id] && marks[id] == 0;
        c.twice += marks[id] > 1;
        c.narrow_marked += marks[id] > 0 && !wide_result[id];
    }
done:
    free(wide);
    free(wide_result);
    free(marks);
    return c;
}

static void check_shader(const char *name, const uint32_t *code, size_t bytes, bool is_double)
{
    size_t words = bytes / 4, out_words = 0, sites = 0;
    struct census before = check_module(code, words);
    uint32_t *out = spirv_exact(code, words, &out_words, &sites);
    expect(out != NULL, "%s: decorated", name);
    if (!out)
        return;
    expect(out_words == words + 3 * sites, "%s: %zu words for %zu decorations", name, out_words,
           sites);
    expect(spirv_valid(name, out, out_words), "%s: valid SPIR-V", name);
    struct census after = check_module(out, out_words);
    expect(sites == before.undecorated, "%s: %zu decorated, %zu were bare", name, sites,
           before.undecorated);
    expect(after.undecorated == 0, "%s: %zu 64-bit results left bare", name, after.undecorated);
    expect(after.twice == 0, "%s: %zu results decorated twice", name, after.twice);
    expect(after.narrow_marked == before.narrow_marked, "%s: %zu other results decorated",
           name, after.narrow_marked - before.narrow_marked);
    if (is_double) {
        expect(sites > 0, "%s: %zu results decorated", name, sites);
        expect(after.driver_rounded == 0, "%s: %zu 64-bit results rounded as a driver chooses",
               name, after.driver_rounded);
    }
    size_t again_words = 0, again = 99;
    uint32_t *second = spirv_exact(out, out_words, &again_words, &again);
    expect(second && again == 0 && again_words == out_words, "%s: a second pass adds %zu", name,
           again);
    free(second);
    free(out);
}

/* Every annotation turned into an OpNop of its own length: a module
 * with nowhere to put the decorations is refused. */
static void check_no_annotations(void)
{
    size_t words = sizeof tp2_trace_double / 4, n, sites;
    uint32_t *copy = malloc(sizeof tp2_trace_double);
    memcpy(copy, tp2_trace_double, sizeof tp2_trace_double);
    for (size_t at = SPIRV_TEST_HEADER; at < words; at += copy[at] >> 16) {
        uint32_t op = copy[at] & 0xffffu;
        if (op == SpvOpDecorate || op == SpvOpMemberDecorate)
            copy[at] = (copy[at] & 0xffff0000u) | SpvOpNop;
    }
    expect(spirv_exact(copy, words, &n, &sites) == NULL, "a module without annotations");
    free(copy);
}

int main(void)
{
    check_shader("double", tp2_trace_double, sizeof tp2_trace_double, true);
    check_shader("double curved", tp2_trace_double_curved, sizeof tp2_trace_double_curved,
                 true);
    check_shader("double basic", tp2_trace_double_basic, sizeof tp2_trace_double_basic, true);
    check_shader("float", tp2_trace_float, sizeof tp2_trace_float, false);
    check_shader("float curved", tp2_trace_float_curved, sizeof tp2_trace_float_curved, false);
    check_shader("float basic", tp2_trace_float_basic, sizeof tp2_trace_float_basic, false);
    spirv_check_refused(spirv_exact, tp2_trace_double, sizeof tp2_trace_double);
    check_no_annotations();
    return unit_report();
}
