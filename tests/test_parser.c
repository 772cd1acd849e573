/* test_parser.c: unit tests of scene_parse_text on inline scenes.
 *
 * Every grammar rule with its parsed values checked, and every error class
 * with its exact message. Prints "N passed, M failed" last; exits 0 only
 * when nothing failed. */
#define _DEFAULT_SOURCE /* mkdtemp */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "lexer.h"
#include "pigments.h"
#include "scene_parse.h"
#include "shapes.h"

#include "unit.h"

static int vec_eq(const double *v, double x, double y, double z)
{
    return v[0] == x && v[1] == y && v[2] == z;
}

/* The keyword lists of "expected ..." messages. */
#define PIGMENT_WORDS "'solid', 'checker', 'gradient', 'texmap' or 'textmap'"
#define SHAPE_WORDS "'sphere', 'plane', 'polyhedron', 'box', 'cylinder', 'cone', 'torus', 'quadric', 'triangle' or 'mesh'"

/* A valid scene, one section per macro, so errors can be placed in it.
 * Lines: camera 1-4, lights 5-7, pigments 8-9, finishes 10-11,
 * objects 12-13, directives from 14. */
#define CAM "0 0 0\n0 0 -1\n0 1 0\n45\n"
#define LIGHTS "2\n0 0 0 1 1 1 1 0 0\n10 10 10 1 1 1 1 0 0\n"
#define PIGS "1\nsolid 1 0 0\n"
#define FINS "1\n0.2 0.6 0.3 20 0 0 0\n"
#define OBJS "1\n0 0 sphere 0 0 -5 1\n"
#define BASE CAM LIGHTS PIGS FINS OBJS

/* Parses text that must be valid; on failure reports it and returns a
 * zeroed scene (whose checks then fail too). */
static struct scene parse_ok(const char *text, int line)
{
    struct scene s;
    char err[512];
    int rc = scene_parse_text("t.txt", text, strlen(text), &s, err, sizeof err);
    expect(rc == 0, "line %d: parse succeeds", line);
    if (rc != 0)
        printf("  error: %s\n", err);
    return s;
}

/* Parses len bytes that must fail with exactly want, leaving *out zero. */
static void expect_error_n(const char *text, size_t len, const char *want,
                           int line)
{
    struct scene s, zero;
    char err[512];
    memset(&s, 0xab, sizeof s);
    memset(&zero, 0, sizeof zero);
    int rc = scene_parse_text("t.txt", text, len, &s, err, sizeof err);
    if (rc == -1 && strcmp(err, want) == 0 &&
        memcmp(&s, &zero, sizeof s) == 0) {
        passed++;
        return;
    }
    failed++;
    printf("FAIL line %d: rc %d\n  got  %s\n  want %s\n", line, rc,
           rc ? err : "(parsed)", want);
    if (rc == 0)
        scene_free(&s);
}

#define EXPECT_ERROR(text, want) \
    expect_error_n((text), strlen(text), (want), __LINE__)

/* ---- valid scenes ------------------------------------------------------ */

static void test_plain_variant(void)
{
    struct scene s = parse_ok(BASE, __LINE__);
    CHECK(!s.has_size && s.width == 0 && s.height == 0);
    CHECK(vec_eq(s.eye, 0, 0, 0) && vec_eq(s.center, 0, 0, -1));
    CHECK(vec_eq(s.up, 0, 1, 0) && s.fov == 45);
    CHECK(s.nlights == 2 && vec_eq(s.lights[1].pos, 10, 10, 10));
    CHECK(vec_eq(s.lights[1].color, 1, 1, 1) && vec_eq(s.lights[1].att, 1, 0, 0));
    CHECK(s.npigments == 1 && s.pigments[0].kind == PIGMENT_SOLID);
    CHECK(vec_eq(s.pigments[0].color1, 1, 0, 0));
    CHECK(s.nfinishes == 1 && s.finishes[0].ka == 0.2 &&
          s.finishes[0].kd == 0.6 && s.finishes[0].ks == 0.3 &&
          s.finishes[0].n == 20 && s.finishes[0].kr == 0 &&
          s.finishes[0].kt == 0 && s.finishes[0].ior == 0);
    CHECK(s.nobjects == 1 && s.objects[0].kind == SHAPE_SPHERE);
    CHECK(s.objects[0].pigment == 0 && s.objects[0].finish == 0);
    CHECK(s.objects[0].count == 4 && vec_eq(scene_object_reals(&s, &s.objects[0]), 0, 0, -5) &&
          scene_object_reals(&s, &s.objects[0])[3] == 1);
    CHECK(!s.has_samples && !s.has_lens && !s.has_fog && !s.has_arealight);
    scene_free(&s);
    CHECK(s.lights == NULL && s.nobjects == 0);
}

static void test_header_variant(void)
{
    struct scene s = parse_ok("out.ppm\n640 480\n" BASE, __LINE__);
    CHECK(s.has_size && s.width == 640 && s.height == 480);
    CHECK(s.fov == 45 && s.nobjects == 1);
    scene_free(&s);
    /* A name that starts like a path, not a number. */
    s = parse_ok("./out/test-1.ppm 1 1\n" BASE, __LINE__);
    CHECK(s.has_size && s.width == 1 && s.height == 1);
    scene_free(&s);
}

static void test_comments(void)
{
    struct scene s = parse_ok("# leading comment\n"
                              "0 0 0 # eye\n"
                              "0 0 -1#center, no space before '#'\n"
                              "0 1 0\n# between\n45\n"
                              "2 # count\n0 0 0 1 1 1 1 0 0\n"
                              "10 10 10 1 1 1 # mid-entry\n 1 0 0\n"
                              PIGS FINS OBJS "# trailing, no newline",
                              __LINE__);
    CHECK(vec_eq(s.center, 0, 0, -1) && s.nlights == 2);
    CHECK(vec_eq(s.lights[1].att, 1, 0, 0) && s.nobjects == 1);
    scene_free(&s);
}

