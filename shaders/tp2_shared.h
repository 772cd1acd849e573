/* tp2_shared.h: constants shared by the C host and the GLSL shader.
 *
 * Included from C and from GLSL (GL_GOOGLE_include_directive), so it holds
 * only #defines: no types, no C or GLSL syntax beyond the preprocessor. */
#ifndef TP2_SHARED_H
#define TP2_SHARED_H

/* Descriptor bindings, all in set 0, storage buffers but for the
 * TP2_TEXEL_BINDINGS (below). The scene's inputs come first, the image
 * and the stats after them. */
#define TP2_BINDING_FRAME 0
#define TP2_BINDING_LIGHTS 1
#define TP2_BINDING_PIGMENTS 2
#define TP2_BINDING_FINISHES 3
#define TP2_BINDING_OBJECTS 4
#define TP2_BINDING_BVH 5
#define TP2_BINDING_EXTRA 6  /* rows objects need beyond their record */
#define TP2_BINDING_TEXELS 7 /* texmap images, one RGBA8 word per texel */
#define TP2_BINDING_IMAGE 8
#define TP2_BINDING_STATS 9
#define TP2_BINDING_STARTED 10   /* per band pixel: its walk has begun */
#define TP2_BINDING_WALKS 11     /* walks that go on in the next pass */
#define TP2_BINDING_WALK_RAYS 12 /* their rays: TP2_WALK_RAYS per walk */
#define TP2_BINDING_SIGNATURES 13 /* per band pixel: its decisions (signature.glsl) */
#define TP2_BINDING_PIXEL_LIST 14 /* band pixels a list pass traces again */
#define TP2_BINDING_OUTPUT 15 /* the finished band as the file needs it (finish.comp) */
#define TP2_BINDING_COUNT 16
/* The bindings read as texel buffers (below), one bit each. */
#define TP2_TEXEL_BINDINGS                                                   \
    (1u << TP2_BINDING_LIGHTS | 1u << TP2_BINDING_PIGMENTS |                 \
     1u << TP2_BINDING_FINISHES | 1u << TP2_BINDING_OBJECTS |                \
     1u << TP2_BINDING_BVH | 1u << TP2_BINDING_EXTRA)

/* finish.comp: TP2_FINISH_GROUP pixels per workgroup; its one
 * specialization constant says whether the file takes 8-bit values (one
 * RGBA8 word per pixel, quantized as image_quantize) or floats (4 words). */
#define TP2_FINISH_GROUP 64
#define TP2_FINISH_SPEC_BYTES 0

/* Objects and BVH nodes, the loads of every ray's inner loop, are read as
 * texel buffers of 16-byte texels (utextureBuffer over R32G32B32A32_UINT,
 * bits reinterpreted): on lavapipe a texel fetch loads a whole texel,
 * where a storage-buffer load loops over the SIMD lanes for each word
 * (renders 4-19% faster, docs/decisions.md). An object is
 * TP2_OBJECT_TEXELS_* texels: rows a, b, c of TP2_ROW_TEXELS_* each, then
 * its ids; a node is TP2_NODE_TEXELS: x, y, z, then its links. */
#define TP2_TEXEL_BYTES 16
#define TP2_ROW_TEXELS_F 1
#define TP2_ROW_TEXELS_D 2
#define TP2_OBJECT_TEXELS_F 4
#define TP2_OBJECT_TEXELS_D 8
#define TP2_NODE_TEXELS 4
/* Lights, pigments and finishes, the loads of every hit, are texels too
 * (as above: a storage-buffer load is a loop over lavapipe's lanes): a
 * light is its position (a row: TP2_ROW_TEXELS_*), color and attenuation;
 * a pigment its two colors, rows p and q, then its kind; a finish its
 * phong and optics texels. A double pigment ends in a texel of padding.
 * An object's extra rows are a row of texels each. */
#define TP2_LIGHT_TEXELS_F 3
#define TP2_LIGHT_TEXELS_D 4
#define TP2_PIGMENT_TEXELS_F 5
#define TP2_PIGMENT_TEXELS_D 8
#define TP2_FINISH_TEXELS 2

/* Specialization constants: the pipeline is compiled for the features the
 * scene uses, so a scene without them pays nothing for them. */
