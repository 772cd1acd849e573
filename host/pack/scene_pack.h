/* scene_pack.h: a parsed scene laid out as the shader's storage buffers. */
#ifndef TP2_SCENE_PACK_H
#define TP2_SCENE_PACK_H

#include <stdbool.h>
#include <stddef.h>

#include "scene.h"
#include "tp2_shared.h"

/* The input buffers, indexed by binding (TP2_BINDING_FRAME ..
 * TP2_BINDING_TEXELS); the image and stats buffers follow them. */
#define TP2_INPUT_BUFFERS TP2_BINDING_IMAGE

/* What the shader is specialised for: the features the scene uses. */
struct scene_features {
    bool reflect, refract, fog, lens, area;
    int pigments;   /* bit TP2_PIGMENT_k: kind k in use */
    int shapes;     /* bit TP2_SHAPE_k: kind k in use */
    int bounded_shape;   /* the one TP2_SHAPE_* of the bounded objects, else -1 */
    int unbounded_shape; /* ... of the unbounded ones, else -1 */
    bool bvh; /* enough bounded objects that the BVH beats a plain loop */
    int samples;
    int twins; /* TP2_TWIN_CAPS, TP2_TWIN_TRIANGLES: some cap, some triangle
                  lies in another object's face (ties.h) */
    bool scene_slots; /* no BVH, and the bounded slots in scene order */
};

struct pack_options {
    int width, height;
    bool use_double; /* pack for the double-precision (reference) shader */
    int samples;     /* samples per pixel; 0: the scene's, else 1 */
    int bvh_min; /* use the BVH from this many bounded objects; 0: default */
    double bailout;  /* rays of smaller weight are not traced; 0: all are */
    /* Called with the scene's features once they are known, before the
     * BVH is built (render.c makes the device and its pipeline from then
     * on, beside the build); NULL: not called. */
    void (*features_known)(const struct scene_features *f, void *user);
    void *user;
};

struct packed_scene {
    /* Each buffer holds at least one element (Vulkan has no empty
     * buffers); the frame's counts say how many are real. */
    void *data[TP2_INPUT_BUFFERS];
    size_t size[TP2_INPUT_BUFFERS];
    struct scene_features features;
    double bvh_time; /* seconds spent building the BVH (for --stats) */
    size_t bounded, unbounded; /* primitives with a box, and those every ray
                                * tests (for --stats) */
};

/* Packs s: camera basis, lights, materials, texels, and the objects as GPU
 * primitives (a mesh makes one per triangle): the bounded ones in BVH
 * order, then the unbounded ones, and the BVH. twin, unless NULL, gets
 * the same scene packed for the double shader (--precision mixed traces
 * some pixels again in double): every buffer but the BVH's and the
 * texels', which both share (out's). Returns 0, or -1 out of memory (out
 * and twin zeroed). */
int scene_pack(const struct scene *s, const struct pack_options *opt,
               struct packed_scene *out, struct packed_scene *twin);

/* Frees the buffers and zeroes p; safe on a zeroed one. */
void packed_scene_free(struct packed_scene *p);

#endif
