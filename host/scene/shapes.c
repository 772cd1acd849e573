/* shapes.c: the table of object kinds (see shapes.h).
 *
 * Each kind's numbers, as stored in scene.reals:
 *   sphere      cx cy cz r
 *   plane       a b c d                      (as written)
 *   polyhedron  a b c d per face             (as written)
 *   box         x0 y0 z0 x1 y1 z1            (as written)
 *   cylinder    x0 y0 z0 x1 y1 z1 r
 *   cone        x0 y0 z0 r0 x1 y1 z1 r1
 *   torus       cx cy cz ax ay az R r
 *   quadric     A B C D E F G H I J
 *   triangle    x0 y0 z0 x1 y1 z1 x2 y2 z2
 *   mesh        9 numbers per triangle of its OBJ file, degenerate ones
 *               dropped
 * and the GPU record each packs into (rows a, b, c of layout.glsl's
 * Object; "extra" rows in the extra buffer at ids.w):
 *   sphere      a = center, r
 *   plane       a = unit normal, d / |n|
 *   polyhedron  a = face count; extra = each face as a plane
 *   box         a = min corner; b = max corner
 *   cylinder    a = base center, r; b = unit axis, length
 *   cone        a = base center, r0; b = unit axis, length; c = r1
 *   torus       a = center, R; b = unit axis, r
 *   quadric     a = A B C D; b = E F G H; c = I J, all about the
 *               reference point extra[0] (its center when it has one)
 *               and scaled so the largest is 1
 *   triangle    a, b, c = the corners, with the unit normal
 *               (counter-clockwise seen from outside) in their w
 * and then moved (each kind's move) so that scene_pack.c's origin is 0. */
#include "shapes.h"

#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "convex.h"
#include "obj_read.h"
#include "tp2_shared.h"
#include "vec3.h"

/* ---- helpers ----------------------------------------------------------- */

static void record_row(struct shape_record *rec, int row, const double v[3], double w)
{
    rec->row[row][0] = v[0];
    rec->row[row][1] = v[1];
    rec->row[row][2] = v[2];
    rec->row[row][3] = w;
}

/* Widens a box computed with a few roundings so it surely holds the
 * exact shape (the BVH then rounds it outward to float). */
static void widen(double lo[3], double hi[3])
{
    for (int a = 0; a < 3; a++) {
        double m = fmax(fabs(lo[a]), fabs(hi[a])) * 1e-12 + DBL_MIN;
        lo[a] -= m;
        hi[a] += m;
    }
}

/* Reads a b c d of a plane or face, (a b c) != 0; `what` names it. */
static int read_plane_numbers(struct scene_reader *r, const char *what)
{
    double v[4];
    struct token at;
    if (read_numbers(r, v, 3, &at))
        return -1;
    if (v[0] == 0 && v[1] == 0 && v[2] == 0)
        return read_fail(r, &at, "%s normal (a b c) must not be zero", what);
    if (read_numbers(r, v + 3, 1, NULL))
        return -1;
    return read_push(r, v, 4);
}

/* A plane a b c d as unit normal and distance. */
static void unit_plane(const double p[4], double out[4])
{
    double len = vec3_unit(p, out);
    out[3] = p[3] / len;
}

static size_t one_primitive(const double *p, size_t n)
{
    (void)p;
    (void)n;
    return 1;
}

static size_t no_extra(const double *p, size_t n)
{
    (void)p;
    (void)n;
    return 0;
}

static bool unbounded(const double *p, size_t n, size_t k, double lo[3], double hi[3])
{
    (void)p, (void)n, (void)k, (void)lo, (void)hi;
    return false;
}

/* Reads two points that must differ; *second gets the second's token. */
static int read_two_points(struct scene_reader *r, double a[3], double b[3],
                           struct token *second)
{
    return read_numbers(r, a, 3, NULL) || read_numbers(r, b, 3, second);
}

/* Box of a disk of radius rad around c, perpendicular to unit axis u. */
static void disk_box(const double c[3], const double u[3], double rad,
                     double lo[3], double hi[3])
{
    for (int a = 0; a < 3; a++) {
        double e = rad * sqrt(fmax(0.0, 1.0 - u[a] * u[a]));
        lo[a] = fmin(lo[a], c[a] - e);
        hi[a] = fmax(hi[a], c[a] + e);
    }
}

