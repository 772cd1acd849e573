/* scene_pack.c: the parsed scene as the shader's storage buffers. What each
 * kind of object and pigment packs into is in shapes.c and pigments.c;
 * this file orders, counts and converts. */
#include "scene_pack.h"

#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "big_alloc.h"
#include "bvh.h"
#include "clock.h"
#include "float_exact.h"
#include "gpu_layout.h"
#include "pigments.h"
#include "shapes.h"
#include "ties.h"
#include "twins.h"
#include "vec3.h"

/* Fewer bounded objects than this are tested in a plain loop: on
 * lavapipe's 8-wide SIMD the loop beats a divergent tree walk up to about
 * here (measured with --bvh-min, docs/decisions.md). */
#define TP2_BVH_MIN_OBJECTS 16

_Static_assert(TP2_BVH_STACK >= TP2_BVH_MAX_DEPTH,
               "the shader's BVH stack must hold the deepest tree");

/* The camera of SPEC 4: u and v already scaled to the image plane's half
 * width and half height at distance 1 along w. */
struct camera_basis {
    double u[3], v[3], w[3];
};

/* A GPU primitive: primitive k of scene object `object`. */
struct prim_ref {
    size_t object, k;
};

/* A surface given another plane by ties.h: a plane's or a face's row
 * replaced, or a cap met through twin extra row `row`. */
struct tie_entry {
    uint32_t slot, part;
    enum tie_role role;
    size_t row;
    double plane[4];
};

/* Everything both packings share, computed once in double. */
struct layout {
    struct camera_basis cam;
    double origin[3];         /* where the GPU's coordinates start: place_origin */
    bool moved;               /* origin != 0 */
    double eye[3];            /* from origin */
    double scale;             /* layout_scale's, before --precision auto grows the BVH */
    size_t nprims, nbounded;  /* slots [0, nbounded): in BVH order if rays walk it, else in scene order */
    struct prim_ref *slots;   /* slot -> primitive */
    size_t nextra;            /* rows of the extra buffer */
    struct bvh bvh;
    size_t ntexels;
    size_t *texel_offset;     /* per texture: its first texel */
    int bounded_kinds, unbounded_kinds; /* bit TP2_SHAPE_k: kind k among them */
    int samples;
    /* --precision auto's near twins (twins.h): per slot, whether it has
     * one (TP2_SHAPE_NEAR_TWIN); the search, NULL where there is none to
     * find; the object whose faces the float pack compares as it packs
     * them, and room for one primitive's faces. */
    bool *near_twin;
    struct twins *twins;
    size_t twins_streamed;
    double (*twin_planes)[4];
    /* Coincident surfaces (ties.h): entries [tie_first[slot],
     * tie_first[slot + 1]) are slot's; NULL where there are none. */
    struct tie_entry *ties;
    size_t *tie_first;
    int twins_compiled;  /* TP2_SPEC_TWINS: TP2_TWIN_CAPS, TP2_TWIN_TRIANGLES */
    bool slot_keys;      /* no BVH: file order as slot_key's keys */
};

/* The parser has rejected eye == center and up parallel to the view. */
static void camera_basis(const struct scene *s, int width, int height,
                         struct camera_basis *cam)
{
    const double pi = 3.14159265358979323846;
    double d[3];
    vec3_sub(s->center, s->eye, d);
    vec3_unit(d, cam->w);
    vec3_cross(cam->w, s->up, cam->u);
    vec3_unit(cam->u, cam->u);
    vec3_cross(cam->u, cam->w, cam->v);
    double half_h = tan(s->fov * pi / 360.0);
    double half_w = half_h * (double)width / (double)height;
    for (int i = 0; i < 3; i++) {
        cam->u[i] *= half_w;
        cam->v[i] *= half_h;
    }
}

static size_t point_lights(const struct scene *s)
{
    return s->nlights > 0 ? s->nlights - 1 : 0;
}

static int gcd(int a, int b)
{
    while (b) {
        int t = a % b;
        a = b;
        b = t;
    }
    return a;
}

/* The generator g of the rank-1 lattice (k/n, k g/n mod 1): coprime with n
 * (so each row holds one sample) and near n / golden ratio, which spreads
 * the points evenly (a Fibonacci lattice when n is a Fibonacci number). */
static int lattice_generator(int n)
{
    int g = (int)lround(n * 0.6180339887498949);
    for (int d = 0; d < n; d++) {
        if (g - d >= 1 && gcd(g - d, n) == 1)
            return g - d;
        if (g + d < n && gcd(g + d, n) == 1)
            return g + d;
    }
    return 1;
}

static void *alloc_buffer(struct packed_scene *out, int binding, size_t count,
                          size_t elem)
{
    if (count == 0)
        count = 1;
    if (count > SIZE_MAX / elem)
        return NULL;
    out->size[binding] = count * elem;
    out->data[binding] = big_calloc(count, elem);
    return out->data[binding];
}

/* rgb (black if NULL) and a fourth value. */
static void put_color(float dst[4], const double *rgb, double w)
{
    for (int i = 0; i < 3; i++)
        dst[i] = rgb ? (float)rgb[i] : 0.0f;
    dst[3] = (float)w;
}

/* SPEC 3: all three coefficients zero means no attenuation. */
static void put_attenuation(float dst[4], const double att[3])
{
    bool none = att[0] == 0 && att[1] == 0 && att[2] == 0;
    dst[0] = none ? 1.0f : (float)att[0];
    dst[1] = (float)att[1];
    dst[2] = (float)att[2];
    dst[3] = 0.0f;
}

