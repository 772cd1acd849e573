/* obj_read.h: the triangles of a Wavefront OBJ file (SPEC 3, mesh).
 *
 * Reads `v x y z` lines (more numbers after z, such as w or a color, are
 * allowed) and `f` lines of 3 or more vertex references `v`, `v/t`,
 * `v//n` or `v/t/n` (1-based, or negative: counted back from the last
 * vertex so far), fanning each polygon into triangles (v0, vi, vi+1).
 * Every other line is ignored; `#` starts a comment. No Vulkan and no
 * scene here, so it can be tested and fuzzed alone. */
#ifndef TP2_OBJ_READ_H
#define TP2_OBJ_READ_H

#include <stddef.h>
#include <stdio.h>

/* Longest line accepted, in bytes: OBJ lines are short; a longer one is
 * an error, so memory follows the mesh and not the input. */
#define OBJ_MAX_LINE 65536

struct obj_mesh {
    double *tri;   /* 9 numbers per triangle: x y z of its three corners */
    size_t ntri;
    size_t skipped; /* triangles dropped as degenerate (zero area) */
};

/* Reads f, called name in messages. Returns 0 and fills *out (free it with
 * obj_mesh_free), or -1 with *out zeroed and one line in err (cut to
 * errsize bytes): "NAME:LINE:COL: error: ...", "tp2: cannot read 'NAME': REASON"
 * or "tp2: out of memory ...". A file with no faces is not an error here (ntri is 0). */
int obj_read(FILE *f, const char *name, struct obj_mesh *out, char *err,
             size_t errsize);

void obj_mesh_free(struct obj_mesh *m);

#endif
