// shapes.glsl: each kind of primitive's intersection (hit_KIND) and surface
// (surface_KIND). What each keeps in its record is listed in host/scene/shapes.c.
//
// Every hit_KIND returns the nearest t > 0 of object i along the ray o + t d
// (|d| = 1), or NO_HIT, and the part of it that was hit (a face, a cap).
// `on` says the ray starts on this very object's surface (rounding must not
// let it hit that point again), `inward` that it goes into its inside;
// each kind applies its own rule:
//  - convex solids (sphere, polyhedron, box, cylinder, cone): leaving
//    outward never meets them again; going inward meets only the exit;
//  - flat ones (plane, triangle): never met again;
//  - torus and quadric: the polynomial in t has a root at 0, divided out.
// Every surface_KIND gives the hit point moved onto the surface (removing
// the error of o + t d), the outward unit normal, and the size of the
// numbers that made it (what the offset of new rays scales with); a curved
// kind also gives its curvature there (surface_point), from the record it
// has already read.

real max_abs(rvec3 p)
{
    rvec3 a = abs(p);
    return max(a.x, max(a.y, a.z));
}

float max_abs2(rvec2 p)
{
    return float(max(abs(p.x), abs(p.y)));
}

// Moves o along the ray to where it passes closest to c and returns how
// far: quadratics and quartics formed there keep the size of the object,
// not of the distance, however far the camera.
real recenter(rvec3 c, inout rvec3 o, rvec3 d)
{
    real t0 = rdot(c - o, d);
    o += t0 * d;
    return t0;
}

// ---- convex solids: the span of t inside them -------------------------

struct Span {
    real t_in, t_out;      // may be -NO_HIT / NO_HIT: no bound on that side
    int part_in, part_out; // the part crossed there
    // Under SIGNATURES (edge_graze, exit_graze): the latest entry but one,
    // the earliest exit but one, and |n.d| of the faces crossed at t_in,
    // t_out, t_in2 and t_out2 (0 where not flat).
    real t_in2, t_out2;
    float cos_in, cos_out, cos_in2, cos_out2;
};

const Span WHOLE_LINE = Span(-NO_HIT, NO_HIT, 0, 0, -NO_HIT, NO_HIT, 0.0, 0.0, 0.0, 0.0);

// Narrows s to [t0, t1], entering through part p0, leaving through p1,
// flat faces crossed at |n.d| = cosine there.
void clip(inout Span s, real t0, real t1, int p0, int p1, float cosine)
{
    if (t0 > s.t_in) {
        if (SIGNATURES) {
            s.t_in2 = s.t_in;
            s.cos_in2 = s.cos_in;
            s.cos_in = cosine;
        }
        s.t_in = t0;
        s.part_in = p0;
    } else if (SIGNATURES && t0 > s.t_in2) {
        s.t_in2 = t0;
        s.cos_in2 = cosine;
    }
    if (t1 < s.t_out) {
        if (SIGNATURES) {
            s.t_out2 = s.t_out;
            s.cos_out2 = s.cos_out;
            s.cos_out = cosine;
        }
        s.t_out = t1;
        s.part_out = p1;
    } else if (SIGNATURES && t1 < s.t_out2) {
        s.t_out2 = t1;
        s.cos_out2 = cosine;
    }
}

// At least how far across a ray two crossings of flat faces at distance
// gap along it (at |n.d| = a and b) lie from meeting: moved across by e,
// the ray crosses each face up to e / |n.d| further along, so they meet
// once e (1/a + 1/b) >= gap, and 1/a + 1/b <= 2 / min(a, b).
float across(real gap, float a, float b)
{
    return 0.5 * float(abs(gap)) * min(a, b);
}

// How far an edge test's ray may be off where it is t along: doubt.x at
// its origin, doubt.y radians in its direction, and the test's own
// rounding on numbers of the size of o and `size` (the edge tests below).
float edge_reach(rvec3 o, vec2 doubt, float t, float size)
{
    return doubt.x + doubt.y * t + 4.0 * ROUNDING * (float(max_abs(o)) + size);
}

// The most reach an edge test counts: TP2_EDGE_REACH of the scene's scale
// (what the BVH's boxes grow by four times under SIGNATURES).
float most_reach()
{
    return float(TP2_EDGE_REACH) * float(frame.eye.w);
}

// Under SIGNATURES, edge becomes where a ray from outside passes an edge
// of a solid bounded by flat faces nearer than it may be off (doubt.x at
// its origin, doubt.y radians in its direction, and this test's own
// rounding): the edge where its entry and exit faces meet (a silhouette,
// hit or missed) or its last two entry faces (which face it meets). A
// straight edge can lie along a row of pixel centers (an axis-aligned
// box seen from a camera on its axes), where rounding flips a run of
// pixels that no neighbour's boundary test finds (signature.glsl,
// edges_seen). A miss counts only where the ray passes within twice that
// of the solid's box [lo, hi] (two faces' planes also meet far from a
// polyhedron) and that reach is at most TP2_EDGE_REACH of the scene's
// scale: there the BVH, whose boxes grow by four times that under
// SIGNATURES, tests the solid as a plain loop does, so that both mark the
// same pixels (an open polyhedron, tested by every ray, has no box: lo >
// hi). Doubts larger still are SENSITIVE's.
void edge_graze(Span s, rvec3 o, rvec3 d, vec2 doubt, rvec3 lo, rvec3 hi, inout float edge)
{
    if (!SIGNATURES || !(s.t_in > 0.0 && s.t_out < NO_HIT))
        return;
    float near = across(s.t_in - s.t_out, s.cos_in, s.cos_out);
    if (s.t_in2 > -NO_HIT && s.t_in <= s.t_out)
        near = min(near, across(s.t_in - s.t_in2, s.cos_in, s.cos_in2));
    float t = float(max(s.t_in, s.t_out));
    float reach = edge_reach(o, doubt, t, t);
    if (near >= reach || reach > most_reach())
        return;
    if (s.t_in > s.t_out && lo.x <= hi.x) { // missed: how far from its box (if any)
        rvec3 q = o + (0.5 * (s.t_in + s.t_out)) * d;
        if (length(vec3(max(max(lo - q, q - hi), rvec3(0.0)))) >= 2.0 * reach)
            return;
    }
    edge = float(min(s.t_in, s.t_out));
}

