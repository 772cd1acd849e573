/* json_write.h: JSON's small pieces, for the scene's JSON (scene_json.c)
 * and the fields each pigment kind writes itself (pigments.c). */
#ifndef TP2_JSON_WRITE_H
#define TP2_JSON_WRITE_H

#include <stddef.h>
#include <stdio.h>

/* `"key": [v0, v1, ...]`, each number with 17 significant digits (it reads
 * back exactly). */
void json_numbers(FILE *out, const char *key, const double *v, size_t n);

/* A string in quotes, its quotes, backslashes and control characters
 * escaped. */
void json_string(FILE *out, const char *s);

#endif
