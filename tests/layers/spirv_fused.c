#include "spirv_fused.h"

#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "spirv_words.h"

enum {
    OP_CAPABILITY = 17,
    OP_TYPE_FLOAT = 22,
    OP_TYPE_VECTOR = 23,
    OP_FUNCTION = 54,
    OP_DECORATE = 71,
    OP_FCONVERT = 115,
    OP_FADD = 129,
    OP_FSUB = 131,
    OP_FMUL = 133,
    OP_VECTOR_TIMES_SCALAR = 142,
    OP_DOT = 148,
    CAPABILITY_FLOAT64 = 10,
    DECORATION_NO_CONTRACTION = 42,
    MAX_COMPONENTS = 4,
    /* the most words one rewritten operation becomes */
    SITE_WORDS = 4 * 3 + 5 * 2 + 4,
    /* new types: a double, and double vectors of 2 to 4 */
    EXTRA_WORDS = 2 + 3 + 4 * 3,
};

/* What the rewrite needs to know of an id. */
struct id_info {
    uint32_t type;                /* the type of the value it names (0: not known) */
    uint32_t product_op, a, b;    /* a product's opcode and factors (op 0: none) */
    uint32_t float_count;         /* a float32 type: 1, or its vector's size (0: other) */
    bool no_contraction;          /* decorated NoContraction (GLSL `precise`) */
};

struct module {
    const uint32_t *code;
    size_t words;
    uint32_t bound;
    struct id_info *ids;
    uint32_t dtype[MAX_COMPONENTS + 1]; /* double and dvecN ids (0: absent) */
    bool has_float64;
};

/* Opcodes whose word 1 is a result type and word 2 a result id, among
 * those that make the values a sum or a dot product can use. */
static bool typed_result(uint32_t op)
{
    static const uint16_t ops[] = {12, 43, 44, 50, 51, 52, 55, 57, 61, 79, 80, 81, 82,
                                   111, 112, 115, 124, 127, 129, 131, 133, 136, 140, 141,
                                   142, 144, 145, 148, 169, 245};
    for (size_t i = 0; i < sizeof ops / sizeof ops[0]; i++)
        if (ops[i] == op)
            return true;
    return false;
}

/* Reads types, the type of each value, and each product's factors. */
static void scan(struct module *m)
{
    const uint32_t *c = m->code;
    for (size_t at = SPIRV_HEADER_WORDS; at < m->words; at += c[at] >> 16) {
        uint32_t count = c[at] >> 16, op = c[at] & 0xffffu;
        if (op == OP_CAPABILITY && count == 2 && c[at + 1] == CAPABILITY_FLOAT64)
            m->has_float64 = true;
        if (op == OP_DECORATE && count == 3 && c[at + 1] < m->bound &&
            c[at + 2] == DECORATION_NO_CONTRACTION)
            m->ids[c[at + 1]].no_contraction = true;
        if (op == OP_TYPE_FLOAT && count == 3 && c[at + 1] < m->bound) {
            if (c[at + 2] == 32)
                m->ids[c[at + 1]].float_count = 1;
            if (c[at + 2] == 64)
                m->dtype[1] = c[at + 1];
        }
        if (op == OP_TYPE_VECTOR && count == 4 && c[at + 1] < m->bound &&
            c[at + 2] < m->bound && c[at + 3] >= 2 && c[at + 3] <= MAX_COMPONENTS) {
            if (m->ids[c[at + 2]].float_count == 1)
                m->ids[c[at + 1]].float_count = c[at + 3];
            if (m->dtype[1] && c[at + 2] == m->dtype[1])
                m->dtype[c[at + 3]] = c[at + 1];
        }
        if (typed_result(op) && count >= 3 && c[at + 2] < m->bound) {
            struct id_info *r = &m->ids[c[at + 2]];
            r->type = c[at + 1];
            if ((op == OP_FMUL || op == OP_VECTOR_TIMES_SCALAR) && count == 5)
                r->product_op = op, r->a = c[at + 3], r->b = c[at + 4];
        }
    }
}

/* The float32 count of type t (1 scalar, 2-4 vector; 0 other). */
static uint32_t floats(const struct module *m, uint32_t t)
{
    return t < m->bound ? m->ids[t].float_count : 0;
}

static uint32_t *emit(uint32_t *out, uint32_t op, uint32_t n, const uint32_t *w)
{
    *out++ = ((n + 1) << 16) | op;
    memcpy(out, w, n * sizeof *w);
    return out + n;
}

/* value converted to double (its type's double twin); returns its new id. */
static uint32_t widened(struct module *m, uint32_t **out, uint32_t value, uint32_t *next)
{
    uint32_t id = (*next)++;
    uint32_t w[3] = {m->dtype[floats(m, m->ids[value].type)], id, value};
    *out = emit(*out, OP_FCONVERT, 3, w);
    return id;
}

