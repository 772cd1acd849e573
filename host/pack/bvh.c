#define _POSIX_C_SOURCE 200809L
#include "bvh.h"
#include "big_alloc.h"
#include "test_hooks.h"
#include "tp2_shared.h"

#include <float.h>
#include <math.h>
#include <pthread.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* SAH bins along the split axis: more bins find better planes, fewer are
 * faster; 16 is the usual balance. */
#define BVH_BINS 16
/* A node with at most this many boxes is always a leaf. */
#define BVH_MIN_SPLIT 2
/* Above this many boxes a node is split even when SAH prefers a leaf. */
#define BVH_MAX_LEAF 8
/* Cost of visiting an inner node, relative to one primitive test. */
#define BVH_TRAVERSAL_COST 1.0
/* The deepest a node may sit (root = 0); see the invariant in bvh.h. */
#define BVH_MAX_NODE_DEPTH (TP2_BVH_MAX_DEPTH - 1)
/* Most boxes accepted: 2 n - 1 nodes must be indexable by int32. */
#define BVH_MAX_PRIMS ((size_t)1 << (31 - TP2_BVH_LEAF_BITS - 1))

/* One box while building: its float bounds, its center (the key that is
 * binned and split on), and where it came from. Partitions move these. */
struct prim {
    float lo[3], hi[3];
    double c[3];
    uint32_t index;
    uint8_t bin; /* bin along the current node's axis, between two passes */
};

/* A node whose boxes are prims[begin, end), still to be filled in;
 * cmin, cmax bound their centers (computed by whoever made the task). */
struct task {
    uint32_t node, begin, end, depth;
    double cmin[3], cmax[3];
};

/* The boxes whose centers fall in one SAH bin. */
struct bin {
    uint32_t count;
    float lo[3], hi[3];
    double cmin[3], cmax[3];
};

/* The float next to finite f toward -inf (dir < 0) or +inf (dir > 0),
 * by its bits: prim_init steps every box bound, and nextafterf was a libm
 * call per bound. A float's bits, read as an integer, grow with its
 * magnitude; zero of either sign steps to the least subnormal. */
static float float_step(float f, int dir)
{
    if (f == 0)
        return dir < 0 ? -FLT_TRUE_MIN : FLT_TRUE_MIN;
    uint32_t bits;
    memcpy(&bits, &f, sizeof bits);
    bits += (f > 0) == (dir > 0) ? 1 : -1;
    memcpy(&f, &bits, sizeof f);
    return f;
}

/* The largest float < x: -inf when there is none (x <= -FLT_MAX, or NaN,
 * which widens the box to the whole line). Strictly below, so that a box
 * bound rounded to nearest in double still lies inside: the float box
 * contains the exact shape. */
static float float_below(double x)
{
    if (!(x > -(double)FLT_MAX))
        return -INFINITY;
    if (x > (double)FLT_MAX)
        return FLT_MAX;
    float f = (float)x; /* to nearest: a neighbour of x, or x itself */
    return (double)f < x ? f : float_step(f, -1);
}

/* The smallest float > x: +inf when there is none. */
static float float_above(double x)
{
    if (!(x < (double)FLT_MAX))
        return INFINITY;
    if (x < -(double)FLT_MAX)
        return -FLT_MAX;
    float f = (float)x;
    return (double)f > x ? f : float_step(f, 1);
}

/* Fills p from one box (lo, hi); its center is the key. */
static void prim_init(struct prim *p, const double box[6], uint32_t index)
{
    for (int a = 0; a < 3; a++) {
        p->lo[a] = float_below(box[a]);
        p->hi[a] = float_above(box[a + 3]);
        p->c[a] = box[a] / 2 + box[a + 3] / 2;
    }
    p->index = index;
    p->bin = 0;
}

static void box_empty(float lo[3], float hi[3])
{
    for (int a = 0; a < 3; a++) {
        lo[a] = INFINITY;
        hi[a] = -INFINITY;
    }
}

