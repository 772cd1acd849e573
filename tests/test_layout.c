/* test_layout.c: the GLSL structs match the C structs, read from the SPIR-V.
 *
 * Walks the word stream of the six embedded trace shaders (float and double,
 * three tiers of kinds each) and,
 * for every storage buffer of shaders/layout.glsl, checks: the variable
 * exists (a buffer the optimiser dropped is a failure), its Binding equals
 * TP2_BINDING_* and its DescriptorSet 0, the runtime array's ArrayStride
 * equals sizeof the C struct, and each member of the GLSL struct has the
 * C field's name, offset, size and scalar type, with as many members as the
 * C table has fields. The objects and the BVH nodes are texel buffers
 * (utextureBuffer: checked by name, binding and image type; their texel
 * layout is pinned by asserts in gpu_layout.h and bvh.h). The bindings of
 * storage and texel buffers must be exactly 0 .. TP2_BINDING_COUNT - 1
 * but the output (trace.comp) and exactly the image and the output
 * (finish.comp, whose push block is checked too), so a buffer added on
 * one side only shows up.
 * Prints "N passed, M failed" last; exits 0 only when nothing failed. */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "bvh.h"
#include "gpu_layout.h"
#include "tp2_shared.h"

/* The generated headers define the arrays with external linkage, as does
 * render_pipelines.c; rename ours so the two can never clash at link time. */
#define tp2_trace_float test_spv_float
#define tp2_trace_double test_spv_double
#define tp2_trace_float_curved test_spv_float_curved
#define tp2_trace_double_curved test_spv_double_curved
#define tp2_trace_float_basic test_spv_float_basic
#define tp2_trace_double_basic test_spv_double_basic
#define tp2_finish test_spv_finish
#include "finish_spv.h"
#include "trace_double_basic_spv.h"
#include "trace_double_curved_spv.h"
#include "trace_double_spv.h"
#include "trace_float_basic_spv.h"
#include "trace_float_curved_spv.h"
#include "trace_float_spv.h"
#undef tp2_trace_float
#undef tp2_trace_double
#undef tp2_trace_float_curved
#undef tp2_trace_double_curved
#undef tp2_trace_float_basic
#undef tp2_trace_double_basic
#undef tp2_finish

/* SPIR-V opcodes, decorations and storage classes used here (SPIR-V 1.x
 * specification, sections 3.32, 3.20 and 3.7). */
enum {
    OP_NAME = 5,
    OP_MEMBER_NAME = 6,
    OP_TYPE_INT = 21,
    OP_TYPE_FLOAT = 22,
    OP_TYPE_IMAGE = 25,
    OP_TYPE_VECTOR = 23,
    OP_TYPE_ARRAY = 28,
    OP_TYPE_RUNTIME_ARRAY = 29,
    OP_TYPE_STRUCT = 30,
    OP_TYPE_POINTER = 32,
    OP_CONSTANT = 43,
    OP_VARIABLE = 59,
    OP_DECORATE = 71,
    OP_MEMBER_DECORATE = 72,
    DEC_BLOCK = 2,
    DEC_ARRAY_STRIDE = 6,
    DEC_BINDING = 33,
    DEC_DESCRIPTOR_SET = 34,
    DEC_OFFSET = 35,
    SC_UNIFORM_CONSTANT = 0,
    SC_PUSH_CONSTANT = 9,
    SC_STORAGE_BUFFER = 12,
    DIM_BUFFER = 5,
    SPV_MAGIC = 0x07230203,
};

#include "unit.h"

/* One SPIR-V module: its words, checked once so every walk below may
 * trust the word counts. */
struct spv {
    const char *label; /* "float" or "double", for messages */
    const uint32_t *w;
    size_t n;
};

/* Checks the header and that the instructions tile the module exactly.
 * Returns 0, or -1 (reported) when it is malformed. */