static void test_number_forms(void)
{
    struct scene s = parse_ok("1-10 5\n0 2.5.3\n+0 -.5e1 1.\n2e1\n"
                              "0\n0\n0\n0\n",
                              __LINE__);
    CHECK(vec_eq(s.eye, 1, -10, 5));
    CHECK(vec_eq(s.center, 0, 2.5, .3));
    CHECK(vec_eq(s.up, 0, -5, 1) && s.fov == 20);
    CHECK(s.nlights == 0 && s.npigments == 0 && s.nobjects == 0);
    scene_free(&s);
    /* strtod's forms: hex floats, underflow to (almost) zero, leading
     * zeros in counts. */
    s = parse_ok("0 0 0 0 0 -0x1p1 0 1 0 45\n"
                 "001\n0 0 0 1e-400 1 1 1 0 0\n0 0 0\n",
                 __LINE__);
    CHECK(s.center[2] == -2 && s.nlights == 1);
    CHECK(s.lights[0].color[0] < 1e-300 && s.lights[0].color[0] >= 0);
    scene_free(&s);
}

static void test_whitespace_forms(void)
{
    struct scene s = parse_ok("0\t0\t0\r\n0 0 -1\r\n0 1 0\r\n45\r\n"
                              "1\r\n0 0 0\t.5 .5 .5\t1 0 0\r\n"
                              "1\r\nchecker\t\t1 0 1  0 0 1  2.5\r\n"
                              "1\r\n0.2 0.6 0.3 20 0 0 0\r\n"
                              "1\r\n0 0 plane 0 1 0 10\r\n",
                              __LINE__);
    CHECK(s.pigments[0].kind == PIGMENT_CHECKER);
    CHECK(vec_eq(s.pigments[0].color1, 1, 0, 1));
    CHECK(vec_eq(s.pigments[0].color2, 0, 0, 1) && s.pigments[0].scale == 2.5);
    CHECK(s.objects[0].kind == SHAPE_PLANE);
    CHECK(vec_eq(scene_object_reals(&s, &s.objects[0]), 0, 1, 0) &&
          scene_object_reals(&s, &s.objects[0])[3] == 10);
    CHECK(vec_eq(s.lights[0].color, .5, .5, .5));
    scene_free(&s);
}

static void test_directives(void)
{
    struct scene s = parse_ok(BASE "fog 0.1 0.2 0.3 0.05\n"
                                   "arealight 1 2.5 16\n"
                                   "lens 0.25 7\nsamples 9\n",
                              __LINE__);
    CHECK(s.has_samples && s.samples == 9);
    CHECK(s.has_lens && s.lens_radius == 0.25 && s.lens_focal == 7);
    CHECK(s.has_fog && vec_eq(s.fog_color, 0.1, 0.2, 0.3) &&
          s.fog_density == 0.05);
    CHECK(s.has_arealight && s.arealight_index == 1 &&
          s.arealight_radius == 2.5 && s.arealight_samples == 16);
    scene_free(&s);
    /* Zero where zero is allowed: pinhole lens, clear fog. */
    s = parse_ok(BASE "lens 0 1 fog 0 0 0 0", __LINE__);
    CHECK(s.has_lens && s.lens_radius == 0 && s.has_fog && s.fog_density == 0);
    scene_free(&s);
}

static void test_semantic_edges(void)
{
    /* Transmission with ior < 1 is allowed; kt = 0 needs no ior. */
    struct scene s = parse_ok(CAM LIGHTS PIGS "2\n0 0 0 1 0 0.5 0.9\n"
                                              "0 0 0 1 0 0 -3\n0\n",
                              __LINE__);
    CHECK(s.nfinishes == 2 && s.finishes[0].ior == 0.9);
    scene_free(&s);
    /* Up only slightly off the view direction, and far-apart points whose
     * difference overflows: both usable. */
    s = parse_ok("0 0 0 0 0 -1 0 1e-6 1 90 0 0 0 0", __LINE__);
    CHECK(s.up[1] == 1e-6);
    scene_free(&s);
    s = parse_ok("-1e308 0 0 1e308 0 0 0 1e-300 0 90 0 0 0 0", __LINE__);
    CHECK(s.center[0] == 1e308);
    scene_free(&s);
}

/* SPEC 3's short finish form: kr ends a finish when the next token is on a
 * later line; then kt = 0 and ior = 1. Full and short forms mix. */
static void test_short_finish(void)
{
    struct scene s = parse_ok(CAM LIGHTS PIGS "3\n0.4 0.6 0 1 0.25\n"
                                              "0.1 0.2 0.3 4 0.5 0.6 1.5\n"
                                              "0.4 0.6 0.7 500 0\n0\n",
                              __LINE__);
    CHECK(s.nfinishes == 3);
    CHECK(s.finishes[0].n == 1 && s.finishes[0].kr == 0.25 &&
          s.finishes[0].kt == 0 && s.finishes[0].ior == 1);
    CHECK(s.finishes[1].kr == 0.5 && s.finishes[1].kt == 0.6 &&
          s.finishes[1].ior == 1.5);
    CHECK(s.finishes[2].ks == 0.7 && s.finishes[2].n == 500 &&
          s.finishes[2].kt == 0 && s.finishes[2].ior == 1);
    CHECK(s.nobjects == 0);
    scene_free(&s);
    /* A comment after kr does not make the next token's line the same. */
    s = parse_ok(CAM LIGHTS PIGS "1\n0.4 0.6 0 1 0.25 # short\n0\n", __LINE__);
    CHECK(s.nfinishes == 1 && s.finishes[0].kt == 0 && s.finishes[0].ior == 1);
    scene_free(&s);
    /* kt on kr's line: the full form, so ior must follow. */
    EXPECT_ERROR(CAM LIGHTS PIGS "1\n0.4 0.6 0 1 0.25 0.5\n0\n",
                 "t.txt:12:1: error: expected a positive index of refraction "
                 "since kt > 0, found '0'");
}

