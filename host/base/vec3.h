/* vec3.h: the few double-precision 3-vector operations the host needs. */
#ifndef TP2_VEC3_H
#define TP2_VEC3_H

#include <math.h>

static inline double vec3_dot(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static inline void vec3_sub(const double a[3], const double b[3], double out[3])
{
    for (int i = 0; i < 3; i++)
        out[i] = a[i] - b[i];
}

static inline void vec3_cross(const double a[3], const double b[3], double out[3])
{
    double x = a[1] * b[2] - a[2] * b[1];
    double y = a[2] * b[0] - a[0] * b[2];
    double z = a[0] * b[1] - a[1] * b[0];
    out[0] = x;
    out[1] = y;
    out[2] = z;
}

/* Largest |component|. */
static inline double vec3_max_abs(const double a[3])
{
    return fmax(fabs(a[0]), fmax(fabs(a[1]), fabs(a[2])));
}

/* Scales v to unit length in out (out may be v) without overflow or
 * underflow; returns its length, or 0 (out zero) if v is zero. */
static inline double vec3_unit(const double v[3], double out[3])
{
    double m = vec3_max_abs(v);
    if (!(m > 0)) {
        out[0] = out[1] = out[2] = 0;
        return 0;
    }
    double a[3] = {v[0] / m, v[1] / m, v[2] / m};
    double len = sqrt(vec3_dot(a, a));
    for (int i = 0; i < 3; i++)
        out[i] = a[i] / len;
    return len * m;
}

#endif
