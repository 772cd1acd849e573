/* twins.c: near twins among flat faces (twins.h).
 *
 * Each face's plane is put in one orientation (its normal's largest
 * component positive) and hashed by the cell it falls in, a grid of CELL
 * tolerances in n.x, n.y, n.z and d. A face near another lies in that
 * face's cell or, along a coordinate within one tolerance of the cell's
 * side, in the cell across: at most 16 cells to look in, and most faces
 * look in one. A normal whose two largest components are nearly equal
 * could be oriented either way, so such a face looks for both. A cell
 * of one object's faces only is passed over by that object's faces, so a
 * mesh's triangles are not compared with each other. In front of the
 * cells, a bitmap of the normals within reach turns most faces away on
 * one bit, and a search of a few faces is walked whole instead. */
#include "twins.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define CELL 8.0
/* Faces walked in one cell before the cell is called crowded and all its
 * faces are marked unsearched (a mesh lying on a floor: every triangle in
 * one cell with the floor, each a near twin anyway). */
#define CROWD 64
/* Searches of at most this many faces are walked whole, without cells. */
#define FEW 32
#define MIXED UINT32_MAX /* cell.owner: faces of several objects */

struct cell {
    uint64_t key; /* 0: empty */
    uint32_t head, owner;
    bool crowded;
};

/* A coarse grid over normals (each component in [-1, 1], COARSE cells
 * along each): a bit per cell that some face's normal is within one
 * tolerance of. Most of a curved mesh's triangles are turned away from
 * every other face and are passed over on one bit. */
#define COARSE 64

struct twins {
    uint64_t turned[COARSE * COARSE * COARSE / 64];
    struct twin_face *faces;
    uint32_t *next; /* per face: the next face in its cell, or UINT32_MAX */
    size_t n;
    struct cell *cells;
    size_t mask;
    double tolerance[4], per_cell[4]; /* 1 / (CELL tolerance) */
};

/* The plane with its normal's largest component positive (the first of
 * equal ones), which is the same for p and -p; *either: whether the
 * other orientation is within reach of a near face's. */
static void oriented(const double p[4], double out[4], bool *either)
{
    double m[3] = {fabs(p[0]), fabs(p[1]), fabs(p[2])};
    int big = m[1] > m[0] ? 1 : 0;
    big = m[2] > m[big] ? 2 : big;
    double second = big == 0 ? (m[1] > m[2] ? m[1] : m[2])
                  : big == 1 ? (m[0] > m[2] ? m[0] : m[2])
                             : (m[0] > m[1] ? m[0] : m[1]);
    *either = second >= m[big] - 2 * TWIN_TOLERANCE;
    double sign = p[big] < 0 ? -1 : 1;
    for (int a = 0; a < 4; a++)
        out[a] = sign * p[a];
}

/* Cell coordinate along one axis, clamped to 16 bits (clamping only
 * merges cells), and how far into its cell v lies (0 to 1). Ternaries and
 * a cast rather than fmin, fmax and floor, which are calls here: this
 * runs for each of a mesh's million triangles. */
static int32_t cell_coord(double v, double per_cell, double *fraction)
{
    double q = v * per_cell;
    q = !(q >= -32767) ? -32767 : q > 32767 ? 32767 : q; /* NaN: -32767 */
    int32_t k = (int32_t)q;
    k -= k > q;
    *fraction = q - k;
    return k;
}

/* -1 or 1 where a cell's fraction lies within `edge` of its low or high
 * side (the neighbour across it may hold a near value), else 0. */
static int side_within(double fraction, double edge)
{
    return fraction < edge ? -1 : 1 - fraction < edge ? 1 : 0;
}

static uint64_t cell_key(const int32_t k[4])
{
    uint64_t key = 0;
    for (int a = 0; a < 4; a++)
        key = key << 16 | (uint64_t)(k[a] + 32768);
    return key; /* never 0: each part is at least 1 */
}

/* The bit of `turned` for normal n (n's cell, moved by step[a] along
 * axis a). */
static size_t turned_bit(const double n[3], const int step[3])
{
    size_t bit = 0;
    for (int a = 0; a < 3; a++) {
        double fraction;
        int32_t k = cell_coord(n[a] + 1, COARSE / 2.0, &fraction) + step[a];
        bit = bit * COARSE + (size_t)(k < 0 ? 0 : k >= COARSE ? COARSE - 1 : k);
    }
    return bit;
}

/* Sets the bits of the cells within a tolerance of normal n. */
static void turn_to(struct twins *t, const double n[3])
{
    int reach[3];
    for (int a = 0; a < 3; a++) {
        double fraction;
        cell_coord(n[a] + 1, COARSE / 2.0, &fraction);
        reach[a] = side_within(fraction, 1.01 * TWIN_TOLERANCE * COARSE / 2.0);
    }
    for (int m = 0; m < 8; m++) {
        int step[3];
        for (int a = 0; a < 3; a++)
            step[a] = m >> a & 1 ? reach[a] : 0;
        size_t bit = turned_bit(n, step);
        t->turned[bit / 64] |= (uint64_t)1 << bit % 64;
    }
}

/* Whether some face's normal may be within a tolerance of n. */
static bool turned_near(const struct twins *t, const double n[3])
{
    static const int none[3] = {0, 0, 0};
    size_t bit = turned_bit(n, none);
    return t->turned[bit / 64] >> bit % 64 & 1;
}

