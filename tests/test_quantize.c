/* test_quantize.c: finish.comp's float-only 8-bit quantization against the
 * host's image_quantize (floor(255 c + 0.5) in double). The shader's
 * arithmetic is replayed here step by step in float, each step rounded
 * (volatile, and this file is built with -ffp-contract=off, as `precise`
 * asks of the shader), on every float within 4096 ulps of each rounding
 * boundary (k - 0.5) / 255, on a sweep of every 61st float in [0, 1], and
 * on the special values; with --all, on every float in [0, 1] (about
 * 1.07e9; run once by hand: 0 differences). The replay and the GLSL must
 * stay the same steps: finish.comp says so where it is defined. */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "image_write.h"
#include "unit.h"

/* finish.comp's quantized(), step by step in float. */
static unsigned quantized(float c)
{
    if (!(c > 0.0f))
        return 0;
    if (c >= 1.0f)
        return 255;
    volatile float a = 256.0f * c, b = -c;
    volatile float hi = a + b;
    volatile float bv = hi - a;
    volatile float av = hi - bv;
    volatile float lo = (a - av) + (b - bv);
    volatile float k = floorf(hi + 0.5f);
    volatile float below = hi - (k - 0.5f);
    volatile float above = hi - (k + 0.5f);
    if (below < -lo)
        k -= 1.0f;
    else if (above >= -lo)
        k += 1.0f;
    return (unsigned)k;
}

static float from_bits(uint32_t u)
{
    float f;
    memcpy(&f, &u, sizeof f);
    return f;
}

static uint32_t to_bits(float f)
{
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    return u;
}

static long differences;

static void check(float c)
{
    if (quantized(c) == image_quantize(c))
        return;
    if (differences++ < 10)
        expect(0, "quantized(%a) = %u, image_quantize = %u", c, quantized(c),
               image_quantize(c));
}

int main(int argc, char **argv)
{
    const uint32_t one = to_bits(1.0f);
    if (argc > 1 && strcmp(argv[1], "--all") == 0) {
        for (uint32_t u = 0; u <= one; u++)
            check(from_bits(u));
    } else {
        for (int k = 1; k <= 255; k++) {
            uint32_t at = to_bits((float)((k - 0.5) / 255.0));
            for (uint32_t u = at - 4096; u <= at + 4096; u++)
                check(from_bits(u));
        }
        for (uint32_t u = 0; u <= one; u += 61)
            check(from_bits(u));
    }
    const float special[] = {0.0f, -0.0f, 1.0f, -1.0f, 2.0f, INFINITY, -INFINITY, NAN,
                             1e-45f, 0.5f / 255.0f, 254.5f / 255.0f, 0x1.fffffep-1f};
    for (size_t i = 0; i < sizeof special / sizeof special[0]; i++)
        check(special[i]);
    expect(differences == 0, "%ld floats quantized otherwise than on the host", differences);
    return unit_report();
}
