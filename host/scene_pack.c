#include "scene_pack.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "bvh.h"
#include "gpu_layout.h"

/* Fewer spheres than this are tested in a plain loop: on lavapipe's 8-wide
 * SIMD the loop beats a divergent tree walk up to about here (measured with
 * --bvh-min, README.TXT "Performance"). */
#define TP2_BVH_MIN_SPHERES 16

_Static_assert(TP2_BVH_STACK >= TP2_BVH_MAX_DEPTH,
               "the shader's BVH stack must hold the deepest tree");

/* The camera of SPEC 4: u and v already scaled to the image plane's half
 * width and half height at distance 1 along w. */
struct camera_basis {
    double u[3], v[3], w[3];
};

/* Everything both packings share, computed once in double. */
struct layout {
    struct camera_basis cam;
    size_t nspheres;
    size_t *object_order; /* GPU slot -> scene object: spheres, then planes */
    struct bvh bvh;
    int samples;
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

static size_t point_lights(const struct scene *s)
{
    return s->nlights > 0 ? s->nlights - 1 : 0;
}

static int gcd(int a, int b)
{
    while (b) {
        int t = a % b;
        a = b;
        b = t;
    }
    return a;
}

/* The generator g of the rank-1 lattice (k/n, k g/n mod 1): coprime with n
 * (so each row holds one sample) and near n / golden ratio, which spreads
 * the points evenly (a Fibonacci lattice when n is a Fibonacci number). */
static int lattice_generator(int n)
{
    int g = (int)lround(n * 0.6180339887498949);
    for (int d = 0; d < n; d++) {
        if (g - d >= 1 && gcd(g - d, n) == 1)
            return g - d;
        if (g + d < n && gcd(g + d, n) == 1)
            return g + d;
    }
    return 1;
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

/* rgb (black if NULL) and a fourth value. */
static void put_color(float dst[4], const double *rgb, double w)
{
    for (int i = 0; i < 3; i++)
        dst[i] = rgb ? (float)rgb[i] : 0.0f;
    dst[3] = (float)w;
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

static void put_finish(float phong[4], float optics[4], const struct scene_finish *f)
{
    const float p[4] = {(float)f->ka, (float)f->kd, (float)f->ks, (float)f->n};
    const float o[4] = {(float)f->kr, (float)f->kt, (float)f->ior, 0.0f};
    memcpy(phong, p, sizeof p);
    memcpy(optics, o, sizeof o);
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

/* Features of the objects actually in the scene (an unused finish with
 * kr > 0 costs nothing). */
static struct scene_features scene_features(const struct scene *s, int samples)
{
    struct scene_features f = {
        .fog = s->has_fog && s->fog_density > 0,
        .lens = s->has_lens && s->lens_radius > 0,
        .area = s->has_arealight,
        .samples = samples,
    };
    for (size_t i = 0; i < s->nobjects; i++) {
        const struct scene_object *o = &s->objects[i];
        f.reflect |= s->finishes[o->finish].kr > 0;
        f.refract |= s->finishes[o->finish].kt > 0;
        f.checker |= s->pigments[o->pigment].kind == PIGMENT_CHECKER;
        f.spheres |= o->kind == OBJECT_SPHERE;
        f.planes |= o->kind == OBJECT_PLANE;
    }
    return f;
}

/* Object order and BVH: spheres in the BVH's order, then planes. */
static int layout_objects(const struct scene *s, struct layout *lay)
{
    double (*spheres)[4] = malloc((s->nobjects ? s->nobjects : 1) * sizeof *spheres);
    size_t *sphere_index = malloc((s->nobjects ? s->nobjects : 1) * sizeof *sphere_index);
    lay->object_order = malloc((s->nobjects ? s->nobjects : 1) * sizeof *lay->object_order);
    int rc = -1;
    if (spheres && sphere_index && lay->object_order) {
        size_t n = 0;
        for (size_t i = 0; i < s->nobjects; i++)
            if (s->objects[i].kind == OBJECT_SPHERE) {
                memcpy(spheres[n], s->objects[i].p, sizeof spheres[n]);
                sphere_index[n++] = i;
            }
        lay->nspheres = n;
        if (bvh_build((const double (*)[4])spheres, n, &lay->bvh) == 0) {
            size_t slot = 0;
            for (; slot < n; slot++)
                lay->object_order[slot] = sphere_index[lay->bvh.order[slot]];
            for (size_t i = 0; i < s->nobjects; i++)
                if (s->objects[i].kind != OBJECT_SPHERE)
                    lay->object_order[slot++] = i;
            rc = 0;
        }
    }
    free(spheres);
    free(sphere_index);
    return rc;
}

static int pack_bvh(const struct bvh *b, struct packed_scene *out)
{
    void *nodes = alloc_buffer(out, TP2_BINDING_BVH, b->node_count, sizeof *b->nodes);
    if (!nodes)
        return -1;
    if (b->node_count)
        memcpy(nodes, b->nodes, b->node_count * sizeof *b->nodes);
    return 0;
}

int scene_pack(const struct scene *s, const struct pack_options *opt,
               struct packed_scene *out)
{
    memset(out, 0, sizeof *out);
    struct layout lay = {.samples = opt->samples ? opt->samples
                                    : s->has_samples ? s->samples : 1};
    camera_basis(s, opt->width, opt->height, &lay.cam);
    out->features = scene_features(s, lay.samples);
    int rc = layout_objects(s, &lay);
    int bvh_min = opt->bvh_min_spheres ? opt->bvh_min_spheres : TP2_BVH_MIN_SPHERES;
    out->features.bvh = lay.nspheres >= (size_t)bvh_min;
    if (rc == 0)
        rc = opt->use_double ? pack_d(s, &lay, opt, out) : pack_f(s, &lay, opt, out);
    if (rc == 0)
        rc = pack_bvh(&lay.bvh, out);
    bvh_free(&lay.bvh);
    free(lay.object_order);
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
