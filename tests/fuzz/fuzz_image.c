/* fuzz_image.c: libFuzzer target for the image decoders (texture_decode:
 * PPM P3/P6 by our own reader, BMP, PNG, JPEG and the rest through
 * stb_image). The fuzz build compiles stb_image itself (stb_image_impl.c)
 * so that the fuzzer sees its branches. Also built into
 * fuzz_replay_image (tests/fuzz/replay.c), against Debian's libstb. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "texture.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    struct texture_image img;
    char why[256];
    if (texture_decode(data, size, &img, why, sizeof why) != 0) {
        if (why[0] == '\0' || img.rgb)
            abort();
        return 0;
    }
    size_t n = (size_t)img.width * (size_t)img.height;
    if (img.width < 1 || img.height < 1 || n > TEXTURE_MAX_TEXELS)
        abort();
    /* Touch every texel, so that a short buffer shows under ASan. */
    size_t sum = 0;
    for (size_t i = 0; i < 3 * n; i++)
        sum += img.rgb[i];
    free(img.rgb);
    if (sum > 255 * 3 * n)
        abort(); /* cannot happen; makes the sum needed */
    return 0;
}