static void put_finish(float phong[4], float optics[4], const struct scene_finish *f)
{
    const float p[4] = {(float)f->ka, (float)f->kd, (float)f->ks, (float)f->n};
    const float o[4] = {(float)f->kr, (float)f->kt, (float)f->ior, 0.0f};
    memcpy(phong, p, sizeof p);
    memcpy(optics, o, sizeof o);
}

/* Pigment i's record, texture resolved to texel offset and size. */
static void pigment_record(const struct scene *s, const struct layout *lay, size_t i,
                           struct pigment_record *rec, int32_t kind[4])
{
    const struct scene_pigment *pg = &s->pigments[i];
    memset(rec, 0, sizeof *rec);
    rec->texture = -1;
    pigment_kinds[pg->kind].pack(pg, rec);
    rec->slope = pigment_kinds[pg->kind].slope ? pigment_kinds[pg->kind].slope(s, pg) : 0;
    if (lay->moved)
        pigment_kinds[pg->kind].move(rec, lay->origin);
    kind[0] = pigment_kinds[pg->kind].gpu_kind;
    if (rec->texture >= 0) {
        const struct scene_texture *t = &s->textures[rec->texture];
        kind[1] = (int32_t)lay->texel_offset[rec->texture];
        kind[2] = t->width;
        kind[3] = t->height;
    }
}

/* Starts loading what object_record will read for a slot PREFETCH_AHEAD
 * slots on: slots are in BVH order, so the objects and their numbers are
 * read in no order, and each read waited on memory. The object's record
 * first, its numbers at half that distance (by then the record is in). */
#define PREFETCH_AHEAD 32
static void prefetch_slot(const struct scene *s, const struct layout *lay, size_t slot)
{
    size_t far = slot + PREFETCH_AHEAD, near = slot + PREFETCH_AHEAD / 2;
    if (far < lay->nprims)
        __builtin_prefetch(&s->objects[lay->slots[far].object]);
    if (near < lay->nprims)
        __builtin_prefetch(scene_object_reals(s, &s->objects[lay->slots[near].object]));
}

/* Slot's file-order key without a BVH (tp2_shared.h, TP2_SHAPE_ORDER_SHIFT):
 * 2 slot + 1 for a bounded primitive; 2 b for an unbounded one, b the
 * bounded primitives of objects listed before it (the bounded slots are
 * in scene order then: order_bounded). */
static size_t slot_key(const struct layout *lay, size_t slot)
{
    if (slot < lay->nbounded)
        return 2 * slot + 1;
    size_t object = lay->slots[slot].object, lo = 0, hi = lay->nbounded;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (lay->slots[mid].object < object)
            lo = mid + 1;
        else
            hi = mid;
    }
    return 2 * lo;
}

/* Primitive slot's record and its extra rows, whose first is *extra_at. */
static void object_record(const struct scene *s, const struct layout *lay, size_t slot,
                          struct shape_record *rec, double (*extra)[4], size_t *extra_at,
                          int32_t ids[4])
{
    const struct prim_ref *ref = &lay->slots[slot];
    const struct scene_object *o = &s->objects[ref->object];
    const struct shape_kind *kind = &shape_kinds[o->kind];
    const double *p = scene_object_reals(s, o);
    memset(rec, 0, sizeof *rec);
    size_t key = lay->slot_keys ? slot_key(lay, slot) : ref->object;
    uint32_t order = key < TP2_ORDER_MAX ? (uint32_t)key : TP2_ORDER_MAX;
    ids[0] = (int32_t)((uint32_t)kind->gpu_kind | order << TP2_SHAPE_ORDER_SHIFT);
    ids[1] = (int32_t)o->pigment;
    ids[2] = (int32_t)o->finish;
    ids[3] = (int32_t)*extra_at;
    kind->pack(p, o->count, ref->k, rec, extra + *extra_at);
    *extra_at += kind->extra_rows(p, o->count);
}

/* Whether every number of a record and its extra rows is a float exactly
 * (TP2_SHAPE_INEXACT). */
static bool record_is_float(const struct shape_record *rec, const double (*extra)[4],
                            size_t nextra)
{
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 4; c++)
            if (!is_float(rec->row[r][c]))
                return false;
    for (size_t r = 0; r < nextra; r++)
        for (int c = 0; c < 4; c++)
            if (!is_float(extra[r][c]))
                return false;
    return true;
}

/* Slot's record and extra rows moved so that the layout's origin is 0. */
static void move_record(const struct scene *s, const struct layout *lay, size_t slot,
                        struct shape_record *rec, double (*extra)[4])
{
    const struct scene_object *o = &s->objects[lay->slots[slot].object];
    shape_kinds[o->kind].move(rec, extra, lay->origin);
}

/* A cylinder or cone turned over: its top becomes its base. */
static void turn_over(struct shape_record *rec, int kind)
{
    double *base = rec->row[0], *axis = rec->row[1];
    for (int a = 0; a < 3; a++) {
        base[a] += axis[3] * axis[a];
        axis[a] = -axis[a];
    }
    if (kind == TP2_SHAPE_CONE) {
        double r = base[3];
        base[3] = rec->row[2][0];
        rec->row[2][0] = r;
    }
}

/* Slot's surfaces that ties.h gave another plane, in its packed record
 * (moved), its extra rows and ids; a triangle's twin row goes into all_rows
 * where given (the whole extra buffer). Where the scene has twin caps
 * (TP2_TWIN_CAPS), every cylinder and cone keeps its base's place along
 * its axis in c.y, where shaders/shapes.glsl, hit_tapered, meets each cap
 * as a plane. A twin cap is made the base, its axis its face's normal,
 * turned its way (they differ by the tolerance at most), and its place
 * the face's, so that the cap is met by plane_cross's arithmetic on that
 * face. */
