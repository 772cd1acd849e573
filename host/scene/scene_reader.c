/* scene_reader.c: the reader that the parser (scene_parse.c) and the kind
 * tables (shapes.c, pigments.c) read a scene's tokens with: messages at a
 * token, numbers, integers, file names, and the scene being filled
 * (scene_reader.h, scene_reader_state.h). It knows no section or kind. */
#include "scene_reader.h"
#include "scene_reader_state.h"

#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "big_alloc.h"
#include "lexer.h"

/* Counts, indices and integer settings are kept within int32. */
#define INT_LIMIT 2147483647u

/* ---- messages ---------------------------------------------------------- */

void read_next(struct scene_reader *p)
{
    lexer_next(&p->lx, &p->tok);
}

/* Writes "NAME:LINE:COL: error: ..." at token at; returns -1. */
int read_fail(struct scene_reader *p, const struct token *at, const char *fmt,
              ...)
{
    char msg[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    if (p->err && p->errsize > 0)
        snprintf(p->err, p->errsize, "%s:%zu:%zu: error: %s", p->shown,
                 at->line, at->col, msg);
    return -1;
}

int read_fail_text(struct scene_reader *p, const char *text)
{
    if (p->err && p->errsize > 0)
        snprintf(p->err, p->errsize, "%s", text);
    return -1;
}

int read_fail_oom(struct scene_reader *p)
{
    if (p->err && p->errsize > 0)
        snprintf(p->err, p->errsize, "tp2: out of memory reading '%s'",
                 p->shown);
    return -1;
}

/* "expected WHAT, found TOKEN" at token at; a lexical error there wins,
 * since it says more about the text than what the grammar wanted. */
int read_expected(struct scene_reader *p, const struct token *at,
                  const char *what)
{
    if (at->kind == TOKEN_ERROR)
        return read_fail(p, at, "%s", p->lx.message);
    char found[LEXER_QUOTE_SIZE];
    token_describe(at, found, sizeof found);
    return read_fail(p, at, "expected %s, found %s", what, found);
}

int read_fail_expected(struct scene_reader *p, const char *what)
{
    return read_expected(p, &p->tok, what);
}

/* ---- tokens ------------------------------------------------------------ */

int read_is_word(const struct token *t, const char *w)
{
    return t->kind == TOKEN_WORD && t->len == strlen(w) &&
           memcmp(t->text, w, t->len) == 0;
}

enum uint_kind { UINT_NOT, UINT_OK, UINT_TOO_BIG };

/* Classifies a token as plain decimal digits within INT_LIMIT. Anything
 * else ("3.0", "-1", "1e3", "+3") is not a count, though strtod reads it. */
static enum uint_kind read_token_uint(const struct token *t, uint32_t *v)
{
    uint64_t acc = 0;
    if (t->kind != TOKEN_NUMBER)
        return UINT_NOT;
    for (size_t i = 0; i < t->len; i++) {
        char c = t->text[i];
        if (c < '0' || c > '9')
            return UINT_NOT;
        if (acc <= INT_LIMIT)
            acc = acc * 10 + (uint64_t)(c - '0');
    }
    *v = (uint32_t)(acc <= INT_LIMIT ? acc : 0);
    return acc <= INT_LIMIT ? UINT_OK : UINT_TOO_BIG;
}

/* Digits of a too-big integer token, cut like a quote but without quotes. */
static void read_digits_text(const struct token *t, char *out, size_t size)
{
    int n = t->len > 32 ? 32 : (int)t->len;
    snprintf(out, size, "%.*s%s", n, t->text, t->len > 32 ? "..." : "");
}

/* ---- values ------------------------------------------------------------ */

/* Reads one finite number; *at (may be NULL) gets its token. */
int read_number(struct scene_reader *p, double *v, struct token *at)
{
    if (at)
        *at = p->tok;
    if (p->tok.kind == TOKEN_NUMBER) {
        *v = p->tok.value;
        read_next(p);
        return 0;
    }
    if (token_is_nonfinite_word(&p->tok))
        return read_fail_expected(p, "a finite number");
    return read_fail_expected(p, "a number");
}

int read_numbers(struct scene_reader *p, double *v, int n, struct token *at)
{
    if (at) /* where the first number is, even to a compiler that cannot see n > 0 */
        *at = p->tok;
    for (int i = 0; i < n; i++)
        if (read_number(p, &v[i], i == 0 ? at : NULL))
            return -1;
    return 0;
}

/* Reads a number that must be > 0 (or >= 0 when zero_ok); what names it. */
int read_bounded(struct scene_reader *p, double *v, int zero_ok,
                 const char *what)
{
    struct token at;
    if (read_number(p, v, &at))
        return -1;
    if (*v > 0 || (zero_ok && *v == 0))
        return 0;
    return read_expected(p, &at, what);
}

/* Reads an integer in [min, INT_LIMIT]; what is the "expected" phrase and
 * noun names the value when it is too large. */
int read_int(struct scene_reader *p, uint32_t min, const char *what,
                    const char *noun, uint32_t *v)
{
    enum uint_kind k = read_token_uint(&p->tok, v);
    if (k == UINT_TOO_BIG) {
        char digits[48];
        read_digits_text(&p->tok, digits, sizeof digits);
        return read_fail(p, &p->tok, "%s %s is too large (at most %u)", noun,
                       digits, INT_LIMIT);
    }
    if (k != UINT_OK || *v < min)
        return read_fail_expected(p, what);
    read_next(p);
    return 0;
}

/* read_int, with values above max reported as too large. */
int read_int_at_most(struct scene_reader *p, uint32_t min, uint32_t max,
                            const char *what, const char *noun, uint32_t *v)
{
    struct token at = p->tok;
    if (read_int(p, min, what, noun, v))
        return -1;
    if (*v > max)
        return read_fail(p, &at, "%s %u is too large (at most %u)", noun, *v, max);
    return 0;
}

int read_integer(struct scene_reader *p, size_t min, size_t max,
                 const char *what, const char *noun, size_t *v)
{
    uint32_t u = 0;
    uint32_t lo = min > INT_LIMIT ? INT_LIMIT : (uint32_t)min;
    uint32_t hi = max > INT_LIMIT ? INT_LIMIT : (uint32_t)max;
    if (read_int_at_most(p, lo, hi, what, noun, &u))
        return -1;
    *v = u;
    return 0;
}

int read_count(struct scene_reader *p, size_t *n)
{
    uint32_t v = 0;
    if (read_int(p, 0, "a non-negative integer count", "count", &v))
        return -1;
    *n = v;
    return 0;
}

/* Reads an index into a list of n things called one/many ("pigment",
 * "pigments"); *at (may be NULL) gets its token. */
int read_index(struct scene_reader *p, const char *one, const char *many,
                      size_t n, size_t *idx, struct token *at)
{
    uint32_t v = 0;
    enum uint_kind k = read_token_uint(&p->tok, &v);
    if (at)
        *at = p->tok;
    if (k == UINT_NOT) {
        char what[64];
        snprintf(what, sizeof what, "a non-negative integer %s index", one);
        return read_fail_expected(p, what);
    }
    if (k == UINT_TOO_BIG || v >= n) {
        char digits[48];
        read_digits_text(&p->tok, digits, sizeof digits);
        return read_fail(p, &p->tok, "%s index %s is out of range (%zu %s)",
                       one, digits, n, n == 1 ? one : many);
    }
    *idx = v;
    read_next(p);
    return 0;
}

/* Grows an array to hold at least need entries, doubling, so a count in
 * the file never decides an allocation by itself. Returns the (possibly
 * moved) array, or NULL when out of memory (arr is then still valid). */
void *read_grow(struct scene_reader *p, void *arr, size_t *cap, size_t need,
                  size_t elem)
{
    if (need <= *cap)
        return arr;
    size_t ncap = *cap ? *cap : 8;
    while (ncap < need && ncap <= SIZE_MAX / 2)
        ncap *= 2;
    if (ncap < need || ncap > SIZE_MAX / elem) {
        read_fail_oom(p);
        return NULL;
    }
    void *bigger = big_realloc(arr, ncap * elem);
    if (!bigger) {
        read_fail_oom(p);
        return NULL;
    }
    *cap = ncap;
    return bigger;
}

/* Keeps the scene's largest length and where it was written (scene.h:
 * max_length; main.c checks it against scene_length_limit). */
void read_note_length(struct scene_reader *p, const struct token *at,
                        double v, const char *what)
{
    if (fabs(v) > p->s.max_length) {
        p->s.max_length = fabs(v);
        p->s.max_length_line = at->line;
        p->s.max_length_col = at->col;
        p->s.max_length_what = what;
    }
}

void read_note_lengths(struct scene_reader *p, const struct token *at,
                         const double v[3], const char *what)
{
    for (int i = 0; i < 3; i++)
        read_note_length(p, at, v[i], what);
}

struct scene *read_scene(struct scene_reader *p)
{
    return &p->s;
}

const struct token *read_peek(const struct scene_reader *p)
{
    return &p->tok;
}

int read_push(struct scene_reader *p, const double *v, size_t n)
{
    struct scene *s = &p->s;
    void *a = read_grow(p, s->reals, &p->cap_reals, s->nreals + n, sizeof *s->reals);
    if (!a)
        return -1;
    s->reals = a;
    memcpy(s->reals + s->nreals, v, n * sizeof *v);
    s->nreals += n;
    return 0;
}

int read_file_name(struct scene_reader *p, const char *what, char **path,
                   struct token *at)
{
    lexer_rescan_word(&p->lx, &p->tok);
    *at = p->tok;
    if (p->tok.kind != TOKEN_WORD)
        return read_expected(p, &p->tok, what);
    size_t dir = p->tok.text[0] == '/' ? 0 : strlen(p->dir) + 1;
    *path = malloc(dir + p->tok.len + 1);
    if (!*path)
        return read_fail_oom(p);
    if (dir) {
        memcpy(*path, p->dir, dir - 1);
        (*path)[dir - 1] = '/';
    }
    memcpy(*path + dir, p->tok.text, p->tok.len);
    (*path)[dir + p->tok.len] = '\0';
    read_next(p);
    return 0;
}

/* The folder of the file called name: what comes before its last '/',
 * "/" for a file in the root, "." for a bare name. NULL when out of
 * memory. */
static char *folder_of(const char *name)
{
    const char *slash = strrchr(name, '/');
    size_t n = !slash ? 1 : slash == name ? 1 : (size_t)(slash - name);
    char *dir = malloc(n + 1);
    if (dir) {
        memcpy(dir, !slash ? "." : name, n);
        dir[n] = '\0';
    }
    return dir;
}

/* Sets up p to read a scene called name (NULL: "<input>") into out, with
 * messages to err; -1 when out of memory (reported). */
int read_begin(struct scene_reader *p, const char *name,
                        struct scene *out, char *err, size_t errsize)
{
    memset(p, 0, sizeof *p);
    memset(out, 0, sizeof *out);
    p->name = name ? name : "<input>";
    p->err = err;
    p->errsize = errsize;
    if (err && errsize > 0)
        err[0] = '\0';
    p->shown_copy = lexer_escape(p->name);
    p->shown = p->shown_copy ? p->shown_copy : "?";
    p->dir = folder_of(p->name);
    return p->shown_copy && p->dir ? 0 : read_fail_oom(p);
}

void read_end(struct scene_reader *p)
{
    lexer_free(&p->lx);
    free(p->dir);
    free(p->shown_copy);
}
