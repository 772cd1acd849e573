/* retrace.h: which pixels --precision auto traces again in double. */
#ifndef TP2_RETRACE_H
#define TP2_RETRACE_H

#include <stddef.h>
#include <stdint.h>

#include "tp2_shared.h"

/* The float pass gives each pixel a signature (shaders/signature.glsl,
 * tp2_shared.h): a hash of its decisions, three bits and its camera rays'
 * shadows. */
#define RETRACE_UNSURE TP2_SIG_UNSURE       /* a decision was within float's error */
#define RETRACE_SENSITIVE TP2_SIG_SENSITIVE /* its boundaries may move by a pixel's
                                             * fraction that matters */
#define RETRACE_STOPPED TP2_SIG_STOPPED     /* its walk stopped at an UNSURE
                                             * decision: the hash is partial */
#define RETRACE_SHADOWS TP2_SIG_SHADOWS     /* the point lights its camera rays
                                             * saw shadowed, where that counts */
#define RETRACE_HASH TP2_SIG_HASH

/* What counts is TP2_SIG_PIXELS and TP2_SIG_STAKE (tp2_shared.h), which
 * scene_pack.c hands the shader in frame.limits.y and .w. */

/* A pixel is traced again in double where it is UNSURE, or where its hash
 * differs from one of its eight neighbours' and one of the two is
 * SENSITIVE, or where their SHADOWS differ: a boundary lies between them
 * that rounding may move across a pixel's center. A STOPPED pixel's hash
 * is taken to differ from every neighbour's.
 *
 * Marks such pixels of a band of n rows of `width` (rows[y * width + x]),
 * neighbours in the row above the band (above, or NULL at the image's
 * top) and below it (below, or NULL at its bottom) included. Writes their
 * indices in the band, y * width + x, to list, and returns how many. The
 * list goes by blocks of RETRACE_BLOCK_X x RETRACE_BLOCK_Y pixels (row
 * order within a block, blocks in row order): the retrace pass gives 8
 * consecutive entries to the 8 lanes of a SIMD batch on lavapipe, and
 * nearby pixels' rays diverge less (docs/decisions.md). */
#define RETRACE_BLOCK_X TP2_LANE_BLOCK_X
#define RETRACE_BLOCK_Y TP2_LANE_BLOCK_Y

size_t retrace_mark(const uint32_t *above, const uint32_t *rows, const uint32_t *below,
                    int width, int n, uint32_t *list);

#endif
