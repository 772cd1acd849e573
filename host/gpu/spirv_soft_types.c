/* spirv_soft_types.c: spirv_soft_double's types and constants: each
 * holding a 64-bit float planned in its lowered form (a double a uvec2, a
 * dvecN an array of N), then the global section written with every
 * declaration after what it uses (the uvec2 may come later in the input
 * than the double it replaces). */
#include "spirv_soft.h"

#include <stdlib.h>
#include <string.h>

#include "spirv_words.h"
#define SPV_ENABLE_UTILITY_CODE
#include <spirv/unified1/spirv.h>

/* SpvHasResultAndType's external definition is spirv_specialize.c's. */

uint32_t soft_result_id(const uint32_t *code, size_t at)
{
    bool has_result = false, has_type = false;
    SpvHasResultAndType((SpvOp)spirv_op(code, at), &has_result, &has_type);
    uint32_t word = has_type ? 2 : 1;
    return has_result && spirv_count(code, at) > word ? code[at + word] : 0;
}

uint32_t soft_result_type(const uint32_t *code, size_t at)
{
    bool has_result = false, has_type = false;
    SpvHasResultAndType((SpvOp)spirv_op(code, at), &has_result, &has_type);
    return has_type && spirv_count(code, at) > 2 ? code[at + 1] : 0;
}


void words_put(struct words *b, uint32_t word)
{
    if (b->failed)
        return;
    if (b->n == b->cap) {
        size_t cap = b->cap ? 2 * b->cap : 1024;
        uint32_t *w = realloc(b->w, cap * sizeof *w);
        if (!w) {
            b->failed = true;
            return;
        }
        b->w = w;
        b->cap = cap;
    }
    b->w[b->n++] = word;
}

void words_inst(struct words *b, uint32_t op, const uint32_t *operands, uint32_t count)
{
    words_put(b, (count + 1) << 16 | op);
    for (uint32_t i = 0; i < count; i++)
        words_put(b, operands[i]);
}

/* Whether variables of storage class sc have explicitly laid out types. */
static bool explicit_storage(uint32_t sc)
{
    return sc == SpvStorageClassStorageBuffer || sc == SpvStorageClassUniform ||
           sc == SpvStorageClassPushConstant || sc == SpvStorageClassPhysicalStorageBuffer;
}

/* Declares (op, operands) in `decls`, its result being `id`. */
static void record(struct soft *s, uint32_t id, uint32_t op, const uint32_t *operands,
                   uint32_t count)
{
    if (id >= s->rec_cap) {
        uint32_t cap = id + 1024;
        size_t *rec = realloc(s->rec, cap * sizeof *rec);
        if (!rec) {
            s->failed = true;
            return;
        }
        memset(rec + s->rec_cap, 0, (cap - s->rec_cap) * sizeof *rec);
        s->rec = rec;
        s->rec_cap = cap;
    }
    uint32_t *recs = realloc(s->recs, (s->rec_count + 1) * sizeof *recs);
    if (!recs) {
        s->failed = true;
        return;
    }
    s->recs = recs;
    s->recs[s->rec_count++] = id;
    s->rec[id] = s->decls.n + 1;
    words_inst(&s->decls, op, operands, count);
}

/* Whether the instruction w declares (op, operands) as a type (result
 * first) or a constant (type, then result, then the rest). */
static bool same_decl(const uint32_t *w, uint32_t op, const uint32_t *operands, uint32_t count,
                      bool constant)
{
    if ((w[0] & 0xffffu) != op || (w[0] >> 16) != count + 2)
        return false;
    if (constant)
        return w[1] == operands[0] && memcmp(&w[3], &operands[1], (count - 1) * 4) == 0;
    return memcmp(&w[2], operands, count * 4) == 0;
}

/* An id declaring (op, operands), among the module's globals that stay
 * and the new ones; 0 when there is none. */
static uint32_t find(struct soft *s, uint32_t op, const uint32_t *operands, uint32_t count,
                     bool constant)
{
    for (size_t at = s->globals; at < s->functions; at += spirv_count(s->code, at)) {
        uint32_t id = soft_result_id(s->code, at);
        if (id && !s->wide[id] && !s->dropped[id] && !s->rec[id] &&
            same_decl(&s->code[at], op, operands, count, constant))
            return id;
    }
    for (size_t i = 0; i < s->rec_count; i++)
        if (same_decl(&s->decls.w[s->rec[s->recs[i]] - 1], op, operands, count, constant))
            return s->recs[i];
    return 0;
}