static struct cell *cell_find(const struct twins *t, uint64_t key)
{
    size_t i = (size_t)((key * 0x9E3779B97F4A7C15u) >> 20) & t->mask;
    while (t->cells[i].key && t->cells[i].key != key)
        i = (i + 1) & t->mask;
    return &t->cells[i];
}

static bool near_planes(const double a[4], const double b[4], const double tolerance[4])
{
    for (int k = 0; k < 4; k++)
        if (!(fabs(a[k] - b[k]) <= tolerance[k]))
            return false;
    return true;
}

static bool same_plane(const double a[4], const double b[4])
{
    return a[0] == b[0] && a[1] == b[1] && a[2] == b[2] && a[3] == b[3];
}

struct twins *twins_new(const struct twin_face *faces, size_t n, double scale)
{
    struct twins *t = calloc(1, sizeof *t);
    if (!t || n >= UINT32_MAX)
        return free(t), NULL;
    size_t size = 16;
    while (size < 2 * n)
        size *= 2;
    t->mask = size - 1;
    t->n = n;
    t->cells = calloc(size, sizeof *t->cells);
    t->faces = malloc((n ? n : 1) * sizeof *t->faces);
    t->next = malloc((n ? n : 1) * sizeof *t->next);
    if (!t->cells || !t->faces || !t->next) {
        twins_finish(t, NULL);
        return NULL;
    }
    for (int a = 0; a < 4; a++) {
        t->tolerance[a] = TWIN_TOLERANCE * (a < 3 ? 1 : scale > 0 ? scale : 1);
        t->per_cell[a] = 1 / (CELL * t->tolerance[a]);
    }
    for (uint32_t i = 0; i < n; i++) {
        double p[4], unused;
        bool either;
        int32_t k[4];
        t->faces[i] = faces[i];
        oriented(faces[i].plane, p, &either);
        memcpy(t->faces[i].plane, p, sizeof p); /* kept oriented */
        turn_to(t, p);
        for (int a = 0; a < 4; a++)
            k[a] = cell_coord(p[a], t->per_cell[a], &unused);
        struct cell *c = cell_find(t, cell_key(k));
        if (!c->key)
            *c = (struct cell){cell_key(k), UINT32_MAX, faces[i].owner, false};
        else if (c->owner != faces[i].owner)
            c->owner = MIXED;
        t->next[i] = c->head;
        c->head = i;
    }
    return t;
}

/* Compares f, oriented as p (own: as the search orients it), with the
 * search's face j. */
static void compare_pair(const struct twins *t, const struct twin_face *f, const double p[4],
                         const double own[4], uint32_t j, bool *near)
{
    const struct twin_face *o = &t->faces[j];
    if (o->owner != f->owner && near_planes(p, o->plane, t->tolerance) &&
        !(f->met_as_plane && o->met_as_plane && same_plane(own, o->plane)))
        near[f->slot] = near[o->slot] = true;
}

/* The same with the faces of cell c. */
static void compare_in_cell(const struct twins *t, const struct twin_face *f,
                            const double p[4], const double own[4], struct cell *c, bool *near)
{
    if (!c->key || c->owner == f->owner)
        return; /* empty, or f's object's faces only */
    if (c->crowded) {
        near[f->slot] = true; /* and the cell's faces, by twins_finish */
        return;
    }
    int walked = 0;
    for (uint32_t j = c->head; j != UINT32_MAX; j = t->next[j]) {
        if (++walked > CROWD) {
            c->crowded = true;
            near[f->slot] = true;
            return;
        }
        compare_pair(t, f, p, own, j, near);
    }
}

/* The cells along each coordinate are p's own and, within one tolerance
 * of a side, the one across it. */
static void compare_oriented(const struct twins *t, const struct twin_face *f, const double p[4],
                             const double own[4], bool *near)
{
    int32_t k[4], step[4];
    for (int a = 0; a < 4; a++) {
        double fraction;
        k[a] = cell_coord(p[a], t->per_cell[a], &fraction);
        step[a] = side_within(fraction, 1.01 / CELL);
    }
    for (int m = 0; m < 16; m++) {
        int32_t at[4];
        bool skip = false;
        for (int a = 0; a < 4; a++) {
            bool across = m >> a & 1;
            skip |= across && step[a] == 0;
            at[a] = k[a] + (across ? step[a] : 0);
        }
        if (!skip)
            compare_in_cell(t, f, p, own, cell_find(t, cell_key(at)), near);
    }
}

void twins_compare(struct twins *t, const struct twin_face *f, bool *near)
{
    double own[4], flipped[4];
    bool either;
    oriented(f->plane, own, &either);
    for (int a = 0; a < 4; a++)
        flipped[a] = -own[a];
    either &= turned_near(t, flipped);
    if (!turned_near(t, own) && !either)
        return;
    if (t->n <= FEW) { /* faster than the cells (a mesh beside a floor) */
        for (uint32_t j = 0; j < t->n; j++) {
            compare_pair(t, f, own, own, j, near);
            if (either)
                compare_pair(t, f, flipped, own, j, near);
        }
        return;
    }
    compare_oriented(t, f, own, own, near);
    if (either)
        compare_oriented(t, f, flipped, own, near);
}

void twins_finish(struct twins *t, bool *near)
{
    if (!t)
        return;
    if (near && t->cells)
        for (size_t c = 0; c <= t->mask; c++)
            if (t->cells[c].crowded)
                for (uint32_t j = t->cells[c].head; j != UINT32_MAX; j = t->next[j])
                    near[t->faces[j].slot] = true;
    free(t->cells);
    free(t->faces);
    free(t->next);
    free(t);
}
