/* obj_read.c: OBJ vertices and faces to triangles (see obj_read.h). */
#define _POSIX_C_SOURCE 200809L
#include "obj_read.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "big_alloc.h"
#include "decimal.h"
#include "lexer.h"
#include "vec3.h"

struct obj_reader {
    FILE *f;
    const char *name;
    char *err;
    size_t errsize;
    char line[OBJ_MAX_LINE + 1];
    size_t lineno;
    double *v; /* 3 per vertex */
    size_t nv, cap_v;
    size_t cap_tri;
    struct obj_mesh *m;
};

static int fail(struct obj_reader *r, size_t col, const char *fmt, ...)
{
    char msg[256];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    if (r->err && r->errsize > 0)
        snprintf(r->err, r->errsize, "%s:%zu:%zu: error: %s", r->name, r->lineno,
                 col, msg);
    return -1;
}

static int fail_oom(struct obj_reader *r)
{
    if (r->err && r->errsize > 0)
        snprintf(r->err, r->errsize, "tp2: out of memory reading '%s'", r->name);
    return -1;
}

/* Grows *arr (elem-byte entries) to hold need; doubling. */
static int grow(struct obj_reader *r, void **arr, size_t *cap, size_t need, size_t elem)
{
    if (need <= *cap)
        return 0;
    size_t ncap = *cap ? *cap : 1024;
    while (ncap < need && ncap <= SIZE_MAX / 2)
        ncap *= 2;
    if (ncap < need || ncap > SIZE_MAX / elem)
        return fail_oom(r);
    void *bigger = big_realloc(*arr, ncap * elem);
    if (!bigger)
        return fail_oom(r);
    *arr = bigger;
    *cap = ncap;
    return 0;
}