uint32_t soft_type(struct soft *s, uint32_t op, const uint32_t *operands, uint32_t count)
{
    uint32_t id = find(s, op, operands, count, false);
    if (id)
        return id;
    uint32_t words[8];
    if (count > 7) {
        s->failed = true;
        return 0;
    }
    words[0] = id = s->next++;
    memcpy(&words[1], operands, count * 4);
    record(s, id, op, words, count + 1);
    return id;
}

uint32_t soft_uint(struct soft *s, uint32_t value)
{
    uint32_t key[2] = {s->uint_type, value};
    uint32_t id = find(s, SpvOpConstant, key, 2, true);
    if (!id) {
        uint32_t words[3] = {s->uint_type, id = s->next++, value};
        record(s, id, SpvOpConstant, words, 3);
    }
    return id;
}

/* A new array of n uvec2, of ArrayStride 8 when `laid`. */
static uint32_t uvec2_array(struct soft *s, uint32_t n, bool laid)
{
    uint32_t words[3] = {s->next++, s->uvec2, soft_uint(s, n)};
    record(s, words[0], SpvOpTypeArray, words, 3);
    if (laid) {
        uint32_t *strided = realloc(s->strided, (s->strided_count + 1) * sizeof *strided);
        if (!strided) {
            s->failed = true;
            return words[0];
        }
        s->strided = strided;
        s->strided[s->strided_count++] = words[0];
    }
    return words[0];
}

static bool is_dvec(const struct soft *s, uint32_t t)
{
    const uint32_t *w = soft_def(s, t);
    return w && (w[0] & 0xffffu) == SpvOpTypeVector && s->wide[t];
}

uint32_t soft_lowered(struct soft *s, uint32_t t, bool laid)
{
    if (t >= s->bound || !s->wide[t])
        return t;
    if (laid && is_dvec(s, t)) {
        if (!s->low_laid[t])
            s->low_laid[t] = uvec2_array(s, soft_def(s, t)[3], true);
        return s->low_laid[t];
    }
    return s->low[t];
}

void soft_mark_wide(struct soft *s)
{
    const uint32_t *c = s->code;
    for (size_t at = s->globals; at < s->words; at += spirv_count(c, at)) {
        const uint32_t *w = &c[at];
        uint32_t op = spirv_op(c, at), n = spirv_count(c, at), id = soft_result_id(c, at);
        uint8_t *wide = s->wide;
        switch (op) {
        case SpvOpTypeFloat:
            wide[id] = w[2] == 64;
            if (wide[id])
                s->f64 = id;
            break;
        case SpvOpTypeVector:
        case SpvOpTypeArray:
        case SpvOpTypeRuntimeArray:
            wide[id] = w[2] < s->bound && wide[w[2]];
            break;
        case SpvOpTypeStruct:
        case SpvOpTypeFunction:
            for (uint32_t i = 2; i < n; i++)
                wide[id] |= w[i] < s->bound && wide[w[i]];
            break;
        case SpvOpTypePointer:
            wide[id] = w[3] < s->bound && wide[w[3]];
            break;
        case SpvOpTypeMatrix:
        case SpvOpTypeImage:
        case SpvOpTypeSampledImage:
            s->failed |= w[2] < s->bound && wide[w[2]];
            break;
        case SpvOpTypeForwardPointer:
            s->failed = true;
            break;
        default:
            if (id && soft_result_type(c, at))
                wide[id] = wide[soft_result_type(c, at)];
        }
    }
}

/* The lowered form of the wide type or global at `at`. Types other than
 * the double and its vectors keep their ids (a pointer or function type
 * that would repeat one already declared becomes that one); constants
 * get new ones, so that the library may keep the 64-bit scalar ones. */