/* reals of object i equal want[0..n). */
static int reals_are(const struct scene *s, size_t i, const double *want, size_t n)
{
    if (i >= s->nobjects || s->objects[i].count != n)
        return 0;
    return memcmp(scene_object_reals(s, &s->objects[i]), want, n * sizeof *want) == 0;
}

/* Every kind of SPEC 3 with its numbers as shapes.c stores them. */
static void test_shape_kinds(void)
{
    struct scene s = parse_ok(CAM LIGHTS PIGS FINS "9\n"
                              "0 0 sphere 1 2 3 4\n"
                              "0 0 plane 0 2 0 -1\n"
                              "0 0 polyhedron 2\n  0 0 1 5\n  1 1 1 -3\n"
                              "0 0 box 1 2 3 -1 -2 -3\n"
                              "0 0 cylinder 0 0 0  0 3 0  0.5\n"
                              "0 0 cone 0 0 0 1  0 2 0 0\n"
                              "0 0 torus 1 2 3  0 0 2  1.5 0.25\n"
                              "0 0 quadric 1 2 3 4 5 6 7 8 9 -10\n"
                              "0 0 triangle 0 0 0  1 0 0  0 1 0\n",
                              __LINE__);
    static const int kinds[] = {SHAPE_SPHERE, SHAPE_PLANE, SHAPE_POLYHEDRON, SHAPE_BOX,
                                SHAPE_CYLINDER, SHAPE_CONE, SHAPE_TORUS, SHAPE_QUADRIC,
                                SHAPE_TRIANGLE};
    CHECK(s.nobjects == 9);
    for (size_t i = 0; i < 9 && i < s.nobjects; i++)
        expect(s.objects[i].kind == kinds[i], "object %zu kind %d", i, s.objects[i].kind);
    static const double sph[] = {1, 2, 3, 4}, pla[] = {0, 2, 0, -1},
                        pol[] = {0, 0, 1, 5, 1, 1, 1, -3}, box[] = {1, 2, 3, -1, -2, -3},
                        cyl[] = {0, 0, 0, 0, 3, 0, 0.5}, con[] = {0, 0, 0, 1, 0, 2, 0, 0},
                        tor[] = {1, 2, 3, 0, 0, 2, 1.5, 0.25},
                        qua[] = {1, 2, 3, 4, 5, 6, 7, 8, 9, -10},
                        tri[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    CHECK(reals_are(&s, 0, sph, 4) && reals_are(&s, 1, pla, 4) && reals_are(&s, 2, pol, 8));
    CHECK(reals_are(&s, 3, box, 6) && reals_are(&s, 4, cyl, 7) && reals_are(&s, 5, con, 8));
    CHECK(reals_are(&s, 6, tor, 8) && reals_are(&s, 7, qua, 10) && reals_are(&s, 8, tri, 9));
    scene_free(&s);
    /* Cone radii may be 0 at either end; a quadric needs only one term. */
    s = parse_ok(CAM LIGHTS PIGS FINS "2\n0 0 cone 0 0 0 0  0 1 0 2\n"
                                      "0 0 quadric 0 0 0 0 0 0 0 0 1 0\n", __LINE__);
    CHECK(s.nobjects == 2);
    scene_free(&s);
}

/* Writes text to dir/name. */
static void write_file(const char *dir, const char *name, const void *data, size_t len)
{
    char path[512];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "wb");
    if (f) {
        fwrite(data, 1, len, f);
        fclose(f);
    }
}

/* Files a scene names are found beside it: a mesh and a texture, with
 * names that look like numbers; the mesh's triangles become its numbers;
 * a texture named twice is read once. */