static void apply_ties(const struct layout *lay, size_t slot, struct shape_record *rec,
                       double (*extra)[4], int32_t ids[4], double (*all_rows)[4])
{
    int kind = ids[0] & TP2_SHAPE_MASK;
    bool twin_cap = false;
    size_t first = lay->tie_first ? lay->tie_first[slot] : 0;
    size_t end = lay->tie_first ? lay->tie_first[slot + 1] : 0;
    for (size_t e = first; e < end; e++) {
        const struct tie_entry *t = &lay->ties[e];
        if (t->role == TIE_PLANE) {
            memcpy(rec->row[0], t->plane, sizeof t->plane);
        } else if (t->role == TIE_FACE) {
            memcpy(extra[t->part], t->plane, sizeof t->plane);
        } else if (t->role == TIE_CAP) {
            if (t->part == 2)
                turn_over(rec, kind);
            double *axis = rec->row[1];
            double sign = vec3_dot(axis, t->plane) < 0 ? -1 : 1;
            for (int a = 0; a < 3; a++)
                axis[a] = sign * t->plane[a];
            rec->row[2][1] = -sign * t->plane[3] + 0.0; /* no -0 */
            twin_cap = true;
        } else {
            ids[0] |= TP2_SHAPE_TWIN;
            ids[3] = (int32_t)t->row;
            if (all_rows)
                memcpy(all_rows[t->row], t->plane, sizeof t->plane);
        }
    }
    if ((kind == TP2_SHAPE_CYLINDER || kind == TP2_SHAPE_CONE) && !twin_cap &&
        (lay->twins_compiled & TP2_TWIN_CAPS))
        rec->row[2][1] = vec3_dot(rec->row[1], rec->row[0]);
}

/* The largest coordinate magnitude of the eye, the lights and the
 * bounded objects' box, from the layout's origin (twins.h's scale). */
static double layout_scale(const struct scene *s, const struct layout *lay)
{
    double m = vec3_max_abs(lay->eye);
    for (size_t i = 1; i < s->nlights; i++) {
        double pos[3];
        vec3_sub(s->lights[i].pos, lay->origin, pos);
        m = fmax(m, vec3_max_abs(pos));
    }
    if (lay->bvh.node_count > 0)
        for (int a = 0; a < 3; a++)
            m = fmax(m, fmax(fabs(lay->bvh.nodes[0].lo[a]), fabs(lay->bvh.nodes[0].hi[a])));
    return m;
}

/* The faces of a packed flat primitive, in lay->twin_planes; how many. */
static size_t packed_faces(const struct scene *s, const struct layout *lay, size_t slot,
                           const struct shape_record *rec, const double (*extra)[4],
                           struct twin_face *face)
{
    size_t owner = lay->slots[slot].object;
    const struct shape_kind *kind = &shape_kinds[s->objects[owner].kind];
    *face = (struct twin_face){.owner = (uint32_t)owner, .slot = (uint32_t)slot,
                               .met_as_plane = kind->met_as_planes};
    return kind->faces(rec, extra, lay->twin_planes);
}

/* Compares a packed primitive of the streamed object with the search. */
static void compare_packed(const struct scene *s, const struct layout *lay, size_t slot,
                           const struct shape_record *rec, const double (*extra)[4])
{
    struct twin_face f;
    size_t count = packed_faces(s, lay, slot, rec, extra, &f);
    for (size_t i = 0; i < count; i++) {
        memcpy(f.plane, lay->twin_planes[i], sizeof f.plane);
        twins_compare(lay->twins, &f, lay->near_twin);
    }
}

/* The surfaces of primitive k of `object` (GPU slot `slot`) that may
 * coincide with another object's (ties.h), packed and moved to `origin`
 * (unless NULL), appended to *list; -1 when out of memory. */
static int prim_surfaces(const struct scene *s, size_t object, size_t k, size_t slot,
                         const double *origin, double (*rows)[4], struct tie_surface **list,
                         size_t *n, size_t *cap)
{
    const struct scene_object *o = &s->objects[object];
    const struct shape_kind *kd = &shape_kinds[o->kind];
    int kind = kd->gpu_kind;
    if (kind != TP2_SHAPE_PLANE && kind != TP2_SHAPE_POLYHEDRON && kind != TP2_SHAPE_BOX &&
        kind != TP2_SHAPE_CYLINDER && kind != TP2_SHAPE_CONE && kind != TP2_SHAPE_TRIANGLE)
        return 0;
    struct shape_record rec;
    memset(&rec, 0, sizeof rec);
    kd->pack(scene_object_reals(s, o), o->count, k, &rec, rows);
    if (origin)
        kd->move(&rec, rows, origin);
    struct tie_surface t[6];
    size_t count = 0;
    const double *r0 = rec.row[0], *r1 = rec.row[1];
    if (kind == TP2_SHAPE_TRIANGLE) {
        double planes[1][4];
        shape_kinds[s->objects[object].kind].faces(&rec, NULL, planes);
        t[count++] = (struct tie_surface){{planes[0][0], planes[0][1], planes[0][2],
                                           planes[0][3]}, 0, 1, 0, TIE_TRIANGLE};
    } else if (kind == TP2_SHAPE_PLANE) {
        t[count++] = (struct tie_surface){{r0[0], r0[1], r0[2], r0[3]}, 0, 0, 0, TIE_PLANE};
    } else if (kind == TP2_SHAPE_BOX) {
        double planes[6][4];
        count = shape_kinds[s->objects[object].kind].faces(&rec, NULL, planes);
        for (size_t i = 0; i < count; i++)
            t[i] = (struct tie_surface){{planes[i][0], planes[i][1], planes[i][2], planes[i][3]},
                                        0, 0, 0, TIE_FIXED};
    } else if (kind == TP2_SHAPE_CYLINDER || kind == TP2_SHAPE_CONE) {
        double along = r0[0] * r1[0] + r0[1] * r1[1] + r0[2] * r1[2];
        double top_radius = kind == TP2_SHAPE_CONE ? rec.row[2][0] : r0[3];
        if (r0[3] > 0)
            t[count++] = (struct tie_surface){{-r1[0], -r1[1], -r1[2], along}, 0, 1, 0, TIE_CAP};
        if (top_radius > 0)
            t[count++] = (struct tie_surface){{r1[0], r1[1], r1[2], -(along + r1[3])}, 0, 2, 0,
                                              TIE_CAP};
    }
    size_t faces = kind == TP2_SHAPE_POLYHEDRON ? (size_t)r0[0] : count;
    if (*n + faces > *cap) {
        size_t more = 2 * *cap + faces + 64;
        struct tie_surface *grown = realloc(*list, more * sizeof *grown);
        if (!grown)
            return -1;
        *list = grown;
        *cap = more;
    }
    for (size_t i = 0; i < faces; i++) {
        struct tie_surface f = kind == TP2_SHAPE_POLYHEDRON
                                   ? (struct tie_surface){{rows[i][0], rows[i][1], rows[i][2],
                                                           rows[i][3]}, 0, (uint32_t)i, 0,
                                                          TIE_FACE}
                                   : t[i];
        f.slot = (uint32_t)slot;
        f.object = object;
        (*list)[(*n)++] = f;
    }
    return 0;
}

