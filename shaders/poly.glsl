// poly.glsl: real roots of quartics and cubics in an interval (the torus).
//
// Closed-form quartic and cubic formulas lose all precision in float for
// grazing, edge-on and far-away rays. Here roots are isolated instead: a
// polynomial is monotone between the roots of its derivative, so each such
// piece whose ends differ in sign holds exactly one root, which Newton
// steps kept inside the piece (bisection when they leave it) converge to.
// The derivative's roots come the same way from its own derivative, a
// quadratic solved in closed form. A polynomial is (c4, c) for
// c4 s^4 + c.w s^3 + c.z s^2 + c.y s + c.x; vectors, not arrays, so nothing
// is indexed at run time.

// Newton or bisection steps per root: far more than convergence takes
// (Newton doubles the digits each step; bisection gains one bit).
const int ROOT_STEPS = 60;

// Roots are sought in units of the object's size (the torus fits the unit
// sphere). A search ends when a bracket is within tol.x, a halving step
// within tol.x, or a Newton step (one that stays in the bracket) within
// tol.y. In double a Newton step of 1e-8 already leaves an error near
// (f'' / 2 f') 1e-16 (each step doubles the digits), of the order of the
// rounding limit of a root of a polynomial evaluated in double, eps
// sum |c_k s^k| / |f'|, so the one more step a tol.y of 4e-16 took is
// spared: for the cuts (a slope's roots, which only split an interval into
// monotone pieces) torus.txt's double render took 0.96-1.00 of its time,
// for the roots too 0.84 (docs/decisions.md), the same bytes. Halving
// still goes on to 4e-16: it gains a bit a step, not digits. In float
// the last step changed an image (a pixel of torus-edge-on by 3 levels),
// so float keeps it.
#ifdef TP2_DOUBLE
const rvec2 ROOT_TOL = rvec2(4e-16LF, 1e-8LF);
const rvec2 CUT_TOL = rvec2(1e-8LF);
#else
const rvec2 ROOT_TOL = rvec2(2e-7);
const rvec2 CUT_TOL = ROOT_TOL;
#endif

real poly_value(real c4, rvec4 c, real s)
{
    return (((c4 * s + c.w) * s + c.z) * s + c.y) * s + c.x;
}

real poly_slope(real c4, rvec4 c, real s)
{
    return ((4.0 * c4 * s + 3.0 * c.w) * s + 2.0 * c.z) * s + c.y;
}

// The root in [a, b] of a polynomial monotone there whose values at a and
// b differ in sign (fa, fb): from where the chord crosses zero, Newton
// steps, or halving when they leave the bracket, until a step or the
// bracket is within tol (ROOT_TOL, or CUT_TOL for cuts; see above).
real bracketed_root(real c4, rvec4 c, real a, real b, real fa, real fb, rvec2 tol)
{
    real x = a - fa * (b - a) / (fb - fa);
    if (!(x > a && x < b))
        x = 0.5 * (a + b);
    for (int step = 0; step < ROOT_STEPS; ++step) {
        real fx = poly_value(c4, c, x);
        if (fx == 0.0)
            break;
        if ((fx < 0.0) == (fa < 0.0))
            a = x;
        else
            b = x;
        real next = x - fx / poly_slope(c4, c, x);
        bool newton = next > a && next < b; // false outside the bracket, or NaN
        if (!newton)
            next = 0.5 * (a + b);
        bool done = abs(next - x) <= (newton ? tol.y : tol.x) || b - a <= tol.x;
        x = next;
        if (done)
            break;
    }
    return x;
}

// The roots of a s^2 + b s + c, ascending, in r; how many (0 to 2). The
// stable form: no subtraction of nearly equal numbers.
int quadratic_roots(real a, real b, real c, out rvec2 r)
{
    r = rvec2(NO_HIT);
    if (a == 0.0) {
        if (b == 0.0)
            return 0;
        r.x = -c / b;
        return 1;
    }
    real disc = b * b - 4.0 * a * c;
    if (disc < 0.0)
        return 0;
    real q = -0.5 * (b + (b < 0.0 ? -sqrt(disc) : sqrt(disc)));
    real s1 = q / a;
    real s2 = q != 0.0 ? c / q : s1;
    r = rvec2(min(s1, s2), max(s1, s2));
    return 2;
}

// Lists of roots are vectors, ascending, padded with NO_HIT at the end;
// x goes in at its place, the last entry falls off. (No vector is indexed
// at run time: lavapipe turns that into slow code.)
rvec4 insert4(rvec4 v, real x)
{
    return min(v, max(rvec4(-NO_HIT, v.xyz), rvec4(x)));
}

rvec3 insert3(rvec3 v, real x)
{
    return min(v, max(rvec3(-NO_HIT, v.xy), rvec3(x)));
}

// The roots in [lo, hi] of the polynomial (c4, c) of degree 3 or 4 whose
// derivative's roots in [lo, hi] are `cuts` (a list as above), to tol.
rvec4 roots_between(real c4, rvec4 c, rvec3 cuts, real lo, real hi, rvec2 tol)
{
    rvec4 roots = rvec4(NO_HIT);
    real a = lo;
    real fa = poly_value(c4, c, a);
    for (int k = 0; k < 4 && a < hi; ++k) {
        real b = min(cuts.x, hi); // the next cut, or the end
        cuts = rvec3(cuts.yz, NO_HIT);
        real fb = poly_value(c4, c, b);
        if (b > a && (fa < 0.0) != (fb < 0.0))
            roots = insert4(roots, fb == 0.0 ? b : bracketed_root(c4, c, a, b, fa, fb, tol));
        a = b;
        fa = fb;
    }
    return roots;
}

// The roots in [lo, hi] of the cubic c.w s^3 + c.z s^2 + c.y s + c.x
// (c.w != 0), to tol.
rvec4 cubic_roots(rvec4 c, real lo, real hi, rvec2 tol)
{
    rvec2 q;
    int nq = quadratic_roots(3.0 * c.w, 2.0 * c.z, c.y, q);
    rvec3 cuts = rvec3(NO_HIT);
    if (nq >= 1 && q.x > lo && q.x < hi)
        cuts = insert3(cuts, q.x);
    if (nq == 2 && q.y > lo && q.y < hi)
        cuts = insert3(cuts, q.y);
    return roots_between(0.0, c, cuts, lo, hi, tol);
}