static void box_grow(float lo[3], float hi[3], const float plo[3],
                     const float phi[3])
{
    /* Conditional moves, not branches: this is the builder's inner loop. */
    for (int a = 0; a < 3; a++) {
        lo[a] = plo[a] < lo[a] ? plo[a] : lo[a];
        hi[a] = phi[a] > hi[a] ? phi[a] : hi[a];
    }
}

/* Half the surface area, which is all SAH ratios need; in double so that
 * boxes near float range do not overflow. */
static double box_half_area(const float lo[3], const float hi[3])
{
    double d[3];
    for (int a = 0; a < 3; a++)
        d[a] = (double)hi[a] - (double)lo[a];
    return d[0] * d[1] + d[1] * d[2] + d[2] * d[0];
}

/* The bin of centroid coordinate c in [cmin, cmin + extent]; NaN goes to
 * bin 0 so that every box lands somewhere. */
static int bin_of(double c, double cmin, double extent)
{
    double f = (c - cmin) / extent * BVH_BINS;
    if (f >= BVH_BINS - 1)
        return BVH_BINS - 1;
    return f > 0 ? (int)f : 0;
}

/* Orders prims by center on axis, then by input index: a total order, so
 * any selection by it gives the same halves. */
static bool prim_less(const struct prim *x, const struct prim *y, int axis)
{
    if (x->c[axis] != y->c[axis])
        return x->c[axis] < y->c[axis];
    return x->index < y->index;
}

static void prim_swap(struct prim *x, struct prim *y)
{
    struct prim t = *x;
    *x = *y;
    *y = t;
}

static void sift_down(struct prim *p, size_t root, size_t n, int axis)
{
    for (;;) {
        size_t child = 2 * root + 1;
        if (child >= n)
            return;
        if (child + 1 < n && prim_less(&p[child], &p[child + 1], axis))
            child++;
        if (!prim_less(&p[root], &p[child], axis))
            return;
        prim_swap(&p[root], &p[child]);
        root = child;
    }
}

/* Heap sort: the worst-case bound quickselect lacks. */
static void prim_heap_sort(struct prim *p, size_t n, int axis)
{
    for (size_t i = n / 2; i-- > 0;)
        sift_down(p, i, n, axis);
    for (size_t end = n; end-- > 1;) {
        prim_swap(&p[0], &p[end]);
        sift_down(p, 0, end, axis);
    }
}

/* Rearranges p[0, n) so that p[k] is where sorting would put it, smaller
 * ones before, larger after. Quickselect with a median-of-three pivot,
 * falling back to heap sort after too many rounds (adversarial input). */
static void prim_select(struct prim *p, size_t n, size_t k, int axis)
{
    size_t lo = 0, hi = n; /* the answer lies in [lo, hi) */
    int rounds = 0;
    while (hi - lo > 2) {
        if (++rounds > 64) {
            prim_heap_sort(p + lo, hi - lo, axis);
            return;
        }
        size_t mid = lo + (hi - lo) / 2;
        /* Sort p[lo], p[mid], p[hi - 1]; the median becomes the pivot. */
        if (prim_less(&p[mid], &p[lo], axis))
            prim_swap(&p[mid], &p[lo]);
        if (prim_less(&p[hi - 1], &p[mid], axis))
            prim_swap(&p[hi - 1], &p[mid]);
        if (prim_less(&p[mid], &p[lo], axis))
            prim_swap(&p[mid], &p[lo]);
        prim_swap(&p[mid], &p[hi - 1]);
        struct prim *pivot = &p[hi - 1];
        size_t store = lo;
        for (size_t i = lo; i < hi - 1; i++)
            if (prim_less(&p[i], pivot, axis))
                prim_swap(&p[i], &p[store++]);
        prim_swap(&p[store], &p[hi - 1]);
        /* Keys are distinct, so the pivot now sits at its sorted place. */
        if (store == k)
            return;
        if (k < store)
            hi = store;
        else
            lo = store + 1;
    }
    if (hi - lo == 2 && prim_less(&p[lo + 1], &p[lo], axis))
        prim_swap(&p[lo], &p[lo + 1]);
}

