/* test_shapes.c: the shape table's bounds and GPU records, and the
 * bounding boxes of convex polyhedra.
 *
 * Bounds must contain every point of the shape (checked on points spread
 * over each surface) and be tight; polyhedra are bounded or not as their
 * faces say, quadrics as their matrix does; a triangle's record carries
 * the normal its winding gives; a quadric's record, about its reference
 * point, is the same function; a record moved to a new origin is the
 * record of the moved shape.
 * Prints "N passed, M failed" last. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "convex.h"
#include "shapes.h"
#include "vec3.h"

#include "unit.h"

static const double pi = 3.14159265358979323846;

static int inside_box(const double p[3], const double lo[3], const double hi[3])
{
    return p[0] >= lo[0] && p[0] <= hi[0] && p[1] >= lo[1] && p[1] <= hi[1] &&
           p[2] >= lo[2] && p[2] <= hi[2];
}

/* Largest distance from the box's faces to the nearest sample: how loose
 * the box is (0 when samples touch all six faces). */
static double looseness(const double (*pts)[3], int n, const double lo[3], const double hi[3])
{
    double worst = 0;
    for (int a = 0; a < 3; a++) {
        double mn = INFINITY, mx = -INFINITY;
        for (int i = 0; i < n; i++) {
            mn = fmin(mn, pts[i][a]);
            mx = fmax(mx, pts[i][a]);
        }
        worst = fmax(worst, fmax(mn - lo[a], hi[a] - mx));
    }
    return worst;
}

/* A frame (u, v) perpendicular to unit axis w. */
static void frame(const double w[3], double u[3], double v[3])
{
    double t[3] = {1, 0, 0};
    if (fabs(w[0]) > 0.9)
        t[0] = 0, t[1] = 1;
    vec3_cross(w, t, u);
    vec3_unit(u, u);
    vec3_cross(w, u, v);
}

enum { SAMPLES = 4000 };
static double pts[SAMPLES][3];

/* Checks kind's bounds of numbers p against n sampled surface points. */
static void check_bounds(const char *name, int kind, const double *p, size_t count, int n,
                         double tight)
{
    double lo[3], hi[3];
    int bounded = shape_kinds[kind].bounds(p, count, 0, lo, hi);
    expect(bounded, "%s: bounded", name);
    int out = 0;
    for (int i = 0; i < n; i++)
        out += !inside_box(pts[i], lo, hi);
    expect(out == 0, "%s: %d of %d surface points outside the bounds", name, out, n);
    double loose = looseness((const double (*)[3])pts, n, lo, hi);
    expect(loose <= tight, "%s: bounds %g looser than the samples (allowed %g)", name, loose, tight);
}

