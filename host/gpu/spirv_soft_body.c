/* spirv_soft_body.c: spirv_soft_double's functions rewritten onto the
 * library: each instruction that makes or reads a 64-bit float, in every
 * function but the library's own, becomes its lowered form. */
#include "spirv_soft.h"

#include <stdlib.h>
#include <string.h>

#include "spirv_words.h"
#include <spirv/unified1/GLSL.std.450.h>
#define SPV_ENABLE_UTILITY_CODE
#include <spirv/unified1/spirv.h>

/* The function being rewritten: its words up to its first block's
 * label, the rest, and the Function-storage temporaries its library
 * calls pass their arguments through (glslang's functions take
 * pointers), declared at the start of that block when it ends. */
struct fn {
    struct words head, body;
    struct {
        uint32_t type, slot, id;
    } temps[8];
    int temp_count;
    bool labelled;
};

enum { MAX_PARTS = 16 };

static void emit(struct soft *s, struct fn *f, uint32_t op, const uint32_t *operands,
                 uint32_t count)
{
    words_inst(&f->body, op, operands, count);
    s->failed |= f->body.failed;
}

static bool wide_value(const struct soft *s, uint32_t id)
{
    return id < s->bound && s->type_of[id] && s->wide[s->type_of[id]];
}

/* What a value is called after lowering (a constant's new id). */
static uint32_t val(const struct soft *s, uint32_t id)
{
    return id < s->bound && s->type_of[id] && s->low[id] ? s->low[id] : id;
}

static uint32_t op_of(const struct soft *s, uint32_t t)
{
    const uint32_t *w = soft_def(s, t);
    return w ? w[0] & 0xffffu : 0;
}

/* A vector type's components (1 for anything else), and their type. */
static uint32_t components(const struct soft *s, uint32_t t)
{
    return op_of(s, t) == SpvOpTypeVector ? soft_def(s, t)[3] : 1;
}

static uint32_t component_type(const struct soft *s, uint32_t t)
{
    return op_of(s, t) == SpvOpTypeVector ? soft_def(s, t)[2] : t;
}

static bool is_dvec(const struct soft *s, uint32_t t)
{
    return op_of(s, t) == SpvOpTypeVector && s->wide[t];
}

static uint32_t temp(struct soft *s, struct fn *f, uint32_t type, uint32_t slot)
{
    for (int i = 0; i < f->temp_count; i++)
        if (f->temps[i].type == type && f->temps[i].slot == slot)
            return f->temps[i].id;
    if (f->temp_count == 8) {
        s->failed = true;
        return 0;
    }
    f->temps[f->temp_count].type = type;
    f->temps[f->temp_count].slot = slot;
    return f->temps[f->temp_count++].id = s->next++;
}

/* `result` = library function `which` of args. */
static void call(struct soft *s, struct fn *f, enum sd_fn which, const uint32_t *args,
                 uint32_t result)
{
    const struct sd_lib *l = &s->lib[which];
    if (!l->id) {
        s->failed = true;
        return;
    }
    uint32_t o[5] = {l->ret, result, l->id};
    for (uint32_t i = 0; i < l->params; i++) {
        uint32_t store[2] = {temp(s, f, l->param[i], i), args[i]};
        emit(s, f, SpvOpStore, store, 2);
        o[3 + i] = store[0];
    }
    emit(s, f, SpvOpFunctionCall, o, 3 + l->params);
    s->sites++;
}

/* Component k of (lowered) value v of original type t: v itself when t
 * is no vector. */
static uint32_t part(struct soft *s, struct fn *f, uint32_t v, uint32_t t, uint32_t k)
{
    if (op_of(s, t) != SpvOpTypeVector)
        return v;
    uint32_t o[4] = {soft_lowered(s, component_type(s, t), false), s->next++, v, k};
    emit(s, f, SpvOpCompositeExtract, o, 4);
    return o[1];
}

/* result, of lowered type `type`, made of n parts. */
static void whole(struct soft *s, struct fn *f, uint32_t type, uint32_t result,
                  const uint32_t *parts, uint32_t n)
{
    uint32_t o[2 + MAX_PARTS] = {type, result};
    memcpy(&o[2], parts, n * 4);
    emit(s, f, SpvOpCompositeConstruct, o, 2 + n);
}

