/* tp2_shared.h: constants shared by the C host and the GLSL shader.
 *
 * Included from C and from GLSL (GL_GOOGLE_include_directive), so it holds
 * only #defines: no types, no C or GLSL syntax beyond the preprocessor. */
#ifndef TP2_SHARED_H
#define TP2_SHARED_H

/* Descriptor bindings, all storage buffers in set 0. */
#define TP2_BINDING_FRAME 0
#define TP2_BINDING_LIGHTS 1
#define TP2_BINDING_PIGMENTS 2
#define TP2_BINDING_FINISHES 3
#define TP2_BINDING_OBJECTS 4
#define TP2_BINDING_IMAGE 5
#define TP2_BINDING_COUNT 6

/* Enumerations stored in ivec4 fields. */
#define TP2_PIGMENT_SOLID 0
#define TP2_PIGMENT_CHECKER 1
#define TP2_OBJECT_SPHERE 0
#define TP2_OBJECT_PLANE 1

/* SPEC 4: a ray at depth k > 10 returns the background. */
#define TP2_MAX_DEPTH 10

/* Rays of depth 0..10 in a full binary tree: 2^(TP2_MAX_DEPTH + 1) - 1.
 * Rays past the limit are never traced (they add gray directly), so the
 * trace loop pops at most this many rays. */
#define TP2_MAX_RAYS 2047

/* Pending rays on the explicit stack. Depth-first, two children per ray:
 * at most one waiting sibling per depth 1..k plus two children at k + 1,
 * and k + 1 <= TP2_MAX_DEPTH, so TP2_MAX_DEPTH + 1 slots always suffice. */
#define TP2_STACK_SIZE (TP2_MAX_DEPTH + 1)

/* Workgroup: 8x8 pixels, a multiple of lavapipe's 8-wide SIMD and of GPUs'
 * 32/64-wide subgroups. */
#define TP2_GROUP_X 8
#define TP2_GROUP_Y 8

#endif