static void test_round_bounds(void)
{
    /* Cylinder from a to b, radius r, tilted: its rims. */
    const double cyl[7] = {1, -2, 0.5, 3.5, 1, -1.5, 0.75};
    double w[3], u[3], v[3];
    double d[3] = {cyl[3] - cyl[0], cyl[4] - cyl[1], cyl[5] - cyl[2]};
    vec3_unit(d, w);
    frame(w, u, v);
    int n = 0;
    for (int end = 0; end < 2; end++)
        for (int k = 0; k < SAMPLES / 2; k++, n++) {
            double phi = 2 * pi * k / (SAMPLES / 2);
            for (int a = 0; a < 3; a++)
                pts[n][a] = cyl[a + 3 * end] + cyl[6] * (cos(phi) * u[a] + sin(phi) * v[a]);
        }
    check_bounds("cylinder", SHAPE_CYLINDER, cyl, 7, n, 1e-5);

    /* Cone with an apex: the base rim and the apex. */
    const double cone[8] = {-1, 0, 2, 1.5, 0.5, 3, 1, 0};
    double dc[3] = {cone[4] - cone[0], cone[5] - cone[1], cone[6] - cone[2]};
    vec3_unit(dc, w);
    frame(w, u, v);
    n = 0;
    for (int k = 0; k < SAMPLES - 1; k++, n++) {
        double phi = 2 * pi * k / (SAMPLES - 1);
        for (int a = 0; a < 3; a++)
            pts[n][a] = cone[a] + cone[3] * (cos(phi) * u[a] + sin(phi) * v[a]);
    }
    memcpy(pts[n++], cone + 4, sizeof pts[0]);
    check_bounds("cone", SHAPE_CONE, cone, 8, n, 1e-5);

    /* Torus with a tilted axis: points over its whole surface. */
    const double tor[8] = {2, -1, 0.5, 1, 2, -0.5, 1.25, 0.4};
    vec3_unit(tor + 3, w);
    frame(w, u, v);
    n = 0;
    for (int i = 0; i < 80; i++)
        for (int j = 0; j < 50; j++, n++) {
            double a1 = 2 * pi * i / 80, a2 = 2 * pi * j / 50;
            for (int a = 0; a < 3; a++) {
                double radial = cos(a1) * u[a] + sin(a1) * v[a];
                pts[n][a] = tor[a] + (tor[6] + tor[7] * cos(a2)) * radial + tor[7] * sin(a2) * w[a];
            }
        }
    check_bounds("torus", SHAPE_TORUS, tor, 8, n, 2e-3);

    /* Sphere, box (corners given in any order), triangle. */
    const double sph[4] = {1e5, -3, 0.25, 2};
    n = 0;
    for (int i = 0; i < 60; i++)
        for (int j = 0; j <= 60; j++, n++) {
            double th = pi * j / 60, ph = 2 * pi * i / 60;
            pts[n][0] = sph[0] + sph[3] * sin(th) * cos(ph);
            pts[n][1] = sph[1] + sph[3] * sin(th) * sin(ph);
            pts[n][2] = sph[2] + sph[3] * cos(th);
        }
    check_bounds("sphere", SHAPE_SPHERE, sph, 4, n, 1e-3);
    const double box[6] = {2, -1, 5, -3, 4, 1};
    n = 0;
    for (int c = 0; c < 8; c++, n++)
        for (int a = 0; a < 3; a++)
            pts[n][a] = box[a + 3 * ((c >> a) & 1)];
    check_bounds("box", SHAPE_BOX, box, 6, n, 0);
    const double tri[9] = {0, 0, 0, 1, 2, -3, -4, 0.5, 1};
    for (int c = 0; c < 3; c++)
        memcpy(pts[c], tri + 3 * c, sizeof pts[0]);
    check_bounds("triangle", SHAPE_TRIANGLE, tri, 9, 3, 0);
    double lo[3], hi[3];
    const double plane[4] = {0, 1, 0, 0};
    CHECK(!shape_kinds[SHAPE_PLANE].bounds(plane, 4, 0, lo, hi));
}

/* The quadric (x - c).M (x - c) - 1 = 0 of the ellipsoid with center c,
 * semi-axes s along the columns of rotation r, as SPEC's A..J (times
 * `sign`: the same surface with its inside outside); its points go to
 * pts, n of them. */
static int ellipsoid(const double c[3], const double s[3], double r[3][3], double sign,
                     double q[10])
{
    double m[3][3];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            m[i][j] = 0;
            for (int k = 0; k < 3; k++)
                m[i][j] += r[i][k] * r[j][k] / (s[k] * s[k]);
        }
    double mc[3] = {vec3_dot(m[0], c), vec3_dot(m[1], c), vec3_dot(m[2], c)};
    const double coef[10] = {m[0][0], m[1][1], m[2][2], 2 * m[0][1], 2 * m[0][2],
                             2 * m[1][2], -2 * mc[0], -2 * mc[1], -2 * mc[2],
                             vec3_dot(c, mc) - 1};
    for (int i = 0; i < 10; i++)
        q[i] = sign * coef[i];
    int n = 0;
    for (int i = 0; i < 80; i++)
        for (int j = 0; j <= 48; j++, n++) {
            double th = pi * j / 48, ph = 2 * pi * i / 80;
            double e[3] = {s[0] * sin(th) * cos(ph), s[1] * sin(th) * sin(ph), s[2] * cos(th)};
            for (int a = 0; a < 3; a++)
                pts[n][a] = c[a] + r[a][0] * e[0] + r[a][1] * e[1] + r[a][2] * e[2];
        }
    return n;
}

/* An ellipsoid written as a quadric is bounded by its exact box, tilted
 * or not, either sign, far from 0 or not; an empty one by its center's
 * point; the quadrics that reach infinity are unbounded. */
