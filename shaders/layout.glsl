// layout.glsl: the GPU structs as the shader sees them (std430).
// Twin of host/pack/gpu_layout_types.h (and struct bvh_gpu_node in host/pack/bvh.h); keep
// field names, order and types identical: tests/test_layout.c checks the
// storage buffers' against the SPIR-V, and host/pack/gpu_layout.h pins the
// records read as texels (lights, pigments, finishes, objects, their
// extra rows, BVH nodes) to the texel counts of tp2_shared.h that the
// loaders below use.
// `real`, `rvec3` and `rvec4` are float or double (see trace.comp).

struct Frame {
    rvec4 eye;        // from the origin the scene was packed from (scene_pack.c);
                      // w: the largest coordinate of the eye, the lights and the
                      // bounded objects' box (shapes.glsl, edge_graze)
    rvec4 u;          // right, scaled to half the image plane's width
    rvec4 v;          // up, scaled to half its height
    rvec4 w;          // unit view direction
    vec4 ambient;     // rgb: color of light 0
    vec4 background;
    vec4 fog;         // rgb, density
    vec4 lens;        // aperture radius, focal distance
    vec4 area;        // x: arealight radius
    vec4 limits;      // x: bailout, the least weight a ray is traced with;
                      // y: least doubt (pixels) of a decision hashed, z: a
                      // pixel's angle (signature.glsl)
    ivec4 counts;     // width, height, point lights, objects
    ivec4 geometry;   // bounded objects (BVH order), unbounded ones after them, BVH nodes
    ivec4 sampling;   // lattice generator, arealight index, arealight samples, TP2_CANARY_STEPS
};

struct Light {
    rvec4 pos;
    vec4 color;
    vec4 att;
};

struct Finish {
    vec4 phong;  // ka kd ks n
    vec4 optics; // kr kt ior
};

// An inner node: its two children's boxes by axis (left lo, left hi,
// right lo, right hi) and their links (tp2_shared.h: -link an inner node,
// else a leaf's objects).
struct BvhNode {
    vec4 x;
    vec4 y;
    vec4 z;
    ivec2 link;
};

layout(std430, set = 0, binding = TP2_BINDING_FRAME) restrict readonly buffer FrameBuf { Frame frame_buffer; };
// The frame, copied once per invocation (main): on lavapipe every
// storage-buffer load is a loop over the SIMD lanes, even of a field
// all lanes share; a private copy is registers. (restrict: nothing else
// writes it, so a GPU compiler may load a field again rather than hold
// it.)
Frame frame;
// Lights, pigments, finishes, objects, the rows objects need beyond
// their record, and BVH nodes, as texels (tp2_shared.h; read below):
// uniform texel buffers as images without a sampler (utextureBuffer:
// a sampled image of Dim Buffer is not valid SPIR-V 1.6, and Mesa 25
// warns of one, which the tests count as a validation message).
layout(set = 0, binding = TP2_BINDING_LIGHTS) uniform utextureBuffer light_texels;
layout(set = 0, binding = TP2_BINDING_PIGMENTS) uniform utextureBuffer pigment_texels;
layout(set = 0, binding = TP2_BINDING_FINISHES) uniform utextureBuffer finish_texels;
layout(set = 0, binding = TP2_BINDING_OBJECTS) uniform utextureBuffer object_texels;
layout(set = 0, binding = TP2_BINDING_BVH) uniform utextureBuffer node_texels;
layout(set = 0, binding = TP2_BINDING_EXTRA) uniform utextureBuffer extra_texels;
// Texmap images: one word per texel, r | g << 8 | b << 16, rows top to bottom.
layout(std430, set = 0, binding = TP2_BINDING_TEXELS) readonly buffer TexelBuf { uint texels[]; };
layout(std430, set = 0, binding = TP2_BINDING_IMAGE) buffer ImageBuf { vec4 pixels[]; };
// Ray counters as (low, high) pairs, then the TP2_COUNTER_*s.
layout(std430, set = 0, binding = TP2_BINDING_STATS) buffer StatsBuf {
    uint ray_counts[2 * TP2_STAT_COUNT];
    uint counters[TP2_COUNTER_COUNT];
};

