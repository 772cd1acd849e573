#version 450
// trace.comp: Whitted ray tracing of one pixel per invocation (SPEC 4).
//
// Recursion is replaced by a depth-first walk over an explicit stack of
// pending rays, each with the weight (product of kr / kt) it contributes
// with. Built twice: TP2_DOUBLE selects double-precision geometry (the
// reference image); lighting stays in float either way.
#extension GL_GOOGLE_include_directive : require

#include "tp2_shared.h"

#ifdef TP2_DOUBLE
#define real double
#define rvec3 dvec3
#define rvec4 dvec4
// Self-intersection offset, relative to the scale of the hit point.
#define TP2_REL_EPS 1e-11LF
#else
#define real float
#define rvec3 vec3
#define rvec4 vec4
#define TP2_REL_EPS 1.52587890625e-5 // 2^-16, about 256 float ulps
#endif

#include "layout.glsl"

layout(local_size_x = TP2_GROUP_X, local_size_y = TP2_GROUP_Y) in;

const float BIG = 3.0e38;

struct Hit {
    real t;
    int object; // -1: none
};

// Nearest t > 0 where the ray meets sphere (center c, radius r), or -1.
// The discriminant is formed from the ray's closest approach to the center
// rather than b^2 - c, which cancels catastrophically for far-away spheres.
real hit_sphere(rvec3 o, rvec3 d, rvec3 c, real r)
{
    rvec3 oc = o - c;
    real b = dot(oc, d);
    rvec3 closest = oc - b * d;
    real disc = r * r - dot(closest, closest);
    if (disc < 0.0)
        return real(-1.0);
    real q = -b - (b < 0.0 ? real(-1.0) : real(1.0)) * sqrt(disc);
    real c0 = dot(oc, oc) - r * r;
    // Roots are c0 / q and q (d is unit length); pick the nearer positive.
    real t0 = q != 0.0 ? c0 / q : real(0.0);
    real t1 = q;
    real near_t = min(t0, t1);
    real far_t = max(t0, t1);
    if (near_t > 0.0)
        return near_t;
    if (far_t > 0.0)
        return far_t;
    return real(-1.0);
}

// t > 0 where the ray meets the plane n.x + dist = 0, or -1.
real hit_plane(rvec3 o, rvec3 d, rvec3 n, real dist)
{
    real denom = dot(n, d);
    if (denom == 0.0)
        return real(-1.0);
    real t = -(dot(n, o) + dist) / denom;
    return t > 0.0 ? t : real(-1.0);
}

real hit_object(int i, rvec3 o, rvec3 d)
{
    Object obj = objects[i];
    if (obj.ids.x == TP2_OBJECT_SPHERE)
        return hit_sphere(o, d, obj.geom.xyz, obj.geom.w);
    return hit_plane(o, d, obj.geom.xyz, obj.geom.w);
}

Hit nearest_hit(rvec3 o, rvec3 d)
{
    Hit h = Hit(real(BIG), -1);
    int n = frame.counts.w;
    for (int i = 0; i < n; ++i) {
        real t = hit_object(i, o, d);
        if (t > 0.0 && t < h.t) {
            h.t = t;
            h.object = i;
        }
    }
    return h;
}

// True if any object crosses the open segment from o to o + dist * d.
bool occluded(rvec3 o, rvec3 d, real dist)
{
    int n = frame.counts.w;
    for (int i = 0; i < n; ++i) {
        real t = hit_object(i, o, d);
        if (t > 0.0 && t < dist)
            return true;
    }
    return false;
}

real max_abs(rvec3 p)
{
    rvec3 a = abs(p);
    return max(a.x, max(a.y, a.z));
}

// The hit point moved onto the surface (removing the error of o + t d) and
// its outward unit normal; scale is the size of the numbers involved.
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
    if (pig.kind.x == TP2_PIGMENT_CHECKER) {
        rvec3 cell = floor(p / pig.params.x);
        real k = cell.x + cell.y + cell.z;
        bool even = k - 2.0 * floor(k * 0.5) == 0.0;
        return even ? pig.color1.rgb : pig.color2.rgb;
    }
    return pig.color1.rgb;
}

// max(0, x)^n with 0^0 = 1, as SPEC's formula reads (GLSL's pow(0, y) is
// undefined).
float phong_power(float x, float n)
{
    if (n == 0.0)
        return 1.0;
    return x > 0.0 ? pow(x, n) : 0.0;
}