/* result = v (of dvecN type t, lowered) as an array of type `to`: the
 * same values, in or out of an explicit layout. */
static void relaid(struct soft *s, struct fn *f, uint32_t v, uint32_t t, uint32_t to,
                   uint32_t result)
{
    uint32_t n = components(s, t), parts[MAX_PARTS];
    if (n > MAX_PARTS) {
        s->failed = true;
        return;
    }
    for (uint32_t k = 0; k < n; k++) {
        uint32_t o[4] = {s->uvec2, parts[k] = s->next++, v, k};
        emit(s, f, SpvOpCompositeExtract, o, 4);
    }
    whole(s, f, to, result, parts, n);
}

/* Lowered value v of original type t as type `want`. */
static uint32_t value_as(struct soft *s, struct fn *f, uint32_t v, uint32_t t, uint32_t want)
{
    if (soft_lowered(s, t, false) == want)
        return v;
    if (!is_dvec(s, t) || want != soft_lowered(s, t, true)) {
        s->failed = true;
        return v;
    }
    uint32_t r = s->next++;
    relaid(s, f, v, t, want, r);
    return r;
}

/* The type a pointer of original type p points to, lowered as its
 * storage lays it out (as the pointer's lowered type says). */
static uint32_t pointee(struct soft *s, uint32_t p)
{
    uint32_t low = soft_lowered(s, p, false);
    if (low < s->rec_cap && s->rec[low])
        return s->decls.w[s->rec[low] - 1 + 3];
    const uint32_t *w = soft_def(s, low);
    return w ? w[3] : 0;
}

/* Walks original type t along indices: the member's type, and whether
 * it lies in an explicit layout. */
static uint32_t member(struct soft *s, uint32_t t, const uint32_t *index, uint32_t n, bool *laid)
{
    *laid = false;
    for (uint32_t i = 0; i < n && t; i++) {
        const uint32_t *w = soft_def(s, t);
        uint32_t op = op_of(s, t);
        *laid = s->laid_out[t] || op == SpvOpTypeRuntimeArray;
        if (op == SpvOpTypeStruct && index[i] + 2 < (w[0] >> 16))
            t = w[2 + index[i]];
        else if (op == SpvOpTypeArray || op == SpvOpTypeRuntimeArray || op == SpvOpTypeVector)
            t = w[2];
        else
            t = 0;
    }
    s->failed |= !t;
    return t;
}

/* result = which(operands) of original type `type`, component by
 * component (a scalar operand goes with each). */
static void per_component(struct soft *s, struct fn *f, enum sd_fn which, uint32_t type,
                          uint32_t result, const uint32_t *operands, uint32_t count)
{
    uint32_t n = components(s, type), parts[MAX_PARTS];
    if (n > MAX_PARTS) {
        s->failed = true;
        return;
    }
    for (uint32_t k = 0; k < n; k++) {
        uint32_t args[2];
        for (uint32_t i = 0; i < count; i++) {
            uint32_t v = val(s, operands[i]);
            args[i] = n == 1 ? v : part(s, f, v, s->type_of[operands[i]], k);
        }
        call(s, f, which, args, parts[k] = n == 1 ? result : s->next++);
    }
    if (n > 1)
        whole(s, f, soft_lowered(s, type, false), result, parts, n);
    s->replaced[result] = 1;
}

/* The library function of an arithmetic or comparison opcode, else -1. */
static int arithmetic(uint32_t op)
{
    switch (op) {
    case SpvOpFAdd: return SD_ADD;
    case SpvOpFSub: return SD_SUB;
    case SpvOpFMul:
    case SpvOpVectorTimesScalar: return SD_MUL;
    case SpvOpFDiv: return SD_DIV;
    case SpvOpFNegate: return SD_NEG;
    case SpvOpFOrdLessThan: return SD_LT;
    case SpvOpFOrdLessThanEqual: return SD_LE;
    case SpvOpFOrdGreaterThan: return SD_GT;
    case SpvOpFOrdGreaterThanEqual: return SD_GE;
    case SpvOpFOrdEqual: return SD_EQ;
    case SpvOpFUnordNotEqual: return SD_UNE;
    default: return -1;
    }
}

