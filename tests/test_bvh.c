/* test_bvh.c: bvh_build on seeded sphere sets, checked against its
 * contract and against a linear scan. The last line is "N passed, M
 * failed"; the exit status is 0 only when nothing failed. */
#define _POSIX_C_SOURCE 200809L
#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bvh.h"
#include "test_hooks.h"
#include "tp2_shared.h"

#include "unit.h"

/* bvh_build over spheres (cx, cy, cz, r) as the packer gives them: each
 * sphere's box is c - r .. c + r. */
static int sphere_bvh_build(const double (*spheres)[4], size_t n, struct bvh *b)
{
    double (*boxes)[6] = malloc((n ? n : 1) * sizeof *boxes);
    if (!boxes)
        return -1;
    for (size_t i = 0; i < n && spheres; i++)
        for (int a = 0; a < 3; a++) {
            boxes[i][a] = spheres[i][a] - fabs(spheres[i][3]);
            boxes[i][a + 3] = spheres[i][a] + fabs(spheres[i][3]);
        }
    int rc = bvh_build(spheres ? (const double (*)[6])boxes : NULL, n, b);
    free(boxes);
    return rc;
}

/* splitmix64: seeded, so every run sees the same spheres and rays. */
static uint64_t rng_state;

static uint64_t rng_next(void)
{
    uint64_t z = (rng_state += 0x9e3779b97f4a7c15u);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9u;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebu;
    return z ^ (z >> 31);
}

/* Uniform in [0, 1). */
static double rng_unit(void)
{
    return (double)(rng_next() >> 11) * 0x1p-53;
}

static double rng_range(double lo, double hi)
{
    return lo + (hi - lo) * rng_unit();
}

/* 10^U(lo, hi): spreads values over many orders of magnitude. */
static double rng_log(double lo_exp, double hi_exp)
{
    return pow(10.0, rng_range(lo_exp, hi_exp));
}

static void rng_direction(double d[3])
{
    double len;
    do {
        for (int a = 0; a < 3; a++)
            d[a] = rng_range(-1, 1);
        len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    } while (len > 1 || len < 1e-3);
    for (int a = 0; a < 3; a++)
        d[a] /= len;
}

