// intersect.glsl: a ray against the whole scene: the bounded objects
// through the BVH (or a plain loop when there are few), then the unbounded
// ones (planes, quadrics other than ellipsoids, open polyhedra). Each
// kind's own test is in shapes.glsl.

const real NO_HIT = real(3.0e38);
const float NO_GRAZE = 3.0e38; // Hit.graze before any sphere was passed

struct Hit {
    real t;
    int object; // -1: none
    int part;   // which part of it (a face, a cap): shapes.glsl
    real next;  // under SIGNATURES: the nearest other crossing tested (signature.glsl),
    int next_object; // and its object
    int next_part;   // and part
    float graze; // and how near it passed a sphere's surface (shapes.glsl: hit_sphere)
    float edge;  // and where it passed a flat solid's or a triangle's edge
                 // within its doubt (shapes.glsl: edge_graze, exit_graze,
                 // triangle_graze), if nearer than the hit
    uint key;    // file_key(object) where test_object needs it (BY_KEYS)
};

// The surface a ray starts on, which rounding must not let it hit again
// at t ~ 0, and whether the ray goes into that object's inside; each kind
// decides what that rules out (shapes.glsl).
struct Start {
    int object; // -1: none
    bool inward;
};

const Start NOWHERE = Start(-1, false);

#include "shapes.glsl"

// A ray tests BVH boxes in float in both builds (the boxes are floats,
// and float's box tests are the cheaper on lavapipe's SIMD: docs/decisions.md). BoxRay is the ray as they see it.
// Each slab's t carries two roundings of relative size 2^-24, so the exit
// is widened by 2^-21 of itself: a ray grazing a box's face far from the
// camera must not miss it (Ize, "Robust BVH Ray Traversal"). The double
// build's ray, rounded to float, may also have moved: its origin by 2^-24
// of itself, which moves each slab by that times 1/d (slack, doubled for
// safety), and 1/d by 2^-24 of itself (entry narrowed by 2^-21 too); so
// no box the double ray meets is missed. The float build's slack is 0
// and its entry is not narrowed: its tests are as they were. Under
// SIGNATURES (mixed's float pass) each box is tested grown by 4 times
// TP2_EDGE_REACH of the scene's scale, so that an edge passed within the
// edge test's reach is tested through the BVH as by a plain loop; the
// retrace, in double, tests the boxes as they are, as the double build
// does. (Grown in the tree both read, they made the retrace of a scene
// seen from far away, where the growth dwarfs the objects, test every
// object for every ray: 47 times the double build's render.)
const float BOX_WIDEN = 4.76837158203125e-7; // 2^-21: a slab's two roundings, with room
const float ORIGIN_ROUNDING = 1.1920928955078125e-7; // 2^-23: twice float's 2^-24

// The origin is kept per slab (lo, hi, lo, hi as a node's vec4s), so
// that the growth costs nothing per node: a box grown by g is the box
// seen from an origin moved by g toward each slab.
struct BoxRay {
    vec4 ox, oy, oz;
    vec3 inv_d, slack;
    float narrow;
};

BoxRay box_ray(rvec3 o, rvec3 inv_d)
{
    vec3 of = vec3(o), inv = vec3(inv_d);
#ifdef TP2_DOUBLE
    vec3 slack = min(abs(of) * ORIGIN_ROUNDING * abs(inv), vec3(1e37));
    float narrow = 1.0 - BOX_WIDEN;
#else
    vec3 slack = vec3(0.0);
    float narrow = 1.0;
#endif
    if (!SIGNATURES)
        return BoxRay(vec4(of.x), vec4(of.y), vec4(of.z), inv, slack, narrow);
    vec4 grow = 4.0 * most_reach() * vec4(1.0, -1.0, 1.0, -1.0);
    return BoxRay(of.x + grow, of.y + grow, of.z + grow, inv, slack, narrow);
}

// Where the ray enters each of a node's two children's boxes (x, y),
// if before tmax; else NO_HIT. Both boxes at once: one vec4 per axis
// holds (left lo, left hi, right lo, right hi).
rvec2 children_entry(BvhNode n, BoxRay r, float tmax)
{
    vec4 tx = (n.x - r.ox) * r.inv_d.x;
    vec4 ty = (n.y - r.oy) * r.inv_d.y;
    vec4 tz = (n.z - r.oz) * r.inv_d.z;
    vec2 enter = max(max(min(tx.xz, tx.yw) - r.slack.x, min(ty.xz, ty.yw) - r.slack.y),
                     max(min(tz.xz, tz.yw) - r.slack.z, vec2(0.0))) *
                 r.narrow;
    vec2 leave = min(min(max(tx.xz, tx.yw) + r.slack.x, max(ty.xz, ty.yw) + r.slack.y),
                     max(tz.xz, tz.yw) + r.slack.z) *
                 (1.0 + BOX_WIDEN);
    return mix(rvec2(NO_HIT), rvec2(enter), lessThanEqual(enter, min(leave, vec2(tmax))));
}

