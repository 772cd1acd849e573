/* render.h: one image of a scene, traced on a Vulkan device. */
#ifndef TP2_RENDER_H
#define TP2_RENDER_H

#include <stdbool.h>

#include "scene.h"

struct render_options {
    int width, height;
    int device_index;  /* -1: the best device */
    bool use_double;   /* double-precision geometry: the reference image */
    bool validate;     /* Khronos validation layer on, messages counted */
};

/* Traces s into rgba, width * height * 4 linear floats, rows top to
 * bottom. Returns 0, or -1 after printing one "tp2: ..." message. */
int render_scene(const struct scene *s, const struct render_options *opt,
                 float *rgba);

#endif