// The same for a ray inside a solid (or on it, going in), whose nearest
// two exits are t1 <= t2 through faces at |n.d| = c1 and c2: the edge
// where they meet decides which face it leaves by (seen through a glass
// box, the far edges of the box).
void exit_graze(real t1, float c1, real t2, float c2, rvec3 o, vec2 doubt, inout float edge)
{
    if (!SIGNATURES || !(t1 > 0.0 && t2 < NO_HIT))
        return;
    float t = float(t1);
    float reach = edge_reach(o, doubt, t, t);
    if (across(t1 - t2, c1, c2) < reach && reach <= most_reach())
        edge = t;
}

// Clips s by the slab lo <= oa + t da <= hi of a ray whose coordinate along
// an axis is oa + t da, met at t_lo and t_hi (where da != 0); parts p_lo
// and p_hi are its two faces. One clip, its ends chosen by da's sign:
// lavapipe runs both arms of an if.
void clip_slab_at(inout Span s, real oa, real da, real lo, real hi, real t_lo, real t_hi,
                  int p_lo, int p_hi)
{
    if (da == 0.0) {
        if (oa < lo || oa > hi)
            s.t_in = NO_HIT; // parallel and outside: empty
        return;
    }
    bool up = da > 0.0;
    clip(s, up ? t_lo : t_hi, up ? t_hi : t_lo, up ? p_lo : p_hi, up ? p_hi : p_lo,
         float(abs(da)));
}

// The same, met where the ray's coordinate is lo and hi.
void clip_slab(inout Span s, real oa, real da, real lo, real hi, int p_lo, int p_hi)
{
    clip_slab_at(s, oa, da, lo, hi, (lo - oa) / da, (hi - oa) / da, p_lo, p_hi);
}

// The hit a convex solid's span gives (see the rules at the top).
real convex_hit(Span s, bool on, bool inward, out int part)
{
    part = s.part_out;
    if (!(s.t_in <= s.t_out))
        return NO_HIT;
    if (on)
        return inward && s.t_out > 0.0 ? s.t_out : NO_HIT;
    if (s.t_in > 0.0) {
        part = s.part_in;
        return s.t_in;
    }
    return s.t_out > 0.0 ? s.t_out : NO_HIT;
}

// ---- sphere: a = center, radius ----------------------------------------

// The discriminant comes from the ray's closest approach to the center
// rather than b^2 - c, which cancels catastrophically for far-away
// spheres; the near root from c / q (no subtraction of near equals).
// Under SIGNATURES, graze becomes at most how near the ray passes the
// surface ahead of o, less this test's own rounding (signature.glsl,
// shadow_grazes); not the surface it starts on, which it leaves at the
// angle its |n.d| test doubts.
real hit_sphere(int i, rvec3 o, rvec3 d, bool on, bool inward, inout float graze)
{
    if (on && !inward)
        return NO_HIT;
    rvec4 sphere = object_row(i, 0);
    rvec3 oc = o - sphere.xyz;
    real r = sphere.w;
    real b = rdot(oc, d);
    rvec3 closest = oc - b * d;
    real disc = r * r - rdot(closest, closest);
    if (SIGNATURES && !on && b < 0.0)
        graze = min(graze, float(abs(disc) / (2.0 * r)) -
                               2.0 * ROUNDING * float(max_abs(oc) + r));
    if (disc < 0.0)
        return NO_HIT;
    real q = -b - (b < 0.0 ? -sqrt(disc) : sqrt(disc));
    real c = rdot(oc, oc) - r * r;
    real t0 = q != 0.0 ? c / q : real(0.0);
    real near_t = min(t0, q);
    real far_t = max(t0, q);
    if (near_t > 0.0 && !on)
        return near_t;
    return far_t > 0.0 ? far_t : NO_HIT;
}

void surface_sphere(int i, inout rvec3 p, out rvec3 n, out real scale, out vec2 curving)
{
    rvec4 sphere = object_row(i, 0);
    n = rnormalize(p - sphere.xyz);
    p = sphere.xyz + sphere.w * n;
    scale = max_abs(sphere.xyz) + sphere.w;
    curving = vec2(1.0 / float(sphere.w));
}

// ---- plane: a = unit normal, distance ----------------------------------

// Where the ray's line meets n.x + dist = 0, denom = n.d != 0: the one
// formula every surface of a coincident group is met by (host/ties.h), so
// that all give one distance, bit for bit.
real plane_cross(rvec4 plane, rvec3 o, real denom)
{
    return -(rdot(plane.xyz, o) + plane.w) / denom;
}

// t > 0 where the ray meets n.x + dist = 0.
real plane_t(rvec4 plane, rvec3 o, rvec3 d)
{
    real denom = rdot(plane.xyz, d);
    if (denom == 0.0)
        return NO_HIT;
    real t = plane_cross(plane, o, denom);
    return t > 0.0 ? t : NO_HIT;
}

