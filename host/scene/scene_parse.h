/* scene_parse.h: reads a scene file (SPEC.md sections 2 and 3) into a
 * struct scene, with compiler-style error messages.
 *
 * No Vulkan here, so tests can call it directly. */
#ifndef TP2_SCENE_PARSE_H
#define TP2_SCENE_PARSE_H

#include <stddef.h>

#include "scene.h"

/* Room in err for every message about a file whose name is name_len bytes
 * long: the name, escaped (up to 4 bytes each), and the message. */
#define SCENE_ERROR_SIZE(name_len) (4 * (size_t)(name_len) + 640)

/* Parses len bytes of text (need not be NUL terminated) named name in
 * messages (NULL means "<input>"; bytes outside printable ASCII shown as
 * \xNN, never cut). Both variants are accepted: the header variant is
 * recognised by a first token that is not a number.
 *
 * Returns 0 and fills *out (which the caller frees with scene_free), or -1
 * with *out zeroed and one line, without a newline, written to err (cut to
 * errsize bytes, always NUL-terminated when errsize > 0; err may be NULL):
 *   NAME:LINE:COL: error: expected a number, found 'sphre'
 * *out is overwritten, never freed. */
int scene_parse_text(const char *name, const char *text, size_t len,
                     struct scene *out, char *err, size_t errsize);

/* Reads the file at path and parses it as scene_parse_text does, naming it
 * path in messages. A file that cannot be read gives
 *   tp2: cannot read 'PATH': REASON
 * Returns 0 or -1 as scene_parse_text. */
int scene_parse_file(const char *path, struct scene *out, char *err,
                     size_t errsize);

#endif