static void test_files_beside_scene(void)
{
    char dir[] = "/tmp/tp2-parser-XXXXXX";
    if (!mkdtemp(dir)) {
        expect(0, "mkdtemp");
        return;
    }
    const char obj[] = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";
    write_file(dir, "1.obj", obj, sizeof obj - 1);
    const char ppm[] = "P3 2 1 255 255 0 0 0 0 255\n";
    write_file(dir, "2x.ppm", ppm, sizeof ppm - 1);
    char name[600];
    snprintf(name, sizeof name, "%s/t.txt", dir);
    const char *text = CAM LIGHTS "3\ntexmap 2x.ppm 1 0 0 0 0 1 0 0\n"
                       "gradient 0 0 0 1 0 0  1 0 0  0 0 1\n"
                       "texmap ./2x.ppm 0 0 1 0 1 0 0 0.5\n" FINS
                       "1\n0 0 mesh 1.obj\n";
    struct scene s;
    char err[512];
    int rc = scene_parse_text(name, text, strlen(text), &s, err, sizeof err);
    expect(rc == 0, "parse with files: %s", rc ? err : "");
    if (rc == 0) {
        CHECK(s.npigments == 3 && s.pigments[0].kind == PIGMENT_TEXMAP &&
              s.pigments[1].kind == PIGMENT_GRADIENT && s.pigments[2].kind == PIGMENT_TEXMAP);
        CHECK(s.ntextures == 2); /* paths are compared as resolved: ./2x.ppm is another */
        CHECK(s.textures[0].width == 2 && s.textures[0].height == 1 &&
              s.textures[0].rgb[0] == 255 && s.textures[0].rgb[5] == 255);
        CHECK(s.pigments[0].s[0] == 1 && s.pigments[2].t[3] == 0.5);
        CHECK(vec_eq(s.pigments[1].p1, 1, 0, 0) && vec_eq(s.pigments[1].color2, 0, 0, 1));
        /* Slopes: the texture steps by 255 between its two texels, and s
         * crosses its 2 texels per unit; the gradient spans 1 over 1. */
        CHECK(s.textures[0].step == 1.0 && s.textures[1].step == 1.0);
        CHECK(pigment_kinds[PIGMENT_TEXMAP].slope(&s, &s.pigments[0]) == 2.0);
        CHECK(pigment_kinds[PIGMENT_GRADIENT].slope(&s, &s.pigments[1]) == 1.0);
        CHECK(!pigment_kinds[PIGMENT_SOLID].slope && !pigment_kinds[PIGMENT_CHECKER].slope);
        static const double tris[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 0, 0, 1, 1, 0, 0, 1, 0};
        CHECK(s.objects[0].kind == SHAPE_MESH && reals_are(&s, 0, tris, 18));
        scene_free(&s);
    }
    /* The same file named the same way twice is decoded once. */
    text = CAM LIGHTS "2\ntexmap 2x.ppm 1 0 0 0 0 1 0 0\ntexmap 2x.ppm 1 0 0 0 0 1 0 0\n"
           "0\n0\n";
    rc = scene_parse_text(name, text, strlen(text), &s, err, sizeof err);
    CHECK(rc == 0 && s.ntextures == 1 && s.pigments[1].texture == 0);
    if (rc == 0)
        scene_free(&s);
    /* `textmap` (the course's 2022 handout) is texmap, keyword and all:
     * the same kind, the same numbers, the same decoded texture. */
    text = CAM LIGHTS "2\ntextmap 2x.ppm\n 1 0 0 0\n 0 1 0 0.5\ntexmap 2x.ppm 1 0 0 0 0 1 0 0.5\n"
           "0\n0\n";
    rc = scene_parse_text(name, text, strlen(text), &s, err, sizeof err);
    expect(rc == 0, "textmap: %s", rc ? err : "");
    if (rc == 0) {
        CHECK(s.pigments[0].kind == PIGMENT_TEXMAP && s.ntextures == 1 &&
              s.pigments[1].texture == 0 && s.pigments[0].s[0] == 1 && s.pigments[0].t[3] == 0.5 &&
              memcmp(s.pigments[0].s, s.pigments[1].s, sizeof s.pigments[0].s) == 0 &&
              memcmp(s.pigments[0].t, s.pigments[1].t, sizeof s.pigments[0].t) == 0);
        scene_free(&s);
    }
    /* A malformed OBJ is reported at its own line and column. */
    write_file(dir, "bad.obj", "v 0 0 0\nf 1 2 3\n", 16);
    text = CAM LIGHTS PIGS FINS "1\n0 0 mesh bad.obj\n";
    rc = scene_parse_text(name, text, strlen(text), &s, err, sizeof err);
    char want[700];
    snprintf(want, sizeof want, "%s/bad.obj:2:5: error: vertex index '2' is out of range "
                                "(1 vertex so far)", dir);
    expect(rc == -1 && strcmp(err, want) == 0, "bad OBJ:\n  got  %s\n  want %s", err, want);
    const char *names[] = {"1.obj", "2x.ppm", "bad.obj", "t.txt"};
    for (int i = 0; i < 4; i++) {
        char path[700];
        snprintf(path, sizeof path, "%s/%s", dir, names[i]);
        remove(path);
    }
    rmdir(dir);
}

/* Object lists grow as they are read; many entries, each checked. */
static void test_many_objects(void)
{
    enum { N = 1000 };
    size_t cap = 64 + N * 32;
    char *text = malloc(cap);
    size_t len = (size_t)snprintf(text, cap, CAM LIGHTS PIGS FINS "%d\n", N);
    for (int i = 0; i < N; i++)
        len += (size_t)snprintf(text + len, cap - len,
                                "0 0 sphere %d 0 -5 1\n", i);
    struct scene s = parse_ok(text, __LINE__);
    int ok = s.nobjects == N;
    for (int i = 0; ok && i < N; i++)
        ok = scene_object_reals(&s, &s.objects[i])[0] == i;
    CHECK(ok);
    scene_free(&s);
    free(text);
}

/* The text need not be NUL terminated: the last byte is a digit that
 * strtod would extend past the buffer (ASan catches a read past it). */
static void test_unterminated_buffer(void)
{
    static const char src[] = BASE "samples 4";
    size_t len = sizeof src - 1;
    char *text = malloc(len);
    memcpy(text, src, len);
    struct scene s;
    char err[256];
    CHECK(scene_parse_text("t.txt", text, len, &s, err, sizeof err) == 0);
    CHECK(s.samples == 4);
    scene_free(&s);
    /* And an error at the very end of such a buffer. */
    memcpy(text + len - 1, "0", 1);
    CHECK(scene_parse_text("t.txt", text, len, &s, err, sizeof err) == -1);
    CHECK(strcmp(err, "t.txt:14:9: error: expected a positive integer "
                      "sample count, found '0'") == 0);
    free(text);
}

/* A text far larger than the lexer's window (lexer.c), made of long
 * numbers, so that reads end inside numbers everywhere: each face number
 * must still read as strtod reads its whole text, and an error at the end
 * has its exact line and column. */
static void test_streamed_window(void)
{
    enum { FACES = 4000 }; /* 16000 numbers of 38 bytes: 600 KB */
    size_t cap = 64 + sizeof BASE + FACES * 4 * 40;
    char *text = malloc(cap);
    int used = snprintf(text, cap, "%s", CAM LIGHTS PIGS FINS "1\n0 0 polyhedron 4000\n");
    for (int f = 0; f < FACES; f++)
        for (int k = 0; k < 4; k++)
            used += snprintf(text + used, cap - (size_t)used, "%s%.30e%c",
                             f % 7 == 0 && k == 0 ? "-" : "", 1.0 + f * 1e-6 + k * 1e-9,
                             k == 3 ? '\n' : ' ');
    struct scene s = parse_ok(text, __LINE__);
    CHECK(s.nobjects == 1 && s.nreals == 4 * FACES);
    int same = s.nreals == 4 * FACES;
    const char *at = strstr(text, "polyhedron 4000\n") + 16;
    for (size_t i = 0; same && i < s.nreals; i++) {
        char *end;
        same = strtod(at, &end) == s.reals[i];
        at = end;
    }
    CHECK(same);
    scene_free(&s);
    /* Something wrong at the very end: line 14 + FACES, column 1. */
    used += snprintf(text + used, cap - (size_t)used, "bogus");
    char err[256], want[256];
    snprintf(want, sizeof want, "t.txt:%d:1: error: expected 'samples', 'lens', 'fog', "
             "'arealight' or end of file, found 'bogus'", 14 + FACES);
    CHECK(scene_parse_text("t.txt", text, (size_t)used, &s, err, sizeof err) == -1);
    CHECK(strcmp(err, want) == 0);
    free(text);
}