/* Moves prims whose bin is <= split before the others; returns how many. */
static uint32_t partition_bins(struct prim *p, uint32_t n, int split)
{
    uint32_t i = 0, j = n;
    while (i < j) {
        if (p[i].bin <= split) {
            i++;
        } else {
            j--;
            prim_swap(&p[i], &p[j]);
        }
    }
    return i;
}

/* How many boxes a subtree with `levels` levels below its root can hold
 * with leaves of at most BVH_MAX_LEAF: median splits achieve it. */
static uint64_t capacity(int levels)
{
    return (uint64_t)BVH_MAX_LEAF << levels;
}

/* Grows the centroid bounds cmin, cmax by c. */
static void centroid_grow(double cmin[3], double cmax[3], const double c[3])
{
    for (int a = 0; a < 3; a++) {
        cmin[a] = c[a] < cmin[a] ? c[a] : cmin[a];
        cmax[a] = c[a] > cmax[a] ? c[a] : cmax[a];
    }
}

static void centroid_empty(double cmin[3], double cmax[3])
{
    for (int a = 0; a < 3; a++) {
        cmin[a] = INFINITY;
        cmax[a] = -INFINITY;
    }
}

/* t's centroid bounds, by a pass over its boxes (the root, and the
 * halves of a median split, which bins do not describe). */
static void task_centroids(const struct prim *prims, struct task *t)
{
    centroid_empty(t->cmin, t->cmax);
    for (uint32_t i = t->begin; i < t->end; i++)
        centroid_grow(t->cmin, t->cmax, prims[i].c);
}

/* kids: t's first mid boxes, and the rest. */
static void halves(const struct task *t, uint32_t mid, struct task kids[2])
{
    kids[0].begin = t->begin;
    kids[0].end = kids[1].begin = t->begin + mid;
    kids[1].end = t->end;
}

/* The halves of a median split, with their centroid bounds. */
static void median_halves(const struct prim *prims, const struct task *t, uint32_t mid,
                          struct task kids[2])
{
    halves(t, mid, kids);
    task_centroids(prims, &kids[0]);
    task_centroids(prims, &kids[1]);
}

/* Makes node a leaf over t's boxes, bounds by a pass over them. */
static void make_leaf(const struct prim *prims, const struct task *t,
                      struct bvh_node *node)
{
    box_empty(node->lo, node->hi);
    for (uint32_t i = t->begin; i < t->end; i++)
        box_grow(node->lo, node->hi, prims[i].lo, prims[i].hi);
    node->first = (int32_t)t->begin;
    node->count = (int32_t)(t->end - t->begin);
}

/* Decides node t. Either makes it a leaf (returns 0), or fills its bounds,
 * partitions its boxes and sets the two children's ranges and centroid
 * bounds in kids (returns 1). The binning pass also gathers the bounds, so
 * an inner node costs two passes over its boxes. */
static int split_node(struct prim *prims, const struct task *t,
                      struct bvh_node *node, struct task kids[2])
{
    struct prim *p = prims + t->begin;
    uint32_t n = t->end - t->begin;
    int axis = 0;
    double extent[3];
    for (int a = 0; a < 3; a++) {
        extent[a] = t->cmax[a] - t->cmin[a];
        if (extent[a] > extent[axis])
            axis = a;
    }
    int levels_left = BVH_MAX_NODE_DEPTH - (int)t->depth;
    /* !(extent > 0): all centers equal, or none comparable (NaN). */
    if (n <= BVH_MIN_SPLIT || levels_left == 0 ||
        (!(extent[axis] > 0) && n <= BVH_MAX_LEAF)) {
        make_leaf(prims, t, node);
        return 0;
    }
    if (!(extent[axis] > 0)) { /* no plane separates them: halve by position */
        make_leaf(prims, t, node); /* the bounds */
        median_halves(prims, t, n / 2, kids);
        return 1;
    }

