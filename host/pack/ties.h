/* ties.h: coincident flat surfaces, found when packing, so that they tie
 * exactly (SPEC 4, Ties).
 *
 * A cylinder's cap standing on a floor plane, or a polyhedron's face lying
 * in a box's, meets a ray at one distance as real numbers; computed by two
 * formulas, the two distances differ by rounding, and which is nearer then
 * changes from pixel to pixel (speckles). Here such surfaces are grouped
 * and each group gets one canonical plane: a box face's own (its slab
 * arithmetic is plane_t's on an axis plane), else the first plane
 * object's, else the first face's in file order. Planes and polyhedron
 * faces then carry that plane (turned to their own side), caps take its
 * normal as their axis and keep its place along it, triangles read it
 * from a twin row (TP2_SHAPE_TWIN_*), and shaders/shapes.glsl computes every
 * member's distance by plane_t's one formula on the same numbers: equal
 * in any precision, and the file order decides.
 *
 * Coincident means: unit normals within TIE_TOLERANCE of each other in
 * each component (either orientation), and d within TIE_TOLERANCE times
 * the scene's scale. Planes that are equal as real numbers come out of
 * packing at most a few units of double's 2^-53 apart (a unit normal from
 * the file's vector, d from the file's decimals or a cap's center along
 * its axis: each a handful of roundings of numbers at most the scale), far
 * within 2^-40; faces that differ by float's 2^-24 (tests/stress/faces-
 * float-step-apart) stay apart by 2^16 times the tolerance. */
#ifndef TP2_TIES_H
#define TP2_TIES_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#define TIE_TOLERANCE 0x1p-40

/* How a surface's distance is computed, and so whether packing may give
 * it another plane; in the order a group's canonical plane is chosen. */
enum tie_role {
    TIE_FIXED,  /* a box face: the slab's arithmetic, an axis plane's */
    TIE_PLANE,  /* a plane object's row: replaced by the canonical plane */
    TIE_FACE,   /* a polyhedron's face row: replaced the same way */
    TIE_CAP,    /* a cylinder's or cone's cap: its axis becomes the plane's
                   normal, its record holds the plane's place along it */
    TIE_TRIANGLE, /* a triangle: its inside by its corners, its distance
                     through a twin row */
};

struct tie_surface {
    double plane[4]; /* unit normal (outward), d: n.x + d = 0, as packed */
    uint32_t slot;   /* its primitive's GPU slot */
    uint32_t part;   /* its face (box, polyhedron) or cap (1 base, 2 top) */
    size_t object;   /* its scene object, in file order */
    enum tie_role role;
};

/* Groups the n surfaces (reordering them) and sets, for each that shares
 * a group with another object's surface, twin[i] = true and canonical[i]
 * to the group's plane turned to face the way surface i's normal does
 * (caps and triangles keep it as the group has it: their distance does not depend on the
 * side). scale: the largest coordinate magnitude of the scene. Faces of
 * one group beyond a window of 256 after one another along d are not
 * compared (more than that many faces in one plane: a few may stay
 * apart). 0, or -1 when out of memory. */
int ties_group(struct tie_surface *s, size_t n, double scale, double (*canonical)[4],
               bool *twin);

/* Whether a plane lies within the tolerance of one of n surfaces (sorted
 * by ties_sort first): a mesh's triangles are put in the search only
 * where they lie in another object's face, so that a million triangles
 * cost a lookup each, not a place in the sort. Surfaces of object
 * other_than are passed over. */
void ties_sort(struct tie_surface *s, size_t n);
bool ties_near(const struct tie_surface *sorted, size_t n, const double plane[4],
               double scale, size_t other_than);

#endif
