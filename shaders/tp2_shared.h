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
#define TP2_BINDING_BVH 5
#define TP2_BINDING_IMAGE 6
#define TP2_BINDING_STATS 7
#define TP2_BINDING_COUNT 8

/* Specialization constants: the pipeline is compiled for the features the
 * scene uses, so a scene without them pays nothing for them. */
#define TP2_SPEC_REFLECT 0   /* bool: some finish has kr > 0 */
#define TP2_SPEC_REFRACT 1   /* bool: some finish has kt > 0 */
#define TP2_SPEC_CHECKER 2   /* bool: some pigment is a checker */
#define TP2_SPEC_PLANES 3    /* bool: the scene has planes */
#define TP2_SPEC_FOG 4       /* bool: fog directive */
#define TP2_SPEC_LENS 5      /* bool: lens directive */
#define TP2_SPEC_AREA 6      /* bool: arealight directive */
#define TP2_SPEC_STATS 7     /* bool: count rays (--stats) */
#define TP2_SPEC_SAMPLES 8   /* int: samples per pixel */
#define TP2_SPEC_SPHERES 9   /* bool: the scene has spheres */
#define TP2_SPEC_BVH 10      /* bool: spheres through the BVH, else a loop */
#define TP2_SPEC_LOOP_GUARD 11 /* bool: count loop steps (lavapipe's limit) */
#define TP2_SPEC_COUNT 12

/* Ray counters in the stats buffer, by kind. */
#define TP2_STAT_CAMERA 0
#define TP2_STAT_SHADOW 1
#define TP2_STAT_REFLECTED 2
#define TP2_STAT_TRANSMITTED 3
#define TP2_STAT_COUNT 4

/* lavapipe ends all loops of a shader invocation (a SIMD vector of lanes)
 * after 65535 iterations in total, silently (Mesa's gallivm,
 * LP_MAX_TGSI_LOOP_ITERATIONS). On CPU devices the shader counts its loop
 * iterations per vector and flags vectors that got this close; the margin
 * covers iterations it does not see (cut-short vectors were measured to
 * count 63500-64600). */
#define TP2_LOOP_LIMIT_NEAR 60000

/* Nodes on the BVH traversal stack (host/bvh.h guarantees the tree fits). */
#define TP2_BVH_STACK 32

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

/* Rays parked on the explicit stack. The walk follows a ray's first child
 * at once and parks the second, so what is parked is at most one sibling
 * per depth 1..TP2_MAX_DEPTH on the path being followed. */
#define TP2_STACK_SIZE TP2_MAX_DEPTH

/* Workgroup: 8x8 pixels, a multiple of lavapipe's 8-wide SIMD and of GPUs'
 * 32/64-wide subgroups. */
#define TP2_GROUP_X 8
#define TP2_GROUP_Y 8

#endif
