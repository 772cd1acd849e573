/* scene_pack.h: a parsed scene laid out as the shader's storage buffers. */
#ifndef TP2_SCENE_PACK_H
#define TP2_SCENE_PACK_H

#include <stdbool.h>
#include <stddef.h>

#include "scene.h"
#include "tp2_shared.h"

/* The scene's input buffers, indexed by binding (TP2_BINDING_FRAME ..
 * TP2_BINDING_OBJECTS). Each holds at least one element, since Vulkan has
 * no empty buffers; the frame's counts say how many are real. */
#define TP2_INPUT_BUFFERS TP2_BINDING_IMAGE

struct packed_scene {
    void *data[TP2_INPUT_BUFFERS];
    size_t size[TP2_INPUT_BUFFERS];
};

/* Packs s for a width x height image, in doubles if use_double (the
 * reference shader) or floats. Returns 0, or -1 out of memory. */
int scene_pack(const struct scene *s, int width, int height, bool use_double,
               struct packed_scene *out);

/* Frees the buffers and zeroes p; safe on a zeroed one. */
void packed_scene_free(struct packed_scene *p);

#endif
