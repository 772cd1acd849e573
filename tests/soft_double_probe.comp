#version 450
#extension GL_GOOGLE_include_directive : require
// soft_double_probe.comp: one operation of shaders/soft_double.glsl on
// each input pair, for tests/test_soft_double.c to compare with the host's
// doubles. No 64-bit type in it: it runs where shaderFloat64 is missing.
layout(local_size_x = 64) in;

#include "soft_double.glsl"

layout(push_constant) uniform Probe { uint op; uint count; };
layout(std430, binding = 0) readonly buffer In { uvec4 pairs[]; }; // a in xy, b in zw
layout(std430, binding = 1) writeonly buffer Out { uvec2 results[]; };

uint flags(uvec2 a, uvec2 b)
{
    return (sd_lt(a, b) ? 1u : 0u) | (sd_le(a, b) ? 2u : 0u) | (sd_gt(a, b) ? 4u : 0u) |
           (sd_ge(a, b) ? 8u : 0u) | (sd_eq(a, b) ? 16u : 0u) | (sd_une(a, b) ? 32u : 0u);
}

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= count)
        return;
    uvec2 a = pairs[i].xy, b = pairs[i].zw;
    uvec2 r = uvec2(0u);
    switch (op) {
    case 0u: r = sd_add(a, b); break;
    case 1u: r = sd_sub(a, b); break;
    case 2u: r = sd_mul(a, b); break;
    case 3u: r = sd_div(a, b); break;
    case 4u: r = sd_sqrt(a); break;
    case 5u: r = sd_floor(a); break;
    case 6u: r = sd_fract(a); break;
    case 7u: r = sd_min(a, b); break;
    case 8u: r = sd_max(a, b); break;
    case 9u: r = uvec2(flags(a, b), 0u); break;
    case 10u: r = uvec2(floatBitsToUint(sd_to_float(a)), 0u); break;
    case 11u: r = sd_from_float(uintBitsToFloat(a.x)); break;
    case 12u: r = sd_from_int(int(a.x)); break;
    case 13u: r = uvec2(uint(sd_to_int(a)), 0u); break;
    case 14u: r = sd_neg(a); break;
    case 15u: r = sd_abs(a); break;
    }
    results[i] = r;
}