// A walk that goes on in the next pass (see TP2_CANARY_STEPS), and its
// rays: the current one, then those parked.
struct Walk {
    ivec4 where;    // pixel x, y; rays parked (-1: finished); rays traced so far
    vec4 color;     // rgb so far, pruning budget left
    uint signature; // the decisions so far (signature.glsl)
};

struct WalkRay {
    rvec4 origin; // xyz, weight
    rvec4 dir;    // xyz
    ivec4 info;   // start object, start inward, depth
    vec4 doubt;   // xyz: Ray.doubt (signature.glsl)
};

layout(std430, set = 0, binding = TP2_BINDING_STARTED) buffer StartedBuf { uint started[]; };
layout(std430, set = 0, binding = TP2_BINDING_WALKS) buffer WalkBuf { Walk walks[]; };
layout(std430, set = 0, binding = TP2_BINDING_WALK_RAYS) buffer WalkRayBuf { WalkRay saved_rays[]; };
// Per band pixel (and the row after the band): its decisions' signature;
// the band pixels a list pass traces, as indices into the band.
layout(std430, set = 0, binding = TP2_BINDING_SIGNATURES) buffer SignatureBuf { uint signatures[]; };
layout(std430, set = 0, binding = TP2_BINDING_PIXEL_LIST) readonly buffer PixelListBuf { uint pixel_list[]; };

#include "tile.glsl"

layout(constant_id = TP2_SPEC_REFLECT) const bool HAS_REFLECT = true;
layout(constant_id = TP2_SPEC_REFRACT) const bool HAS_REFRACT = true;
layout(constant_id = TP2_SPEC_PIGMENTS) const int PIGMENT_KINDS = -1;
layout(constant_id = TP2_SPEC_SHAPES) const int SHAPE_KINDS = -1;
layout(constant_id = TP2_SPEC_BOUNDED_SHAPE) const int BOUNDED_SHAPE = -1;
layout(constant_id = TP2_SPEC_UNBOUNDED_SHAPE) const int UNBOUNDED_SHAPE = -1;
layout(constant_id = TP2_SPEC_FOG) const bool HAS_FOG = false;
layout(constant_id = TP2_SPEC_LENS) const bool HAS_LENS = false;
layout(constant_id = TP2_SPEC_AREA) const bool HAS_AREA = false;
layout(constant_id = TP2_SPEC_STATS) const bool COUNT_RAYS = false;
layout(constant_id = TP2_SPEC_SAMPLES) const int SAMPLES = 1;
layout(constant_id = TP2_SPEC_BVH) const bool USE_BVH = true;
layout(constant_id = TP2_SPEC_LOOP_GUARD) const bool LOOP_GUARD = false;
layout(constant_id = TP2_SPEC_WALK) const int WALK = TP2_WALK_WHOLE;
layout(constant_id = TP2_SPEC_SIGNATURES) const bool SIGNATURES = false;
layout(constant_id = TP2_SPEC_PIXEL_LIST) const bool PIXEL_LIST = false;
layout(constant_id = TP2_SPEC_OCCLUDER_HINT) const bool OCCLUDER_HINT = true;
layout(constant_id = TP2_SPEC_SLABS) const int SLABS = 1;
layout(constant_id = TP2_SPEC_SCENE_SLOTS) const bool SCENE_SLOTS = false;
layout(constant_id = TP2_SPEC_TWINS) const int TWIN_KINDS = TP2_TWIN_CAPS | TP2_TWIN_TRIANGLES;

// Whether some cap, some triangle lies in another object's face
// (shapes.glsl, hit_tapered, hit_triangle): else their code compiles out.
const bool TWIN_CAPS = (TWIN_KINDS & TP2_TWIN_CAPS) != 0;
const bool TWIN_TRIANGLES = (TWIN_KINDS & TP2_TWIN_TRIANGLES) != 0;

// Whether the scene uses pigment kind k / shape kind k (TP2_PIGMENT_*,
// TP2_SHAPE_*: kinds.h): code for kinds it does not use is compiled out.
#define USES_PIGMENT(k) ((PIGMENT_KINDS & (1 << (k))) != 0)
#define USES_SHAPE(k) ((SHAPE_KINDS & (1 << (k))) != 0)