real hit_plane(int i, rvec3 o, rvec3 d, bool on)
{
    return on ? NO_HIT : plane_t(object_row(i, 0), o, d);
}

// p moved onto plane (unit normal, distance), and its normal.
void onto_plane(rvec4 plane, inout rvec3 p, out rvec3 n, out real scale)
{
    n = plane.xyz;
    p -= (rdot(n, p) + plane.w) * n;
    scale = max(max_abs(p), abs(plane.w));
}

// ---- polyhedron: a.x = face count; faces in extra rows as planes -----------

// Whether exit_graze counts for span s: the ray starts inside the solid,
// or on it going in.
bool inside_span(Span s, bool on, bool inward)
{
    return (on ? inward : s.t_in <= 0.0) && s.t_in <= s.t_out && s.t_out > 0.0;
}

// The faces whose outward normals point against the ray are where it
// enters; the latest such entry and the earliest exit bound the span.
real hit_polyhedron(int i, rvec3 o, rvec3 d, bool on, bool inward, vec2 doubt,
                    inout float edge, out int part)
{
    int first = object_ids(i).w;
    int faces = int(object_row(i, 0).x);
    Span s = WHOLE_LINE;
    for (int k = 0; k < faces; ++k) {
        rvec4 f = extra_row(first + k);
        real denom = rdot(f.xyz, d);
        real dist = rdot(f.xyz, o) + f.w; // > 0: o is outside this face
        if (denom == 0.0) {
            if (dist > 0.0)
                return NO_HIT;
        } else {
            real t = -dist / denom;
            if (denom < 0.0)
                clip(s, t, NO_HIT, k, k, float(-denom));
            else
                clip(s, -NO_HIT, t, k, k, float(denom));
        }
    }
    if (!on)
        edge_graze(s, o, d, doubt, object_row(i, 1).xyz, object_row(i, 2).xyz, edge);
    if (SIGNATURES && inside_span(s, on, inward))
        exit_graze(s.t_out, s.cos_out, s.t_out2, s.cos_out2, o, doubt, edge);
    return convex_hit(s, on, inward, part);
}

void surface_polyhedron(int i, int part, inout rvec3 p, out rvec3 n, out real scale)
{
    onto_plane(extra_row(object_ids(i).w + part), p, n, scale);
}

// ---- box: a = min corner, b = max corner --------------------------------

// Parts: axis + 3 for the face at the max corner.
real hit_box(int i, rvec3 o, rvec3 d, bool on, bool inward, vec2 doubt, inout float edge,
             out int part)
{
    rvec3 lo = object_row(i, 0).xyz;
    rvec3 hi = object_row(i, 1).xyz;
    Span s = WHOLE_LINE;
    clip_slab(s, o.x, d.x, lo.x, hi.x, 0, 3);
    clip_slab(s, o.y, d.y, lo.y, hi.y, 1, 4);
    clip_slab(s, o.z, d.z, lo.z, hi.z, 2, 5);
    if (!on)
        edge_graze(s, o, d, doubt, lo, hi, edge);
    if (SIGNATURES && inside_span(s, on, inward))
        exit_graze(s.t_out, s.cos_out, s.t_out2, s.cos_out2, o, doubt, edge);
    return convex_hit(s, on, inward, part);
}

// The face's coordinate is exact: the point is put on it.
// The outward normal of a box's face `part`.
rvec3 box_normal(int part)
{
    rvec3 n = rvec3(0.0);
    n[part % 3] = part >= 3 ? 1.0 : -1.0;
    return n;
}

void surface_box(int i, int part, inout rvec3 p, out rvec3 n, out real scale)
{
    int axis = part % 3;
    rvec3 corner = part >= 3 ? object_row(i, 1).xyz : object_row(i, 0).xyz;
    n = box_normal(part);
    p[axis] = corner[axis];
    scale = max(max_abs(p), max(max_abs(object_row(i, 0).xyz), max_abs(object_row(i, 1).xyz)));
}

#ifdef TP2_CURVED // the build with the curved kinds (see CMakeLists.txt)
#include "poly.glsl"

// ---- cylinder: a = base center, radius; b = unit axis, length -----------
// ---- cone: the same with a.w = r0 at the base and c.x = r1 at the top ----
// Parts: 0 the side, 1 the base cap, 2 the top cap.

