/* scene_parse.c: scene text -> struct scene, one function per section;
 * each kind of pigment and object reads its own parameters through the
 * tables of pigments.c and shapes.c, and everything reads its tokens
 * through the reader (scene_reader.c).
 *
 * The parser looks one token ahead (p->tok). A lexical error is reported
 * only when the parser reaches it, so errors come out in text order. */
#include "scene_parse.h"

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lexer.h"
#include "pigments.h"
#include "scene_reader.h"
#include "scene_reader_state.h"
#include "shapes.h"

/* |w x up| below this (unit vectors) means up gives no usable "up". */
#define PARALLEL_EPS 1e-9

/* ---- camera ------------------------------------------------------------ */

/* The optional header variant: an output name (ignored: the command line
 * names the output), then W H. A first token that is not a number marks
 * it; a number-like name such as "1.ppm" is a malformed number instead. */
static int parse_header(struct scene_reader *p)
{
    uint32_t w = 0, h = 0;
    if (p->tok.kind != TOKEN_WORD)
        return 0;
    read_next(p);
    struct token w_at = p->tok;
    if (read_int(p, 1, "a positive integer image width", "image width", &w))
        return -1;
    struct token h_at = p->tok;
    if (read_int(p, 1, "a positive integer image height", "image height", &h))
        return -1;
    if (w > TP2_MAX_IMAGE_SIDE || h > TP2_MAX_IMAGE_SIDE)
        return read_fail(p, w > TP2_MAX_IMAGE_SIDE ? &w_at : &h_at,
                       "image %s %u is too large (at most %d)",
                       w > TP2_MAX_IMAGE_SIDE ? "width" : "height",
                       w > TP2_MAX_IMAGE_SIDE ? w : h, TP2_MAX_IMAGE_SIDE);
    p->s.has_size = 1;
    p->s.width = (int)w;
    p->s.height = (int)h;
    return 0;
}

/* Scales v to unit length without overflow; returns 0 if v is zero. */
static int unit(const double v[3], double u[3])
{
    double m = fmax(fabs(v[0]), fmax(fabs(v[1]), fabs(v[2])));
    if (m == 0)
        return 0;
    double a[3] = { v[0] / m, v[1] / m, v[2] / m };
    double len = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    for (int i = 0; i < 3; i++)
        u[i] = a[i] / len;
    return 1;
}

/* 1 if up gives no direction across the view: zero, or parallel to
 * center - eye within PARALLEL_EPS (relative, so any scale works). */
static int up_is_parallel(const struct scene *s)
{
    double d[3], w[3], u[3];
    for (int i = 0; i < 3; i++)
        d[i] = s->center[i] - s->eye[i];
    if (!isfinite(d[0]) || !isfinite(d[1]) || !isfinite(d[2]))
        for (int i = 0; i < 3; i++) /* same direction, cannot overflow */
            d[i] = s->center[i] / 2 - s->eye[i] / 2;
    if (!unit(d, w) || !unit(s->up, u))
        return 1;
    double c[3] = { w[1] * u[2] - w[2] * u[1], w[2] * u[0] - w[0] * u[2],
                    w[0] * u[1] - w[1] * u[0] };
    return sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]) < PARALLEL_EPS;
}

static int parse_camera(struct scene_reader *p)
{
    struct scene *s = &p->s;
    struct token eye_at, center_at, up_at, fov_at;
    if (read_numbers(p, s->eye, 3, &eye_at) ||
        read_numbers(p, s->center, 3, &center_at))
        return -1;
    read_note_lengths(p, &eye_at, s->eye, "camera eye");
    if (s->eye[0] == s->center[0] && s->eye[1] == s->center[1] &&
        s->eye[2] == s->center[2])
        return read_fail(p, &center_at, "center must differ from eye");
    if (read_numbers(p, s->up, 3, &up_at))
        return -1;
    if (up_is_parallel(s))
        return read_fail(p, &up_at,
                       "up vector is parallel to the view direction");
    if (read_number(p, &s->fov, &fov_at))
        return -1;
    if (!(s->fov > 0 && s->fov < 180))
        return read_expected(p, &fov_at,
                          "a field of view between 0 and 180 degrees "
                          "(exclusive)");
    return 0;
}

/* ---- lights, pigments, finishes ---------------------------------------- */

/* The ambient light's position is never used, so it is not a length. */
static int parse_light(struct scene_reader *p, struct scene_light *l, int ambient)
{
    struct token at;
    if (read_numbers(p, l->pos, 3, &at) || read_numbers(p, l->color, 3, NULL))
        return -1;
    if (!ambient)
        read_note_lengths(p, &at, l->pos, "light position");
    for (int i = 0; i < 3; i++)
        if (read_bounded(p, &l->att[i], 1,
                         "a non-negative attenuation coefficient"))
            return -1;
    return 0;
}