static int slot_surfaces(const struct scene *s, const struct layout *lay, size_t slot,
                         double (*rows)[4], struct tie_surface **list, size_t *n,
                         size_t *cap)
{
    const struct prim_ref *ref = &lay->slots[slot];
    return prim_surfaces(s, ref->object, ref->k, slot, lay->moved ? lay->origin : NULL, rows,
                         list, n, cap);
}

/* Which of caps and triangles may lie in another object's surface
 * (*found: TP2_TWIN_CAPS, TP2_TWIN_TRIANGLES), found in the scene's own
 * coordinates before the layout, with room for the move to its origin:
 * the shaders' code for twin caps, and apart from it for twin triangles,
 * is compiled only then (TP2_SPEC_TWINS), as lavapipe runs it for every
 * object of the kinds tested where a kind is not known (a mesh's
 * triangles run a cylinder's test). -1 when out of memory. */
static int early_twins(const struct scene *s, int *found)
{
    *found = 0;
    double (*rows)[4] = malloc(TP2_MAX_FACES * sizeof *rows);
    struct tie_surface *list = NULL;
    size_t n = 0, cap = 0;
    int rc = rows ? 0 : -1;
    bool curved = false;
    for (size_t i = 0; rc == 0 && i < s->nobjects; i++) {
        int kind = shape_kinds[s->objects[i].kind].gpu_kind;
        curved |= kind == TP2_SHAPE_CYLINDER || kind == TP2_SHAPE_CONE ||
                  kind == TP2_SHAPE_TRIANGLE;
        if (kind != TP2_SHAPE_TRIANGLE)
            rc = prim_surfaces(s, i, 0, 0, NULL, rows, &list, &n, &cap);
    }
    double scale = vec3_max_abs(s->eye);
    for (size_t i = 0; i < n; i++)
        scale = fmax(scale, fabs(list[i].plane[3]));
    scale *= 16; /* the move changes d by its rounding */
    if (rc == 0 && curved && n > 0) {
        ties_sort(list, n);
        for (size_t i = 0; i < n && !(*found & TP2_TWIN_CAPS); i++)
            if (list[i].role == TIE_CAP &&
                ties_near(list, n, list[i].plane, scale, list[i].object))
                *found |= TP2_TWIN_CAPS;
        for (size_t i = 0; rc == 0 && i < s->nobjects && !(*found & TP2_TWIN_TRIANGLES); i++) {
            const struct scene_object *o = &s->objects[i];
            if (shape_kinds[o->kind].gpu_kind != TP2_SHAPE_TRIANGLE)
                continue;
            size_t prims = shape_kinds[o->kind].primitives(scene_object_reals(s, o), o->count);
            for (size_t k = 0; rc == 0 && k < prims && !(*found & TP2_TWIN_TRIANGLES); k++) {
                size_t before = n;
                rc = prim_surfaces(s, i, k, 0, NULL, rows, &list, &n, &cap);
                if (rc == 0 && ties_near(list, before, list[before].plane, scale, i))
                    *found |= TP2_TWIN_TRIANGLES;
                n = before;
            }
        }
    }
    free(rows);
    free(list);
    return rc;
}

static int by_slot(const void *x, const void *y)
{
    const struct tie_entry *a = x, *b = y;
    return a->slot != b->slot ? (a->slot < b->slot ? -1 : 1)
                              : a->part < b->part ? -1 : a->part > b->part;
}

/* Finds the coincident surfaces (ties.h) and what each becomes
 * (lay->ties); a triangle's twin rows are added to the extra buffer's end.
 * Nothing to do without a plane, a polyhedron, a cylinder, a cone or a
 * triangle. A triangle is compared only with the other kinds' surfaces:
 * two meshes lying in one plane keep their own distances. */