static int builtin(uint32_t inst)
{
    switch (inst) {
    case GLSLstd450FAbs: return SD_ABS;
    case GLSLstd450Sqrt: return SD_SQRT;
    case GLSLstd450Floor: return SD_FLOOR;
    case GLSLstd450Fract: return SD_FRACT;
    case GLSLstd450FMin: return SD_MIN;
    case GLSLstd450FMax: return SD_MAX;
    default: return -1;
    }
}

static bool float_of(const struct soft *s, uint32_t t, uint32_t width)
{
    const uint32_t *w = soft_def(s, component_type(s, t));
    return w && (w[0] & 0xffffu) == SpvOpTypeFloat && w[2] == width;
}

/* A conversion to or from double, component by component. */
static void convert(struct soft *s, struct fn *f, const uint32_t *w)
{
    uint32_t op = w[0] & 0xffffu, from = s->type_of[w[3]];
    int which = -1;
    if (op == SpvOpFConvert && float_of(s, w[1], 64) && float_of(s, from, 32))
        which = SD_FROM_FLOAT;
    else if (op == SpvOpFConvert && float_of(s, w[1], 32) && float_of(s, from, 64))
        which = SD_TO_FLOAT;
    else if (op == SpvOpConvertSToF && float_of(s, w[1], 64))
        which = SD_FROM_INT;
    else if (op == SpvOpConvertFToS && float_of(s, from, 64))
        which = SD_TO_INT;
    if (which < 0) {
        s->failed = true;
        return;
    }
    per_component(s, f, (enum sd_fn)which, w[1], w[2], &w[3], 1);
}

/* OpSelect: before SPIR-V 1.4 a uvec2 needs a bvec2 condition and an
 * array cannot be selected, so each component is its own select. */
static void select_wide(struct soft *s, struct fn *f, const uint32_t *w)
{
    uint32_t n = components(s, w[1]), parts[MAX_PARTS];
    if ((w[0] >> 16) != 6 || (w[1] != s->f64 && !is_dvec(s, w[1])) || n > MAX_PARTS) {
        s->failed = true;
        return;
    }
    uint32_t bool_pair[2] = {s->bool_type, 2};
    uint32_t bvec2 = soft_type(s, SpvOpTypeVector, bool_pair, 2), cond_type = s->type_of[w[3]];
    for (uint32_t k = 0; k < n; k++) {
        uint32_t c = part(s, f, w[3], cond_type, k);
        uint32_t pair[4] = {bvec2, s->next++, c, c};
        emit(s, f, SpvOpCompositeConstruct, pair, 4);
        uint32_t o[5] = {s->uvec2, parts[k] = n == 1 ? w[2] : s->next++, pair[1],
                         part(s, f, val(s, w[4]), w[1], k), part(s, f, val(s, w[5]), w[1], k)};
        emit(s, f, SpvOpSelect, o, 5);
    }
    if (n > 1)
        whole(s, f, soft_lowered(s, w[1], false), w[2], parts, n);
}

/* OpVectorShuffle of dvecs: the components picked out and put together. */
static void shuffle(struct soft *s, struct fn *f, const uint32_t *w, uint32_t n)
{
    if (n < 5 || n - 5 > MAX_PARTS) {
        s->failed = true;
        return;
    }
    uint32_t first = components(s, s->type_of[w[3]]), parts[MAX_PARTS];
    for (uint32_t k = 0; k + 5 < n; k++) {
        uint32_t c = w[5 + k] == 0xffffffffu ? 0 : w[5 + k]; /* undefined: any */
        uint32_t from = c < first ? w[3] : w[4];
        parts[k] = part(s, f, val(s, from), s->type_of[from], c < first ? c : c - first);
    }
    whole(s, f, soft_lowered(s, w[1], false), w[2], parts, n - 5);
}

/* OpCompositeConstruct of a wide type: a dvec's parts flattened (a
 * vector's may be vectors), a struct's or array's members laid out as
 * their places are. */
