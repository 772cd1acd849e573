/* convex.h: the bounding box of a convex polyhedron given by half-spaces.
 *
 * A polyhedron of SPEC 3 is the set of points x with n.x + d <= 0 for each
 * face (n, d); it may be unbounded (one face is a half-space). The BVH needs
 * boxes for the bounded ones; the rest are tested by every ray. */
#ifndef TP2_CONVEX_H
#define TP2_CONVEX_H

#include <stddef.h>

/* Returns 1 and a box containing the polyhedron of n faces (each a b c d,
 * (a b c) != 0) when it is bounded and not empty, or 0 when it is
 * unbounded, empty, or reaches 2^19 times (1 + its farthest face's
 * distance from the origin): those are tested by every ray, which costs
 * speed, never correctness. The box errs toward larger (by 1e-9 of itself
 * and 1e-12 of that distance); "bounded" and "not empty" err toward 0.
 * Expected time linear in n; past 256 n + 4096 projected faces per side
 * (an order that defeats the shuffle) it gives up and returns 0. */
int convex_bounds(const double *faces, size_t n, double lo[3], double hi[3]);

#endif
