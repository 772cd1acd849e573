/* spirv_soft_double.c: the pass's outline: the module read, the
 * library found, then the header, the debug names and annotations (less
 * what went away, plus the new arrays' strides), the global section
 * (spirv_soft_types.c) and the functions (spirv_soft_body.c). */
#include "spirv_soft_double.h"

#include <stdlib.h>
#include <string.h>

#include "spirv_soft.h"
#include "spirv_words.h"

#include <spirv/unified1/spirv.h>

static const char *const library_names[SD_COUNT] = {
    "sd_add", "sd_sub", "sd_mul", "sd_div", "sd_neg", "sd_abs", "sd_sqrt",
    "sd_floor", "sd_fract", "sd_min", "sd_max", "sd_lt", "sd_le", "sd_gt",
    "sd_ge", "sd_eq", "sd_une", "sd_from_float", "sd_to_float", "sd_from_int",
    "sd_to_int"};

/* Instructions of the sections before the types (layout, debug,
 * annotations). */
static bool preamble(uint32_t op)
{
    switch (op) {
    case SpvOpCapability: case SpvOpExtension: case SpvOpExtInstImport:
    case SpvOpMemoryModel: case SpvOpEntryPoint: case SpvOpExecutionMode:
    case SpvOpExecutionModeId: case SpvOpString: case SpvOpSource:
    case SpvOpSourceContinued: case SpvOpSourceExtension: case SpvOpName:
    case SpvOpMemberName: case SpvOpModuleProcessed: case SpvOpDecorate:
    case SpvOpMemberDecorate: case SpvOpDecorationGroup: case SpvOpGroupDecorate:
    case SpvOpGroupMemberDecorate: case SpvOpDecorateId: case SpvOpDecorateString:
    case SpvOpMemberDecorateString: case SpvOpNop:
        return true;
    default:
        return false;
    }
}

/* A function's OpName: library function `which`'s (by the name before
 * its parameters), marked as library when it starts sd_. */
static void read_name(struct soft *s, const uint32_t *w, uint32_t n)
{
    const char *name = (const char *)&w[2];
    if (!memchr(name, 0, (n - 2) * 4) || strncmp(name, "sd_", 3) != 0)
        return;
    s->library[w[1]] = 1;
    size_t stem = strcspn(name, "(");
    for (int i = 0; i < SD_COUNT; i++)
        if (strlen(library_names[i]) == stem && strncmp(name, library_names[i], stem) == 0)
            s->lib[i].id = w[1];
}

/* Whether an instruction the pass reads by word has its words: the
 * declarations it looks into (malformed modules are refused, not read
 * past). */
static bool sized(uint32_t op, uint32_t n)
{
    switch (op) {
    case SpvOpTypeVector:
    case SpvOpTypeMatrix:
    case SpvOpTypeArray:
    case SpvOpTypePointer:
    case SpvOpTypeInt:
        return n == 4;
    case SpvOpTypeRuntimeArray:
    case SpvOpTypeFloat:
        return n == 3 || (op == SpvOpTypeFloat && n == 4);
    case SpvOpTypeFunction:
    case SpvOpTypeImage:
    case SpvOpTypeSampledImage:
    case SpvOpName:
        return n >= 3;
    case SpvOpFunction:
        return n == 5;
    default:
        return true;
    }
}

/* Ids, types, sections, names, layouts. False when malformed. */
static bool read_module(struct soft *s)
{
    const uint32_t *c = s->code;
    for (size_t at = SPIRV_HEADER_WORDS; at < s->words; at += spirv_count(c, at)) {
        const uint32_t *w = &c[at];
        uint32_t op = spirv_op(c, at), n = spirv_count(c, at);
        uint32_t id = soft_result_id(c, at), type = soft_result_type(c, at);
        if (id >= s->bound || type >= s->bound || !sized(op, n))
            return false;
        s->def[id] = at;
        s->type_of[id] = type;
        if (!s->globals && !preamble(op))
            s->globals = at;
        if (!s->functions && op == SpvOpFunction)
            s->functions = at;
        if (op == SpvOpExtInstImport && n >= 3 &&
            strncmp((const char *)&w[2], "GLSL.std.450", (n - 2) * 4) == 0)
            s->glsl = w[1];
        if (op == SpvOpName && n >= 3 && w[1] < s->bound)
            read_name(s, w, n);
        if (((op == SpvOpMemberDecorate && n >= 4 && w[3] == SpvDecorationOffset) ||
             (op == SpvOpDecorate && n >= 3 && w[2] == SpvDecorationArrayStride)) &&
            w[1] < s->bound)
            s->laid_out[w[1]] = 1;
    }
    if (!s->functions)
        s->functions = s->words;
    if (!s->globals)
        s->globals = s->functions;
    return s->globals <= s->functions;
}

/* Each library function's signature; false when one is not what the
 * calls need (one or two pointer parameters). */
