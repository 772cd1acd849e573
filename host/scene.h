/* scene.h: the scene as read from a file, in plain C and double precision.
 *
 * Nothing here knows about Vulkan; scene_pack.c turns it into GPU buffers.
 * All arrays are owned by the scene and freed by scene_free(). */
#ifndef TP2_SCENE_H
#define TP2_SCENE_H

#include <stddef.h>

/* Largest image side accepted, from the command line or a scene header:
 * far beyond any display, and width * height * 16 bytes cannot overflow. */
#define TP2_MAX_IMAGE_SIDE 32768

/* Most samples per pixel, and points per area light: 4096 already brings
 * stratified noise far below one 8-bit level. */
#define TP2_MAX_SAMPLES 4096

enum pigment_kind { PIGMENT_SOLID, PIGMENT_CHECKER };
enum object_kind { OBJECT_SPHERE, OBJECT_PLANE };

struct scene_light {
    double pos[3];
    double color[3];
    double att[3]; /* 1 / (a + b d + c d^2); all zero means no attenuation */
};

struct scene_pigment {
    /* Largest image side accepted, from the command line or a scene header:
 * far beyond any display, and width * height * 16 bytes cannot overflow. */
#define TP2_MAX_IMAGE_SIDE 32768

/* Most samples per pixel, and points per area light: 4096 already brings
 * stratified noise far below one 8-bit level. */
#define TP2_MAX_SAMPLES 4096

enum pigment_kind kind;
    double color1[3];
    double color2[3]; /* checker only */
    double scale;     /* checker cube side, > 0 */
};

struct scene_finish {
    double ka, kd, ks, n; /* Phong */
    double kr, kt, ior;   /* reflection, transmission, inside index */
};

struct scene_object {
    enum object_kind kind;
    size_t pigment, finish;
    double p[4]; /* sphere: cx cy cz r; plane: a b c d (as written) */
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
    struct scene_finish *finishes;
    size_t nfinishes;
    struct scene_object *objects;
    size_t nobjects;

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
};

/* Frees every array of s and zeroes it; safe on a zeroed scene. */
void scene_free(struct scene *s);

#endif
