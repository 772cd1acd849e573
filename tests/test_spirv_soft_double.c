/* test_spirv_soft_double.c: the double build with its 64-bit floats done
 * by the software library (host/gpu/spirv_soft_double.h). On each of the
 * three embedded double builds, after the pass: the module is valid for
 * Vulkan 1.1 (SPIRV-Tools' validator); no 64-bit float is left outside
 * the library's sd_* functions, and where those use none either (the real
 * library, integers only) none at all and no Float64 capability; each
 * 64-bit arithmetic, comparison, conversion and builtin of the input is
 * one call per component to its library function, and the pass's count
 * of sites is those calls; after spirv_specialize (under two sets of
 * constants) it is still valid and sd_keep is gone. After spirv_exact
 * first, the same, and no NoContraction is left on a call. The float
 * builds have nothing to lower. Malformed modules, a missing library
 * function and a 64-bit operation without one (FMod) are refused. */
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <spirv/unified1/GLSL.std.450.h>
#define SPV_ENABLE_UTILITY_CODE
#include <spirv/unified1/spirv.h>

#include "spirv_exact.h"
#include "spirv_soft_double.h"
#include "spirv_specialize.h"
#include "kinds.h"
#include "tp2_shared.h"
#include "trace_double_basic_spv.h"
#include "trace_double_curved_spv.h"
#include "trace_double_spv.h"
#include "trace_float_basic_spv.h"
#include "unit.h"
#include "spirv_test.h"

/* The library's functions, as the pass must call them: written out here,
 * not taken from the pass. */
enum { ADD, SUB, MUL, DIV, NEG, ABS, SQRT, FLOOR, FRACT, MIN, MAX, LT, LE, GT, GE, EQ, UNE,
       FROM_FLOAT, TO_FLOAT, FROM_INT, TO_INT, FUNCTIONS };
static const char *const names[FUNCTIONS] = {
    "sd_add(", "sd_sub(", "sd_mul(", "sd_div(", "sd_neg(", "sd_abs(", "sd_sqrt(",
    "sd_floor(", "sd_fract(", "sd_min(", "sd_max(", "sd_lt(", "sd_le(", "sd_gt(",
    "sd_ge(", "sd_eq(", "sd_une(", "sd_from_float(", "sd_to_float(", "sd_from_int(",
    "sd_to_int("};

/* The library function an instruction of the input must become, or -1. */
static int function_of(uint32_t op, uint32_t glsl_inst, bool wide_result)
{
    switch (op) {
    case SpvOpFAdd: return ADD;
    case SpvOpFSub: return SUB;
    case SpvOpFMul: case SpvOpVectorTimesScalar: return MUL;
    case SpvOpFDiv: return DIV;
    case SpvOpFNegate: return NEG;
    case SpvOpFOrdLessThan: return LT;
    case SpvOpFOrdLessThanEqual: return LE;
    case SpvOpFOrdGreaterThan: return GT;
    case SpvOpFOrdGreaterThanEqual: return GE;
    case SpvOpFOrdEqual: return EQ;
    case SpvOpFUnordNotEqual: return UNE;
    case SpvOpFConvert: return wide_result ? FROM_FLOAT : TO_FLOAT;
    case SpvOpConvertSToF: return FROM_INT;
    case SpvOpConvertFToS: return TO_INT;
    case SpvOpExtInst:
        switch (glsl_inst) {
        case GLSLstd450FAbs: return ABS;
        case GLSLstd450Sqrt: return SQRT;
        case GLSLstd450Floor: return FLOOR;
        case GLSLstd450Fract: return FRACT;
        case GLSLstd450FMin: return MIN;
        case GLSLstd450FMax: return MAX;
        default: return -1;
        }
    default: return -1;
    }
}

struct census {
    size_t lowered[FUNCTIONS]; /* input: component operations; output: calls */
    size_t calls;              /* output: all calls to the library outside it */
    size_t wide_outside;       /* instructions outside sd_* with a 64-bit type or operand */
    size_t wide_inside;        /* instructions inside sd_* with a 64-bit result type */
    bool float64;              /* the Float64 capability */
    bool float64_type;         /* an OpTypeFloat 64 */
    bool keep;                 /* sd_keep is there */
    size_t marked_calls;       /* calls decorated NoContraction */
};

