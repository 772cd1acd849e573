/* scene.c: ownership of the scene's arrays (see scene.h). */
#include "scene.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void scene_free(struct scene *s)
{
    if (!s)
        return;
    for (size_t i = 0; i < s->ntextures; i++) {
        free(s->textures[i].path);
        free(s->textures[i].rgb);
    }
    free(s->textures);
    free(s->lights);
    free(s->pigments);
    free(s->finishes);
    free(s->objects);
    free(s->reals);
    memset(s, 0, sizeof *s);
}

/* The shaders square lengths: the sphere test forms |o - c|^2 and r^2,
 * length() and normalize() square the vector between two points, lighting
 * squares a light's distance. With every coordinate and size at most L, a
 * difference is at most 2L and a squared length at most 3 (2L)^2 = 12 L^2,
 * which must stay below the largest value of the type: float's is about
 * 2^128 (3.4e38), so L = 2^60 (1.2e18) leaves a factor 16 for sums of such
 * terms. Beyond it a float render loses whole objects (1e40 is infinite:
 * a sphere of radius 1e20 vanishes into the background) with no error.
 * Double geometry goes much further, but lighting stays in float there
 * too (a light's distance, the arealight and lens sizes), so a distance
 * must stay a finite float: L = 2^120 (1.3e36), a distance of at most
 * 2 sqrt(3) L < 2^122. main.c renders a scene past the float bound in
 * double unless --precision float was asked for, and refuses one past
 * the double bound. */
double scene_length_limit(bool use_double)
{
    return use_double ? ldexp(1.0, 120) : ldexp(1.0, 60);
}
