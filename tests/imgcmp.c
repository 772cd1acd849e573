/* imgcmp.c: tp2-imgcmp, compares two images in 8-bit levels.
 *
 * usage: tp2-imgcmp [--diff OUT.ppm] [--min-within1 F] [--max-bad8 N] A B
 *
 * A and B are PPM (P6 or P3, any maxval) or PFM (PF or Pf, either byte
 * order) files of the same size; the format is read from the file's magic,
 * not its name. PFM values become levels as tp2 quantises them (clamped to
 * [0, 1], round(255 c), NaN 0); other maxvals are rescaled to 255. Prints
 * one line of key=value:
 *   psnr     10 log10(255^2 / MSE) in dB, "inf" when identical
 *   mae      mean absolute difference per channel value, in levels
 *   max      largest absolute difference, in levels
 *   within1  fraction of channel values within +-1 level
 *   bad8     pixels with any channel off by more than 8 levels
 *   pixels   width * height
 *   fmax     largest absolute float difference (only when both are PFM)
 * Exit status: 0 when the thresholds given are met (or none is given),
 * 1 when one is not, 2 on a usage error, an unreadable or malformed file,
 * or images of different sizes. Standalone C11: no tp2 code. */
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Largest image side accepted, as tp2's; the pixel count is capped too so
 * a lying header cannot ask for gigabytes. */
#define IMGCMP_MAX_SIDE 32768
#define IMGCMP_MAX_PIXELS (1L << 26)

/* Levels amplified by this in the --diff image, so small errors show. */
#define IMGCMP_DIFF_GAIN 8

/* A channel is "bad" beyond this many levels (the bad8 count). */
#define IMGCMP_BAD_LEVELS 8

/* One decoded image, rows top to bottom, 3 channels per pixel. */
struct image {
    int width, height;
    unsigned char *level; /* width * height * 3 levels */
    float *value;         /* the same as floats for a PFM, else NULL */
};

/* Prints "tp2-imgcmp: MESSAGE" to stderr. */
static void error(const char *fmt, ...) __attribute__((format(printf, 1, 2)));

static void error(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fputs("tp2-imgcmp: ", stderr);
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
    va_end(ap);
}

static void usage(FILE *out)
{
    fputs("usage: tp2-imgcmp [--diff OUT.ppm] [--min-within1 F] [--max-bad8 N] A B\n"
          "\n"
          "Compares images A and B (PPM P6/P3 or PFM, same size) in 8-bit\n"
          "levels and prints psnr, mae, max, within1, bad8, pixels (and fmax\n"
          "when both are PFM).\n"
          "\n"
          "options:\n"
          "  --diff OUT.ppm     write |A - B| x 8, clamped, as a PPM\n"
          "  --min-within1 F    fail (exit 1) unless within1 >= F\n"
          "  --max-bad8 N       fail (exit 1) unless bad8 <= N\n"
          "  --help             show this text and exit\n"
          "\n"
          "exit status: 0 thresholds met, 1 not met, 2 usage or input error\n",
          out);
}

/* 8-bit level of a linear value, as tp2's image_quantize. */
static unsigned char quantize(float c)
{
    if (!(c > 0.0f)) /* also NaN */
        return 0;
    if (c >= 1.0f)
        return 255;
    return (unsigned char)floor((double)c * 255.0 + 0.5);
}

/* The whole of path into a malloc'd buffer; NULL (reported) on failure. */
static unsigned char *read_file(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        error("cannot open '%s': %s", path, strerror(errno));
        return NULL;
    }
    size_t cap = 1 << 16, n = 0;
    unsigned char *buf = malloc(cap);
    while (buf) {
        n += fread(buf + n, 1, cap - n, f);
        if (n < cap)
            break;
        /* 12 bytes a pixel (PFM) plus a header, and no more. */
        if (cap > (size_t)IMGCMP_MAX_PIXELS * 12 + 4096) {
            error("'%s': file too large", path);
            free(buf);
            fclose(f);
            return NULL;
        }
        unsigned char *grown = realloc(buf, cap * 2);
        if (!grown)
            free(buf);
        buf = grown;
        cap *= 2;
    }
    int bad = ferror(f);
    fclose(f);
    if (!buf || bad) {
        error("cannot read '%s': %s", path, buf ? "read error" : "out of memory");
        free(buf);
        return NULL;
    }
    *len = n;
    return buf;
}

/* A cursor over a file's bytes, for the text parts of its header. */
struct reader {
    const char *path;
    const unsigned char *p, *end;
};