// Object i, one primitive: rows a, b, c (what each kind keeps in them:
// host/scene/shapes.c) and ids (TP2_SHAPE_*, pigment, finish, first extra_row).
#ifdef TP2_DOUBLE
#define OBJECT_TEXELS TP2_OBJECT_TEXELS_D
#define ROW_TEXELS TP2_ROW_TEXELS_D
#else
#define OBJECT_TEXELS TP2_OBJECT_TEXELS_F
#define ROW_TEXELS TP2_ROW_TEXELS_F
#endif

// Lights, pigments and finishes (tp2_shared.h; host/pack/gpu_layout.h pins
// the C structs to these texels). What each pigment kind keeps where:
// host/scene/pigments.c.
#ifdef TP2_DOUBLE
#define LIGHT_TEXELS TP2_LIGHT_TEXELS_D
#define PIGMENT_TEXELS TP2_PIGMENT_TEXELS_D
#else
#define LIGHT_TEXELS TP2_LIGHT_TEXELS_F
#define PIGMENT_TEXELS TP2_PIGMENT_TEXELS_F
#endif

vec4 float_texel(utextureBuffer b, int at)
{
    return uintBitsToFloat(texelFetch(b, at));
}

// A real 4-vector from texel `at` on (ROW_TEXELS of them).
rvec4 real_texel(utextureBuffer b, int at)
{
#ifdef TP2_DOUBLE
    uvec4 lo = texelFetch(b, at);
    uvec4 hi = texelFetch(b, at + 1);
    return dvec4(packDouble2x32(lo.xy), packDouble2x32(lo.zw), packDouble2x32(hi.xy),
                 packDouble2x32(hi.zw));
#else
    return float_texel(b, at);
#endif
}

Light load_light(int i)
{
    int at = LIGHT_TEXELS * i;
    return Light(real_texel(light_texels, at), float_texel(light_texels, at + ROW_TEXELS),
                 float_texel(light_texels, at + ROW_TEXELS + 1));
}

Finish load_finish(int i)
{
    int at = TP2_FINISH_TEXELS * i;
    return Finish(float_texel(finish_texels, at), float_texel(finish_texels, at + 1));
}

// Pigment i's fields, each loaded where its kind needs it.
vec4 pigment_color1(int i)
{
    return float_texel(pigment_texels, PIGMENT_TEXELS * i);
}

vec4 pigment_color2(int i)
{
    return float_texel(pigment_texels, PIGMENT_TEXELS * i + 1);
}

rvec4 pigment_p(int i)
{
    return real_texel(pigment_texels, PIGMENT_TEXELS * i + 2);
}

rvec4 pigment_q(int i)
{
    return real_texel(pigment_texels, PIGMENT_TEXELS * i + 2 + ROW_TEXELS);
}

ivec4 pigment_kind(int i) // TP2_PIGMENT_*; texmap: first texel, width, height
{
    return ivec4(texelFetch(pigment_texels, PIGMENT_TEXELS * i + 2 + 2 * ROW_TEXELS));
}

// Row k (0: a, 1: b, 2: c) of object i.
rvec4 object_row(int i, int k)
{
    return real_texel(object_texels, OBJECT_TEXELS * i + ROW_TEXELS * k);
}

// Row k of the rows objects keep beyond their record (object_ids(i).w
// is an object's first).
rvec4 extra_row(int k)
{
    return real_texel(extra_texels, ROW_TEXELS * k);
}

ivec4 object_ids(int i)
{
    return ivec4(texelFetch(object_texels, OBJECT_TEXELS * i + 3 * ROW_TEXELS));
}

// Inner node i of the BVH.
BvhNode load_node(int i)
{
    int at = TP2_NODE_TEXELS * i;
    return BvhNode(uintBitsToFloat(texelFetch(node_texels, at)),
                   uintBitsToFloat(texelFetch(node_texels, at + 1)),
                   uintBitsToFloat(texelFetch(node_texels, at + 2)),
                   ivec2(texelFetch(node_texels, at + 3).xy));
}
