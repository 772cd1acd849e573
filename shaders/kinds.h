/* kinds.h: every kind of object and of pigment, one row each. The host's
 * enums (shapes.h, pigments.h), the GPU ids (TP2_SHAPE_*, TP2_PIGMENT_*,
 * in C and in GLSL), each kind's keyword, the shader build that has its
 * code and whether it is flat all come from these lists; what else a new
 * kind needs is in docs/adding-a-kind.md.
 *
 * Included from C and from GLSL (through tp2_shared.h): the lists are
 * macros, and what they expand to below is valid in both. */
#ifndef TP2_KINDS_H
#define TP2_KINDS_H

/* The shader builds (CMakeLists.txt), each with the code of the kinds of
 * its tier and of the tiers below it: a scene gets the least that has all
 * its kinds, so that lavapipe compiles less (render_pipelines.c). */
#define TP2_TIER_BASIC 0   /* trace_*_basic: spheres and planes */
#define TP2_TIER_FACETED 1 /* trace_*: and faces (-DTP2_FACETED) */
#define TP2_TIER_CURVED 2  /* trace_*_curved: and the curved rest (-DTP2_CURVED) */
#define TP2_TIERS 3

/* Object kinds, in the order of the host's enum shape (and of the
 * keywords in messages): X(NAME, keyword, id, tier, flat)
 *   NAME     SHAPE_NAME on the host, TP2_SHAPE_NAME the GPU id
 *   keyword  as a scene writes it (SPEC 3)
 *   id       its GPU id (Object.ids.x, shapes.glsl's dispatch); a mesh is
 *            triangles on the GPU, so it has the triangle's id
 *   tier     TP2_TIER_*, without the prefix
 *   flat     1 where flat wherever a ray meets it (a plane, faces: twins,
 *            shapes.glsl's flat_kind), 0 where curved */
#define TP2_SHAPES(X)                                \
    X(SPHERE,     sphere,     0, BASIC,   0)         \
    X(PLANE,      plane,      1, BASIC,   1)         \
    X(POLYHEDRON, polyhedron, 2, FACETED, 1)         \
    X(BOX,        box,        3, FACETED, 1)         \
    X(CYLINDER,   cylinder,   4, CURVED,  0)         \
    X(CONE,       cone,       5, CURVED,  0)         \
    X(TORUS,      torus,      6, CURVED,  0)         \
    X(QUADRIC,    quadric,    7, CURVED,  0)         \
    X(TRIANGLE,   triangle,   8, FACETED, 1)         \
    X(MESH,       mesh,       8, FACETED, 1)
#define TP2_GPU_SHAPES 9 /* GPU ids 0 .. 8 */

/* Pigment kinds, in the order of the host's enum pigment: X(NAME, keyword,
 * id), as above (Pigment.kind.x, pigments.glsl's). */
#define TP2_PIGMENTS(X)                              \
    X(SOLID,    solid,    0)                         \
    X(CHECKER,  checker,  1)                         \
    X(GRADIENT, gradient, 2)                         \
    X(TEXMAP,   texmap,   3)
#define TP2_GPU_PIGMENTS 4

/* The GPU ids by name: TP2_SHAPE_SPHERE, ..., TP2_PIGMENT_SOLID, ... */
#define TP2_SHAPE_ID_(NAME, keyword, id, tier, flat) TP2_CONST_INT(TP2_SHAPE_##NAME, id)
#define TP2_PIGMENT_ID_(NAME, keyword, id) TP2_CONST_INT(TP2_PIGMENT_##NAME, id)
#ifdef __STDC__ /* C */
#define TP2_CONST_INT(name, value) name = value,
enum tp2_gpu_shape { TP2_SHAPES(TP2_SHAPE_ID_) };
enum tp2_gpu_pigment { TP2_PIGMENTS(TP2_PIGMENT_ID_) };
#else /* GLSL */
#define TP2_CONST_INT(name, value) const int name = value;
TP2_SHAPES(TP2_SHAPE_ID_)
TP2_PIGMENTS(TP2_PIGMENT_ID_)
#endif
#undef TP2_CONST_INT
#undef TP2_SHAPE_ID_
#undef TP2_PIGMENT_ID_

#endif