static int is_space(int c)
{
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' ||
           c == '\f';
}

/* Skips whitespace and, for PNM, '#' comments to the end of the line. */
static void skip_space(struct reader *r, int comments)
{
    while (r->p < r->end) {
        if (is_space(*r->p))
            r->p++;
        else if (comments && *r->p == '#')
            while (r->p < r->end && *r->p != '\n')
                r->p++;
        else
            break;
    }
}

/* A decimal integer in [lo, hi] after optional whitespace; 0 or -1
 * (reported, naming what). */
static int read_int(struct reader *r, int comments, long lo, long hi,
                    const char *what, long *out)
{
    skip_space(r, comments);
    long v = 0;
    const unsigned char *start = r->p;
    while (r->p < r->end && *r->p >= '0' && *r->p <= '9') {
        v = v * 10 + (*r->p - '0');
        r->p++;
        if (v > hi)
            break;
    }
    if (r->p == start || v < lo || v > hi ||
        (r->p < r->end && !is_space(*r->p) && *r->p != '#')) {
        error("'%s': bad %s (want an integer in %ld..%ld)", r->path, what, lo, hi);
        return -1;
    }
    *out = v;
    return 0;
}

/* Width and height, checked against the limits. */
static int read_size(struct reader *r, int comments, struct image *img)
{
    long w, h;
    if (read_int(r, comments, 1, IMGCMP_MAX_SIDE, "width", &w) != 0 ||
        read_int(r, comments, 1, IMGCMP_MAX_SIDE, "height", &h) != 0)
        return -1;
    if (w * h > IMGCMP_MAX_PIXELS) {
        error("'%s': %ldx%ld is too large", r->path, w, h);
        return -1;
    }
    img->width = (int)w;
    img->height = (int)h;
    return 0;
}

/* The single whitespace byte that ends a binary format's header. */
static int end_header(struct reader *r)
{
    if (r->p >= r->end || !is_space(*r->p)) {
        error("'%s': header not followed by whitespace", r->path);
        return -1;
    }
    r->p++;
    return 0;
}

static size_t channels(const struct image *img)
{
    return (size_t)img->width * img->height * 3;
}

static int alloc_levels(struct image *img, const char *path)
{
    img->level = malloc(channels(img));
    if (!img->level) {
        error("'%s': out of memory", path);
        return -1;
    }
    return 0;
}

/* Rescales v in [0, maxval] to [0, 255]. */
static unsigned char rescale(long v, long maxval)
{
    return (unsigned char)(maxval == 255 ? v : (v * 255 + maxval / 2) / maxval);
}

/* P6 after its magic: binary samples, 1 byte (maxval < 256) or 2
 * big-endian bytes each. */
static int parse_p6(struct reader *r, struct image *img)
{
    long maxval;
    if (read_size(r, 1, img) != 0 ||
        read_int(r, 1, 1, 65535, "maxval", &maxval) != 0 || end_header(r) != 0)
        return -1;
    size_t n = channels(img), bytes = maxval < 256 ? 1 : 2;
    if ((size_t)(r->end - r->p) < n * bytes) {
        error("'%s': truncated (%zu bytes of pixel data, want %zu)", r->path,
              (size_t)(r->end - r->p), n * bytes);
        return -1;
    }
    if (alloc_levels(img, r->path) != 0)
        return -1;
    for (size_t i = 0; i < n; i++) {
        long v = bytes == 1 ? r->p[i] : (long)r->p[2 * i] << 8 | r->p[2 * i + 1];
        if (v > maxval) {
            error("'%s': sample %ld above maxval %ld", r->path, v, maxval);
            return -1;
        }
        img->level[i] = rescale(v, maxval);
    }
    return 0;
}

/* P3 after its magic: decimal samples separated by whitespace. */
static int parse_p3(struct reader *r, struct image *img)
{
    long maxval;
    if (read_size(r, 1, img) != 0 ||
        read_int(r, 1, 1, 65535, "maxval", &maxval) != 0 ||
        alloc_levels(img, r->path) != 0)
        return -1;
    size_t n = channels(img);
    for (size_t i = 0; i < n; i++) {
        long v;
        if (read_int(r, 1, 0, maxval, "sample", &v) != 0)
            return -1;
        img->level[i] = rescale(v, maxval);
    }
    return 0;
}

