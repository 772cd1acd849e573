/* test_twins.c: near twins among flat faces (host/pack/twins.h) and the shape
 * table's face planes they come from.
 *
 * Faces of real records (boxes, planes, polyhedra, triangles, packed by
 * the table) are marked where they lie near another object's face without
 * being on its plane; random sets built to straddle the search's cells and
 * orientations are marked exactly as a search over all pairs says; crowded
 * cells mark at least that. Prints "N passed, M failed" last. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "shapes.h"
#include "twins.h"
#include "vec3.h"

#include "unit.h"

#define MAX_FACES 256

struct faces {
    struct twin_face f[MAX_FACES];
    size_t n;
};

/* Adds the faces of one object of kind k with numbers p as slot `slot`. */
static void add_object(struct faces *set, int k, const double *p, size_t np, uint32_t slot)
{
    const struct shape_kind *kind = &shape_kinds[k];
    struct shape_record rec;
    double extra[16][4], planes[16][4];
    memset(&rec, 0, sizeof rec);
    kind->pack(p, np, 0, &rec, extra);
    size_t count = kind->faces(&rec, (const double (*)[4])extra, planes);
    for (size_t i = 0; i < count; i++) {
        struct twin_face *f = &set->f[set->n++];
        memcpy(f->plane, planes[i], sizeof f->plane);
        f->owner = slot;
        f->slot = slot;
        f->met_as_plane = kind->met_as_planes;
    }
}

/* Marks near twins among faces[0..n) the way scene_pack.c does: every
 * face but those of object `streamed` goes into the search, then every
 * face is compared with it. streamed -1: all go in. */
static void mark_faces(const struct twin_face *faces, size_t n, double scale, long streamed,
                       bool *near)
{
    static struct twin_face in[MAX_FACES];
    size_t m = 0;
    for (size_t i = 0; i < n; i++)
        if ((long)faces[i].owner != streamed)
            in[m++] = faces[i];
    struct twins *t = twins_new(in, m, scale);
    CHECK(t != NULL);
    for (size_t i = 0; t && i < n; i++)
        twins_compare(t, &faces[i], near);
    twins_finish(t, near);
}

/* Marks of a set of objects (slots 0..objects-1) at scale 1. */
static void mark(const struct faces *set, bool *near, size_t objects)
{
    memset(near, 0, objects * sizeof *near);
    mark_faces(set->f, set->n, 1.0, -1, near);
}

static void test_face_planes(void)
{
    /* A box's six planes: each face's corner points on it, normals out. */
    const double box[6] = {-1, -2, -3, 4, 5, 6};
    struct faces set = {.n = 0};
    add_object(&set, SHAPE_BOX, box, 6, 0);
    CHECK(set.n == 6);
    const double center[3] = {1.5, 1.5, 1.5};
    for (size_t i = 0; i < set.n; i++) {
        const double *p = set.f[i].plane;
        int axis = (int)i / 2;
        double corner[3] = {i % 2 ? box[3] : box[0], i % 2 ? box[4] : box[1],
                            i % 2 ? box[5] : box[2]};
        expect(vec3_dot(p, corner) + p[3] == 0 && fabs(p[axis]) == 1,
               "box face %zu lies on its plane", i);
        expect(vec3_dot(p, center) + p[3] < 0, "box face %zu's normal points out", i);
    }
    /* A triangle's plane holds its corners; a plane's and a polyhedron's
     * are their unit planes. */
    const double tri[9] = {0.4, 0.16, 0.5, 1.4, 0.06, 0.5, 0.9, 0.31, -0.5};
    set.n = 0;
    add_object(&set, SHAPE_TRIANGLE, tri, 9, 0);
    CHECK(set.n == 1 && !set.f[0].met_as_plane);
    for (int c = 0; c < 3; c++)
        expect(fabs(vec3_dot(set.f[0].plane, tri + 3 * c) + set.f[0].plane[3]) < 1e-15,
               "triangle corner %d on its plane", c);
    const double plane[4] = {0, 2, 0, -0.6};
    set.n = 0;
    add_object(&set, SHAPE_PLANE, plane, 4, 0);
    CHECK(set.n == 1 && set.f[0].met_as_plane && set.f[0].plane[1] == 1 &&
          set.f[0].plane[3] == -0.3);
    const double poly[8] = {0, 0, 3, -3, 0, 0, -1, -1};
    set.n = 0;
    add_object(&set, SHAPE_POLYHEDRON, poly, 8, 0);
    CHECK(set.n == 2 && set.f[1].plane[2] == -1 && set.f[0].plane[3] == -1);
}

/* Two objects: whether each is marked. */
static void expect_pair(int ka, const double *a, size_t na, int kb, const double *b, size_t nb,
                        bool want, const char *what)
{
    struct faces set = {.n = 0};
    bool near[2];
    add_object(&set, ka, a, na, 0);
    add_object(&set, kb, b, nb, 1);
    mark(&set, near, 2);
    expect(near[0] == want && near[1] == want, "%s: marked %d %d, want %d", what, near[0],
           near[1], want);
}

