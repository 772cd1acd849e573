/* ties.c: coincident flat surfaces (ties.h).
 *
 * Each plane is put in one orientation (its normal's largest component
 * positive, the first of those within a few tolerances of the largest),
 * the surfaces sorted by that d, and each compared with those after it
 * whose d is within the tolerance: a union-find joins the coincident. */
#include "ties.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define WINDOW 256

struct keyed {
    double p[4]; /* oriented */
    size_t at;   /* index into the surfaces */
};

static void oriented(const double p[4], double out[4])
{
    double m[3] = {fabs(p[0]), fabs(p[1]), fabs(p[2])};
    double big = fmax(m[0], fmax(m[1], m[2]));
    int a = m[0] >= big - 4 * TIE_TOLERANCE ? 0 : m[1] >= big - 4 * TIE_TOLERANCE ? 1 : 2;
    double sign = p[a] < 0 ? -1 : 1;
    for (int k = 0; k < 4; k++)
        out[k] = sign * p[k];
}

static int by_d(const void *x, const void *y)
{
    double a = ((const struct keyed *)x)->p[3], b = ((const struct keyed *)y)->p[3];
    return a < b ? -1 : a > b ? 1 : 0;
}

static size_t root(size_t *up, size_t i)
{
    while (up[i] != i)
        i = up[i] = up[up[i]];
    return i;
}

/* Whether surface a is a better canonical plane than b. */
static bool better(const struct tie_surface *a, const struct tie_surface *b)
{
    return a->role != b->role ? a->role < b->role : a->object < b->object;
}

int ties_group(struct tie_surface *s, size_t n, double scale, double (*canonical)[4],
               bool *twin)
{
    struct keyed *k = malloc((n ? n : 1) * sizeof *k);
    size_t *up = malloc((n ? n : 1) * sizeof *up);
    size_t *best = malloc((n ? n : 1) * sizeof *best);
    size_t *owner = malloc((n ? n : 1) * sizeof *owner); /* an object of the group, or SIZE_MAX: several */
    if (!k || !up || !best || !owner) {
        free(k), free(up), free(best), free(owner);
        return -1;
    }
    double tol_d = TIE_TOLERANCE * (scale > 0 ? scale : 1);
    for (size_t i = 0; i < n; i++) {
        oriented(s[i].plane, k[i].p);
        k[i].at = i;
        up[i] = i;
        twin[i] = false;
        tol_d = fmax(tol_d, TIE_TOLERANCE * fabs(s[i].plane[3]));
    }
    qsort(k, n, sizeof *k, by_d);
    for (size_t i = 0; i < n; i++)
        for (size_t j = i + 1; j < n && j <= i + WINDOW && k[j].p[3] - k[i].p[3] <= tol_d; j++)
            if (fabs(k[i].p[0] - k[j].p[0]) <= TIE_TOLERANCE &&
                fabs(k[i].p[1] - k[j].p[1]) <= TIE_TOLERANCE &&
                fabs(k[i].p[2] - k[j].p[2]) <= TIE_TOLERANCE) {
                size_t a = root(up, k[i].at), b = root(up, k[j].at);
                if (a != b)
                    up[a] = b;
            }
    for (size_t i = 0; i < n; i++) {
        best[i] = SIZE_MAX;
        owner[i] = s[i].object;
    }
    for (size_t i = 0; i < n; i++) {
        size_t r = root(up, i);
        if (best[r] == SIZE_MAX || better(&s[i], &s[best[r]]))
            best[r] = i;
        if (owner[r] != s[i].object)
            owner[r] = SIZE_MAX;
    }
    for (size_t i = 0; i < n; i++) {
        size_t r = root(up, i);
        if (owner[r] != SIZE_MAX)
            continue; /* one object's faces only */
        const double *c = s[best[r]].plane;
        bool flip = s[i].role < TIE_CAP &&
                    s[i].plane[0] * c[0] + s[i].plane[1] * c[1] + s[i].plane[2] * c[2] < 0;
        for (int a = 0; a < 4; a++)
            canonical[i][a] = (flip ? -c[a] : c[a]) + 0.0; /* -0 is 0: the row stays as it was */
        twin[i] = true;
    }
    free(k), free(up), free(best), free(owner);
    return 0;
}

/* By oriented d, for ties_near's binary search. */
static int by_oriented_d(const void *x, const void *y)
{
    double a[4], b[4];
    oriented(((const struct tie_surface *)x)->plane, a);
    oriented(((const struct tie_surface *)y)->plane, b);
    return a[3] < b[3] ? -1 : a[3] > b[3] ? 1 : 0;
}

void ties_sort(struct tie_surface *s, size_t n)
{
    qsort(s, n, sizeof *s, by_oriented_d);
}

bool ties_near(const struct tie_surface *sorted, size_t n, const double plane[4],
               double scale, size_t other_than)
{
    double p[4];
    oriented(plane, p);
    double tol_d = TIE_TOLERANCE * fmax(scale > 0 ? scale : 1, fabs(p[3]));
    size_t lo = 0, hi = n; /* the first with d >= p[3] - tol_d */
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        double q[4];
        oriented(sorted[mid].plane, q);
        if (q[3] < p[3] - tol_d)
            lo = mid + 1;
        else
            hi = mid;
    }
    for (size_t j = lo; j < n && j < lo + WINDOW; j++) {
        double q[4];
        oriented(sorted[j].plane, q);
        if (q[3] > p[3] + tol_d)
            break;
        if (sorted[j].object != other_than && fabs(q[0] - p[0]) <= TIE_TOLERANCE &&
            fabs(q[1] - p[1]) <= TIE_TOLERANCE && fabs(q[2] - p[2]) <= TIE_TOLERANCE)
            return true;
    }
    return false;
}
