#include "spirv_specialize.h"

#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "spirv_words.h"

#define SPV_ENABLE_UTILITY_CODE
#include <spirv/unified1/spirv.h>

/* The header's helper is an inline definition; this declaration makes
 * this file provide it (C11 6.7.4), whether or not calls are inlined. */
extern void SpvHasResultAndType(SpvOp opcode, bool *hasResult, bool *hasResultType);

/* A value's place in the lattice: not yet known to run (UNKNOWN), one
 * constant (CONSTANT), or anything (VARYING). It only ever moves down. */
enum state { UNKNOWN, CONSTANT, VARYING };

struct block {
    uint32_t label;
    size_t start, end;        /* its instructions, OpLabel to terminator */
    size_t terminator;
    uint32_t continue_target; /* a loop header's (else 0) */
    uint32_t selection_merge; /* a selection header's (else 0) */
    bool runs;                /* reached under the constants */
    uint32_t branch_to;       /* emptied: where it still branches (else 0:
                               * OpUnreachable), see plan_emptied */
};

struct module {
    const uint32_t *code;
    size_t words;
    uint32_t bound;
    uint8_t *state;    /* by id */
    uint32_t *value;   /* by id, where CONSTANT */
    uint8_t *scalar;   /* by type id: 1 bool, 2 32-bit integer, 0 other */
    uint32_t *type_of; /* by id: the type of the value it names (0: none) */
    int64_t *spec_id;  /* by id: its SpecId, or -1 */
    uint32_t *block_of; /* by label id: index + 1 into blocks */
    struct block *blocks;
    size_t block_count;
};

/* The result id of the instruction at `at`, or 0. */
static uint32_t result_id(const uint32_t *c, size_t at)
{
    bool has_result = false, has_type = false;
    SpvHasResultAndType((SpvOp)spirv_op(c, at), &has_result, &has_type);
    uint32_t word = has_type ? 2 : 1;
    return has_result && spirv_count(c, at) > word ? c[at + word] : 0;
}

/* The result type of the instruction at `at`, or 0. */
static uint32_t result_type(const uint32_t *c, size_t at)
{
    bool has_result = false, has_type = false;
    SpvHasResultAndType((SpvOp)spirv_op(c, at), &has_result, &has_type);
    return has_type && spirv_count(c, at) > 2 ? c[at + 1] : 0;
}

/* A module spirv_well_formed, whose result ids and types are all below
 * its bound (the arrays by id are that long). */
static bool well_formed(const uint32_t *code, size_t words)
{
    if (!spirv_well_formed(code, words))
        return false;
    for (size_t at = SPIRV_HEADER_WORDS; at < words; at += spirv_count(code, at))
        if (result_id(code, at) >= code[3] || result_type(code, at) >= code[3])
            return false;
    return true;
}

/* Lowers id's state to (s, v); returns whether that changed anything. */
static bool lower(struct module *m, uint32_t id, enum state s, uint32_t v)
{
    if (id >= m->bound || m->state[id] == VARYING || s == UNKNOWN)
        return false;
    if (m->state[id] == CONSTANT && s == CONSTANT && m->value[id] == v)
        return false;
    m->state[id] = m->state[id] == UNKNOWN ? (uint8_t)s : VARYING;
    m->value[id] = v;
    return true;
}

/* State and value of operand id (ids out of range vary). */
static enum state state_of(const struct module *m, uint32_t id, uint32_t *v)
{
    if (id >= m->bound)
        return VARYING;
    *v = m->value[id];
    return (enum state)m->state[id];
}

/* The value of `op` over the operands a (and b), 32-bit, or false when it
 * is not one this follows. Booleans are 0 or 1. */