static int find_ties(const struct scene *s, struct layout *lay)
{
    int kinds = lay->bounded_kinds | lay->unbounded_kinds;
    int changeable = 1 << TP2_SHAPE_PLANE | 1 << TP2_SHAPE_POLYHEDRON |
                     1 << TP2_SHAPE_CYLINDER | 1 << TP2_SHAPE_CONE | 1 << TP2_SHAPE_TRIANGLE;
    if (!(kinds & changeable) || s->nobjects < 2)
        return 0;
    if (lay->nprims > UINT32_MAX)
        return 0;
    double (*rows)[4] = malloc(TP2_MAX_FACES * sizeof *rows);
    struct tie_surface *list = NULL;
    size_t n = 0, cap = 0;
    int rc = rows ? 0 : -1;
    /* The other kinds' surfaces first, then the triangles that lie in one */
    for (size_t slot = 0; rc == 0 && slot < lay->nprims; slot++)
        if (shape_kinds[s->objects[lay->slots[slot].object].kind].gpu_kind != TP2_SHAPE_TRIANGLE)
            rc = slot_surfaces(s, lay, slot, rows, &list, &n, &cap);
    size_t others = n;
    if (rc == 0 && others > 0 && (kinds & 1 << TP2_SHAPE_TRIANGLE))
        ties_sort(list, others);
    for (size_t slot = 0; rc == 0 && others > 0 && slot < lay->nprims; slot++)
        if (shape_kinds[s->objects[lay->slots[slot].object].kind].gpu_kind == TP2_SHAPE_TRIANGLE) {
            size_t before = n;
            rc = slot_surfaces(s, lay, slot, rows, &list, &n, &cap);
            if (rc == 0 &&
                !ties_near(list, others, list[before].plane, lay->scale, SIZE_MAX))
                n = before;
        }
    free(rows);
    double (*canonical)[4] = malloc((n ? n : 1) * sizeof *canonical);
    bool *twin = malloc((n ? n : 1) * sizeof *twin);
    if (rc == 0 && (!canonical || !twin))
        rc = -1;
    if (rc == 0)
        rc = ties_group(list, n, lay->scale, canonical, twin);
    for (size_t i = 0; rc == 0 && i < n; i++)
        twin[i] &= list[i].role == TIE_CAP        ? (lay->twins_compiled & TP2_TWIN_CAPS) != 0
                   : list[i].role == TIE_TRIANGLE ? (lay->twins_compiled & TP2_TWIN_TRIANGLES) != 0
                                                  : true;
    size_t m = 0;
    for (size_t i = 0; rc == 0 && i < n; i++)
        if (twin[i] && list[i].role != TIE_FIXED &&
            (list[i].role >= TIE_CAP || memcmp(canonical[i], list[i].plane, sizeof canonical[i])))
            m++;
    if (rc == 0 && m > 0) {
        lay->ties = malloc(m * sizeof *lay->ties);
        lay->tie_first = calloc(lay->nprims + 1, sizeof *lay->tie_first);
        if (!lay->ties || !lay->tie_first)
            rc = -1;
    }
    if (rc == 0 && m > 0) {
        size_t e = 0;
        for (size_t i = 0; i < n; i++)
            if (twin[i] && list[i].role != TIE_FIXED &&
                (list[i].role >= TIE_CAP ||
                 memcmp(canonical[i], list[i].plane, sizeof canonical[i]))) {
                lay->ties[e] = (struct tie_entry){list[i].slot, list[i].part, list[i].role, 0,
                                                  {0}};
                memcpy(lay->ties[e].plane, canonical[i], sizeof canonical[i]);
                e++;
            }
        qsort(lay->ties, m, sizeof *lay->ties, by_slot);
        /* One twin per cap or triangle: a cylinder standing on one face
         * and touching another with its top keeps its base's (its record
         * holds one plane: a cylinder's test costs less); a triangle's
         * plane goes to a twin row of its own. */
        size_t kept = 0;
        for (e = 0; e < m; e++) {
            struct tie_entry t = lay->ties[e];
            if (t.role >= TIE_CAP && kept > 0 && lay->ties[kept - 1].slot == t.slot &&
                lay->ties[kept - 1].role >= TIE_CAP)
                continue;
            if (t.role == TIE_TRIANGLE)
                t.row = lay->nextra++;
            lay->ties[kept++] = t;
            lay->tie_first[t.slot + 1]++;
        }
        for (size_t slot = 0; slot < lay->nprims; slot++)
            lay->tie_first[slot + 1] += lay->tie_first[slot];
    }
    free(list);
    free(canonical);
    free(twin);
    return rc;
}

/* Starts the search for near twins (twins.h): every flat object's faces
 * go into it, but the faces of the one of most primitives (a mesh of a
 * million triangles), which the float pack compares as it packs them
 * (twins_streamed); the others are compared here. With fewer than two
 * flat objects there is nothing to find, and no search. */
