/* test_obj.c: obj_read on OBJ text held in memory (fmemopen).
 *
 * Every accepted form (v lines with extra numbers, faces with v, v/t, v//n
 * and v/t/n parts, negative indices, polygons fanned, comments, CRLF,
 * other lines ignored, degenerate triangles dropped) with its triangles
 * checked, and every error with its exact message and position. Prints
 * "N passed, M failed" last. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "obj_read.h"

#include "unit.h"

/* Reads text as "m.obj"; rc, and the mesh or the message in err. */
static int read_text(const char *text, size_t len, struct obj_mesh *m, char *err,
                     size_t size)
{
    FILE *f = fmemopen((void *)text, len, "rb");
    if (!f)
        return -2;
    int rc = obj_read(f, "m.obj", m, err, size);
    fclose(f);
    return rc;
}

/* Triangle k's corner c is (x, y, z). */
static int corner_is(const struct obj_mesh *m, size_t k, int c, double x, double y, double z)
{
    const double *p = m->tri + 9 * k + 3 * c;
    return k < m->ntri && p[0] == x && p[1] == y && p[2] == z;
}

static void expect_error(const char *text, const char *want, int line)
{
    struct obj_mesh m;
    char err[256] = "";
    int rc = read_text(text, strlen(text), &m, err, sizeof err);
    expect(rc == -1 && strcmp(err, want) == 0 && m.tri == NULL && m.ntri == 0,
           "line %d: rc %d\n  got  %s\n  want %s", line, rc, err, want);
    if (rc == 0)
        obj_mesh_free(&m);
}

#define EXPECT_ERROR(text, want) expect_error((text), (want), __LINE__)

static void test_forms(void)
{
    const char *text =
        "# a comment line\r\n"
        "o square\r\n"
        "v 0 0 0\r\n"
        "v 1 0 0 1.0\r\n"           /* w */
        "v 1 1 0 0.5 0.5 0.5\r\n"   /* a color */
        "v 0 1 0 # trailing comment\r\n"
        "vt 0 0\nvn 0 0 1\ng group\nusemtl red\ns off\nmtllib x.mtl\nl 1 2\n"
        "f 1/1/1 2/1/1 3/1/1 4/1/1\n"   /* a quad: fanned into 2 triangles */
        "f -4 -3 -2\n"                  /* relative: vertices 1 2 3 */
        "f 1//1 3//1 4//1\n"
        "f 1/1 2/1 4/1\n"
        "\tf  2 3 4 \n";                /* blanks around */
    struct obj_mesh m;
    char err[256] = "";
    int rc = read_text(text, strlen(text), &m, err, sizeof err);
    CHECK(rc == 0);
    if (rc != 0) {
        printf("  error: %s\n", err);
        return;
    }
    CHECK(m.ntri == 6 && m.skipped == 0);
    CHECK(corner_is(&m, 0, 0, 0, 0, 0) && corner_is(&m, 0, 1, 1, 0, 0) &&
          corner_is(&m, 0, 2, 1, 1, 0));
    CHECK(corner_is(&m, 1, 0, 0, 0, 0) && corner_is(&m, 1, 1, 1, 1, 0) &&
          corner_is(&m, 1, 2, 0, 1, 0));
    CHECK(corner_is(&m, 2, 0, 0, 0, 0) && corner_is(&m, 2, 1, 1, 0, 0) &&
          corner_is(&m, 2, 2, 1, 1, 0));
    CHECK(corner_is(&m, 5, 0, 1, 0, 0) && corner_is(&m, 5, 2, 0, 1, 0));
    obj_mesh_free(&m);
}

static void test_degenerate_dropped(void)
{
    /* Collinear and repeated corners have no area: dropped, counted. */
    const char *text = "v 0 0 0\nv 1 1 1\nv 2 2 2\nv 0 1 0\n"
                       "f 1 2 3\nf 1 1 4\nf 1 2 4\n";
    struct obj_mesh m;
    char err[256];
    int rc = read_text(text, strlen(text), &m, err, sizeof err);
    CHECK(rc == 0 && m.ntri == 1 && m.skipped == 2);
    if (rc == 0)
        obj_mesh_free(&m);
    /* Tiny and huge coordinates: area judged without underflow or overflow. */
    text = "v 0 0 0\nv 1e-200 0 0\nv 0 1e-200 0\nv 1e300 0 0\nv 0 1e300 0\n"
           "f 1 2 3\nf 1 4 5\n";
    rc = read_text(text, strlen(text), &m, err, sizeof err);
    CHECK(rc == 0 && m.ntri == 2 && m.skipped == 0);
    if (rc == 0)
        obj_mesh_free(&m);
}

