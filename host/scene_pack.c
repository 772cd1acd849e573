#include "scene_pack.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gpu_layout.h"

/* The camera of SPEC 4: u and v already scaled to the image plane's half
 * width and half height at distance 1 along w. */
struct camera_basis {
    double u[3], v[3], w[3];
};

static void normalize3(double v[3])
{
    double len = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int i = 0; i < 3; i++)
        v[i] /= len;
}

static void cross3(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

/* The parser has rejected eye == center and up parallel to the view. */
static void camera_basis(const struct scene *s, int width, int height,
                         struct camera_basis *cam)
{
    const double pi = 3.14159265358979323846;
    for (int i = 0; i < 3; i++)
        cam->w[i] = s->center[i] - s->eye[i];
    normalize3(cam->w);
    cross3(cam->w, s->up, cam->u);
    normalize3(cam->u);
    cross3(cam->u, cam->w, cam->v);
    double half_h = tan(s->fov * pi / 360.0);
    double half_w = half_h * (double)width / (double)height;
    for (int i = 0; i < 3; i++) {
        cam->u[i] *= half_w;
        cam->v[i] *= half_h;
    }
}

static void *alloc_buffer(struct packed_scene *out, int binding, size_t count,
                          size_t elem)
{
    if (count == 0)
        count = 1;
    if (count > SIZE_MAX / elem)
        return NULL;
    out->size[binding] = count * elem;
    out->data[binding] = calloc(count, elem);
    return out->data[binding];
}

static void put_color(float dst[4], const double *rgb)
{
    for (int i = 0; i < 3; i++)
        dst[i] = rgb ? (float)rgb[i] : 0.0f;
    dst[3] = 0.0f;
}

/* SPEC 3: all three coefficients zero means no attenuation. */
static void put_attenuation(float dst[4], const double att[3])
{
    bool none = att[0] == 0 && att[1] == 0 && att[2] == 0;
    dst[0] = none ? 1.0f : (float)att[0];
    dst[1] = (float)att[1];
    dst[2] = (float)att[2];
    dst[3] = 0.0f;
}

/* Sphere: center and radius as written. Plane: (a b c d) divided by
 * |(a b c)|, so the shader gets a unit normal and a true distance. */
static int object_geometry(const struct scene_object *o, double g[4])
{
    memcpy(g, o->p, 4 * sizeof *g);
    if (o->kind == OBJECT_SPHERE)
        return TP2_OBJECT_SPHERE;
    double len = sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
    for (int i = 0; i < 4; i++)
        g[i] /= len;
    return TP2_OBJECT_PLANE;
}

#define TP2_REAL float
#define TP2_SUFFIX _f
#include "scene_pack_types.inc"
#undef TP2_REAL
#undef TP2_SUFFIX

#define TP2_REAL double
#define TP2_SUFFIX _d
#include "scene_pack_types.inc"
#undef TP2_REAL
#undef TP2_SUFFIX

int scene_pack(const struct scene *s, int width, int height, bool use_double,
               struct packed_scene *out)
{
    memset(out, 0, sizeof *out);
    struct camera_basis cam;
    camera_basis(s, width, height, &cam);
    int rc = use_double ? pack_d(s, &cam, width, height, out)
                        : pack_f(s, &cam, width, height, out);
    if (rc != 0)
        packed_scene_free(out);
    return rc;
}

void packed_scene_free(struct packed_scene *p)
{
    for (int i = 0; i < TP2_INPUT_BUFFERS; i++)
        free(p->data[i]);
    memset(p, 0, sizeof *p);
}