static int twins_start(const struct scene *s, struct layout *lay)
{
    size_t *prims = calloc(s->nobjects ? s->nobjects : 1, sizeof *prims);
    size_t flat = 0, streamed = 0;
    if (!prims)
        return -1;
    for (size_t slot = 0; slot < lay->nprims; slot++) {
        size_t o = lay->slots[slot].object;
        if (shape_kinds[s->objects[o].kind].faces) {
            flat += prims[o]++ == 0;
            if (prims[o] > prims[streamed])
                streamed = o;
        }
    }
    free(prims);
    if (flat < 2)
        return 0;
    lay->twins_streamed = streamed;
    lay->near_twin = calloc(lay->nprims, sizeof *lay->near_twin);
    /* an object's extra rows (at most a polyhedron's faces), its planes */
    double (*rows)[4] = malloc(TP2_MAX_FACES * sizeof *rows);
    lay->twin_planes = malloc(TP2_MAX_FACES * sizeof *lay->twin_planes);
    struct twin_face *faces = NULL;
    size_t n = 0, cap = 0;
    double scale = lay->scale;
    int rc = lay->near_twin && rows && lay->twin_planes ? 0 : -1;
    for (size_t slot = 0; rc == 0 && slot < lay->nprims; slot++) {
        size_t o = lay->slots[slot].object;
        if (!shape_kinds[s->objects[o].kind].faces || o == streamed)
            continue;
        struct shape_record rec;
        size_t extra_at = 0;
        int32_t ids[4];
        object_record(s, lay, slot, &rec, rows, &extra_at, ids);
        if (lay->moved)
            move_record(s, lay, slot, &rec, rows);
        apply_ties(lay, slot, &rec, rows, ids, NULL);
        struct twin_face f;
        size_t count = packed_faces(s, lay, slot, &rec, (const double (*)[4])rows, &f);
        if (n + count > cap) {
            size_t more = 2 * cap + count + 64;
            struct twin_face *grown = realloc(faces, more * sizeof *faces);
            if (!grown) {
                rc = -1;
                break;
            }
            faces = grown;
            cap = more;
        }
        for (size_t i = 0; i < count; i++) {
            memcpy(f.plane, lay->twin_planes[i], sizeof f.plane);
            faces[n++] = f;
        }
    }
    for (size_t i = 0; i < n; i++)
        scale = fmax(scale, fabs(faces[i].plane[3]));
    if (rc == 0 && !(lay->twins = twins_new(faces, n, scale)))
        rc = -1;
    for (size_t i = 0; rc == 0 && i < n; i++)
        twins_compare(lay->twins, &faces[i], lay->near_twin);
    free(faces);
    free(rows);
    return rc;
}

/* Ends the search: TP2_SHAPE_NEAR_TWIN on every slot that has a near twin
 * in the float scene `objects`. */
static void twins_end(struct layout *lay, struct gpu_object_f *objects)
{
    if (!lay->twins)
        return;
    twins_finish(lay->twins, lay->near_twin);
    lay->twins = NULL;
    for (size_t slot = 0; objects && slot < lay->nprims; slot++)
        if (lay->near_twin[slot])
            objects[slot].ids[0] |= TP2_SHAPE_NEAR_TWIN;
}

#define TP2_REAL float
#define TP2_SUFFIX _f
#include "scene_pack_types.inc"
#undef TP2_REAL
#undef TP2_SUFFIX

#define TP2_REAL double
#define TP2_SUFFIX _d
#include "scene_pack_types.inc"
#undef TP2_REAL
#undef TP2_SUFFIX

/* Features of the objects actually in the scene (an unused finish with
 * kr > 0 costs nothing). */
static struct scene_features scene_features(const struct scene *s, int samples)
{
    struct scene_features f = {
        .fog = s->has_fog && s->fog_density > 0,
        .lens = s->has_lens && s->lens_radius > 0,
        .area = s->has_arealight,
        .samples = samples,
    };
    for (size_t i = 0; i < s->nobjects; i++) {
        const struct scene_object *o = &s->objects[i];
        f.reflect |= s->finishes[o->finish].kr > 0;
        f.refract |= s->finishes[o->finish].kt > 0;
        f.pigments |= 1 << pigment_kinds[s->pigments[o->pigment].kind].gpu_kind;
        f.shapes |= 1 << shape_kinds[o->kind].gpu_kind;
    }
    return f;
}

/* The kind whose bit alone is set in kinds, else -1. */
static int single_kind(int kinds)
{
    for (int k = 0; k < 31; k++)
        if (kinds == 1 << k)
            return k;
    return -1;
}

/* The bounded primitives, whose boxes bvh_build_from asks for one by one. */
struct bounded_prims {
    const struct scene *s;
    const struct prim_ref *refs;
};

static void bounded_box(const void *source, size_t i, double box[6])
{
    const struct bounded_prims *b = source;
    const struct prim_ref *ref = &b->refs[i];
    const struct scene_object *o = &b->s->objects[ref->object];
    shape_kinds[o->kind].bounds(scene_object_reals(b->s, o), o->count, ref->k, box, box + 3);
}

/* Slots: every object's primitives, the bounded ones first (in scene
 * order until order_bounded puts them in the BVH's), then the unbounded
 * ones in scene order. `bounded` gets the bounded ones' references. */
static int classify_objects(const struct scene *s, struct layout *lay,
                            struct prim_ref **bounded)
{
    lay->nprims = 0;
    for (size_t i = 0; i < s->nobjects; i++) {
        const struct scene_object *o = &s->objects[i];
        const struct shape_kind *kind = &shape_kinds[o->kind];
        const double *p = scene_object_reals(s, o);
        lay->nprims += kind->primitives(p, o->count);
        lay->nextra += kind->extra_rows(p, o->count);
    }
    size_t n = lay->nprims ? lay->nprims : 1;
    *bounded = big_alloc(n * sizeof **bounded);
    lay->slots = big_alloc(n * sizeof *lay->slots);
    if (!*bounded || !lay->slots)
        return -1;
    size_t nb = 0, nu = lay->nprims;
    for (size_t i = 0; i < s->nobjects; i++) {
        const struct scene_object *o = &s->objects[i];
        const struct shape_kind *kind = &shape_kinds[o->kind];
        const double *p = scene_object_reals(s, o);
        size_t count = kind->primitives(p, o->count);
        for (size_t k = 0; k < count; k++) {
            struct prim_ref ref = {i, k};
            double lo[3], hi[3]; /* asked for again by the build */
            if (kind->bounds(p, o->count, k, lo, hi)) {
                (*bounded)[nb++] = ref;
                lay->bounded_kinds |= 1 << kind->gpu_kind;
            } else {
                lay->slots[--nu] = ref; /* filled from the end */
                lay->unbounded_kinds |= 1 << kind->gpu_kind;
            }
        }
    }
    /* The unbounded came in reverse: restore scene order. */
    for (size_t a = nb, b = lay->nprims; a + 1 < b; a++, b--) {
        struct prim_ref t = lay->slots[a];
        lay->slots[a] = lay->slots[b - 1];
        lay->slots[b - 1] = t;
    }
    lay->nbounded = nb;
    return 0;
}