static struct census count(const uint32_t *code, size_t words)
{
    struct census c = {0};
    uint32_t bound = code[3], glsl = 0;
    bool *wide = calloc(bound, 1), *library = calloc(bound, 1), *marked = calloc(bound, 1);
    int *function = malloc(bound * sizeof *function);
    uint32_t *type_of = calloc(bound, sizeof *type_of), *components = calloc(bound, 4);
    if (!wide || !library || !marked || !function || !type_of || !components) {
        c.wide_outside = 1;
        goto done;
    }
    for (uint32_t id = 0; id < bound; id++)
        function[id] = -1;
    bool in_library = false, in_function = false;
    uint32_t f64 = 0;
    for (size_t at = SPIRV_TEST_HEADER; at < words; at += code[at] >> 16) {
        const uint32_t *w = &code[at];
        uint32_t op = w[0] & 0xffffu, n = w[0] >> 16;
        bool result = false, type = false;
        SpvHasResultAndType((SpvOp)op, &result, &type);
        if (type && result && n > 2)
            type_of[w[2]] = w[1];
        if (op == SpvOpCapability && w[1] == SpvCapabilityFloat64)
            c.float64 = true;
        if (op == SpvOpExtInstImport && strcmp((const char *)&w[2], "GLSL.std.450") == 0)
            glsl = w[1];
        if (op == SpvOpName && strncmp((const char *)&w[2], "sd_", 3) == 0) {
            library[w[1]] = true;
            c.keep |= strcmp((const char *)&w[2], "sd_keep(") == 0;
            for (int i = 0; i < FUNCTIONS; i++)
                if (strncmp((const char *)&w[2], names[i], strlen(names[i])) == 0)
                    function[w[1]] = i;
        }
        if (op == SpvOpDecorate && w[2] == SpvDecorationNoContraction)
            marked[w[1]] = true;
        if (op == SpvOpTypeFloat && w[2] == 64) {
            wide[w[1]] = c.float64_type = true;
            f64 = w[1];
        }
        if (op == SpvOpTypeVector || op == SpvOpTypeMatrix || op == SpvOpTypeArray ||
            op == SpvOpTypeRuntimeArray) {
            wide[w[1]] = wide[w[2]];
            components[w[1]] = op == SpvOpTypeVector ? w[3] : 1;
        }
        if (op == SpvOpTypeStruct || op == SpvOpTypeFunction)
            for (uint32_t i = 2; i < n; i++)
                wide[w[1]] |= wide[w[i]];
        if (op == SpvOpTypePointer)
            wide[w[1]] = wide[w[3]];
        if (op == SpvOpFunction) {
            in_library = library[w[2]];
            in_function = true;
        }
        if (in_library) {
            c.wide_inside += type && wide[w[1]];
            continue;
        }
        /* Outside functions, 64-bit scalars and their constants may stay
         * for the library; nothing made of them. Inside, nothing. */
        if (!in_function) {
            bool scalar = op == SpvOpTypeFloat || (type && w[1] == f64 && op != SpvOpVariable);
            c.wide_outside += result && wide[w[type ? 2 : 1]] && !scalar;
            continue;
        }
        bool touches = type && wide[w[1]];
        for (uint32_t i = 1 + type + result; i < n && !touches; i++)
            touches = w[i] < bound && type_of[w[i]] && wide[type_of[w[i]]];
        c.wide_outside += touches && op != SpvOpFunction;
        if (op == SpvOpFunctionCall && function[w[3]] >= 0) {
            c.lowered[function[w[3]]]++;
            c.calls++;
            c.marked_calls += marked[w[2]];
        }
        uint32_t first = op == SpvOpExtInst ? 5 : 3; /* the first operand */
        bool wide_operand = n > first && w[first] < bound && wide[type_of[w[first]]];
        int f = function_of(op, op == SpvOpExtInst && w[3] == glsl ? w[4] : 0, type && wide[w[1]]);
        if (f >= 0 && (wide[w[1]] || wide_operand))
            c.lowered[f] += components[w[1]] ? components[w[1]] : 1;
    }
done:
    free(wide);
    free(library);
    free(marked);
    free(function);
    free(type_of);
    free(components);
    return c;
}

/* Constants of a sphere-and-plane scene and of everything at once. */
static void constants(int32_t v[TP2_SPEC_COUNT], bool everything)
{
    memset(v, 0, TP2_SPEC_COUNT * sizeof *v);
    v[TP2_SPEC_PIGMENTS] = everything ? -1 : 1 << TP2_PIGMENT_SOLID;
    v[TP2_SPEC_SHAPES] = everything ? -1 : 1 << TP2_SHAPE_SPHERE | 1 << TP2_SHAPE_PLANE;
    v[TP2_SPEC_BOUNDED_SHAPE] = everything ? -1 : TP2_SHAPE_SPHERE;
    v[TP2_SPEC_UNBOUNDED_SHAPE] = everything ? -1 : TP2_SHAPE_PLANE;
    v[TP2_SPEC_SAMPLES] = everything ? 4 : 1;
    v[TP2_SPEC_SLABS] = 1;
    v[TP2_SPEC_REFLECT] = v[TP2_SPEC_REFRACT] = v[TP2_SPEC_FOG] = v[TP2_SPEC_LENS] =
        v[TP2_SPEC_AREA] = v[TP2_SPEC_BVH] = everything;
}

