/* scene.c: ownership of the scene's arrays (see scene.h). */
#include "scene.h"

#include <stdlib.h>
#include <string.h>

void scene_free(struct scene *s)
{
    if (!s)
        return;
    free(s->lights);
    free(s->pigments);
    free(s->finishes);
    free(s->objects);
    memset(s, 0, sizeof *s);
}
