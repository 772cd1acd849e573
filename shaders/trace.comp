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

// A pixel sample's walk through its ray tree: it follows each ray's first
// child at once and parks the second, so the stack is only touched where
// the tree branches. Global, so that passes can save and resume it.
Ray walk_ray;                    // the ray to trace next, if live
Ray walk_pending[STACK_SIZE];    // rays parked
int walk_sp;                     // how many
int walk_traced;                 // rays traced so far
bool walk_live;
vec3 walk_color;                 // what the rays traced so far add
float walk_budget;               // pruning budget left (see traced())

void walk_start(rvec3 eye, rvec3 dir)
{
    walk_ray = Ray(eye, dir, NOWHERE, 1.0, 0);
    walk_sp = 0;
    walk_traced = 0;
    walk_live = true;
    walk_color = vec3(0.0);
    walk_budget = 0.5 * frame.limits.x;
}

// Traces at most `rays` more rays of the walk.
void walk_on(int rays, vec2 area_shift)
{
    for (int i = 0; i < rays && walk_live && walk_traced < MAX_RAYS; ++i) {
        Ray first, second;
        int children = trace_step(walk_ray, area_shift, walk_color, walk_budget, first, second);
        ++walk_traced;
        if (children == 2 && walk_sp < STACK_SIZE)
            walk_pending[walk_sp++] = second;
        if (children > 0)
            walk_ray = first;
        else if (walk_sp > 0)
            walk_ray = walk_pending[--walk_sp];
        else
            walk_live = false;
    }
    if (walk_traced >= MAX_RAYS) // cannot happen: a full tree has MAX_RAYS rays
        walk_live = false;
}

WalkRay packed_ray(Ray r)
{
    return WalkRay(rvec4(r.origin, r.weight), rvec4(r.dir, 0.0),
                   ivec4(r.start.object, int(r.start.inward), r.depth, 0));
}

Ray unpacked_ray(WalkRay w)
{
    return Ray(w.origin.xyz, w.dir.xyz, Start(w.info.x, w.info.y != 0), float(w.origin.w),
               w.info.z);
}

void walk_save(int entry, ivec2 pixel)
{
    walks[entry] = Walk(ivec4(pixel, walk_sp, walk_traced), vec4(walk_color, walk_budget));
    int base = entry * TP2_WALK_RAYS;
    saved_rays[base] = packed_ray(walk_ray);
    for (int k = 0; k < walk_sp; ++k)
        saved_rays[base + 1 + k] = packed_ray(walk_pending[k]);
}

// Resumes saved walk `entry`; its pixel.
ivec2 walk_load(int entry)
{
    Walk w = walks[entry];
    walk_sp = w.where.z;
    walk_traced = w.where.w;
    walk_live = true;
    walk_color = w.color.rgb;
    walk_budget = w.color.a;
    int base = entry * TP2_WALK_RAYS;
    walk_ray = unpacked_ray(saved_rays[base]);
    for (int k = 0; k < walk_sp; ++k)
        walk_pending[k] = unpacked_ray(saved_rays[base + 1 + k]);
    return w.where.xy;
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

// Whether lavapipe cut this invocation short (see TP2_CANARY_STEPS).
bool was_cut()
{
    int canary = 0;
    for (int k = 0; k < frame.sampling.w; ++k)
        ++canary;
    return canary != frame.sampling.w;
}

// Adds this invocation's rays to the stats (64-bit counters from 32-bit
// atomics: a carry goes into the high word).
void count_rays()
{
    for (int i = 0; i < TP2_STAT_COUNT; ++i) {
        uint before = atomicAdd(ray_counts[2 * i], ray_tally[i]);
        if (before + ray_tally[i] < before)
            atomicAdd(ray_counts[2 * i + 1], 1u);
    }
}

// One pixel sample, or one saved walk, for one pass (TP2_PASS_*): its walk
// goes on for pass_rays rays; if it finishes, the sample's share is added
// to its pixel, else it is saved for the next pass. An invocation that
// lavapipe cut short writes nothing (its pass runs again with fewer rays).
void main()
{
    int width = frame.counts.x;
    int height = frame.counts.y;
    for (int i = 0; i < TP2_STAT_COUNT; ++i)
        ray_tally[i] = 0u;
    int s = sample_index;
    ivec2 pixel;
    int entry = -1; // the saved walk this invocation goes on with
    if (pass_kind == TP2_PASS_CONTINUE) {
        entry = int(gl_WorkGroupID.x) * (TP2_GROUP_X * TP2_GROUP_Y) + int(gl_LocalInvocationIndex);
        if (entry >= min(int(counters[TP2_COUNTER_WALKS]), walk_capacity) ||
            walks[entry].where.z < 0)
            return;
        pixel = walk_load(entry);
    } else {
        pixel = tile_origin + ivec2(gl_GlobalInvocationID.xy);
        if (pixel.x >= width || pixel.y >= height)
            return;
        if (LOOP_GUARD && started[int(gl_GlobalInvocationID.y) * width + pixel.x] != 0u)
            return;
        // Sample s of SAMPLES: the pixel center when there is one, else
        // stratified in the pixel. Each adds its share to the pixel.
        vec2 offset = SAMPLES == 1 ? vec2(0.5) : lattice2(s, SAMPLES, frame.sampling.x, random2(pixel, 0u));
        real x = (2.0 * (real(pixel.x) + real(offset.x))) / real(width) - 1.0;
        real y = 1.0 - (2.0 * (real(pixel.y) + real(offset.y))) / real(height);
        rvec3 origin, dir;
        camera_ray(x, y, random2(pixel, uint(2 * s + 1)), origin, dir);
        walk_start(origin, dir);
        ray_tally[TP2_STAT_CAMERA] = 1u;
    }
    walk_on(pass_rays, random2(pixel, uint(2 * s + 2)));

    bool cut = LOOP_GUARD && was_cut();
    if (cut) {
        atomicAdd(counters[TP2_COUNTER_CUT], 1u);
        if (accept_cut == 0)
            return;
        atomicAdd(counters[TP2_COUNTER_LOST], 1u);
        walk_live = false; // what there is, wrong: tp2 says so
    }
    // pixels[] holds one band of whole rows, from row tile_origin.y on.
    int index = (pixel.y - tile_origin.y) * width + pixel.x;
    if (!walk_live) {
        vec3 share = walk_color / float(SAMPLES);
        pixels[index] = vec4((s == 0 ? vec3(0.0) : pixels[index].rgb) + share, 1.0);
        if (entry >= 0)
            walks[entry].where.z = -1;
        else if (LOOP_GUARD)
            started[index] = 1u;
    } else {
        if (entry < 0) {
            entry = int(atomicAdd(counters[TP2_COUNTER_WALKS], 1u));
            if (entry >= walk_capacity) { // no room: it starts again later
                atomicAdd(counters[TP2_COUNTER_WAITING], 1u);
                return;
            }
            started[index] = 1u;
        }
        walk_save(entry, pixel);
        atomicAdd(counters[TP2_COUNTER_UNFINISHED], 1u);
    }
    if (COUNT_RAYS)
        count_rays();
}