static void test_real_objects(void)
{
    const double box[6] = {-1, -1, -1, 1, 0.3, 1};
    const double apart[4] = {0, 1, 0, -0.3000000001};  /* 0.3 in float */
    const double step[4] = {0, 1, 0, -0.30000005};     /* one float step up */
    const double same[4] = {0, 1, 0, -0.3};
    const double scaled[4] = {0, 4, 0, -1.2};          /* the same plane */
    const double floor[4] = {0, 1, 0, 1};              /* y = -1: the bottom */
    const double far[4] = {0, 1, 0, -0.31};
    const double tilted[4] = {0, 1, 1e-7, -0.3};
    expect_pair(SHAPE_BOX, box, 6, SHAPE_PLANE, apart, 4, true, "box top 0.3, plane 0.3000000001");
    expect_pair(SHAPE_BOX, box, 6, SHAPE_PLANE, step, 4, true, "box top, plane a float step up");
    expect_pair(SHAPE_BOX, box, 6, SHAPE_PLANE, tilted, 4, true, "box top, plane tilted 1e-7");
    expect_pair(SHAPE_BOX, box, 6, SHAPE_PLANE, same, 4, false, "box top on a plane");
    expect_pair(SHAPE_BOX, box, 6, SHAPE_PLANE, scaled, 4, false, "box top, plane written x4");
    expect_pair(SHAPE_BOX, box, 6, SHAPE_PLANE, floor, 4, false, "box bottom on the floor");
    expect_pair(SHAPE_BOX, box, 6, SHAPE_PLANE, far, 4, false, "box top 0.01 under a plane");
    /* A face of the other orientation on the same plane; and a triangle,
     * met through its corners, on it. */
    const double below[8] = {0, -1, 0, 0.3, 0, 1, 0, 5};
    const double above[8] = {0, -1, 0, 0.3000000001, 0, 1, 0, 5};
    const double tri[9] = {-3, 0.3, -3, 3, 0.3, -3, 0, 0.3, 4};
    expect_pair(SHAPE_POLYHEDRON, below, 8, SHAPE_BOX, box, 6, false,
                "polyhedron on the box top");
    expect_pair(SHAPE_POLYHEDRON, above, 8, SHAPE_BOX, box, 6, true,
                "polyhedron 1e-10 over the box top");
    expect_pair(SHAPE_TRIANGLE, tri, 9, SHAPE_BOX, box, 6, true, "triangle on the box top");
    /* One object's faces are never twins of each other. */
    const double slab[8] = {0, 1, 0, -0.3, 0, 1, 0, -0.3000000001};
    struct faces set = {.n = 0};
    bool near[1];
    add_object(&set, SHAPE_POLYHEDRON, slab, 8, 0);
    mark(&set, near, 1);
    CHECK(!near[0]);
}

static uint64_t rng = 88172645463325252u;

static double uniform(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return (double)(rng >> 11) / 9007199254740992.0;
}

/* Whether a and b are near twins, pair by pair, as twins.h defines them:
 * near in either orientation, and not the same plane met as planes. */
static bool oracle_pair(const struct twin_face *a, const struct twin_face *b, double scale)
{
    if (a->owner == b->owner)
        return false;
    bool near = false, same = false;
    for (int sign = -1; sign <= 1; sign += 2) {
        bool close = true, equal = true;
        for (int k = 0; k < 4; k++) {
            double d = fabs(a->plane[k] - sign * b->plane[k]);
            close &= d <= TWIN_TOLERANCE * (k == 3 ? scale : 1);
            equal &= a->plane[k] == sign * b->plane[k];
        }
        near |= close;
        same |= equal;
    }
    return near && !(same && a->met_as_plane && b->met_as_plane);
}

/* A coordinate near a multiple of the search's cells (8 tolerances), or
 * anywhere. */
static double coordinate(double unit)
{
    double r = uniform();
    if (r < 0.6)
        return unit * (8 * floor(uniform() * 20 - 10) + (uniform() - 0.5) * 2.5);
    return (uniform() * 2 - 1) * 160 * unit;
}

/* Random sets: a few base planes, copies moved by up to 1.5 tolerances
 * along some coordinates, flipped, or met as triangles, in 2-4 objects,
 * each face a primitive of its own;
 * marked exactly as the oracle says (no cell is crowded at this size, and
 * the larger sets are searched through cells, the smaller walked whole). */