// 1 / d with zero components replaced by a tiny positive number, so the
// slab test never computes 0 * inf.
rvec3 safe_inverse(rvec3 d)
{
    const real tiny = real(1e-30);
    return real(1.0) / mix(d, rvec3(tiny), lessThan(abs(d), rvec3(tiny)));
}

// Object i's place in the scene file, or without a BVH a key in the
// same order (tp2_shared.h, TP2_SHAPE_ORDER_SHIFT).
uint file_key(int i)
{
    return uint(object_ids(i).x) >> TP2_SHAPE_ORDER_SHIFT;
}

// How test_object tells which of two objects at one distance is listed
// first in the scene file. A constant at each call, as lavapipe runs
// every arm: what a rule reads, it reads for every object tested.
const int BY_KEYS = 0;        // i's key, read where its kind is (shape_of),
                              // against the hit's, kept in h.key; then the
                              // layout (a mesh's own triangles, and past
                              // TP2_ORDER_MAX)
const int IN_FILE_ORDER = 1;  // slots tested in scene order (trace_plain):
                              // the hit so far was listed first
const int AFTER_BOUNDED = 2;  // an unbounded slot, tested after the bounded
                              // ones in scene order (trace_plain): its key
                              // against a bounded hit's slot

// Tests object i, of kind `kind`, and keeps the nearer hit in h; whether
// an any-hit ray has found one. An exact tie goes to the object listed
// first in the scene file (SPEC 4), whatever order the BVH or a plain
// loop tests them in (it differs where mixed's float pass grows boxes);
// `order` says how that is told. An any-hit search takes any hit.
bool test_object(inout Hit h, int i, int kind, rvec3 o, rvec3 d, Start start, bool any_hit,
                 vec2 doubt, int order)
{
    int part;
    float edge = NO_EDGE;
    real t = hit_object(i, kind, o, d, i == start.object, start.inward, doubt, part, h.graze,
                        edge);
    bool grazed = SIGNATURES && edge < NO_EDGE;
    if (grazed && edge <= float(h.t) + most_reach())
        h.edge = min(h.edge, edge);
    uint key = order == BY_KEYS ? file_key(i) : 0u;
    bool first_listed; // of i and h.object, if at one distance
    if (order == IN_FILE_ORDER)
        first_listed = false;
    else if (order == AFTER_BOUNDED)
        first_listed = h.object < frame.geometry.x &&
                       int(file_key(i)) < min(2 * h.object + 1, TP2_ORDER_MAX);
    else
        first_listed = h.object >= 0 && (key < h.key || (key == h.key && i < h.object));
    bool nearer = (t < h.t || (t == h.t && first_listed)) && !(any_hit && grazed);
    if (nearer) {
        h = Hit(t, i, part, h.t, h.object, h.part, h.graze, any_hit ? NO_EDGE : h.edge, key);
    } else if (SIGNATURES && t < h.next) {
        h.next = t;
        h.next_object = i;
        h.next_part = part;
    }
    return nearer && any_hit;
}

// Without a BVH, where the bounded objects are of one kind and the
// unbounded ones of one too (or none): a loop per kind, each with its
// kind a constant, as lavapipe runs every arm of hit_object's chain of
// kinds for each object it tests (one loop where both are one kind). A
// `first` of the first loop's objects is tested first (k = -1); another
// in its turn only (the hint is a guess: any occluder answers the same).
// Without mixed's float pass, every slot is in scene order (SCENE_SLOTS:
// host/pack/scene_pack.c, order_bounded): a loop over the bounded slots
// alone tests them in file order, and the unbounded loop compares one key
// per object with a bounded hit's slot (test_object's orders).
Hit trace_plain(rvec3 o, rvec3 d, Start start, real tmax, bool any_hit, int first, vec2 doubt)
{
    Hit h = Hit(tmax, -1, 0, tmax, -1, 0, NO_GRAZE, NO_EDGE, 0u);
    const bool two_kinds = UNBOUNDED_SHAPE >= 0 && UNBOUNDED_SHAPE != BOUNDED_SHAPE;
    const bool bounded_only = two_kinds || UNBOUNDED_SHAPE < 0;
    int total = frame.geometry.x + frame.geometry.y;
    int split = two_kinds ? frame.geometry.x : total;
    bool done = false;
    int k = OCCLUDER_HINT && HAS_AREA && first >= 0 && first < split ? -1 : 0;
    for (; k < split && !done; ++k)
        done = test_object(h, k < 0 ? first : k, BOUNDED_SHAPE, o, d, start, any_hit, doubt,
                           SCENE_SLOTS && bounded_only ? IN_FILE_ORDER : BY_KEYS);
    if (two_kinds)
        for (int i = split; i < total && !done; ++i)
            done = test_object(h, i, UNBOUNDED_SHAPE, o, d, start, any_hit, doubt,
                               SCENE_SLOTS ? AFTER_BOUNDED : BY_KEYS);
    return h;
}