    struct bin bins[BVH_BINS];
    for (int b = 0; b < BVH_BINS; b++) {
        bins[b].count = 0;
        box_empty(bins[b].lo, bins[b].hi);
        centroid_empty(bins[b].cmin, bins[b].cmax);
    }
    for (uint32_t i = 0; i < n; i++) {
        int b = bin_of(p[i].c[axis], t->cmin[axis], extent[axis]);
        p[i].bin = (uint8_t)b;
        bins[b].count++;
        box_grow(bins[b].lo, bins[b].hi, p[i].lo, p[i].hi);
        centroid_grow(bins[b].cmin, bins[b].cmax, p[i].c);
    }

    /* right_area[b], right_count[b]: bins b .. BVH_BINS - 1 together. */
    double right_area[BVH_BINS];
    uint32_t right_count[BVH_BINS];
    float rlo[3], rhi[3];
    box_empty(rlo, rhi);
    uint32_t rn = 0;
    double ra = 0;
    for (int b = BVH_BINS - 1; b > 0; b--) {
        if (bins[b].count) { /* empty bins change nothing: skip the area */
            box_grow(rlo, rhi, bins[b].lo, bins[b].hi);
            rn += bins[b].count;
            ra = box_half_area(rlo, rhi);
        }
        right_count[b] = rn;
        right_area[b] = ra;
    }
    /* Split after bin `best`: the first of equal costs, for determinism.
     * A split after an empty bin repeats the one before it, so only
     * non-empty bins are tried. The sweep ends with the node's own bounds
     * in lo, hi. */
    int best = -1;
    double best_cost = INFINITY;
    uint32_t best_left = 0;
    float lo[3], hi[3];
    box_empty(lo, hi);
    uint32_t ln = 0;
    for (int b = 0; b < BVH_BINS; b++) {
        if (bins[b].count == 0)
            continue;
        box_grow(lo, hi, bins[b].lo, bins[b].hi);
        ln += bins[b].count;
        if (b == BVH_BINS - 1 || right_count[b + 1] == 0)
            continue;
        double cost = box_half_area(lo, hi) * ln +
                      right_area[b + 1] * right_count[b + 1];
        if (cost < best_cost) {
            best_cost = cost;
            best = b;
            best_left = ln;
        }
    }
    memcpy(node->lo, lo, sizeof lo);
    memcpy(node->hi, hi, sizeof hi);
    node->first = (int32_t)t->begin;
    node->count = (int32_t)n;

    double area = box_half_area(lo, hi);
    double split_cost = BVH_TRAVERSAL_COST * area + best_cost;
    double leaf_cost = (double)n * area;
    if (n <= BVH_MAX_LEAF && !(split_cost < leaf_cost))
        return 0;

    /* A SAH split whose larger side would not fit the levels left (or no
     * usable plane, from rounding in bin_of) becomes a median split, which
     * halves n and so always fits: n <= capacity(levels_left) holds at
     * the root and is passed down. */
    uint32_t larger = best_left > n - best_left ? best_left : n - best_left;
    uint32_t mid;
    if (best < 0 || larger > capacity(levels_left - 1)) {
        mid = n / 2;
        prim_select(p, n, mid, axis);
        median_halves(prims, t, mid, kids);
        return 1;
    }
    mid = partition_bins(p, n, best);
    halves(t, mid, kids);
    for (int k = 0; k < 2; k++)
        centroid_empty(kids[k].cmin, kids[k].cmax);
    for (int b = 0; b < BVH_BINS; b++) {
        struct task *k = &kids[b > best];
        if (bins[b].count) {
            centroid_grow(k->cmin, k->cmax, bins[b].cmin);
            centroid_grow(k->cmin, k->cmax, bins[b].cmax);
        }
    }
    return 1;
}

/* Builds the subtree of task root, depth-first with an explicit stack,
 * left child first, so subtrees sit together: its root at nodes[root.node],
 * the k-th node made after it at nodes[base + k - 1] (for a whole tree,
 * root.node 0 and base 1). A task at depth d finds at most d right
 * siblings of its ancestors waiting, and pushes two only when d <
 * BVH_MAX_NODE_DEPTH, so the stack never exceeds TP2_BVH_MAX_DEPTH.
 * Returns the number of nodes made, its root included. */
