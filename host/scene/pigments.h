/* pigments.h: every kind of pigment of SPEC 3, one table entry each.
 *
 * An entry says how the kind is written (keyword and reader, with
 * positioned errors), what it is on the GPU (TP2_PIGMENT_*, whose color
 * function lives in shaders/pigments.glsl) and how it packs into the GPU
 * pigment record. The kinds, their keywords and GPU ids are listed in
 * shaders/kinds.h (docs/adding-a-kind.md). */
#ifndef TP2_PIGMENTS_H
#define TP2_PIGMENTS_H

#include <stdio.h>

#include "kinds.h"
#include "scene_reader.h"

/* Host kinds, in kinds.h's order; scene_pigment.kind holds one. */
#define TP2_PIGMENT_ENUM_(NAME, keyword, id) PIGMENT_##NAME,
enum pigment { TP2_PIGMENTS(TP2_PIGMENT_ENUM_) PIGMENT_COUNT };
#undef TP2_PIGMENT_ENUM_

/* One pigment as the GPU record holds it (layout.glsl's Pigment), in
 * double until packing. */
struct pigment_record {
    double color1[3], color2[3];
    double slope; /* the kind's slope */
    double p[4], q[4];
    long texture; /* index into scene.textures, or -1 */
};

struct pigment_kind {
    /* From kinds.h. */
    const char *keyword;
    int gpu_kind; /* TP2_PIGMENT_* */
    /* From the kind's KEYWORD_OPS in pigments.c: */
    /* Reads what follows the keyword into pg, each parameter checked with
     * a positioned error; a texmap decodes its image into the scene's
     * textures. 0 or -1. */
    int (*read)(struct scene_reader *r, struct scene_pigment *pg);
    void (*pack)(const struct scene_pigment *pg, struct pigment_record *rec);
    /* Moves a record as pack filled it so that `origin` becomes 0, as
     * shapes.h's move does to objects: the pigment stays where the scene
     * put it. */
    void (*move)(struct pigment_record *rec, const double origin[3]);
    /* Writes its fields for tp2 --dump-scene (scene_json.h): `"a": ...,
     * "b": ...`, without braces. */
    void (*json)(FILE *out, const struct scene *s, const struct scene_pigment *pg);
    /* How fast its color may change along a surface: color units per unit
     * of length, the most of any channel (signature.glsl's steep-pigment
     * test: a hit point off by d has its color off by up to d times this).
     * NULL for none: a solid's color does not change, a checker's cells
     * are decisions of their own. */
    double (*slope)(const struct scene *s, const struct scene_pigment *pg);
    /* Another spelling read the same (texmap_OPS sets it), or NULL. */
    const char *alias;
};

extern const struct pigment_kind pigment_kinds[PIGMENT_COUNT];

/* "'solid', 'checker', 'gradient', 'texmap' or 'textmap'": the keywords,
 * each followed by its alias. */
const char *pigment_keywords(void);

#endif
