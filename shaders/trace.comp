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
#extension GL_EXT_samplerless_texture_functions : require // texelFetch of a utextureBuffer

#include "tp2_shared.h"
#include "kinds.h"

#include "real.glsl"
#include "layout.glsl"
#include "signature.glsl"
#include "random.glsl"
#include "intersect.glsl"
#include "pigments.glsl"
#include "shade.glsl"
#ifdef TP2_DOUBLE
#include "soft_double_keep.glsl"
#endif

layout(local_size_x = TP2_GROUP_X, local_size_y = TP2_GROUP_Y) in;

// How many children a ray can have, and so how big the walk gets: with
// both kinds a full binary tree of depth TP2_MAX_DEPTH, with one a chain.
const int BRANCHES = int(HAS_REFLECT) + int(HAS_REFRACT);
const int MAX_RAYS = BRANCHES == 2 ? TP2_MAX_RAYS : BRANCHES == 1 ? TP2_MAX_DEPTH + 1 : 1;
const int STACK_SIZE = BRANCHES == 2 ? TP2_STACK_SIZE : 1;
// Pigments whose color varies smoothly, so that a hit point's doubt is a
// doubt about its color (under SIGNATURES).
const bool SMOOTH_PIGMENTS = SIGNATURES && (USES_PIGMENT(TP2_PIGMENT_TEXMAP) ||
                                            USES_PIGMENT(TP2_PIGMENT_GRADIENT));

struct Ray {
    rvec3 origin;
    rvec3 dir;
    Start start;
    float weight;
    int depth;
};

uint ray_tally[TP2_STAT_COUNT]; // this invocation's rays, by kind

// Pruning with a bounded error: a child ray fainter than the bailout W is
// not traced, but only while the weights of the rays a sample has pruned
// so far add up to at most W (`budget` is what is left). A pruned ray adds
// its weight times 0.5, the middle of [0, 1], in place of the radiance it
// would bring back; where radiance is within [0, 1] each such guess is off
// by at most half its weight, so a sample's error is at most W / 2: half
// an 8-bit level for the default 1/255 (docs/accuracy.md). Without the
// budget, a deep tree prunes thousands of faint rays whose weights add up
// to whole levels; without the guess, the same bound allows half the
// budget, and more rays are traced.
bool traced(float w, inout float budget, inout vec3 color)
{
    if (w >= frame.limits.x || w > budget)
        return true;
    budget -= w;
    color += w * 0.5;
    return false;
}

