/* scene_reader_state.h: the reader's state and the helpers that only the
 * parser (scene_parse.c) uses besides scene_reader.h: reading counts and
 * indices, growing the scene's arrays, setting the reader up. The kind
 * tables (shapes.c, pigments.c) see scene_reader.h alone. */
#ifndef TP2_SCENE_READER_STATE_H
#define TP2_SCENE_READER_STATE_H

#include <stddef.h>
#include <stdint.h>

#include "lexer.h"
#include "scene.h"
#include "scene_reader.h"

struct scene_reader {
    struct lexer lx;
    struct token tok; /* the next token, not yet consumed */
    const char *name;
    char *dir;         /* the scene file's folder, for the files it names */
    const char *shown; /* name as messages show it (lexer_escape) */
    char *shown_copy;  /* what shown points to, unless out of memory */
    char *err;
    size_t errsize;
    struct scene s;
    size_t cap_lights, cap_pigments, cap_finishes, cap_objects, cap_reals;
};

/* Moves to the next token. */
void read_next(struct scene_reader *p);

/* Reports running out of memory; returns -1. */
int read_fail_oom(struct scene_reader *p);

/* read_expected at the next token. */
int read_fail_expected(struct scene_reader *p, const char *what);

/* Whether t is the word w. */
int read_is_word(const struct token *t, const char *w);

/* Reads one finite number; *at (may be NULL) gets its token. */
int read_number(struct scene_reader *p, double *v, struct token *at);

/* Reads an integer in [min, 2^31 - 1] (read_int_at_most: [min, max]);
 * what is the "expected" phrase, noun names the value when too large. */
int read_int(struct scene_reader *p, uint32_t min, const char *what,
             const char *noun, uint32_t *v);
int read_int_at_most(struct scene_reader *p, uint32_t min, uint32_t max,
                     const char *what, const char *noun, uint32_t *v);

/* Reads a count (a non-negative integer). */
int read_count(struct scene_reader *p, size_t *n);

/* Reads an index into a list of n things called one/many ("pigment",
 * "pigments"); *at (may be NULL) gets its token. */
int read_index(struct scene_reader *p, const char *one, const char *many,
               size_t n, size_t *idx, struct token *at);

/* Grows an array to hold at least need entries of elem bytes (*cap is its
 * capacity); the array, possibly moved, or NULL when out of memory
 * (reported; arr is then still valid). */
void *read_grow(struct scene_reader *p, void *arr, size_t *cap, size_t need,
                size_t elem);

/* Keeps the scene's largest length and where it was written (scene.h:
 * max_length). */
void read_note_length(struct scene_reader *p, const struct token *at,
                      double v, const char *what);
void read_note_lengths(struct scene_reader *p, const struct token *at,
                       const double v[3], const char *what);

/* Sets up p to read a scene called name (NULL: "<input>") into out, with
 * messages to err; -1 when out of memory (reported). The caller then sets
 * up p->lx and reads; read_end frees what p holds. */
int read_begin(struct scene_reader *p, const char *name, struct scene *out,
               char *err, size_t errsize);
void read_end(struct scene_reader *p);

#endif