static void construct(struct soft *s, struct fn *f, const uint32_t *w, uint32_t n)
{
    uint32_t o[2 + MAX_PARTS] = {soft_lowered(s, w[1], false), w[2]}, count = 0;
    if (n - 3 > MAX_PARTS) {
        s->failed = true;
        return;
    }
    for (uint32_t i = 3; i < n; i++) {
        uint32_t v = val(s, w[i]), t = s->type_of[w[i]];
        if (is_dvec(s, w[1])) {
            for (uint32_t k = 0; k < components(s, t) && count < MAX_PARTS; k++)
                o[2 + count++] = part(s, f, v, t, k);
        } else {
            bool laid = false;
            uint32_t index = i - 3, m = member(s, w[1], &index, 1, &laid);
            o[2 + count++] = value_as(s, f, v, t, soft_lowered(s, m, laid));
        }
    }
    emit(s, f, SpvOpCompositeConstruct, o, 2 + count);
}

/* OpLoad or OpCompositeExtract: made in the type its place lays out,
 * then brought to the value's. */
static void read_member(struct soft *s, struct fn *f, const uint32_t *w, uint32_t n,
                        uint32_t laid_type)
{
    uint32_t o[64], value_type = soft_lowered(s, w[1], false);
    memcpy(o, &w[1], (n - 1) * 4);
    o[2] = val(s, w[3]);
    o[0] = laid_type;
    if (laid_type != value_type)
        o[1] = s->next++;
    emit(s, f, w[0] & 0xffffu, o, n - 1);
    if (laid_type != value_type)
        relaid(s, f, o[1], w[1], value_type, w[2]);
}

/* Whether w (n words, operands from `from`) makes or reads a 64-bit
 * float: its result type, or an operand that is an id (the literals of
 * those that have some are skipped: they could be any id's number). */
static bool touches_wide(const struct soft *s, const uint32_t *w, uint32_t n, uint32_t from)
{
    if (from == 3 && s->wide[w[1]])
        return true;
    switch (w[0] & 0xffffu) {
    case SpvOpExtInst:
        from = 5;
        break;
    case SpvOpLoad:
    case SpvOpCompositeExtract:
        n = n < 4 ? n : 4;
        break;
    case SpvOpStore:
    case SpvOpCompositeInsert:
    case SpvOpVectorShuffle:
        n = n < from + 2 ? n : from + 2;
        break;
    default:
        break;
    }
    for (uint32_t i = from; i < n; i++)
        if (wide_value(s, w[i]))
            return true;
    return false;
}

/* Where an instruction's operands start (after its result). */
static uint32_t operands_at(uint32_t op)
{
    bool result = false, type = false;
    SpvHasResultAndType((SpvOp)op, &result, &type);
    return 1 + result + type;
}

static void lower_ext(struct soft *s, struct fn *f, const uint32_t *w, uint32_t n)
{
    int which = w[3] == s->glsl ? builtin(w[4]) : -1;
    if (w[3] == s->glsl && (w[4] == GLSLstd450PackDouble2x32 ||
                            w[4] == GLSLstd450UnpackDouble2x32) && n == 6) {
        uint32_t o[3] = {soft_lowered(s, w[1], false), w[2], val(s, w[5])};
        emit(s, f, SpvOpCopyObject, o, 3);
        s->replaced[w[2]] = 1;
    } else if (which >= 0 && n - 5 == s->lib[which].params) {
        per_component(s, f, (enum sd_fn)which, w[1], w[2], &w[5], n - 5);
    } else {
        s->failed = true;
    }
}