static void lower_global(struct soft *s, size_t at)
{
    const uint32_t *w = &s->code[at];
    uint32_t op = w[0] & 0xffffu, n = w[0] >> 16, id = soft_result_id(s->code, at);
    uint32_t o[64];
    if (n > 64) {
        s->failed = true;
        return;
    }
    memcpy(o, &w[1], (n - 1) * 4);
    bool keepable = s->keep_f64;
    switch (op) {
    case SpvOpTypeFloat:
        s->low[id] = s->uvec2;
        break;
    case SpvOpTypeVector: /* the library's doubles are scalars */
        s->low[id] = uvec2_array(s, w[3], false);
        s->dropped[id] = 1;
        return;
    case SpvOpTypeArray:
    case SpvOpTypeRuntimeArray:
        o[1] = soft_lowered(s, w[2], s->laid_out[id] || op == SpvOpTypeRuntimeArray);
        record(s, s->low[id] = id, op, o, n - 1);
        return;
    case SpvOpTypeStruct:
        for (uint32_t i = 2; i < n; i++)
            o[i - 1] = soft_lowered(s, w[i], s->laid_out[id]);
        record(s, s->low[id] = id, op, o, n - 1);
        return;
    case SpvOpTypePointer:
    case SpvOpTypeFunction:
        if (op == SpvOpTypePointer)
            o[2] = soft_lowered(s, w[3], explicit_storage(w[2]));
        else
            for (uint32_t i = 2; i < n; i++)
                o[i - 1] = soft_lowered(s, w[i], false);
        s->low[id] = find(s, op, &o[1], n - 2, false);
        if (s->low[id]) {
            s->dropped[id] = 1;
            return;
        }
        record(s, s->low[id] = id, op, o, n - 1);
        return;
    case SpvOpConstant:
        if (n != 5) {
            s->failed = true;
            return;
        }
        o[0] = s->uvec2;
        o[1] = s->low[id] = s->next++;
        o[2] = soft_uint(s, w[3]); /* the low word first, as in packDouble2x32 */
        o[3] = soft_uint(s, w[4]);
        record(s, o[1], SpvOpConstantComposite, o, 4);
        break;
    case SpvOpConstantComposite:
    case SpvOpConstantNull:
        keepable = keepable && w[1] == s->f64;
        o[0] = soft_lowered(s, w[1], false);
        o[1] = s->low[id] = s->next++;
        for (uint32_t i = 3; i < n; i++)
            o[i - 1] = w[i] < s->bound && s->low[w[i]] ? s->low[w[i]] : w[i];
        record(s, o[1], op, o, n - 1);
        break;
    case SpvOpUndef:
    case SpvOpVariable:
        o[0] = soft_lowered(s, w[1], false);
        if (n > 4 && w[4] < s->bound && s->low[w[4]])
            o[3] = s->low[w[4]];
        record(s, id, op, o, n - 1);
        return;
    default: /* 64-bit specialization constants among them */
        s->failed = true;
        return;
    }
    s->dropped[id] = !keepable;
}

void soft_plan_types(struct soft *s)
{
    uint32_t int32[2] = {32, 0};
    s->uint_type = soft_type(s, SpvOpTypeInt, int32, 2);
    uint32_t pair[2] = {s->uint_type, 2};
    s->uvec2 = soft_type(s, SpvOpTypeVector, pair, 2);
    s->bool_type = soft_type(s, SpvOpTypeBool, pair, 0);
    for (size_t at = s->globals; at < s->functions && !s->failed; at += spirv_count(s->code, at)) {
        uint32_t id = soft_result_id(s->code, at);
        if (id && s->wide[id])
            lower_global(s, at);
    }
}

/* The ids an instruction of the global section uses (words[] indices
 * from, and where they stop); literals among them do no harm. */
static uint32_t first_use(uint32_t op)
{
    switch (op) {
    case SpvOpTypeVector:
    case SpvOpTypeMatrix:
    case SpvOpTypeArray:
    case SpvOpTypeRuntimeArray:
    case SpvOpTypeStruct:
    case SpvOpTypeFunction:
    case SpvOpTypeImage:
    case SpvOpTypeSampledImage:
        return 2;
    case SpvOpTypePointer:
        return 3;
    default:
        return 1;
    }
}

/* Writes the declaration of global `id` (new, lowered or original) to
 * out, after those it uses; nothing if it is none or written already. */
static void pull(struct soft *s, struct words *out, uint8_t *done, uint32_t id)
{
    if (id >= s->next || done[id])
        return;
    const uint32_t *w = NULL;
    if (id < s->rec_cap && s->rec[id])
        w = &s->decls.w[s->rec[id] - 1];
    else if (id < s->bound && s->def[id] >= s->globals && s->def[id] < s->functions &&
             !s->dropped[id])
        w = &s->code[s->def[id]];
    if (!w)
        return;
    done[id] = 1;
    uint32_t op = w[0] & 0xffffu, n = w[0] >> 16;
    for (uint32_t i = first_use(op); i < n; i++)
        if (w[i] != id)
            pull(s, out, done, w[i]);
    for (uint32_t i = 0; i < n; i++)
        words_put(out, w[i]);
}

void soft_emit_globals(struct soft *s, struct words *out)
{
    uint8_t *done = calloc(s->next, 1);
    if (!done) {
        s->failed = true;
        return;
    }
    for (size_t at = s->globals; at < s->functions; at += spirv_count(s->code, at)) {
        uint32_t id = soft_result_id(s->code, at);
        if (id)
            pull(s, out, done, id);
        else
            for (uint32_t i = 0; i < spirv_count(s->code, at); i++)
                words_put(out, s->code[at + i]);
    }
    for (size_t i = 0; i < s->rec_count; i++)
        pull(s, out, done, s->recs[i]);
    free(done);
}