/* Tokens up to LEXER_TOKEN_MAX bytes read; a longer one is an error at its
 * start. Comments and blanks of any length cost nothing. */
static void test_token_limit(void)
{
    size_t cap = 3 * LEXER_TOKEN_MAX + sizeof BASE + 64;
    char *text = malloc(cap);
    /* An eye x of exactly LEXER_TOKEN_MAX bytes: 0.5000...0. */
    memset(text, '0', LEXER_TOKEN_MAX);
    text[1] = '.';
    text[2] = '5';
    snprintf(text + LEXER_TOKEN_MAX, cap - LEXER_TOKEN_MAX, " %s", BASE + 2);
    struct scene s = parse_ok(text, __LINE__);
    CHECK(s.eye[0] == 0.5);
    scene_free(&s);
    /* One byte more. */
    memset(text, '0', LEXER_TOKEN_MAX + 1);
    text[1] = '.';
    text[2] = '5';
    snprintf(text + LEXER_TOKEN_MAX + 1, cap - LEXER_TOKEN_MAX - 1, " %s", BASE + 2);
    EXPECT_ERROR(text, "t.txt:1:1: error: token '0.500000000000000000000000000000...' "
                       "is longer than 65536 bytes");
    /* A word too: the header's name, after a comment of 3 windows' size. */
    memset(text, ' ', 2 * LEXER_TOKEN_MAX);
    text[0] = '#';
    text[2 * LEXER_TOKEN_MAX] = '\n';
    memset(text + 2 * LEXER_TOKEN_MAX + 1, 'a', LEXER_TOKEN_MAX + 1);
    text[3 * LEXER_TOKEN_MAX + 2] = '\0';
    EXPECT_ERROR(text, "t.txt:2:1: error: token 'aaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaa...' "
                       "is longer than 65536 bytes");
    /* A NUL byte far in is reported where it is. */
    memset(text, '\n', 2 * LEXER_TOKEN_MAX);
    memcpy(text + 2 * LEXER_TOKEN_MAX, " \0", 2);
    expect_error_n(text, 2 * LEXER_TOKEN_MAX + 2,
                   "t.txt:131073:2: error: unexpected character '\\x00'", __LINE__);
    free(text);
}

/* The largest length the shaders get, and where (scene_length_limit):
 * object numbers as packed (a plane's normal is scaled to 1), not the
 * ambient light's unused position. */
static void test_max_length(void)
{
    struct scene s = parse_ok(CAM "2\n5e30 0 0 1 1 1 0 0 0\n3 -40 0 1 1 1 1 0 0\n" PIGS FINS
                              "2\n0 0 plane 0 0 1e30 2e30\n0 0 sphere 0 0 -5 1\n",
                              __LINE__);
    CHECK(s.max_length == 40 && s.max_length_line == 7 && s.max_length_col == 1);
    CHECK(s.max_length_what && strcmp(s.max_length_what, "light position") == 0);
    scene_free(&s);
    s = parse_ok(CAM LIGHTS PIGS FINS "2\n0 0 plane 0 0 1e-30 2e30\n"
                 "0 0 sphere 0 0 -5 1e20\nlens 0 1e21\n", __LINE__);
    CHECK(s.max_length == 2e60 && s.max_length_line == 13 && s.max_length_col == 5);
    CHECK(s.max_length_what && strcmp(s.max_length_what, "plane") == 0);
    scene_free(&s);
    CHECK(scene_length_limit(false) == 0x1p60 && scene_length_limit(true) == 0x1p120);
}

static void test_api_edges(void)
{
    struct scene s;
    char small[12];
    /* A short err buffer gets a cut, terminated message; NULL is allowed. */
    CHECK(scene_parse_text("t.txt", "", 0, &s, small, sizeof small) == -1);
    CHECK(strcmp(small, "t.txt:1:1: ") == 0);
    CHECK(scene_parse_text(NULL, "x", 1, &s, NULL, 0) == -1);
    char err[256];
    /* "x" is a header name; the width is missing. */
    CHECK(scene_parse_text(NULL, "x", 1, &s, err, sizeof err) == -1);
    CHECK(strcmp(err, "<input>:1:2: error: expected a positive integer "
                      "image width, found end of file") == 0);
    /* Files. */
    CHECK(scene_parse_file("/nonexistent/tp2/scene.txt", &s, err,
                           sizeof err) == -1);
    CHECK(strcmp(err, "tp2: cannot read '/nonexistent/tp2/scene.txt': "
                      "No such file or directory") == 0);
    CHECK(scene_parse_file(".", &s, err, sizeof err) == -1);
    CHECK(strncmp(err, "tp2: cannot read '.': ", 22) == 0);
    /* scene_free is safe on a zeroed scene and twice. */
    memset(&s, 0, sizeof s);
    scene_free(&s);
    scene_free(&s);
    CHECK(s.lights == NULL);
}

/* ---- errors ------------------------------------------------------------ */