static int spv_validate(const struct spv *m)
{
    if (m->n < 5 || m->w[0] != SPV_MAGIC) {
        expect(0, "%s: " "not a SPIR-V module (magic 0x%08x)", m->label,
              m->n ? (unsigned)m->w[0] : 0u);
        return -1;
    }
    size_t i = 5;
    while (i < m->n) {
        uint32_t wc = m->w[i] >> 16;
        if (wc == 0 || wc > m->n - i) {
            expect(0, "%s: " "bad word count %u at word %zu", m->label, (unsigned)wc, i);
            return -1;
        }
        i += wc;
    }
    expect(1, "%s: " "module well formed", m->label);
    return 0;
}

/* Instruction walk: for (i = 5; i < n; i += wc) with op and wc decoded. */
#define SPV_FOR(m, i, op, wc)                                                \
    for (size_t i = 5, wc = 0, op = 0;                                       \
         i < (m)->n && ((wc = (m)->w[i] >> 16), (op = (m)->w[i] & 0xffff), 1); \
         i += wc)

/* Compares the literal string at words [at, end) with s. */
static int spv_str_eq(const struct spv *m, size_t at, size_t end, const char *s)
{
    size_t k = 0;
    for (size_t i = at; i < end; i++) {
        for (int b = 0; b < 4; b++) {
            char c = (char)((m->w[i] >> (8 * b)) & 0xff);
            if (c != s[k])
                return 0;
            if (c == '\0')
                return 1;
            k++;
        }
    }
    return 0; /* unterminated */
}

/* Copies the literal string at words [at, end) into buf (truncated). */
static void spv_str_copy(const struct spv *m, size_t at, size_t end, char *buf,
                         size_t size)
{
    size_t k = 0;
    for (size_t i = at; i < end && k + 1 < size; i++) {
        for (int b = 0; b < 4 && k + 1 < size; b++) {
            char c = (char)((m->w[i] >> (8 * b)) & 0xff);
            if (c == '\0')
                goto done;
            buf[k++] = c;
        }
    }
done:
    buf[k] = '\0';
}

/* Word index of the instruction that defines id as a type, constant or
 * variable, or 0 if none does. */
static size_t spv_def(const struct spv *m, uint32_t id)
{
    SPV_FOR(m, i, op, wc) {
        if (op >= OP_TYPE_INT && op <= OP_TYPE_POINTER && wc >= 2 &&
            m->w[i + 1] == id)
            return i;
        if ((op == OP_VARIABLE || op == OP_CONSTANT) && wc >= 4 &&
            m->w[i + 2] == id)
            return i;
    }
    return 0;
}

/* Opcode of the instruction at word i (0 stands for "none"). */
static uint32_t spv_op(const struct spv *m, size_t i)
{
    return i ? m->w[i] & 0xffff : 0;
}

static uint32_t spv_wc(const struct spv *m, size_t i)
{
    return i ? m->w[i] >> 16 : 0;
}

/* Whether id has OpName name. */
static int spv_named(const struct spv *m, uint32_t id, const char *name)
{
    SPV_FOR(m, i, op, wc)
        if (op == OP_NAME && wc >= 3 && m->w[i + 1] == id &&
            spv_str_eq(m, i + 2, i + wc, name))
            return 1;
    return 0;
}

/* OpMemberName of member k of struct id into buf; "" if none. */
static void spv_member_name(const struct spv *m, uint32_t id, uint32_t k,
                            char *buf, size_t size)
{
    buf[0] = '\0';
    SPV_FOR(m, i, op, wc)
        if (op == OP_MEMBER_NAME && wc >= 4 && m->w[i + 1] == id &&
            m->w[i + 2] == k) {
            spv_str_copy(m, i + 3, i + wc, buf, size);
            return;
        }
}

/* Literal of decoration dec on id, or -1 if absent; 1 for a decoration
 * without a literal (Block). */
static long spv_decoration(const struct spv *m, uint32_t id, uint32_t dec)
{
    SPV_FOR(m, i, op, wc)
        if (op == OP_DECORATE && wc >= 3 && m->w[i + 1] == id &&
            m->w[i + 2] == dec)
            return wc >= 4 ? (long)m->w[i + 3] : 1;
    return -1;
}