static bool read_library(struct soft *s)
{
    for (int i = 0; i < SD_COUNT; i++) {
        struct sd_lib *l = &s->lib[i];
        const uint32_t *fn = soft_def(s, l->id);
        if (!l->id)
            continue;
        const uint32_t *type = fn && (fn[0] & 0xffffu) == SpvOpFunction ? soft_def(s, fn[4]) : NULL;
        if (!type || (type[0] & 0xffffu) != SpvOpTypeFunction || (type[0] >> 16) < 4 ||
            (type[0] >> 16) > 5)
            return false;
        l->ret = fn[1];
        l->params = (type[0] >> 16) - 3;
        for (uint32_t k = 0; k < l->params; k++)
            l->param[k] = type[3 + k];
    }
    return true;
}

/* Whether the library's own code uses 64-bit floats (then they stay),
 * as scalars only: false for anything wider. */
static bool library_doubles(struct soft *s)
{
    bool library = false;
    for (size_t at = s->functions; at < s->words; at += spirv_count(s->code, at)) {
        const uint32_t *w = &s->code[at];
        if (spirv_op(s->code, at) == SpvOpFunction)
            library = spirv_count(s->code, at) == 5 && s->library[w[2]];
        uint32_t type = soft_result_type(s->code, at);
        if (!library || !type || !s->wide[type])
            continue;
        if (type != s->f64)
            return false;
        s->keep_f64 = true;
    }
    return true;
}

/* The sections before the types, less the Float64 capability when no
 * 64-bit float stays, the names and decorations of what went away and
 * NoContraction on what is now a call, plus the new arrays' strides. */
static void write_preamble(struct soft *s, struct words *out)
{
    const uint32_t *c = s->code;
    for (size_t at = SPIRV_HEADER_WORDS; at < s->globals; at += spirv_count(c, at)) {
        const uint32_t *w = &c[at];
        uint32_t op = spirv_op(c, at), n = spirv_count(c, at);
        bool named = op == SpvOpName || op == SpvOpMemberName || op == SpvOpDecorate ||
                     op == SpvOpMemberDecorate || op == SpvOpDecorateId ||
                     op == SpvOpDecorateString || op == SpvOpMemberDecorateString;
        if (op == SpvOpCapability && n == 2 && w[1] == SpvCapabilityFloat64 && !s->keep_f64)
            continue;
        if (named && n >= 2 && w[1] < s->bound && s->dropped[w[1]])
            continue;
        if (op == SpvOpDecorate && n == 3 && w[2] == SpvDecorationNoContraction &&
            w[1] < s->bound && s->replaced[w[1]])
            continue;
        words_inst(out, op, &w[1], n - 1);
    }
    for (size_t i = 0; i < s->strided_count; i++) {
        uint32_t o[3] = {s->strided[i], SpvDecorationArrayStride, 8};
        words_inst(out, SpvOpDecorate, o, 3);
    }
}

static void release(struct soft *s)
{
    free(s->def);
    free(s->type_of);
    free(s->wide);
    free(s->laid_out);
    free(s->library);
    free(s->dropped);
    free(s->replaced);
    free(s->low);
    free(s->low_laid);
    free(s->rec);
    free(s->recs);
    free(s->decls.w);
    free(s->strided);
}

uint32_t *spirv_soft_double(const uint32_t *code, size_t words, size_t *out_words,
                            size_t *sites)
{
    if (!spirv_well_formed(code, words))
        return NULL;
    uint32_t bound = code[3];
    struct soft s = {.code = code, .words = words, .bound = bound, .next = bound,
                     .rec_cap = bound};
    s.def = calloc(bound, sizeof *s.def);
    s.type_of = calloc(bound, sizeof *s.type_of);
    s.wide = calloc(bound, 1);
    s.laid_out = calloc(bound, 1);
    s.library = calloc(bound, 1);
    s.dropped = calloc(bound, 1);
    s.replaced = calloc(bound, 1);
    s.low = calloc(bound, sizeof *s.low);
    s.low_laid = calloc(bound, sizeof *s.low_laid);
    s.rec = calloc(bound, sizeof *s.rec);
    struct words functions = {0}, out = {0};
    bool ok = s.def && s.type_of && s.wide && s.laid_out && s.library && s.dropped &&
              s.replaced && s.low && s.low_laid && s.rec && read_module(&s) &&
              read_library(&s);
    if (ok) {
        soft_mark_wide(&s);
        ok = !s.failed && library_doubles(&s);
    }
    if (ok) {
        soft_plan_types(&s);
        soft_lower_functions(&s, &functions);
        for (int i = 0; i < SPIRV_HEADER_WORDS; i++)
            words_put(&out, code[i]);
        write_preamble(&s, &out);
        soft_emit_globals(&s, &out);
        for (size_t i = 0; i < functions.n; i++)
            words_put(&out, functions.w[i]);
        ok = !s.failed && !functions.failed && !out.failed && !s.decls.failed &&
             s.next <= SPIRV_MAX_BOUND;
    }
    release(&s);
    free(functions.w);
    if (!ok) {
        free(out.w);
        return NULL;
    }
    out.w[3] = s.next;
    *out_words = out.n;
    *sites = s.sites;
    return out.w;
}