// The span inside the solid cone or cylinder: the side's quadratic, the
// slab between the caps. Its radius at height z along the axis is
// r0 + k z; the side holds |x_perp|^2 <= (r0 + k z)^2 on the nappe where
// r0 + k z >= 0, which the slab keeps (both radii are >= 0).
// The caps: where the scene has a cap lying in another object's face (a
// twin cap, host/pack/ties.h; TWIN_CAPS), every cap is met as a plane
// is, from the ray as it came: (c - axis.o) / (axis.d), c the cap's place
// along the axis, c.y for the base and c.y + h for the top. Packing made
// a twin the base (turning the solid over where it is the top), its axis
// that face's normal (up to its sign) and c.y the face's place, so this
// is plane_cross's arithmetic on that face, bit for bit. c.y shares its
// texel with a cone's top radius. The span is clipped in the ray's own
// distances.
real hit_tapered(int i, real r1, rvec3 o, rvec3 d, bool on, bool inward, out int part)
{
    rvec4 base = object_row(i, 0);
    rvec4 axis = object_row(i, 1);
    real h = axis.w;
    real k = (r1 - base.w) / h;
    real ao = rdot(axis.xyz, o); // before o moves
    real t0 = recenter(base.xyz + (0.5 * h) * axis.xyz, o, d);
    rvec3 oc = o - base.xyz;
    real oa = rdot(oc, axis.xyz);
    real da = rdot(d, axis.xyz);
    rvec3 op = oc - oa * axis.xyz;
    rvec3 dp = d - da * axis.xyz;
    real rho = base.w + k * oa; // the radius at the origin's height
    real slope = k * da;        // how fast the radius grows along the ray
    real c = TWIN_CAPS ? object_row(i, 2).y : 0.0;
    rvec2 caps = TWIN_CAPS ? (rvec2(c, c + h) - ao) / da : rvec2(0.0 - oa, h - oa) / da + t0;
    Span s = WHOLE_LINE;
    clip_slab_at(s, oa, da, 0.0, h, caps.x, caps.y, 1, 2);
    rvec2 r;
    real qa = rdot(dp, dp) - slope * slope;
    int n = quadratic_roots(qa, 2.0 * (rdot(op, dp) - rho * slope), rdot(op, op) - rho * rho, r);
    r += t0;
    if (n == 2 && qa > 0.0) {
        clip(s, r.x, r.y, 0, 0, 0.0);
    } else if (n == 2) { // steeper than the side: the half-line on our nappe
        if (slope > 0.0)
            clip(s, r.y, NO_HIT, 0, 0, 0.0);
        else
            clip(s, -NO_HIT, r.x, 0, 0, 0.0);
    } else if (n == 1) { // parallel to the side: one crossing
        bool below = 2.0 * (rdot(op, dp) - rho * slope) > 0.0; // Q < 0 before it
        if (below)
            clip(s, -NO_HIT, r.x, 0, 0, 0.0);
        else
            clip(s, r.x, NO_HIT, 0, 0, 0.0);
    } else if (qa > 0.0 || (qa == 0.0 && rdot(op, op) > rho * rho)) {
        return NO_HIT; // outside the side all along (else inside all along)
    }
    return convex_hit(s, on, inward, part);
}

// The radius at the top: a cylinder's is its radius.
real top_radius(int i, int kind)
{
    return kind == TP2_SHAPE_CYLINDER ? object_row(i, 0).w : object_row(i, 2).x;
}

void surface_tapered(int i, real r1, int part, inout rvec3 p, out rvec3 n, out real scale,
                     out vec2 curving)
{
    rvec4 base = object_row(i, 0);
    rvec4 axis = object_row(i, 1);
    rvec3 y = p - base.xyz;
    real z = rdot(y, axis.xyz);
    scale = max_abs(p) + axis.w + max(base.w, r1);
    curving = vec2(0.0);
    if (part != 0) {
        bool top = part == 2;
        n = top ? axis.xyz : -axis.xyz;
        p -= (z - (top ? axis.w : 0.0)) * axis.xyz;
        return;
    }
    real k = (r1 - base.w) / axis.w;
    rvec3 radial = y - z * axis.xyz;
    real len = rlength(radial);
    rvec3 e = len > 0.0 ? radial / len : rvec3(0.0);
    n = len > 0.0 ? rnormalize(e - k * axis.xyz) : (k > 0.0 ? -axis.xyz : axis.xyz);
    p = base.xyz + z * axis.xyz + (base.w + k * z) * e;
    // 0 along the side; 1 / (the distance to the axis) around it
    rvec3 yp = p - base.xyz;
    curving.y = 1.0 / float(rlength(yp - rdot(yp, axis.xyz) * axis.xyz));
}

// ---- torus: a = center, R; b = unit axis, r ------------------------------

// In units of R + r around the center: |x|^2 + R^2 - r^2)^2 =
// 4 R^2 |x_perp|^2, a monic quartic in s along the ray, solved by
// isolation (poly.glsl). A ray starting on it has the root s = 0, divided
// out (a cubic). A spindle torus (R < r) also has the inner lemon
// ((rho + R)^2 + z^2 = r^2) as roots; they are skipped.
real hit_torus(int i, rvec3 o, rvec3 d, bool on)
{
    rvec4 ca = object_row(i, 0);
    rvec4 ab = object_row(i, 1);
    real size = ca.w + ab.w;
    real t0 = on ? real(0.0) : recenter(ca.xyz, o, d);
    rvec3 x = (o - ca.xyz) / size;
    real R = ca.w / size, r = ab.w / size;
    real alpha = rdot(x, d);
    real xx = rdot(x, x);
    real near_sq = alpha * alpha - xx + 1.0; // the unit bounding sphere
    if (near_sq < 0.0)
        return NO_HIT;
    real lo = on ? real(0.0) : max(-alpha - sqrt(near_sq), -t0 / size);
    real hi = -alpha + sqrt(near_sq);
    if (!(lo < hi))
        return NO_HIT;
    real dz = rdot(d, ab.xyz), xz = rdot(x, ab.xyz);
    real beta = xx + R * R - r * r;
    real R4 = 4.0 * R * R;
    rvec4 c = rvec4(beta * beta - R4 * (xx - xz * xz),
                    4.0 * alpha * beta - 2.0 * R4 * (alpha - xz * dz),
                    4.0 * alpha * alpha + 2.0 * beta - R4 * (1.0 - dz * dz),
                    4.0 * alpha);
    // On the surface: the roots of s^3 + c.w s^2 + c.z s + c.y, the
    // quartic over s. Else the quartic's, cut where its slope (a cubic)
    // is zero.
    rvec4 cubic = on ? rvec4(c.y, c.z, c.w, 1.0) : rvec4(c.y, 2.0 * c.z, 3.0 * c.w, 4.0);
    rvec4 roots = cubic_roots(cubic, lo, hi, on ? ROOT_TOL : CUT_TOL);
    if (!on)
        roots = roots_between(1.0, c, roots.xyz, lo, hi, ROOT_TOL);
    // The first root that is on the tube (not the lemon) and ahead.
    real found = NO_HIT;
    for (int k = 0; k < 4 && roots.x < NO_HIT && found == NO_HIT; ++k) {
        rvec3 y = x + roots.x * d;
        real z = rdot(y, ab.xyz);
        real rho = rlength(y - z * ab.xyz);
        real tube = (rho - R) * (rho - R) + z * z - r * r;
        real lemon = (rho + R) * (rho + R) + z * z - r * r;
        real t = t0 + roots.x * size;
        if (abs(tube) <= abs(lemon) && t > 0.0)
            found = t;
        roots = rvec4(roots.yzw, NO_HIT);
    }
    return found;
}

