// real.glsl: the geometry's precision (real, rvec2-4: TP2_DOUBLE selects
// double) and the functions of it whose rounding GLSL leaves to a driver.
//
// In double, the exact image's model and what the default's retrace
// settles doubts in, the geometry is evaluated as written, so that every
// device rounds it alike: a point exactly on a boundary (a checker cell
// face through a row of pixel centers, as course files with whole-number
// coordinates have) falls on the same side on lavapipe and on a GPU. The
// host decorates the double build's arithmetic NoContraction (no fused
// multiply-adds: host/gpu/spirv_exact.h), and here dot, length and normalize
// are products, sums, a sqrt and a division in a fixed order: GLSL's own
// leave order and method to the driver (an NVIDIA H200's double image of
// a course file differed from lavapipe's at 37 pixels of such a row, and
// at none with these; docs/accuracy.md). In float they are GLSL's own:
// the float pass's doubt covers their rounding.

#ifdef TP2_DOUBLE
#define real double
#define rvec2 dvec2
#define rvec3 dvec3
#define rvec4 dvec4
#else
#define real float
#define rvec2 vec2
#define rvec3 vec3
#define rvec4 vec4
#endif

// TP2_REL_EPS: offset of a new ray's origin off its surface, relative to
// the scale of the hit point: 16 ulps, against coincident surfaces
// (self-hits are ruled out by Start, not by this).
#ifdef TP2_DOUBLE
#define TP2_REL_EPS 5.6843418860808015e-14LF // 2^-44
#define REAL_EPSILON 1.1102230246251565e-16LF // the unit roundoff, 2^-53

real rdot(rvec3 a, rvec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
real rlength(rvec3 v) { return sqrt(rdot(v, v)); }
rvec3 rnormalize(rvec3 v) { return v / rlength(v); }
#else
#define TP2_REL_EPS 9.5367431640625e-7 // 2^-20
#define REAL_EPSILON 5.9604645e-8 // the unit roundoff, 2^-24

real rdot(rvec3 a, rvec3 b) { return dot(a, b); }
real rlength(rvec3 v) { return length(v); }
rvec3 rnormalize(rvec3 v) { return normalize(v); }
#endif
