/* scene_json.c: the parsed scene as JSON (see scene_json.h). */
#include "scene_json.h"

#include "json_write.h"
#include "pigments.h"
#include "shapes.h"

static void write_pigment(FILE *out, const struct scene *s, const struct scene_pigment *pg)
{
    fprintf(out, "{\"kind\": \"%s\", ", pigment_kinds[pg->kind].keyword);
    pigment_kinds[pg->kind].json(out, s, pg);
    fputc('}', out);
}

int scene_write_json(const struct scene *s, FILE *out)
{
    if (s->has_size)
        fprintf(out, "{\"size\": [%d, %d],\n", s->width, s->height);
    else
        fputs("{\"size\": null,\n", out);
    fputc(' ', out);
    json_numbers(out, "eye", s->eye, 3);
    fputs(", ", out);
    json_numbers(out, "center", s->center, 3);
    fputs(", ", out);
    json_numbers(out, "up", s->up, 3);
    fprintf(out, ", \"fov\": %.17g,\n \"lights\": [", s->fov);
    for (size_t i = 0; i < s->nlights; i++) {
        fputs(i ? ",\n  {" : "\n  {", out);
        json_numbers(out, "pos", s->lights[i].pos, 3);
        fputs(", ", out);
        json_numbers(out, "color", s->lights[i].color, 3);
        fputs(", ", out);
        json_numbers(out, "att", s->lights[i].att, 3);
        fputc('}', out);
    }
    fputs("],\n \"pigments\": [", out);
    for (size_t i = 0; i < s->npigments; i++) {
        fputs(i ? ",\n  " : "\n  ", out);
        write_pigment(out, s, &s->pigments[i]);
    }
    fputs("],\n \"finishes\": [", out);
    for (size_t i = 0; i < s->nfinishes; i++) {
        const struct scene_finish *f = &s->finishes[i];
        fprintf(out, "%s{\"ka\": %.17g, \"kd\": %.17g, \"ks\": %.17g, \"n\": %.17g, "
                     "\"kr\": %.17g, \"kt\": %.17g, \"ior\": %.17g}",
                i ? ",\n  " : "\n  ", f->ka, f->kd, f->ks, f->n, f->kr, f->kt, f->ior);
    }
    fputs("],\n \"objects\": [", out);
    for (size_t i = 0; i < s->nobjects; i++) {
        const struct scene_object *o = &s->objects[i];
        fprintf(out, "%s{\"kind\": \"%s\", \"pigment\": %zu, \"finish\": %zu, ",
                i ? ",\n  " : "\n  ", shape_kinds[o->kind].keyword, o->pigment, o->finish);
        json_numbers(out, "numbers", scene_object_reals(s, o), o->count);
        fputc('}', out);
    }
    fputs("],\n", out);
    if (s->has_samples)
        fprintf(out, " \"samples\": %d,\n", s->samples);
    else
        fputs(" \"samples\": null,\n", out);
    if (s->has_lens)
        fprintf(out, " \"lens\": [%.17g, %.17g],\n", s->lens_radius, s->lens_focal);
    else
        fputs(" \"lens\": null,\n", out);
    if (s->has_fog) {
        fputs(" \"fog\": {", out);
        json_numbers(out, "color", s->fog_color, 3);
        fprintf(out, ", \"density\": %.17g},\n", s->fog_density);
    } else {
        fputs(" \"fog\": null,\n", out);
    }
    if (s->has_arealight)
        fprintf(out, " \"arealight\": {\"light\": %zu, \"radius\": %.17g, \"samples\": %d}}\n",
                s->arealight_index, s->arealight_radius, s->arealight_samples);
    else
        fputs(" \"arealight\": null}\n", out);
    return fflush(out) == 0 && !ferror(out) ? 0 : -1;
}
