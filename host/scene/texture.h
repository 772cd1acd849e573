/* texture.h: decoding the images a texmap pigment names (SPEC 3).
 *
 * BMP through stb_image (Debian's libstb), PNG through libpng and JPEG
 * through libjpeg-turbo: well-kept decoders beat hand-written ones. PPM
 * through a small reader of our own, since stb_image reads neither ASCII
 * P3 nor maxvals other than 255 and 65535 (it does not scale them). */
#ifndef TP2_TEXTURE_H
#define TP2_TEXTURE_H

#include <stddef.h>
#include <stdint.h>

/* Most texels in one image: 32 Mi texels of 4 bytes fill lavapipe's
 * largest storage buffer (128 MiB). The fuzz build lowers it (a header
 * claiming a large image then costs no decode of zeros), nothing else. */
#ifndef TEXTURE_MAX_TEXELS
#define TEXTURE_MAX_TEXELS ((size_t)1 << 25)
#endif

struct texture_image {
    int width, height;
    uint8_t *rgb; /* width * height * 3 bytes, rows top to bottom */
};

/* Decodes the image file at path into *out (free rgb with free()).
 * Returns 0, or -1 with *out zeroed and a reason written to why (no file
 * name in it: "No such file or directory", "not a BMP, PNG, JPEG or PPM
 * image", "PPM data ends early", ...). It looks before it loads: a file
 * whose first bytes are no BMP, PNG, JPEG or PPM is refused then, and an
 * image is read no further than its header says it needs (or its decoder
 * asks), so an endless file (a FIFO, /dev/zero) costs only its image.
 * What no header bounds stops at 1 GiB ("File too large"). */
int texture_load(const char *path, struct texture_image *out, char *why,
                 size_t whysize);

/* Decodes an image file's len bytes held in memory, whatever its format
 * (PPM by its magic P3 or P6, JPEG by libjpeg, PNG by libpng, BMP by
 * stb_image); as texture_load, by the same readers, so that they can be
 * tested and fuzzed without files. */
int texture_decode(const unsigned char *data, size_t len, struct texture_image *out,
                   char *why, size_t whysize);

/* Decodes a PPM (P3 or P6, '#' comments, maxval 1..65535) held in memory;
 * as texture_load. Values are scaled to 8 bits, round(255 v / maxval). */
int texture_decode_ppm(const unsigned char *data, size_t len,
                       struct texture_image *out, char *why, size_t whysize);

/* The steepest step of the image: the largest difference of a channel
 * between two texels side by side or one above the other, the image
 * repeating (its last column beside its first, its last row above its
 * first), in [0, 1]. Filtered bilinearly, the texture's color moves by at
 * most that across a texel (the shader's pigment_slope). */
double texture_step(const struct texture_image *img);

#endif
