// pigments.glsl: the color of pigment `index` at point p (SPEC 3). What
// each kind keeps in its record is listed in host/pigments.c.

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
    rvec4 srow = pigments[index].p;
    rvec4 trow = pigments[index].q;
    ivec4 info = pigments[index].kind; // kind, first texel, width, height
    float fx, fy;
    ivec2 x = wrapped_cells(dot(srow.xyz, p) + srow.w, info.z, fx);
    ivec2 y = wrapped_cells(dot(trow.xyz, p) + trow.w, info.w, fy);
    vec3 top = mix(texel(info.y, info.z, x.x, y.x), texel(info.y, info.z, x.y, y.x), fx);
    vec3 bottom = mix(texel(info.y, info.z, x.x, y.y), texel(info.y, info.z, x.y, y.y), fx);
    return mix(top, bottom, fy);
}

vec3 pigment_color(int index, rvec3 p)
{
    int kind = pigments[index].kind.x;
    if (USES_PIGMENT(TP2_PIGMENT_CHECKER) && kind == TP2_PIGMENT_CHECKER) {
        rvec3 cell = floor(p / pigments[index].p.x);
        real k = cell.x + cell.y + cell.z;
        bool even = k - 2.0 * floor(k * 0.5) == 0.0;
        return even ? pigments[index].color1.rgb : pigments[index].color2.rgb;
    }
    if (USES_PIGMENT(TP2_PIGMENT_GRADIENT) && kind == TP2_PIGMENT_GRADIENT) {
        float f = clamp(float(dot(p - pigments[index].p.xyz, pigments[index].q.xyz)), 0.0, 1.0);
        return mix(pigments[index].color1.rgb, pigments[index].color2.rgb, f);
    }
    if (USES_PIGMENT(TP2_PIGMENT_TEXMAP) && kind == TP2_PIGMENT_TEXMAP)
        return texmap_color(index, p);
    return pigments[index].color1.rgb;
}