static int parse_lights(struct scene_reader *p)
{
    struct scene *s = &p->s;
    size_t n = 0;
    if (read_count(p, &n))
        return -1;
    for (size_t i = 0; i < n; i++) {
        void *a = read_grow(p, s->lights, &p->cap_lights, i + 1, sizeof *s->lights);
        if (!a)
            return -1;
        s->lights = a;
        memset(&s->lights[i], 0, sizeof s->lights[i]);
        s->nlights = i + 1;
        if (parse_light(p, &s->lights[i], i == 0))
            return -1;
    }
    return 0;
}

/* A pigment keyword (or its alias: the course's 2022 handout writes
 * `textmap`), then that kind's parameters (pigments.c). */
static int parse_pigment(struct scene_reader *p, struct scene_pigment *pg)
{
    for (int k = 0; k < PIGMENT_COUNT; k++)
        if (read_is_word(&p->tok, pigment_kinds[k].keyword) ||
            (pigment_kinds[k].alias && read_is_word(&p->tok, pigment_kinds[k].alias))) {
            read_next(p);
            pg->kind = k;
            return pigment_kinds[k].read(p, pg);
        }
    return read_fail_expected(p, pigment_keywords());
}

static int parse_pigments(struct scene_reader *p)
{
    struct scene *s = &p->s;
    size_t n = 0;
    if (read_count(p, &n))
        return -1;
    for (size_t i = 0; i < n; i++) {
        void *a = read_grow(p, s->pigments, &p->cap_pigments, i + 1,
                       sizeof *s->pigments);
        if (!a)
            return -1;
        s->pigments = a;
        memset(&s->pigments[i], 0, sizeof s->pigments[i]);
        s->npigments = i + 1;
        if (parse_pigment(p, &s->pigments[i]))
            return -1;
    }
    return 0;
}

/* `ka kd ks n kr kt ior`, or the short form `ka kd ks n kr` of other
 * courses' files (SPEC 3): kr is last when the next token begins on a later
 * line, and then kt = 0, ior = 1. */
static int parse_finish(struct scene_reader *p, struct scene_finish *f)
{
    struct token kr_at, ior_at;
    if (read_number(p, &f->ka, NULL) || read_number(p, &f->kd, NULL) ||
        read_number(p, &f->ks, NULL) || read_number(p, &f->n, NULL) ||
        read_number(p, &f->kr, &kr_at))
        return -1;
    if (p->tok.kind != TOKEN_EOF && p->tok.line > kr_at.line) {
        f->kt = 0;
        f->ior = 1;
        return 0;
    }
    if (read_number(p, &f->kt, NULL) || read_number(p, &f->ior, &ior_at))
        return -1;
    if (f->kt > 0 && !(f->ior > 0))
        return read_expected(p, &ior_at,
                          "a positive index of refraction since kt > 0");
    return 0;
}

static int parse_finishes(struct scene_reader *p)
{
    struct scene *s = &p->s;
    size_t n = 0;
    if (read_count(p, &n))
        return -1;
    for (size_t i = 0; i < n; i++) {
        void *a = read_grow(p, s->finishes, &p->cap_finishes, i + 1,
                       sizeof *s->finishes);
        if (!a)
            return -1;
        s->finishes = a;
        memset(&s->finishes[i], 0, sizeof s->finishes[i]);
        s->nfinishes = i + 1;
        if (parse_finish(p, &s->finishes[i]))
            return -1;
    }
    return 0;
}

/* ---- objects ----------------------------------------------------------- */

/* Indices, an object keyword, then that kind's parameters (shapes.c),
 * which become the object's numbers. */
static int parse_object(struct scene_reader *p, struct scene_object *o)
{
    const struct scene *s = &p->s;
    if (read_index(p, "pigment", "pigments", s->npigments, &o->pigment,
                   NULL) ||
        read_index(p, "finish", "finishes", s->nfinishes, &o->finish, NULL))
        return -1;
    for (int k = 0; k < SHAPE_COUNT; k++)
        if (read_is_word(&p->tok, shape_kinds[k].keyword)) {
            struct token at = p->tok;
            read_next(p);
            o->kind = k;
            o->first = s->nreals;
            int rc = shape_kinds[k].read(p);
            o->count = s->nreals - o->first;
            if (rc)
                return rc;
            double extent = shape_extent(k, s->reals + o->first, o->count);
            if (extent < 0)
                return read_fail_oom(p);
            read_note_length(p, &at, extent, shape_kinds[k].keyword);
            return 0;
        }
    return read_fail_expected(p, shape_keywords());
}

static int parse_objects(struct scene_reader *p)
{
    struct scene *s = &p->s;
    size_t n = 0;
    if (read_count(p, &n))
        return -1;
    for (size_t i = 0; i < n; i++) {
        void *a = read_grow(p, s->objects, &p->cap_objects, i + 1,
                       sizeof *s->objects);
        if (!a)
            return -1;
        s->objects = a;
        memset(&s->objects[i], 0, sizeof s->objects[i]);
        s->nobjects = i + 1;
        if (parse_object(p, &s->objects[i]))
            return -1;
    }
    return 0;
}

/* ---- trailing directives ----------------------------------------------- */