static double now_s(void)
{
    struct timespec ts;
    timespec_get(&ts, TIME_UTC);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* ---- Sphere sets ---- */

enum set_kind {
    SET_UNIFORM,     /* centers in the unit cube, small radii */
    SET_SAME_CENTER, /* one center, radii over six decades */
    SET_FEW_CENTERS, /* three centers shared by many spheres */
    SET_MIXED,       /* clusters from 1e-27 to 1e30, radii 1e-30 to 1e29 */
    SET_GEOMETRIC,   /* centers 1.03^i on a line: SAH peels one at a time */
    SET_HUGE,        /* coordinates and radii near and past float range */
    SET_EXTREME,     /* near double range: sums overflow to infinity */
};

static double (*make_set(enum set_kind kind, size_t n, uint64_t seed))[4]
{
    double (*s)[4] = malloc((n ? n : 1) * sizeof *s);
    if (!s) {
        fputs("test_bvh: out of memory\n", stderr);
        exit(2);
    }
    rng_state = seed;
    for (size_t i = 0; i < n; i++) {
        double *p = s[i];
        switch (kind) {
        case SET_UNIFORM:
            for (int a = 0; a < 3; a++)
                p[a] = rng_unit();
            p[3] = rng_range(0.002, 0.006);
            break;
        case SET_SAME_CENTER:
            p[0] = 1.5;
            p[1] = -2.25;
            p[2] = 3.0;
            p[3] = rng_log(-3, 3);
            break;
        case SET_FEW_CENTERS: {
            int c = (int)(rng_next() % 3);
            p[0] = c;
            p[1] = 2.0 * c;
            p[2] = -c;
            p[3] = rng_range(0.01, 0.5);
            break;
        }
        case SET_MIXED: {
            static const double scales[] = {1e-27, 1e-9, 1.0, 1e12, 1e30};
            double scale = scales[rng_next() % 5];
            for (int a = 0; a < 3; a++)
                p[a] = rng_range(-scale, scale);
            p[3] = scale * rng_log(-3, -1);
            if (i % 50 == 0)
                p[3] = rng_log(-30, 29); /* a stray tiny or huge one */
            break;
        }
        case SET_GEOMETRIC:
            p[0] = pow(1.03, (double)i);
            p[1] = 0;
            p[2] = 0;
            p[3] = 1e-3 * p[0];
            break;
        case SET_HUGE:
            for (int a = 0; a < 3; a++)
                p[a] = rng_range(-3e38, 3e38);
            p[3] = i % 2 ? rng_log(30, 38.5) : rng_log(-30, 0);
            break;
        case SET_EXTREME:
            for (int a = 0; a < 3; a++)
                p[a] = rng_range(-1, 1) * (i % 3 ? 1e308 : 1);
            p[3] = rng_log(-300, 308);
            break;
        }
    }
    return s;
}

/* ---- Structure ---- */

/* Walks the tree from the root and checks everything the contract says
 * about its shape and bounds; returns the deepest node's depth (-1 when
 * there are no nodes). */
static int check_structure(const char *name, const double (*s)[4], size_t n,
                           const struct bvh *b)
{
    if (n == 0) {
        expect(b->nodes == NULL && b->node_count == 0 && b->order == NULL,
               "%s: n = 0 gives no nodes and no order", name);
        return -1;
    }
    expect(b->node_count >= 1 && b->node_count <= 2 * n - 1,
           "%s: node count %zu within [1, 2n - 1]", name, b->node_count);

    /* order is a permutation of 0 .. n - 1. */
    bool *seen = calloc(n, 1);
    bool *slot_used = calloc(n, 1);
    bool *node_seen = calloc(b->node_count, 1);
    if (!seen || !slot_used || !node_seen) {
        fputs("test_bvh: out of memory\n", stderr);
        exit(2);
    }
    size_t bad_order = 0;
    for (size_t i = 0; i < n; i++) {
        if (b->order[i] >= n || seen[b->order[i]])
            bad_order++;
        else
            seen[b->order[i]] = true;
    }
    expect(bad_order == 0, "%s: order is a permutation (%zu bad)", name,
           bad_order);

    size_t bad_child = 0, node_twice = 0, bad_leaf = 0, slot_twice = 0;
    size_t outside_leaf = 0, outside_parent = 0, not_union = 0;
    size_t big_leaf = 0, inverted = 0;
    int max_depth = 0;
    struct {
        int32_t node;
        int depth;
    } stack[2 * TP2_BVH_MAX_DEPTH + 64];
    int sp = 0;
    int stack_cap = (int)(sizeof stack / sizeof stack[0]);
    stack[sp].node = 0;
    stack[sp++].depth = 0;
    while (sp > 0) {
        int32_t ni = stack[--sp].node;
        int depth = stack[sp].depth;
        if (node_seen[ni]) {
            node_twice++;
            continue;
        }
        node_seen[ni] = true;
        if (depth > max_depth)
            max_depth = depth;
        const struct bvh_node *nd = &b->nodes[ni];
        for (int a = 0; a < 3; a++)
            if (!(nd->lo[a] <= nd->hi[a]))
                inverted++;
        if (nd->count < 0) {
            bad_leaf++;
            continue;
        }
        if (nd->count > 0) {
            if (nd->first < 0 || (size_t)nd->first + (size_t)nd->count > n) {
                bad_leaf++;
                continue;
            }
            for (int32_t k = nd->first; k < nd->first + nd->count; k++) {
                if (slot_used[k])
                    slot_twice++;
                slot_used[k] = true;
                const double *p = s[b->order[k]];
                double r = fabs(p[3]);
                for (int a = 0; a < 3; a++)
                    if (!((double)nd->lo[a] <= p[a] - r &&
                          p[a] + r <= (double)nd->hi[a]))
                        outside_leaf++;
            }
            if (nd->count > TP2_BVH_LEAF_MAX)
                big_leaf++;
            continue;
        }
        if (nd->first < 1 || (size_t)nd->first + 1 >= b->node_count) {
            bad_child++;
            continue;
        }
        const struct bvh_node *l = &b->nodes[nd->first];
        const struct bvh_node *r = &b->nodes[nd->first + 1];
        for (int a = 0; a < 3; a++) {
            if (!(nd->lo[a] <= l->lo[a] && l->hi[a] <= nd->hi[a] &&
                  nd->lo[a] <= r->lo[a] && r->hi[a] <= nd->hi[a]))
                outside_parent++;
            /* Bounds are unions of float boxes, so a parent is exactly its
             * children's union: anything looser wastes traversal. */
            if (nd->lo[a] != fminf(l->lo[a], r->lo[a]) ||
                nd->hi[a] != fmaxf(l->hi[a], r->hi[a]))
                not_union++;
        }
        if (sp + 2 > stack_cap) {
            bad_child++; /* deeper than this walk can follow */
            continue;
        }
        stack[sp].node = nd->first + 1;
        stack[sp++].depth = depth + 1;
        stack[sp].node = nd->first;
        stack[sp++].depth = depth + 1;
    }

    size_t unreached = 0, empty_slots = 0;
    for (size_t i = 0; i < b->node_count; i++)
        unreached += !node_seen[i];
    for (size_t i = 0; i < n; i++)
        empty_slots += !slot_used[i];
    expect(bad_child == 0, "%s: inner nodes' children in range (%zu bad)",
           name, bad_child);
    expect(node_twice == 0 && unreached == 0,
           "%s: every node reached once (%zu twice, %zu never)", name,
           node_twice, unreached);
    expect(bad_leaf == 0, "%s: leaves non-empty and in range (%zu bad)",
           name, bad_leaf);
    expect(slot_twice == 0 && empty_slots == 0,
           "%s: every slot in exactly one leaf (%zu twice, %zu never)", name,
           slot_twice, empty_slots);
    expect(inverted == 0, "%s: lo <= hi in every node (%zu not)", name,
           inverted);
    expect(outside_leaf == 0, "%s: spheres inside their leaf (%zu not)",
           name, outside_leaf);
    expect(outside_parent == 0, "%s: children inside parents (%zu not)",
           name, outside_parent);
    expect(not_union == 0, "%s: parents are their children's union (%zu not)",
           name, not_union);
    expect(big_leaf == 0,
           "%s: no leaf holds more than 8 (%zu do)", name,
           big_leaf);
    expect(max_depth <= TP2_BVH_MAX_DEPTH - 1,
           "%s: depth %d <= TP2_BVH_MAX_DEPTH - 1", name, max_depth);
    free(seen);
    free(slot_used);
    free(node_seen);
    return max_depth;
}

/* ---- Rays ---- */

/* Nearest t > 0 where the ray o + t d (d unit) meets sphere s, or
 * INFINITY. Measures the miss distance from the closest point, which stays
 * accurate far from the sphere, unlike b^2 - c. */
static double hit_sphere(const double o[3], const double d[3],
                         const double s[4])
{
    double f[3], l[3];
    for (int a = 0; a < 3; a++)
        f[a] = o[a] - s[a];
    double b = -(f[0] * d[0] + f[1] * d[1] + f[2] * d[2]);
    for (int a = 0; a < 3; a++)
        l[a] = f[a] + b * d[a];
    double disc = s[3] * s[3] - (l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
    if (disc < 0)
        return INFINITY;
    double q = sqrt(disc);
    if (b - q > 0)
        return b - q;
    if (b + q > 0)
        return b + q;
    return INFINITY;
}

/* Where the ray enters node's box, or INFINITY when it misses it or only
 * meets it beyond t_max. A relative slack of 1e-9 absorbs this test's own
 * rounding (the bounds are checked exactly elsewhere), so only a wrong
 * tree can lose a hit. */
static double hit_box(const struct bvh_node *nd, const double o[3],
                      const double inv[3], double t_max)
{
    double enter = 0, exit = INFINITY;
    for (int a = 0; a < 3; a++) {
        double t0 = ((double)nd->lo[a] - o[a]) * inv[a];
        double t1 = ((double)nd->hi[a] - o[a]) * inv[a];
        if (t0 > t1) {
            double t = t0;
            t0 = t1;
            t1 = t;
        }
        enter = fmax(enter, t0); /* fmax and fmin skip 0 * inf = NaN */
        exit = fmin(exit, t1);
    }
    double slack = 1e-9 * fmax(fabs(enter), fabs(exit));
    if (enter > exit + slack || enter > t_max + 1e-9 * fabs(t_max) + slack)
        return INFINITY;
    return enter;
}

struct hit {
    double t;
    uint32_t sphere; /* input index; UINT32_MAX for none */
};

static struct hit linear_scan(const double (*s)[4], size_t n,
                              const double o[3], const double d[3])
{
    struct hit h = {INFINITY, UINT32_MAX};
    for (size_t i = 0; i < n; i++) {
        double t = hit_sphere(o, d, s[i]);
        if (t < h.t) {
            h.t = t;
            h.sphere = (uint32_t)i;
        }
    }
    return h;
}

/* The shader's traversal: test both children, descend into the nearer,
 * push the farther on a stack of TP2_BVH_MAX_DEPTH. Counts the nodes
 * entered in *visited; sets *overflow if the stack would overflow. */
static struct hit traverse(const double (*s)[4], const struct bvh *b,
                           const double o[3], const double d[3],
                           long *visited, bool *overflow)
{
    struct hit h = {INFINITY, UINT32_MAX};
    if (b->node_count == 0)
        return h;
    double inv[3];
    for (int a = 0; a < 3; a++)
        inv[a] = 1.0 / d[a];
    int32_t stack[TP2_BVH_MAX_DEPTH];
    int sp = 0;
    int32_t ni = 0;
    if (hit_box(&b->nodes[0], o, inv, h.t) == INFINITY)
        return h;
    for (;;) {
        const struct bvh_node *nd = &b->nodes[ni];
        ++*visited;
        if (nd->count > 0) {
            for (int32_t k = nd->first; k < nd->first + nd->count; k++) {
                uint32_t i = b->order[k];
                double t = hit_sphere(o, d, s[i]);
                if (t < h.t) {
                    h.t = t;
                    h.sphere = i;
                }
            }
        } else {
            int32_t near = nd->first, far = nd->first + 1;
            double tn = hit_box(&b->nodes[near], o, inv, h.t);
            double tf = hit_box(&b->nodes[far], o, inv, h.t);
            if (tf < tn) {
                int32_t x = near;
                near = far;
                far = x;
                double t = tn;
                tn = tf;
                tf = t;
            }
            if (tn < INFINITY) {
                if (tf < INFINITY) {
                    if (sp == TP2_BVH_MAX_DEPTH) {
                        *overflow = true;
                        return h;
                    }
                    stack[sp++] = far;
                }
                ni = near;
                continue;
            }
        }
        /* Pop the next far child that the best hit so far has not culled. */
        for (;;) {
            if (sp == 0)
                return h;
            ni = stack[--sp];
            if (hit_box(&b->nodes[ni], o, inv, h.t) < INFINITY)
                break;
        }
    }
}

/* Where the ray enters a box given as lo, hi; as hit_box. */
static double hit_lohi(const float lo[3], const float hi[3], const double o[3],
                       const double inv[3], double t_max)
{
    struct bvh_node nd = {{lo[0], lo[1], lo[2]}, 0, {hi[0], hi[1], hi[2]}, 0};
    return hit_box(&nd, o, inv, t_max);
}

/* The shader's traversal of the shader's nodes (bvh_gpu_nodes): test
 * both children of an inner node, enter the nearer (an inner node, or a
 * leaf's objects through its link), push the farther link. */
static struct hit traverse_gpu(const double (*s)[4], const struct bvh *b,
                               const struct bvh_gpu_node *g, const double o[3],
                               const double d[3], bool *overflow)
{
    struct hit h = {INFINITY, UINT32_MAX};
    if (b->node_count == 0)
        return h;
    double inv[3];
    for (int a = 0; a < 3; a++)
        inv[a] = 1.0 / d[a];
    int32_t stack[TP2_BVH_MAX_DEPTH];
    double stack_t[TP2_BVH_MAX_DEPTH];
    int sp = 0;
    int32_t link = 0; /* inner node -link: the root */
    bool inner = true;
    for (;;) {
        if (inner) {
            const struct bvh_gpu_node *nd = &g[-link];
            double t[2];
            for (int k = 0; k < 2; k++) {
                float lo[3] = {nd->x[2 * k], nd->y[2 * k], nd->z[2 * k]};
                float hi[3] = {nd->x[2 * k + 1], nd->y[2 * k + 1], nd->z[2 * k + 1]};
                t[k] = hit_lohi(lo, hi, o, inv, h.t);
            }
            int near = t[1] < t[0];
            if (t[1 - near] < INFINITY) {
                if (sp == TP2_BVH_MAX_DEPTH) {
                    *overflow = true;
                    return h;
                }
                stack_t[sp] = t[1 - near];
                stack[sp++] = nd->link[1 - near];
            }
            if (t[near] < INFINITY) {
                link = nd->link[near];
                inner = link < 0;
                continue;
            }
        } else {
            int32_t first = link >> TP2_BVH_LEAF_BITS;
            int32_t count = (link & TP2_BVH_LEAF_MASK) + 1;
            for (int32_t k = first; k < first + count; k++) {
                uint32_t i = b->order[k];
                double t = hit_sphere(o, d, s[i]);
                if (t < h.t) {
                    h.t = t;
                    h.sphere = i;
                }
            }
        }
        for (;;) { /* the next pending child the best hit has not culled */
            if (sp == 0)
                return h;
            --sp;
            if (stack_t[sp] <= h.t) {
                link = stack[sp];
                inner = link < 0;
                break;
            }
        }
    }
}

/* A ray of one of three kinds, to cover hits as well as misses: random
 * origin and direction inside the set's box; from far outside aimed at a
 * random sphere; from just outside a random sphere (at its own scale, so
 * that tiny spheres among huge coordinates are hit too) aimed at it. */
static void make_ray(const double (*s)[4], size_t n, const double box_lo[3],
                     const double box_hi[3], double o[3], double d[3])
{
    int kind = (int)(rng_next() % 3);
    const double *t = s[rng_next() % n];
    double jitter[3];
    rng_direction(jitter);
    if (kind == 0) {
        for (int a = 0; a < 3; a++)
            o[a] = rng_range(box_lo[a], box_hi[a]);
        rng_direction(d);
        return;
    }
    double dir[3], dist;
    rng_direction(dir);
    if (kind == 1) {
        double ext = 0;
        for (int a = 0; a < 3; a++)
            ext = fmax(ext, box_hi[a] - box_lo[a]);
        dist = 2 * ext + 4 * t[3];
    } else {
        dist = t[3] * rng_range(1.5, 20);
    }
    double len = 0;
    for (int a = 0; a < 3; a++) {
        o[a] = t[a] + dir[a] * dist;
        d[a] = t[a] + 0.9 * t[3] * rng_unit() * jitter[a] - o[a];
        len += d[a] * d[a];
    }
    len = sqrt(len);
    if (!(len > 0) || !isfinite(len)) {
        rng_direction(d);
        return;
    }
    for (int a = 0; a < 3; a++)
        d[a] /= len;
}

/* Casts n_rays seeded rays through the tree and through a linear scan;
 * the nearest hits must agree. Returns the average nodes entered. */
static double check_rays(const char *name, const double (*s)[4], size_t n,
                         const struct bvh *b, int n_rays, uint64_t seed)
{
    if (n_rays == 0)
        return 0;
    if (n == 0) {
        double o[3] = {0, 0, 0}, d[3] = {0, 0, 1};
        long visited = 0;
        bool overflow = false;
        struct hit h = traverse(s, b, o, d, &visited, &overflow);
        expect(h.sphere == UINT32_MAX && visited == 0,
               "%s: an empty tree is never hit", name);
        return 0;
    }
    double box_lo[3] = {INFINITY, INFINITY, INFINITY};
    double box_hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < n; i++)
        for (int a = 0; a < 3; a++) {
            box_lo[a] = fmin(box_lo[a], s[i][a] - s[i][3]);
            box_hi[a] = fmax(box_hi[a], s[i][a] + s[i][3]);
        }
    struct bvh_gpu_node *g = malloc(bvh_gpu_count(b) * sizeof *g);
    expect(g && bvh_gpu_nodes(b, g) == 0, "%s: the shader's nodes are made", name);
    if (!g)
        return 0;
    rng_state = seed;
    int mismatches = 0, gpu_mismatches = 0, hits = 0;
    long visited = 0;
    bool overflow = false;
    for (int i = 0; i < n_rays; i++) {
        double o[3], d[3];
        make_ray(s, n, box_lo, box_hi, o, d);
        struct hit want = linear_scan(s, n, o, d);
        struct hit got = traverse(s, b, o, d, &visited, &overflow);
        struct hit gpu = traverse_gpu(s, b, g, o, d, &overflow);
        hits += want.sphere != UINT32_MAX;
        if (got.t != want.t) { /* equal t: a tie, either sphere is right */
            if (mismatches++ < 3)
                printf("  %s ray %d: tree %u at %.17g, scan %u at %.17g\n",
                       name, i, got.sphere, got.t, want.sphere, want.t);
        }
        if (gpu.t != want.t && gpu_mismatches++ < 3)
            printf("  %s ray %d: shader's nodes %u at %.17g, scan %u at %.17g\n",
                   name, i, gpu.sphere, gpu.t, want.sphere, want.t);
    }
    free(g);
    expect(mismatches == 0, "%s: %d rays (%d hits) agree with a linear scan "
           "(%d do not)", name, n_rays, hits, mismatches);
    expect(gpu_mismatches == 0, "%s: %d rays through the shader's nodes agree with "
           "a linear scan (%d do not)", name, n_rays, gpu_mismatches);
    expect(!overflow, "%s: traversal stack of %d never overflows", name,
           TP2_BVH_MAX_DEPTH);
    return (double)visited / n_rays;
}

/* 1 if a and b are the same tree whatever their node numbering: the same
 * boxes and leaves, met in the same depth-first order. */
static bool same_shape(const struct bvh *a, const struct bvh *b)
{
    if (a->node_count != b->node_count)
        return false;
    int32_t sa[64], sb[64];
    int sp = 0;
    sa[sp] = 0;
    sb[sp++] = 0;
    while (sp > 0) {
        sp--;
        const struct bvh_node *x = &a->nodes[sa[sp]], *y = &b->nodes[sb[sp]];
        if (memcmp(x->lo, y->lo, sizeof x->lo) || memcmp(x->hi, y->hi, sizeof x->hi) ||
            x->count != y->count || (x->count > 0 && x->first != y->first))
            return false;
        if (x->count == 0) {
            if (sp + 2 > 64)
                return false;
            for (int k = 1; k >= 0; k--) {
                sa[sp] = x->first + k;
                sb[sp++] = y->first + k;
            }
        }
    }
    return true;
}

/* Large sets are built on two threads, each half of the tree on its own,
 * in place: the tree must be the one a single thread builds, node for
 * node in the same numbering. */
static void check_threads_agree(const char *name, const double (*s)[4], size_t n,
                                const struct bvh *b)
{
    struct bvh one;
    test_hooks_edit()->bvh_one_thread = true;
    int rc = sphere_bvh_build(s, n, &one);
    test_hooks_edit()->bvh_one_thread = false;
    expect(rc == 0 && same_shape(b, &one) && one.node_count == b->node_count &&
               memcmp(one.nodes, b->nodes, b->node_count * sizeof *b->nodes) == 0 &&
               memcmp(one.order, b->order, n * sizeof *b->order) == 0,
           "%s: one thread builds the same tree as two, node for node", name);
    bvh_free(&one);
}

/* bvh_build_from's source: the boxes, and which it was asked for, in
 * what order. */
struct box_source {
    const double (*boxes)[6];
    size_t asked, out_of_order;
};

static void box_from_source(const void *source, size_t i, double box[6])
{
    struct box_source *b = (struct box_source *)source;
    if (i != b->asked)
        b->out_of_order++;
    b->asked++;
    memcpy(box, b->boxes[i], sizeof b->boxes[i]);
}

/* Boxes handed over one by one build the tree an array of them builds,
 * each asked for once, in order. */
static void check_build_from(void)
{
    size_t n = 100000; /* two threads */
    double (*s)[4] = make_set(SET_MIXED, n, 77);
    double (*boxes)[6] = malloc(n * sizeof *boxes);
    if (!s || !boxes) {
        fputs("test_bvh: out of memory\n", stderr);
        exit(2);
    }
    for (size_t i = 0; i < n; i++)
        for (int a = 0; a < 3; a++) {
            boxes[i][a] = s[i][a] - fabs(s[i][3]);
            boxes[i][a + 3] = s[i][a] + fabs(s[i][3]);
        }
    struct bvh from_array, from_source;
    struct box_source source = {(const double (*)[6])boxes, 0, 0};
    bool built = bvh_build((const double (*)[6])boxes, n, &from_array) == 0 &&
                 bvh_build_from(box_from_source, &source, n, &from_source) == 0;
    expect(built && from_array.node_count == from_source.node_count &&
               memcmp(from_array.nodes, from_source.nodes,
                      from_array.node_count * sizeof *from_array.nodes) == 0 &&
               memcmp(from_array.order, from_source.order, n * sizeof *from_array.order) == 0,
           "build_from: the same tree as from an array");
    expect(source.asked == n && source.out_of_order == 0,
           "build_from: each of %zu boxes asked for once, in order (%zu asks, %zu out of "
           "order)", n, source.asked, source.out_of_order);
    bvh_free(&from_array);
    bvh_free(&from_source);
    free(boxes);
    free(s);
}

/* ---- Driver ---- */

struct set_case {
    const char *name;
    enum set_kind kind;
    size_t n;
    int n_rays;
};

static void run_case(const struct set_case *c, uint64_t seed)
{
    double (*s)[4] = make_set(c->kind, c->n, seed);
    struct bvh b, again;
    double t0 = now_s();
    int rc = sphere_bvh_build((const double (*)[4])s, c->n, &b);
    double build_s = now_s() - t0;
    expect(rc == 0, "%s: bvh_build returns 0", c->name);
    if (rc != 0) {
        free(s);
        return;
    }
    int depth = check_structure(c->name, (const double (*)[4])s, c->n, &b);

    if (c->n <= 100000) { /* a second build of the largest set is slow */
        rc = sphere_bvh_build((const double (*)[4])s, c->n, &again);
        expect(rc == 0 && again.node_count == b.node_count &&
                   (b.node_count == 0 ||
                    (memcmp(again.nodes, b.nodes,
                            b.node_count * sizeof *b.nodes) == 0 &&
                     memcmp(again.order, b.order, c->n * sizeof *b.order) ==
                         0)),
               "%s: the same input builds the same tree", c->name);
        bvh_free(&again);
    }

    if (c->n >= 100000)
        check_threads_agree(c->name, (const double (*)[4])s, c->n, &b);

    double avg = check_rays(c->name, (const double (*)[4])s, c->n, &b,
                            c->n_rays, seed ^ 0x5eed);
    printf("%-16s n %8zu  nodes %8zu  depth %2d  build %7.3f s  "
           "nodes/ray %7.1f\n",
           c->name, c->n, b.node_count, depth, build_s, avg);
    bvh_free(&b);
    expect(b.nodes == NULL && b.order == NULL && b.node_count == 0,
           "%s: bvh_free zeroes the tree", c->name);
    bvh_free(&b); /* again, on the zeroed one */
    free(s);
}

/* SAH must cull: on uniform spheres a ray enters few nodes. */
static void check_quality(void)
{
    const size_t n = 100000;
    double (*s)[4] = make_set(SET_UNIFORM, n, 77);
    struct bvh b;
    if (sphere_bvh_build((const double (*)[4])s, n, &b) != 0) {
        expect(false, "quality: bvh_build returns 0");
        free(s);
        return;
    }
    rng_state = 99;
    const int n_rays = 10000;
    long visited = 0;
    bool overflow = false;
    for (int i = 0; i < n_rays; i++) {
        /* From a random point around the unit cube toward one inside. */
        double o[3], d[3], len = 0;
        for (int a = 0; a < 3; a++) {
            o[a] = rng_range(-1, 2);
            d[a] = rng_unit() - o[a];
            len += d[a] * d[a];
        }
        len = sqrt(len);
        for (int a = 0; a < 3; a++)
            d[a] /= len;
        traverse((const double (*)[4])s, &b, o, d, &visited, &overflow);
    }
    double avg = (double)visited / n_rays;
    printf("quality: %.1f nodes entered per ray over %zu uniform spheres\n",
           avg, n);
    expect(avg < 200, "quality: %.1f nodes per ray < 200", avg);
    bvh_free(&b);
    free(s);
}

/* Zeroed on failure and n == 0, and safe to free either way. */
static void check_edges(void)
{
    struct bvh b;
    memset(&b, 0xab, sizeof b);
    expect(sphere_bvh_build(NULL, 0, &b) == 0 && b.nodes == NULL && b.order == NULL &&
               b.node_count == 0,
           "edges: n = 0 with no array gives a zeroed tree");
    bvh_free(&b);

    struct bvh zero = {0};
    bvh_free(&zero);
    expect(zero.nodes == NULL, "edges: bvh_free on a zeroed tree");

    double one[1][4] = {{1e30, -1e-30, 0, 1e-30}};
    expect(sphere_bvh_build((const double (*)[4])one, 1, &b) == 0 &&
               b.node_count == 1 && b.nodes[0].count == 1 &&
               b.nodes[0].first == 0 && b.order[0] == 0,
           "edges: one sphere is one leaf");
    /* Rounded outward, never onto the value itself. */
    expect((double)b.nodes[0].lo[0] < 1e30 && (double)b.nodes[0].hi[0] > 1e30 &&
               (double)b.nodes[0].lo[1] < -1e-30 - 1e-30 &&
               (double)b.nodes[0].hi[1] > 0 && b.nodes[0].lo[2] < 0 &&
               b.nodes[0].hi[2] > 0,
           "edges: a single sphere's bounds strictly contain it");
    bvh_free(&b);

    /* The tightest float box strictly outside the exact one: each bound
     * moves to the next float beyond it, or stays put where it lies
     * between two floats; past float range it becomes infinite. */
    struct {
        double lo, hi;
        float want_lo, want_hi;
    } bounds[] = {
        {1.0, 2.0, 0x1.fffffep-1f, 0x1.000002p+1f},
        {0.0, 0.0, -FLT_TRUE_MIN, FLT_TRUE_MIN},
        {-0.0, 0x1p-200, -FLT_TRUE_MIN, FLT_TRUE_MIN},
        {0.1, 0.1, 0x1.999998p-4f, 0x1.99999ap-4f}, /* 0.1 lies between floats */
        {-FLT_MAX, FLT_MAX, -INFINITY, INFINITY},
        {1e300, INFINITY, FLT_MAX, INFINITY},
        {-INFINITY, -1e300, -INFINITY, -FLT_MAX},
    };
    for (size_t i = 0; i < sizeof bounds / sizeof bounds[0]; i++) {
        double box[1][6] = {{bounds[i].lo, bounds[i].lo, bounds[i].lo, bounds[i].hi,
                             bounds[i].hi, bounds[i].hi}};
        bool exact = bvh_build((const double (*)[6])box, 1, &b) == 0 && b.node_count == 1;
        for (int a = 0; exact && a < 3; a++)
            exact = b.nodes[0].lo[a] == bounds[i].want_lo &&
                    b.nodes[0].hi[a] == bounds[i].want_hi;
        expect(exact, "edges: box [%a, %a] rounds out to [%a, %a]", bounds[i].lo, bounds[i].hi,
               (double)bounds[i].want_lo, (double)bounds[i].want_hi);
        bvh_free(&b);
    }

    /* Beyond what the index type can hold: refused before reading. */
    memset(&b, 0xab, sizeof b);
    double one_box[1][6] = {{0, 0, 0, 1, 1, 1}};
    expect(bvh_build((const double (*)[6])one_box, ((size_t)1 << 30) + 1, &b) ==
                   -1 &&
               b.nodes == NULL && b.order == NULL && b.node_count == 0,
           "edges: n > 2^30 fails with a zeroed tree");

    /* Outside the contract, but the build must neither crash nor lose a
     * sphere: a NaN center gets an infinite box. */
    double with_nan[12][4];
    for (int i = 0; i < 12; i++) {
        with_nan[i][0] = i;
        with_nan[i][1] = -i;
        with_nan[i][2] = 0.5 * i;
        with_nan[i][3] = 0.25;
    }
    with_nan[5][1] = NAN;
    bool ok = sphere_bvh_build((const double (*)[4])with_nan, 12, &b) == 0;
    bool found = false;
    for (size_t i = 0; ok && i < b.node_count; i++) {
        const struct bvh_node *nd = &b.nodes[i];
        for (int32_t k = nd->first; nd->count > 0 && k < nd->first + nd->count;
             k++)
            if (b.order[k] == 5)
                found = nd->lo[1] == -INFINITY && nd->hi[1] == INFINITY;
    }
    expect(ok && found, "edges: a NaN center's leaf is unbounded");
    bvh_free(&b);
}

/* A tree moved by -origin (bvh_move) is a tree over its spheres moved the
 * same way: every box still holds them, each parent its children. */
static void check_moved(void)
{
    const double origin[3] = {4096, -8192.5, 2048.25};
    const size_t n = 1000;
    double (*near)[4] = make_set(SET_UNIFORM, n, 77);
    double (*far)[4] = malloc(n * sizeof *far);
    if (!near || !far) {
        fputs("test_bvh: out of memory\n", stderr);
        exit(2);
    }
    for (size_t i = 0; i < n; i++) {
        for (int a = 0; a < 3; a++)
            far[i][a] = near[i][a] + origin[a];
        far[i][3] = near[i][3];
        for (int a = 0; a < 3; a++) /* what the records get: rounded once more */
            near[i][a] = far[i][a] - origin[a];
    }
    struct bvh b;
    CHECK(sphere_bvh_build((const double (*)[4])far, n, &b) == 0);
    bvh_move(&b, origin);
    check_structure("moved", (const double (*)[4])near, n, &b);
    bvh_free(&b);
    free(near);
    free(far);
}

int main(void)
{
    static const struct set_case cases[] = {
        {"empty", SET_UNIFORM, 0, 1},
        {"one", SET_UNIFORM, 1, 1000},
        {"two", SET_UNIFORM, 2, 1000},
        {"seven", SET_UNIFORM, 7, 1000},
        {"uniform-1000", SET_UNIFORM, 1000, 1000},
        {"uniform-100000", SET_UNIFORM, 100000, 1000},
        {"same-center", SET_SAME_CENTER, 3000, 1000},
        {"few-centers", SET_FEW_CENTERS, 3000, 1000},
        {"mixed-scales", SET_MIXED, 20000, 1000},
        {"geometric", SET_GEOMETRIC, 2000, 1000},
        {"huge", SET_HUGE, 500, 1000},
        {"extreme", SET_EXTREME, 500, 0}, /* no rays: r^2 overflows */
        {"uniform-1000000", SET_UNIFORM, 1000000, 20},
    };
    check_edges();
    check_build_from();
    check_moved();
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++)
        run_case(&cases[i], 1000 + i);
    check_quality();
    return unit_report();
}