static size_t build_subtree(struct prim *prims, struct task root, size_t base,
                            struct bvh_node *nodes)
{
    struct task stack[TP2_BVH_MAX_DEPTH];
    int sp = 0;
    stack[sp++] = root;
    size_t node_count = 1;
    while (sp > 0) {
        struct task t = stack[--sp];
        struct bvh_node *node = &nodes[t.node];
        struct task kids[2];
        if (!split_node(prims, &t, node, kids))
            continue;
        uint32_t left = (uint32_t)(base + node_count - 1);
        node_count += 2;
        node->first = (int32_t)left;
        node->count = 0;
        for (int k = 1; k >= 0; k--) {
            kids[k].node = left + (uint32_t)k;
            kids[k].depth = t.depth + 1;
            stack[sp++] = kids[k];
        }
    }
    return node_count;
}

/* Below this many boxes a second thread costs more than it saves. */
#define BVH_PARALLEL_MIN 65536

/* One half of the tree built by a thread of its own. */
struct half {
    struct prim *prims;
    struct task root;
    size_t base;
    struct bvh_node *nodes;
    size_t count;
};

static void *build_half(void *arg)
{
    struct half *h = arg;
    h->count = build_subtree(h->prims, h->root, h->base, h->nodes);
    return NULL;
}

/* The tree below the root's split, its two halves on two threads (the
 * boxes of one half are a range of prims no other thread touches), built
 * where they belong in nodes[] (2 n - 1 of them): the same nodes, in the
 * same order, as one thread makes. The roots of the halves are nodes 1 and
 * 2, and the left half's other nodes follow from 3 on. The right half's
 * place depends on how many nodes the left one makes, so it is built past
 * the most the left one can make (2 m - 1 for m boxes), which fits, and
 * then moved down next to it. Returns the node count. */
static size_t build_halves(struct prim *prims, struct task kids[2],
                           struct bvh_node *nodes)
{
    size_t left_most = 2 * (size_t)(kids[0].end - kids[0].begin) - 1;
    size_t right_base = 3 + left_most - 1;
    struct half h[2];
    for (int k = 0; k < 2; k++) {
        kids[k].depth = 1;
        kids[k].node = 1 + (uint32_t)k;
        h[k] = (struct half){prims, kids[k], k == 0 ? 3 : right_base, nodes, 0};
    }
    pthread_t thread;
    bool threaded = pthread_create(&thread, NULL, build_half, &h[0]) == 0;
    if (!threaded)
        build_half(&h[0]);
    build_half(&h[1]);
    if (threaded)
        pthread_join(thread, NULL);

    size_t to = 3 + h[0].count - 1, moved = h[1].count - 1;
    if (to < right_base) {
        memmove(&nodes[to], &nodes[right_base], moved * sizeof *nodes);
        int32_t shift = (int32_t)(right_base - to);
        if (nodes[2].count == 0)
            nodes[2].first -= shift;
        for (size_t i = to; i < to + moved; i++)
            if (nodes[i].count == 0)
                nodes[i].first -= shift;
    }
    return 1 + h[0].count + h[1].count;
}

/* Two threads where there are two cores, unless a unit test asks for one
 * (test_hooks.h: to compare both builds). */
static bool two_threads(void)
{
    return !test_hooks()->bvh_one_thread && sysconf(_SC_NPROCESSORS_ONLN) > 1;
}

static void box_of_array(const void *source, size_t i, double box[6])
{
    memcpy(box, ((const double (*)[6])source)[i], 6 * sizeof *box);
}

int bvh_build(const double (*boxes)[6], size_t n, struct bvh *b)
{
    return bvh_build_from(box_of_array, boxes, n, b);
}