static bool evaluate(uint32_t op, uint32_t a, uint32_t b, uint32_t *r)
{
    int32_t sa = (int32_t)a, sb = (int32_t)b;
    switch (op) {
    case SpvOpLogicalAnd: *r = a && b; return true;
    case SpvOpLogicalOr: *r = a || b; return true;
    case SpvOpLogicalEqual: *r = (a != 0) == (b != 0); return true;
    case SpvOpLogicalNotEqual: *r = (a != 0) != (b != 0); return true;
    case SpvOpLogicalNot: *r = !a; return true;
    case SpvOpIEqual: *r = a == b; return true;
    case SpvOpINotEqual: *r = a != b; return true;
    case SpvOpSLessThan: *r = sa < sb; return true;
    case SpvOpSLessThanEqual: *r = sa <= sb; return true;
    case SpvOpSGreaterThan: *r = sa > sb; return true;
    case SpvOpSGreaterThanEqual: *r = sa >= sb; return true;
    case SpvOpULessThan: *r = a < b; return true;
    case SpvOpULessThanEqual: *r = a <= b; return true;
    case SpvOpUGreaterThan: *r = a > b; return true;
    case SpvOpUGreaterThanEqual: *r = a >= b; return true;
    case SpvOpBitwiseAnd: *r = a & b; return true;
    case SpvOpBitwiseOr: *r = a | b; return true;
    case SpvOpBitwiseXor: *r = a ^ b; return true;
    case SpvOpNot: *r = ~a; return true;
    case SpvOpIAdd: *r = a + b; return true;
    case SpvOpISub: *r = a - b; return true;
    case SpvOpIMul: *r = a * b; return true;
    case SpvOpSNegate: *r = 0u - a; return true;
    case SpvOpShiftLeftLogical: *r = b < 32 ? a << b : 0; return true;
    case SpvOpShiftRightLogical: *r = b < 32 ? a >> b : 0; return true;
    case SpvOpCopyObject: *r = a; return true;
    default: return false;
    }
}

static bool unary(uint32_t op)
{
    return op == SpvOpLogicalNot || op == SpvOpNot || op == SpvOpSNegate || op == SpvOpCopyObject;
}

/* The state of `op` applied to operand ids w[0] (and w[1]; w[0..2] for
 * OpSelect) of a scalar result: UNKNOWN while an operand is, VARYING for
 * operations this does not follow. A known false (true) decides a logical
 * and (or) alone. */
static enum state apply(const struct module *m, uint32_t op, const uint32_t *w, uint32_t n,
                        uint32_t *r)
{
    uint32_t a = 0, b = 0, c = 0;
    if (op == SpvOpSelect && n == 3) {
        enum state s = state_of(m, w[0], &c);
        if (s != CONSTANT)
            return s;
        return state_of(m, c ? w[1] : w[2], r);
    }
    if (n != (unary(op) ? 1u : 2u) || !evaluate(op, 0, 1, r))
        return VARYING;
    enum state sa = state_of(m, w[0], &a);
    enum state sb = n > 1 ? state_of(m, w[1], &b) : CONSTANT;
    for (int k = 0; k < 2 && (op == SpvOpLogicalAnd || op == SpvOpLogicalOr); k++) {
        enum state s = k ? sb : sa;
        uint32_t v = k ? b : a;
        if (s == CONSTANT && (op == SpvOpLogicalAnd ? v == 0 : v != 0)) {
            *r = op == SpvOpLogicalOr;
            return CONSTANT;
        }
    }
    if (sa == VARYING || sb == VARYING)
        return VARYING;
    if (sa == UNKNOWN || sb == UNKNOWN)
        return UNKNOWN;
    evaluate(op, a, b, r);
    return CONSTANT;
}