#define TP2_SPEC_REFLECT 0    /* bool: some finish in use has kr > 0 */
#define TP2_SPEC_REFRACT 1    /* bool: some finish in use has kt > 0 */
#define TP2_SPEC_PIGMENTS 2   /* int: bit k set when TP2_PIGMENT_k is in use */
#define TP2_SPEC_SHAPES 3     /* int: bit k set when TP2_SHAPE_k is in use */
#define TP2_SPEC_BOUNDED_SHAPE 4 /* int: the one TP2_SHAPE_* of the bounded objects, else -1 */
#define TP2_SPEC_FOG 5        /* bool: fog directive */
#define TP2_SPEC_LENS 6       /* bool: lens directive */
#define TP2_SPEC_AREA 7       /* bool: arealight directive */
#define TP2_SPEC_STATS 8      /* bool: count rays (--stats) */
#define TP2_SPEC_SAMPLES 9    /* int: samples per pixel */
#define TP2_SPEC_BVH 10       /* bool: bounded objects through the BVH, else a loop */
#define TP2_SPEC_LOOP_GUARD 11 /* bool: detect lavapipe's loop limit */
#define TP2_SPEC_UNBOUNDED_SHAPE 12 /* int: the one TP2_SHAPE_* of the unbounded ones, else -1 */
#define TP2_SPEC_WALK 13      /* int: TP2_WALK_*, what a pass does with walks */
#define TP2_SPEC_SIGNATURES 14 /* bool: record each pixel's decisions (signature.glsl) */
#define TP2_SPEC_PIXEL_LIST 15 /* bool: trace the listed pixels, not the whole band */
#define TP2_SPEC_OCCLUDER_HINT 16 /* bool: an arealight sample's shadow ray tests the last one's occluder first */
#define TP2_SPEC_SLABS 17    /* int: slabs a dispatch's rows of workgroups are cut into (render_bands.c) */
#define TP2_SPEC_TWINS 18    /* int: TP2_TWIN_*, which kinds have twins (host/pack/ties.h) */
#define TP2_SPEC_SCENE_SLOTS 19 /* bool: no BVH, slots in scene order (host/pack/scene_pack.c, order_bounded) */
#define TP2_SPEC_SOFT_KEEP 20 /* bool: always false (shaders/soft_double_keep.glsl) */
#define TP2_SPEC_COUNT 21

/* A pixel's signature word (shaders/signature.glsl, host/render/retrace.c): a
 * hash of the float pass's decisions, three bits and the camera rays'
 * shadows. UNSURE: a decision was within float's error of flipping;
 * SENSITIVE: boundaries seen there may move by a pixel's fraction that
 * matters; STOPPED: the walk stopped at its first UNSURE decision, so the
 * hash and SENSITIVE cover only the rays before it. SHADOWS: which point
 * lights the camera rays' hits saw shadowed (a bit per class of lights,
 * j % 4), where rounding may move their edges by a pixel's fraction that
 * matters for shadows. */
#define TP2_SIG_UNSURE 0x80000000u
#define TP2_SIG_SENSITIVE 0x40000000u
#define TP2_SIG_STOPPED 0x20000000u
#define TP2_SIG_SHADOWS 0x1e000000u
#define TP2_SIG_SHADOW_LOW 0x02000000u /* SHADOWS' lowest bit */
#define TP2_SIG_HASH 0x01ffffffu

/* What counts (frame.limits.y and .w; host/render/retrace.h marks): a
 * boundary between two pixels of different hashes is traced again where
 * rounding may move it by at least
 * TP2_SIG_PIXELS of a pixel (to move it across a pixel's center it would
 * have to pass within that distance of it; with S samples per pixel,
 * TP2_SIG_PIXELS / S, and a tenth of that where rounding known to be
 * close to float's error moves it, a ray's own or a hit's fresh
 * rounding: signature.glsl's seen); a decision counts where
 * flipping it could change the pixel by TP2_SIG_STAKE or more (one 8-bit
 * level, for radiance within [0, 1]). docs/accuracy.md has the
 * measurements that chose them. */
#define TP2_SIG_PIXELS 0.1
#define TP2_SIG_STAKE (1.0 / 255.0)

/* Ray counters in the stats buffer, by kind. */
#define TP2_STAT_CAMERA 0
#define TP2_STAT_SHADOW 1
#define TP2_STAT_REFLECTED 2
#define TP2_STAT_TRANSMITTED 3
#define TP2_STAT_COUNT 4

/* lavapipe ends all loops of a shader invocation (a SIMD vector of lanes)
 * after 65535 iterations in total, silently (Mesa's gallivm,
 * LP_MAX_TGSI_LOOP_ITERATIONS): a deep ray tree, or a ray meeting many
 * objects, needs more. On CPU devices each invocation ends with a loop of
 * TP2_CANARY_STEPS iterations (a count read from the frame, so no
 * compiler can unroll it): if it stops early, the invocation was cut and
 * writes nothing. Its pixel sample is then traced again in passes of at
 * most a given number of rays (TP2_WALK_*): a walk that has more to do
 * saves its state and goes on in the next pass, and a pass that is cut is
 * run again with fewer rays. */
#define TP2_CANARY_STEPS 2

/* Counters in the stats buffer, after the ray counts. */
#define TP2_COUNTER_CUT 0        /* invocations cut short in this pass */
#define TP2_COUNTER_WALKS 1      /* walks saved (may exceed the capacity) */
#define TP2_COUNTER_UNFINISHED 2 /* walks that go on after this pass */
#define TP2_COUNTER_WAITING 3    /* walks with no room to be saved */
#define TP2_COUNTER_LOST 4       /* samples cut even one ray at a time */
#define TP2_COUNTER_COUNT 5