// p moved onto the tube: r from the nearest point of the core circle.
void surface_torus(int i, inout rvec3 p, out rvec3 n, out real scale, out vec2 curving)
{
    rvec4 ca = object_row(i, 0);
    rvec4 ab = object_row(i, 1);
    rvec3 y = p - ca.xyz;
    real z = rdot(y, ab.xyz);
    rvec3 radial = y - z * ab.xyz;
    real len = rlength(radial);
    rvec3 core = len > 0.0 ? (ca.w / len) * radial : rvec3(0.0);
    rvec3 w = y - core;
    n = rlength(w) > 0.0 ? rnormalize(w) : (z >= 0.0 ? ab.xyz : -ab.xyz);
    p = ca.xyz + core + ab.w * n;
    scale = max_abs(ca.xyz) + ca.w + ab.w;
    // 1/r around the tube; (rho - R) / (r rho) around the axis
    rvec3 yp = p - ca.xyz;
    float rho = float(rlength(yp - rdot(yp, ab.xyz) * ab.xyz));
    float tube = 1.0 / float(ab.w), ring = (rho - float(ca.w)) / (float(ab.w) * rho);
    curving = vec2(min(tube, ring), max(tube, ring));
}

// ---- quadric: a = A B C D, b = E F G H, c.xy = I J about extra_row(ids.w) ----

// M y for the symmetric matrix of the quadratic part.
rvec3 quadric_m(int i, rvec3 y)
{
    rvec4 a = object_row(i, 0);
    rvec4 b = object_row(i, 1);
    return rvec3(a.x * y.x + 0.5 * (a.w * y.y + b.x * y.z),
                 a.y * y.y + 0.5 * (a.w * y.x + b.y * y.z),
                 a.z * y.z + 0.5 * (b.x * y.x + b.y * y.y));
}

rvec3 quadric_g(int i)
{
    return rvec3(object_row(i, 1).zw, object_row(i, 2).x);
}

real hit_quadric(int i, rvec3 o, rvec3 d, bool on)
{
    rvec3 ref = extra_row(object_ids(i).w).xyz;
    real t0 = on ? real(0.0) : recenter(ref, o, d);
    rvec3 y = o - ref;
    rvec3 g = quadric_g(i);
    rvec3 md = quadric_m(i, d);
    real qa = rdot(d, md);
    real qb = 2.0 * rdot(y, md) + rdot(g, d);
    if (on) // the root at 0 divided out: qa s + qb = 0
        return qa != 0.0 && -qb / qa > 0.0 ? -qb / qa : NO_HIT;
    real qc = rdot(y, quadric_m(i, y)) + rdot(g, y) + object_row(i, 2).y;
    rvec2 r;
    int n = quadratic_roots(qa, qb, qc, r);
    if (n >= 1 && t0 + r.x > 0.0)
        return t0 + r.x;
    return n == 2 && t0 + r.y > 0.0 ? t0 + r.y : NO_HIT;
}

// One Newton step onto Q = 0 along the gradient, which points outward
// (toward Q > 0).
void surface_quadric(int i, rvec3 d, inout rvec3 p, out rvec3 n, out real scale,
                     out vec2 curving)
{
    rvec3 ref = extra_row(object_ids(i).w).xyz;
    rvec3 y = p - ref;
    rvec3 my = quadric_m(i, y);
    rvec3 g = quadric_g(i);
    rvec3 grad = 2.0 * my + g;
    real q = rdot(y, my) + rdot(g, y) + object_row(i, 2).y;
    real gg = rdot(grad, grad);
    if (gg > 0.0) {
        p -= (q / gg) * grad;
        n = rnormalize(grad);
    } else { // a singular point (a cone's apex): face the ray
        n = -d;
    }
    scale = max_abs(p);
    // either sign, up to |Hessian| / |gradient| at p (the Hessian 2M
    // bounded by its row sums)
    rvec3 at = 2.0 * quadric_m(i, p - ref) + g;
    vec3 rows = vec3(abs(quadric_m(i, rvec3(1, 0, 0)))) + vec3(abs(quadric_m(i, rvec3(0, 1, 0)))) +
                vec3(abs(quadric_m(i, rvec3(0, 0, 1))));
    float k = 2.0 * max(rows.x, max(rows.y, rows.z)) / float(rlength(at));
    curving = vec2(-k, k);
}

#endif // TP2_CURVED

// ---- triangle: a, b, c = corners, unit normal in their w ---------------