/* Types, SpecIds and the module-level constants (specialized). */
static void read_globals(struct module *m, const int32_t *values, size_t count)
{
    const uint32_t *c = m->code;
    for (size_t at = SPIRV_HEADER_WORDS; at < m->words; at += spirv_count(c, at)) {
        uint32_t op = spirv_op(c, at), n = spirv_count(c, at);
        if (op == SpvOpDecorate && n >= 4 && c[at + 2] == SpvDecorationSpecId && c[at + 1] < m->bound)
            m->spec_id[c[at + 1]] = c[at + 3];
    }
    for (size_t at = SPIRV_HEADER_WORDS; at < m->words; at += spirv_count(c, at)) {
        uint32_t op = spirv_op(c, at), n = spirv_count(c, at);
        if (op == SpvOpFunction)
            break;
        if (op == SpvOpTypeBool && n >= 2 && c[at + 1] < m->bound)
            m->scalar[c[at + 1]] = 1;
        if (op == SpvOpTypeInt && n >= 3 && c[at + 1] < m->bound && c[at + 2] == 32)
            m->scalar[c[at + 1]] = 2;
        uint32_t id = result_id(c, at);
        if (!id || id >= m->bound)
            continue;
        m->state[id] = VARYING;
        uint32_t type = m->type_of[id] = result_type(c, at);
        if (!m->scalar[type])
            continue;
        int64_t spec = m->spec_id[id];
        bool given = spec >= 0 && (size_t)spec < count;
        uint32_t v = 0;
        enum state s = VARYING;
        if (op == SpvOpConstantTrue || op == SpvOpConstantFalse) {
            v = op == SpvOpConstantTrue;
            s = CONSTANT;
        } else if (op == SpvOpSpecConstantTrue || op == SpvOpSpecConstantFalse) {
            v = given ? values[spec] != 0 : op == SpvOpSpecConstantTrue;
            s = CONSTANT;
        } else if ((op == SpvOpConstant || op == SpvOpSpecConstant) && n == 4) {
            v = op == SpvOpSpecConstant && given ? (uint32_t)values[spec] : c[at + 3];
            s = CONSTANT;
        } else if (op == SpvOpSpecConstantOp && n >= 5) {
            s = apply(m, c[at + 3], c + at + 4, n - 4, &v);
            s = s == UNKNOWN ? VARYING : s;
        }
        if (s == CONSTANT) {
            m->state[id] = CONSTANT;
            m->value[id] = m->scalar[type] == 1 ? v != 0 : v;
        }
    }
}

/* One function: where it lies, and its blocks in m->blocks. */
struct function {
    uint32_t id;
    size_t start, end;      /* OpFunction to after OpFunctionEnd */
    size_t first, count;    /* its blocks */
    bool called;            /* from an entry point, through blocks that run */
};

/* Reads the function starting at `at` (OpFunction): its blocks go to
 * m->blocks. Returns false if it is malformed. */
static bool read_function(struct module *m, size_t at, struct function *fn)
{
    const uint32_t *c = m->code;
    *fn = (struct function){.id = spirv_count(c, at) >= 3 ? c[at + 2] : 0, .start = at,
                            .first = m->block_count};
    struct block *b = NULL;
    for (; at < m->words; at += spirv_count(c, at)) {
        uint32_t op = spirv_op(c, at), n = spirv_count(c, at);
        if (op == SpvOpFunctionEnd) {
            fn->end = at + n;
            fn->count = m->block_count - fn->first;
            return fn->count > 0 && b->terminator && fn->id < m->bound;
        }
        if (op == SpvOpLabel) {
            if ((b && !b->terminator) || n < 2 || c[at + 1] >= m->bound ||
                m->block_of[c[at + 1]])
                return false;
            b = &m->blocks[m->block_count++];
            *b = (struct block){.label = c[at + 1], .start = at};
            m->block_of[b->label] = (uint32_t)m->block_count;
            continue;
        }
        if (result_type(c, at))
            m->type_of[result_id(c, at)] = result_type(c, at);
        if (!b) { /* OpFunction, OpFunctionParameter: a parameter varies */
            if (op == SpvOpFunctionParameter && n >= 3)
                m->state[c[at + 2]] = VARYING;
            continue;
        }
        if (b->terminator)
            return false;
        if (op == SpvOpLoopMerge && n >= 3)
            b->continue_target = c[at + 2];
        if (op == SpvOpSelectionMerge && n >= 2)
            b->selection_merge = c[at + 1];
        if (op == SpvOpBranch || op == SpvOpBranchConditional || op == SpvOpSwitch ||
            op == SpvOpReturn || op == SpvOpReturnValue || op == SpvOpKill ||
            op == SpvOpUnreachable || op == SpvOpTerminateInvocation) {
            b->terminator = at;
            b->end = at + n;
            if ((op == SpvOpBranch && n < 2) || (op == SpvOpBranchConditional && n < 4) ||
                (op == SpvOpSwitch && n < 3))
                return false;
            /* A switch's case literals are one word only on a 32-bit selector. */
            if (op == SpvOpSwitch && (c[at + 1] >= m->bound || m->type_of[c[at + 1]] >= m->bound ||
                                      m->scalar[m->type_of[c[at + 1]]] != 2))
                return false;
        }
    }
    return false;
}

