/* scene.h: the scene as read from a file, in plain C and double precision.
 *
 * Nothing here knows about Vulkan; scene_pack.c turns it into GPU buffers.
 * What each kind of object and pigment means lives in shapes.c and
 * pigments.c. All arrays are owned by the scene and freed by scene_free(). */
#ifndef TP2_SCENE_H
#define TP2_SCENE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* Largest image side accepted, from the command line or a scene header:
 * far beyond any display, and width * height * 16 bytes cannot overflow. */
#define TP2_MAX_IMAGE_SIDE 32768

/* Most samples per pixel, and points per area light: 4096 already brings
 * stratified noise far below one 8-bit level. */
#define TP2_MAX_SAMPLES 4096

struct scene_light {
    double pos[3];
    double color[3];
    double att[3]; /* 1 / (a + b d + c d^2); all zero means no attenuation */
};

/* One pigment: kind indexes the table of pigments.c (PIGMENT_*), which
 * says which fields it uses. */
struct scene_pigment {
    int kind;
    double color1[3];
    double color2[3];  /* checker: odd cells; gradient: color at point 1 */
    double scale;      /* checker cube side, > 0 */
    double p0[3], p1[3]; /* gradient end points, distinct */
    double s[4], t[4];   /* texmap: s = s . (x y z 1), t = t . (x y z 1) */
    size_t texture;      /* texmap: index into scene.textures */
};

/* An image a texmap reads, decoded to 8-bit RGB, rows top to bottom. */
struct scene_texture {
    char *path;   /* as resolved against the scene file's folder */
    int width, height;
    uint8_t *rgb; /* width * height * 3 bytes */
    double step;  /* texture_step's */
};

struct scene_finish {
    double ka, kd, ks, n; /* Phong */
    double kr, kt, ior;   /* reflection, transmission, inside index */
};

/* One object: kind indexes the table of shapes.c (SHAPE_*); its numbers,
 * in the form that table documents, are reals[first .. first + count). */
struct scene_object {
    int kind;
    size_t pigment, finish;
    size_t first, count;
};

struct scene {
    /* Header variant: output name and "W H" before the camera. */
    int has_size;
    int width, height;

    double eye[3], center[3], up[3];
    double fov; /* vertical, degrees, 0 < fov < 180 */

    struct scene_light *lights; /* lights[0] is the ambient light */
    size_t nlights;
    struct scene_pigment *pigments;
    size_t npigments;
    struct scene_texture *textures;
    size_t ntextures;
    struct scene_finish *finishes;
    size_t nfinishes;
    struct scene_object *objects;
    size_t nobjects;
    double *reals; /* the objects' numbers */
    size_t nreals;

    /* Trailing directives; has_* is 0 when absent. */
    int has_samples;
    int samples;
    int has_lens;
    double lens_radius, lens_focal;
    int has_fog;
    double fog_color[3], fog_density;
    int has_arealight;
    size_t arealight_index;
    double arealight_radius;
    int arealight_samples;

    /* The largest magnitude among the lengths the shaders get (camera
     * eye, light positions, every number of every object's GPU records,
     * lens and area light sizes), and where it was written: what
     * scene_length_limit is checked against. what names it ("sphere"). */
    double max_length;
    size_t max_length_line, max_length_col;
    const char *max_length_what; /* static; NULL while max_length is 0 */
};

/* The largest length (coordinate or size, in magnitude) that renders
 * faithfully in each precision; see scene.c for why. */
double scene_length_limit(bool use_double);

/* The numbers of object o. */
static inline const double *scene_object_reals(const struct scene *s,
                                               const struct scene_object *o)
{
    return s->reals + o->first;
}

/* Frees every array of s and zeroes it; safe on a zeroed scene. */
void scene_free(struct scene *s);

#endif