/* Literal of member decoration dec on member k of id, or -1 if absent. */
static long spv_member_decoration(const struct spv *m, uint32_t id, uint32_t k,
                                  uint32_t dec)
{
    SPV_FOR(m, i, op, wc)
        if (op == OP_MEMBER_DECORATE && wc >= 5 && m->w[i + 1] == id &&
            m->w[i + 2] == k && m->w[i + 3] == dec)
            return (long)m->w[i + 4];
    return -1;
}

/* The variable of storage class `storage` whose block type is named
 * block, through its pointer type; 0 if none. *count gets how many there
 * are. */
static uint32_t spv_find_variable(const struct spv *m, uint32_t storage, const char *block,
                                  uint32_t *block_type, int *count)
{
    uint32_t found = 0;
    *count = 0;
    SPV_FOR(m, i, op, wc) {
        if (op != OP_VARIABLE || wc < 4 || m->w[i + 3] != storage)
            continue;
        size_t ptr = spv_def(m, m->w[i + 1]);
        if (spv_op(m, ptr) != OP_TYPE_POINTER || spv_wc(m, ptr) < 4)
            continue;
        uint32_t type = m->w[ptr + 3];
        if (spv_named(m, type, block)) {
            found = m->w[i + 2];
            *block_type = type;
            ++*count;
        }
    }
    return found;
}

/* The storage-buffer variable whose block type is named block. */
static uint32_t spv_find_buffer(const struct spv *m, const char *block,
                                uint32_t *block_type, int *count)
{
    return spv_find_variable(m, SC_STORAGE_BUFFER, block, block_type, count);
}

/* Scalar kinds a C field's elements may have. */
enum kind {
    KIND_F32 = 'f',
    KIND_F64 = 'd',
    KIND_I32 = 'i',
    KIND_U32 = 'u',
    KIND_OTHER = '?',
};

/* Element kind of a C field, array or scalar: `+ 0` decays an array to a
 * pointer to its elements and leaves a scalar's type as it is. */
#define KIND_OF(x)                                                          \
    _Generic((x) + 0, float: KIND_F32, float *: KIND_F32,                   \
             double: KIND_F64, double *: KIND_F64, int32_t: KIND_I32,       \
             int32_t *: KIND_I32, uint32_t: KIND_U32, uint32_t *: KIND_U32, \
             default: KIND_OTHER)

/* Size in bytes and scalar kind of a scalar or vector type; 0 if it is
 * neither. */
static size_t spv_type_size(const struct spv *m, uint32_t type, enum kind *kind)
{
    size_t s = spv_def(m, type);
    size_t n = 1;
    if (spv_op(m, s) == OP_TYPE_VECTOR && spv_wc(m, s) >= 4) {
        n = m->w[s + 3];
        s = spv_def(m, m->w[s + 2]);
    }
    uint32_t op = spv_op(m, s);
    if (op == OP_TYPE_FLOAT && spv_wc(m, s) >= 3) {
        uint32_t width = m->w[s + 2];
        *kind = width == 32 ? KIND_F32 : width == 64 ? KIND_F64 : KIND_OTHER;
        return n * width / 8;
    }
    if (op == OP_TYPE_INT && spv_wc(m, s) >= 4) {
        uint32_t width = m->w[s + 2];
        *kind = width != 32 ? KIND_OTHER : m->w[s + 3] ? KIND_I32 : KIND_U32;
        return n * width / 8;
    }
    return 0;
}

/* One C field: name, offset, size, scalar kind. */
struct field {
    const char *name;
    size_t offset, size;
    enum kind kind;
};

/* One storage buffer of layout.glsl and the C struct of its element. */
struct buffer {
    const char *block;  /* GLSL block name: FrameBuf */
    const char *glsl;   /* GLSL struct name: Frame */
    const char *c;      /* C struct name, for messages */
    long binding;       /* TP2_BINDING_* */
    int array;          /* 1: block holds a runtime array of the struct */
    size_t size, align; /* sizeof and _Alignof the C struct */
    const struct field *fields;
    size_t nfields;
};

#define FIELD(T, f)                                                           \
    {#f, offsetof(struct T, f), sizeof(((struct T *)0)->f),                   \
     KIND_OF(((struct T *)0)->f)},

