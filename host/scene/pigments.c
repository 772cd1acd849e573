/* pigments.c: the table of pigment kinds (see pigments.h).
 *
 * GPU records (layout.glsl's Pigment):
 *   solid     color1
 *   checker   color1 (even cells), color2 (odd), p.x = cube side,
 *             p.yzw = the packed origin (scene_pack.c), which the shader
 *             adds back: cells are the scene's; q.x = 1 where the side
 *             is a float exactly (the same side in both precisions)
 *   gradient  color1 at point p, color2 at p + 1 / q: the color is
 *             mix(color1, color2, clamp((x - p) . q, 0, 1)),
 *             q = (p1 - p0) / |p1 - p0|^2
 *   texmap    p = the s row, q = the t row; the texture's texels, size
 *             and place in the texel buffer come from scene_pack.c
 * and color1.w = the kind's slope (0 without one).
 * Points are packed from the origin (each kind's move). */
#include "pigments.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "float_exact.h"
#include "json_write.h"
#include "texture.h"
#include "tp2_shared.h"
#include "vec3.h"

static int solid_read(struct scene_reader *r, struct scene_pigment *pg)
{
    return read_numbers(r, pg->color1, 3, NULL);
}

static void solid_pack(const struct scene_pigment *pg, struct pigment_record *rec)
{
    memcpy(rec->color1, pg->color1, sizeof rec->color1);
}

static void unmoved(struct pigment_record *rec, const double origin[3])
{
    (void)rec, (void)origin;
}

static void solid_json(FILE *out, const struct scene *s, const struct scene_pigment *pg)
{
    (void)s;
    json_numbers(out, "color", pg->color1, 3);
}

static int checker_read(struct scene_reader *r, struct scene_pigment *pg)
{
    if (read_numbers(r, pg->color1, 3, NULL) || read_numbers(r, pg->color2, 3, NULL))
        return -1;
    return read_bounded(r, &pg->scale, 0, "a positive checker cube side");
}

static void checker_pack(const struct scene_pigment *pg, struct pigment_record *rec)
{
    memcpy(rec->color1, pg->color1, sizeof rec->color1);
    memcpy(rec->color2, pg->color2, sizeof rec->color2);
    rec->p[0] = pg->scale;
    rec->q[0] = is_float(pg->scale);
}

/* Exact: the origin is a float, and p + origin in the shader puts a point
 * on a cell face back on it. */
static void checker_move(struct pigment_record *rec, const double origin[3])
{
    memcpy(rec->p + 1, origin, 3 * sizeof *origin);
}

static void checker_json(FILE *out, const struct scene *s, const struct scene_pigment *pg)
{
    (void)s;
    json_numbers(out, "color1", pg->color1, 3);
    fputs(", ", out);
    json_numbers(out, "color2", pg->color2, 3);
    fprintf(out, ", \"side\": %.17g", pg->scale);
}

static int gradient_read(struct scene_reader *r, struct scene_pigment *pg)
{
    struct token second;
    if (read_numbers(r, pg->p0, 3, NULL) || read_numbers(r, pg->p1, 3, &second))
        return -1;
    if (pg->p0[0] == pg->p1[0] && pg->p0[1] == pg->p1[1] && pg->p0[2] == pg->p1[2])
        return read_fail(r, &second, "gradient end points must differ");
    return read_numbers(r, pg->color1, 3, NULL) || read_numbers(r, pg->color2, 3, NULL);
}

static void gradient_pack(const struct scene_pigment *pg, struct pigment_record *rec)
{
    double d[3], u[3];
    vec3_sub(pg->p1, pg->p0, d);
    double len = vec3_unit(d, u); /* no overflow in |d|^2 */
    memcpy(rec->color1, pg->color1, sizeof rec->color1);
    memcpy(rec->color2, pg->color2, sizeof rec->color2);
    memcpy(rec->p, pg->p0, sizeof pg->p0);
    for (int i = 0; i < 3; i++)
        rec->q[i] = u[i] / len;
}

/* The color span over the distance between the end points. */
static double gradient_slope(const struct scene *s, const struct scene_pigment *pg)
{
    (void)s;
    double d[3], span = 0;
    vec3_sub(pg->p1, pg->p0, d);
    for (int c = 0; c < 3; c++)
        span = fmax(span, fabs(pg->color2[c] - pg->color1[c]));
    return span / sqrt(vec3_dot(d, d));
}

static void gradient_move(struct pigment_record *rec, const double origin[3])
{
    vec3_sub(rec->p, origin, rec->p);
}

static void gradient_json(FILE *out, const struct scene *s, const struct scene_pigment *pg)
{
    (void)s;
    json_numbers(out, "p0", pg->p0, 3);
    fputs(", ", out);
    json_numbers(out, "p1", pg->p1, 3);
    fputs(", ", out);
    json_numbers(out, "color0", pg->color1, 3);
    fputs(", ", out);
    json_numbers(out, "color1", pg->color2, 3);
}

