/* gpu_layout.h: the GPU structs as C sees them, in float and double.
 *
 * The float structs feed the default shader, the double ones the reference
 * shader (--precision double). Their GLSL twin is shaders/layout.glsl; the
 * asserts below pin every size and offset to the std430 rules. */
#ifndef TP2_GPU_LAYOUT_H
#define TP2_GPU_LAYOUT_H

#include <stddef.h>
#include <stdint.h>

#include "tp2_shared.h"

#define TP2_CAT_(a, b) a##b
#define TP2_CAT(a, b) TP2_CAT_(a, b)

#define TP2_REAL float
#define TP2_SUFFIX _f
#include "gpu_layout_types.h"
#undef TP2_REAL
#undef TP2_SUFFIX

#define TP2_REAL double
#define TP2_SUFFIX _d
#include "gpu_layout_types.h"
#undef TP2_REAL
#undef TP2_SUFFIX

/* A saved walk: no reals, so one struct serves both shaders. */
struct gpu_walk {
    _Alignas(16) int32_t where[4]; /* pixel x, y; rays parked (-1: done); rays traced */
    _Alignas(16) float color[4];   /* rgb so far, pruning budget left */
    uint32_t signature;            /* the decisions so far (signature.glsl) */
};

/* What one dispatch covers: layout.glsl's push-constant block Tile (the
 * field names are the GLSL members'): a band of rows from tile_origin (or
 * the listed pixels of it), one sample, one pass of its walks. */
struct gpu_tile {
    int32_t tile_origin[2];
    int32_t sample_index;
    int32_t pass_rays;     /* rays each walk may trace in this pass */
    int32_t walk_capacity; /* walks the walk buffers hold */
    int32_t accept_cut;    /* 1: pass_rays is 1 and still cut: keep what there is */
    int32_t tile_rows;     /* rows of the band */
    int32_t list_length;   /* pixels in the pixel list */
};