static struct block *block_at(const struct module *m, uint32_t label)
{
    uint32_t k = label < m->bound ? m->block_of[label] : 0;
    return k && k <= m->block_count && m->blocks[k - 1].label == label ? &m->blocks[k - 1]
                                                                        : NULL;
}

/* Whether the edge from block `from` to label `to` can be taken. */
static bool edge_runs(const struct module *m, const struct block *from, uint32_t to)
{
    const uint32_t *c = m->code;
    size_t t = from->terminator;
    uint32_t op = spirv_op(c, t), n = spirv_count(c, t), v = 0;
    if (!from->runs)
        return false;
    if (op == SpvOpBranch)
        return c[t + 1] == to;
    if (op == SpvOpBranchConditional) {
        enum state s = state_of(m, c[t + 1], &v);
        if (s == UNKNOWN)
            return false;
        return s == VARYING ? c[t + 2] == to || c[t + 3] == to : c[t + (v ? 2 : 3)] == to;
    }
    if (op == SpvOpSwitch) {
        enum state s = state_of(m, c[t + 1], &v);
        if (s == UNKNOWN)
            return false;
        bool matched = false;
        for (uint32_t k = 3; k + 1 < n; k += 2) {
            bool hit = s == VARYING || c[t + k] == v;
            matched |= hit && s == CONSTANT;
            if (hit && c[t + k + 1] == to)
                return true;
        }
        return c[t + 2] == to && (s == VARYING || !matched);
    }
    return false;
}

/* One sweep over fn's blocks: marks blocks that can run and lowers the
 * values they compute. Returns whether anything changed. */
static bool sweep(struct module *m, const struct function *fn)
{
    const uint32_t *c = m->code;
    bool changed = false;
    for (size_t k = fn->first; k < fn->first + fn->count; k++) {
        struct block *b = &m->blocks[k];
        if (!b->runs)
            continue;
        for (size_t at = b->start; at < b->end; at += spirv_count(c, at)) {
            uint32_t op = spirv_op(c, at), n = spirv_count(c, at);
            uint32_t id = result_id(c, at), type = result_type(c, at);
            if (!id || !type)
                continue;
            bool tracked = m->scalar[type] != 0;
            uint32_t v = 0;
            enum state s = VARYING;
            if (tracked && op == SpvOpPhi) {
                s = UNKNOWN;
                for (uint32_t w = 3; w + 1 < n; w += 2) {
                    const struct block *from = block_at(m, c[at + w + 1]);
                    uint32_t x = 0;
                    if (!from || !edge_runs(m, from, b->label))
                        continue;
                    enum state sx = state_of(m, c[at + w], &x);
                    if (sx == VARYING || (sx == CONSTANT && s == CONSTANT && x != v))
                        s = VARYING;
                    else if (sx == CONSTANT && s == UNKNOWN)
                        s = CONSTANT, v = x;
                }
            } else if (tracked) {
                s = apply(m, op, c + at + 3, n - 3, &v);
            }
            changed |= lower(m, id, s, v);
        }
        size_t t = b->terminator;
        uint32_t op = spirv_op(c, t), n = spirv_count(c, t);
        /* the words that name successors: 1; 2 and 3; 2, 4, 6, ... */
        uint32_t first = op == SpvOpBranch ? 1 : 2;
        uint32_t step = op == SpvOpSwitch ? 2 : 1;
        uint32_t last = op == SpvOpBranch ? 2 : op == SpvOpBranchConditional ? 4
                        : op == SpvOpSwitch ? n : 0;
        for (uint32_t w = first; w < last; w += step) {
            struct block *to = block_at(m, c[t + w]);
            if (to && !to->runs && edge_runs(m, b, to->label))
                to->runs = changed = true;
        }
    }
    return changed;
}

/* Marks the functions fn calls from blocks that run; returns whether one
 * was new. */
static bool note_calls(const struct module *m, const struct function *fn,
                       struct function *functions, const uint32_t *function_of)
{
    const uint32_t *c = m->code;
    bool more = false;
    for (size_t k = fn->first; k < fn->first + fn->count; k++)
        for (size_t at = m->blocks[k].start; m->blocks[k].runs && at < m->blocks[k].end;
             at += spirv_count(c, at))
            if (spirv_op(c, at) == SpvOpFunctionCall && spirv_count(c, at) >= 4 &&
                c[at + 3] < m->bound && function_of[c[at + 3]]) {
                struct function *callee = &functions[function_of[c[at + 3]] - 1];
                more |= !callee->called;
                callee->called = true;
            }
    return more;
}