static void box_empty(double lo[3], double hi[3])
{
    for (int a = 0; a < 3; a++) {
        lo[a] = INFINITY;
        hi[a] = -INFINITY;
    }
}

/* Point v (xyz) with origin at 0. */
static void move_point(double v[4], const double origin[3])
{
    vec3_sub(v, origin, v);
}

/* Plane v (unit normal, d: n.x + d = 0) with origin at 0. */
static void move_plane(double v[4], const double origin[3])
{
    v[3] += vec3_dot(v, origin);
}

/* Kinds whose only point is row a (a center, a base). */
static void move_first_row(struct shape_record *rec, double (*extra)[4],
                           const double origin[3])
{
    (void)extra;
    move_point(rec->row[0], origin);
}

/* ---- sphere ------------------------------------------------------------ */

static int sphere_read(struct scene_reader *r)
{
    double v[4];
    if (read_numbers(r, v, 3, NULL) ||
        read_bounded(r, &v[3], 0, "a positive sphere radius"))
        return -1;
    return read_push(r, v, 4);
}

static bool sphere_bounds(const double *p, size_t n, size_t k, double lo[3], double hi[3])
{
    (void)n, (void)k;
    for (int a = 0; a < 3; a++) {
        lo[a] = p[a] - p[3];
        hi[a] = p[a] + p[3];
    }
    widen(lo, hi);
    return true;
}

static void sphere_pack(const double *p, size_t n, size_t k, struct shape_record *rec,
                        double (*extra)[4])
{
    (void)n, (void)k, (void)extra;
    record_row(rec, 0, p, p[3]);
}

/* ---- plane ------------------------------------------------------------- */

static int plane_read(struct scene_reader *r)
{
    return read_plane_numbers(r, "plane");
}

static void plane_pack(const double *p, size_t n, size_t k, struct shape_record *rec,
                       double (*extra)[4])
{
    (void)n, (void)k, (void)extra;
    unit_plane(p, rec->row[0]);
}

static void plane_move(struct shape_record *rec, double (*extra)[4], const double origin[3])
{
    (void)extra;
    move_plane(rec->row[0], origin);
}

static size_t plane_faces(const struct shape_record *rec, const double (*extra)[4],
                          double (*planes)[4])
{
    (void)extra;
    memcpy(planes[0], rec->row[0], sizeof planes[0]);
    return 1;
}

/* ---- polyhedron -------------------------------------------------------- */

static int polyhedron_read(struct scene_reader *r)
{
    size_t faces = 0;
    if (read_integer(r, 1, TP2_MAX_FACES, "a positive integer face count",
                     "face count", &faces))
        return -1;
    for (size_t i = 0; i < faces; i++)
        if (read_plane_numbers(r, "polyhedron face"))
            return -1;
    return 0;
}

static bool polyhedron_bounds(const double *p, size_t n, size_t k, double lo[3],
                              double hi[3])
{
    (void)k;
    return convex_bounds(p, n / 4, lo, hi) == 1;
}

static size_t polyhedron_extra(const double *p, size_t n)
{
    (void)p;
    return n / 4;
}

/* Row 0: the face count; rows 1 and 2 its box's corners, which the float
 * pass's edge test (shapes.glsl, edge_graze) reads: crossed (lo > hi)
 * where it is open or beyond float's range, else rounded to floats, as
 * the record's other numbers are where the faces are (TP2_SHAPE_INEXACT
 * counts them all; the test's margin is far above that rounding). */
static void polyhedron_pack(const double *p, size_t n, size_t k, struct shape_record *rec,
                            double (*extra)[4])
{
    double lo[3], hi[3];
    bool boxed = polyhedron_bounds(p, n, k, lo, hi);
    for (int a = 0; a < 3; a++)
        boxed = boxed && fabs(lo[a]) <= FLT_MAX && fabs(hi[a]) <= FLT_MAX;
    for (int a = 0; a < 3; a++) {
        lo[a] = boxed ? (float)lo[a] : 1;
        hi[a] = boxed ? (float)hi[a] : 0;
    }
    rec->row[0][0] = (double)(n / 4);
    record_row(rec, 1, lo, 0);
    record_row(rec, 2, hi, 0);
    for (size_t i = 0; i < n / 4; i++)
        unit_plane(p + 4 * i, extra[i]);
}