static bool is_blank(char c)
{
    return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

/* Skips blanks; returns the new position. */
static char *skip(char *s)
{
    while (is_blank(*s))
        s++;
    return s;
}

/* The rest of the current word (up to a blank or the end), quoted. */
static void describe(const char *s, char *out, size_t size)
{
    if (*s == '\0') {
        snprintf(out, size, "end of line");
        return;
    }
    size_t n = 0;
    while (s[n] && !is_blank(s[n]))
        n++;
    lexer_quote(s, n, out, size);
}

/* Reads one finite number at *s, which must end at a blank or the end. */
static int number(struct obj_reader *r, char **s, double *v)
{
    char *p = skip(*s), *end = NULL;
    char found[LEXER_QUOTE_SIZE];
    *v = decimal_read(p, &end);
    if (end == p || (*end && !is_blank(*end)) || !isfinite(*v)) {
        describe(p, found, sizeof found);
        return fail(r, (size_t)(p - r->line) + 1, "expected a finite number, found %s", found);
    }
    *s = end;
    return 0;
}

static int read_vertex(struct obj_reader *r, char *s)
{
    if (grow(r, (void **)&r->v, &r->cap_v, 3 * (r->nv + 1), sizeof *r->v))
        return -1;
    for (int i = 0; i < 3; i++)
        if (number(r, &s, &r->v[3 * r->nv + i]))
            return -1;
    r->nv++;
    return 0; /* anything after z (w, a color) is allowed and ignored */
}

/* One vertex reference `v[/t[/n]]` at *s: its 0-based vertex. */
static int vertex_ref(struct obj_reader *r, char **s, size_t *index)
{
    char *p = skip(*s), *end = NULL;
    char found[LEXER_QUOTE_SIZE];
    size_t col = (size_t)(p - r->line) + 1;
    long long v = strtoll(p, &end, 10);
    bool ok = end != p && (*end == '\0' || *end == '/' || is_blank(*end));
    if (!ok) {
        describe(p, found, sizeof found);
        return fail(r, col, "expected a vertex index, found %s", found);
    }
    /* Resolve: 1..nv, or -1..-nv counting back. */
    long long n = (long long)r->nv;
    long long i = v > 0 ? v - 1 : n + v;
    if (v == 0 || i < 0 || i >= n) {
        describe(p, found, sizeof found);
        return fail(r, col, "vertex index %s is out of range (%zu vert%s so far)", found,
                    r->nv, r->nv == 1 ? "ex" : "ices");
    }
    /* Texture and normal indices are not used; they must still be plain
     * integers, so a mangled part is not silently read. */
    while (*end == '/') {
        char *q = end + 1;
        if (*q == '/' ) {
            end = q;
            continue;
        }
        if (*q == '\0' || is_blank(*q)) { /* an empty part: "1//" ends here */
            end = q;
            break;
        }
        char *qend = NULL;
        strtoll(q, &qend, 10);
        if (qend == q || (*qend && *qend != '/' && !is_blank(*qend))) {
            describe(p, found, sizeof found);
            return fail(r, col, "malformed vertex reference %s", found);
        }
        end = qend;
    }
    if (*end && !is_blank(*end)) {
        describe(p, found, sizeof found);
        return fail(r, col, "malformed vertex reference %s", found);
    }
    *index = (size_t)i;
    *s = end;
    return 0;
}

/* Appends triangle (a, b, c) unless it has no area. */
static int add_triangle(struct obj_reader *r, size_t a, size_t b, size_t c)
{
    const double *pa = r->v + 3 * a, *pb = r->v + 3 * b, *pc = r->v + 3 * c;
    double e1[3], e2[3], n[3];
    vec3_sub(pb, pa, e1);
    vec3_sub(pc, pa, e2);
    double s1 = vec3_max_abs(e1), s2 = vec3_max_abs(e2);
    if (s1 > 0 && s2 > 0) /* scaled, so the test neither overflows nor underflows */
        for (int i = 0; i < 3; i++) {
            e1[i] /= s1;
            e2[i] /= s2;
        }
    vec3_cross(e1, e2, n);
    if (!(vec3_max_abs(n) > 0)) {
        r->m->skipped++;
        return 0;
    }
    struct obj_mesh *m = r->m;
    if (grow(r, (void **)&m->tri, &r->cap_tri, 9 * (m->ntri + 1), sizeof *m->tri))
        return -1;
    double *t = m->tri + 9 * m->ntri++;
    memcpy(t, pa, 3 * sizeof *t);
    memcpy(t + 3, pb, 3 * sizeof *t);
    memcpy(t + 6, pc, 3 * sizeof *t);
    return 0;
}

static int read_face(struct obj_reader *r, char *s)
{
    size_t first = 0, prev = 0, idx = 0;
    int k = 0;
    for (s = skip(s); *s; s = skip(s), k++) {
        if (vertex_ref(r, &s, &idx))
            return -1;
        if (k == 0)
            first = idx;
        else if (k >= 2 && add_triangle(r, first, prev, idx))
            return -1;
        prev = idx;
    }
    if (k < 3)
        return fail(r, (size_t)(s - r->line) + 1,
                    "a face needs at least 3 vertices, found %d", k);
    return 0;
}

/* A read error (errno set): "tp2: cannot read 'NAME': REASON", as the
 * parser says of a scene; a line number would be 0 before any line, as
 * for a directory (found by tests/fuzz/fuzz_scene.c). */
static int fail_read(struct obj_reader *r)
{
    int saved = errno ? errno : EIO;
    if (r->err && r->errsize > 0)
        snprintf(r->err, r->errsize, "tp2: cannot read '%s': %s", r->name, strerror(saved));
    return -1;
}

/* Reads the next line into r->line without its newline or comment;
 * returns 1, 0 at the end, -1 on error. */
static int next_line(struct obj_reader *r)
{
    size_t n = 0;
    int c = getc_unlocked(r->f);
    if (c == EOF)
        return ferror(r->f) ? fail_read(r) : 0;
    r->lineno++;
    for (; c != EOF && c != '\n'; c = getc_unlocked(r->f)) {
        if (c == '\0')
            return fail(r, n + 1, "unexpected character '\\x00'");
        if (n == OBJ_MAX_LINE)
            return fail(r, 1, "line longer than %d bytes", OBJ_MAX_LINE);
        r->line[n++] = (char)c;
    }
    if (ferror(r->f))
        return fail_read(r);
    r->line[n] = '\0';
    char *hash = strchr(r->line, '#');
    if (hash)
        *hash = '\0';
    return 1;
}

int obj_read(FILE *f, const char *name, struct obj_mesh *out, char *err, size_t errsize)
{
    memset(out, 0, sizeof *out);
    struct obj_reader *r = calloc(1, sizeof *r);
    if (!r) {
        if (err && errsize > 0)
            snprintf(err, errsize, "tp2: out of memory reading '%s'", name);
        return -1;
    }
    *r = (struct obj_reader){.f = f, .name = name, .err = err, .errsize = errsize, .m = out};
    int rc;
    while ((rc = next_line(r)) == 1) {
        char *s = skip(r->line);
        int line_rc = 0;
        if (s[0] == 'v' && (s[1] == '\0' || is_blank(s[1])))
            line_rc = read_vertex(r, s + 1);
        else if (s[0] == 'f' && (s[1] == '\0' || is_blank(s[1])))
            line_rc = read_face(r, s + 1);
        if (line_rc) {
            rc = -1;
            break;
        }
    }
    free(r->v);
    free(r);
    if (rc != 0) {
        obj_mesh_free(out);
        return -1;
    }
    return 0;
}

void obj_mesh_free(struct obj_mesh *m)
{
    free(m->tri);
    memset(m, 0, sizeof *m);
}