/* Where emptied blocks still branch, so that the constructs around them
 * stay structured: a selection's arm that is never taken (the header
 * runs) goes straight to the selection's merge, as an empty arm would (an
 * OpUnreachable there would break a continue construct, which must reach
 * its back edge); a loop's continue target that is never reached (the
 * header runs) branches back to the header, as a loop needs. */
static void plan_emptied(struct module *m, const struct function *fn)
{
    const uint32_t *c = m->code;
    for (size_t k = fn->first; k < fn->first + fn->count; k++) {
        struct block *h = &m->blocks[k];
        if (!h->runs || !h->selection_merge)
            continue;
        size_t t = h->terminator;
        uint32_t op = spirv_op(c, t), n = spirv_count(c, t);
        uint32_t last = op == SpvOpBranchConditional ? 4 : op == SpvOpSwitch ? n : 0;
        for (uint32_t w = 2; w < last; w += op == SpvOpSwitch ? 2 : 1) {
            struct block *arm = block_at(m, c[t + w]);
            if (arm && !arm->runs && arm->label != h->selection_merge)
                arm->branch_to = h->selection_merge;
        }
    }
    for (size_t k = fn->first; k < fn->first + fn->count; k++) {
        struct block *h = &m->blocks[k];
        struct block *t = h->runs && h->continue_target ? block_at(m, h->continue_target) : NULL;
        if (t && !t->runs && t != h)
            t->branch_to = h->label;
    }
}

/* How many words writing fn may add to it: an emptied block that still
 * branches takes a word more than a label and OpUnreachable, and adds an
 * entry of two words to each OpPhi where it branches. */
static size_t growth(const struct module *m, const struct function *fn)
{
    const uint32_t *c = m->code;
    size_t words = 0;
    for (size_t k = fn->first; k < fn->first + fn->count; k++) {
        const struct block *to = m->blocks[k].branch_to ? block_at(m, m->blocks[k].branch_to)
                                                        : NULL;
        words += m->blocks[k].branch_to ? 1 : 0;
        for (size_t at = to ? to->start : 0; to && at < to->end; at += spirv_count(c, at))
            words += spirv_op(c, at) == SpvOpPhi ? 2 : 0;
    }
    return words;
}

/* Values the output adds to the module's globals, with new ids from
 * next_id: an OpUndef per type that needs one (undef_of, by type) and
 * the constants true and false (bool: the module's boolean type). */
struct added {
    uint32_t next_id;
    uint32_t *undef_of;
    uint32_t bool_type, true_id, false_id;
};

static uint32_t undef(struct added *a, uint32_t type)
{
    if (!a->undef_of[type])
        a->undef_of[type] = a->next_id++;
    return a->undef_of[type];
}

static uint32_t constant(struct added *a, bool value)
{
    uint32_t *id = value ? &a->true_id : &a->false_id;
    if (!*id)
        *id = a->next_id++;
    return *id;
}

static uint32_t *put(uint32_t *out, const uint32_t *c, size_t at)
{
    memcpy(out, c + at, spirv_count(c, at) * sizeof *c);
    return out + spirv_count(c, at);
}

/* Writes function fn: its blocks that run as they were, but for OpPhi
 * operands from emptied blocks (dropped, or an undefined value where the
 * emptied block still branches here: that edge is never taken); the
 * others as a label and OpUnreachable or their branch (plan_emptied).
 * Marks the ids that stay defined in `defined`; an OpUndef of type T is
 * undef_of[T]. */
