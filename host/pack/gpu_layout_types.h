/* gpu_layout_types.h: one instantiation of the GPU structs (std430).
 *
 * Included twice by gpu_layout.h, with TP2_REAL = float / suffix _f and
 * TP2_REAL = double / suffix _d. Every 4-vector carries the alignment std430
 * gives it (16 bytes for vec4, 32 for dvec4), so C lays the struct out as the
 * shader does; gpu_layout.h checks every size and offset. The GLSL side is
 * shaders/layout.glsl. No include guard: included once per real type. */

#define TP2_RVEC4(name) _Alignas(4 * sizeof(TP2_REAL)) TP2_REAL name[4]
#define TP2_VEC4(name) _Alignas(16) float name[4]
#define TP2_IVEC4(name) _Alignas(16) int32_t name[4]
#define TP2_T(name) TP2_CAT(name, TP2_SUFFIX)

struct TP2_T(gpu_frame) {
    TP2_RVEC4(eye);     /* xyz: camera position, from scene_pack.c's origin */
    TP2_RVEC4(u);       /* xyz: right, scaled by half the image width */
    TP2_RVEC4(v);       /* xyz: up, scaled by half the image height */
    TP2_RVEC4(w);       /* xyz: unit view direction (image plane at 1) */
    TP2_VEC4(ambient);  /* rgb: color of light 0 */
    TP2_VEC4(background);
    TP2_VEC4(fog);      /* rgb, density */
    TP2_VEC4(lens);     /* aperture radius, focal distance */
    TP2_VEC4(area);     /* x: arealight radius */
    TP2_VEC4(limits);   /* x: bailout, the least weight a ray is traced with */
    TP2_IVEC4(counts);  /* width, height, point lights, objects */
    TP2_IVEC4(geometry); /* bounded objects, unbounded ones after them, BVH nodes */
    TP2_IVEC4(sampling); /* lattice generator, arealight index, samples,
                          * TP2_CANARY_STEPS */
};

struct TP2_T(gpu_light) {
    TP2_RVEC4(pos);   /* xyz */
    TP2_VEC4(color);  /* rgb */
    TP2_VEC4(att);    /* a b c of 1 / (a + b d + c d^2), already non-zero */
};

struct TP2_T(gpu_pigment) { /* what each kind keeps where: pigments.c */
    TP2_VEC4(color1);
    TP2_VEC4(color2);
    TP2_RVEC4(p);
    TP2_RVEC4(q);
    TP2_IVEC4(kind);   /* TP2_PIGMENT_*; texmap: first texel, width, height */
};

struct TP2_T(gpu_finish) {
    TP2_VEC4(phong);  /* ka kd ks n */
    TP2_VEC4(optics); /* kr kt ior */
};

struct TP2_T(gpu_object) { /* what each kind keeps where: shapes.c */
    TP2_RVEC4(a);
    TP2_RVEC4(b);
    TP2_RVEC4(c);
    TP2_IVEC4(ids);  /* TP2_SHAPE_*, pigment, finish, first row in extra */
};

struct TP2_T(gpu_walk_ray) { /* a saved walk's ray (layout.glsl, WalkRay) */
    TP2_RVEC4(origin); /* xyz, weight */
    TP2_RVEC4(dir);    /* xyz */
    TP2_IVEC4(info);   /* start object, start inward, depth */
    TP2_VEC4(doubt);   /* xyz: its rounding's bound (signature.glsl) */
};

#undef TP2_RVEC4
#undef TP2_VEC4
#undef TP2_IVEC4
#undef TP2_T