/* Where the GPU's coordinates start. Float rounds a number by a share of
 * its size, so a scene written far from 0 (a small scene at 1e4, the
 * camera near it) would lose its positions to 1e-3 there: such a scene is
 * moved to near 0 along each axis where its span (the eye and the bounded
 * primitives) lies further from 0 than it is wide, by a multiple of a power
 * of two at least that wide. Points then differ from the origin exactly
 * in double as a rule, and the origin is a float, so that a point on a
 * checker's cell face stays on it when the checker adds it back
 * (pigments.c). Elsewhere the origin is 0, and nothing changes (moving a
 * scene around 0 to its eye made float worse: objects near 0 then rounded
 * at their distance). */
static void place_origin(const struct scene *s, struct layout *lay)
{
    lay->moved = false;
    memcpy(lay->eye, s->eye, sizeof lay->eye);
    if (lay->bvh.node_count == 0)
        return; /* only unbounded objects: nothing says where the scene is */
    double span[6]; /* the eye's point and the BVH's root box */
    for (int a = 0; a < 3; a++) {
        span[a] = fmin(s->eye[a], lay->bvh.nodes[0].lo[a]);
        span[a + 3] = fmax(s->eye[a], lay->bvh.nodes[0].hi[a]);
    }
    double width = 0;
    for (int a = 0; a < 3; a++)
        width = fmax(width, span[a + 3] - span[a]);
    if (!(width > 0))
        return;
    double step = exp2(ceil(log2(width)));
    for (int a = 0; a < 3; a++) {
        double mid = (span[a] + span[a + 3]) / 2;
        lay->origin[a] = fabs(mid) > width ? (float)(round(mid / step) * step) : 0.0f;
        lay->eye[a] = s->eye[a] - lay->origin[a];
        lay->moved |= lay->origin[a] != 0;
    }
    if (lay->moved)
        bvh_move(&lay->bvh, lay->origin);
}

/* Builds the BVH over the bounded primitives and puts their slots in its
 * order. If rays do not walk it (!use), the slots are then sorted by
 * object, stably: in scene order, so that the shader's plain loop decides
 * a tie between two objects by their slots (shaders/intersect.glsl,
 * trace_plain), and one object's primitives (a mesh's triangles) in the
 * BVH's order still, so that a tie between two of them goes the same way
 * with or without the BVH. The tree, its root box aside, is then not
 * read. */
static int order_bounded(const struct scene *s, struct layout *lay,
                         const struct prim_ref *bounded, bool use, double *bvh_time)
{
    double t0 = clock_seconds();
    struct bounded_prims source = {s, bounded};
    int built = bvh_build_from(bounded_box, &source, lay->nbounded, &lay->bvh);
    *bvh_time = clock_seconds() - t0;
    if (built != 0)
        return -1;
    if (use || lay->nbounded == 0) {
        for (size_t slot = 0; slot < lay->nbounded; slot++)
            lay->slots[slot] = bounded[lay->bvh.order[slot]];
        return 0;
    }
    size_t *first = calloc(s->nobjects + 1, sizeof *first); /* counting sort */
    if (!first)
        return -1;
    for (size_t b = 0; b < lay->nbounded; b++)
        first[bounded[b].object + 1]++;
    for (size_t i = 0; i < s->nobjects; i++)
        first[i + 1] += first[i];
    for (size_t slot = 0; slot < lay->nbounded; slot++) {
        struct prim_ref ref = bounded[lay->bvh.order[slot]];
        lay->slots[first[ref.object]++] = ref;
    }
    free(first);
    return 0;
}

/* Each texture's first texel in the texel buffer. */
static int layout_texels(const struct scene *s, struct layout *lay)
{
    lay->texel_offset = malloc((s->ntextures ? s->ntextures : 1) * sizeof *lay->texel_offset);
    if (!lay->texel_offset)
        return -1;
    for (size_t i = 0; i < s->ntextures; i++) {
        lay->texel_offset[i] = lay->ntexels;
        lay->ntexels += (size_t)s->textures[i].width * (size_t)s->textures[i].height;
    }
    return 0;
}

static int pack_texels(const struct scene *s, const struct layout *lay,
                       struct packed_scene *out)
{
    uint32_t *texels = alloc_buffer(out, TP2_BINDING_TEXELS, lay->ntexels, sizeof *texels);
    if (!texels)
        return -1;
    for (size_t i = 0; i < s->ntextures; i++) {
        const struct scene_texture *t = &s->textures[i];
        size_t n = (size_t)t->width * (size_t)t->height;
        uint32_t *dst = texels + lay->texel_offset[i];
        for (size_t j = 0; j < n; j++)
            dst[j] = (uint32_t)t->rgb[3 * j] | (uint32_t)t->rgb[3 * j + 1] << 8 |
                     (uint32_t)t->rgb[3 * j + 2] << 16;
    }
    return 0;
}

static int pack_bvh(const struct bvh *b, struct packed_scene *out)
{
    struct bvh_gpu_node *nodes =
        alloc_buffer(out, TP2_BINDING_BVH, bvh_gpu_count(b), sizeof *nodes);
    return nodes ? bvh_gpu_nodes(b, nodes) : -1;
}