static void polyhedron_move(struct shape_record *rec, double (*extra)[4],
                            const double origin[3])
{
    move_point(rec->row[1], origin);
    move_point(rec->row[2], origin);
    for (size_t i = 0; i < (size_t)rec->row[0][0]; i++)
        move_plane(extra[i], origin);
}

static size_t polyhedron_faces(const struct shape_record *rec, const double (*extra)[4],
                               double (*planes)[4])
{
    size_t n = (size_t)rec->row[0][0];
    memcpy(planes, extra, n * sizeof planes[0]);
    return n;
}

/* ---- box --------------------------------------------------------------- */

static int box_read(struct scene_reader *r)
{
    double v[6];
    struct token second;
    if (read_two_points(r, v, v + 3, &second))
        return -1;
    if (v[0] == v[3] || v[1] == v[4] || v[2] == v[5])
        return read_fail(r, &second, "box corners must differ in x, y and z");
    return read_push(r, v, 6);
}

static bool box_bounds(const double *p, size_t n, size_t k, double lo[3], double hi[3])
{
    (void)n, (void)k;
    for (int a = 0; a < 3; a++) {
        lo[a] = fmin(p[a], p[a + 3]);
        hi[a] = fmax(p[a], p[a + 3]);
    }
    return true;
}

static void box_pack(const double *p, size_t n, size_t k, struct shape_record *rec,
                     double (*extra)[4])
{
    double lo[3], hi[3];
    (void)extra;
    box_bounds(p, n, k, lo, hi);
    record_row(rec, 0, lo, 0);
    record_row(rec, 1, hi, 0);
}

static void box_move(struct shape_record *rec, double (*extra)[4], const double origin[3])
{
    (void)extra;
    move_point(rec->row[0], origin);
    move_point(rec->row[1], origin);
}

/* Faces -x + lo = 0 and x - hi = 0 per axis: clip_slab's (lo - o) / d is
 * plane_t's arithmetic on them, sign for sign. */
static size_t box_faces(const struct shape_record *rec, const double (*extra)[4],
                        double (*planes)[4])
{
    (void)extra;
    for (int a = 0; a < 3; a++) {
        double *low = planes[2 * a], *high = planes[2 * a + 1];
        memset(low, 0, sizeof planes[0]);
        memset(high, 0, sizeof planes[0]);
        low[a] = -1;
        low[3] = rec->row[0][a];
        high[a] = 1;
        high[3] = -rec->row[1][a];
    }
    return 6;
}

/* ---- cylinder and cone ------------------------------------------------- */

static int cylinder_read(struct scene_reader *r)
{
    double v[7];
    struct token second;
    if (read_two_points(r, v, v + 3, &second))
        return -1;
    if (v[0] == v[3] && v[1] == v[4] && v[2] == v[5])
        return read_fail(r, &second, "cylinder end points must differ");
    if (read_bounded(r, &v[6], 0, "a positive cylinder radius"))
        return -1;
    return read_push(r, v, 7);
}

/* The axis of a cylinder or cone from a to b: unit u; returns the length. */
static double axis_of(const double a[3], const double b[3], double u[3])
{
    double d[3];
    vec3_sub(b, a, d);
    return vec3_unit(d, u);
}

/* Box of the solid between a disk of radius ra around a and one of radius
 * rb around b, both perpendicular to the axis a-b (a cylinder, a cone). */
static bool tapered_bounds(const double a[3], double ra, const double b[3], double rb,
                           double lo[3], double hi[3])
{
    double u[3];
    axis_of(a, b, u);
    box_empty(lo, hi);
    disk_box(a, u, ra, lo, hi);
    disk_box(b, u, rb, lo, hi);
    widen(lo, hi);
    return true;
}

