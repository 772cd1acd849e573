#version 450
// trace.comp: Whitted ray tracing of one pixel per invocation (SPEC 4).
//
// Recursion is replaced by a depth-first walk: the loop follows each ray's
// first child and parks the second on an explicit stack; every ray carries
// the weight (product of kr, kt and fog transmittance) it contributes
// with. Built twice: TP2_DOUBLE selects
// double-precision geometry (the reference image); lighting stays in float.
// Specialization constants (layout.glsl) strip what the scene does not use.
#extension GL_GOOGLE_include_directive : require

#include "tp2_shared.h"

// TP2_REL_EPS: offset of a new ray's origin off its surface, relative to
// the scale of the hit point: 16 ulps, against coincident surfaces
// (self-hits are ruled out by Start, not by this).
#ifdef TP2_DOUBLE
#define real double
#define rvec2 dvec2
#define rvec3 dvec3
#define rvec4 dvec4
#define TP2_REL_EPS 5.6843418860808015e-14LF // 2^-44
#else
#define real float
#define rvec2 vec2
#define rvec3 vec3
#define rvec4 vec4
#define TP2_REL_EPS 9.5367431640625e-7 // 2^-20
#endif

#include "layout.glsl"
#include "random.glsl"
#include "intersect.glsl"
#include "pigments.glsl"
#include "shade.glsl"

layout(local_size_x = TP2_GROUP_X, local_size_y = TP2_GROUP_Y) in;

// How many children a ray can have, and so how big the walk gets: with
// both kinds a full binary tree of depth TP2_MAX_DEPTH, with one a chain.
const int BRANCHES = int(HAS_REFLECT) + int(HAS_REFRACT);
const int MAX_RAYS = BRANCHES == 2 ? TP2_MAX_RAYS : BRANCHES == 1 ? TP2_MAX_DEPTH + 1 : 1;
const int STACK_SIZE = BRANCHES == 2 ? TP2_STACK_SIZE : 1;

struct Ray {
    rvec3 origin;
    rvec3 dir;
    Start start;
    float weight;
    int depth;
};

uint ray_tally[TP2_STAT_COUNT]; // this invocation's rays, by kind

// Pruning with a bounded error: a child ray fainter than the bailout is
// not traced, but only while the weights of the rays a sample has pruned
// so far add up to at most half the bailout (`budget` is what is left).
// What a pruned ray would have added is its weight times the radiance it
// brings back, so a sample's error is at most bailout / 2 times the
// largest such radiance: half an 8-bit level for the default 1/255 where
// radiance is within [0, 1]. Without the budget, a deep tree prunes
// thousands of faint rays whose weights add up to whole levels.
bool traced(float w, inout float budget)
{
    if (w >= frame.limits.x || w > budget)
        return true;
    budget -= w;
    return false;
}

// Traces one ray: adds what it sees to color and returns how many
// children it spawns (0 to 2), the first in `first`, the other in `second`.
//
// Query 0 is the ray itself; queries 1.. are its hit's shadow rays, one
// per light sample. One call of trace_scene serves them all, so the
// intersection code of every kind is compiled once: drivers inline each
// call, and compile time grows with the copies.
int trace_step(Ray ray, vec2 area_shift, inout vec3 color, inout float budget, out Ray first,
               out Ray second)
{
    first = second = ray;
    vec3 gray = frame.background.rgb;
    float weight = ray.weight;
    Hit h;
    Shading sh;
    rvec3 n;
    bool entering;
    rvec3 offset;
    vec3 local = vec3(0.0);
    int queries = 1;
    for (int q = 0; q < queries; ++q) {
        rvec3 o = ray.origin;
        rvec3 d = ray.dir;
        real tmax = NO_HIT;
        Start start = ray.start;
        vec3 lit = vec3(0.0);
        if (q > 0) {
            if (!light_ray(sh, q - 1, area_shift, d, tmax, lit))
                continue;
            o = sh.origin;
            start = sh.start;
            ++ray_tally[TP2_STAT_SHADOW];
        }
        Hit found = trace_scene(o, d, start, tmax, q > 0);
        if (q > 0) {
            if (found.object < 0)
                local += lit;
            continue;
        }
        h = found;
        if (h.object < 0) {
            color += weight * (HAS_FOG ? frame.fog.rgb : gray);
            return 0;
        }
        if (HAS_FOG) { // SPEC 3: the segment keeps exp(-density t) of its color
            float keep = exp(-frame.fog.w * float(h.t));
            color += weight * (1.0 - keep) * frame.fog.rgb;
            weight *= keep;
        }
        real scale;
        surface_point(h.object, h.part, ray.origin, ray.dir, h.t, sh.p, n, scale);
        entering = dot(ray.dir, n) < 0.0;
        sh.nf = entering ? n : -n;
        sh.view = -ray.dir;
        offset = sh.nf * (scale * TP2_REL_EPS);
        // Rays leaving on the incoming side start here, going along nf:
        // into the object when the ray came from inside.
        sh.origin = sh.p + offset;
        sh.start = Start(h.object, !entering);
        ivec4 ids = objects[h.object].ids;
        sh.fin = finishes[ids.z];
        sh.pig = pigment_color(ids.y, sh.p);
        local = sh.fin.phong.x * frame.ambient.rgb * sh.pig;
        queries = 1 + light_samples(sh.fin);
    }
    color += weight * local;
    rvec3 p = sh.p;
    rvec3 nf = sh.nf;
    rvec3 outside = sh.origin;
    Start back = sh.start;
    Finish fin = sh.fin;

    float kr = HAS_REFLECT ? fin.optics.x : 0.0;
    float kt = HAS_REFRACT ? fin.optics.y : 0.0;
    int depth = ray.depth + 1;
    if (depth > TP2_MAX_DEPTH) { // children past the limit are plain gray
        color += weight * (max(kr, 0.0) + max(kt, 0.0)) * gray;
        return 0;
    }
    int children = 0;
    if (kr > 0.0 && traced(weight * kr, budget)) {
        rvec3 r = ray.dir - 2.0 * dot(ray.dir, nf) * nf;
        first = Ray(outside, r, back, weight * kr, depth);
        ++children;
        ++ray_tally[TP2_STAT_REFLECTED];
    }
    if (kt > 0.0 && traced(weight * kt, budget)) {
        real eta = entering ? real(1.0) / real(fin.optics.z) : real(fin.optics.z);
        real cosi = -dot(ray.dir, nf);
        real k = 1.0 - eta * eta * (1.0 - cosi * cosi);
        Ray t;
        if (!has_inside(h.object)) { // SPEC 3: through a triangle unbent
            t = Ray(p - offset, ray.dir, Start(h.object, entering), weight * kt, depth);
        } else if (k < 0.0) { // total internal reflection: the mirror direction
            t = Ray(outside, ray.dir + 2.0 * cosi * nf, back, weight * kt, depth);
        } else {
            rvec3 dir_t = normalize(eta * ray.dir + (eta * cosi - sqrt(k)) * nf);
            t = Ray(p - offset, dir_t, Start(h.object, entering), weight * kt, depth);
        }
        if (children == 0)
            first = t;
        else
            second = t;
        ++children;
        ++ray_tally[TP2_STAT_TRANSMITTED];
    }
    return children;
}