// The nearest object with 0 < t < tmax, or, if any_hit, any one of them,
// for a ray from o along unit d that starts on `start`; object `first`
// (unless -1) is tested before all others, as a likely any-hit. Bounded
// objects sit in BVH order at the start of objects[], the unbounded ones
// after them.
//
// Under SIGNATURES, doubt (x: how far the ray's origin may be off, y: its
// direction, radians; shapes.glsl, edge_graze) says which edges it passes
// within its error of: Hit.edge is the nearest such, if nearer than the
// hit or at most TP2_EDGE_REACH of the scene's scale beyond it (kept
// whatever the order objects are tested in: an edge is kept against the
// nearest hit so far; trace_step counts one beyond the hit within the
// hit distance's doubt). An any-hit search does not stop at an occluder
// whose edge it passes so near: only a sure one settles the shadow (and
// clears Hit.edge), else Hit.edge says that rounding may have decided it.
//
// Without a BVH, and with the bounded objects' kind known, trace_plain does
// it. Otherwise one loop tests one object per step, and between the ranges of
// objects to test, walks the BVH to its next leaf (nearest first), the
// unbounded objects last; with few bounded objects (no BVH: a plain loop is
// faster) the range is all of them at once and the loop is a plain loop. The
// object test appears once, so each kind's code is compiled once (see
// trace_step). A descent from a node to the leaf it leads to is one step (an
// inner loop): lanes descending no longer pay an object test per node for the
// lanes testing objects beside them (docs/decisions.md: 11% on BVH scenes
// on lavapipe; testing a leaf's objects in an inner loop as well, or popping
// there too, was no better).
Hit trace_scene(rvec3 o, rvec3 d, Start start, real tmax, bool any_hit, int first,
                vec2 doubt)
{
    if (!USE_BVH && BOUNDED_SHAPE >= 0)
        return trace_plain(o, d, start, tmax, any_hit, first, doubt);
    Hit h = Hit(tmax, -1, 0, tmax, -1, 0, NO_GRAZE, NO_EDGE, 0u);
    int bounded = frame.geometry.x;
    int total = bounded + frame.geometry.y;
    BoxRay box = box_ray(o, USE_BVH ? safe_inverse(d) : d);
    int stack_node[TP2_BVH_STACK];
    real stack_t[TP2_BVH_STACK];
    int sp = 0;
    int node = USE_BVH && first < 0 ? 0 : -1; // the root: its children's boxes are tested
    int i = max(first, 0); // objects [i, end) come next
    int end = first >= 0 ? first + 1 : USE_BVH ? 0 : total;
    bool all_left = first >= 0; // object `first` alone, then the root (or all objects)
    bool unbounded_left = true;
    // Each object is tested once (a one-leaf tree's twice, `first` twice),
    // each node visited and each link popped at most once, the first and
    // the unbounded ranges set once.
    int steps = total + TP2_BVH_LEAF_MAX + 2 * frame.geometry.z + 4;
    for (int step = 0; step < steps; ++step) {
        int link = 0;       // a child to enter after this step, if `enter`
        bool enter = false;
        if (i < end) {
            if (test_object(h, i, shape_of(i), o, d, start, any_hit, doubt, BY_KEYS))
                break;
            ++i;
        } else if (USE_BVH && node >= 0) { // without a BVH these arms compile out
            // Down through inner nodes (a path is at most TP2_BVH_STACK long)
            // until a leaf is entered or both children are missed.
            for (int level = 0; level < TP2_BVH_STACK && node >= 0; ++level) {
                BvhNode n = load_node(node);
                node = -1;
                rvec2 t = children_entry(n, box, float(h.t));
                bool left_first = t.x <= t.y;
                if (max(t.x, t.y) < NO_HIT && sp < TP2_BVH_STACK) {
                    stack_node[sp] = left_first ? n.link.y : n.link.x;
                    stack_t[sp] = max(t.x, t.y);
                    ++sp;
                }
                link = left_first ? n.link.x : n.link.y;
                enter = min(t.x, t.y) < NO_HIT;
                if (enter && link < 0) {
                    node = -link;
                    enter = false;
                }
            }
        } else if (USE_BVH && sp > 0) { // the nearest pending child, if still closer than the hit
            --sp;
            link = stack_node[sp];
            enter = stack_t[sp] < h.t;
        } else if (all_left) {
            all_left = false;
            if (USE_BVH) {
                node = 0;
            } else {
                i = 0;
                end = total;
                unbounded_left = false;
            }
        } else if (USE_BVH && unbounded_left) {
            i = bounded;
            end = total;
            unbounded_left = false;
        } else {
            break;
        }
        if (USE_BVH && enter) { // an inner node next, or a leaf's objects
            if (link < 0) {
                node = -link;
            } else {
                i = link >> TP2_BVH_LEAF_BITS;
                end = i + (link & TP2_BVH_LEAF_MASK) + 1;
            }
        }
    }
    return h;
}