static void check_lowered(const char *name, const uint32_t *code, size_t words)
{
    size_t out_words = 0, sites = 0;
    uint32_t *out = spirv_soft_double(code, words, &out_words, &sites);
    expect(out != NULL, "%s: lowered", name);
    if (!out)
        return;
    expect(spirv_valid(name, out, out_words), "%s: valid SPIR-V", name);
    struct census after = count(out, out_words);
    printf("%s: %zu words in, %zu out, %zu calls\n", name, words, out_words, sites);
    expect(after.wide_outside == 0, "%s: %zu instructions outside sd_* still 64-bit", name,
           after.wide_outside);
    bool library_wide = after.wide_inside > 0;
    expect(library_wide || (!after.float64 && !after.float64_type),
           "%s: 64-bit floats declared though nothing uses them", name);
    expect(!library_wide || after.float64, "%s: the library's 64-bit floats without Float64",
           name);
    expect(sites == after.calls, "%s: %zu sites, %zu calls", name, sites, after.calls);
    expect(after.marked_calls == 0, "%s: %zu calls decorated NoContraction", name,
           after.marked_calls);
    for (int everything = 0; everything < 2; everything++) {
        int32_t v[TP2_SPEC_COUNT];
        constants(v, everything);
        size_t spec_words = 0;
        uint32_t *spec = spirv_specialize(out, out_words, v, TP2_SPEC_COUNT, &spec_words);
        expect(spec != NULL, "%s: specialized", name);
        if (!spec)
            continue;
        expect(spirv_valid(name, spec, spec_words), "%s: valid after spirv_specialize", name);
        expect(!count(spec, spec_words).keep, "%s: sd_keep left after spirv_specialize", name);
        free(spec);
    }
    free(out);
}

/* That each input operation is exactly one call per component (the
 * calls in sd_keep, the library's, are not counted). */
static void check_calls(const char *name, const uint32_t *code, size_t words)
{
    size_t out_words = 0, sites = 0;
    struct census in = count(code, words);
    uint32_t *out = spirv_soft_double(code, words, &out_words, &sites);
    if (!out)
        return;
    struct census after = count(out, out_words);
    for (int i = 0; i < FUNCTIONS; i++)
        expect(after.lowered[i] == in.lowered[i], "%s: %zu %s operations, %zu calls", name,
               in.lowered[i], names[i], after.lowered[i]);
    free(out);
}

/* spirv_exact first, as where a device has both passes run. */
static void check_after_exact(const char *name, const uint32_t *code, size_t words)
{
    size_t exact_words = 0, sites = 0;
    uint32_t *exact = spirv_exact(code, words, &exact_words, &sites);
    if (!exact) {
        expect(false, "%s: exact", name);
        return;
    }
    check_lowered(name, exact, exact_words);
    free(exact);
}

/* A copy of the module with one change: what `edit` does to it. */
static void check_refused_edit(const char *what, const uint32_t *code, size_t bytes,
                               bool (*edit)(uint32_t *code, size_t words))
{
    size_t words = bytes / 4, n, sites;
    uint32_t *copy = malloc(bytes);
    memcpy(copy, code, bytes);
    expect(edit(copy, words) && spirv_soft_double(copy, words, &n, &sites) == NULL, "%s",
           what);
    free(copy);
}

static bool rename_add(uint32_t *code, size_t words)
{
    for (size_t at = SPIRV_TEST_HEADER; at < words; at += code[at] >> 16)
        if ((code[at] & 0xffffu) == SpvOpName &&
            strncmp((const char *)&code[at + 2], "sd_add(", 7) == 0) {
            ((char *)&code[at + 2])[0] = 'x';
            return true;
        }
    return false;
}

/* The first 64-bit sum made a 64-bit modulo, which the library lacks. */
static bool sum_to_mod(uint32_t *code, size_t words)
{
    uint32_t f64 = 0;
    for (size_t at = SPIRV_TEST_HEADER; at < words; at += code[at] >> 16) {
        uint32_t op = code[at] & 0xffffu;
        if (op == SpvOpTypeFloat && code[at + 2] == 64)
            f64 = code[at + 1];
        if (op == SpvOpFAdd && code[at + 1] == f64) {
            code[at] = (code[at] & 0xffff0000u) | SpvOpFMod;
            return true;
        }
    }
    return false;
}

int main(void)
{
    static const struct {
        const char *name;
        const uint32_t *code;
        size_t bytes;
    } builds[] = {
        {"double basic", tp2_trace_double_basic, sizeof tp2_trace_double_basic},
        {"double", tp2_trace_double, sizeof tp2_trace_double},
        {"double curved", tp2_trace_double_curved, sizeof tp2_trace_double_curved},
    };
    for (size_t k = 0; k < 3; k++) {
        check_lowered(builds[k].name, builds[k].code, builds[k].bytes / 4);
        check_calls(builds[k].name, builds[k].code, builds[k].bytes / 4);
        check_after_exact(builds[k].name, builds[k].code, builds[k].bytes / 4);
    }
    size_t n = 0, sites = 99;
    uint32_t *same = spirv_soft_double(tp2_trace_float_basic, sizeof tp2_trace_float_basic / 4,
                                       &n, &sites);
    expect(same && sites == 0 && spirv_valid("float basic", same, n),
           "a float build: nothing to lower");
    free(same);
    spirv_check_refused(spirv_soft_double, tp2_trace_double, sizeof tp2_trace_double);
    check_refused_edit("a library function missing", tp2_trace_double, sizeof tp2_trace_double,
                       rename_add);
    check_refused_edit("a 64-bit modulo", tp2_trace_double, sizeof tp2_trace_double, sum_to_mod);
    return unit_report();
}