static bool cylinder_bounds(const double *p, size_t n, size_t k, double lo[3], double hi[3])
{
    (void)n, (void)k;
    return tapered_bounds(p, p[6], p + 3, p[6], lo, hi);
}

static void cylinder_pack(const double *p, size_t n, size_t k, struct shape_record *rec,
                          double (*extra)[4])
{
    double u[3];
    (void)n, (void)k, (void)extra;
    double h = axis_of(p, p + 3, u);
    record_row(rec, 0, p, p[6]);
    record_row(rec, 1, u, h);
}

static int cone_read(struct scene_reader *r)
{
    double v[8];
    struct token second, r1_at;
    if (read_numbers(r, v, 3, NULL) ||
        read_bounded(r, &v[3], 1, "a non-negative cone radius") ||
        read_numbers(r, v + 4, 3, &second))
        return -1;
    if (v[0] == v[4] && v[1] == v[5] && v[2] == v[6])
        return read_fail(r, &second, "cone end points must differ");
    r1_at = *read_peek(r);
    if (read_bounded(r, &v[7], 1, "a non-negative cone radius"))
        return -1;
    if (v[3] == 0 && v[7] == 0)
        return read_fail(r, &r1_at, "cone radii must not both be 0");
    return read_push(r, v, 8);
}

static bool cone_bounds(const double *p, size_t n, size_t k, double lo[3], double hi[3])
{
    (void)n, (void)k;
    return tapered_bounds(p, p[3], p + 4, p[7], lo, hi);
}

static void cone_pack(const double *p, size_t n, size_t k, struct shape_record *rec,
                      double (*extra)[4])
{
    double u[3];
    const double r1[3] = {p[7], 0, 0};
    (void)n, (void)k, (void)extra;
    double h = axis_of(p, p + 4, u);
    record_row(rec, 0, p, p[3]);
    record_row(rec, 1, u, h);
    record_row(rec, 2, r1, 0);
}

/* ---- torus ------------------------------------------------------------- */

static int torus_read(struct scene_reader *r)
{
    double v[8];
    struct token axis_at;
    if (read_numbers(r, v, 3, NULL) || read_numbers(r, v + 3, 3, &axis_at))
        return -1;
    if (v[3] == 0 && v[4] == 0 && v[5] == 0)
        return read_fail(r, &axis_at, "torus axis must not be zero");
    if (read_bounded(r, &v[6], 0, "a positive torus radius R") ||
        read_bounded(r, &v[7], 0, "a positive torus tube radius r"))
        return -1;
    return read_push(r, v, 8);
}

static bool torus_bounds(const double *p, size_t n, size_t k, double lo[3], double hi[3])
{
    double u[3];
    (void)n, (void)k;
    vec3_unit(p + 3, u);
    for (int a = 0; a < 3; a++) {
        double e = p[6] * sqrt(fmax(0.0, 1.0 - u[a] * u[a])) + p[7];
        lo[a] = p[a] - e;
        hi[a] = p[a] + e;
    }
    widen(lo, hi);
    return true;
}

static void torus_pack(const double *p, size_t n, size_t k, struct shape_record *rec,
                       double (*extra)[4])
{
    double u[3];
    (void)n, (void)k, (void)extra;
    vec3_unit(p + 3, u);
    record_row(rec, 0, p, p[6]);
    record_row(rec, 1, u, p[7]);
}

/* ---- quadric ----------------------------------------------------------- */

static int quadric_read(struct scene_reader *r)
{
    double v[10];
    struct token at;
    if (read_numbers(r, v, 10, &at))
        return -1;
    bool any = false;
    for (int i = 0; i < 9; i++)
        any |= v[i] != 0;
    if (!any)
        return read_fail(r, &at, "quadric needs an x, y or z term (A to I are all 0)");
    return read_push(r, v, 10);
}

static size_t quadric_extra(const double *p, size_t n)
{
    (void)p, (void)n;
    return 1;
}

/* The quadric's symmetric matrix M (x.M x is its quadratic part). */
static void quadric_matrix(const double *q, double m[3][3])
{
    m[0][0] = q[0];
    m[1][1] = q[1];
    m[2][2] = q[2];
    m[0][1] = m[1][0] = q[3] / 2;
    m[0][2] = m[2][0] = q[4] / 2;
    m[1][2] = m[2][1] = q[5] / 2;
}