// Traces one ray: adds what it sees to color, its decisions to sig, and
// returns how many children it spawns (0 to 2), the first in `first`, the
// other in `second`. Under SIGNATURES, `doubt` is the ray's (signature.glsl)
// and the children's come out in first_doubt and second_doubt; otherwise
// all of that compiles out (it lives apart from Ray so that the walk's
// stack of rays does not carry it).
// (trace_scene is called twice, for the ray and for shadow rays: each call
// is inlined whole, which costs compile time, but one call serving both
// was 25% slower on lavapipe.)
int trace_step(Ray ray, vec4 doubt, vec2 area_shift, inout vec3 color, inout float budget,
               inout uint sig, out Ray first, out Ray second, out vec4 first_doubt,
               out vec4 second_doubt)
{
    first = second = ray;
    first_doubt = second_doubt = doubt;
    vec3 gray = frame.background.rgb;
    float weight = ray.weight;
    float stake = weight / float(SAMPLES); // what a flip here can change
    Hit h = trace_scene(ray.origin, ray.dir, ray.start, NO_HIT, false, -1,
                        edge_doubt(doubt, stake));
    decided(sig, uint(h.object));
    if (h.object < 0) { // boundaries beyond move with the direction (signature.glsl)
        edges_seen(sig, h.edge, float(h.t), 0.0);
        seen(sig, far_pixels(doubt), own_far_pixels(doubt), stake);
        color += weight * (HAS_FOG ? frame.fog.rgb : gray);
        return 0;
    }
    if (HAS_FOG) { // SPEC 3: the segment keeps exp(-density t) of its color
        float keep = exp(-frame.fog.w * float(h.t));
        color += weight * (1.0 - keep) * frame.fog.rgb;
        weight *= keep;
    }
    Shading sh;
    rvec3 n;
    real scale;
    vec2 curving; // the surface's, as the ray meets it (from inside, hollow)
    surface_point(h.object, h.part, ray.origin, ray.dir, h.t, sh.p, n, scale, curving);
    bool entering = rdot(ray.dir, n) < 0.0;
    // How far the hit may be off, and its footprint (signature.glsl).
    float cosine = abs(float(rdot(ray.dir, n)));
    curving = clamp(curving, -1e15, 1e15);
    curving = entering ? curving : -curving.yx;
    float bend = max(abs(curving.x), abs(curving.y));
    float sizes = hit_rounding(h.object) * float(scale + max_abs(ray.origin));
    HitDoubt hd = doubt_at(doubt, float(h.t), sizes, cosine, bend);
    seen(sig, max(hd.pixels, far_pixels(doubt)), max(hd.own, own_far_pixels(doubt)), stake);
    if (ray.depth == 0)
        shifted(sig, hd.pixels, stake);
    decided(sig, uint(h.part));
    if (at_stake(stake) && cosine < hd.angle) // entering or leaving
        sig |= UNSURE;
    // An edge as far as the hit, within its distance's doubt, may be
    // nearer in double; counted up to TP2_EDGE_REACH of the scene's scale,
    // which the BVH's grown boxes cover (intersect.glsl, box_ray).
    edges_seen(sig, h.edge, float(h.t), min(distance_doubt(hd, float(h.t), sizes), most_reach()));
    float margin = float(h.next - h.t);
    if (at_stake(stake) && nearer_unsure(margin, hd, float(h.t), sizes) &&
        (margin > 0.0 || !coincident_faces(h.object, h.next_object, h.next_part, n)))
        sig |= UNSURE; // which of two crossings is nearer
    rvec3 nf = entering ? n : -n;
    rvec3 offset = nf * (scale * TP2_REL_EPS);
    // Rays leaving on the incoming side start here, going along nf: into
    // the object when the ray came from inside.
    rvec3 outside = sh.p + offset;
    Start back = Start(h.object, !entering);
    sh.nf = nf;
    sh.view = -ray.dir;
    sh.origin = outside;
    sh.start = back;
    ivec4 ids = object_ids(h.object);
    Finish fin = load_finish(ids.z);
    sh.fin = fin;
    sh.pig = pigment_color(ids.y, sh.p, nf, h.object, at_stake(stake) ? hd.along : 0.0, sig);
    vec3 tint = fin.phong.x * frame.ambient.rgb; // what multiplies the pigment
    vec3 local = tint * sh.pig;
    int samples = light_samples(fin);
    int occluder = -1; // what blocked the last blocked sample
    float graze = NO_GRAZE; // how near a shadow ray passed a sphere (shapes.glsl)
    // Edges passed within a point light's shadow ray's doubt (an area
    // light's samples are turned per pixel: penumbra_seen).
    vec2 shadow_doubt = shadow_edge_doubt(ray.depth, hd, sizes, stake);
    vec2 penumbra = vec2(0.0); // the arealight's samples: the most one lit, one shadowed adds
    for (int j = 0; j < samples; ++j) {
        rvec3 d;
        real dist;
        vec3 lit, lit_tint;
        if (!light_ray(sh, j, area_shift, d, dist, lit, lit_tint))
            continue;
        ++ray_tally[TP2_STAT_SHADOW];
        // The arealight's samples from one point tend to be shadowed by
        // one object: the last sample's occluder is tested first. (Any
        // occluder answers the same; for point lights this was no faster.)
        int hint = OCCLUDER_HINT && area_sample(j) ? occluder : -1;
        Hit shadow = trace_scene(outside, d, back, dist, true, hint,
                                 area_sample(j) ? vec2(-NO_EDGE, 0.0) : shadow_doubt);
        int blocker = shadow.object;
        bool shadowed = blocker >= 0;
        occluder = shadowed ? blocker : occluder;
        if (!area_sample(j)) { // each is a share of its light, turned per pixel
            decided(sig, uint(shadowed));
            shadow_seen(sig, ray.depth, j, shadowed);
            graze = min(graze, shadow.graze);
            edges_seen(sig, shadow.edge, float(dist), 0.0);
        } else {
            penumbra = max(penumbra, area_share(lit, shadowed));
        }
        if (!shadowed) {
            local += lit;
            tint += lit_tint;
        }
    }
    color += weight * local;
    shadows_kept(sig, ray.depth, hd.pixels, stake); // signature.glsl, SHADOWS
    shadow_grazes(sig, graze, ray.depth, hd, sizes, stake);
    penumbra_seen(sig, ray.depth, penumbra, hd, stake);
    // A steep texture or gradient moves with the hit point (signature.glsl).
    if (SMOOTH_PIGMENTS && at_stake(stake) &&
        stake * max(tint.r, max(tint.g, tint.b)) * pigment_slope(ids.y) * hd.along >=
            frame.limits.w)
        sig |= UNSURE;
    rvec3 p = sh.p;

    float kr = HAS_REFLECT ? fin.optics.x : 0.0;
    float kt = HAS_REFRACT ? fin.optics.y : 0.0;
    int depth = ray.depth + 1;
    if (depth > TP2_MAX_DEPTH) { // children past the limit are plain gray
        color += weight * (max(kr, 0.0) + max(kt, 0.0)) * gray;
        return 0;
    }
    vec4 mirrored = mirrored_doubt(doubt, hd, curving);
    int children = 0;
    if (kr > 0.0 && traced(weight * kr, budget, color)) {
        rvec3 r = ray.dir - 2.0 * rdot(ray.dir, nf) * nf;
        first = Ray(outside, r, back, weight * kr, depth);
        first_doubt = mirrored;
        ++children;
        ++ray_tally[TP2_STAT_REFLECTED];
    }
    if (kt > 0.0 && traced(weight * kt, budget, color)) {
        real eta = entering ? real(1.0) / real(fin.optics.z) : real(fin.optics.z);
        real cosi = -rdot(ray.dir, nf);
        real k = 1.0 - eta * eta * (1.0 - cosi * cosi);
        float e2 = float(eta * eta);
        Ray t;
        vec4 t_doubt = mirrored;
        if (at_stake(stake * kt) && has_inside(h.object) &&
            abs(float(k)) < 2.0 * e2 * hd.angle)
            sig |= UNSURE; // total internal reflection or not
        if (!has_inside(h.object)) { // SPEC 3: through a triangle unbent
            t = Ray(p - offset, ray.dir, Start(h.object, entering), weight * kt, depth);
            t_doubt = refracted_doubt(doubt, hd, vec2(0.0), 1.0, 1.0);
        } else if (k < 0.0) { // total internal reflection: the mirror direction
            t = Ray(outside, ray.dir + 2.0 * cosi * nf, back, weight * kt, depth);
        } else {
            rvec3 dir_t = rnormalize(eta * ray.dir + (eta * cosi - sqrt(k)) * nf);
            t = Ray(p - offset, dir_t, Start(h.object, entering), weight * kt, depth);
            t_doubt = refracted_doubt(doubt, hd, curving, float(eta), float(sqrt(k)));
        }
        if (children == 0) {
            first = t;
            first_doubt = t_doubt;
        } else {
            second = t;
            second_doubt = t_doubt;
        }
        ++children;
        ++ray_tally[TP2_STAT_TRANSMITTED];
    }
    return children;
}

