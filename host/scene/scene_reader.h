/* scene_reader.h: what the tables of shapes.c and pigments.c read their
 * parameters with.
 *
 * The reader (scene_reader.c) looks one token ahead, and every
 * function here reports a failure itself, as one message
 * "FILE:LINE:COL: error: ..." at the token that caused it, and returns -1.
 * Nothing is printed; scene_parse_text hands the message to its caller. */
#ifndef TP2_SCENE_READER_H
#define TP2_SCENE_READER_H

#include <stddef.h>

#include "lexer.h"
#include "scene.h"

struct scene_reader;

/* The scene read so far. */
struct scene *read_scene(struct scene_reader *r);

/* The next token, not yet read. */
const struct token *read_peek(const struct scene_reader *r);

/* Reads n finite numbers into v; *at (may be NULL) gets the first's token. */
int read_numbers(struct scene_reader *r, double *v, int n, struct token *at);

/* Reads one number that must be > 0, or >= 0 when zero_ok; `what` names it
 * in the message ("a positive sphere radius"). */
int read_bounded(struct scene_reader *r, double *v, int zero_ok,
                 const char *what);

/* Reads a plain decimal integer in [min, max]; `what` is the "expected"
 * phrase, `noun` names the value when it is too large. */
int read_integer(struct scene_reader *r, size_t min, size_t max,
                 const char *what, const char *noun, size_t *v);

/* Reads the next token as a file name, whatever it looks like ("1.ppm"
 * too), and resolves it against the scene file's folder unless it is
 * absolute. *path is malloc'd (the caller frees it); *at gets the token. */
int read_file_name(struct scene_reader *r, const char *what, char **path,
                   struct token *at);

/* Reports "expected WHAT, found TOKEN" at token at. */
int read_expected(struct scene_reader *r, const struct token *at,
                  const char *what);

/* Reports a printf-style message at token at. */
int read_fail(struct scene_reader *r, const struct token *at, const char *fmt,
              ...) __attribute__((format(printf, 3, 4)));

/* Reports a message that already names its place (an OBJ file's line). */
int read_fail_text(struct scene_reader *r, const char *text);

/* Appends n numbers to the object being read (scene.reals); -1 when out of
 * memory (reported). */
int read_push(struct scene_reader *r, const double *v, size_t n);

#endif
