/* convex.h: the bounding box of a convex polyhedron given by half-spaces.
 *
 * A polyhedron of SPEC 3 is the set of points x with n.x + d <= 0 for each
 * face (n, d); it may be unbounded (one face is a half-space). The BVH needs
 * boxes for the bounded ones; the rest are tested by every ray. */
#ifndef TP2_CONVEX_H
#define TP2_CONVEX_H

#include <stddef.h>

/* Polyhedra with more faces than this are not bounded here (vertex
 * enumeration is quartic in the faces); they are treated as unbounded,
 * which costs speed, never correctness. */
#define CONVEX_MAX_FACES 128

/* Returns 1 and a box containing the polyhedron of n faces (each a b c d,
 * (a b c) != 0) when it is bounded, or 0 when it is unbounded or has more
 * than CONVEX_MAX_FACES faces. "Bounded" is decided with a tolerance that
 * errs toward "unbounded"; the box errs toward larger. An empty bounded
 * polyhedron gets the point box at the origin. */
int convex_bounds(const double *faces, size_t n, double lo[3], double hi[3]);

#endif