/* The center -M^-1 g / 2 of quadric q (g = G H I), with M, its cofactor
 * rows (M being symmetric, M^-1 is them over det) and det; false unless
 * M is well invertible (ellipsoids, hyperboloids: |det| > 1e-9 size^3). */
static bool quadric_center(const double *q, double m[3][3], double cof[3][3], double *det,
                           double center[3])
{
    quadric_matrix(q, m);
    vec3_cross(m[1], m[2], cof[0]);
    vec3_cross(m[2], m[0], cof[1]);
    vec3_cross(m[0], m[1], cof[2]);
    *det = vec3_dot(m[0], cof[0]);
    double size = fmax(vec3_max_abs(m[0]), fmax(vec3_max_abs(m[1]), vec3_max_abs(m[2])));
    if (!(fabs(*det) > 1e-9 * size * size * size))
        return false;
    const double g[3] = {q[6] / 2, q[7] / 2, q[8] / 2};
    for (int i = 0; i < 3; i++)
        center[i] = -vec3_dot(cof[i], g) / *det;
    return isfinite(center[0]) && isfinite(center[1]) && isfinite(center[2]);
}

/* Where rays are measured from: the center when there is one, so that the
 * ray's numbers stay the size of the quadric however far the camera; else
 * the origin. */
static void quadric_reference(const double *q, double ref[3])
{
    double m[3][3], cof[3][3], det;
    if (!quadric_center(q, m, cof, &det, ref))
        ref[0] = ref[1] = ref[2] = 0;
}

static void quadric_pack(const double *q, size_t n, size_t k, struct shape_record *rec,
                         double (*extra)[4])
{
    double m[3][3], ref[3], mr[3];
    (void)n, (void)k;
    quadric_matrix(q, m);
    quadric_reference(q, ref);
    /* Q(ref + y) = y.M y + (2 M ref + g).y + Q(ref). */
    for (int i = 0; i < 3; i++)
        mr[i] = vec3_dot(m[i], ref);
    double c[10];
    memcpy(c, q, 6 * sizeof *c);
    for (int i = 0; i < 3; i++)
        c[6 + i] = 2 * mr[i] + q[6 + i];
    c[9] = vec3_dot(ref, mr) + q[6] * ref[0] + q[7] * ref[1] + q[8] * ref[2] + q[9];
    double big = 0;
    for (int i = 0; i < 10; i++)
        big = fmax(big, fabs(c[i]));
    for (int i = 0; i < 10; i++)
        c[i] /= big;
    memcpy(rec->row[0], c, 4 * sizeof *c);
    memcpy(rec->row[1], c + 4, 4 * sizeof *c);
    rec->row[2][0] = c[8];
    rec->row[2][1] = c[9];
    record_row((struct shape_record *)extra, 0, ref, 0);
}

/* An ellipsoid's box: bounded when the packed quadratic part M is definite
 * (its leading minors' signs + + + or - + -) and has a center
 * (quadric_center; then det, M^-1 and the box are off by far less than
 * the 1e-4 they are widened by). About its center y0 the packed quadric
 * is y.M y = r with r = -(c + g.y0 / 2), so the surface reaches
 * sqrt(r (M^-1)ii) along axis i. Computed from what pack gives the GPU,
 * so the box holds the surface the shader sees. An empty one (r of the
 * wrong sign) gets its center's point. Hyperboloids, paraboloids and
 * cylinders stay unbounded. */
