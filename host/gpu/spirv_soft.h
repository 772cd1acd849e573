/* spirv_soft.h: what the parts of spirv_soft_double share: the module
 * read, its types lowered (spirv_soft_types.c) and its functions
 * rewritten onto the library (spirv_soft_body.c). Private to them. */
#ifndef TP2_SPIRV_SOFT_H
#define TP2_SPIRV_SOFT_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* A growing run of words; `failed` once memory ran out. */
struct words {
    uint32_t *w;
    size_t n, cap;
    bool failed;
};

/* The library's functions, as the pass calls them. */
enum sd_fn {
    SD_ADD, SD_SUB, SD_MUL, SD_DIV, SD_NEG, SD_ABS, SD_SQRT, SD_FLOOR, SD_FRACT, SD_MIN,
    SD_MAX, SD_LT, SD_LE, SD_GT, SD_GE, SD_EQ, SD_UNE, SD_FROM_FLOAT, SD_TO_FLOAT,
    SD_FROM_INT, SD_TO_INT, SD_COUNT
};

struct sd_lib {
    uint32_t id, ret;   /* the function, its return type */
    uint32_t params;    /* how many (1 or 2) */
    uint32_t param[2];  /* their pointer types (Function storage) */
};

struct soft {
    const uint32_t *code;
    size_t words;
    uint32_t bound, next;      /* the input's id bound; the next id to hand out */
    size_t globals, functions; /* where types and functions start */
    bool failed;               /* met what this does not lower, or out of memory */
    /* By original id. */
    size_t *def;         /* where it is defined (0: nowhere) */
    uint32_t *type_of;   /* a value's type */
    uint8_t *wide;       /* a type holding a 64-bit float, or a value of one */
    uint8_t *laid_out;   /* a struct with Offsets, an array with an ArrayStride */
    uint8_t *library;    /* a function named sd_* */
    uint8_t *dropped;    /* not declared in the output */
    uint8_t *replaced;   /* a result now made by a call or a copy */
    uint32_t *low;       /* a wide type's lowered type, a wide constant's lowered one */
    uint32_t *low_laid;  /* a dvecN's lowered type in an explicit layout */
    /* By any id: 1 + where `decls` declares a new or lowered global. */
    size_t *rec;
    uint32_t rec_cap;
    uint32_t *recs;      /* those ids, in order */
    size_t rec_count;
    struct words decls;  /* their declarations */
    uint32_t *strided;   /* the arrays that need ArrayStride 8 */
    size_t strided_count;
    bool keep_f64;       /* the library uses 64-bit floats itself */
    uint32_t f64, uint_type, bool_type, uvec2, glsl;
    struct sd_lib lib[SD_COUNT];
    size_t sites;
};

void words_put(struct words *b, uint32_t word);
/* One instruction: opcode, then `count` operand words. */
void words_inst(struct words *b, uint32_t op, const uint32_t *operands, uint32_t count);

uint32_t soft_result_id(const uint32_t *code, size_t at);
uint32_t soft_result_type(const uint32_t *code, size_t at);

/* Which types hold a 64-bit float, and so which values are of one
 * (spirv_soft_types.c). */
void soft_mark_wide(struct soft *s);
/* Plans the wide types' lowered forms and the lowered constants. */
void soft_plan_types(struct soft *s);
/* The type that values of original type t have after lowering; `laid`:
 * in an explicit layout (a dvecN's array then has an ArrayStride). */
uint32_t soft_lowered(struct soft *s, uint32_t t, bool laid);
/* A type or constant declared once: found among the module's or made. */
uint32_t soft_type(struct soft *s, uint32_t op, const uint32_t *operands, uint32_t count);
uint32_t soft_uint(struct soft *s, uint32_t value);
/* Appends the global section, original and new declarations each after
 * what it uses. */
void soft_emit_globals(struct soft *s, struct words *out);

/* Rewrites the functions into `out` (spirv_soft_body.c). */
void soft_lower_functions(struct soft *s, struct words *out);

/* The definition of original id `id` (NULL: none), and its opcode. */
static inline const uint32_t *soft_def(const struct soft *s, uint32_t id)
{
    return id < s->bound && s->def[id] ? &s->code[s->def[id]] : NULL;
}

#endif