static void test_lexical_errors(void)
{
    EXPECT_ERROR("", "t.txt:1:1: error: expected a number, found end of file");
    EXPECT_ERROR("  # only a comment\n",
                 "t.txt:2:1: error: expected a number, found end of file");
    EXPECT_ERROR("0 0 0\n0 0 1abc",
                 "t.txt:2:5: error: malformed number '1abc'");
    EXPECT_ERROR("0 0 0\n0 0 -1\n0 1 0\n3x",
                 "t.txt:4:1: error: malformed number '3x'");
    EXPECT_ERROR("0 0 0 0 0 -1 0 1 0 2.5.3e",
                 "t.txt:1:23: error: malformed number '.3e'");
    EXPECT_ERROR("0 0 0 0 0 -1 0 1 0 1--2",
                 "t.txt:1:20: error: malformed number '1--2'");
    EXPECT_ERROR("0 0 0 0 0 -1 0 1 0 nan",
                 "t.txt:1:20: error: expected a finite number, found 'nan'");
    EXPECT_ERROR("0 0 0 0 0 -1 0 1 0 INF",
                 "t.txt:1:20: error: expected a finite number, found 'INF'");
    EXPECT_ERROR("0 0 0 0 0 -1 0 1 0 infinity",
                 "t.txt:1:20: error: expected a finite number, "
                 "found 'infinity'");
    EXPECT_ERROR("0 0 0 0 0 -1 0 1 0 -nan",
                 "t.txt:1:20: error: expected a finite number, found '-nan'");
    EXPECT_ERROR("0 0 0 0 0 -1 0 1 0 1e999",
                 "t.txt:1:20: error: expected a finite number, "
                 "found '1e999'");
    EXPECT_ERROR("0 0 0 0 0 -1 0 1 0 -1e400",
                 "t.txt:1:20: error: expected a finite number, "
                 "found '-1e400'");
    /* "info" is a word, not "inf" followed by junk. */
    EXPECT_ERROR("0 0 0 0 0 -1 0 1 0 info",
                 "t.txt:1:20: error: expected a number, found 'info'");
    EXPECT_ERROR("0 0 0\n0 0 sphre",
                 "t.txt:2:5: error: expected a number, found 'sphre'");
    EXPECT_ERROR("0 0 0\n\t\t-\n",
                 "t.txt:2:3: error: expected a number, found '-'");
    EXPECT_ERROR("0 0 0\r\n0 0 x\r\n",
                 "t.txt:2:5: error: expected a number, found 'x'");
}

static void test_byte_errors(void)
{
    expect_error_n("0 0\0 0", 6, "t.txt:1:4: error: unexpected character "
                                 "'\\x00'", __LINE__);
    expect_error_n("\0", 1, "t.txt:1:1: error: unexpected character '\\x00'",
                   __LINE__);
    expect_error_n("0 0 0 # a comment \0 with a NUL\n", 31,
                   "t.txt:1:19: error: unexpected character '\\x00'",
                   __LINE__);
    EXPECT_ERROR("0 0 \xff\xfe",
                 "t.txt:1:5: error: expected a number, found '\\xff\\xfe'");
    EXPECT_ERROR("0 0 0 0 0 "
                 "aaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaa",
                 "t.txt:1:11: error: expected a number, found "
                 "'aaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaa...'");
    EXPECT_ERROR("0 0 0 0 0 "
                 "1234567890123456789012345678901234567890abc",
                 "t.txt:1:11: error: malformed number "
                 "'12345678901234567890123456789012...'");
}

/* A UTF-8 byte-order mark before the text is skipped: the scene parses,
 * and positions count from the first byte after it. Anywhere else, or
 * cut short, it is an error like any other bytes. */
static void test_byte_order_mark(void)
{
    struct scene s = parse_ok("\xef\xbb\xbf" BASE, __LINE__);
    CHECK(s.nlights == 2 && s.nobjects == 1 && s.fov == 45);
    scene_free(&s);
    s = parse_ok("\xef\xbb\xbf# comment\n" BASE, __LINE__);
    CHECK(s.nobjects == 1);
    scene_free(&s);
    s = parse_ok("\xef\xbb\xbf" "out.ppm 64 48\n" BASE, __LINE__);
    CHECK(s.has_size && s.width == 64 && s.height == 48);
    scene_free(&s);
    EXPECT_ERROR("\xef\xbb\xbf" "0 0 y\n", "t.txt:1:5: error: expected a number, found 'y'");
    EXPECT_ERROR("\xef\xbb\xbf" "0 0 0\n0 0 x\n",
                 "t.txt:2:5: error: expected a number, found 'x'");
    /* Only one mark, only at the start. */
    EXPECT_ERROR("0 \xef\xbb\xbf", "t.txt:1:3: error: expected a number, found "
                                      "'\\xef\\xbb\\xbf'");
    EXPECT_ERROR("\xef\xbb\xbf" "0 0 0\n\xef\xbb\xbf",
                 "t.txt:2:1: error: expected a number, found '\\xef\\xbb\\xbf'");
}

/* A file name with bytes outside printable ASCII (escape sequences, new
 * lines) is shown with them as \xNN, whole, however long. */
static void test_escaped_names(void)
{
    struct scene s;
    char err[4096];
    const char *text = "0 0 x\n";
    int rc = scene_parse_text("a\x1b[2Jb\nc.txt", text, strlen(text), &s, err, sizeof err);
    CHECK(rc == -1 &&
          strcmp(err, "a\\x1b[2Jb\\x0ac.txt:1:5: error: expected a number, found 'x'") == 0);
    char name[301];
    memset(name, 'n', 300);
    name[300] = '\0';
    name[150] = '\t';
    rc = scene_parse_text(name, text, strlen(text), &s, err, sizeof err);
    CHECK(rc == -1 && strncmp(err, name, 150) == 0 && strncmp(err + 150, "\\x09", 4) == 0 &&
          strncmp(err + 154, name + 151, 149) == 0 && strcmp(err + 303, ":1:5: error: "
          "expected a number, found 'x'") == 0);
    CHECK(SCENE_ERROR_SIZE(300) > strlen(err));
    rc = scene_parse_file("/nonexistent/\x01.txt", &s, err, sizeof err);
    const char *want = "tp2: cannot read '/nonexistent/\\x01.txt': ";
    CHECK(rc == -1 && strncmp(err, want, strlen(want)) == 0);
}