/* Rewrites instruction c (a float32 OpFAdd, OpFSub or OpDot) if it is a
 * site; returns whether it did. */
static bool rewrite(struct module *m, const uint32_t *c, uint32_t **out, uint32_t *next)
{
    uint32_t op = c[0] & 0xffffu, type = c[1], result = c[2], x = c[3], y = c[4];
    if ((c[0] >> 16) != 5 || x >= m->bound || y >= m->bound || floats(m, type) == 0 ||
        result >= m->bound || m->ids[result].no_contraction)
        return false;
    uint32_t wide;
    if (op == OP_DOT) {
        if (floats(m, m->ids[x].type) < 2 || floats(m, m->ids[y].type) < 2)
            return false;
        uint32_t u = widened(m, out, x, next), v = widened(m, out, y, next);
        wide = (*next)++;
        *out = emit(*out, OP_DOT, 4, (uint32_t[]){m->dtype[1], wide, u, v});
    } else {
        bool first = m->ids[x].product_op && m->ids[x].type == type &&
                     !m->ids[x].no_contraction;
        bool second = m->ids[y].product_op && m->ids[y].type == type &&
                      !m->ids[y].no_contraction;
        if (!first && !second)
            return false;
        const struct id_info *p = &m->ids[first ? x : y];
        if (p->a >= m->bound || p->b >= m->bound || floats(m, m->ids[p->a].type) == 0 ||
            floats(m, m->ids[p->b].type) == 0)
            return false;
        uint32_t a = widened(m, out, p->a, next), b = widened(m, out, p->b, next);
        uint32_t other = widened(m, out, first ? y : x, next);
        uint32_t product = (*next)++;
        uint32_t dtype = m->dtype[floats(m, type)];
        *out = emit(*out, p->product_op, 4, (uint32_t[]){dtype, product, a, b});
        wide = (*next)++;
        uint32_t sum[4] = {dtype, wide, first ? product : other, first ? other : product};
        *out = emit(*out, op, 4, sum);
    }
    *out = emit(*out, OP_FCONVERT, 3, (uint32_t[]){type, result, wide});
    return true;
}

uint32_t *spirv_fused(const uint32_t *code, size_t words, size_t *out_words, size_t *sites)
{
    if (!spirv_well_formed(code, words))
        return NULL;
    struct module m = {code, words, code[3], calloc(code[3], sizeof(struct id_info)), {0},
                       false};
    size_t candidates = 0;
    for (size_t at = SPIRV_HEADER_WORDS; at < words; at += code[at] >> 16) {
        uint32_t op = code[at] & 0xffffu;
        candidates += op == OP_FADD || op == OP_FSUB || op == OP_DOT;
    }
    uint32_t *out = malloc((words + 2 + EXTRA_WORDS + candidates * SITE_WORDS) * sizeof *out);
    if (!m.ids || !out) {
        free(m.ids);
        free(out);
        return NULL;
    }
    scan(&m);
    uint32_t next = m.bound;
    uint32_t *o = out;
    memcpy(o, code, SPIRV_HEADER_WORDS * sizeof *o);
    o += SPIRV_HEADER_WORDS;
    if (!m.has_float64)
        o = emit(o, OP_CAPABILITY, 1, (uint32_t[]){CAPABILITY_FLOAT64});
    bool typed = false;
    *sites = 0;
    for (size_t at = SPIRV_HEADER_WORDS; at < words; at += code[at] >> 16) {
        uint32_t count = code[at] >> 16, op = code[at] & 0xffffu;
        if (op == OP_FUNCTION && !typed) { /* the double types, before any code */
            typed = true;
            if (!m.dtype[1]) {
                m.dtype[1] = next++;
                o = emit(o, OP_TYPE_FLOAT, 2, (uint32_t[]){m.dtype[1], 64});
            }
            for (uint32_t n = 2; n <= MAX_COMPONENTS; n++)
                if (!m.dtype[n]) {
                    m.dtype[n] = next++;
                    o = emit(o, OP_TYPE_VECTOR, 3, (uint32_t[]){m.dtype[n], m.dtype[1], n});
                }
        }
        if (typed && (op == OP_FADD || op == OP_FSUB || op == OP_DOT) &&
            rewrite(&m, &code[at], &o, &next)) {
            ++*sites;
            continue;
        }
        memcpy(o, &code[at], count * sizeof *o);
        o += count;
    }
    out[3] = next;
    free(m.ids);
    *out_words = (size_t)(o - out);
    return out;
}