static int parse_samples(struct scene_reader *p)
{
    uint32_t n = 0;
    if (read_int_at_most(p, 1, TP2_MAX_SAMPLES, "a positive integer sample count",
                         "sample count", &n))
        return -1;
    p->s.has_samples = 1;
    p->s.samples = (int)n;
    return 0;
}

static int parse_lens(struct scene_reader *p)
{
    struct token at = p->tok;
    if (read_bounded(p, &p->s.lens_radius, 1, "a non-negative lens radius") ||
        read_bounded(p, &p->s.lens_focal, 0, "a positive focal distance"))
        return -1;
    read_note_length(p, &at, fmax(p->s.lens_radius, p->s.lens_focal), "lens");
    p->s.has_lens = 1;
    return 0;
}

static int parse_fog(struct scene_reader *p)
{
    if (read_numbers(p, p->s.fog_color, 3, NULL) ||
        read_bounded(p, &p->s.fog_density, 1, "a non-negative fog density"))
        return -1;
    p->s.has_fog = 1;
    return 0;
}

static int parse_arealight(struct scene_reader *p)
{
    struct scene *s = &p->s;
    struct token at;
    uint32_t n = 0;
    if (read_index(p, "light", "lights", s->nlights, &s->arealight_index,
                   &at))
        return -1;
    if (s->arealight_index == 0)
        return read_fail(p, &at, "light 0 is the ambient light and cannot be "
                               "an area light");
    struct token radius_at = p->tok;
    if (read_bounded(p, &s->arealight_radius, 0,
                     "a positive area light radius") ||
        read_int_at_most(p, 1, TP2_MAX_SAMPLES, "a positive integer sample count",
                         "sample count", &n))
        return -1;
    read_note_length(p, &radius_at, s->arealight_radius, "area light radius");
    s->has_arealight = 1;
    s->arealight_samples = (int)n;
    return 0;
}

struct directive {
    const char *name;
    int (*parse)(struct scene_reader *p);
};

static const struct directive directives[] = {
    { "samples", parse_samples },
    { "lens", parse_lens },
    { "fog", parse_fog },
    { "arealight", parse_arealight },
};

#define NDIRECTIVES (sizeof directives / sizeof directives[0])

/* Directives until the end of the file, any order, each at most once. */
static int parse_directives(struct scene_reader *p)
{
    struct token first[NDIRECTIVES];
    int seen[NDIRECTIVES] = { 0 };
    while (p->tok.kind != TOKEN_EOF) {
        size_t i = 0;
        while (i < NDIRECTIVES && !read_is_word(&p->tok, directives[i].name))
            i++;
        if (i == NDIRECTIVES)
            return read_fail_expected(p, "'samples', 'lens', 'fog', 'arealight' "
                                    "or end of file");
        if (seen[i])
            return read_fail(p, &p->tok, "duplicate '%s' directive (first at "
                                       "%zu:%zu)", directives[i].name,
                           first[i].line, first[i].col);
        seen[i] = 1;
        first[i] = p->tok;
        read_next(p);
        if (directives[i].parse(p))
            return -1;
    }
    return 0;
}

/* ---- entry points ------------------------------------------------------ */

/* The sections in file order; the first error stops everything. */
static int parse_scene(struct scene_reader *p)
{
    if (parse_header(p) || parse_camera(p) || parse_lights(p) ||
        parse_pigments(p) || parse_finishes(p) || parse_objects(p) ||
        parse_directives(p))
        return -1;
    return 0;
}

/* Parses what p's lexer gives, then frees p. */
static int reader_run(struct scene_reader *p, struct scene *out)
{
    read_next(p);
    int rc = parse_scene(p);
    if (rc == 0)
        *out = p->s;
    else
        scene_free(&p->s);
    return rc;
}

int scene_parse_text(const char *name, const char *text, size_t len,
                     struct scene *out, char *err, size_t errsize)
{
    struct scene_reader p;
    int rc = read_begin(&p, name, out, err, errsize);
    if (rc == 0 && lexer_init_text(&p.lx, text, len) != 0)
        rc = read_fail_oom(&p);
    if (rc == 0)
        rc = reader_run(&p, out);
    read_end(&p);
    return rc;
}

/* The text streams from the file (lexer.h): it is never held whole. */
int scene_parse_file(const char *path, struct scene *out, char *err,
                     size_t errsize)
{
    struct scene_reader p;
    int rc = read_begin(&p, path, out, err, errsize);
    if (rc != 0) {
        read_end(&p);
        return rc;
    }
    errno = 0;
    FILE *f = fopen(path, "rb");
    if (!f || lexer_init_file(&p.lx, f) != 0) {
        int saved = errno ? errno : EIO;
        if (saved == ENOMEM)
            read_fail_oom(&p);
        else if (err && errsize > 0)
            snprintf(err, errsize, "tp2: cannot read '%s': %s", p.shown,
                     strerror(saved));
        rc = -1;
    } else {
        rc = reader_run(&p, out);
    }
    read_end(&p);
    if (f)
        fclose(f);
    return rc;
}