int bvh_build_from(bvh_box_fn *box_at, const void *source, size_t n, struct bvh *b)
{
    memset(b, 0, sizeof *b);
    if (n == 0)
        return 0;
    if (n > BVH_MAX_PRIMS)
        return -1;

    size_t max_nodes = 2 * n - 1;
    struct prim *prims = big_alloc(n * sizeof *prims);
    b->nodes = big_alloc(max_nodes * sizeof *b->nodes);
    b->order = big_alloc(n * sizeof *b->order);
    if (!prims || !b->nodes || !b->order) {
        free(prims);
        bvh_free(b);
        return -1;
    }
    for (size_t i = 0; i < n; i++) {
        double box[6];
        box_at(source, i, box);
        prim_init(&prims[i], box, (uint32_t)i);
    }

    struct task root = {.node = 0, .begin = 0, .end = (uint32_t)n};
    task_centroids(prims, &root);
    size_t node_count;
    struct task kids[2];
    if (n >= BVH_PARALLEL_MIN && two_threads() &&
        split_node(prims, &root, &b->nodes[0], kids)) {
        b->nodes[0].first = 1;
        b->nodes[0].count = 0;
        node_count = build_halves(prims, kids, b->nodes);
    } else {
        node_count = build_subtree(prims, root, 1, b->nodes);
    }

    for (size_t i = 0; i < n; i++)
        b->order[i] = prims[i].index;
    free(prims);
    b->node_count = node_count;
    /* Give back the unused tail; keeping the larger block is harmless. */
    struct bvh_node *shrunk = realloc(b->nodes, node_count * sizeof *shrunk);
    if (shrunk)
        b->nodes = shrunk;
    return 0;
}

/* The link to node ni of b (tp2_shared.h); gpu_index[ni] is its place
 * among the shader's nodes when it is an inner node. */
static int32_t gpu_link(const struct bvh *b, int32_t ni, const int32_t *gpu_index)
{
    const struct bvh_node *nd = &b->nodes[ni];
    if (nd->count > 0)
        return nd->first << TP2_BVH_LEAF_BITS | (nd->count - 1);
    return -gpu_index[ni];
}

/* Child k of the shader's node: its box at k of each axis' vec4. */
static void gpu_child(struct bvh_gpu_node *g, int k, const struct bvh_node *c)
{
    g->x[2 * k] = c->lo[0], g->x[2 * k + 1] = c->hi[0];
    g->y[2 * k] = c->lo[1], g->y[2 * k + 1] = c->hi[1];
    g->z[2 * k] = c->lo[2], g->z[2 * k + 1] = c->hi[2];
}

size_t bvh_gpu_count(const struct bvh *b)
{
    return b->node_count <= 1 ? b->node_count : (b->node_count - 1) / 2;
}

int bvh_gpu_nodes(const struct bvh *b, struct bvh_gpu_node *out)
{
    if (b->node_count == 0)
        return 0;
    if (b->node_count == 1) { /* one leaf: both children of a root */
        memset(out, 0, sizeof *out);
        gpu_child(out, 0, &b->nodes[0]);
        gpu_child(out, 1, &b->nodes[0]);
        out->link[0] = out->link[1] = gpu_link(b, 0, NULL);
        return 0;
    }
    /* Inner nodes keep their order (the root first); leaves drop out. */
    int32_t *gpu_index = big_alloc(b->node_count * sizeof *gpu_index);
    if (!gpu_index)
        return -1;
    int32_t next = 0;
    for (size_t i = 0; i < b->node_count; i++)
        gpu_index[i] = b->nodes[i].count > 0 ? -1 : next++;
    for (size_t i = 0; i < b->node_count; i++) {
        const struct bvh_node *nd = &b->nodes[i];
        if (nd->count > 0)
            continue;
        struct bvh_gpu_node *g = &out[gpu_index[i]];
        memset(g, 0, sizeof *g);
        for (int k = 0; k < 2; k++) {
            gpu_child(g, k, &b->nodes[nd->first + k]);
            g->link[k] = gpu_link(b, nd->first + k, gpu_index);
        }
    }
    free(gpu_index);
    return 0;
}

void bvh_move(struct bvh *b, const double origin[3])
{
    for (size_t i = 0; i < b->node_count; i++) {
        struct bvh_node *n = &b->nodes[i];
        for (int a = 0; a < 3; a++) {
            n->lo[a] = float_below((double)n->lo[a] - origin[a]);
            n->hi[a] = float_above((double)n->hi[a] - origin[a]);
        }
    }
}

void bvh_free(struct bvh *b)
{
    free(b->nodes);
    free(b->order);
    memset(b, 0, sizeof *b);
}