static void test_truncation_errors(void)
{
    EXPECT_ERROR("0 0 0\n0 0 -1\n0 1 0\n",
                 "t.txt:4:1: error: expected a number, found end of file");
    EXPECT_ERROR(CAM, "t.txt:5:1: error: expected a non-negative integer "
                      "count, found end of file");
    EXPECT_ERROR(CAM "2\n0 0 0 1 1 1 1 0 0\n10 10 10",
                 "t.txt:7:9: error: expected a number, found end of file");
    EXPECT_ERROR(CAM LIGHTS "1\nchecker 1 0 0 0 0 1\n",
                 "t.txt:10:1: error: expected a number, found end of file");
    EXPECT_ERROR(CAM LIGHTS "1\n",
                 "t.txt:9:1: error: expected " PIGMENT_WORDS ", found end of file");
    EXPECT_ERROR(CAM LIGHTS PIGS "2\n0.2 0.6 0.3 20 0 0 0\n",
                 "t.txt:12:1: error: expected a number, found end of file");
    /* A huge count must fail at the end, not allocate for it. */
    EXPECT_ERROR(CAM LIGHTS PIGS FINS "2000000000\n0 0 sphere 0 0 -5 1\n",
                 "t.txt:14:1: error: expected a non-negative integer "
                 "pigment index, found end of file");
    EXPECT_ERROR(CAM LIGHTS PIGS FINS "1\n0 0 sphere 0 0 -5",
                 "t.txt:13:18: error: expected a number, found end of file");
    EXPECT_ERROR(CAM LIGHTS PIGS FINS "1\n0 0",
                 "t.txt:13:4: error: expected " SHAPE_WORDS ", found end of file");
    EXPECT_ERROR("out.ppm 640",
                 "t.txt:1:12: error: expected a positive integer image "
                 "height, found end of file");
    EXPECT_ERROR(BASE "fog 1 1 1",
                 "t.txt:14:10: error: expected a number, found end of file");
}

static void test_count_errors(void)
{
    EXPECT_ERROR(CAM "-1\n", "t.txt:5:1: error: expected a non-negative "
                             "integer count, found '-1'");
    EXPECT_ERROR(CAM "3.0\n", "t.txt:5:1: error: expected a non-negative "
                              "integer count, found '3.0'");
    EXPECT_ERROR(CAM LIGHTS "1e3\n", "t.txt:8:1: error: expected a "
                                     "non-negative integer count, found "
                                     "'1e3'");
    EXPECT_ERROR(CAM LIGHTS "+1\n", "t.txt:8:1: error: expected a "
                                    "non-negative integer count, found '+1'");
    EXPECT_ERROR(CAM LIGHTS PIGS "two\n", "t.txt:10:1: error: expected a "
                                          "non-negative integer count, "
                                          "found 'two'");
    EXPECT_ERROR(CAM LIGHTS PIGS FINS "2147483648\n",
                 "t.txt:12:1: error: count 2147483648 is too large "
                 "(at most 2147483647)");
    EXPECT_ERROR("out.ppm -640 480\n", "t.txt:1:9: error: expected a "
                                       "positive integer image width, "
                                       "found '-640'");
    EXPECT_ERROR("out.ppm 640 0\n", "t.txt:1:13: error: expected a positive "
                                    "integer image height, found '0'");
    EXPECT_ERROR("out.ppm 640 99999999999\n",
                 "t.txt:1:13: error: image height 99999999999 is too large "
                 "(at most 2147483647)");
}

static void test_index_errors(void)
{
    EXPECT_ERROR(CAM LIGHTS PIGS FINS "1\n1 0 sphere 0 0 -5 1\n",
                 "t.txt:13:1: error: pigment index 1 is out of range "
                 "(1 pigment)");
    EXPECT_ERROR(CAM LIGHTS PIGS FINS "1\n0 3 sphere 0 0 -5 1\n",
                 "t.txt:13:3: error: finish index 3 is out of range "
                 "(1 finish)");
    EXPECT_ERROR(CAM LIGHTS PIGS "2\n1 1 1 1 0 0 0\n1 1 1 1 0 0 0\n"
                                 "1\n0 2 plane 0 0 1 0\n",
                 "t.txt:14:3: error: finish index 2 is out of range "
                 "(2 finishes)");
    EXPECT_ERROR(CAM LIGHTS PIGS FINS "1\n-1 0 sphere 0 0 -5 1\n",
                 "t.txt:13:1: error: expected a non-negative integer "
                 "pigment index, found '-1'");
    EXPECT_ERROR(CAM LIGHTS PIGS FINS "1\n0 0.0 sphere 0 0 -5 1\n",
                 "t.txt:13:3: error: expected a non-negative integer "
                 "finish index, found '0.0'");
    EXPECT_ERROR(CAM LIGHTS PIGS FINS "1\n99999999999 0 sphere 0 0 -5 1\n",
                 "t.txt:13:1: error: pigment index 99999999999 is out of "
                 "range (1 pigment)");
    EXPECT_ERROR(CAM LIGHTS "0\n" FINS "1\n0 0 sphere 0 0 -5 1\n",
                 "t.txt:12:1: error: pigment index 0 is out of range "
                 "(0 pigments)");
}

static void test_keyword_errors(void)
{
    EXPECT_ERROR(CAM LIGHTS "1\nSolid 1 0 0\n",
                 "t.txt:9:1: error: expected " PIGMENT_WORDS ", found 'Solid'");
    EXPECT_ERROR(CAM LIGHTS "1\n1 0 0\n",
                 "t.txt:9:1: error: expected " PIGMENT_WORDS ", found '1'");
    EXPECT_ERROR(CAM LIGHTS PIGS FINS "1\n0 0 cube 0 0 -5 1\n",
                 "t.txt:13:5: error: expected " SHAPE_WORDS ", found 'cube'");
}

