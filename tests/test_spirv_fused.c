/* test_spirv_fused.c: the rewrite with which VK_LAYER_TP2_fused
 * (tests/layers) makes shaders round as a device that fuses multiply-adds
 * (spirv_fused.h). On each of the six embedded trace shaders: operations
 * are rewritten, the result is a well-formed module that declares Float64
 * once and defines every id once (SSA), its id bound covers every id,
 * SPIRV-Tools' validator accepts it, and a second pass finds nothing left
 * to fuse. finish.comp, all of whose arithmetic on products is `precise`
 * (NoContraction), has none of that fused. Malformed modules are refused.
 * (That rewritten shaders render is checked under the layer and the
 * validation layer by effect_mixed_same_when_fused.) */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "finish_spv.h"
#include "spirv_fused.h"
#include "trace_double_basic_spv.h"
#include "trace_double_curved_spv.h"
#include "trace_double_spv.h"
#include "trace_float_basic_spv.h"
#include "trace_float_curved_spv.h"
#include "trace_float_spv.h"
#include "unit.h"
#include "spirv_test.h"

enum { HEADER = 5, OP_CAPABILITY = 17, FLOAT64 = 10 };

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

static void check_shader(const char *name, const uint32_t *code, size_t bytes)
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
    expect(spirv_valid(name, out, out_words), "%s: valid SPIR-V", name);
    size_t again_words = 0, again = 99;
    uint32_t *second = spirv_fused(out, out_words, &again_words, &again);
    expect(second && again == 0, "%s: a second pass fuses %zu more", name, again);
    free(second);
    free(out);
}

int main(void)
{
    check_shader("float", tp2_trace_float, sizeof tp2_trace_float);
    check_shader("float curved", tp2_trace_float_curved, sizeof tp2_trace_float_curved);
    check_shader("double", tp2_trace_double, sizeof tp2_trace_double);
    check_shader("double curved", tp2_trace_double_curved, sizeof tp2_trace_double_curved);
    check_shader("float basic", tp2_trace_float_basic, sizeof tp2_trace_float_basic);
    check_shader("double basic", tp2_trace_double_basic, sizeof tp2_trace_double_basic);
    size_t words, sites = 99;
    uint32_t *finish = spirv_fused(tp2_finish, sizeof tp2_finish / 4, &words, &sites);
    expect(finish && sites == 0, "finish.comp: %zu operations fused despite `precise`", sites);
    free(finish);
    spirv_check_refused(spirv_fused, tp2_trace_float, sizeof tp2_trace_float);
    return unit_report();
}