static uint32_t *write_function(const struct module *m, const struct function *fn,
                                uint32_t *out, bool *defined, struct added *added)
{
    const uint32_t *c = m->code;
    for (size_t at = fn->start; at < m->blocks[fn->first].start; at += spirv_count(c, at)) {
        out = put(out, c, at); /* OpFunction and its parameters */
        defined[result_id(c, at)] = true;
    }
    for (size_t k = fn->first; k < fn->first + fn->count; k++) {
        const struct block *b = &m->blocks[k];
        defined[b->label] = true;
        if (!b->runs) {
            *out++ = 2u << 16 | SpvOpLabel;
            *out++ = b->label;
            if (b->branch_to) {
                *out++ = 2u << 16 | SpvOpBranch;
                *out++ = b->branch_to;
            } else {
                *out++ = 1u << 16 | SpvOpUnreachable;
            }
            continue;
        }
        for (size_t at = b->start; at < b->end; at += spirv_count(c, at)) {
            uint32_t id = result_id(c, at);
            if (id < m->bound)
                defined[id] = true;
            uint32_t cond = spirv_op(c, at) == SpvOpBranchConditional ? c[at + 1] : 0, v = 0;
            if (cond && added->bool_type && state_of(m, cond, &v) == CONSTANT) {
                /* A condition known here, made a literal constant: lavapipe
                 * then drops the arm not taken before it makes any code
                 * (an OpUnreachable left behind a condition it cannot
                 * fold costs a mask in every loop around it). */
                uint32_t *branch = out;
                out = put(out, c, at);
                branch[1] = constant(added, v != 0);
                continue;
            }
            if (spirv_op(c, at) != SpvOpPhi) {
                out = put(out, c, at);
                continue;
            }
            uint32_t *head = out;
            out += 3;
            head[1] = c[at + 1];
            head[2] = c[at + 2];
            for (uint32_t w = 3; w + 1 < spirv_count(c, at); w += 2) {
                const struct block *from = block_at(m, c[at + w + 1]);
                if (from && !from->runs)
                    continue; /* emptied: no longer a predecessor, or below */
                *out++ = c[at + w];
                *out++ = c[at + w + 1];
            }
            /* Emptied blocks that still branch here: never taken. */
            for (size_t e = fn->first; e < fn->first + fn->count; e++) {
                if (m->blocks[e].runs || m->blocks[e].branch_to != b->label)
                    continue;
                *out++ = undef(added, c[at + 1]);
                *out++ = m->blocks[e].label;
            }
            head[0] = (uint32_t)(out - head) << 16 | SpvOpPhi;
        }
    }
    *out++ = 1u << 16 | SpvOpFunctionEnd;
    return out;
}

/* Whether a name or decoration at `at` is about an id that stays. */
static bool about_kept(const uint32_t *c, size_t at, const bool *defined, uint32_t bound)
{
    uint32_t op = spirv_op(c, at);
    if (op != SpvOpName && op != SpvOpDecorate && op != SpvOpDecorateId &&
        op != SpvOpDecorateString)
        return true;
    return spirv_count(c, at) < 2 || (c[at + 1] < bound && defined[c[at + 1]]);
}

/* The functions of the module, in m->blocks and `functions` (function_of:
 * index + 1 by id); the offset where they start (after the globals), or 0
 * if one is malformed. */
static size_t read_functions(struct module *m, struct function *functions, size_t *count,
                             uint32_t *function_of)
{
    const uint32_t *c = m->code;
    size_t globals_end = SPIRV_HEADER_WORDS;
    while (globals_end < m->words && spirv_op(c, globals_end) != SpvOpFunction)
        globals_end += spirv_count(c, globals_end);
    *count = 0;
    for (size_t at = globals_end; at < m->words;) {
        struct function *fn = &functions[*count];
        if (spirv_op(c, at) != SpvOpFunction || !read_function(m, at, fn) || function_of[fn->id])
            return 0;
        function_of[fn->id] = (uint32_t)++*count;
        at = fn->end;
    }
    return globals_end;
}