static void test_quadric_bounds(void)
{
    double q[10], lo[3], hi[3];
    double r[3][3], w[3] = {0.3, -0.5, 0.81}, u[3], v[3];
    vec3_unit(w, w);
    frame(w, u, v);
    for (int a = 0; a < 3; a++)
        r[a][0] = u[a], r[a][1] = v[a], r[a][2] = w[a];
    const double c[3] = {1.5, -2, 0.25}, s[3] = {2, 0.5, 1.25};
    int n = ellipsoid(c, s, r, 1, q);
    check_bounds("tilted ellipsoid", SHAPE_QUADRIC, q, 10, n, 2e-3);
    n = ellipsoid(c, s, r, -1, q);
    check_bounds("tilted ellipsoid, inside out", SHAPE_QUADRIC, q, 10, n, 2e-3);
    const double far[3] = {-3e3, 1e3, 2e3}, cigar[3] = {0.01, 0.01, 5};
    n = ellipsoid(far, cigar, r, 1, q);
    check_bounds("far thin ellipsoid", SHAPE_QUADRIC, q, 10, n, 2e-3);
    double axes[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    n = ellipsoid(c, s, axes, 1, q);
    check_bounds("ellipsoid", SHAPE_QUADRIC, q, 10, n, 1e-9 + 1e-4 * 2);

    const double empty[10] = {1, 2, 3, 0, 0, 0, -2, 0, 0, 5}; /* (x-1)^2 + ... = -4 */
    CHECK(shape_kinds[SHAPE_QUADRIC].bounds(empty, 10, 0, lo, hi));
    CHECK(fabs(lo[0] - 1) < 1e-9 && fabs(hi[0] - 1) < 1e-9 && hi[1] - lo[1] < 1e-9 &&
          hi[2] - lo[2] < 1e-9);
    const double unbounded[][10] = {
        {1, 1, -1, 0, 0, 0, 0, 0, 0, -1}, /* hyperboloid of one sheet */
        {-1, -1, 1, 0, 0, 0, 0, 0, 0, -1}, /* of two sheets */
        {1, 0, 1, 0, 0, 0, 0, -1, 0, 0},  /* paraboloid */
        {1, 4, 0, 0, 0, 0, 0, 0, 0, -1},  /* elliptic cylinder */
        {1, 1, 1, 2, 0, 0, 0, 0, 0, -1},  /* (x + y)^2 + z^2: a cylinder, tilted */
        {0, 0, 0, 0, 0, 0, 1, 1, 1, 0},   /* a plane */
    };
    for (size_t i = 0; i < sizeof unbounded / sizeof unbounded[0]; i++)
        expect(!shape_kinds[SHAPE_QUADRIC].bounds(unbounded[i], 10, 0, lo, hi),
               "quadric %zu: bounded", i);
}

/* The oracle: the previous method, cubic in the faces. A bounded
 * polyhedron is the hull of its corners (every triple of faces meeting in
 * one point that all faces hold); it is unbounded when some direction v
 * has n.v <= 0 for every face, found among the n_i x n_j (or the normals
 * do not span space). */
#define ORACLE_TOL 1e-9

static int oracle_unbounded(const double *f, size_t n)
{
    int spans = 0;
    for (size_t i = 0; i < n; i++)
        for (size_t j = i + 1; j < n; j++) {
            double v[3];
            vec3_cross(f + 4 * i, f + 4 * j, v);
            if (!vec3_unit(v, v))
                continue;
            for (size_t k = 0; k < n && !spans; k++) {
                double u[3];
                vec3_unit(f + 4 * k, u);
                spans = fabs(vec3_dot(u, v)) > ORACLE_TOL;
            }
            for (int sign = -1; sign <= 1; sign += 2) {
                size_t k = 0;
                for (; k < n; k++) {
                    double u[3];
                    vec3_unit(f + 4 * k, u);
                    if (sign * vec3_dot(u, v) > ORACLE_TOL)
                        break;
                }
                if (k == n)
                    return 1;
            }
        }
    return !spans;
}

/* The corners' box; 0 if there is no corner (empty). */
static int oracle_corners(const double *f, size_t n, double lo[3], double hi[3])
{
    int any = 0;
    for (int a = 0; a < 3; a++)
        lo[a] = INFINITY, hi[a] = -INFINITY;
    for (size_t i = 0; i < n; i++)
        for (size_t j = i + 1; j < n; j++)
            for (size_t k = j + 1; k < n; k++) {
                const double *a = f + 4 * i, *b = f + 4 * j, *c = f + 4 * k;
                double bc[3], ca[3], ab[3], x[3];
                vec3_cross(b, c, bc);
                vec3_cross(c, a, ca);
                vec3_cross(a, b, ab);
                double det = vec3_dot(a, bc);
                double scale = sqrt(vec3_dot(a, a) * vec3_dot(b, b) * vec3_dot(c, c));
                if (!(fabs(det) > ORACLE_TOL * scale))
                    continue;
                for (int e = 0; e < 3; e++)
                    x[e] = -(a[3] * bc[e] + b[3] * ca[e] + c[3] * ab[e]) / det;
                size_t m = 0;
                for (; m < n; m++) {
                    const double *p = f + 4 * m;
                    double len = sqrt(vec3_dot(p, p));
                    if (vec3_dot(p, x) + p[3] > ORACLE_TOL * (fabs(p[3]) + len * vec3_max_abs(x)))
                        break;
                }
                if (m < n)
                    continue;
                any = 1;
                for (int e = 0; e < 3; e++)
                    lo[e] = fmin(lo[e], x[e]), hi[e] = fmax(hi[e], x[e]);
            }
    return any;
}

static uint64_t rng_state = 88172645463325252u;

static double uniform(double a, double b)
{
    rng_state ^= rng_state << 13, rng_state ^= rng_state >> 7, rng_state ^= rng_state << 17;
    return a + (b - a) * (double)(rng_state >> 11) * 0x1p-53;
}

static void random_unit(double u[3])
{
    do
        for (int a = 0; a < 3; a++)
            u[a] = uniform(-1, 1);
    while (vec3_dot(u, u) > 1 || vec3_dot(u, u) < 1e-4);
    vec3_unit(u, u);
}

/* A face n.(x - c) <= r, written with an arbitrary positive scale k. */
static void tangent_face(double *f, const double n[3], const double c[3], double r, double k)
{
    for (int a = 0; a < 3; a++)
        f[a] = k * n[a];
    f[3] = -k * (vec3_dot(n, c) + r);
}

/* Random polyhedra of 4-24 faces, 1e-3 to 1e3 in size, up to 1e4 from 0:
 * the box is the oracle's (it holds every corner, and each side is within
 * 1e-7 of the polyhedron's size, and its own pad, of a corner); unbounded
 * and empty ones get no box. */
static void test_convex_against_oracle(void)
{
    enum { CASES = 600, MAXF = 24 };
    static double f[MAXF * 4];
    int bounded = 0, open = 0, empty = 0, bad = 0;
    for (int t = 0; t < CASES; t++) {
        size_t n = 4 + (size_t)uniform(0, MAXF - 4 + 0.999);
        double c[3], size = pow(10, uniform(-3, 3)), away = pow(10, uniform(-1, 4));
        random_unit(c);
        for (int a = 0; a < 3; a++)
            c[a] *= away;
        int hemisphere = t % 7 == 3; /* every normal's z > 0: unbounded */
        for (size_t i = 0; i < n; i++) {
            double u[3];
            random_unit(u);
            if (hemisphere)
                u[2] = fabs(u[2]) + 1e-3;
            double r = size * uniform(0.3, 1);
            if (t % 11 == 5 && i == n - 1) /* a sliver: the others' r >= 0.3 */
                r = -size * uniform(0.2, 0.29);
            if (t % 11 == 6 && i >= n - 2) { /* empty: u.(x - c) <= -r <= r <= u.(x - c) */
                r = -size * 0.2;
                if (i == n - 1)
                    for (int a = 0; a < 3; a++)
                        u[a] = -f[4 * (n - 2) + a];
                vec3_unit(u, u);
            }
            tangent_face(f + 4 * i, u, c, r, pow(10, uniform(-2, 2)));
        }
        if (t % 13 == 7) /* repeated faces */
            memmove(f + 4 * (n / 2), f, 4 * (n - n / 2) * sizeof f[0]);
        double lo[3], hi[3], olo[3], ohi[3];
        int got = convex_bounds(f, n, lo, hi);
        int is_open = oracle_unbounded(f, n);
        int want = !is_open && oracle_corners(f, n, olo, ohi);
        bounded += want;
        open += is_open;
        empty += !want && !is_open;
        if (got != want) {
            bad++;
            expect(0, "polyhedron %d (%zu faces): box %d, oracle %d", t, n, got, want);
            continue;
        }
        for (int a = 0; a < 3 && want; a++) {
            /* the box's own pad is 1e-9 of |lo| + |hi| + the span */
            double near = 1e-7 * (ohi[a] - olo[a]) + 4e-9 * fmax(fabs(olo[a]), fabs(ohi[a]));
            if (!(lo[a] <= olo[a] && hi[a] >= ohi[a] && olo[a] - lo[a] <= near &&
                  hi[a] - ohi[a] <= near)) {
                bad++;
                expect(0, "polyhedron %d axis %d: [%.17g, %.17g] against corners [%.17g, %.17g]",
                       t, a, lo[a], hi[a], olo[a], ohi[a]);
            }
        }
    }
    expect(bad == 0, "%d of %d polyhedra wrong", bad, CASES);
    /* The cases must cover all three answers. */
    expect(bounded > 300 && open > 50 && empty > 10, "bounded %d, unbounded %d, empty %d",
           bounded, open, empty);
}

/* Ill-conditioned: faces up to 1.15e15 from 0 around a polyhedron about
 * 2e9 across (found by a random search; its corners, computed in rational
 * arithmetic from these doubles, give the box below, rounded to nearest).
 * The box must hold it: corners lie about 100 units off in double here,
 * which a pad of 1e-9 of the box alone (about 4 units) did not cover. */
static void test_convex_ill_conditioned(void)
{
    const double f[8][4] = {
        {-2497.9262366530315, 108.35541359617572, 0.035242146360025275, -2.8643988357656069e+18},
        {0, -263481.69506371877, 0, 1.3602390983587313e-05},
        {0.11059897057298618, 1.954461593773594e-68, -0.030662538707460708,
         -0.00073808054199104981},
        {1.7465200656387566e-06, 91929.939796462058, 7.8697657588723348e-06, -2665.0001454087633},
        {-0.010512874662480848, 0.11070356410426065, -3748.4712117086492, 0.11404613350782342},
        {5.3922431881273441e-264, 0, -0.46460792460956635, -0.0032167499479483913},
        {-7.7967694385650997e-06, 0.00065503045955449897, -1.9422185028529131e-05,
         -0.0049336077286206538},
        {-2.004190796726172e-227, 0.6592541773733569, -3.5333174307445992e-06,
         -5.5760304501232038e-05},
    };
    const double exact_lo[3] = {-1886474336.0210984, 5.16255635151345e-11, 3.0405965778206537e-05};
    const double exact_hi[3] = {88442545.34871915, 0.028989274586877382, 757298959.6440297};
    double lo[3], hi[3];
    CHECK(convex_bounds(&f[0][0], 8, lo, hi) == 1);
    for (int a = 0; a < 3; a++) /* and no side 1e-6 of its largest extent away */
        expect(lo[a] <= exact_lo[a] && hi[a] >= exact_hi[a] && exact_lo[a] - lo[a] < 3e3 &&
                   hi[a] - exact_hi[a] < 3e3,
               "ill-conditioned, axis %d: [%.17g, %.17g]", a, lo[a], hi[a]);
}

/* Many faces: 4096 tangent planes of a sphere, its box within the
 * planes' covering angle (with the six axis planes among them: exact); the
 * same faces all leaning one way, or along a belt: unbounded; 4095 faces
 * meeting at one apex. */
static void test_convex_many_faces(void)
{
    enum { N = 4096 };
    static double f[N * 4];
    const double c[3] = {1e3, -20, 0.5}, r = 3;
    const double golden = pi * (3 - sqrt(5.0));
    double lo[3], hi[3];
    for (int axis_planes = 0; axis_planes <= 1; axis_planes++) {
        for (int i = 0; i < N; i++) {
            double z = 1 - (2 * i + 1.0) / N, ring = sqrt(1 - z * z);
            double u[3] = {ring * cos(golden * i), ring * sin(golden * i), z};
            if (axis_planes && i < 6) {
                u[0] = u[1] = u[2] = 0;
                u[i / 2] = i % 2 ? 1 : -1;
            }
            tangent_face(f + 4 * i, u, c, r, 1 + i % 5);
        }
        CHECK(convex_bounds(f, N, lo, hi) == 1);
        for (int a = 0; a < 3; a++) {
            CHECK(lo[a] <= c[a] - r && hi[a] >= c[a] + r);
            /* 4096 spread normals leave no direction 0.04 radians from one. */
            double slack = axis_planes ? 1e-8 * (fabs(c[a]) + r) : r * (1 / cos(0.04) - 1);
            expect(c[a] - r - lo[a] <= slack && hi[a] - c[a] - r <= slack,
                   "4096 faces, axis %d: [%.17g, %.17g]", a, lo[a], hi[a]);
        }
    }
    for (int i = 0; i < N; i++) /* all leaning up: open toward -z */
        f[4 * i + 2] = fabs(f[4 * i + 2]) + 1e-6;
    CHECK(convex_bounds(f, N, lo, hi) == 0);
    for (int i = 0; i < N; i++) { /* normals along a belt: a prism open along z */
        double th = 2 * pi * i / N, u[3] = {cos(th), sin(th), 0};
        tangent_face(f + 4 * i, u, c, r, 1);
    }
    CHECK(convex_bounds(f, N, lo, hi) == 0);
    /* A pyramid: 4095 faces at 45 degrees through the apex (0, 0, 2), a
     * base z >= 0. Its box: the apex and the base's disk of radius 2. */
    const double apex[3] = {0, 0, 2};
    for (int i = 0; i < N - 1; i++) {
        double th = 2 * pi * i / (N - 1), u[3] = {cos(th), sin(th), 1};
        vec3_unit(u, u);
        tangent_face(f + 4 * i, u, apex, 0, 1);
    }
    const double base[4] = {0, 0, -1, 0};
    memcpy(f + 4 * (N - 1), base, sizeof base);
    CHECK(convex_bounds(f, N, lo, hi) == 1);
    expect(fabs(hi[2] - 2) < 1e-8 && fabs(lo[2]) < 1e-8 && fabs(hi[0] - 2) < 1e-8 &&
               fabs(lo[1] + 2) < 1e-5,
           "pyramid [%.17g %.17g %.17g] [%.17g %.17g %.17g]", lo[0], lo[1], lo[2], hi[0],
           hi[1], hi[2]);
}

static void test_convex_bounds(void)
{
    double lo[3], hi[3];
    /* The cube 0 <= x, y, z <= 2: tight. */
    const double cube[6][4] = {{-1, 0, 0, 0}, {1, 0, 0, -2}, {0, -1, 0, 0},
                               {0, 1, 0, -2}, {0, 0, -1, 0}, {0, 0, 1, -2}};
    CHECK(convex_bounds(&cube[0][0], 6, lo, hi) == 1);
    CHECK(fabs(lo[0]) < 1e-8 && fabs(lo[1]) < 1e-8 && fabs(lo[2]) < 1e-8);
    CHECK(fabs(hi[0] - 2) < 1e-8 && fabs(hi[1] - 2) < 1e-8 && fabs(hi[2] - 2) < 1e-8);
    CHECK(lo[0] <= 0 && hi[0] >= 2); /* outward, never inward */
    /* Unbounded: one face, a three-face wedge, a five-face open box. */
    CHECK(convex_bounds(&cube[0][0], 1, lo, hi) == 0);
    const double wedge[3][4] = {{1, 1, 0, -3}, {-1, 1, 0, -1}, {0, 0, 1, 4}};
    CHECK(convex_bounds(&wedge[0][0], 3, lo, hi) == 0);
    CHECK(convex_bounds(&cube[0][0], 5, lo, hi) == 0);
    /* Six faces that leave a direction open (two of them parallel). */
    const double slab[6][4] = {{-1, 0, 0, 0}, {1, 0, 0, -2}, {0, -1, 0, 0},
                               {0, 1, 0, -2}, {0, -1, 0, -1}, {0, 1, 0, -3}};
    CHECK(convex_bounds(&slab[0][0], 6, lo, hi) == 0);
    /* A tetrahedron with corners (0,0,0), (3,0,0), (0,2,0), (0,0,1). */
    const double tet[4][4] = {{-1, 0, 0, 0}, {0, -1, 0, 0}, {0, 0, -1, 0},
                              {2, 3, 6, -6}};
    CHECK(convex_bounds(&tet[0][0], 4, lo, hi) == 1);
    CHECK(fabs(hi[0] - 3) < 1e-8 && fabs(hi[1] - 2) < 1e-8 && fabs(hi[2] - 1) < 1e-8);
    /* Empty: x <= 0 and x >= 1 (with a closed box around): no box, so
     * tested by every ray, where it is never hit. */
    const double empty[6][4] = {{1, 0, 0, 0}, {-1, 0, 0, 1}, {0, -1, 0, -5},
                                {0, 1, 0, -5}, {0, 0, -1, -5}, {0, 0, 1, -5}};
    CHECK(convex_bounds(&empty[0][0], 6, lo, hi) == 0);
    /* Scale: a tiny cube far away stays tight. */
    double far_cube[6][4];
    memcpy(far_cube, cube, sizeof cube);
    for (int i = 0; i < 6; i++) { /* 1e6 <= x <= 1e6 + 2e-3 ... */
        double *f = far_cube[i];
        int axis = i / 2;
        f[3] = (f[axis] < 0) ? 1e6 : -(1e6 + 2e-3);
    }
    CHECK(convex_bounds(&far_cube[0][0], 6, lo, hi) == 1);
    CHECK(lo[0] <= 1e6 && hi[0] >= 1e6 + 2e-3 && hi[0] - lo[0] < 2e-3 + 1e-2);
}

static void test_triangle_record(void)
{
    /* Counter-clockwise seen from +z: normal +z; the other way: -z. */
    const double ccw[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const double cw[9] = {0, 0, 0, 0, 1, 0, 1, 0, 0};
    struct shape_record rec;
    shape_kinds[SHAPE_TRIANGLE].pack(ccw, 9, 0, &rec, NULL);
    CHECK(rec.row[0][3] == 0 && rec.row[1][3] == 0 && rec.row[2][3] == 1);
    CHECK(rec.row[1][0] == 1 && rec.row[2][1] == 1); /* the corners themselves */
    shape_kinds[SHAPE_TRIANGLE].pack(cw, 9, 0, &rec, NULL);
    CHECK(rec.row[2][3] == -1);
    /* A mesh's triangle k. */
    double two[18];
    memcpy(two, cw, sizeof cw);
    memcpy(two + 9, ccw, sizeof ccw);
    CHECK(shape_kinds[SHAPE_MESH].primitives(two, 18) == 2);
    shape_kinds[SHAPE_MESH].pack(two, 18, 1, &rec, NULL);
    CHECK(rec.row[2][3] == 1);
}

static double quadric_at(const double q[10], const double x[3])
{
    return q[0] * x[0] * x[0] + q[1] * x[1] * x[1] + q[2] * x[2] * x[2] +
           q[3] * x[0] * x[1] + q[4] * x[0] * x[2] + q[5] * x[1] * x[2] +
           q[6] * x[0] + q[7] * x[1] + q[8] * x[2] + q[9];
}

static void test_quadric_record(void)
{
    /* An ellipsoid centered at (100, -50, 20): the record is about its
     * center and scaled; Q and the record agree up to that scale. */
    const double q[10] = {1, 4, 9, 0.5, 0, -0.25, -200 - 0.5 * -50, 400 - 0.5 * 100 + 0.25 * 20,
                          -360 + 0.25 * -50, 0};
    struct shape_record rec;
    double extra[1][4];
    shape_kinds[SHAPE_QUADRIC].pack(q, 10, 0, &rec, extra);
    double r[10] = {rec.row[0][0], rec.row[0][1], rec.row[0][2], rec.row[0][3],
                    rec.row[1][0], rec.row[1][1], rec.row[1][2], rec.row[1][3],
                    rec.row[2][0], rec.row[2][1]};
    double big = 0;
    for (int i = 0; i < 10; i++)
        big = fmax(big, fabs(r[i]));
    CHECK(big == 1);
    /* Linear terms vanish about the center. */
    CHECK(fabs(r[6]) < 1e-12 && fabs(r[7]) < 1e-12 && fabs(r[8]) < 1e-12);
    double ratio = 0;
    int agree = 1;
    for (int i = 0; i < 20; i++) {
        double x[3] = {90 + i, -60 + 1.5 * i, 25 - i}, y[3];
        vec3_sub(x, extra[0], y);
        double a = quadric_at(q, x), b = quadric_at(r, y);
        if (i == 0)
            ratio = a / b;
        agree &= fabs(a - ratio * b) <= 1e-9 * fabs(a) + 1e-9;
    }
    CHECK(agree);
    /* A paraboloid (singular matrix): the origin is the reference. */
    const double para[10] = {1, 0, 1, 0, 0, 0, 0, -1, 0, 0};
    shape_kinds[SHAPE_QUADRIC].pack(para, 10, 0, &rec, extra);
    CHECK(extra[0][0] == 0 && extra[0][1] == 0 && extra[0][2] == 0);
}

/* A record moved to origin o is the record of the shape written at p - o
 * (numbers chosen so that every step is exact), for every kind whose
 * numbers are points, sizes and unit planes; the quadric's reference point
 * moves and its coefficients, about that point, stay. */
static void test_moved_records(void)
{
    const double o[3] = {4096, -8192.5, 2048.25};
    static const struct {
        int kind;
        size_t count;
        double p[16];
        const char *points; /* 'p': starts a point of three numbers */
    } cases[] = {
        {SHAPE_SPHERE, 4, {4097, -8190, 2050.5, 1.5}, "p..."},
        {SHAPE_BOX, 6, {4095, -8193, 2047, 4099, -8191, 2049}, "p..p.."},
        {SHAPE_CYLINDER, 7, {4096, -8192, 2048, 4096, -8189, 2052, 0.5}, "p..p..."},
        {SHAPE_CONE, 8, {4096, -8192, 2048, 1, 4099, -8192, 2052, 0.25}, "p...p..."},
        {SHAPE_TORUS, 8, {4100, -8190, 2040, 0, 3, 4, 2, 0.5}, "p......."},
        {SHAPE_TRIANGLE, 9, {4096, -8192, 2048, 4098, -8192, 2048, 4096, -8190, 2049},
         "p..p..p.."},
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        const struct shape_kind *kind = &shape_kinds[cases[c].kind];
        double moved[16];
        memcpy(moved, cases[c].p, sizeof moved);
        for (size_t i = 0; i < cases[c].count; i++)
            if (cases[c].points[i] == 'p')
                for (int a = 0; a < 3; a++)
                    moved[i + a] -= o[a];
        struct shape_record a, b;
        double extra[1][4];
        memset(&a, 0, sizeof a);
        memset(&b, 0, sizeof b);
        kind->pack(cases[c].p, cases[c].count, 0, &a, extra);
        kind->move(&a, extra, o);
        kind->pack(moved, cases[c].count, 0, &b, extra);
        expect(memcmp(&a, &b, sizeof a) == 0, "%s: moved record differs", kind->keyword);
    }
    /* Planes and faces: n.x + d = 0 (n a unit) gains n.o. */
    const double plane[4] = {0, 0, 2, -6000}, faces[8] = {0, 1, 0, 8000, 0, 0, -1, 2000};
    struct shape_record rec;
    double extra[2][4];
    shape_kinds[SHAPE_PLANE].pack(plane, 4, 0, &rec, extra);
    shape_kinds[SHAPE_PLANE].move(&rec, extra, o);
    CHECK(rec.row[0][3] == -3000 + 2048.25);
    shape_kinds[SHAPE_POLYHEDRON].pack(faces, 8, 0, &rec, extra);
    shape_kinds[SHAPE_POLYHEDRON].move(&rec, extra, o);
    CHECK(extra[0][3] == 8000 - 8192.5 && extra[1][3] == 2000 - 2048.25);
    /* The quadric: its reference point moves, its coefficients stay. */
    const double q[10] = {1, 2, 1, 0, 0, 0, -2 * 4097, 4 * 8190, -2 * 2050,
                          4097.0 * 4097 + 2 * 8190.0 * 8190 + 2050.0 * 2050 - 4};
    struct shape_record before;
    double ref[1][4];
    shape_kinds[SHAPE_QUADRIC].pack(q, 10, 0, &before, ref);
    double was[3] = {ref[0][0], ref[0][1], ref[0][2]};
    rec = before;
    shape_kinds[SHAPE_QUADRIC].move(&rec, ref, o);
    CHECK(memcmp(&rec, &before, sizeof rec) == 0);
    CHECK(ref[0][0] == was[0] - o[0] && ref[0][1] == was[1] - o[1] &&
          ref[0][2] == was[2] - o[2]);
}

/* The table follows kinds.h: a flat kind lists its faces (twins.h needs
 * them), a curved one has none; every GPU id is one the shader knows. */
static void test_kind_table(void)
{
    for (int k = 0; k < SHAPE_COUNT; k++) {
        const struct shape_kind *kind = &shape_kinds[k];
        expect(kind->flat == (kind->faces != NULL), "%s: flat is %d but faces %s",
               kind->keyword, kind->flat, kind->faces ? "listed" : "NULL");
        expect(!kind->met_as_planes || kind->flat, "%s: met as planes but not flat",
               kind->keyword);
        expect(kind->gpu_kind >= 0 && kind->gpu_kind < TP2_GPU_SHAPES,
               "%s: GPU id %d", kind->keyword, kind->gpu_kind);
        expect(kind->tier >= TP2_TIER_BASIC && kind->tier < TP2_TIERS, "%s: tier %d",
               kind->keyword, kind->tier);
    }
    CHECK(shape_kinds[SHAPE_MESH].gpu_kind == TP2_SHAPE_TRIANGLE);
}

int main(void)
{
    test_kind_table();
    test_round_bounds();
    test_quadric_bounds();
    test_convex_bounds();
    test_convex_against_oracle();
    test_convex_many_faces();
    test_convex_ill_conditioned();
    test_triangle_record();
    test_quadric_record();
    test_moved_records();
    return unit_report();
}