#define TP2_LAYOUT(type, field, offset) \
    _Static_assert(offsetof(struct type, field) == (offset), #type "." #field)
#define TP2_SIZE(type, size) \
    _Static_assert(sizeof(struct type) == (size), "sizeof " #type)

/* float: vec4 everywhere, 16-byte aligned. */
TP2_LAYOUT(gpu_frame_f, eye, 0);
TP2_LAYOUT(gpu_frame_f, u, 16);
TP2_LAYOUT(gpu_frame_f, v, 32);
TP2_LAYOUT(gpu_frame_f, w, 48);
TP2_LAYOUT(gpu_frame_f, ambient, 64);
TP2_LAYOUT(gpu_frame_f, background, 80);
TP2_LAYOUT(gpu_frame_f, fog, 96);
TP2_LAYOUT(gpu_frame_f, lens, 112);
TP2_LAYOUT(gpu_frame_f, area, 128);
TP2_LAYOUT(gpu_frame_f, limits, 144);
TP2_LAYOUT(gpu_frame_f, counts, 160);
TP2_LAYOUT(gpu_frame_f, geometry, 176);
TP2_LAYOUT(gpu_frame_f, sampling, 192);
TP2_SIZE(gpu_frame_f, 208);
TP2_LAYOUT(gpu_light_f, pos, 0);
TP2_LAYOUT(gpu_light_f, color, 16);
TP2_LAYOUT(gpu_light_f, att, 32);
TP2_SIZE(gpu_light_f, 48);
TP2_LAYOUT(gpu_pigment_f, color1, 0);
TP2_LAYOUT(gpu_pigment_f, color2, 16);
TP2_LAYOUT(gpu_pigment_f, p, 32);
TP2_LAYOUT(gpu_pigment_f, q, 48);
TP2_LAYOUT(gpu_pigment_f, kind, 64);
TP2_SIZE(gpu_pigment_f, 80);
TP2_LAYOUT(gpu_finish_f, phong, 0);
TP2_LAYOUT(gpu_finish_f, optics, 16);
TP2_SIZE(gpu_finish_f, 32);
TP2_LAYOUT(gpu_object_f, a, 0);
TP2_LAYOUT(gpu_object_f, b, 16);
TP2_LAYOUT(gpu_object_f, c, 32);
TP2_LAYOUT(gpu_object_f, ids, 48);
TP2_SIZE(gpu_object_f, 64);

/* double: dvec4 is 32 bytes and 32-aligned, so structs round up to 32. */
TP2_LAYOUT(gpu_frame_d, eye, 0);
TP2_LAYOUT(gpu_frame_d, u, 32);
TP2_LAYOUT(gpu_frame_d, v, 64);
TP2_LAYOUT(gpu_frame_d, w, 96);
TP2_LAYOUT(gpu_frame_d, ambient, 128);
TP2_LAYOUT(gpu_frame_d, background, 144);
TP2_LAYOUT(gpu_frame_d, fog, 160);
TP2_LAYOUT(gpu_frame_d, lens, 176);
TP2_LAYOUT(gpu_frame_d, area, 192);
TP2_LAYOUT(gpu_frame_d, limits, 208);
TP2_LAYOUT(gpu_frame_d, counts, 224);
TP2_LAYOUT(gpu_frame_d, geometry, 240);
TP2_LAYOUT(gpu_frame_d, sampling, 256);
TP2_SIZE(gpu_frame_d, 288);
TP2_LAYOUT(gpu_light_d, pos, 0);
TP2_LAYOUT(gpu_light_d, color, 32);
TP2_LAYOUT(gpu_light_d, att, 48);
TP2_SIZE(gpu_light_d, 64);
TP2_LAYOUT(gpu_pigment_d, color1, 0);
TP2_LAYOUT(gpu_pigment_d, color2, 16);
TP2_LAYOUT(gpu_pigment_d, p, 32);
TP2_LAYOUT(gpu_pigment_d, q, 64);
TP2_LAYOUT(gpu_pigment_d, kind, 96);
TP2_SIZE(gpu_pigment_d, 128);
TP2_LAYOUT(gpu_finish_d, phong, 0);
TP2_LAYOUT(gpu_finish_d, optics, 16);
TP2_SIZE(gpu_finish_d, 32);
TP2_LAYOUT(gpu_object_d, a, 0);
TP2_LAYOUT(gpu_object_d, b, 32);
TP2_LAYOUT(gpu_object_d, c, 64);
TP2_LAYOUT(gpu_object_d, ids, 96);
TP2_SIZE(gpu_object_d, 128);

/* Objects are read as texels (tp2_shared.h): rows of TP2_ROW_TEXELS_*
 * texels each, ids after the three rows, TP2_OBJECT_TEXELS_* in all. */
#define TP2_TEXEL_LAYOUT(T, rows, texels)                                         \
    _Static_assert(offsetof(struct T, b) == TP2_TEXEL_BYTES * (rows) &&           \
                       offsetof(struct T, c) == TP2_TEXEL_BYTES * 2 * (rows) &&   \
                       offsetof(struct T, ids) == TP2_TEXEL_BYTES * 3 * (rows) && \
                       sizeof(struct T) == TP2_TEXEL_BYTES * (texels),            \
                   #T " as the shader's texels")
TP2_TEXEL_LAYOUT(gpu_object_f, TP2_ROW_TEXELS_F, TP2_OBJECT_TEXELS_F);
TP2_TEXEL_LAYOUT(gpu_object_d, TP2_ROW_TEXELS_D, TP2_OBJECT_TEXELS_D);

/* Lights, pigments and finishes too (tp2_shared.h; layout.glsl's
 * load_light, pigment_* and load_finish read them so). */
#define TP2_LIGHT_TEXEL_LAYOUT(T, rows, texels)                                   \
    _Static_assert(offsetof(struct T, color) == TP2_TEXEL_BYTES * (rows) &&       \
                       offsetof(struct T, att) == TP2_TEXEL_BYTES * ((rows) + 1) && \
                       sizeof(struct T) == TP2_TEXEL_BYTES * (texels),            \
                   #T " as the shader's texels")
#define TP2_PIGMENT_TEXEL_LAYOUT(T, rows, texels)                                  \
    _Static_assert(offsetof(struct T, color2) == TP2_TEXEL_BYTES &&                \
                       offsetof(struct T, p) == TP2_TEXEL_BYTES * 2 &&             \
                       offsetof(struct T, q) == TP2_TEXEL_BYTES * (2 + (rows)) &&  \
                       offsetof(struct T, kind) == TP2_TEXEL_BYTES * (2 + 2 * (rows)) && \
                       sizeof(struct T) == TP2_TEXEL_BYTES * (texels),             \
                   #T " as the shader's texels")
TP2_LIGHT_TEXEL_LAYOUT(gpu_light_f, TP2_ROW_TEXELS_F, TP2_LIGHT_TEXELS_F);
TP2_LIGHT_TEXEL_LAYOUT(gpu_light_d, TP2_ROW_TEXELS_D, TP2_LIGHT_TEXELS_D);
TP2_PIGMENT_TEXEL_LAYOUT(gpu_pigment_f, TP2_ROW_TEXELS_F, TP2_PIGMENT_TEXELS_F);
TP2_PIGMENT_TEXEL_LAYOUT(gpu_pigment_d, TP2_ROW_TEXELS_D, TP2_PIGMENT_TEXELS_D);
/* An object's extra rows (polyhedron faces, a quadric's center) are
 * 4-vectors of reals, a row of texels each. */
_Static_assert(4 * sizeof(float) == TP2_TEXEL_BYTES * TP2_ROW_TEXELS_F &&
                   4 * sizeof(double) == TP2_TEXEL_BYTES * TP2_ROW_TEXELS_D,
               "an extra row as the shader's texels");
_Static_assert(offsetof(struct gpu_finish_f, optics) == TP2_TEXEL_BYTES &&
                   sizeof(struct gpu_finish_f) == TP2_TEXEL_BYTES * TP2_FINISH_TEXELS &&
                   offsetof(struct gpu_finish_d, optics) == TP2_TEXEL_BYTES &&
                   sizeof(struct gpu_finish_d) == TP2_TEXEL_BYTES * TP2_FINISH_TEXELS,
               "gpu_finish as the shader's texels");

TP2_LAYOUT(gpu_walk_ray_f, origin, 0);
TP2_LAYOUT(gpu_walk_ray_f, dir, 16);
TP2_LAYOUT(gpu_walk_ray_f, info, 32);
TP2_LAYOUT(gpu_walk_ray_f, doubt, 48);
TP2_SIZE(gpu_walk_ray_f, 64);
TP2_LAYOUT(gpu_walk_ray_d, origin, 0);
TP2_LAYOUT(gpu_walk_ray_d, dir, 32);
TP2_LAYOUT(gpu_walk_ray_d, info, 64);
TP2_LAYOUT(gpu_walk_ray_d, doubt, 80);
TP2_SIZE(gpu_walk_ray_d, 96);
TP2_LAYOUT(gpu_walk, where, 0);
TP2_LAYOUT(gpu_walk, color, 16);
TP2_LAYOUT(gpu_walk, signature, 32);
TP2_SIZE(gpu_walk, 48);
TP2_LAYOUT(gpu_tile, tile_origin, 0);
TP2_LAYOUT(gpu_tile, list_length, 28);
TP2_SIZE(gpu_tile, 32);

#undef TP2_LAYOUT
#undef TP2_SIZE

#endif
