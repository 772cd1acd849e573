#version 450
// finish.comp: a finished band of the image as the file needs it, so that
// only that crosses the bus to the host: 8-bit RGB for PPM and PNG (one
// word per pixel instead of four floats), floats for PFM. It reads the
// band's pixels (trace.comp's running sums, rgb and a junk alpha) and
// writes the output buffer, TP2_FINISH_GROUP pixels per workgroup.
#extension GL_GOOGLE_include_directive : require

#include "tp2_shared.h"

layout(local_size_x = TP2_FINISH_GROUP) in;

layout(constant_id = TP2_FINISH_SPEC_BYTES) const bool BYTES = true;

layout(std430, set = 0, binding = TP2_BINDING_IMAGE) readonly buffer ImageBuf { vec4 pixels[]; };
layout(std430, set = 0, binding = TP2_BINDING_OUTPUT) writeonly buffer OutputBuf { uint words[]; };

#include "tile.glsl" // list_length: the band's pixels

// The 8-bit level of a linear channel exactly as the host's
// image_quantize: clamped to [0, 1], floor(255 c + 0.5) of the exact
// product (the host computes it in double), NaN giving 0; in float alone,
// as devices without shaderFloat64 must. 255 c is split exactly into
// hi + lo (256 c is exact, and Knuth's two-sum gives the rounding error of
// 256 c - c); floor(hi + 0.5) is then off by at most one, and the exact
// comparisons of hi - (k -+ 0.5) with -lo settle it (both differences are
// exact where it matters, by Sterbenz's lemma). `precise` keeps compilers
// from fusing or reordering any of it. Checked against image_quantize on
// every float in [0, 1] (tests/test_quantize.c replays these steps).
uint quantized(float c)
{
    if (!(c > 0.0))
        return 0u;
    if (c >= 1.0)
        return 255u;
    precise float a = 256.0 * c;
    precise float b = -c;
    precise float hi = a + b;
    precise float bv = hi - a;
    precise float av = hi - bv;
    precise float lo = (a - av) + (b - bv);
    precise float k = floor(hi + 0.5);
    precise float below = hi - (k - 0.5);
    precise float above = hi - (k + 0.5);
    if (below < -lo)
        k -= 1.0;
    else if (above >= -lo)
        k += 1.0;
    return uint(k);
}

void main()
{
    int i = int(gl_GlobalInvocationID.x);
    if (i >= list_length)
        return;
    vec4 p = pixels[i];
    if (BYTES) {
        words[i] = quantized(p.r) | quantized(p.g) << 8 | quantized(p.b) << 16;
    } else {
        for (int c = 0; c < 4; ++c)
            words[4 * i + c] = floatBitsToUint(p[c]);
    }
}