// The edge test of edge_graze for a triangle: edge becomes where the ray
// passes one of its edges nearer than it may be off (doubt as there, and
// this test's own rounding), hit or missed, if ahead. Edge bc's side is
// u's sign, and u is bc's length in the sheared plane times the ray's
// distance from it there; a move of the ray by e moves it in that plane
// by at most (1 + sqrt(2)) e (the shear's entries are at most 1). The ray
// passes the segment, not its line beyond a corner, where v and w have
// one sign (or near a corner, where two edges are near). A mesh whose
// edges lie along a row of pixel centers flips a run of pixels, as a box
// does (tests/stress/triangle-edges-on-pixel-rows.txt).
// `sides` bounds each edge's length in the sheared plane (sqrt(2) times
// it is at least the length), `along` the corners' least and greatest t,
// `size` their largest coordinate; `spans`, whether the corners lie on
// both sides of the ray in the sheared plane, along its wider axis.
void triangle_graze(rvec3 uvw, real tw, vec3 sides, vec2 along, float size, bool spans,
                    rvec3 o, vec2 doubt, inout float edge)
{
    if (!(along.y > 0.0))
        return;
    real det = uvw.x + uvw.y + uvw.z;
    // where the ray meets the plane (if it does: else, as far as the
    // farthest corner, for the reach)
    float t = det != 0.0 ? float(tw / det) : along.y;
    float reach = edge_reach(o, doubt, t, size);
    if (reach > most_reach())
        return;
    // |u| = distance times length <= (1 + sqrt(2)) reach times sqrt(2) sides
    bvec3 near = lessThanEqual(abs(vec3(uvw)), 3.6 * reach * sides);
    bvec3 pos = greaterThanEqual(uvw, rvec3(0.0));
    bvec3 agree = equal(pos.yzx, pos.zxy); // the other two weights agree
    bool corner = (near.x && (near.y || near.z)) || (near.y && near.z);
    // Near all three: seen edge-on (or smaller than the reach), from its
    // nearest corner; only where the ray passes through it in the sheared
    // plane, as an edge-on triangle's plane holds rays far beyond it too,
    // which the BVH's boxes keep from it (the rest are near an edge).
    if (all(near))
        edge = spans ? max(along.x, 0.0) : edge;
    else if (t > 0.0 && (corner || any(bvec3(near.x && agree.x, near.y && agree.y,
                                                 near.z && agree.z))))
        edge = t;
}

// Watertight (Woop, Benthin and Wald 2013): the ray becomes the z axis by
// a permutation and a shear, and each edge's side is decided by a 2D
// cross product computed the same way for the two triangles sharing it, so
// no ray slips between them. Gives the corners' weights (u, v, w) of the
// point the ray's line meets the triangle's plane (their sum is not 1),
// and how far along the ray it is, t = tw / (u + v + w). With `graze`,
// under SIGNATURES, the edge test too (triangle_graze), here where the
// corners are at hand: against the most reach that counts first, which
// most rays pass no edge within, so that the rest is skipped.
rvec3 triangle_weights(int i, rvec3 o, rvec3 d, bool graze, vec2 doubt, out real tw,
                       inout float edge)
{
    rvec3 ad = abs(d);
    // Permute so that z is d's largest component, keeping the winding.
    ivec3 k = ad.x > ad.y ? (ad.x > ad.z ? ivec3(1, 2, 0) : ivec3(0, 1, 2))
                          : (ad.y > ad.z ? ivec3(2, 0, 1) : ivec3(0, 1, 2));
    if (d[k.z] < 0.0)
        k.xy = k.yx;
    rvec3 shear = rvec3(d[k.x], d[k.y], 1.0) / d[k.z];
    rvec3 a = object_row(i, 0).xyz - o;
    rvec3 b = object_row(i, 1).xyz - o;
    rvec3 c = object_row(i, 2).xyz - o;
    rvec3 pa = rvec3(a[k.x], a[k.y], a[k.z]);
    rvec3 pb = rvec3(b[k.x], b[k.y], b[k.z]);
    rvec3 pc = rvec3(c[k.x], c[k.y], c[k.z]);
    rvec2 sa = pa.xy - shear.xy * pa.z;
    rvec2 sb = pb.xy - shear.xy * pb.z;
    rvec2 sc = pc.xy - shear.xy * pc.z;
    rvec3 uvw = rvec3(sc.x * sb.y - sc.y * sb.x, sa.x * sc.y - sa.y * sc.x,
                      sb.x * sa.y - sb.y * sa.x);
    tw = (uvw.x * pa.z + uvw.y * pb.z + uvw.z * pc.z) * shear.z;
    if (SIGNATURES && graze) {
        // each edge's length in the sheared plane is at most sqrt(2) times this
        vec3 sides = vec3(max_abs2(sb - sc), max_abs2(sc - sa), max_abs2(sa - sb));
        if (any(lessThanEqual(abs(vec3(uvw)), (3.6 * most_reach()) * sides))) {
            vec3 z = vec3(rvec3(pa.z, pb.z, pc.z) * shear.z); // the corners' t
            float size = float(max(max_abs(pa), max(max_abs(pb), max_abs(pc))));
            // whether the ray's trace (0, 0) lies between the corners
            // along the wider of the two axes (for triangle_graze's edge-on)
            vec2 lo = vec2(min(sa, min(sb, sc))), hi = vec2(max(sa, max(sb, sc)));
            bvec2 spans = bvec2(lo.x <= 0.0 && hi.x >= 0.0, lo.y <= 0.0 && hi.y >= 0.0);
            triangle_graze(uvw, tw, sides, vec2(min(z.x, min(z.y, z.z)), max(z.x, max(z.y, z.z))),
                           size, hi.x - lo.x >= hi.y - lo.y ? spans.x : spans.y, o, doubt, edge);
        }
    }
    return uvw;
}