static void test_camera_errors(void)
{
    EXPECT_ERROR("1 2 3\n1 2 3\n0 0 1\n45\n",
                 "t.txt:2:1: error: center must differ from eye");
    EXPECT_ERROR("0 0 0\n0 0 -1\n0 0 5\n45\n",
                 "t.txt:3:1: error: up vector is parallel to the view "
                 "direction");
    EXPECT_ERROR("0 0 0\n0 0 -1\n0 0 0\n45\n",
                 "t.txt:3:1: error: up vector is parallel to the view "
                 "direction");
    /* Relative test: tiny vectors, parallel, still parallel. */
    EXPECT_ERROR("0 0 0\n1e-200 2e-200 0\n1e-300 2e-300 0\n45\n",
                 "t.txt:3:1: error: up vector is parallel to the view "
                 "direction");
    EXPECT_ERROR("0 0 0\n0 0 -1\n0 1 0\n0\n",
                 "t.txt:4:1: error: expected a field of view between 0 and "
                 "180 degrees (exclusive), found '0'");
    EXPECT_ERROR("0 0 0\n0 0 -1\n0 1 0\n180.0\n",
                 "t.txt:4:1: error: expected a field of view between 0 and "
                 "180 degrees (exclusive), found '180.0'");
    EXPECT_ERROR("0 0 0\n0 0 -1\n0 1 0\n-30\n",
                 "t.txt:4:1: error: expected a field of view between 0 and "
                 "180 degrees (exclusive), found '-30'");
}

static void test_value_errors(void)
{
    EXPECT_ERROR(CAM "1\n0 0 0 1 1 1 1 -1 0\n",
                 "t.txt:6:15: error: expected a non-negative attenuation "
                 "coefficient, found '-1'");
    EXPECT_ERROR(CAM LIGHTS "1\nchecker 1 1 1 0 0 0 0\n",
                 "t.txt:9:21: error: expected a positive checker cube side, "
                 "found '0'");
    EXPECT_ERROR(CAM LIGHTS PIGS "1\n0 1 0 1 0 0.5 0\n",
                 "t.txt:11:15: error: expected a positive index of "
                 "refraction since kt > 0, found '0'");
    EXPECT_ERROR(CAM LIGHTS PIGS FINS "1\n0 0 sphere 0 0 -5 -1\n",
                 "t.txt:13:19: error: expected a positive sphere radius, "
                 "found '-1'");
    EXPECT_ERROR(CAM LIGHTS PIGS FINS "1\n0 0 plane 0 0 0 5\n",
                 "t.txt:13:11: error: plane normal (a b c) must not be zero");
}

static void test_directive_errors(void)
{
    EXPECT_ERROR(BASE "samples 4\nsamples 4\n",
                 "t.txt:15:1: error: duplicate 'samples' directive "
                 "(first at 14:1)");
    EXPECT_ERROR(BASE "lens 0 1 fog 0 0 0 1 lens 0 1\n",
                 "t.txt:14:22: error: duplicate 'lens' directive "
                 "(first at 14:1)");
    EXPECT_ERROR(BASE "samples 0\n",
                 "t.txt:14:9: error: expected a positive integer sample "
                 "count, found '0'");
    EXPECT_ERROR(BASE "samples 2.5\n",
                 "t.txt:14:9: error: expected a positive integer sample "
                 "count, found '2.5'");
    EXPECT_ERROR(BASE "lens -0.1 5\n",
                 "t.txt:14:6: error: expected a non-negative lens radius, "
                 "found '-0.1'");
    EXPECT_ERROR(BASE "lens 0.1 0\n",
                 "t.txt:14:10: error: expected a positive focal distance, "
                 "found '0'");
    EXPECT_ERROR(BASE "fog 1 1 1 -2\n",
                 "t.txt:14:11: error: expected a non-negative fog density, "
                 "found '-2'");
    EXPECT_ERROR(BASE "arealight 0 1 4\n",
                 "t.txt:14:11: error: light 0 is the ambient light and "
                 "cannot be an area light");
    EXPECT_ERROR(BASE "arealight 2 1 4\n",
                 "t.txt:14:11: error: light index 2 is out of range "
                 "(2 lights)");
    EXPECT_ERROR(BASE "arealight 1 0 4\n",
                 "t.txt:14:13: error: expected a positive area light radius, "
                 "found '0'");
    EXPECT_ERROR(BASE "arealight 1 1 0\n",
                 "t.txt:14:15: error: expected a positive integer sample "
                 "count, found '0'");
    EXPECT_ERROR(BASE "junk\n",
                 "t.txt:14:1: error: expected 'samples', 'lens', 'fog', "
                 "'arealight' or end of file, found 'junk'");
    EXPECT_ERROR(BASE "samples 2 7\n",
                 "t.txt:14:11: error: expected 'samples', 'lens', 'fog', "
                 "'arealight' or end of file, found '7'");
    EXPECT_ERROR(BASE "Samples 2\n",
                 "t.txt:14:1: error: expected 'samples', 'lens', 'fog', "
                 "'arealight' or end of file, found 'Samples'");
}

int main(void)
{
    test_plain_variant();
    test_header_variant();
    test_comments();
    test_number_forms();
    test_whitespace_forms();
    test_directives();
    test_semantic_edges();
    test_short_finish();
    test_shape_kinds();
    test_files_beside_scene();
    test_many_objects();
    test_unterminated_buffer();
    test_streamed_window();
    test_token_limit();
    test_max_length();
    test_api_edges();
    test_lexical_errors();
    test_byte_errors();
    test_byte_order_mark();
    test_escaped_names();
    test_truncation_errors();
    test_count_errors();
    test_index_errors();
    test_keyword_errors();
    test_camera_errors();
    test_value_errors();
    test_directive_errors();
    return unit_report();
}