/* A float in the byte order given (little: the PFM scale is negative). */
static float get_float(const unsigned char *p, int little)
{
    uint32_t u = little ? (uint32_t)p[0] | (uint32_t)p[1] << 8 |
                              (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24
                        : (uint32_t)p[3] | (uint32_t)p[2] << 8 |
                              (uint32_t)p[1] << 16 | (uint32_t)p[0] << 24;
    float f;
    memcpy(&f, &u, sizeof f);
    return f;
}

/* PF (color) or Pf (gray, copied to 3 channels) after its magic: size,
 * scale (sign: byte order), then rows bottom to top. */
static int parse_pfm(struct reader *r, struct image *img, int gray)
{
    if (read_size(r, 0, img) != 0)
        return -1;
    skip_space(r, 0);
    char token[64];
    size_t k = 0;
    while (r->p < r->end && !is_space(*r->p) && k < sizeof token - 1)
        token[k++] = (char)*r->p++;
    token[k] = '\0';
    char *rest;
    double scale = strtod(token, &rest);
    if (k == 0 || *rest != '\0' || !isfinite(scale) || scale == 0.0) {
        error("'%s': bad PFM scale '%s'", r->path, token);
        return -1;
    }
    if (end_header(r) != 0)
        return -1;
    size_t per_pixel = gray ? 1 : 3;
    size_t need = (size_t)img->width * img->height * per_pixel * 4;
    if ((size_t)(r->end - r->p) < need) {
        error("'%s': truncated (%zu bytes of pixel data, want %zu)", r->path,
              (size_t)(r->end - r->p), need);
        return -1;
    }
    if (alloc_levels(img, r->path) != 0)
        return -1;
    img->value = malloc(channels(img) * sizeof *img->value);
    if (!img->value) {
        error("'%s': out of memory", r->path);
        return -1;
    }
    for (int y = 0; y < img->height; y++) {
        const unsigned char *row =
            r->p + (size_t)(img->height - 1 - y) * img->width * per_pixel * 4;
        for (int x = 0; x < img->width; x++)
            for (int c = 0; c < 3; c++) {
                size_t src = (size_t)x * per_pixel + (gray ? 0 : (size_t)c);
                size_t dst = ((size_t)y * img->width + x) * 3 + c;
                img->value[dst] = get_float(row + 4 * src, scale < 0.0);
                img->level[dst] = quantize(img->value[dst]);
            }
    }
    return 0;
}

/* Reads path into img by its magic; 0, or -1 (reported, img freed). */
static int image_read(const char *path, struct image *img)
{
    memset(img, 0, sizeof *img);
    size_t len;
    unsigned char *buf = read_file(path, &len);
    if (!buf)
        return -1;
    struct reader r = {path, buf + 2, buf + len};
    int rc = -1;
    if (len < 2)
        error("'%s': not a PPM or PFM file", path);
    else if (buf[0] == 'P' && buf[1] == '6')
        rc = parse_p6(&r, img);
    else if (buf[0] == 'P' && buf[1] == '3')
        rc = parse_p3(&r, img);
    else if (buf[0] == 'P' && (buf[1] == 'F' || buf[1] == 'f'))
        rc = parse_pfm(&r, img, buf[1] == 'f');
    else
        error("'%s': not a PPM (P6, P3) or PFM file", path);
    free(buf);
    if (rc != 0) {
        free(img->level);
        free(img->value);
        memset(img, 0, sizeof *img);
    }
    return rc;
}

/* Writes |a - b| * IMGCMP_DIFF_GAIN, clamped, as a P6; 0 or -1 (reported). */
static int write_diff(const char *path, const struct image *a,
                      const struct image *b)
{
    FILE *f = fopen(path, "wb");
    if (!f) {
        error("cannot write '%s': %s", path, strerror(errno));
        return -1;
    }
    int ok = fprintf(f, "P6\n%d %d\n255\n", a->width, a->height) > 0;
    size_t n = channels(a);
    for (size_t i = 0; i < n && ok; i++) {
        int d = abs((int)a->level[i] - (int)b->level[i]) * IMGCMP_DIFF_GAIN;
        ok = fputc(d > 255 ? 255 : d, f) != EOF;
    }
    if (fclose(f) != 0)
        ok = 0;
    if (!ok) {
        error("cannot write '%s': %s", path, strerror(errno));
        remove(path);
        return -1;
    }
    return 0;
}

/* A number in [lo, hi], the whole string; 0 or -1. */
static int parse_number(const char *s, double lo, double hi, double *out)
{
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    if (end == s || *end != '\0' || errno != 0 || !(v >= lo && v <= hi))
        return -1;
    *out = v;
    return 0;
}

int main(int argc, char **argv)
{
    const char *diff = NULL, *files[2];
    int nfiles = 0;
    double min_within1 = -1.0, max_bad8 = -1.0;
    for (int i = 1; i < argc; i++) {
        const char *arg = argv[i];
        if (strcmp(arg, "--help") == 0) {
            usage(stdout);
            return 0;
        }
        int takes_value = strcmp(arg, "--diff") == 0 ||
                          strcmp(arg, "--min-within1") == 0 ||
                          strcmp(arg, "--max-bad8") == 0;
        if (takes_value && i + 1 >= argc) {
            error("%s needs a value", arg);
            return 2;
        }
        if (strcmp(arg, "--diff") == 0) {
            diff = argv[++i];
        } else if (strcmp(arg, "--min-within1") == 0) {
            if (parse_number(argv[++i], 0.0, 1.0, &min_within1) != 0) {
                error("--min-within1: '%s' is not a number in [0, 1]", argv[i]);
                return 2;
            }
        } else if (strcmp(arg, "--max-bad8") == 0) {
            if (parse_number(argv[++i], 0.0, 1e15, &max_bad8) != 0 ||
                max_bad8 != floor(max_bad8)) {
                error("--max-bad8: '%s' is not a non-negative integer", argv[i]);
                return 2;
            }
        } else if (arg[0] == '-' && arg[1] != '\0') {
            error("unknown option '%s'", arg);
            usage(stderr);
            return 2;
        } else if (nfiles < 2) {
            files[nfiles++] = arg;
        } else {
            error("too many files ('%s')", arg);
            usage(stderr);
            return 2;
        }
    }
    if (nfiles != 2) {
        error("need two images");
        usage(stderr);
        return 2;
    }

    struct image a, b;
    if (image_read(files[0], &a) != 0)
        return 2;
    if (image_read(files[1], &b) != 0) {
        free(a.level);
        free(a.value);
        return 2;
    }
    int status = 0;
    if (a.width != b.width || a.height != b.height) {
        error("sizes differ: '%s' is %dx%d, '%s' is %dx%d", files[0], a.width,
              a.height, files[1], b.width, b.height);
        status = 2;
        goto done;
    }

    size_t n = channels(&a), within1 = 0, bad8 = 0;
    double sum_abs = 0.0, sum_sq = 0.0;
    int max = 0, pixel_bad = 0;
    for (size_t i = 0; i < n; i++) {
        int d = abs((int)a.level[i] - (int)b.level[i]);
        sum_abs += d;
        sum_sq += (double)d * d;
        max = d > max ? d : max;
        within1 += d <= 1;
        pixel_bad |= d > IMGCMP_BAD_LEVELS;
        if (i % 3 == 2) {
            bad8 += pixel_bad;
            pixel_bad = 0;
        }
    }
    if (diff && write_diff(diff, &a, &b) != 0) {
        status = 2;
        goto done;
    }
    double mse = sum_sq / (double)n;
    double frac1 = (double)within1 / (double)n;
    if (mse == 0.0)
        printf("psnr=inf");
    else
        printf("psnr=%.4f", 10.0 * log10(255.0 * 255.0 / mse));
    printf(" mae=%.6f max=%d within1=%.6f bad8=%zu pixels=%zu",
           sum_abs / (double)n, max, frac1, bad8, n / 3);
    if (a.value && b.value) {
        /* Equal bits (NaN == NaN) count 0; NaN or inf against anything
         * else is an infinite difference. */
        double fmax = 0.0;
        for (size_t i = 0; i < n; i++) {
            float x = a.value[i], y = b.value[i];
            double d = memcmp(&x, &y, sizeof x) == 0 || x == y ? 0.0
                       : isfinite(x) && isfinite(y)            ? fabs((double)x - y)
                                                               : INFINITY;
            fmax = d > fmax ? d : fmax;
        }
        printf(" fmax=%.9g", fmax);
    }
    putchar('\n');
    if (fflush(stdout) != 0) {
        error("cannot write the result: %s", strerror(errno));
        status = 2;
        goto done;
    }

    if (min_within1 >= 0.0 && frac1 < min_within1) {
        error("within1 %.6f < %g", frac1, min_within1);
        status = 1;
    }
    if (max_bad8 >= 0.0 && (double)bad8 > max_bad8) {
        error("bad8 %zu > %.0f", bad8, max_bad8);
        status = 1;
    }
done:
    free(a.level);
    free(a.value);
    free(b.level);
    free(b.value);
    return status;
}