// Triangle i's unit normal (its corners' w).
rvec3 triangle_normal(int i)
{
    return rvec3(object_row(i, 0).w, object_row(i, 1).w, object_row(i, 2).w);
}

// Whether a ray along d lies in triangle i's plane to within rounding
// (|n.d| at most 4 units of the precision's roundoff). The model meets
// such a triangle nowhere (u + v + w = 0), but rounding leaves u, v and w
// all noise, which may agree in sign: a "hit" at a noise distance, on a
// ray that need not pass near the triangle (a shadow ray whose light and
// point both lie in the plane of a triangle seen edge-on). Asked only of
// a hit, so the unit normal (the corners' w) is read only then.
bool edge_on(int i, rvec3 d)
{
    return abs(rdot(triangle_normal(i), d)) <= 4.0 * REAL_EPSILON;
}

real hit_triangle(int i, rvec3 o, rvec3 d, bool on, vec2 doubt, inout float edge)
{
    if (on)
        return NO_HIT;
    real tw;
    rvec3 uvw = triangle_weights(i, o, d, true, doubt, tw, edge);
    if (any(lessThan(uvw, rvec3(0.0))) && any(greaterThan(uvw, rvec3(0.0))))
        return NO_HIT;
    real det = uvw.x + uvw.y + uvw.z;
    if (det == 0.0 || edge_on(i, d))
        return NO_HIT;
    real t = tw / det;
    // In another object's face (host/ties.h): that face's distance, so
    // that the two tie exactly; asked only of a ray inside the corners.
    ivec4 ids = TWIN_TRIANGLES ? object_ids(i) : ivec4(0);
    if (TWIN_TRIANGLES && (ids.x & TP2_SHAPE_TWIN) != 0) {
        rvec4 twin = extra_row(ids.w);
        real denom = rdot(twin.xyz, d);
        t = denom != 0.0 ? plane_cross(twin, o, denom) : t;
    }
    return t > 0.0 ? t : NO_HIT;
}

// The point from the corners' weights rather than o + t d: it then lies
// on this triangle to the precision of its corners, however far the ray
// came, and not just past an edge on a neighbor's side (where its shadow
// rays would hit the neighbor: acne on meshes seen from afar).
void surface_triangle(int i, rvec3 o, rvec3 d, inout rvec3 p, out rvec3 n, out real scale)
{
    rvec4 a = object_row(i, 0);
    rvec4 b = object_row(i, 1);
    rvec4 c = object_row(i, 2);
    n = rvec3(a.w, b.w, c.w);
    real tw;
    float edge = NO_EDGE; // (no edge test here)
    rvec3 uvw = triangle_weights(i, o, d, false, vec2(0.0), tw, edge);
    uvw /= uvw.x + uvw.y + uvw.z;
    p = uvw.x * a.xyz + uvw.y * b.xyz + uvw.z * c.xyz;
    scale = max(max_abs(a.xyz), max(max_abs(b.xyz), max_abs(c.xyz)));
}

// ---- by kind -----------------------------------------------------------

// Object i's kind; a constant when the bounded objects (those before
// frame.geometry.x) are all of one kind, and the unbounded ones too: the
// kind is then not loaded for every object a ray meets.
int shape_of(int i)
{
    if (BOUNDED_SHAPE >= 0 && (UNBOUNDED_SHAPE >= 0 || i < frame.geometry.x))
        return i < frame.geometry.x ? BOUNDED_SHAPE : UNBOUNDED_SHAPE;
    if (UNBOUNDED_SHAPE >= 0 && i >= frame.geometry.x)
        return UNBOUNDED_SHAPE;
    return object_ids(i).x & TP2_SHAPE_MASK;
}

// Whether object i's numbers are the same in float as in double
// (TP2_SHAPE_INEXACT).
bool same_in_float(int i)
{
    return (object_ids(i).x & TP2_SHAPE_INEXACT) == 0;
}

// Object i's nearest t > 0 and part (see the top of this file); graze
// and edge: see hit_sphere and edge_graze (doubt: the ray's). kind is
// shape_of(i), a constant where the caller knows it (intersect.glsl,
// trace_plain): only that kind's test is then compiled there.
real hit_object(int i, int kind, rvec3 o, rvec3 d, bool on, bool inward, vec2 doubt,
                out int part, inout float graze, inout float edge)
{
    part = 0;
    if (USES_SHAPE(TP2_SHAPE_SPHERE) && kind == TP2_SHAPE_SPHERE)
        return hit_sphere(i, o, d, on, inward, graze);
    if (USES_SHAPE(TP2_SHAPE_PLANE) && kind == TP2_SHAPE_PLANE)
        return hit_plane(i, o, d, on);
#ifdef TP2_FACETED // the builds with faces (see CMakeLists.txt)
    if (USES_SHAPE(TP2_SHAPE_TRIANGLE) && kind == TP2_SHAPE_TRIANGLE)
        return hit_triangle(i, o, d, on, doubt, edge);
    if (USES_SHAPE(TP2_SHAPE_BOX) && kind == TP2_SHAPE_BOX)
        return hit_box(i, o, d, on, inward, doubt, edge, part);
    if (USES_SHAPE(TP2_SHAPE_POLYHEDRON) && kind == TP2_SHAPE_POLYHEDRON)
        return hit_polyhedron(i, o, d, on, inward, doubt, edge, part);
#endif
#ifdef TP2_CURVED
    if ((USES_SHAPE(TP2_SHAPE_CYLINDER) && kind == TP2_SHAPE_CYLINDER) ||
        (USES_SHAPE(TP2_SHAPE_CONE) && kind == TP2_SHAPE_CONE))
        return hit_tapered(i, top_radius(i, kind), o, d, on, inward, part);
    if (USES_SHAPE(TP2_SHAPE_TORUS) && kind == TP2_SHAPE_TORUS)
        return hit_torus(i, o, d, on);
    if (USES_SHAPE(TP2_SHAPE_QUADRIC) && kind == TP2_SHAPE_QUADRIC)
        return hit_quadric(i, o, d, on);
#endif
    return NO_HIT;
}