static bool quadric_bounds(const double *p, size_t n, size_t k, double lo[3], double hi[3])
{
    struct shape_record rec;
    double ref[4], m[3][3], cof[3][3], det, y0[3];
    quadric_pack(p, n, k, &rec, &ref);
    const double *a = rec.row[0], *b = rec.row[1];
    double q[10] = {a[0], a[1], a[2], a[3], b[0], b[1], b[2], b[3], rec.row[2][0],
                    rec.row[2][1]};
    if (!quadric_center(q, m, cof, &det, y0))
        return false;
    double minor2 = m[0][0] * m[1][1] - m[0][1] * m[0][1];
    if (!(minor2 > 0 && m[0][0] * det > 0))
        return false;
    double r = -(q[9] + (q[6] * y0[0] + q[7] * y0[1] + q[8] * y0[2]) / 2);
    for (int i = 0; i < 3; i++) {
        double half = sqrt(fmax(0.0, r * cof[i][i] / det)) * (1 + 1e-4);
        lo[i] = ref[i] + y0[i] - half;
        hi[i] = ref[i] + y0[i] + half;
    }
    widen(lo, hi);
    return true;
}

/* Only the reference point moves: the coefficients are about it. */
static void quadric_move(struct shape_record *rec, double (*extra)[4],
                         const double origin[3])
{
    (void)rec;
    move_point(extra[0], origin);
}

/* ---- triangle and mesh -------------------------------------------------- */

/* The unit normal of triangle t (corners counter-clockwise seen from the
 * side it points to); false when its corners are collinear. */
static bool triangle_normal(const double *t, double n[3])
{
    double e1[3], e2[3];
    vec3_sub(t + 3, t, e1);
    vec3_sub(t + 6, t, e2);
    double s1 = vec3_max_abs(e1), s2 = vec3_max_abs(e2);
    if (!(s1 > 0 && s2 > 0))
        return false;
    for (int i = 0; i < 3; i++) { /* scaled: no overflow, no underflow */
        e1[i] /= s1;
        e2[i] /= s2;
    }
    vec3_cross(e1, e2, n);
    return vec3_unit(n, n) > 0;
}

static int triangle_read(struct scene_reader *r)
{
    double v[9], n[3];
    struct token at;
    if (read_numbers(r, v, 9, &at))
        return -1;
    if (!triangle_normal(v, n))
        return read_fail(r, &at, "triangle corners must not be collinear");
    return read_push(r, v, 9);
}

static size_t triangle_count(const double *p, size_t n)
{
    (void)p;
    return n / 9;
}

static bool triangle_bounds(const double *p, size_t n, size_t k, double lo[3], double hi[3])
{
    const double *t = p + 9 * k;
    (void)n;
    for (int a = 0; a < 3; a++) {
        lo[a] = fmin(t[a], fmin(t[a + 3], t[a + 6]));
        hi[a] = fmax(t[a], fmax(t[a + 3], t[a + 6]));
    }
    return true;
}

static void triangle_pack(const double *p, size_t n, size_t k, struct shape_record *rec,
                          double (*extra)[4])
{
    const double *t = p + 9 * k;
    double normal[3] = {0, 0, 0};
    (void)n, (void)extra;
    triangle_normal(t, normal);
    for (int i = 0; i < 3; i++)
        record_row(rec, i, t + 3 * i, normal[i]);
}

/* The plane of the packed corners and unit normal (0 faces for a
 * degenerate one, which no ray meets). */
static size_t triangle_faces(const struct shape_record *rec, const double (*extra)[4],
                             double (*planes)[4])
{
    double n[3] = {rec->row[0][3], rec->row[1][3], rec->row[2][3]};
    (void)extra;
    if (!(vec3_max_abs(n) > 0))
        return 0;
    memcpy(planes[0], n, sizeof n);
    planes[0][3] = -vec3_dot(n, rec->row[0]);
    return 1;
}

static void triangle_move(struct shape_record *rec, double (*extra)[4],
                          const double origin[3])
{
    (void)extra;
    for (int i = 0; i < 3; i++)
        move_point(rec->row[i], origin);
}

