/* render.h: one image of a scene, traced on a Vulkan device. */
#ifndef TP2_RENDER_H
#define TP2_RENDER_H

#include <stdbool.h>
#include <stdint.h>

#include "scene.h"
#include "tp2_shared.h"

struct render_options {
    int width, height;
    int device_index;  /* -1: the best device */
    int samples;       /* samples per pixel; 0: the scene's (default 1) */
    int bvh_min;       /* BVH from this many spheres; 0: the default */
    double bailout;    /* least weight of a traced ray; 0: the exact model */
    bool use_double;   /* double-precision geometry: the reference image */
    bool validate;     /* Khronos validation layer on, messages counted */
    bool count_rays;   /* fill render_stats.rays (costs a little speed) */
    bool progress;     /* draw a progress bar on stderr after a second */
};

/* Wall times of the phases, in seconds, and rays traced by kind. */
struct render_stats {
    double device, pipeline, upload, render, readback;
    uint64_t rays[TP2_STAT_COUNT]; /* TP2_STAT_*; zero unless count_rays */
    char device_name[256];
};

/* Traces s into rgba, width * height * 4 linear floats, rows top to
 * bottom, and fills stats. Returns 0, or -1 after printing one
 * "tp2: ..." message. */
int render_scene(const struct scene *s, const struct render_options *opt,
                 float *rgba, struct render_stats *stats);

#endif