// The hit point of object i at t (part from hit_object) moved onto its
// surface, the outward unit normal there, and the scale of its numbers;
// and the surface's curvature there, as the least and the greatest of its
// principal curvatures, positive where it bulges outward (a sphere of
// radius r: 1/r, 1/r; flat faces: 0, 0). The float pass's doubt uses it
// (signature.glsl): how far a normal computed from a point off by e may
// turn (e times the largest magnitude), and how much a mirror or a lens
// there may spread or focus a beam. (Where no pass uses it, the compiler
// drops it.)
void surface_point(int i, int part, rvec3 o, rvec3 d, real t,
                   out rvec3 p, out rvec3 n, out real scale, out vec2 curving)
{
    p = o + t * d;
    curving = vec2(0.0);
    int kind = shape_of(i);
    if (USES_SHAPE(TP2_SHAPE_SPHERE) && kind == TP2_SHAPE_SPHERE)
        surface_sphere(i, p, n, scale, curving);
    else if (USES_SHAPE(TP2_SHAPE_PLANE) && kind == TP2_SHAPE_PLANE)
        onto_plane(object_row(i, 0), p, n, scale);
#ifdef TP2_FACETED
    else if (USES_SHAPE(TP2_SHAPE_TRIANGLE) && kind == TP2_SHAPE_TRIANGLE)
        surface_triangle(i, o, d, p, n, scale);
    else if (USES_SHAPE(TP2_SHAPE_BOX) && kind == TP2_SHAPE_BOX)
        surface_box(i, part, p, n, scale);
    else if (USES_SHAPE(TP2_SHAPE_POLYHEDRON) && kind == TP2_SHAPE_POLYHEDRON)
        surface_polyhedron(i, part, p, n, scale);
#endif
#ifdef TP2_CURVED
    else if ((USES_SHAPE(TP2_SHAPE_CYLINDER) && kind == TP2_SHAPE_CYLINDER) ||
             (USES_SHAPE(TP2_SHAPE_CONE) && kind == TP2_SHAPE_CONE))
        surface_tapered(i, top_radius(i, kind), part, p, n, scale, curving);
    else if (USES_SHAPE(TP2_SHAPE_TORUS) && kind == TP2_SHAPE_TORUS)
        surface_torus(i, p, n, scale, curving);
    else if (USES_SHAPE(TP2_SHAPE_QUADRIC) && kind == TP2_SHAPE_QUADRIC)
        surface_quadric(i, d, p, n, scale, curving);
#endif
    else {
        n = -d;
        scale = max_abs(p);
    }
}

// How many times a plain intersection's rounding object i's may have: a
// torus's quartic, solved by isolation, loses more digits (256 times:
// measured, docs/accuracy.md).
float hit_rounding(int i)
{
    int kind = shape_of(i);
    return USES_SHAPE(TP2_SHAPE_TORUS) && kind == TP2_SHAPE_TORUS ? 256.0 : 1.0;
}

// Whether object i is flat wherever a ray meets it (a plane or faces).
bool flat_kind(int i)
{
    int kind = shape_of(i);
    return kind == TP2_SHAPE_PLANE || kind == TP2_SHAPE_POLYHEDRON || kind == TP2_SHAPE_BOX ||
           kind == TP2_SHAPE_TRIANGLE;
}

// The unit normal of part `part` of flat object i (flat_kind), either way.
rvec3 flat_normal(int i, int part)
{
    int kind = shape_of(i);
    if (kind == TP2_SHAPE_PLANE)
        return object_row(i, 0).xyz;
    if (kind == TP2_SHAPE_TRIANGLE)
        return triangle_normal(i);
    if (kind == TP2_SHAPE_POLYHEDRON)
        return extra_row(object_ids(i).w + part).xyz;
    return box_normal(part);
}

// Whether crossings of objects a and b that float finds at one distance
// are on faces that coincide in double too (a box on the floor), so that
// the same object wins in both: both flat, on one plane (the hit's normal
// n and part b_part of b agree), and neither has a face near another
// object's face without being on its plane (a box top at 0.3 under a
// plane at 0.3000000001: TP2_SHAPE_NEAR_TWIN, host/pack/twins.h). Two faces
// that cross tie in float along the line where they meet, which may lie
// along a row of pixel centers (a mirror floor meeting a wall there),
// where double orders them its own way. b < 0: no second crossing.
bool coincident_faces(int a, int b, int b_part, rvec3 n)
{
    return b >= 0 && flat_kind(a) && flat_kind(b) &&
           ((object_ids(a).x | object_ids(b).x) & TP2_SHAPE_NEAR_TWIN) == 0 &&
           abs(float(rdot(n, flat_normal(b, b_part)))) >= 1.0 - 1.0 / 65536.0;
}

// Whether a ray through object i's surface goes into an inside (a
// triangle has none: transmitted rays go on unbent).
bool has_inside(int i)
{
    return !(USES_SHAPE(TP2_SHAPE_TRIANGLE) && shape_of(i) == TP2_SHAPE_TRIANGLE);
}