// A pixel sample's walk through its ray tree follows each ray's first
// child at once and parks the second, so the stack is only touched where
// the tree branches. Its state is a struct of locals, not globals:
// lavapipe keeps globals in memory (measured: 15-20% of the render time).
struct Walk_ {
    Ray ray;         // the ray to trace next, if live
    int sp;          // rays parked in `pending`
    int traced;      // rays traced so far
    bool live;
    vec3 color;      // what the rays traced so far add
    float budget;    // pruning budget left (see traced())
    uint sig;        // the decisions so far (signature.glsl)
    vec4 doubt;      // the ray's doubt, under SIGNATURES (signature.glsl)
};

WalkRay packed_ray(Ray r, vec4 doubt)
{
    return WalkRay(rvec4(r.origin, r.weight), rvec4(r.dir, 0.0),
                   ivec4(r.start.object, int(r.start.inward), r.depth, 0), doubt);
}

Ray unpacked_ray(WalkRay w)
{
    return Ray(w.origin.xyz, w.dir.xyz, Start(w.info.x, w.info.y != 0), float(w.origin.w),
               w.info.z);
}

// The camera ray through image-plane position (x, y) in [-1, 1]^2, through
// a lens point when the scene has a lens (SPEC 3: thin lens, focal plane).
void camera_ray(real x, real y, vec2 lens_sample, out rvec3 origin, out rvec3 dir)
{
    dir = rnormalize(frame.w.xyz + x * frame.u.xyz + y * frame.v.xyz);
    origin = frame.eye.xyz;
    if (HAS_LENS && frame.lens.x > 0.0) {
        rvec3 focus = origin + dir * (real(frame.lens.y) / rdot(dir, frame.w.xyz));
        vec2 disk = float(frame.lens.x) * square_to_disk(lens_sample);
        origin += disk.x * rnormalize(frame.u.xyz) + disk.y * rnormalize(frame.v.xyz);
        dir = rnormalize(focus - origin);
    }
}