/* From this many BVH nodes up, they are packed on a thread beside the
 * objects (a million spheres' nodes, 52 MB, took 0.12-0.2 s to pack). */
#define PACK_NODES_BESIDE ((size_t)1 << 14)

/* A part of the packing run on a thread of its own beside the rest (or
 * in place, where no thread can be made): the double twin, the BVH's
 * nodes. Each writes its own buffers only. */
struct side_job {
    const struct scene *s;
    const struct layout *lay;
    const struct pack_options *opt;
    struct packed_scene *into;
    int rc;
    pthread_t thread;
    bool threaded; /* rc and threaded stay 0 for a job never started */
};

static void *pack_twin(void *arg)
{
    struct side_job *job = arg;
    job->rc = pack_d(job->s, job->lay, job->opt, job->into);
    return NULL;
}

static void *pack_nodes(void *arg)
{
    struct side_job *job = arg;
    job->rc = pack_bvh(&job->lay->bvh, job->into);
    return NULL;
}

static void side_start(struct side_job *job, void *(*fn)(void *))
{
    job->threaded = pthread_create(&job->thread, NULL, fn, job) == 0;
    if (!job->threaded)
        fn(job);
}

/* The job's result; 0 if it was never started. */
static int side_join(struct side_job *job)
{
    if (job->threaded)
        pthread_join(job->thread, NULL);
    return job->rc;
}

int scene_pack(const struct scene *s, const struct pack_options *opt,
               struct packed_scene *out, struct packed_scene *twin)
{
    memset(out, 0, sizeof *out);
    if (twin)
        memset(twin, 0, sizeof *twin);
    struct layout lay = {.samples = opt->samples ? opt->samples
                                    : s->has_samples ? s->samples : 1};
    camera_basis(s, opt->width, opt->height, &lay.cam);
    struct prim_ref *bounded = NULL;
    int rc = classify_objects(s, &lay, &bounded);
    out->features = scene_features(s, lay.samples);
    out->features.bounded_shape = single_kind(lay.bounded_kinds);
    out->features.unbounded_shape = single_kind(lay.unbounded_kinds);
    /* The bounded objects' one kind, known beside unbounded ones of
     * several kinds, made the shader slower, not faster (docs/design.md): then neither is known. */
    if (lay.unbounded_kinds != 0 && out->features.unbounded_shape < 0)
        out->features.bounded_shape = -1;
    int bvh_min = opt->bvh_min ? opt->bvh_min : TP2_BVH_MIN_OBJECTS;
    out->features.bvh = lay.nbounded >= (size_t)bvh_min;
    /* Not under mixed (a twin): its float pass's edge marks depend on
     * the order objects are tested in, which the BVH's keeps as a loop's
     * (check_effects.py, grown_boxes_mark_as_loop). */
    lay.slot_keys = !out->features.bvh && !twin;
    out->features.scene_slots = lay.slot_keys;
    if (rc == 0)
        rc = early_twins(s, &lay.twins_compiled);
    out->features.twins = lay.twins_compiled;
    out->bounded = lay.nbounded;
    out->unbounded = lay.nprims - lay.nbounded;
    if (rc == 0 && opt->features_known)
        opt->features_known(&out->features, opt->user);
    if (rc == 0)
        rc = order_bounded(s, &lay, bounded, !lay.slot_keys, &out->bvh_time);
    if (rc == 0) {
        place_origin(s, &lay);
        lay.scale = layout_scale(s, &lay);
    }
    free(bounded);
    if (rc == 0)
        rc = layout_texels(s, &lay);
    if (rc == 0)
        rc = find_ties(s, &lay);
    if (rc == 0 && twin && !opt->use_double)
        rc = twins_start(s, &lay);
    /* The twin (--precision auto's double scene) is packed beside the
     * rest: for a million spheres it is 128 MB of its own. Without a
     * twin the nodes go beside instead (52 MB there), but for a small
     * tree. */
    struct side_job twin_job = {.s = s, .lay = &lay, .opt = opt, .into = twin};
    struct side_job nodes_job = {.s = s, .lay = &lay, .opt = opt, .into = out};
    bool nodes_beside = !twin && bvh_gpu_count(&lay.bvh) >= PACK_NODES_BESIDE;
    if (rc == 0 && twin) {
        twin->features = out->features;
        side_start(&twin_job, pack_twin);
    }
    if (rc == 0 && nodes_beside)
        side_start(&nodes_job, pack_nodes);
    if (rc == 0)
        rc = opt->use_double ? pack_d(s, &lay, opt, out) : pack_f(s, &lay, opt, out);
    twins_end(&lay, rc == 0 ? out->data[TP2_BINDING_OBJECTS] : NULL);
    if (rc == 0 && !nodes_beside)
        rc = pack_bvh(&lay.bvh, out);
    if (rc == 0)
        rc = pack_texels(s, &lay, out);
    int twin_rc = side_join(&twin_job);
    int nodes_rc = side_join(&nodes_job);
    if (rc == 0)
        rc = twin_rc ? twin_rc : nodes_rc;
    bvh_free(&lay.bvh);
    free(lay.slots);
    free(lay.texel_offset);
    free(lay.near_twin);
    free(lay.twin_planes);
    free(lay.ties);
    free(lay.tie_first);
    if (rc != 0) {
        packed_scene_free(out);
        if (twin)
            packed_scene_free(twin);
    }
    return rc;
}

void packed_scene_free(struct packed_scene *p)
{
    for (int i = 0; i < TP2_INPUT_BUFFERS; i++)
        free(p->data[i]);
    memset(p, 0, sizeof *p);
}