static int mesh_read(struct scene_reader *r)
{
    char *path = NULL;
    struct token at;
    char quoted[LEXER_QUOTE_SIZE];
    if (read_file_name(r, "an OBJ file name", &path, &at))
        return -1;
    token_describe(&at, quoted, sizeof quoted);
    FILE *f = fopen(path, "rb");
    if (!f) {
        int saved = errno;
        free(path);
        return read_fail(r, &at, "cannot read mesh %s: %s", quoted, strerror(saved));
    }
    struct obj_mesh mesh;
    char err[512];
    char *shown = lexer_escape(path); /* messages quote names safely */
    free(path);
    if (!shown) {
        fclose(f);
        return read_fail(r, &at, "out of memory reading mesh %s", quoted);
    }
    int rc = obj_read(f, shown, &mesh, err, sizeof err);
    fclose(f);
    free(shown);
    if (rc != 0)
        return read_fail_text(r, err);
    if (mesh.ntri == 0)
        rc = read_fail(r, &at, "mesh %s has no triangles", quoted);
    else
        rc = read_push(r, mesh.tri, 9 * mesh.ntri);
    obj_mesh_free(&mesh);
    return rc;
}

/* ---- the table --------------------------------------------------------- */

/* Each kind's functions, in struct shape_kind's order after the fields
 * kinds.h gives: KEYWORD_OPS for each row of TP2_SHAPES. */
#define sphere_OPS \
    sphere_read, one_primitive, sphere_bounds, \
    no_extra, sphere_pack, move_first_row, .faces = NULL
#define plane_OPS \
    plane_read, one_primitive, unbounded, \
    no_extra, plane_pack, plane_move, .faces = plane_faces, .met_as_planes = true
#define polyhedron_OPS \
    polyhedron_read, one_primitive, polyhedron_bounds, \
    polyhedron_extra, polyhedron_pack, polyhedron_move, \
    .faces = polyhedron_faces, .met_as_planes = true
#define box_OPS \
    box_read, one_primitive, box_bounds, \
    no_extra, box_pack, box_move, .faces = box_faces, .met_as_planes = true
#define cylinder_OPS \
    cylinder_read, one_primitive, cylinder_bounds, \
    no_extra, cylinder_pack, move_first_row, .faces = NULL
#define cone_OPS \
    cone_read, one_primitive, cone_bounds, \
    no_extra, cone_pack, move_first_row, .faces = NULL
#define torus_OPS \
    torus_read, one_primitive, torus_bounds, \
    no_extra, torus_pack, move_first_row, .faces = NULL
#define quadric_OPS \
    quadric_read, one_primitive, quadric_bounds, \
    quadric_extra, quadric_pack, quadric_move, .faces = NULL
#define triangle_OPS \
    triangle_read, triangle_count, triangle_bounds, \
    no_extra, triangle_pack, triangle_move, .faces = triangle_faces, .met_as_planes = false
#define mesh_OPS \
    mesh_read, triangle_count, triangle_bounds, \
    no_extra, triangle_pack, triangle_move, .faces = triangle_faces, .met_as_planes = false

#define TP2_SHAPE_ROW_(NAME, keyword, id, tier, flat)                         \
    [SHAPE_##NAME] = {#keyword, id, TP2_TIER_##tier, flat, keyword##_OPS},
const struct shape_kind shape_kinds[SHAPE_COUNT] = {TP2_SHAPES(TP2_SHAPE_ROW_)};

double shape_extent(int k, const double *p, size_t n)
{
    const struct shape_kind *kind = &shape_kinds[k];
    size_t rows = kind->extra_rows(p, n);
    double (*extra)[4] = calloc(rows ? rows : 1, sizeof *extra);
    if (!extra)
        return -1;
    double m = 0;
    for (size_t i = 0, prims = kind->primitives(p, n); i < prims; i++) {
        struct shape_record rec;
        memset(&rec, 0, sizeof rec);
        kind->pack(p, n, i, &rec, extra);
        for (int r = 0; r < 3; r++)
            for (int c = 0; c < 4; c++)
                m = fmax(m, fabs(rec.row[r][c]));
        for (size_t r = 0; r < rows; r++)
            for (int c = 0; c < 4; c++)
                m = fmax(m, fabs(extra[r][c]));
    }
    free(extra);
    return m;
}

const char *shape_keywords(void)
{
    static char text[256];
    if (!text[0]) {
        const char *words[SHAPE_COUNT];
        for (int k = 0; k < SHAPE_COUNT; k++)
            words[k] = shape_kinds[k].keyword;
        keyword_list(words, SHAPE_COUNT, text, sizeof text);
    }
    return text;
}
