/* bvh.h: a bounding volume hierarchy over boxes (the bounded objects of a
 * scene), built as a binary tree (struct bvh_node) and laid out for the
 * shader (struct bvh_gpu_node).
 *
 * Depth invariant: every node's depth (root = 0) is at most
 * TP2_BVH_MAX_DEPTH - 1. A traversal that pushes the far child and
 * descends into the near one holds, at a node of depth d, at most d
 * entries (one far sibling per level above it), so at most
 * TP2_BVH_MAX_DEPTH - 1. Variants that push the root first, or push both
 * children and then pop the near one, peak at TP2_BVH_MAX_DEPTH. Either
 * way a stack of TP2_BVH_MAX_DEPTH entries never overflows. */
#ifndef TP2_BVH_H
#define TP2_BVH_H

#include <stddef.h>
#include <stdint.h>

#include "tp2_shared.h"

/* The shader's traversal stack holds this many node indices. */
#define TP2_BVH_MAX_DEPTH 32

/* One node of the tree as built. Bounds are floats rounded outward, so
 * each node's box contains its objects exactly, not just their float
 * approximations. */
struct bvh_node {
    float lo[3];
    int32_t first; /* inner: left child, right is first + 1; leaf: 1st slot */
    float hi[3];
    int32_t count; /* 0: inner; > 0: leaf over slots [first, first + count) */
};

_Static_assert(sizeof(struct bvh_node) == 32, "bvh_node is 32 bytes");
_Static_assert(offsetof(struct bvh_node, lo) == 0, "bvh_node.lo at 0");
_Static_assert(offsetof(struct bvh_node, first) == 12, "bvh_node.first at 12");
_Static_assert(offsetof(struct bvh_node, hi) == 16, "bvh_node.hi at 16");
_Static_assert(offsetof(struct bvh_node, count) == 28, "bvh_node.count at 28");

struct bvh {
    struct bvh_node *nodes; /* NULL, like order, when n == 0 */
    size_t node_count;      /* at most 2 n - 1; nodes[0] is the root */
    uint32_t *order;        /* order[slot] = input box there; n entries */
};

/* One inner node as the shader reads it: the boxes of both children,
 * interleaved by axis so that one vec4 per axis tests both (x = left lo,
 * left hi, right lo, right hi; y and z alike), and the two children's
 * links (tp2_shared.h: an inner node, or a leaf's objects). A visit loads
 * 14 words and enters a leaf without loading anything more; the tree as
 * built needed 8 words per node and 12 more for its children's boxes.
 * (Four 16-byte texels: x, y, z, then link and padding.) */
struct bvh_gpu_node {
    float x[4], y[4], z[4];
    int32_t link[2];
    int32_t pad[2];
};

_Static_assert(sizeof(struct bvh_gpu_node) == 64, "bvh_gpu_node is 64 bytes");
_Static_assert(offsetof(struct bvh_gpu_node, y) == 16, "bvh_gpu_node.y at 16");
_Static_assert(offsetof(struct bvh_gpu_node, z) == 32, "bvh_gpu_node.z at 32");
_Static_assert(offsetof(struct bvh_gpu_node, link) == 48, "bvh_gpu_node.link at 48");
_Static_assert(sizeof(struct bvh_gpu_node) == TP2_NODE_TEXELS * TP2_TEXEL_BYTES &&
                   offsetof(struct bvh_gpu_node, link) == 3 * TP2_TEXEL_BYTES,
               "bvh_gpu_node as the shader's texels: x, y, z, then the links");

/* The shader's nodes of b, written to out (room for bvh_gpu_count(b)):
 * one per inner node, the root first, in the tree's order. A tree that is
 * a single leaf becomes a root whose two children are both that leaf.
 * Returns 0, or -1 when out of memory. */
size_t bvh_gpu_count(const struct bvh *b);
int bvh_gpu_nodes(const struct bvh *b, struct bvh_gpu_node *out);

/* Builds a BVH over n boxes given as (lo x y z, hi x y z), with binned
 * SAH (16 bins on the longest axis of the centroid bounds). A node becomes
 * a leaf when it holds <= 2 boxes, or <= 8 and splitting costs no less
 * than intersecting them all; no leaf holds more than 8 (boxes whose
 * centers are all equal are halved by position). Near the depth limit,
 * splits that would not fit in the levels left become median splits, so
 * leaves stay small there too. The same input always gives the same tree.
 * Coordinates beyond float range give infinite bounds; NaN gives an
 * infinite box. Returns 0, or -1 when out of memory or n > 2^27 (a leaf's
 * link, object << 3, must fit int32); b is zeroed on failure and when
 * n == 0. */
int bvh_build(const double (*boxes)[6], size_t n, struct bvh *b);

/* The same, with box i of the n written by box_at(source, i, box) as the
 * build first reads it (each once, in order), so that a caller need not
 * keep an array of them: for a million objects that array was 48 MB of
 * fresh memory, written once and read once. */
typedef void bvh_box_fn(const void *source, size_t i, double box[6]);
int bvh_build_from(bvh_box_fn *box_at, const void *source, size_t n, struct bvh *b);

/* Moves every node's bounds by -origin, rounded outward, so that they
 * hold the shapes moved the same way. */
void bvh_move(struct bvh *b, const double origin[3]);

/* Frees the arrays and zeroes b; safe on a zeroed one. */
void bvh_free(struct bvh *b);

#endif
