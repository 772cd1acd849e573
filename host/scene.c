/* scene.c: ownership of the scene's arrays (see scene.h). */
#include "scene.h"

#include <stdlib.h>
#include <string.h>

void scene_free(struct scene *s)
{
    if (!s)
        return;
    for (size_t i = 0; i < s->ntextures; i++) {
        free(s->textures[i].path);
        free(s->textures[i].rgb);
    }
    free(s->textures);
    free(s->lights);
    free(s->pigments);
    free(s->finishes);
    free(s->objects);
    free(s->reals);
    memset(s, 0, sizeof *s);
}
