// shade.glsl: surface points, pigments and the Phong sum of SPEC 4.

real max_abs(rvec3 p)
{
    rvec3 a = abs(p);
    return max(a.x, max(a.y, a.z));
}

// The hit point moved onto the surface (removing the error of o + t d),
// its outward unit normal, and the size of the numbers that made it (what
// the self-intersection offset scales with).
void surface_point(Object obj, rvec3 o, rvec3 d, real t,
                   out rvec3 p, out rvec3 n, out real scale)
{
    p = o + t * d;
    if (obj.ids.x == TP2_OBJECT_SPHERE) {
        n = normalize(p - obj.geom.xyz);
        p = obj.geom.xyz + obj.geom.w * n;
        scale = max_abs(obj.geom.xyz) + obj.geom.w;
    } else {
        n = obj.geom.xyz;
        p -= (dot(n, p) + obj.geom.w) * n;
        scale = max(max_abs(p), abs(obj.geom.w));
    }
}

vec3 pigment_color(int index, rvec3 p)
{
    Pigment pig = pigments[index];
    if (HAS_CHECKER && pig.kind.x == TP2_PIGMENT_CHECKER) {
        rvec3 cell = floor(p / pig.params.x);
        real k = cell.x + cell.y + cell.z;
        bool even = k - 2.0 * floor(k * 0.5) == 0.0;
        return even ? pig.color1.rgb : pig.color2.rgb;
    }
    return pig.color1.rgb;
}

// max(0, x)^n with 0^0 = 1 as SPEC's formula reads (GLSL's pow(0, y) is
// undefined).
float phong_power(float x, float n)
{
    if (n == 0.0)
        return 1.0;
    return x > 0.0 ? pow(x, n) : 0.0;
}

// Where a surface point's shadow rays start: `origin` (the point lifted
// off the surface on the viewer's side) on the surface `start`.
struct ShadowStart {
    rvec3 origin;
    Start start;
};

// What one point light at `pos` adds at surface point p (normal nf facing
// the viewer, view direction toward the viewer), shadows included.
vec3 light_term(rvec3 pos, vec3 color, vec4 att, Finish fin, vec3 pig,
                rvec3 p, rvec3 nf, rvec3 view, ShadowStart from, inout uint shadow_rays)
{
    rvec3 to_light = pos - p;
    real dist = length(to_light);
    if (dist == 0.0)
        return vec3(0.0);
    rvec3 l = to_light / dist;
    float ndotl = float(dot(nf, l));
    if (ndotl <= 0.0)
        return vec3(0.0);
    rvec3 lo = pos - from.origin;
    real ldist = length(lo);
    ++shadow_rays;
    if (trace_scene(from.origin, lo / ldist, from.start, ldist, true).object >= 0)
        return vec3(0.0);
    float fd = float(dist);
    float a = 1.0 / (att.x + att.y * fd + att.z * fd * fd);
    rvec3 r = 2.0 * dot(nf, l) * nf - l;
    float spec = phong_power(float(dot(r, view)), fin.phong.w);
    return a * color * (fin.phong.y * ndotl * pig + fin.phong.z * spec);
}

// Ambient plus every light at surface point p. The arealight, if any, is
// `area_samples` point lights of color Ci / samples spread over its sphere.
vec3 local_color(Finish fin, vec3 pig, rvec3 p, rvec3 nf, rvec3 view,
                 ShadowStart from, vec2 area_shift, inout uint shadow_rays)
{
    vec3 c = fin.phong.x * frame.ambient.rgb * pig;
    // A finish with kd = ks = 0 (a pure mirror or glass) needs no shadow rays.
    int nl = fin.phong.y == 0.0 && fin.phong.z == 0.0 ? 0 : frame.counts.z;
    for (int i = 0; i < nl; ++i) {
        TP2_STEP();
        Light light = lights[i];
        if (HAS_AREA && i == frame.sampling.y) {
            int n = frame.sampling.z;
            vec3 color = light.color.rgb / float(n);
            for (int j = 0; j < n; ++j) {
                TP2_STEP();
                rvec3 q = light.pos.xyz + real(frame.area.x) * rvec3(sphere_point(j, n, area_shift));
                c += light_term(q, color, light.att, fin, pig, p, nf, view, from, shadow_rays);
            }
        } else {
            c += light_term(light.pos.xyz, light.color.rgb, light.att, fin, pig, p, nf,
                            view, from, shadow_rays);
        }
    }
    return c;
}
