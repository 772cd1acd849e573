/* convex.c: bounding boxes of convex polyhedra (see convex.h). */
#include "convex.h"

#include <math.h>
#include <stdbool.h>

#include "vec3.h"

/* Relative tolerance of the tests below: far above rounding error of a
 * few operations in double, far below anything a scene means. */
#define CONVEX_TOL 1e-9

/* 1 if some direction v != 0 has n.v <= 0 for every face: the polyhedron
 * then contains a ray from each of its points, so it is unbounded (or
 * empty). Such a cone, unless it holds a line, is spanned by extreme rays
 * on two independent faces, parallel to n_i x n_j; one holding a line
 * exists exactly when the normals do not span space. */
static bool has_recession_direction(const double *f, size_t n)
{
    bool spans = false;
    for (size_t i = 0; i < n; i++)
        for (size_t j = i + 1; j < n; j++) {
            double v[3];
            vec3_cross(f + 4 * i, f + 4 * j, v);
            if (!vec3_unit(v, v))
                continue;
            for (size_t k = 0; k < n && !spans; k++) {
                double u[3];
                vec3_unit(f + 4 * k, u);
                spans = fabs(vec3_dot(u, v)) > CONVEX_TOL;
            }
            for (int sign = -1; sign <= 1; sign += 2) {
                size_t k = 0;
                for (; k < n; k++) {
                    double u[3];
                    vec3_unit(f + 4 * k, u);
                    if (sign * vec3_dot(u, v) > CONVEX_TOL)
                        break;
                }
                if (k == n)
                    return true;
            }
        }
    return !spans;
}

/* The point where faces i, j, k meet (Cramer's rule); false if they do
 * not meet in one point. */
static bool corner(const double *a, const double *b, const double *c, double x[3])
{
    double bc[3], ca[3], ab[3];
    vec3_cross(b, c, bc);
    vec3_cross(c, a, ca);
    vec3_cross(a, b, ab);
    double det = vec3_dot(a, bc);
    double scale = sqrt(vec3_dot(a, a) * vec3_dot(b, b) * vec3_dot(c, c));
    if (!(fabs(det) > CONVEX_TOL * scale))
        return false;
    for (int i = 0; i < 3; i++)
        x[i] = -(a[3] * bc[i] + b[3] * ca[i] + c[3] * ab[i]) / det;
    return isfinite(x[0]) && isfinite(x[1]) && isfinite(x[2]);
}

/* x satisfies every face, within the tolerance (generous: a corner kept
 * by mistake only widens the box). */
static bool inside_all(const double *f, size_t n, const double x[3])
{
    for (size_t m = 0; m < n; m++) {
        const double *p = f + 4 * m;
        double len = sqrt(vec3_dot(p, p));
        double slack = CONVEX_TOL * (fabs(p[3]) + len * vec3_max_abs(x));
        if (vec3_dot(p, x) + p[3] > slack)
            return false;
    }
    return true;
}

int convex_bounds(const double *f, size_t n, double lo[3], double hi[3])
{
    if (n < 4 || n > CONVEX_MAX_FACES || has_recession_direction(f, n))
        return 0;
    bool any = false;
    for (int a = 0; a < 3; a++) {
        lo[a] = INFINITY;
        hi[a] = -INFINITY;
    }
    /* A bounded polyhedron is the hull of its corners. */
    for (size_t i = 0; i < n; i++)
        for (size_t j = i + 1; j < n; j++)
            for (size_t k = j + 1; k < n; k++) {
                double x[3];
                if (!corner(f + 4 * i, f + 4 * j, f + 4 * k, x) || !inside_all(f, n, x))
                    continue;
                any = true;
                for (int a = 0; a < 3; a++) {
                    lo[a] = fmin(lo[a], x[a]);
                    hi[a] = fmax(hi[a], x[a]);
                }
            }
    for (int a = 0; a < 3; a++) {
        if (!any) {
            lo[a] = hi[a] = 0;
            continue;
        }
        double pad = CONVEX_TOL * (fabs(lo[a]) + fabs(hi[a]) + (hi[a] - lo[a]));
        lo[a] -= pad;
        hi[a] += pad;
    }
    return 1;
}