// Ambient plus every visible point light at surface point p.
vec3 local_color(Finish fin, vec3 pig, rvec3 p, rvec3 nf, rvec3 view,
                 rvec3 origin)
{
    vec3 c = fin.phong.x * frame.ambient.rgb * pig;
    int nl = frame.counts.z;
    for (int i = 0; i < nl; ++i) {
        Light light = lights[i];
        rvec3 to_light = light.pos.xyz - p;
        real dist = length(to_light);
        if (dist == 0.0)
            continue;
        rvec3 l = to_light / dist;
        float ndotl = float(dot(nf, l));
        if (ndotl <= 0.0)
            continue;
        rvec3 lo = light.pos.xyz - origin;
        real ldist = length(lo);
        if (occluded(origin, lo / ldist, ldist))
            continue;
        float fd = float(dist);
        float att = 1.0 / (light.att.x + light.att.y * fd + light.att.z * fd * fd);
        rvec3 r = 2.0 * dot(nf, l) * nf - l;
        float spec = phong_power(float(dot(r, view)), fin.phong.w);
        c += att * light.color.rgb * (fin.phong.y * ndotl * pig + fin.phong.z * spec);
    }
    return c;
}

struct Ray {
    rvec3 origin;
    rvec3 dir;
    float weight;
    int depth;
};

vec3 trace(rvec3 eye, rvec3 dir)
{
    Ray stack[TP2_STACK_SIZE];
    int sp = 0;
    stack[sp++] = Ray(eye, dir, 1.0, 0);
    vec3 color = vec3(0.0);
    vec3 gray = frame.background.rgb;

    for (int iter = 0; iter < TP2_MAX_RAYS && sp > 0; ++iter) {
        Ray ray = stack[--sp];
        Hit h = nearest_hit(ray.origin, ray.dir);
        if (h.object < 0) {
            color += ray.weight * gray;
            continue;
        }
        Object obj = objects[h.object];
        rvec3 p, n;
        real scale;
        surface_point(obj, ray.origin, ray.dir, h.t, p, n, scale);
        bool entering = dot(ray.dir, n) < 0.0;
        rvec3 nf = entering ? n : -n;
        rvec3 offset = nf * (scale * TP2_REL_EPS);
        rvec3 outside = p + offset; // start of rays leaving on the ray's side

        Finish fin = finishes[obj.ids.z];
        vec3 pig = pigment_color(obj.ids.y, p);
        color += ray.weight * local_color(fin, pig, p, nf, -ray.dir, outside);

        float kr = fin.optics.x;
        float kt = fin.optics.y;
        int depth = ray.depth + 1;
        if (depth > TP2_MAX_DEPTH) { // children past the limit are gray
            color += ray.weight * (max(kr, 0.0) + max(kt, 0.0)) * gray;
            continue;
        }
        if (kr > 0.0 && sp < TP2_STACK_SIZE) {
            rvec3 r = ray.dir - 2.0 * dot(ray.dir, nf) * nf;
            stack[sp++] = Ray(outside, r, ray.weight * kr, depth);
        }
        if (kt > 0.0 && sp < TP2_STACK_SIZE) {
            real eta = entering ? real(1.0) / real(fin.optics.z) : real(fin.optics.z);
            real cosi = -dot(ray.dir, nf);
            real k = 1.0 - eta * eta * (1.0 - cosi * cosi);
            Ray t;
            if (k < 0.0) { // total internal reflection: the mirror direction
                t = Ray(outside, ray.dir + 2.0 * cosi * nf, ray.weight * kt, depth);
            } else {
                rvec3 dir_t = normalize(eta * ray.dir + (eta * cosi - sqrt(k)) * nf);
                t = Ray(p - offset, dir_t, ray.weight * kt, depth);
            }
            stack[sp++] = t;
        }
    }
    return color;
}

void main()
{
    ivec2 pixel = tile_origin + ivec2(gl_GlobalInvocationID.xy);
    int width = frame.counts.x;
    int height = frame.counts.y;
    if (pixel.x >= width || pixel.y >= height)
        return;
    real x = (2.0 * (real(pixel.x) + 0.5)) / real(width) - 1.0;
    real y = 1.0 - (2.0 * (real(pixel.y) + 0.5)) / real(height);
    rvec3 dir = normalize(frame.w.xyz + x * frame.u.xyz + y * frame.v.xyz);
    vec3 c = trace(frame.eye.xyz, dir);
    pixels[pixel.y * width + pixel.x] = vec4(c, 1.0);
}