// This workgroup's column and row in the dispatch: render_bands.c cuts the rows
// into SLABS slabs of z, one per thread of lavapipe's, and slab z has rows
// z, z + SLABS, z + 2 SLABS ... (dispatch_slabs).
ivec2 group_place()
{
    return ivec2(gl_WorkGroupID.x, int(gl_WorkGroupID.y) * SLABS + int(gl_WorkGroupID.z));
}

// This invocation's place in a one-dimensional dispatch (over saved walks
// or a pixel list): a column of workgroups.
int flat_invocation()
{
    return group_place().y * (TP2_GROUP_X * TP2_GROUP_Y) + int(gl_LocalInvocationIndex);
}

// This invocation's pixel in its workgroup. Lavapipe runs 8 consecutive
// invocations as the lanes of one SIMD batch, which waits for its slowest
// lane: each batch takes a TP2_LANE_BLOCK_X x _Y block of pixels
// (tp2_shared.h). A permutation: each pixel is still traced once, and the
// same way.
#if TP2_LANE_BLOCK_X * TP2_LANE_BLOCK_Y != 8 || TP2_GROUP_X % TP2_LANE_BLOCK_X != 0
#error "a lane block is 8 pixels, and a workgroup's rows are whole blocks"
#endif
ivec2 pixel_in_group()
{
    const uint across = TP2_GROUP_X / TP2_LANE_BLOCK_X; // blocks in a row of blocks
    uint batch = gl_LocalInvocationIndex / 8u, lane = gl_LocalInvocationIndex % 8u;
    return ivec2(batch % across * TP2_LANE_BLOCK_X + lane % TP2_LANE_BLOCK_X,
                 batch / across * TP2_LANE_BLOCK_Y + lane / TP2_LANE_BLOCK_X);
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

// A parked doubt in slot `slot`, written and read at constant indices (a
// loop over the slots, unrolled): lavapipe then keeps the few slots in
// registers, where indexing them by slot cost the float pass of
// --precision auto 15-20% on glass scenes (docs/decisions.md). The
// parked rays themselves were no faster so.
void park_doubt(inout uvec2 parked[STACK_SIZE], int slot, uvec2 doubt)
{
    for (int k = 0; k < STACK_SIZE; ++k)
        if (k == slot)
            parked[k] = doubt;
}

uvec2 parked_doubt(uvec2 parked[STACK_SIZE], int slot)
{
    uvec2 doubt = uvec2(0u);
    for (int k = 0; k < STACK_SIZE; ++k)
        if (k == slot)
            doubt = parked[k];
    return doubt;
}

// One pixel sample, or one saved walk, for one pass (TP2_WALK_*): its walk
// traces its whole tree, or goes on for pass_rays rays; if it finishes,
// the sample's share is added to its pixel, else it is saved for the next
// pass. An invocation that lavapipe cut short writes nothing.
void main()
{
    frame = frame_buffer;
#ifdef TP2_DOUBLE
    if (SOFT_DOUBLE_KEEP)
        sd_keep();
#endif
    int width = frame.counts.x;
    int height = frame.counts.y;
    for (int i = 0; i < TP2_STAT_COUNT; ++i)
        ray_tally[i] = 0u;
    int s = sample_index;
    ivec2 pixel;
    int entry = -1; // the saved walk this invocation goes on with
    Walk_ w;
    Ray pending[STACK_SIZE];
    uvec2 pending_doubt[STACK_SIZE]; // under SIGNATURES only, as halves
    if (WALK == TP2_WALK_CONTINUE) {
        entry = flat_invocation();
        if (entry >= min(int(counters[TP2_COUNTER_WALKS]), walk_capacity))
            return;
        Walk saved = walks[entry];
        if (saved.where.z < 0) // finished in an earlier pass
            return;
        pixel = saved.where.xy;
        int base = entry * TP2_WALK_RAYS;
        w = Walk_(unpacked_ray(saved_rays[base]), saved.where.z, saved.where.w, true,
                  saved.color.rgb, saved.color.a, saved.signature, saved_rays[base].doubt);
        for (int k = 0; k < w.sp; ++k) {
            pending[k] = unpacked_ray(saved_rays[base + 1 + k]);
            if (SIGNATURES)
                pending_doubt[k] = packed_doubt(saved_rays[base + 1 + k].doubt);
        }
    } else {
        if (PIXEL_LIST) { // the listed pixels of the band, one per invocation
            int at = flat_invocation();
            if (at >= list_length)
                return;
            int listed = int(pixel_list[at]);
            pixel = ivec2(listed % width, tile_origin.y + listed / width);
        } else { // the band, and the row after it when recording signatures
            pixel = tile_origin + group_place() * ivec2(TP2_GROUP_X, TP2_GROUP_Y) +
                    pixel_in_group();
            if (pixel.x >= width || pixel.y >= height ||
                pixel.y - tile_origin.y >= tile_rows + int(SIGNATURES))
                return;
        }
        int index = (pixel.y - tile_origin.y) * width + pixel.x;
        if (LOOP_GUARD && started[index] != 0u)
            return;
        // Sample s of SAMPLES: the pixel center when there is one, else
        // stratified in the pixel. Each adds its share to the pixel.
        vec2 offset = SAMPLES == 1 ? vec2(0.5) : lattice2(s, SAMPLES, frame.sampling.x, random2(pixel, 0u));
        real x = (2.0 * (real(pixel.x) + real(offset.x))) / real(width) - 1.0;
        real y = 1.0 - (2.0 * (real(pixel.y) + real(offset.y))) / real(height);
        rvec3 origin, dir;
        camera_ray(x, y, random2(pixel, uint(2 * s + 1)), origin, dir);
        uint sig = SIGNATURES && s > 0 ? signatures[index] : SIGNATURE_START;
        // The direction's rounding, and a pixel's footprint (signature.glsl;
        // frame.limits.z is a pixel's angle).
        vec4 doubt = vec4(0.0, ROUNDING, 0.0, frame.limits.z);
        w = Walk_(Ray(origin, dir, NOWHERE, 1.0, 0), 0, 0, true, vec3(0.0), frame.limits.x,
                  sig, doubt);
        ray_tally[TP2_STAT_CAMERA] = unsure(sig) ? 0u : 1u;
    }

    // The walk: all of it, or at most pass_rays rays (a full tree has
    // MAX_RAYS), or until a decision is UNSURE: then the pixel is traced
    // again in double, every sample, and what float would trace after is
    // not needed (signature.glsl, STOPPED).
    vec2 area_shift = random2(pixel, uint(2 * s + 2));
    int end = WALK == TP2_WALK_WHOLE ? MAX_RAYS : min(w.traced + pass_rays, MAX_RAYS);
    for (; w.traced < end && w.live && !unsure(w.sig); ++w.traced) {
        Ray first, second;
        vec4 first_doubt, second_doubt;
        int children = trace_step(w.ray, w.doubt, area_shift, w.color, w.budget, w.sig, first,
                                  second, first_doubt, second_doubt);
        if (children == 2 && w.sp < STACK_SIZE) {
            if (SIGNATURES)
                park_doubt(pending_doubt, w.sp, packed_doubt(second_doubt));
            pending[w.sp++] = second;
        }
        if (children > 0) {
            w.ray = first;
            if (SIGNATURES)
                w.doubt = first_doubt;
        } else if (w.sp > 0) {
            w.ray = pending[--w.sp];
            if (SIGNATURES)
                w.doubt = unpacked_doubt(parked_doubt(pending_doubt, w.sp));
        } else {
            w.live = false;
        }
    }
    w.live = w.live && w.traced < MAX_RAYS;
    if (unsure(w.sig)) {
        w.live = false;
        w.sig |= STOPPED;
    }

    bool cut = LOOP_GUARD && was_cut();
    if (cut) {
        atomicAdd(counters[TP2_COUNTER_CUT], 1u);
        if (WALK == TP2_WALK_WHOLE || accept_cut == 0)
            return;
        atomicAdd(counters[TP2_COUNTER_LOST], 1u);
        w.live = false; // what there is, wrong: tp2 says so
    }
    // pixels[] holds one band of whole rows, from row tile_origin.y on;
    // the row after it is traced for its signatures only.
    int index = (pixel.y - tile_origin.y) * width + pixel.x;
    if (!w.live) {
        vec3 share = w.color / float(SAMPLES);
        if (pixel.y - tile_origin.y < tile_rows)
            pixels[index] = vec4((s == 0 ? vec3(0.0) : pixels[index].rgb) + share, 1.0);
        if (SIGNATURES)
            signatures[index] = w.sig;
        if (entry >= 0)
            walks[entry].where.z = -1;
        else if (LOOP_GUARD)
            started[index] = 1u;
    } else if (WALK != TP2_WALK_WHOLE) {
        if (entry < 0) {
            entry = int(atomicAdd(counters[TP2_COUNTER_WALKS], 1u));
            if (entry >= walk_capacity) { // no room: it starts again later
                atomicAdd(counters[TP2_COUNTER_WAITING], 1u);
                return;
            }
            started[index] = 1u;
        }
        walks[entry] = Walk(ivec4(pixel, w.sp, w.traced), vec4(w.color, w.budget), w.sig);
        int base = entry * TP2_WALK_RAYS;
        saved_rays[base] = packed_ray(w.ray, SIGNATURES ? w.doubt : vec4(0.0));
        for (int k = 0; k < w.sp; ++k) {
            vec4 doubt = SIGNATURES ? unpacked_doubt(pending_doubt[k]) : vec4(0.0);
            saved_rays[base + 1 + k] = packed_ray(pending[k], doubt);
        }
        atomicAdd(counters[TP2_COUNTER_UNFINISHED], 1u);
    }
    if (COUNT_RAYS)
        count_rays();
}
