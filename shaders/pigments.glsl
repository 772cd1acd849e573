// pigments.glsl: the color of pigment `index` at point p (SPEC 3). What
// each kind keeps in its record is listed in host/scene/pigments.c.

// Texel (x, y) of the texture whose first texel is `first`.
vec3 texel(int first, int width, int x, int y)
{
    uint w = texels[first + y * width + x];
    return vec3(float(w & 255u), float((w >> 8) & 255u), float(w >> 16)) / 255.0;
}

// Cells of side `size` along coordinate x, and where x sits between the
// centers of the cells either side of it: texel centers lie at (i + 0.5)
// / size, and the texture repeats, so cell -1 is cell size - 1 (a t of
// exactly 0 blends the first and last rows half and half).
ivec2 wrapped_cells(real s, int size, out float weight)
{
    real x = fract(s) * real(size) - 0.5;
    real cell = floor(x);
    weight = float(x - cell);
    int c0 = int(cell);
    int c1 = c0 + 1;
    return ivec2(c0 < 0 ? c0 + size : c0, c1 >= size ? c1 - size : c1);
}

// s = p.(s row), t = p.(t row) looked up with bilinear filtering.
vec3 texmap_color(int index, rvec3 p)
{
    rvec4 srow = pigment_p(index);
    rvec4 trow = pigment_q(index);
    ivec4 info = pigment_kind(index); // kind, first texel, width, height
    float fx, fy;
    ivec2 x = wrapped_cells(rdot(srow.xyz, p) + srow.w, info.z, fx);
    ivec2 y = wrapped_cells(rdot(trow.xyz, p) + trow.w, info.w, fy);
    vec3 top = mix(texel(info.y, info.z, x.x, y.x), texel(info.y, info.z, x.y, y.x), fx);
    vec3 bottom = mix(texel(info.y, info.z, x.x, y.y), texel(info.y, info.z, x.y, y.y), fx);
    return mix(top, bottom, fy);
}

// Whether x = (p + o) / size is that quotient without rounding: the sum's
// rounding error (TwoSum) and x size's (Dekker's product, since fma need
// not be fused on every device) are 0, and x size is the sum. `precise`
// keeps compilers from reassociating or contracting them.
#ifdef TP2_DOUBLE
const real SPLIT = 134217729.0LF; // 2^27 + 1: halves of a double's digits
#else
const real SPLIT = 4097.0; // 2^12 + 1: halves of a float's digits
#endif
bool exact_quotient(real p, real o, real size, real x)
{
    precise real sum = p + o;
    precise real o_part = sum - p;
    precise real p_part = sum - o_part;
    precise real sum_error = (p - p_part) + (o - o_part);
    precise real xs = x * SPLIT;
    precise real x_hi = xs - (xs - x);
    precise real x_lo = x - x_hi;
    precise real ss = size * SPLIT;
    precise real s_hi = ss - (ss - size);
    precise real s_lo = size - s_hi;
    precise real product = x * size;
    precise real product_error =
        ((x_hi * s_hi - product) + x_hi * s_lo + x_lo * s_hi) + x_lo * s_lo;
    return sum_error == 0.0 && product_error == 0.0 && product == sum;
}

// Whether p, which may be off by `doubt` along object's surface of normal
// nf, may lie in another checker cell (signature.glsl): nearer a cell face
// than that (a doubt of 0: none); x = (p + o) / size, cell = floor(x).
// A flat face along a cell face (nf an axis, p exactly on it) lies there
// in both precisions where float's numbers are double's (the face's,
// same_in_float; the side's, pigment_q.x, unless x is 0) and float
// computed x without rounding. Counting any x that came out whole (as an
// earlier build did) let a face at 0.3 under cells of 0.1 (3 in float,
// 2.9999999999999996 in double), or one 8571.0307 from 0 under cells of
// 0.03 (x rounded to 1/32 of a cell there), flipped whole faces. A curved
// face does not count, though its normal may round to an axis: a
// sphere's top touching a cell face (../shared/corpus/test05.txt's floor,
// radius 100) has float's hits there exactly on the face, double's a few
// millionths below it.
bool unsure_cell(rvec3 p, rvec3 o, real size, int pigment, rvec3 x, rvec3 cell, rvec3 nf,
                 int object, float doubt)
{
    vec3 f = vec3(x - cell);
    vec3 margin = min(f, 1.0 - f) * float(size);
    bvec3 axis = equal(abs(vec3(nf)), vec3(1.0));
    for (int k = 0; k < 3; ++k) {
        if (!(margin[k] < doubt))
            continue;
        if (!(axis[k] && f[k] == 0.0 && flat_kind(object)))
            return true;
        // Rare: loaded only here.
        if (!(same_in_float(object) && (x[k] == 0.0 || pigment_q(pigment).x == 1.0) &&
              exact_quotient(p[k], o[k], size, x[k])))
            return true;
    }
    return false;
}

// How fast pigment `index`'s color may change along a surface: color
// units per unit of length, the most of any channel (each kind's slope
// in host/scene/pigments.c; 0 for solids and checkers). A hit point off by d
// along the surface has its color off by up to d times this.
float pigment_slope(int index)
{
    return pigment_color1(index).w;
}

// The color of pigment `index` at p on object's surface (doubt: see
// unsure_cell); a checker's cell is a decision (signature.glsl), the other
// kinds vary smoothly.
vec3 pigment_color(int index, rvec3 p, rvec3 nf, int object, float doubt, inout uint sig)
{
    int kind = pigment_kind(index).x;
    if (USES_PIGMENT(TP2_PIGMENT_CHECKER) && kind == TP2_PIGMENT_CHECKER) {
        // Cells are the scene's: yzw is where the packed origin lies in it
        // (0 unless the scene was moved; host/scene/pigments.c), and adding it
        // rounds by a share of its size.
        rvec4 cube = pigment_p(index);
        real size = cube.x;
        rvec3 x = (p + cube.yzw) / size;
        rvec3 cell = floor(x);
        real k = cell.x + cell.y + cell.z;
        bool even = k - 2.0 * floor(k * 0.5) == 0.0;
        float moved = ROUNDING * float(max_abs(cube.yzw));
        if (SIGNATURES && doubt > 0.0 &&
            unsure_cell(p, cube.yzw, size, index, x, cell, nf, object, doubt + moved))
            sig |= UNSURE;
        return even ? pigment_color1(index).rgb : pigment_color2(index).rgb;
    }
    if (USES_PIGMENT(TP2_PIGMENT_GRADIENT) && kind == TP2_PIGMENT_GRADIENT) {
        float f = clamp(float(rdot(p - pigment_p(index).xyz, pigment_q(index).xyz)), 0.0, 1.0);
        return mix(pigment_color1(index).rgb, pigment_color2(index).rgb, f);
    }
    if (USES_PIGMENT(TP2_PIGMENT_TEXMAP) && kind == TP2_PIGMENT_TEXMAP)
        return texmap_color(index, p);
    return pigment_color1(index).rgb;
}
