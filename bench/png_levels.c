/* png_levels.c: how long libpng takes to encode tp2's images at each zlib
 * level and row filter, and how large the files get (docs/decisions.md,
 * PNG output). Reads binary PPMs (tp2's output), encodes
 * each in memory --runs times per setting and prints the median CPU time.
 *
 *     cc -O2 bench/png_levels.c -lpng -o /tmp/png_levels
 *     /tmp/png_levels [--runs N] IMAGE.ppm...
 */
#define _POSIX_C_SOURCE 200809L
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

struct sink {
    size_t bytes;
};

static void count_bytes(png_structp png, png_bytep data, png_size_t n)
{
    (void)data;
    ((struct sink *)png_get_io_ptr(png))->bytes += n;
}

static void no_flush(png_structp png)
{
    (void)png;
}

static unsigned char *read_ppm(const char *path, int *w, int *h)
{
    FILE *f = fopen(path, "rb");
    int maxval;
    if (!f || fscanf(f, "P6 %d %d %d", w, h, &maxval) != 3 || maxval != 255 ||
        fgetc(f) == EOF) {
        fprintf(stderr, "%s: not a binary PPM of maxval 255\n", path);
        exit(2);
    }
    size_t n = (size_t)*w * (size_t)*h * 3;
    unsigned char *rgb = malloc(n);
    if (!rgb || fread(rgb, 1, n, f) != n)
        exit(2);
    fclose(f);
    return rgb;
}

static double cpu_seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* Encodes once; returns the file size, *seconds the CPU time. */
static size_t encode(const unsigned char *rgb, int w, int h, int level, int filters,
                     double *seconds)
{
    struct sink sink = {0};
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png_create_info_struct(png);
    if (setjmp(png_jmpbuf(png)))
        exit(3);
    double t0 = cpu_seconds();
    png_set_write_fn(png, &sink, count_bytes, no_flush);
    png_set_compression_level(png, level);
    png_set_filter(png, 0, filters);
    png_set_IHDR(png, info, (png_uint_32)w, (png_uint_32)h, 8, PNG_COLOR_TYPE_RGB,
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    for (int y = 0; y < h; y++)
        png_write_row(png, rgb + (size_t)y * (size_t)w * 3);
    png_write_end(png, NULL);
    *seconds = cpu_seconds() - t0;
    png_destroy_write_struct(&png, &info);
    return sink.bytes;
}

static int by_value(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

int main(int argc, char **argv)
{
    int runs = 5, first = 1;
    if (argc > 2 && strcmp(argv[1], "--runs") == 0) {
        runs = atoi(argv[2]);
        first = 3;
    }
    if (runs < 1 || runs > 99 || first >= argc) {
        fprintf(stderr, "usage: png_levels [--runs N] IMAGE.ppm...\n");
        return 2;
    }
    static const struct {
        const char *name;
        int bits;
    } filters[] = {{"all (libpng default)", PNG_ALL_FILTERS},
                   {"none", PNG_FILTER_NONE},
                   {"sub", PNG_FILTER_SUB},
                   {"paeth", PNG_FILTER_PAETH}};
    static const int levels[] = {1, 3, 6, 9};
    printf("%-24s %-22s %5s %10s %12s\n", "image", "filters", "level", "median s", "bytes");
    for (int i = first; i < argc; i++) {
        int w, h;
        unsigned char *rgb = read_ppm(argv[i], &w, &h);
        const char *base = strrchr(argv[i], '/') ? strrchr(argv[i], '/') + 1 : argv[i];
        for (size_t f = 0; f < sizeof filters / sizeof filters[0]; f++)
            for (size_t l = 0; l < sizeof levels / sizeof levels[0]; l++) {
                double t[99];
                size_t bytes = 0;
                for (int r = 0; r < runs; r++)
                    bytes = encode(rgb, w, h, levels[l], filters[f].bits, &t[r]);
                qsort(t, (size_t)runs, sizeof t[0], by_value);
                printf("%-24s %-22s %5d %10.3f %12zu\n", base, filters[f].name, levels[l],
                       t[runs / 2], bytes);
            }
        free(rgb);
    }
    return 0;
}