/* Field lists, in declaration order, of gpu_layout_types.h. */
#define FRAME_FIELDS(F, T) F(T, eye) F(T, u) F(T, v) F(T, w) F(T, ambient) \
    F(T, background) F(T, fog) F(T, lens) F(T, area) F(T, limits) F(T, counts)           \
    F(T, geometry) F(T, sampling)
#define WALK_FIELDS(F, T) F(T, where) F(T, color) F(T, signature)
#define WALK_RAY_FIELDS(F, T) F(T, origin) F(T, dir) F(T, info) F(T, doubt)
#define TILE_FIELDS(F, T) F(T, tile_origin) F(T, sample_index) F(T, pass_rays) \
    F(T, walk_capacity) F(T, accept_cut) F(T, tile_rows) F(T, list_length)

#define FIELDS(list, T) static const struct field T##_fields[] = {list(FIELD, T)};
FIELDS(FRAME_FIELDS, gpu_frame_f)
FIELDS(FRAME_FIELDS, gpu_frame_d)
FIELDS(WALK_FIELDS, gpu_walk)  /* no reals: the same in both */
FIELDS(WALK_RAY_FIELDS, gpu_walk_ray_f)
FIELDS(WALK_RAY_FIELDS, gpu_walk_ray_d)
FIELDS(TILE_FIELDS, gpu_tile)

