/* shapes.h: every kind of object of SPEC 3, one table entry each.
 *
 * An entry says how the kind is written (its keyword and reader, with a
 * positioned error for each bad parameter), what it becomes on the GPU
 * (TP2_SHAPE_*, whose hit_ and surface_ functions live in
 * shaders/shapes.glsl), its bounds (or none), and how it packs into the
 * GPU object record. The kinds themselves, their keywords, GPU ids and
 * tiers are listed in shaders/kinds.h (docs/adding-a-kind.md). */
#ifndef TP2_SHAPES_H
#define TP2_SHAPES_H

#include <stdbool.h>
#include <stddef.h>

#include "kinds.h"
#include "scene_reader.h"

/* Host kinds, in kinds.h's order; scene_object.kind holds one. */
#define TP2_SHAPE_ENUM_(NAME, keyword, id, tier, flat) SHAPE_##NAME,
enum shape { TP2_SHAPES(TP2_SHAPE_ENUM_) SHAPE_COUNT };
#undef TP2_SHAPE_ENUM_

/* One primitive as the GPU object record holds it (shaders/layout.glsl's
 * Object): three rows of four numbers, in double until packing, and how
 * many rows of the extra buffer it uses (polyhedron faces; a quadric's
 * reference point). */
struct shape_record {
    double row[3][4];
};

struct shape_kind {
    /* From kinds.h. */
    const char *keyword;
    int gpu_kind; /* TP2_SHAPE_* */
    int tier;     /* TP2_TIER_* */
    bool flat;    /* faces is not NULL */
    /* From the kind's KEYWORD_OPS in shapes.c: */
    /* Reads what follows the keyword, pushing the object's numbers
     * (read_push), each checked with a positioned error. 0 or -1. */
    int (*read)(struct scene_reader *r);
    /* GPU primitives an object of n numbers makes: 1, but a mesh makes
     * one per triangle. */
    size_t (*primitives)(const double *p, size_t n);
    /* Bounds of primitive k, containing it exactly (rounded outward);
     * returns false when it is unbounded (a plane, a quadric other than
     * an ellipsoid, an open polyhedron), which every ray then tests. */
    bool (*bounds)(const double *p, size_t n, size_t k, double lo[3], double hi[3]);
    /* Rows of the extra buffer primitive k needs. */
    size_t (*extra_rows)(const double *p, size_t n);
    /* Fills primitive k's record and its extra rows. */
    void (*pack)(const double *p, size_t n, size_t k, struct shape_record *rec,
                 double (*extra)[4]);
    /* Moves a record and its extra rows, as pack filled them, so that
     * `origin` becomes 0: points lose it, planes (unit normal, d) gain
     * n . origin. Directions and sizes stay. */
    void (*move)(struct shape_record *rec, double (*extra)[4], const double origin[3]);
    /* Flat kinds (flat wherever a ray meets them: shapes.glsl's
     * flat_kind) list the planes of a packed record's faces (unit normal,
     * d: n.x + d = 0) in `planes` (room for TP2_MAX_FACES) and return how
     * many; NULL for curved kinds. Only flat kinds carry TP2_SHAPE_INEXACT
     * and TP2_SHAPE_NEAR_TWIN (twins.h). */
    size_t (*faces)(const struct shape_record *rec, const double (*extra)[4],
                    double (*planes)[4]);
    /* The shader meets each face with plane_t's arithmetic, so that faces
     * on equal planes give equal distances in either precision; a
     * triangle is met through its corners instead. */
    bool met_as_planes;
};

extern const struct shape_kind shape_kinds[SHAPE_COUNT];

/* The largest magnitude among the numbers an object of kind k with numbers
 * p[0..n) packs into (its records and extra rows, as the GPU gets them):
 * lengths, unit vectors and a quadric's coefficients scaled to at most 1.
 * -1 when out of memory. */
double shape_extent(int k, const double *p, size_t n);

/* "'sphere', 'plane', ... or 'mesh'", for "expected ..." messages. */
const char *shape_keywords(void);

#endif