// The color seen along a camera ray. The walk follows each ray's first
// child at once and parks the second on the stack, so the stack is only
// touched where the tree branches.
vec3 trace(rvec3 eye, rvec3 dir, vec2 area_shift)
{
    Ray pending[STACK_SIZE];
    int sp = 0;
    Ray ray = Ray(eye, dir, NOWHERE, 1.0, 0);
    bool live = true; // `ray` is still to be traced
    vec3 color = vec3(0.0);
    float budget = 0.5 * frame.limits.x; // pruned weight this sample may drop
    for (int iter = 0; iter < MAX_RAYS && live; ++iter) {
        Ray first, second;
        int children = trace_step(ray, area_shift, color, budget, first, second);
        if (children == 2 && sp < STACK_SIZE)
            pending[sp++] = second;
        if (children > 0)
            ray = first;
        else if (sp > 0)
            ray = pending[--sp];
        else
            live = false;
    }
    return color;
}

// The camera ray through image-plane position (x, y) in [-1, 1]^2, through
// a lens point when the scene has a lens (SPEC 3: thin lens, focal plane).
void camera_ray(real x, real y, vec2 lens_sample, out rvec3 origin, out rvec3 dir)
{
    dir = normalize(frame.w.xyz + x * frame.u.xyz + y * frame.v.xyz);
    origin = frame.eye.xyz;
    if (HAS_LENS && frame.lens.x > 0.0) {
        rvec3 focus = origin + dir * (real(frame.lens.y) / dot(dir, frame.w.xyz));
        vec2 disk = float(frame.lens.x) * square_to_disk(lens_sample);
        origin += disk.x * normalize(frame.u.xyz) + disk.y * normalize(frame.v.xyz);
        dir = normalize(focus - origin);
    }
}

void main()
{
    ivec2 pixel = tile_origin + ivec2(gl_GlobalInvocationID.xy);
    int width = frame.counts.x;
    int height = frame.counts.y;
    if (pixel.x >= width || pixel.y >= height)
        return;
    for (int i = 0; i < TP2_STAT_COUNT; ++i)
        ray_tally[i] = 0u;

    // Sample sample_index of SAMPLES: the pixel center when there is one,
    // else stratified in the pixel. Each adds its share to the pixel.
    int s = sample_index;
    vec2 offset = SAMPLES == 1 ? vec2(0.5) : lattice2(s, SAMPLES, frame.sampling.x, random2(pixel, 0u));
    real x = (2.0 * (real(pixel.x) + real(offset.x))) / real(width) - 1.0;
    real y = 1.0 - (2.0 * (real(pixel.y) + real(offset.y))) / real(height);
    rvec3 origin, dir;
    camera_ray(x, y, random2(pixel, uint(2 * s + 1)), origin, dir);
    vec3 share = trace(origin, dir, random2(pixel, uint(2 * s + 2))) / float(SAMPLES);
    // pixels[] holds one band of whole rows, from row tile_origin.y on.
    int index = int(gl_GlobalInvocationID.y) * width + pixel.x;
    pixels[index] = vec4((s == 0 ? vec3(0.0) : pixels[index].rgb) + share, 1.0);
    ray_tally[TP2_STAT_CAMERA] = 1u;

    if (LOOP_GUARD) { // see TP2_CANARY_STEPS
        int canary = 0;
        for (int k = 0; k < frame.sampling.w; ++k)
            ++canary;
        if (canary != frame.sampling.w)
            atomicAdd(cut_short, 1u);
    }
    if (COUNT_RAYS)
        for (int i = 0; i < TP2_STAT_COUNT; ++i) {
            // 64-bit counters from 32-bit atomics: carry into the high word.
            uint before = atomicAdd(ray_counts[2 * i], ray_tally[i]);
            if (before + ray_tally[i] < before)
                atomicAdd(ray_counts[2 * i + 1], 1u);
        }
}