uint32_t *spirv_specialize(const uint32_t *code, size_t words, const int32_t *values,
                           size_t count, size_t *out_words)
{
    if (!well_formed(code, words))
        return NULL;
    struct module m = {.code = code, .words = words, .bound = code[3]};
    size_t b = m.bound;
    m.state = calloc(b, 1);
    m.value = calloc(b, sizeof *m.value);
    m.scalar = calloc(b, 1);
    m.type_of = calloc(b, sizeof *m.type_of);
    m.spec_id = malloc(b * sizeof *m.spec_id);
    m.block_of = calloc(b, sizeof *m.block_of);
    m.blocks = malloc((words / 2 + 1) * sizeof *m.blocks);
    struct function *functions = malloc((words / 2 + 1) * sizeof *functions);
    uint32_t *function_of = calloc(b, sizeof *function_of);
    bool *defined = calloc(b, 1);
    uint32_t *undef_of = calloc(b, sizeof *undef_of);
    uint32_t *out = NULL, *funcs_out = NULL, *result = NULL;
    size_t function_count = 0, globals_end = 0;
    if (!m.state || !m.value || !m.scalar || !m.type_of || !m.spec_id || !m.block_of ||
        !m.blocks || !functions || !function_of || !defined || !undef_of)
        goto done;
    for (size_t i = 0; i < b; i++)
        m.spec_id[i] = -1;
    read_globals(&m, values, count);
    globals_end = read_functions(&m, functions, &function_count, function_of);
    if (!globals_end)
        goto done;
    /* Each function solved once (the analysis stays within it: a call's
     * result varies); then the functions called from entry points on,
     * through blocks that run. */
    for (size_t k = 0; k < function_count; k++) {
        m.blocks[functions[k].first].runs = true;
        while (sweep(&m, &functions[k]))
            ;
        plan_emptied(&m, &functions[k]);
    }
    for (size_t at = SPIRV_HEADER_WORDS; at < globals_end; at += spirv_count(code, at))
        if (spirv_op(code, at) == SpvOpEntryPoint && spirv_count(code, at) >= 3 &&
            code[at + 2] < b && function_of[code[at + 2]])
            functions[function_of[code[at + 2]] - 1].called = true;
    for (bool more = true; more;) {
        more = false;
        for (size_t k = 0; k < function_count; k++)
            if (functions[k].called)
                more |= note_calls(&m, &functions[k], functions, function_of);
    }
    /* The output is longer than the input by at most the OpUndefs (3
     * words, one per type), the two constants and what writing the
     * functions adds. */
    size_t extra = 0;
    for (size_t k = 0; k < function_count; k++)
        extra += functions[k].called ? growth(&m, &functions[k]) : 0;
    out = malloc((words + 3 * b + 6 + extra) * sizeof *out);
    funcs_out = malloc((words + extra) * sizeof *funcs_out);
    if (!out || !funcs_out)
        goto done;
    /* The functions that stay, written first to learn what stays defined
     * and which OpUndefs are needed; then the globals, filtered, before them. */
    struct added added = {.next_id = m.bound, .undef_of = undef_of};
    for (uint32_t id = 0; id < b && !added.bool_type; id++)
        added.bool_type = m.scalar[id] == 1 ? id : 0;
    uint32_t *f = funcs_out;
    for (size_t at = SPIRV_HEADER_WORDS; at < globals_end; at += spirv_count(code, at)) {
        uint32_t id = result_id(code, at);
        if (id < b)
            defined[id] = true;
    }
    for (size_t k = 0; k < function_count; k++)
        if (functions[k].called)
            f = write_function(&m, &functions[k], f, defined, &added);
    uint32_t *w = out;
    memcpy(w, code, SPIRV_HEADER_WORDS * sizeof *code);
    w += SPIRV_HEADER_WORDS;
    for (size_t at = SPIRV_HEADER_WORDS; at < globals_end; at += spirv_count(code, at))
        if (about_kept(code, at, defined, m.bound))
            w = put(w, code, at);
    for (uint32_t type = 0; type < b; type++)
        if (undef_of[type]) {
            *w++ = 3u << 16 | SpvOpUndef;
            *w++ = type;
            *w++ = undef_of[type];
        }
    for (int k = 0; k < 2; k++)
        if (k ? added.true_id : added.false_id) {
            *w++ = 3u << 16 | (k ? SpvOpConstantTrue : SpvOpConstantFalse);
            *w++ = added.bool_type;
            *w++ = k ? added.true_id : added.false_id;
        }
    memcpy(w, funcs_out, (size_t)(f - funcs_out) * sizeof *f);
    w += f - funcs_out;
    out[3] = added.next_id;
    *out_words = (size_t)(w - out);
    result = out;
    out = NULL;
done:
    free(m.state);
    free(m.value);
    free(m.scalar);
    free(m.type_of);
    free(m.spec_id);
    free(m.block_of);
    free(m.blocks);
    free(functions);
    free(function_of);
    free(defined);
    free(undef_of);
    free(out);
    free(funcs_out);
    return result;
}