/* The texture at path, decoded once however many pigments name it. */
static int add_texture(struct scene_reader *r, char *path, const struct token *at,
                       size_t *index)
{
    struct scene *s = read_scene(r);
    for (size_t i = 0; i < s->ntextures; i++)
        if (strcmp(s->textures[i].path, path) == 0) {
            free(path);
            *index = i;
            return 0;
        }
    struct texture_image img;
    char why[256], quoted[LEXER_QUOTE_SIZE];
    if (texture_load(path, &img, why, sizeof why) != 0) {
        free(path);
        token_describe(at, quoted, sizeof quoted);
        return read_fail(r, at, "cannot read texture %s: %s", quoted, why);
    }
    struct scene_texture *grown = realloc(s->textures, (s->ntextures + 1) * sizeof *grown);
    if (!grown) {
        free(path);
        free(img.rgb);
        return read_fail(r, at, "out of memory for texture");
    }
    s->textures = grown;
    s->textures[s->ntextures] = (struct scene_texture){
        .path = path, .width = img.width, .height = img.height, .rgb = img.rgb,
        .step = texture_step(&img)};
    *index = s->ntextures++;
    return 0;
}

static int texmap_read(struct scene_reader *r, struct scene_pigment *pg)
{
    char *path = NULL;
    struct token at;
    if (read_file_name(r, "an image file name", &path, &at) ||
        add_texture(r, path, &at, &pg->texture))
        return -1;
    return read_numbers(r, pg->s, 4, NULL) || read_numbers(r, pg->t, 4, NULL);
}

static void texmap_pack(const struct scene_pigment *pg, struct pigment_record *rec)
{
    memcpy(rec->p, pg->s, sizeof rec->p);
    memcpy(rec->q, pg->t, sizeof rec->q);
    rec->texture = (long)pg->texture;
}

/* A row r . (x y z 1) of points moved by -origin: its constant gains
 * r . origin, of which only the fraction counts (the texture repeats), and
 * keeping that alone keeps float's s and t as fine as near 0. */
static void move_row(double r[4], const double origin[3])
{
    double shift = vec3_dot(r, origin);
    if (shift != 0)
        r[3] = fmod(r[3] + shift, 1.0);
}

/* Filtered bilinearly, a channel moves by at most the texture's steepest
 * step between neighbouring texels across a texel: that, times texels per
 * unit of length along s or t. */
static double texmap_slope(const struct scene *s, const struct scene_pigment *pg)
{
    const struct scene_texture *t = &s->textures[pg->texture];
    double across = sqrt(vec3_dot(pg->s, pg->s)) * t->width;
    double down = sqrt(vec3_dot(pg->t, pg->t)) * t->height;
    return t->step * fmax(across, down);
}

static void texmap_move(struct pigment_record *rec, const double origin[3])
{
    move_row(rec->p, origin);
    move_row(rec->q, origin);
}

static void texmap_json(FILE *out, const struct scene *s, const struct scene_pigment *pg)
{
    const struct scene_texture *t = &s->textures[pg->texture];
    fputs("\"file\": ", out);
    json_string(out, t->path);
    fprintf(out, ", \"width\": %d, \"height\": %d, ", t->width, t->height);
    json_numbers(out, "s", pg->s, 4);
    fputs(", ", out);
    json_numbers(out, "t", pg->t, 4);
}

/* Each kind's functions and alias, in struct pigment_kind's order after
 * the fields kinds.h gives: KEYWORD_OPS for each row of TP2_PIGMENTS. */
#define solid_OPS solid_read, solid_pack, unmoved, solid_json, NULL, NULL
#define checker_OPS checker_read, checker_pack, checker_move, checker_json, NULL, NULL
#define gradient_OPS gradient_read, gradient_pack, gradient_move, gradient_json, gradient_slope, \
                     NULL
#define texmap_OPS texmap_read, texmap_pack, texmap_move, texmap_json, texmap_slope, \
                   "textmap" /* the 2022 handout's spelling */

#define TP2_PIGMENT_ROW_(NAME, keyword, id) [PIGMENT_##NAME] = {#keyword, id, keyword##_OPS},
const struct pigment_kind pigment_kinds[PIGMENT_COUNT] = {TP2_PIGMENTS(TP2_PIGMENT_ROW_)};

const char *pigment_keywords(void)
{
    static char text[128];
    if (!text[0]) {
        const char *words[2 * PIGMENT_COUNT];
        int n = 0;
        for (int k = 0; k < PIGMENT_COUNT; k++) {
            words[n++] = pigment_kinds[k].keyword;
            if (pigment_kinds[k].alias)
                words[n++] = pigment_kinds[k].alias;
        }
        keyword_list(words, n, text, sizeof text);
    }
    return text;
}
