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

real poly_value(real c4, rvec4 c, real s)
{
    return (((c4 * s + c.w) * s + c.z) * s + c.y) * s + c.x;
}

real poly_slope(real c4, rvec4 c, real s)
{
    return ((4.0 * c4 * s + 3.0 * c.w) * s + 2.0 * c.z) * s + c.y;
}

// The root in [a, b] of a polynomial monotone there whose values at a and
// b differ in sign (fa is its value at a).
real bracketed_root(real c4, rvec4 c, real a, real b, real fa)
{
    real x = 0.5 * (a + b);
    for (int step = 0; step < ROOT_STEPS; ++step) {
        TP2_STEP();
        real fx = poly_value(c4, c, x);
        if (fx == 0.0)
            break;
        if ((fx < 0.0) == (fa < 0.0))
            a = x;
        else
            b = x;
        real next = x - fx / poly_slope(c4, c, x);
        if (!(next > a && next < b)) // outside the bracket, or NaN
            next = 0.5 * (a + b);
        if (next == x)
            break;
        x = next;
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

// Where a piece [a, b] of the polynomial ends: the next of the ascending
// cut points cuts[0..n) above a, else b.
real piece_end(rvec3 cuts, int n, int k, real b)
{
    return k < n ? min(cuts[k], b) : b;
}

// The roots in [lo, hi] of the polynomial (c4, c) of degree 3 or 4 whose
// derivative's roots in [lo, hi] are cuts[0..ncuts), ascending.
int roots_between(real c4, rvec4 c, rvec3 cuts, int ncuts, real lo, real hi, out rvec4 roots)
{
    int n = 0;
    roots = rvec4(NO_HIT);
    real a = lo;
    real fa = poly_value(c4, c, a);
    for (int k = 0; k <= ncuts; ++k) {
        TP2_STEP();
        real b = piece_end(cuts, ncuts, k, hi);
        real fb = poly_value(c4, c, b);
        if (b > a && (fa < 0.0) != (fb < 0.0))
            roots[n++] = fb == 0.0 ? b : bracketed_root(c4, c, a, b, fa);
        a = max(a, b);
        fa = fb;
    }
    return n;
}

// The roots in [lo, hi] of the cubic c.w s^3 + c.z s^2 + c.y s + c.x
// (c.w != 0), ascending.
int cubic_roots(rvec4 c, real lo, real hi, out rvec4 roots)
{
    rvec2 q;
    int nq = quadratic_roots(3.0 * c.w, 2.0 * c.z, c.y, q);
    rvec3 cuts = rvec3(NO_HIT);
    int ncuts = 0;
    for (int k = 0; k < nq; ++k)
        if (q[k] > lo && q[k] < hi)
            cuts[ncuts++] = q[k];
    return roots_between(0.0, c, cuts, ncuts, lo, hi, roots);
}
