/* convex.c: bounding boxes of convex polyhedra (see convex.h).
 *
 * Each side of the box is a linear program: the largest (or smallest) x, y
 * or z over the faces' half-spaces. They are solved by Seidel's randomized
 * incremental algorithm, in expected time linear in the faces: keep the
 * best point of the half-spaces added so far; when the next one excludes
 * it, the new best point lies on that half-space's plane, a problem of one
 * dimension less over the half-spaces before it. A box of half-width M
 * around the origin keeps every problem bounded; a side that reaches it is
 * an unbounded polyhedron (or one too large to be worth a box). */
#include "convex.h"

#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>

#include "vec3.h"

/* Relative tolerance of the tests below: far above rounding error of a
 * few operations in double, far below anything a scene means. */
#define CONVEX_TOL 1e-9

/* a.x <= b, over the coordinates not yet eliminated (a[k] == 0 for the
 * others); scale is the size of the terms it was made of, for tolerances. */
struct half {
    double a[3], b, scale;
};

struct lp {
    double m;             /* the bounding box's half-width */
    struct half *work[3]; /* each dimension's projected half-spaces */
    size_t budget;        /* half-spaces it may still project */
};

/* The part of h's side that is rounding, at x. */
static double slack(const struct half *h, const double x[3])
{
    double terms = fabs(h->b);
    for (int l = 0; l < 3; l++)
        terms += fabs(h->a[l] * x[l]);
    return CONVEX_TOL * terms;
}

/* The best x_k over the half-spaces (one coordinate k left): false if they
 * exclude each other. Coefficients that are rounding are taken for 0,
 * which drops a half-space nearly parallel to the line (a larger box) or
 * calls the problem infeasible (then no box at all): both are safe. */
static bool solve_1d(const struct lp *p, int k, const struct half *h, size_t n,
                     const double c[3], double x[3])
{
    double lo = -p->m, hi = p->m;
    for (size_t i = 0; i < n; i++) {
        double rest = h[i].b;
        for (int l = 0; l < 3; l++)
            if (l != k)
                rest -= h[i].a[l] * x[l];
        double a = h[i].a[k];
        if (fabs(a) <= 1e-12 * h[i].scale) {
            if (rest < -slack(&h[i], x))
                return false;
        } else if (a > 0) {
            hi = fmin(hi, rest / a);
        } else {
            lo = fmax(lo, rest / a);
        }
    }
    if (lo > hi + CONVEX_TOL * (fabs(lo) + fabs(hi)))
        return false;
    x[k] = c[k] > 0 ? hi : c[k] < 0 ? lo : fmin(fmax(0.0, lo), hi);
    return true;
}

/* h projected onto the plane p.x = q, coordinate k eliminated. */
static struct half project(const struct half *h, const struct half *plane, int k)
{
    double f = h->a[k] / plane->a[k];
    struct half out = {{0, 0, 0}, h->b - f * plane->b, h->scale + fabs(f) * plane->scale};
    for (int l = 0; l < 3; l++)
        out.a[l] = l == k ? 0 : h->a[l] - f * plane->a[l];
    return out;
}

/* Maximizes c.x over the half-spaces h[0..n) and the box, over the d
 * coordinates whose bit is in `free` (x holds the others). */