/* Passes, each a pipeline of its own (TP2_SPEC_WALK): whole trees in one
 * go, as GPUs always do and CPU devices first try; else walks started
 * with at most a number of rays, and saved ones gone on with. The walk
 * pipelines are made only for scenes whose trees lavapipe cut. */
#define TP2_WALK_WHOLE 0
#define TP2_WALK_START 1
#define TP2_WALK_CONTINUE 2
#define TP2_WALK_KINDS 3

/* Nodes on the BVH traversal stack (host/pack/bvh.h guarantees the tree fits). */
#define TP2_BVH_STACK 32

/* A BVH child link (host/pack/bvh.h, struct bvh_gpu_node): a negative link is
 * the inner node -link; a link >= 0 a leaf over the objects from
 * link >> TP2_BVH_LEAF_BITS, (link & TP2_BVH_LEAF_MASK) + 1 of them. */
#define TP2_BVH_LEAF_BITS 3
#define TP2_BVH_LEAF_MASK 7
#define TP2_BVH_LEAF_MAX 8

/* How far, at most, across a ray the float pass's edge test reaches
 * (shaders/shapes.glsl, edge_graze), in units of the scene's scale
 * (Frame.eye.w); that pass tests the BVH's boxes grown by 4 times that
 * (intersect.glsl, box_ray), so that an edge passed that near is
 * tested through the BVH as by a plain loop. */
#define TP2_EDGE_REACH (1.0 / 4096.0)

/* Shape and pigment kinds and their GPU ids (TP2_SHAPE_*, TP2_PIGMENT_*)
 * are in kinds.h. */

/* Object.ids.x holds the shape kind in its low bits and, above them, this
 * flag: some number of a flat object's record or extra rows is not a
 * float, so float's surface may not be double's (a face at 0.3 lies at
 * 0.30000001192092896 in float). Set in the float scene only;
 * shaders/pigments.glsl trusts a flat face to lie exactly on a cell face
 * only without it. */
#define TP2_SHAPE_MASK 0xf
#define TP2_SHAPE_INEXACT 0x10
/* And this one: some face of the flat object lies so near another
 * object's face, without being on the same plane, that float may find
 * both at one distance where double does not (host/pack/twins.h). Set in the
 * float scene of --precision auto only; shaders/shapes.glsl's
 * coincident_faces takes equal distances for coincident faces only
 * without it. */
#define TP2_SHAPE_NEAR_TWIN 0x20
/* A triangle lies in another object's face: it is met by plane_t's
 * arithmetic on that face's plane, kept in extra row ids.w, so that both
 * give one distance (host/pack/ties.h). A cap that does (a twin cap) is
 * met so too, from its record (shaders/shapes.glsl, hit_tapered). The
 * code for each is compiled only where TP2_SPEC_TWINS has its bit
 * (TP2_TWIN_CAPS, TP2_TWIN_TRIANGLES). */
#define TP2_TWIN_CAPS 1
#define TP2_TWIN_TRIANGLES 2
#define TP2_SHAPE_TWIN 0x40
/* Above the flags: the object's place in the scene file (SPEC 4, Ties:
 * of two objects hit at one distance, the one listed first is the hit),
 * up to TP2_ORDER_MAX (later ones share it, and the layout decides
 * between them). A mesh's triangles share their mesh's. Without a BVH,
 * where every slot is in scene order, it is a key in the same order
 * that the slots give: 2 slot + 1 for a bounded primitive, 2 b for an
 * unbounded one listed after b bounded primitives (intersect.glsl,
 * trace_plain, compares an unbounded object's with a bounded hit's slot). */
#define TP2_SHAPE_ORDER_SHIFT 8
#define TP2_ORDER_MAX 0xffffff

/* Most faces of one polyhedron: its face count travels as a float, exact
 * to 2^24, and every ray that meets it loops over all of them. */
#define TP2_MAX_FACES 4096

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

/* Rays a saved walk keeps: the current one and those parked. */
#define TP2_WALK_RAYS (TP2_STACK_SIZE + 1)

/* Workgroup: 8x8 pixels, a multiple of lavapipe's 8-wide SIMD and of GPUs'
 * 32/64-wide subgroups. */
#define TP2_GROUP_X 8
#define TP2_GROUP_Y 8

/* The pixels 8 lanes of one lavapipe SIMD batch trace together, in the
 * band pass (trace.comp, pixel_in_group) and in the retrace pass's list
 * (host/render/retrace.c): a 4 x 2 block, whose rays diverge less than a row of
 * 8 pixels' (docs/decisions.md). */
#define TP2_LANE_BLOCK_X 4
#define TP2_LANE_BLOCK_Y 2

#endif
