/* twins.h: flat faces that float may take for one face while double tells
 * them apart.
 *
 * Where the float pass finds two crossings at exactly the same distance on
 * two flat objects, it takes them for coincident faces (a box on the
 * floor), which double cannot tell apart either (signature.glsl,
 * nearer_unsure). That holds only where the two planes are the same in
 * double too. A box top at 0.3 under a plane at 0.3000000001, or one float
 * step apart, meet rays at the same float distance over whole areas, and
 * double sees the plane first. The host finds such near twins here; their
 * objects carry TP2_SHAPE_NEAR_TWIN, and the float pass marks their equal
 * crossings UNSURE (traced again in double). */
#ifndef TP2_TWINS_H
#define TP2_TWINS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

struct twins;

/* One face of a flat primitive as packed (in the layout's coordinates). */
struct twin_face {
    double plane[4];   /* unit normal, d: n.x + d = 0 */
    uint32_t owner;    /* its scene object: one object's faces are not compared */
    uint32_t slot;     /* its primitive's GPU slot */
    bool met_as_plane; /* shape_kind.met_as_planes */
};

/* Two faces are near when their unit normals differ by at most this in
 * every component and their d by at most this times the scene's scale:
 * float's distances along a ray are good to a few 2^-24 of the distances
 * and coordinates involved, so nearer planes can come out equal in float,
 * and planes this far apart only where they cross (where the neighbouring
 * pixels' different hits mark them anyway). Wider than it needs to be on
 * purpose: the mark costs only where two crossings come out equal. */
#define TWIN_TOLERANCE 0x1p-10

/* A search over faces that others are compared with (a copy of them).
 * scale is the largest coordinate magnitude of the scene's eye, lights,
 * bounded objects and faces. NULL when out of memory. */
struct twins *twins_new(const struct twin_face *faces, size_t n, double scale);

/* Compares face f with the search's faces, marking near[] for f and for
 * each twin of f found: a face of another object whose plane (in either
 * orientation) is near f's but not the same plane, or not met as a plane
 * by both (a triangle's distances come from its corners, so even on the
 * same plane they may round differently). Comparing every face of a
 * scene, the search's own among them, marks every near twin. f may be
 * compared without being in the search (a mesh's million triangles, as
 * they are packed). */
void twins_compare(struct twins *t, const struct twin_face *f, bool *near);

/* Marks near[] for the faces of the search's crowded cells, where a face
 * compared stopped walking (more retracing, never less), and frees t. */
void twins_finish(struct twins *t, bool *near);

#endif
