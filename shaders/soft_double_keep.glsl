// soft_double_keep.glsl: the software double library (soft_double.glsl)
// kept whole in the double builds. A device without 64-bit floats runs
// them lowered onto it (host/gpu/spirv_soft_double.h), which calls its
// functions by name; glslang emits only the functions something calls,
// so main calls sd_keep, which calls each, under SOFT_DOUBLE_KEEP: a
// specialization constant the host always sets false, whose dead branch
// spirv_specialize takes away before a driver sees it.
#include "soft_double.glsl"

layout(constant_id = TP2_SPEC_SOFT_KEEP) const bool SOFT_DOUBLE_KEEP = false;

void sd_keep()
{
    uvec2 a = uvec2(1u), b = uvec2(2u);
    a = sd_add(sd_sub(a, b), sd_mul(sd_div(a, b), sd_neg(a)));
    a = sd_abs(sd_sqrt(sd_floor(sd_fract(a))));
    a = sd_min(a, sd_max(a, b));
    bool c = sd_lt(a, b) || sd_le(a, b) || sd_gt(a, b) || sd_ge(a, b) || sd_eq(a, b) ||
             sd_une(a, b);
    a = sd_from_float(sd_to_float(a) + float(c));
    a = sd_from_int(sd_to_int(a));
}