#define BUFFER(block, glsl, T, binding, array)                                \
    {block, glsl, #T, binding, array, sizeof(struct T), _Alignof(struct T),   \
     T##_fields, sizeof T##_fields / sizeof T##_fields[0]}

static const struct buffer float_buffers[] = {
    BUFFER("FrameBuf", "Frame", gpu_frame_f, TP2_BINDING_FRAME, 0),
    BUFFER("WalkBuf", "Walk", gpu_walk, TP2_BINDING_WALKS, 1),
    BUFFER("WalkRayBuf", "WalkRay", gpu_walk_ray_f, TP2_BINDING_WALK_RAYS, 1),
};

static const struct buffer double_buffers[] = {
    BUFFER("FrameBuf", "Frame", gpu_frame_d, TP2_BINDING_FRAME, 0),
    BUFFER("WalkBuf", "Walk", gpu_walk, TP2_BINDING_WALKS, 1),
    BUFFER("WalkRayBuf", "WalkRay", gpu_walk_ray_d, TP2_BINDING_WALK_RAYS, 1),
};

/* The C table itself covers the struct: fields in order, not overlapping,
 * the last one ending where sizeof (rounded to the alignment) says, so a
 * field added to C but not to the table (or to GLSL) shows up. */
static void check_c_table(const char *label, const struct buffer *b)
{
    size_t end = 0;
    int ordered = 1;
    for (size_t k = 0; k < b->nfields; k++) {
        ordered &= b->fields[k].offset >= end;
        end = b->fields[k].offset + b->fields[k].size;
    }
    size_t rounded = (end + b->align - 1) / b->align * b->align;
    expect(ordered && rounded == b->size, "%s: " "struct %s: table fields in order and cover sizeof %zu (end %zu)", label,
          b->c, b->size, end);
}

/* Checks struct id (GLSL b->glsl) member by member against b's C fields. */
static void check_struct(const struct spv *m, uint32_t id,
                         const struct buffer *b)
{
    size_t def = spv_def(m, id);
    expect(spv_op(m, def) == OP_TYPE_STRUCT, "%s: " "%s: element of %s is a struct", m->label, b->glsl, b->block);
    if (spv_op(m, def) != OP_TYPE_STRUCT)
        return;
    expect(spv_named(m, id, b->glsl), "%s: " "%s: element of %s is named %s", m->label,
          b->glsl, b->block, b->glsl);
    size_t members = spv_wc(m, def) - 2;
    expect(members == b->nfields, "%s: " "%s: %zu members in SPIR-V, %zu fields in struct %s", m->label, b->glsl,
          members, b->nfields, b->c);
    for (size_t k = 0; k < members && k < b->nfields; k++) {
        const struct field *f = &b->fields[k];
        char name[64];
        spv_member_name(m, id, (uint32_t)k, name, sizeof name);
        expect(strcmp(name, f->name) == 0, "%s: " "%s member %zu is '%s', C field is '%s'", m->label, b->glsl, k, name,
              f->name);
        long off = spv_member_decoration(m, id, (uint32_t)k, DEC_OFFSET);
        expect(off >= 0 && (size_t)off == f->offset, "%s: " "%s.%s: Offset %ld, offsetof(struct %s, %s) %zu", m->label, b->glsl, name,
              off, b->c, f->name, f->offset);
        enum kind kind = KIND_OTHER;
        size_t size = spv_type_size(m, m->w[def + 2 + k], &kind);
        expect(size == f->size && kind == f->kind, "%s: " "%s.%s: %zu bytes of kind '%c'; C field %zu bytes of kind '%c'", m->label,
              b->glsl, name, size, kind, f->size, f->kind);
    }
}

/* The push-constant block Tile against struct gpu_tile, member by member. */
static void check_push_constants(const struct spv *m)
{
    static const struct buffer tile = BUFFER("Tile", "Tile", gpu_tile, -1, 0);
    uint32_t block = 0;
    int count = 0;
    spv_find_variable(m, SC_PUSH_CONSTANT, "Tile", &block, &count);
    expect(count == 1, "%s: %d push-constant blocks named Tile, want 1", m->label, count);
    if (count == 1)
        check_struct(m, block, &tile);
    check_c_table(m->label, &tile);
}

/* Checks one buffer: variable, binding, set, block, array stride, struct. */
static void check_buffer(const struct spv *m, const struct buffer *b)
{
    uint32_t block = 0;
    int count = 0;
    uint32_t var = spv_find_buffer(m, b->block, &block, &count);
    expect(count == 1, "%s: " "buffer %s: %d storage-buffer variables (optimised away?), want 1", m->label,
          b->block, count);
    if (count != 1)
        return;
    long binding = spv_decoration(m, var, DEC_BINDING);
    expect(binding == b->binding, "%s: " "buffer %s: Binding %ld, want %ld", m->label,
          b->block, binding, b->binding);
    long set = spv_decoration(m, var, DEC_DESCRIPTOR_SET);
    expect(set == 0, "%s: " "buffer %s: DescriptorSet %ld, want 0", m->label,
          b->block, set);
    expect(spv_decoration(m, block, DEC_BLOCK) == 1, "%s: " "buffer %s: decorated Block", m->label, b->block);

    size_t def = spv_def(m, block);
    int ok = spv_op(m, def) == OP_TYPE_STRUCT && spv_wc(m, def) == 3;
    expect(ok, "%s: " "buffer %s: a block of exactly one member", m->label, b->block);
    if (!ok)
        return;
    expect(spv_member_decoration(m, block, 0, DEC_OFFSET) == 0, "%s: " "buffer %s: member at Offset 0", m->label, b->block);
    uint32_t member = m->w[def + 2];
    if (!b->array) {
        check_struct(m, member, b);
        return;
    }
    size_t arr = spv_def(m, member);
    ok = spv_op(m, arr) == OP_TYPE_RUNTIME_ARRAY && spv_wc(m, arr) >= 3;
    expect(ok, "%s: " "buffer %s: member is a runtime array", m->label, b->block);
    if (!ok)
        return;
    long stride = spv_decoration(m, member, DEC_ARRAY_STRIDE);
    expect(stride >= 0 && (size_t)stride == b->size, "%s: " "%s[]: ArrayStride %ld, sizeof(struct %s) %zu", m->label, b->glsl, stride,
          b->c, b->size);
    check_struct(m, m->w[arr + 2], b);
}

/* A buffer that is a runtime array of scalars or vectors (no struct): the
 * image (vec4: the host reads 4 floats per pixel), the extra rows (rvec4:
 * the host writes TP2_REAL[4]) and the texels (uint). */
static void check_plain_array(const struct spv *m, const char *name, long binding,
                              size_t elem_size, enum kind elem_kind, const char *what)
{
    uint32_t block = 0;
    int count = 0;
    uint32_t var = spv_find_buffer(m, name, &block, &count);
    expect(count == 1, "%s: " "buffer %s: %d variables, want 1", m->label, name, count);
    if (count != 1)
        return;
    long b = spv_decoration(m, var, DEC_BINDING);
    expect(b == binding, "%s: " "buffer %s: Binding %ld, want %ld", m->label, name, b, binding);
    expect(spv_decoration(m, var, DEC_DESCRIPTOR_SET) == 0, "%s: " "buffer %s: DescriptorSet 0", m->label, name);
    size_t def = spv_def(m, block);
    size_t arr = spv_op(m, def) == OP_TYPE_STRUCT && spv_wc(m, def) == 3
                     ? spv_def(m, m->w[def + 2])
                     : 0;
    int ok = spv_op(m, arr) == OP_TYPE_RUNTIME_ARRAY && spv_wc(m, arr) >= 3;
    expect(ok, "%s: " "buffer %s: one runtime array member", m->label, name);
    if (!ok)
        return;
    enum kind kind = KIND_OTHER;
    size_t size = spv_type_size(m, m->w[arr + 2], &kind);
    expect(size == elem_size && kind == elem_kind, "%s: " "%s: element is %s (%zu bytes of kind '%c')",
           m->label, name, what, elem_size, elem_kind);
    long stride = spv_decoration(m, m->w[def + 2], DEC_ARRAY_STRIDE);
    expect(stride == (long)elem_size, "%s: " "%s: ArrayStride %ld, want %zu", m->label, name,
           stride, elem_size);
}

/* Member k of struct def is a fixed array of n uints at byte offset; name
 * names it in messages. */
static void check_uint_array(const struct spv *m, uint32_t block, size_t def, uint32_t k,
                             long n, long offset, const char *name)
{
    size_t arr = spv_def(m, m->w[def + 2 + k]);
    int ok = spv_op(m, arr) == OP_TYPE_ARRAY && spv_wc(m, arr) >= 4;
    expect(ok, "%s: %s: a fixed-size array", m->label, name);
    if (!ok)
        return;
    enum kind kind = KIND_OTHER;
    size_t size = spv_type_size(m, m->w[arr + 2], &kind);
    expect(size == sizeof(uint32_t) && kind == KIND_U32, "%s: %s[]: element is uint", m->label, name);
    size_t len = spv_def(m, m->w[arr + 3]);
    long got = spv_op(m, len) == OP_CONSTANT && spv_wc(m, len) >= 4 ? (long)m->w[len + 3] : -1;
    expect(got == n, "%s: %s[]: %ld elements, want %ld", m->label, name, got, n);
    long stride = spv_decoration(m, m->w[def + 2 + k], DEC_ARRAY_STRIDE);
    expect(stride == (long)sizeof(uint32_t), "%s: %s[]: ArrayStride %ld", m->label, name, stride);
    long off = spv_member_decoration(m, block, k, DEC_OFFSET);
    expect(off == offset, "%s: %s: Offset %ld, want %ld", m->label, name, off, offset);
}

/* The stats buffer: uint ray_counts[2 * TP2_STAT_COUNT], then uint
 * counters[TP2_COUNTER_COUNT], at TP2_BINDING_STATS, read by render.c as
 * that many uint32_t words. */
static void check_stats(const struct spv *m)
{
    uint32_t block = 0;
    int count = 0;
    uint32_t var = spv_find_buffer(m, "StatsBuf", &block, &count);
    expect(count == 1, "%s: " "buffer StatsBuf: %d variables, want 1", m->label, count);
    if (count != 1)
        return;
    long binding = spv_decoration(m, var, DEC_BINDING);
    expect(binding == TP2_BINDING_STATS, "%s: " "buffer StatsBuf: Binding %ld, want %d", m->label, binding, TP2_BINDING_STATS);
    expect(spv_decoration(m, var, DEC_DESCRIPTOR_SET) == 0, "%s: " "buffer StatsBuf: DescriptorSet 0", m->label);
    size_t def = spv_def(m, block);
    int ok = spv_op(m, def) == OP_TYPE_STRUCT && spv_wc(m, def) == 4;
    expect(ok, "%s: buffer StatsBuf: two members", m->label);
    if (!ok)
        return;
    check_uint_array(m, block, def, 0, 2 * TP2_STAT_COUNT, 0, "ray_counts");
    check_uint_array(m, block, def, 1, TP2_COUNTER_COUNT,
                     (long)(2 * TP2_STAT_COUNT * sizeof(uint32_t)), "counters");
}

/* A texel buffer of layout.glsl: the uniform variable `name`, at binding
 * in set 0, a utextureBuffer (an image of Dim Buffer, Sampled 1, over
 * 32-bit unsigned integers, with no sampler: a sampled image of Dim Buffer
 * is invalid since SPIR-V 1.6), as the host's R32G32B32A32_UINT views
 * need. */
static void check_texel_buffer(const struct spv *m, const char *name, long binding)
{
    int count = 0;
    size_t at = 0;
    SPV_FOR(m, i, op, wc)
        if (op == OP_VARIABLE && wc >= 4 && m->w[i + 3] == SC_UNIFORM_CONSTANT &&
            spv_named(m, m->w[i + 2], name)) {
            at = i;
            count++;
        }
    expect(count == 1, "%s: texel buffer %s: %d variables, want 1", m->label, name, count);
    if (count != 1)
        return;
    uint32_t var = m->w[at + 2];
    expect(spv_decoration(m, var, DEC_BINDING) == binding &&
               spv_decoration(m, var, DEC_DESCRIPTOR_SET) == 0,
           "%s: texel buffer %s: Binding %ld in set 0", m->label, name, binding);
    size_t ptr = spv_def(m, m->w[at + 1]);
    size_t image = spv_wc(m, ptr) >= 4 ? spv_def(m, m->w[ptr + 3]) : 0;
    size_t elem = spv_op(m, image) == OP_TYPE_IMAGE && spv_wc(m, image) >= 9
                      ? spv_def(m, m->w[image + 2])
                      : 0;
    expect(elem && m->w[image + 3] == DIM_BUFFER && m->w[image + 7] == 1 &&
               spv_op(m, elem) == OP_TYPE_INT && m->w[elem + 2] == 32 && m->w[elem + 3] == 0,
           "%s: texel buffer %s: a utextureBuffer", m->label, name);
}

/* Every storage and texel buffer in the module: bindings exactly those
 * of the mask (bit TP2_BINDING_*), each once, all in set 0, so one the
 * tables above miss is noticed. */
static void check_binding_set(const struct spv *m, unsigned mask)
{
    int seen[TP2_BINDING_COUNT] = {0};
    int stray = 0, misread = 0;
    SPV_FOR(m, i, op, wc) {
        if (op != OP_VARIABLE || wc < 4 ||
            (m->w[i + 3] != SC_STORAGE_BUFFER && m->w[i + 3] != SC_UNIFORM_CONSTANT))
            continue;
        long b = spv_decoration(m, m->w[i + 2], DEC_BINDING);
        if (b >= 0 && b < TP2_BINDING_COUNT) {
            seen[b]++;
            /* texels exactly where render.c binds texel buffers */
            misread += (m->w[i + 3] == SC_UNIFORM_CONSTANT) != (TP2_TEXEL_BINDINGS >> b & 1);
        } else {
            stray++;
        }
    }
    int ok = stray == 0;
    for (int b = 0; b < TP2_BINDING_COUNT; b++)
        ok &= seen[b] == (int)(mask >> b & 1);
    expect(ok, "%s: storage and texel buffers bound exactly once each at 0x%x (%d stray)",
           m->label, mask, stray);
    expect(misread == 0, "%s: %d bindings read otherwise than TP2_TEXEL_BINDINGS says",
           m->label, misread);
}

/* Bindings are distinct and below TP2_BINDING_COUNT, as the host's
 * descriptor set layout assumes. */
static void check_bindings(void)
{
    const long b[] = {TP2_BINDING_FRAME,    TP2_BINDING_LIGHTS,
                      TP2_BINDING_PIGMENTS, TP2_BINDING_FINISHES,
                      TP2_BINDING_OBJECTS,  TP2_BINDING_BVH,
                      TP2_BINDING_EXTRA,    TP2_BINDING_TEXELS,
                      TP2_BINDING_IMAGE,    TP2_BINDING_STATS,
                      TP2_BINDING_STARTED,  TP2_BINDING_WALKS,
                      TP2_BINDING_WALK_RAYS, TP2_BINDING_SIGNATURES,
                      TP2_BINDING_PIXEL_LIST, TP2_BINDING_OUTPUT};
    size_t n = sizeof b / sizeof b[0];
    int ok = n == TP2_BINDING_COUNT;
    for (size_t i = 0; i < n; i++) {
        ok &= b[i] >= 0 && b[i] < TP2_BINDING_COUNT;
        for (size_t j = 0; j < i; j++)
            ok &= b[i] != b[j];
    }
    expect(ok, "%s: " "bindings distinct, 0..TP2_BINDING_COUNT-1", "tp2_shared.h");
}

static void check_module(const struct spv *m, const struct buffer *buffers, size_t n)
{
    if (spv_validate(m) != 0)
        return;
    for (size_t i = 0; i < n; i++) {
        check_c_table(m->label, &buffers[i]);
        check_buffer(m, &buffers[i]);
    }
    check_plain_array(m, "ImageBuf", TP2_BINDING_IMAGE, 4 * sizeof(float), KIND_F32, "vec4");
    check_plain_array(m, "TexelBuf", TP2_BINDING_TEXELS, sizeof(uint32_t), KIND_U32, "uint");
    check_plain_array(m, "StartedBuf", TP2_BINDING_STARTED, sizeof(uint32_t), KIND_U32, "uint");
    check_plain_array(m, "SignatureBuf", TP2_BINDING_SIGNATURES, sizeof(uint32_t), KIND_U32,
                      "uint");
    check_plain_array(m, "PixelListBuf", TP2_BINDING_PIXEL_LIST, sizeof(uint32_t), KIND_U32,
                      "uint");
    check_stats(m);
    check_push_constants(m);
    check_texel_buffer(m, "light_texels", TP2_BINDING_LIGHTS);
    check_texel_buffer(m, "pigment_texels", TP2_BINDING_PIGMENTS);
    check_texel_buffer(m, "finish_texels", TP2_BINDING_FINISHES);
    check_texel_buffer(m, "object_texels", TP2_BINDING_OBJECTS);
    check_texel_buffer(m, "extra_texels", TP2_BINDING_EXTRA);
    check_texel_buffer(m, "node_texels", TP2_BINDING_BVH);
    /* every binding but the finish pass's output */
    check_binding_set(m, ((1u << TP2_BINDING_COUNT) - 1) & ~(1u << TP2_BINDING_OUTPUT));
}

/* finish.comp: the band's pixels in, the output words out, the push block
 * of trace.comp; together with trace.comp's, every binding. */
static void check_finish(const struct spv *m)
{
    if (spv_validate(m) != 0)
        return;
    check_plain_array(m, "ImageBuf", TP2_BINDING_IMAGE, 4 * sizeof(float), KIND_F32, "vec4");
    check_plain_array(m, "OutputBuf", TP2_BINDING_OUTPUT, sizeof(uint32_t), KIND_U32, "uint");
    check_push_constants(m);
    check_binding_set(m, 1u << TP2_BINDING_IMAGE | 1u << TP2_BINDING_OUTPUT);
}

#define SPV(label, words) {label, words, sizeof words / sizeof words[0]}

/* One trace build: its double-ness picks the C tables it must match. */
static void check_trace(const struct spv *m, int is_double)
{
    if (is_double)
        check_module(m, double_buffers, sizeof double_buffers / sizeof double_buffers[0]);
    else
        check_module(m, float_buffers, sizeof float_buffers / sizeof float_buffers[0]);
}

int main(void)
{
    check_bindings();
    const struct spv traces[] = {
        SPV("float basic", test_spv_float_basic),   SPV("double basic", test_spv_double_basic),
        SPV("float", test_spv_float),               SPV("double", test_spv_double),
        SPV("float curved", test_spv_float_curved), SPV("double curved", test_spv_double_curved),
    };
    for (int k = 0; k < 6; k++)
        check_trace(&traces[k], k % 2);
    const struct spv fin = SPV("finish", test_spv_finish);
    check_finish(&fin);
    return unit_report();
}
