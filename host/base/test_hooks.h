/* test_hooks.h: the TP2_* environment variables with which tests reach
 * paths and limits of the real binary that small scenes and lavapipe would
 * not reach. They are read in this one place, once, and listed with what
 * each does in docs/testing.md. None changes an image; device simulations
 * (a device without shaderFloat64, one that fuses multiply-adds) are
 * Vulkan layers built with the tests (tests/layers/), not switches here. */
#ifndef TP2_TEST_HOOKS_H
#define TP2_TEST_HOOKS_H

#include <stdbool.h>

/* A device limit a test may lower: `set` where the variable holds an
 * unsigned decimal number, then the limit becomes at most `at_most`. */
struct hook_limit {
    bool set;
    unsigned long long at_most;
};

struct test_hooks {
    bool validate;                    /* TP2_VALIDATE=1: as --validate */
    struct hook_limit band_bytes;     /* TP2_BAND_BYTES: the band buffer */
    struct hook_limit storage_range;  /* TP2_STORAGE_RANGE: maxStorageBufferRange */
    struct hook_limit texel_elements; /* TP2_TEXEL_ELEMENTS: maxTexelBufferElements */
    bool eager_retrace_set;           /* TP2_EAGER_RETRACE: samples from which */
    double eager_retrace;             /* auto makes its retrace pipeline early */
    bool early_pipelines;             /* TP2_EARLY_PIPELINES=1: before packing ends */
    long pass_rays;                   /* TP2_PASS_RAYS: rays a pass (0: not set) */
    bool dispatch_slabs_set;          /* TP2_DISPATCH_SLABS: slabs a dispatch */
    long dispatch_slabs;
    bool no_occluder_hint;            /* TP2_OCCLUDER_HINT=0 */
    bool no_specialize;               /* TP2_SPECIALIZE=0: whole shader modules */
    bool no_host_import;              /* TP2_HOST_IMPORT=0: scene copied, not imported */
    bool bvh_one_thread;              /* no variable: set by tests/test_bvh.c */
};

/* The hooks, read from the environment on the first call (from any
 * thread); the same struct after. */
const struct test_hooks *test_hooks(void);

/* The same struct, writable: for unit tests that compare both sides of a
 * hook in one process. tp2 itself never calls it. */
struct test_hooks *test_hooks_edit(void);

/* limit, or the hook's value where it is set and smaller. */
unsigned long long hook_lowered(struct hook_limit hook, unsigned long long limit);

#endif