static void test_against_oracle(void)
{
    int wrong = 0, marked = 0, cases = 3000;
    for (int c = 0; c < cases; c++) {
        double scale = uniform() < 0.5 ? 1 : exp2(floor(uniform() * 40 - 20));
        struct faces set = {.n = 0};
        int objects = 2 + (int)(uniform() * 3);
        int bases = 1 + (int)(uniform() * 3);
        double base[3][4];
        for (int b = 0; b < bases; b++) {
            for (int k = 0; k < 3; k++)
                base[b][k] = coordinate(TWIN_TOLERANCE);
            if (uniform() < 0.3) { /* two largest components nearly equal */
                base[b][0] = 0.5 + uniform() * 0.3;
                base[b][1] = -base[b][0] * (1 + (uniform() - 0.5) * 4 * TWIN_TOLERANCE);
            } else {
                base[b][(int)(uniform() * 3)] += uniform() < 0.5 ? 1 : -1;
            }
            base[b][3] = coordinate(TWIN_TOLERANCE * scale);
        }
        size_t n = 2 + (size_t)(uniform() * 58); /* past FEW: both ways; under CROWD */
        for (size_t i = 0; i < n; i++) {
            struct twin_face *f = &set.f[set.n++];
            memcpy(f->plane, base[(int)(uniform() * bases)], sizeof f->plane);
            for (int k = 0; k < 4; k++)
                if (uniform() < 0.3)
                    f->plane[k] += (uniform() * 3 - 1.5) * TWIN_TOLERANCE * (k == 3 ? scale : 1);
            if (uniform() < 0.3)
                for (int k = 0; k < 4; k++)
                    f->plane[k] = -f->plane[k];
            f->owner = (uint32_t)(uniform() * objects);
            f->slot = (uint32_t)i; /* each face its own primitive: each checked */
            f->met_as_plane = uniform() < 0.8;
        }
        /* all faces in the search, or all but one object's (streamed) */
        bool near[MAX_FACES] = {false}, streamed[MAX_FACES] = {false},
             want[MAX_FACES] = {false};
        mark_faces(set.f, set.n, scale, -1, near);
        mark_faces(set.f, set.n, scale, (long)(uniform() * objects), streamed);
        for (size_t i = 0; i < set.n; i++)
            for (size_t j = 0; j < set.n; j++)
                if (oracle_pair(&set.f[i], &set.f[j], scale))
                    want[set.f[i].slot] = true;
        for (size_t i = 0; i < set.n; i++) {
            wrong += (near[i] != want[i]) + (streamed[i] != want[i]);
            marked += want[i];
        }
    }
    expect(wrong == 0, "%d of the random faces marked unlike the oracle", wrong);
    expect(marked > cases * 5, "the random sets have twins to find (%d marked)", marked);
    printf("random sets: %d faces with near twins\n", marked);
}

/* A crowded cell: 100 faces of each of two objects on one plane, and
 * first (so walked last) a face of a third just off it. Crowding may mark
 * more than the oracle, never less: here it marks all three, whichever
 * object's faces are compared without going into the search. */
static void test_crowded(void)
{
    struct faces set = {.n = 0};
    for (int i = 0; i < 201; i++) {
        struct twin_face *f = &set.f[set.n++];
        double plane[4] = {0, 1, 0, i == 0 ? -0.3000000001 : -0.3};
        memcpy(f->plane, plane, sizeof plane);
        f->owner = f->slot = i == 0 ? 2 : i <= 100 ? 0 : 1;
        f->met_as_plane = true;
    }
    for (long streamed = -1; streamed < 3; streamed++) {
        bool near[3] = {false};
        mark_faces(set.f, set.n, 1.0, streamed, near);
        expect(near[0] && near[1] && near[2],
               "every object beside the face off the plane marked (object %ld streamed)",
               streamed);
    }
    /* A face compared from outside the search with a crowd of one
     * object's primitives (slots 0-99): those past the walk are marked
     * when the search ends. */
    set.n = 0;
    for (int i = 0; i < 101; i++) {
        struct twin_face *f = &set.f[set.n++];
        double plane[4] = {0, 1, 0, i == 100 ? -0.3000000001 : -0.3};
        memcpy(f->plane, plane, sizeof plane);
        f->owner = i == 100;
        f->slot = (uint32_t)i;
        f->met_as_plane = true;
    }
    bool crowd[101] = {false};
    mark_faces(set.f, set.n, 1.0, 1, crowd);
    int crowd_marked = 0;
    for (int i = 0; i < 101; i++)
        crowd_marked += crowd[i];
    expect(crowd_marked == 101, "%d of a crowd of 100 and its twin marked", crowd_marked);
    /* Crowds of one object's faces alone are not searched through: a
     * mesh's coplanar triangles are not twins of each other. */
    set.n = 0;
    for (int i = 0; i < 200; i++) {
        struct twin_face *f = &set.f[set.n++];
        double plane[4] = {0, 1, 0, -0.3};
        memcpy(f->plane, plane, sizeof plane);
        f->owner = 0;
        f->slot = (uint32_t)i;
        f->met_as_plane = false;
    }
    bool alone[200] = {false};
    mark_faces(set.f, set.n, 1.0, -1, alone);
    bool any = false;
    for (int i = 0; i < 200; i++)
        any |= alone[i];
    CHECK(!any);
}

int main(void)
{
    test_face_planes();
    test_real_objects();
    test_against_oracle();
    test_crowded();
    return unit_report();
}