/* The instruction w (n words) of a function other than the library's. */
static void lower(struct soft *s, struct fn *f, const uint32_t *w, uint32_t n)
{
    uint32_t op = w[0] & 0xffffu, from = operands_at(op), o[64];
    if (n > 64 || n < from || !touches_wide(s, w, n, from)) {
        s->failed |= n > 64 || n < from;
        emit(s, f, op, &w[1], n - 1);
        return;
    }
    memcpy(o, &w[1], (n - 1) * 4);
    bool laid = false;
    int which = arithmetic(op);
    if (which >= 0 && n - 3 == s->lib[which].params) {
        per_component(s, f, (enum sd_fn)which, w[1], w[2], &w[3], n - 3);
        return;
    }
    switch (op) {
    case SpvOpLoad:
        read_member(s, f, w, n, pointee(s, s->type_of[w[3]]));
        return;
    case SpvOpCompositeExtract: {
        uint32_t m = member(s, s->type_of[w[3]], &w[4], n - 4, &laid);
        read_member(s, f, w, n, soft_lowered(s, m, laid));
        return;
    }
    case SpvOpStore:
        o[1] = value_as(s, f, val(s, w[2]), s->type_of[w[2]], pointee(s, s->type_of[w[1]]));
        break;
    case SpvOpCompositeInsert: {
        uint32_t m = member(s, w[1], &w[5], n - 5, &laid);
        o[2] = value_as(s, f, val(s, w[3]), s->type_of[w[3]], soft_lowered(s, m, laid));
        o[3] = val(s, w[4]);
        o[0] = soft_lowered(s, w[1], false);
        break;
    }
    case SpvOpVariable:
    case SpvOpAccessChain:
    case SpvOpInBoundsAccessChain:
    case SpvOpCopyObject:
    case SpvOpPhi:
    case SpvOpUndef:
    case SpvOpFunctionCall:
    case SpvOpReturnValue:
        /* Values keep their ids; types and constants change. */
        for (uint32_t i = from; i < n; i++)
            o[i - 1] = val(s, w[i]);
        if (from == 3)
            o[0] = soft_lowered(s, w[1], false);
        if (op == SpvOpVariable)
            o[2] = w[3]; /* its storage class */
        break;
    case SpvOpCompositeConstruct:
        construct(s, f, w, n);
        return;
    case SpvOpSelect:
        select_wide(s, f, w);
        return;
    case SpvOpVectorShuffle:
        shuffle(s, f, w, n);
        return;
    case SpvOpFConvert:
    case SpvOpConvertSToF:
    case SpvOpConvertFToS:
        convert(s, f, w);
        return;
    case SpvOpExtInst:
        lower_ext(s, f, w, n);
        return;
    default: /* dot, mod, matrices, bit casts, other comparisons ... */
        s->failed = true;
        return;
    }
    emit(s, f, op, o, n - 1);
}

/* Appends function f, its temporaries declared first in its first block. */
static void finish(struct soft *s, struct fn *f, struct words *out)
{
    for (size_t i = 0; i < f->head.n; i++)
        words_put(out, f->head.w[i]);
    for (int i = 0; i < f->temp_count; i++) {
        uint32_t o[3] = {f->temps[i].type, f->temps[i].id, SpvStorageClassFunction};
        words_inst(out, SpvOpVariable, o, 3);
    }
    for (size_t i = 0; i < f->body.n; i++)
        words_put(out, f->body.w[i]);
    words_inst(out, SpvOpFunctionEnd, NULL, 0);
    s->failed |= f->head.failed || f->body.failed;
    f->head.n = f->body.n = 0;
    f->temp_count = 0;
    f->labelled = false;
}

void soft_lower_functions(struct soft *s, struct words *out)
{
    struct fn f = {0};
    bool library = false;
    for (size_t at = s->functions; at < s->words && !s->failed; at += spirv_count(s->code, at)) {
        const uint32_t *w = &s->code[at];
        uint32_t op = spirv_op(s->code, at), n = spirv_count(s->code, at);
        if (op == SpvOpFunction)
            library = n == 5 && s->library[w[2]];
        if (library) { /* as it is */
            words_inst(out, op, &w[1], n - 1);
            continue;
        }
        if (op == SpvOpFunction && n == 5) {
            uint32_t o[4] = {soft_lowered(s, w[1], false), w[2], w[3], soft_lowered(s, w[4], false)};
            words_inst(&f.head, op, o, 4);
        } else if (op == SpvOpFunctionParameter && n == 3) {
            uint32_t o[2] = {soft_lowered(s, w[1], false), w[2]};
            words_inst(&f.head, op, o, 2);
        } else if (op == SpvOpLabel && !f.labelled) {
            words_inst(&f.head, op, &w[1], n - 1);
            f.labelled = true;
        } else if (op == SpvOpFunctionEnd) {
            finish(s, &f, out);
        } else {
            lower(s, &f, w, n);
        }
    }
    free(f.head.w);
    free(f.body.w);
}