static void test_no_faces(void)
{
    struct obj_mesh m;
    char err[256];
    const char *text = "v 0 0 0\n# nothing else\n";
    CHECK(read_text(text, strlen(text), &m, err, sizeof err) == 0 && m.ntri == 0);
    obj_mesh_free(&m);
    CHECK(read_text("", 0, &m, err, sizeof err) == 0 && m.ntri == 0);
    obj_mesh_free(&m);
}

static void test_errors(void)
{
    EXPECT_ERROR("v 0 0\n", "m.obj:1:6: error: expected a finite number, found end of line");
    EXPECT_ERROR("v 0 0 x\n", "m.obj:1:7: error: expected a finite number, found 'x'");
    EXPECT_ERROR("v 0 0 1e999\n", "m.obj:1:7: error: expected a finite number, found '1e999'");
    EXPECT_ERROR("v 0 nan 0\n", "m.obj:1:5: error: expected a finite number, found 'nan'");
    EXPECT_ERROR("v 0 1.5.2 0\n", "m.obj:1:5: error: expected a finite number, found '1.5.2'");
    EXPECT_ERROR("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n",
                 "m.obj:4:6: error: a face needs at least 3 vertices, found 2");
    EXPECT_ERROR("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n",
                 "m.obj:4:7: error: vertex index '0' is out of range (3 vertices so far)");
    EXPECT_ERROR("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n",
                 "m.obj:4:7: error: vertex index '4' is out of range (3 vertices so far)");
    EXPECT_ERROR("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -4 1 2\n",
                 "m.obj:4:3: error: vertex index '-4' is out of range (3 vertices so far)");
    /* A face may only use vertices read before it. */
    EXPECT_ERROR("v 0 0 0\nv 1 0 0\nf 1 2 3\nv 0 1 0\n",
                 "m.obj:3:7: error: vertex index '3' is out of range (2 vertices so far)");
    EXPECT_ERROR("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n",
                 "m.obj:4:7: error: expected a vertex index, found 'x'");
    EXPECT_ERROR("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2/a 3\n",
                 "m.obj:4:5: error: malformed vertex reference '2/a'");
    EXPECT_ERROR("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3.5\n",
                 "m.obj:4:7: error: expected a vertex index, found '3.5'");
    /* A NUL byte is reported where it is. */
    static const char nul[] = "v 0 0 0\nv 1\0 0 0\n";
    struct obj_mesh m;
    char err[256] = "";
    int rc = read_text(nul, sizeof nul - 1, &m, err, sizeof err);
    expect(rc == -1 && strcmp(err, "m.obj:2:4: error: unexpected character '\\x00'") == 0,
           "NUL byte: rc %d, %s", rc, err);
    /* A line longer than OBJ_MAX_LINE is refused, not grown into. */
    size_t n = OBJ_MAX_LINE + 10;
    char *long_line = malloc(n + 1);
    memset(long_line, ' ', n);
    long_line[0] = 'v';
    long_line[n] = '\0';
    rc = read_text(long_line, n, &m, err, sizeof err);
    expect(rc == -1 && strstr(err, "m.obj:1:1: error: line longer than") == err,
           "long line: rc %d, %s", rc, err);
    free(long_line);
}

/* A file that cannot be read, such as a directory (a scene may name one):
 * the reason, and no line 0 (found by tests/fuzz/fuzz_scene.c). */
static void test_unreadable(void)
{
    FILE *f = fopen("/", "rb");
    if (!f) {
        expect(1, "skipped: / cannot be opened");
        return;
    }
    struct obj_mesh m;
    char err[256];
    int rc = obj_read(f, "/", &m, err, sizeof err);
    fclose(f);
    expect(rc == -1 && !m.tri && strcmp(err, "tp2: cannot read '/': Is a directory") == 0,
           "directory: rc %d, %s", rc, err);
}

int main(void)
{
    test_forms();
    test_degenerate_dropped();
    test_no_faces();
    test_errors();
    test_unreadable();
    return unit_report();
}
