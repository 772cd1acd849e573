/* float_exact.h: whether a double survives packing into float unchanged.
 *
 * The float scene is exact where its numbers are (TP2_SHAPE_INEXACT, a
 * checker side's flag: shaders/pigments.glsl, unsure_cell). */
#ifndef TP2_FLOAT_EXACT_H
#define TP2_FLOAT_EXACT_H

#include <float.h>
#include <math.h>
#include <stdbool.h>

/* Whether v is a float exactly (the range test first: converting a double
 * beyond float's range is undefined). */
static inline bool is_float(double v)
{
    return fabs(v) <= FLT_MAX && (double)(float)v == v;
}

#endif
