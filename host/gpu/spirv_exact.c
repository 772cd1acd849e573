#include "spirv_exact.h"

#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "spirv_words.h"
#include <spirv/unified1/spirv.h>

/* Whether op makes a float result that a compiler could fuse or reorder
 * with another: the arithmetic SPIR-V lets NoContraction forbid that. */
static bool arithmetic(uint32_t op)
{
    switch (op) {
    case SpvOpFNegate:
    case SpvOpFAdd:
    case SpvOpFSub:
    case SpvOpFMul:
    case SpvOpFDiv:
    case SpvOpFRem:
    case SpvOpFMod:
    case SpvOpVectorTimesScalar:
    case SpvOpMatrixTimesScalar:
    case SpvOpVectorTimesMatrix:
    case SpvOpMatrixTimesVector:
    case SpvOpMatrixTimesMatrix:
    case SpvOpOuterProduct:
    case SpvOpDot:
        return true;
    default:
        return false;
    }
}

static bool annotation(uint32_t op)
{
    return op == SpvOpDecorate || op == SpvOpMemberDecorate || op == SpvOpDecorationGroup ||
           op == SpvOpGroupDecorate || op == SpvOpGroupMemberDecorate ||
           op == SpvOpDecorateId || op == SpvOpDecorateString ||
           op == SpvOpMemberDecorateString;
}

uint32_t *spirv_exact(const uint32_t *code, size_t words, size_t *out_words, size_t *sites)
{
    if (!spirv_well_formed(code, words))
        return NULL;
    uint32_t bound = code[3];
    bool *wide = calloc(bound, 1); /* a 64-bit float type: scalar, vector, matrix */
    bool *marked = calloc(bound, 1); /* decorated NoContraction, before or here */
    uint32_t *results = malloc((words / 3 + 1) * sizeof *results);
    uint32_t *out = NULL;
    if (!wide || !marked || !results)
        goto done;
    size_t count = 0, insert_at = 0;
    bool in_functions = false;
    for (size_t at = SPIRV_HEADER_WORDS; at < words; at += spirv_count(code, at)) {
        uint32_t n = spirv_count(code, at), op = spirv_op(code, at);
        const uint32_t *w = &code[at];
        in_functions = in_functions || op == SpvOpFunction;
        if (!in_functions && annotation(op))
            insert_at = at + n;
        if (op == SpvOpDecorate && n == 3 && w[1] < bound && w[2] == SpvDecorationNoContraction)
            marked[w[1]] = true;
        if (op == SpvOpTypeFloat && n == 3 && w[1] < bound && w[2] == 64)
            wide[w[1]] = true;
        if ((op == SpvOpTypeVector || op == SpvOpTypeMatrix) && n == 4 && w[1] < bound &&
            w[2] < bound && wide[w[2]])
            wide[w[1]] = true;
        if (arithmetic(op) && n >= 4 && w[1] < bound && w[2] < bound && wide[w[1]] &&
            !marked[w[2]]) {
            marked[w[2]] = true;
            results[count++] = w[2];
        }
    }
    if (!insert_at)
        goto done;
    out = malloc((words + 3 * count) * sizeof *out);
    if (!out)
        goto done;
    memcpy(out, code, insert_at * sizeof *out);
    uint32_t *o = out + insert_at;
    for (size_t i = 0; i < count; i++) {
        *o++ = (3u << 16) | SpvOpDecorate;
        *o++ = results[i];
        *o++ = SpvDecorationNoContraction;
    }
    memcpy(o, code + insert_at, (words - insert_at) * sizeof *out);
    *out_words = words + 3 * count;
    *sites = count;
done:
    free(wide);
    free(marked);
    free(results);
    return out;
}
