/* scene_json.h: the parsed scene as JSON (tp2 --dump-scene), so that tools
 * (tests/render_checks.py, bench/scene2pov.py) read scenes exactly as tp2
 * does instead of parsing the format again. */
#ifndef TP2_SCENE_JSON_H
#define TP2_SCENE_JSON_H

#include <stdio.h>

#include "scene.h"

/* Writes s to out as one JSON object:
 *   {"size": [W, H] | null, "eye": [x, y, z], "center": [...], "up": [...],
 *    "fov": F,
 *    "lights": [{"pos": [...], "color": [...], "att": [a, b, c]}, ...],
 *    "pigments": [{"kind": "solid", ...}, ...]   (fields per kind:
 *                 pigments.c's table),
 *    "finishes": [{"ka": .., "kd", "ks", "n", "kr", "kt", "ior"}, ...],
 *    "objects": [{"kind": "sphere", "pigment": i, "finish": j,
 *                 "numbers": [...]}, ...]        (numbers as listed at the
 *                 top of shapes.c; a mesh's are its triangles),
 *    "samples": N | null, "lens": [radius, focal] | null,
 *    "fog": {"color": [...], "density": D} | null,
 *    "arealight": {"light": i, "radius": r, "samples": n} | null}
 * Numbers are printed with 17 significant digits: they read back exactly.
 * Returns 0, or -1 if writing failed. */
int scene_write_json(const struct scene *s, FILE *out);

#endif