static bool solve(struct lp *p, int d, unsigned free, const struct half *h, size_t n,
                  const double c[3], double x[3])
{
    int only = free & 1 ? 0 : free & 2 ? 1 : 2;
    if (d == 1)
        return solve_1d(p, only, h, n, c, x);
    for (int l = 0; l < 3; l++) /* the box's best corner */
        if (free >> l & 1)
            x[l] = c[l] > 0 ? p->m : c[l] < 0 ? -p->m : 0;
    struct half *sub = p->work[d - 1];
    for (size_t i = 0; i < n; i++) {
        /* No tolerance here: a point kept that a half-space excludes, by
         * however little, is no longer the best of those before it, and
         * the next plane's problem could then miss the best point. */
        if (vec3_dot(h[i].a, x) <= h[i].b)
            continue;
        int k = -1; /* eliminate the coordinate the plane depends on most */
        for (int l = 0; l < 3; l++)
            if (free >> l & 1 && (k < 0 || fabs(h[i].a[l]) > fabs(h[i].a[k])))
                k = l;
        if (!(fabs(h[i].a[k]) > 1e-12 * h[i].scale))
            return false; /* 0 <= b, violated: infeasible */
        if (p->budget < i + 2)
            return false; /* an order that defeats the shuffle: give up */
        p->budget -= i + 2;
        /* The box's own sides on k now bound the plane's problem. */
        struct half side[2] = {{{0, 0, 0}, p->m, 1}, {{0, 0, 0}, p->m, 1}};
        side[0].a[k] = 1;
        side[1].a[k] = -1;
        size_t m = 0;
        for (int s = 0; s < 2; s++)
            sub[m++] = project(&side[s], &h[i], k);
        for (size_t j = 0; j < i; j++)
            sub[m++] = project(&h[j], &h[i], k);
        double f = c[k] / h[i].a[k], cs[3];
        for (int l = 0; l < 3; l++)
            cs[l] = l == k ? 0 : c[l] - f * h[i].a[l];
        if (!solve(p, d - 1, free & ~(1u << k), sub, m, cs, x))
            return false;
        double rest = h[i].b;
        for (int l = 0; l < 3; l++)
            if (l != k)
                rest -= h[i].a[l] * x[l];
        x[k] = rest / h[i].a[k];
    }
    return true;
}

int convex_bounds(const double *f, size_t n, double lo[3], double hi[3])
{
    if (n < 4) /* fewer than four half-spaces never enclose a volume */
        return 0;
    struct half *h = malloc((3 * n + 4) * sizeof *h);
    if (!h)
        return 0; /* unbounded is always right, only slower */
    struct lp p = {0, {NULL, h + n, h + 2 * n + 2}, 0};
    double far = 0;
    for (size_t i = 0; i < n; i++) {
        double len = vec3_unit(f + 4 * i, h[i].a);
        h[i].b = -f[4 * i + 3] / len;
        h[i].scale = 1;
        far = fmax(far, fabs(h[i].b));
    }
    /* The same shuffle every run (the box must not change between runs):
     * the expected linear time holds for any polyhedron, as long as the
     * order does not depend on it. */
    uint64_t s = 0x9e3779b97f4a7c15u;
    for (size_t i = n - 1; i > 0; i--) {
        s ^= s << 13, s ^= s >> 7, s ^= s << 17;
        size_t j = (size_t)(s % (i + 1));
        struct half t = h[i];
        h[i] = h[j], h[j] = t;
    }
    p.m = 0x1p20 * (far + 1);
    /* Per side: the tests' polyhedra project at most 27 n half-spaces; at
     * 4096 faces this caps a side at a few milliseconds. */
    size_t budget = 256 * n + 4096;
    int bounded = 1;
    for (int side = 0; side < 6 && bounded; side++) {
        int a = side / 2;
        double c[3] = {0, 0, 0}, x[3] = {0, 0, 0};
        c[a] = side % 2 ? 1 : -1;
        p.budget = budget;
        if (!solve(&p, 3, 7, h, n, c, x) || !(fabs(x[a]) < 0.5 * p.m))
            bounded = 0; /* infeasible (empty: nothing to see) or unbounded */
        else if (side % 2)
            hi[a] = x[a];
        else
            lo[a] = x[a];
    }
    free(h);
    for (int a = 0; a < 3 && bounded; a++)
        bounded = lo[a] <= hi[a]; /* else empty, but for rounding */
    if (!bounded)
        return 0;
    /* Corners are found to about 1e-16 of the faces' distances from 0
     * (a face that does not touch the polyhedron may lie much farther out
     * than it) times how nearly parallel the faces are: the pad allows a
     * factor of 1e4 for that. */
    for (int a = 0; a < 3; a++) {
        double pad = CONVEX_TOL * (fabs(lo[a]) + fabs(hi[a]) + (hi[a] - lo[a])) + 1e-12 * far;
        lo[a] -= pad;
        hi[a] += pad;
    }
    return 1;
}
