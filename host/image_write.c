#define _POSIX_C_SOURCE 200809L
#include "image_write.h"

#include <errno.h>
#include <math.h>
#include <png.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

enum image_format image_format_of(const char *path)
{
    const char *dot = strrchr(path, '.');
    const char *slash = strrchr(path, '/');
    if (!dot || (slash && dot < slash))
        return IMAGE_UNKNOWN;
    if (strcasecmp(dot, ".ppm") == 0)
        return IMAGE_PPM;
    if (strcasecmp(dot, ".png") == 0)
        return IMAGE_PNG;
    if (strcasecmp(dot, ".pfm") == 0)
        return IMAGE_PFM;
    return IMAGE_UNKNOWN;
}

unsigned char image_quantize(float c)
{
    if (!(c > 0.0f)) /* also NaN */
        return 0;
    if (c >= 1.0f)
        return 255;
    return (unsigned char)floor((double)c * 255.0 + 0.5);
}

/* One row of 8-bit RGB from row y of rgba. */
static void quantize_row(const float *rgba, int width, int y, unsigned char *out)
{
    const float *row = rgba + (size_t)y * width * 4;
    for (int x = 0; x < width; x++)
        for (int c = 0; c < 3; c++)
            out[x * 3 + c] = image_quantize(row[x * 4 + c]);
}

static int write_ppm(FILE *f, int width, int height, const float *rgba)
{
    unsigned char *row = malloc((size_t)width * 3);
    if (!row)
        return -1;
    int ok = fprintf(f, "P6\n%d %d\n255\n", width, height) > 0;
    for (int y = 0; y < height && ok; y++) {
        quantize_row(rgba, width, y, row);
        ok = fwrite(row, 3, (size_t)width, f) == (size_t)width;
    }
    free(row);
    return ok ? 0 : -1;
}

/* PFM: little-endian floats (scale -1), rows bottom to top, unclamped. */
static int write_pfm(FILE *f, int width, int height, const float *rgba)
{
    float *row = malloc((size_t)width * 3 * sizeof *row);
    if (!row)
        return -1;
    int ok = fprintf(f, "PF\n%d %d\n-1.0\n", width, height) > 0;
    for (int y = height - 1; y >= 0 && ok; y--) {
        const float *src = rgba + (size_t)y * width * 4;
        for (int x = 0; x < width; x++)
            memcpy(&row[x * 3], &src[x * 4], 3 * sizeof *row);
        ok = fwrite(row, 3 * sizeof *row, (size_t)width, f) == (size_t)width;
    }
    free(row);
    return ok ? 0 : -1;
}

static int write_png(FILE *f, int width, int height, const float *rgba)
{
    unsigned char *row = malloc((size_t)width * 3);
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    if (!row || !info || setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        free(row);
        return -1;
    }
    png_init_io(png, f);
    png_set_IHDR(png, info, (png_uint_32)width, (png_uint_32)height, 8,
                 PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    for (int y = 0; y < height; y++) {
        quantize_row(rgba, width, y, row);
        png_write_row(png, row);
    }
    png_write_end(png, NULL);
    png_destroy_write_struct(&png, &info);
    free(row);
    return 0;
}

/* mkstemp makes the file 0600; give it the mode a new file would get. */
static void set_default_mode(int fd)
{
    mode_t mask = umask(0);
    umask(mask);
    fchmod(fd, 0666 & ~mask);
}

int image_write(const char *path, enum image_format format, int width,
                int height, const float *rgba)
{
    size_t n = strlen(path);
    char *tmp = malloc(n + sizeof ".tmp-XXXXXX");
    if (!tmp) {
        fputs("tp2: out of memory\n", stderr);
        return -1;
    }
    memcpy(tmp, path, n);
    memcpy(tmp + n, ".tmp-XXXXXX", sizeof ".tmp-XXXXXX");
    int fd = mkstemp(tmp);
    if (fd < 0) {
        fprintf(stderr, "tp2: cannot write '%s': %s\n", path, strerror(errno));
        free(tmp);
        return -1;
    }
    set_default_mode(fd);
    FILE *f = fdopen(fd, "wb");
    int rc = -1;
    if (f) {
        switch (format) {
        case IMAGE_PPM: rc = write_ppm(f, width, height, rgba); break;
        case IMAGE_PNG: rc = write_png(f, width, height, rgba); break;
        case IMAGE_PFM: rc = write_pfm(f, width, height, rgba); break;
        default: break;
        }
        int saved = errno;
        if (fclose(f) != 0)
            rc = -1;
        else
            errno = saved;
    } else {
        close(fd);
    }
    if (rc == 0 && rename(tmp, path) != 0)
        rc = -1;
    if (rc != 0) {
        fprintf(stderr, "tp2: cannot write '%s': %s\n", path,
                errno ? strerror(errno) : "write failed");
        unlink(tmp);
    }
    free(tmp);
    return rc;
}
