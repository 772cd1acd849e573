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
    bool retrace;      /* --precision mixed or auto: float, then the pixels on
                        * decision boundaries again in double (in software
                        * where the device has no shaderFloat64), where the
                        * double scene fits the device */
    bool double_on_cpu; /* --precision auto: on a CPU device the whole
                         * image in double instead (render.c, auto_on_device) */
    /* Set when use_double was chosen for the scene's range, not asked for:
     * where its largest length was written ("FILE:LINE:COL") and what it
     * is. Without shaderFloat64 the render is then refused naming them;
     * with it, a note says so (unless quiet). */
    const char *double_where, *double_what;
    bool validate;     /* Khronos validation layer on, messages counted */
    bool count_rays;   /* fill render_stats.rays (costs a little speed) */
    bool progress;     /* draw a progress bar on stderr after a second */
    bool quiet;        /* no note about the precision chosen */
    bool bytes;        /* rows as 8-bit values, quantized on the device (the
                        * file is PPM or PNG), else as floats (PFM) */
};

/* Wall times of the phases, in seconds, and rays traced by kind. Bands
 * are rendered, read back and written in turn, the rows of one band being
 * written while the next renders: render is the band loop's time less
 * readback (copying finished bands out of device memory) and write (the
 * time spent in the row callback). */
struct render_stats {
    double device, pipeline, bvh, upload, render, readback, write;
    uint64_t bounded, unbounded; /* primitives in the BVH (or its plain loop),
                                  * and those every ray tests */
    bool has_bvh;         /* whether the bounded ones have a BVH */
    double pipeline_beside; /* making the pipelines beside bvh and upload
                             * (a large scene); pipeline counts only what
                             * was waited for */
    uint64_t in_place;    /* bytes of the scene the device reads from the
                           * host's arrays instead of a copy */
    int bands, band_rows; /* bands rendered, rows in each (the last: fewer) */
    uint32_t passes;      /* dispatches: a pass per band and sample, more
                           * where walks went on or lavapipe cut a pass */
    int pass_rays;        /* rays per walk per pass at the end */
    uint64_t rays[TP2_STAT_COUNT]; /* TP2_STAT_*; zero unless count_rays */
    bool retracing;       /* mixed's double retrace ran */
    bool retrace_soft;    /* ... in software double (no shaderFloat64) */
    double device_choice; /* seconds packing waited for the choice of device (auto) */
    uint64_t retraced;    /* pixels traced again in double */
    double retrace;       /* seconds marking and retracing them (in render) */
    char precision[128];  /* the precision used, in words */
    char device_name[256];
};

/* Receives the image as it is rendered: rows [first, first + count), rows
 * top to bottom, every row once and in order. Each row is width words
 * r | g << 8 | b << 16 of 8-bit values (image_quantize's, computed on the
 * device) under render_options.bytes, else width * 4 linear floats (rgb,
 * then a junk alpha). Returns 0, or -1 to stop the render (after printing
 * its own message). */
typedef int (*render_rows_fn)(void *user, const void *rows, int first, int count);

/* Traces s in bands of whole rows, handing each band's rows to on_rows,
 * and fills stats. Memory stays bounded whatever the image size: one band
 * on the device and one copy of it on the host. Returns 0, or -1 after
 * printing one "tp2: ..." message (or after on_rows failed). */
int render_scene(const struct scene *s, const struct render_options *opt,
                 render_rows_fn on_rows, void *user, struct render_stats *stats);

#endif
