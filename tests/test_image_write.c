/* test_image_write.c: unit tests of image_write.h.
 *
 * An asymmetric 5x3 image (every channel of every pixel a different level,
 * width != height, like stb's "F") is written as PPM, PFM and PNG into a
 * fresh temporary folder and read back (PPM and PFM by hand, PNG through
 * libpng) to catch flips, transposes and channel swaps, whole and streamed
 * in bands of rows through the image_writer API. Also checked:
 * quantisation at its boundaries, failure paths (nothing left behind),
 * atomic replacement, file modes kept, long names, outputs refused before
 * anything is written, and image_format_of. Prints "N passed, M failed"
 * last; exits 0 only when nothing failed. */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <png.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "image_write.h"

#include "unit.h"

/* The test image: W x H, level(x, y, c) distinct for every pixel and
 * channel, none equal to its mirror or transpose. */
#define W 5
#define H 3

static int level(int x, int y, int c)
{
    return 10 + 15 * (y * W + x) + 5 * c; /* 10 .. 230 */
}

/* W x H rgba floats of the test image; alpha is junk that must be ignored. */
static void make_image(float *rgba)
{
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            float *p = rgba + (y * W + x) * 4;
            for (int c = 0; c < 3; c++)
                p[c] = (float)level(x, y, c) / 255.0f;
            p[3] = 0.25f;
        }
}

/* Contents of path (NUL-terminated past *len), or NULL. */
static unsigned char *read_all(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    size_t cap = 4096, n = 0;
    unsigned char *buf = malloc(cap + 1);
    size_t got;
    while (buf && (got = fread(buf + n, 1, cap - n, f)) > 0) {
        n += got;
        if (n == cap) {
            unsigned char *grown = realloc(buf, 2 * cap + 1);
            if (!grown) {
                free(buf);
                buf = NULL;
                break;
            }
            buf = grown;
            cap *= 2;
        }
    }
    fclose(f);
    if (buf)
        buf[n] = '\0';
    *len = n;
    return buf;
}

/* Parses the three header lines tp2 writes, "MAGIC\nW H\nVALUE\n" (PPM:
 * P6 and maxval; PFM: PF and scale). The data may begin with bytes that
 * look like whitespace (the test image's first level is 10, '\n'), so the
 * header ends exactly at its third newline. Returns the offset of the data,
 * or 0 when the header is not that. */
static size_t parse_header(const unsigned char *buf, size_t len,
                           const char *magic, int *w, int *h, char *value,
                           size_t value_size)
{
    char head[64];
    size_t n = 0;
    int lines = 0;
    for (; n < len && n < sizeof head - 1 && lines < 3; n++) {
        head[n] = (char)buf[n];
        lines += head[n] == '\n';
    }
    head[n] = '\0';
    char m[4], v[32];
    if (lines != 3 || sscanf(head, "%3s %d %d %31s", m, w, h, v) != 4 ||
        strcmp(m, magic) != 0)
        return 0;
    snprintf(value, value_size, "%s", v);
    return n;
}

/* Level of channel c at (x, y) in 8-bit RGB rows, top to bottom. */
static int rgb_at(const unsigned char *rgb, int x, int y, int c)
{
    return rgb[(y * W + x) * 3 + c];
}

/* Every channel of every pixel as written; one check for the whole image,
 * the first mismatch printed. */
static void check_levels(const unsigned char *rgb, const char *what, int line)
{
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            for (int c = 0; c < 3; c++)
                if (rgb_at(rgb, x, y, c) != level(x, y, c)) {
                    printf("  %s: (%d,%d) channel %d is %d, want %d\n", what, x,
                           y, c, rgb_at(rgb, x, y, c), level(x, y, c));
                    expect(0, "line %d: %s", line, what);
                    return;
                }
    expect(1, "line %d: %s", line, what);
}

/* The little-endian float at p, independent of the host's byte order. */
static float le_float(const unsigned char *p)
{
    uint32_t u = (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 |
                 (uint32_t)p[3] << 24;
    float f;
    memcpy(&f, &u, sizeof f);
    return f;
}

/* Same bits (so NaN == NaN, -0 != 0). */
static int same_float(float a, float b)
{
    return memcmp(&a, &b, sizeof a) == 0;
}

/* Reads a PPM written by tp2 into rgb (w * h * 3 bytes, malloc'd). */
static unsigned char *read_ppm(const char *path, int *w, int *h)
{
    size_t len;
    unsigned char *buf = read_all(path, &len);
    if (!buf)
        return NULL;
    char maxval[32];
    size_t at = parse_header(buf, len, "P6", w, h, maxval, sizeof maxval);
    unsigned char *rgb = NULL;
    if (at && strcmp(maxval, "255") == 0 && *w > 0 && *h > 0 &&
        len - at == (size_t)*w * *h * 3) {
        rgb = malloc(len - at);
        if (rgb)
            memcpy(rgb, buf + at, len - at);
    }
    free(buf);
    return rgb;
}

/* Reads a PFM written by tp2 into rgb floats, rows top to bottom; the
 * scale line must be "-1.0" (little-endian). */
static float *read_pfm(const char *path, int *w, int *h)
{
    size_t len;
    unsigned char *buf = read_all(path, &len);
    if (!buf)
        return NULL;
    char scale[32];
    size_t at = parse_header(buf, len, "PF", w, h, scale, sizeof scale);
    float *rgb = NULL;
    if (at && strcmp(scale, "-1.0") == 0 && *w > 0 && *h > 0 &&
        len - at == (size_t)*w * *h * 12) {
        rgb = malloc((size_t)*w * *h * 3 * sizeof *rgb);
        for (int y = 0; rgb && y < *h; y++) {
            /* File row 0 is the bottom row. */
            const unsigned char *row = buf + at + (size_t)(*h - 1 - y) * *w * 12;
            for (int i = 0; i < *w * 3; i++)
                rgb[(size_t)y * *w * 3 + i] = le_float(row + 4 * i);
        }
    }
    free(buf);
    return rgb;
}

/* Reads an 8-bit RGB, non-interlaced PNG into rgb (malloc'd). */
static unsigned char *read_png(const char *path, int *w, int *h)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    unsigned char *volatile rgb = NULL;
    png_bytep *volatile rows = NULL;
    if (!info || setjmp(png_jmpbuf(png))) {
        png_destroy_read_struct(&png, &info, NULL);
        free(rows);
        free(rgb);
        fclose(f);
        return NULL;
    }
    png_init_io(png, f);
    png_read_info(png, info);
    png_uint_32 pw, ph;
    int depth, color, interlace;
    png_get_IHDR(png, info, &pw, &ph, &depth, &color, &interlace, NULL, NULL);
    if (depth != 8 || color != PNG_COLOR_TYPE_RGB ||
        interlace != PNG_INTERLACE_NONE || pw == 0 || ph == 0 || pw > 1000 ||
        ph > 1000)
        png_error(png, "not 8-bit RGB");
    rgb = malloc((size_t)pw * ph * 3);
    rows = malloc(ph * sizeof *rows);
    if (!rgb || !rows)
        png_error(png, "out of memory");
    for (png_uint_32 y = 0; y < ph; y++)
        rows[y] = rgb + (size_t)y * pw * 3;
    png_read_image(png, rows);
    png_read_end(png, NULL);
    png_destroy_read_struct(&png, &info, NULL);
    free(rows);
    fclose(f);
    *w = (int)pw;
    *h = (int)ph;
    return rgb;
}

static char dir[64]; /* the temporary folder of this run */

static void path_in(char *out, size_t size, const char *name)
{
    if (snprintf(out, size, "%s/%.*s", dir, 128, name) >= (int)size)
        out[0] = '\0'; /* cannot happen: dir is short, names are cut */
}

/* The writer's temporary files: ".tp2-XXXXXX" beside the output. */
static int is_temp(const char *name)
{
    return strncmp(name, ".tp2-", 5) == 0;
}

static int is_entry(const char *name)
{
    return strcmp(name, ".") != 0 && strcmp(name, "..") != 0;
}

/* Number of entries in dir whose name passes keep, or -1. */
static int count_names(int (*keep)(const char *name))
{
    DIR *d = opendir(dir);
    if (!d)
        return -1;
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d)))
        n += keep(e->d_name) != 0;
    closedir(d);
    return n;
}

/* Removes dir and the plain files and empty folders in it. */
static void remove_dir(void)
{
    DIR *d = opendir(dir);
    if (!d)
        return;
    struct dirent *e;
    char p[256];
    while ((e = readdir(d))) {
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0)
            continue;
        path_in(p, sizeof p, e->d_name);
        if (unlink(p) != 0)
            rmdir(p);
    }
    closedir(d);
    rmdir(dir);
}

/* stderr redirected to a file while a failure is provoked, so its message
 * can be checked (and does not clutter the log). */
static int saved_stderr = -1;
static char err_path[128];

static void capture_begin(void)
{
    fflush(stderr);
    snprintf(err_path, sizeof err_path, "%s-stderr", dir);
    int fd = open(err_path, O_WRONLY | O_CREAT | O_TRUNC, 0600);
    saved_stderr = dup(2);
    if (fd >= 0) {
        dup2(fd, 2);
        close(fd);
    }
}

/* Restores stderr; returns what was written (malloc'd, maybe ""). */
static char *capture_end(void)
{
    fflush(stderr);
    if (saved_stderr >= 0) {
        dup2(saved_stderr, 2);
        close(saved_stderr);
        saved_stderr = -1;
    }
    size_t len;
    char *text = (char *)read_all(err_path, &len);
    unlink(err_path);
    return text ? text : calloc(1, 1);
}

static int starts_with(const char *s, const char *prefix)
{
    return strncmp(s, prefix, strlen(prefix)) == 0;
}

static void test_format_of(void)
{
    CHECK(image_format_of("out.ppm") == IMAGE_PPM);
    CHECK(image_format_of("OUT.PPM") == IMAGE_PPM);
    CHECK(image_format_of("out.png") == IMAGE_PNG);
    CHECK(image_format_of("a/b.Png") == IMAGE_PNG);
    CHECK(image_format_of("out.pfm") == IMAGE_PFM);
    CHECK(image_format_of("x.tar.pfm") == IMAGE_PFM);
    CHECK(image_format_of("file") == IMAGE_UNKNOWN);
    CHECK(image_format_of("dir.with.dot/file") == IMAGE_UNKNOWN);
    CHECK(image_format_of("dir.ppm/file") == IMAGE_UNKNOWN);
    CHECK(image_format_of("out.jpg") == IMAGE_UNKNOWN);
    CHECK(image_format_of("out.ppm.txt") == IMAGE_UNKNOWN);
    CHECK(image_format_of("out.ppmx") == IMAGE_UNKNOWN);
    CHECK(image_format_of("out.") == IMAGE_UNKNOWN);
    CHECK(image_format_of("") == IMAGE_UNKNOWN);
}

/* Floats on either side of the exact boundary b / 255 (b a half level):
 * *lo the largest float below it, *hi the smallest at or above it. */
static void straddle(double b, float *lo, float *hi)
{
    float f = (float)(b / 255.0);
    if ((double)f * 255.0 >= b) {
        *hi = f;
        *lo = nextafterf(f, 0.0f);
    } else {
        *lo = f;
        *hi = nextafterf(f, 1.0f);
    }
}

/* Values and their expected levels, used directly and through files. */
#define NQ 14
static float q_in[NQ];
static unsigned char q_want[NQ];

static void make_quantize_cases(void)
{
    float lo, hi;
    int k = 0;
    q_in[k] = -0.5f, q_want[k++] = 0;
    q_in[k] = 0.0f, q_want[k++] = 0;
    q_in[k] = -0.0f, q_want[k++] = 0;
    straddle(0.5, &lo, &hi);
    q_in[k] = lo, q_want[k++] = 0;
    q_in[k] = hi, q_want[k++] = 1;
    q_in[k] = 127.5f / 255.0f, q_want[k++] = 128; /* exactly 0.5: ties up */
    straddle(200.5, &lo, &hi);
    q_in[k] = lo, q_want[k++] = 200;
    q_in[k] = hi, q_want[k++] = 201;
    straddle(254.5, &lo, &hi);
    q_in[k] = lo, q_want[k++] = 254;
    q_in[k] = hi, q_want[k++] = 255;
    q_in[k] = 1.0f, q_want[k++] = 255;
    q_in[k] = 2.0f, q_want[k++] = 255;
    q_in[k] = NAN, q_want[k++] = 0;
    q_in[k] = INFINITY, q_want[k++] = 255;
}

static void test_quantize(void)
{
    make_quantize_cases();
    for (int k = 0; k < NQ; k++) {
        unsigned char got = image_quantize(q_in[k]);
        if (got != q_want[k])
            printf("  image_quantize(%.9g) = %d, want %d\n", q_in[k], got,
                   q_want[k]);
        CHECK(got == q_want[k]);
    }
    CHECK(image_quantize(-INFINITY) == 0);
    CHECK(image_quantize((float)(37.0 / 255.0)) == 37);
}

/* The quantisation cases as a 5x3 image row by row (the last slot pads
 * with 0), through PPM and PNG; PFM keeps the raw floats. */
static void test_quantize_files(void)
{
    float rgba[W * H * 4];
    for (int i = 0; i < W * H; i++) {
        for (int c = 0; c < 3; c++) {
            int k = (i + c * 5) % (NQ + 1); /* each value in every channel */
            rgba[i * 4 + c] = k < NQ ? q_in[k] : 0.0f;
        }
        rgba[i * 4 + 3] = 1.0f;
    }
    const char *names[] = {"q.ppm", "q.png"};
    for (int n = 0; n < 2; n++) {
        char p[256];
        path_in(p, sizeof p, names[n]);
        CHECK(image_write(p, image_format_of(p), W, H, rgba) == 0);
        int w = 0, h = 0;
        unsigned char *rgb = n == 0 ? read_ppm(p, &w, &h) : read_png(p, &w, &h);
        CHECK(rgb && w == W && h == H);
        int ok = rgb != NULL;
        for (int i = 0; ok && i < W * H * 3; i++) {
            int k = (i / 3 + (i % 3) * 5) % (NQ + 1);
            int want = k < NQ ? q_want[k] : 0;
            if (rgb[i] != want) {
                printf("  %s: value %d is %d, want %d\n", names[n], i, rgb[i], want);
                ok = 0;
            }
        }
        expect(ok, "line %d: %s", __LINE__, names[n]);
        free(rgb);
    }
    char p[256];
    path_in(p, sizeof p, "q.pfm");
    CHECK(image_write(p, IMAGE_PFM, W, H, rgba) == 0);
    int w = 0, h = 0;
    float *f = read_pfm(p, &w, &h);
    CHECK(f && w == W && h == H);
    int ok = f != NULL;
    for (int i = 0; ok && i < W * H * 3; i++)
        ok = same_float(f[i], rgba[(i / 3) * 4 + i % 3]);
    expect(ok, "line %d: %s", __LINE__, "q.pfm: raw floats, unclamped, NaN kept");
    free(f);
}

static void test_formats(const float *rgba)
{
    char p[256];
    int w = 0, h = 0;

    path_in(p, sizeof p, "f.ppm");
    CHECK(image_write(p, IMAGE_PPM, W, H, rgba) == 0);
    size_t len;
    unsigned char *raw = read_all(p, &len);
    CHECK(raw && len == 11 + W * H * 3 && memcmp(raw, "P6\n5 3\n255\n", 11) == 0);
    free(raw);
    unsigned char *rgb = read_ppm(p, &w, &h);
    CHECK(rgb && w == W && h == H);
    if (rgb)
        check_levels(rgb, "f.ppm levels", __LINE__);
    free(rgb);

    path_in(p, sizeof p, "f.png");
    CHECK(image_write(p, IMAGE_PNG, W, H, rgba) == 0);
    rgb = read_png(p, &w, &h);
    CHECK(rgb && w == W && h == H);
    if (rgb)
        check_levels(rgb, "f.png levels", __LINE__);
    free(rgb);

    path_in(p, sizeof p, "f.pfm");
    CHECK(image_write(p, IMAGE_PFM, W, H, rgba) == 0);
    raw = read_all(p, &len);
    CHECK(raw && len == 12 + W * H * 12 && memcmp(raw, "PF\n5 3\n-1.0\n", 12) == 0);
    /* First stored float: red of the bottom-left pixel, little-endian. */
    CHECK(raw && len >= 16 && same_float(le_float(raw + 12), rgba[(H - 1) * W * 4]));
    free(raw);
    float *f = read_pfm(p, &w, &h);
    CHECK(f && w == W && h == H);
    int ok = f != NULL;
    for (int i = 0; ok && i < W * H * 3; i++)
        ok = same_float(f[i], rgba[(i / 3) * 4 + i % 3]);
    expect(ok, "line %d: %s", __LINE__, "f.pfm floats, rows bottom to top");
    free(f);

    /* A new file gets the mode open(2) would give it, not mkstemp's 0600. */
    mode_t mask = umask(0);
    umask(mask);
    struct stat st;
    CHECK(stat(p, &st) == 0 && (st.st_mode & 0777) == (0666 & ~mask));
}

/* Writing over an existing file replaces it by rename: a hard link to the
 * old file keeps the old content, the path gets the new one. */
static void test_replace(const float *rgba)
{
    char p[256], old[256];
    path_in(p, sizeof p, "r.ppm");
    path_in(old, sizeof old, "r-old.ppm");
    float dark[W * H * 4] = {0};
    CHECK(image_write(p, IMAGE_PPM, W, H, dark) == 0);
    CHECK(link(p, old) == 0);
    CHECK(image_write(p, IMAGE_PPM, W, H, rgba) == 0);
    int w = 0, h = 0;
    unsigned char *rgb = read_ppm(p, &w, &h);
    CHECK(rgb && w == W && h == H);
    if (rgb)
        check_levels(rgb, "replaced r.ppm has the new image", __LINE__);
    free(rgb);
    rgb = read_ppm(old, &w, &h);
    int zero = rgb != NULL;
    for (int i = 0; zero && i < W * H * 3; i++)
        zero = rgb[i] == 0;
    expect(zero, "line %d: %s", __LINE__, "old inode untouched (replaced by rename)");
    free(rgb);
    struct stat a, b;
    CHECK(stat(p, &a) == 0 && stat(old, &b) == 0 && a.st_ino != b.st_ino);
    unlink(old);
}

/* Failures return -1, print "tp2: cannot write 'PATH'...", and leave no
 * file and no temporary behind; an existing target is kept. */
static void test_failures(const float *rgba)
{
    char p[256], msg[300];
    int before = count_names(is_entry);

    path_in(p, sizeof p, "missing/out.ppm");
    capture_begin();
    int rc = image_write(p, IMAGE_PPM, W, H, rgba);
    char *err = capture_end();
    CHECK(rc == -1);
    snprintf(msg, sizeof msg, "tp2: cannot write '%s': ", p);
    CHECK(starts_with(err, msg));
    free(err);
    path_in(p, sizeof p, "missing");
    CHECK(access(p, F_OK) != 0);
    CHECK(count_names(is_entry) == before);

    /* Unknown format: refused before any file exists. */
    path_in(p, sizeof p, "u.xyz");
    capture_begin();
    rc = image_write(p, IMAGE_UNKNOWN, W, H, rgba);
    err = capture_end();
    CHECK(rc == -1);
    CHECK(starts_with(err, "tp2: cannot write '"));
    free(err);
    CHECK(access(p, F_OK) != 0);
    CHECK(count_names(is_temp) == 0);
    CHECK(count_names(is_entry) == before);

    /* Failing over an existing file leaves it as it was. */
    path_in(p, sizeof p, "keep.ppm");
    CHECK(image_write(p, IMAGE_PPM, W, H, rgba) == 0);
    capture_begin();
    rc = image_write(p, IMAGE_UNKNOWN, W, H, rgba);
    free(capture_end());
    CHECK(rc == -1);
    int w = 0, h = 0;
    unsigned char *rgb = read_ppm(p, &w, &h);
    CHECK(rgb && w == W && h == H);
    if (rgb)
        check_levels(rgb, "keep.ppm survives a failed write", __LINE__);
    free(rgb);
    unlink(p);

    /* The target is a folder: the rename fails, the temporary is removed. */
    path_in(p, sizeof p, "adir.ppm");
    CHECK(mkdir(p, 0700) == 0);
    capture_begin();
    rc = image_write(p, IMAGE_PPM, W, H, rgba);
    err = capture_end();
    CHECK(rc == -1);
    CHECK(starts_with(err, "tp2: cannot write '"));
    free(err);
    struct stat st;
    CHECK(stat(p, &st) == 0 && S_ISDIR(st.st_mode));
    CHECK(count_names(is_temp) == 0);
    rmdir(p);
    CHECK(count_names(is_entry) == before);
}


/* Streams the test image in bands of the given heights (summing to H). */
static int write_in_bands(const char *p, enum image_format format, const float *rgba,
                          const int *bands, int nbands)
{
    struct image_writer *w = image_writer_open(p, format, W, H);
    if (!w)
        return -1;
    int y = 0;
    for (int b = 0; b < nbands; b++) {
        if (image_writer_rows(w, rgba + (size_t)y * W * 4, bands[b]) != 0) {
            image_writer_abort(w);
            return -1;
        }
        y += bands[b];
    }
    return image_writer_finish(w);
}

/* Same bytes in both files. */
static int same_file(const char *a, const char *b)
{
    size_t na, nb;
    unsigned char *da = read_all(a, &na), *db = read_all(b, &nb);
    int same = da && db && na == nb && memcmp(da, db, na) == 0;
    free(da);
    free(db);
    return same;
}

/* Rows arriving in bands (2 + 1 and 1 + 1 + 1 rows) give the same file as
 * the whole image at once, in every format; the levels are checked again
 * through the readers, so a band written at the wrong place (PFM stores
 * rows bottom to top) cannot hide. */
static void test_streaming(const float *rgba)
{
    static const char *ext[] = {"ppm", "png", "pfm"};
    static const enum image_format fmt[] = {IMAGE_PPM, IMAGE_PNG, IMAGE_PFM};
    static const int split_a[] = {2, 1}, split_b[] = {1, 1, 1};
    for (int f = 0; f < 3; f++) {
        char whole[256], a[256], b[256], name[32];
        snprintf(name, sizeof name, "whole.%s", ext[f]);
        path_in(whole, sizeof whole, name);
        snprintf(name, sizeof name, "bands-a.%s", ext[f]);
        path_in(a, sizeof a, name);
        snprintf(name, sizeof name, "bands-b.%s", ext[f]);
        path_in(b, sizeof b, name);
        CHECK(image_write(whole, fmt[f], W, H, rgba) == 0);
        CHECK(write_in_bands(a, fmt[f], rgba, split_a, 2) == 0);
        CHECK(write_in_bands(b, fmt[f], rgba, split_b, 3) == 0);
        expect(same_file(whole, a), "line %d: %s in bands of 2 + 1 rows", __LINE__, ext[f]);
        expect(same_file(whole, b), "line %d: %s in bands of 1 row", __LINE__, ext[f]);
        int w = 0, h = 0;
        unsigned char *rgb = f == 0 ? read_ppm(a, &w, &h) : f == 1 ? read_png(a, &w, &h) : NULL;
        if (f == 2) {
            float *fl = read_pfm(a, &w, &h);
            rgb = fl ? malloc(W * H * 3) : NULL;
            for (int i = 0; rgb && i < W * H * 3; i++)
                rgb[i] = image_quantize(fl[i]);
            free(fl);
        }
        CHECK(rgb && w == W && h == H);
        if (rgb)
            check_levels(rgb, ext[f], __LINE__);
        free(rgb);
        unlink(whole);
        unlink(a);
        unlink(b);
    }
}

/* Rows given as 8-bit words (the renderer's, quantized on the device)
 * make the very file the float rows make, in PPM and PNG, streamed in
 * bands; a PFM writer refuses them with a message and leaves nothing. */
static void test_rgba8_rows(const float *rgba)
{
    static const char *ext[] = {"ppm", "png"};
    static const enum image_format fmt[] = {IMAGE_PPM, IMAGE_PNG};
    uint32_t words[W * H];
    for (int i = 0; i < W * H; i++) /* alpha byte set: it must be ignored */
        words[i] = image_quantize(rgba[4 * i]) | image_quantize(rgba[4 * i + 1]) << 8 |
                   (uint32_t)image_quantize(rgba[4 * i + 2]) << 16 | 0xab000000u;
    for (int f = 0; f < 2; f++) {
        char want[256], got[256], name[32];
        snprintf(name, sizeof name, "floats.%s", ext[f]);
        path_in(want, sizeof want, name);
        snprintf(name, sizeof name, "words.%s", ext[f]);
        path_in(got, sizeof got, name);
        CHECK(image_write(want, fmt[f], W, H, rgba) == 0);
        struct image_writer *w = image_writer_open(got, fmt[f], W, H);
        CHECK(w && image_writer_rows_rgba8(w, words, 2) == 0 &&
              image_writer_rows_rgba8(w, words + 2 * W, H - 2) == 0 &&
              image_writer_finish(w) == 0);
        expect(same_file(want, got), "line %d: %s from 8-bit rows", __LINE__, ext[f]);
        unlink(want);
        unlink(got);
    }
    int before = count_names(is_entry);
    char p[256];
    path_in(p, sizeof p, "words.pfm");
    struct image_writer *w = image_writer_open(p, IMAGE_PFM, W, H);
    capture_begin();
    int rc = w ? image_writer_rows_rgba8(w, words, H) : 0;
    char *err = capture_end();
    CHECK(rc == -1 && strstr(err, "8-bit rows for a PFM file") != NULL);
    free(err);
    image_writer_abort(w);
    CHECK(count_names(is_entry) == before && access(p, F_OK) != 0);
}

/* A writer given too few or too many rows fails and leaves nothing; one
 * aborted leaves an existing output as it was. */
static void test_streaming_failures(const float *rgba)
{
    char p[256];
    int before = count_names(is_entry);
    path_in(p, sizeof p, "short.png");
    struct image_writer *w = image_writer_open(p, IMAGE_PNG, W, H);
    CHECK(w != NULL);
    CHECK(count_names(is_temp) == 1); /* created before any row */
    CHECK(w && image_writer_rows(w, rgba, H - 1) == 0);
    capture_begin();
    int rc = w ? image_writer_finish(w) : -1;
    char *err = capture_end();
    CHECK(rc == -1 && starts_with(err, "tp2: cannot write '"));
    free(err);
    CHECK(count_names(is_entry) == before);

    path_in(p, sizeof p, "long.pfm");
    w = image_writer_open(p, IMAGE_PFM, W, H);
    capture_begin();
    rc = w ? image_writer_rows(w, rgba, H + 1) : 0;
    free(capture_end());
    CHECK(rc == -1);
    image_writer_abort(w);
    CHECK(count_names(is_entry) == before);

    path_in(p, sizeof p, "kept.ppm");
    CHECK(image_write(p, IMAGE_PPM, W, H, rgba) == 0);
    w = image_writer_open(p, IMAGE_PPM, W, H);
    CHECK(w && image_writer_rows(w, rgba, 1) == 0);
    image_writer_abort(w);
    int ww = 0, hh = 0;
    unsigned char *rgb = read_ppm(p, &ww, &hh);
    CHECK(rgb && ww == W && hh == H);
    if (rgb)
        check_levels(rgb, "kept.ppm survives an aborted writer", __LINE__);
    free(rgb);
    unlink(p);
    CHECK(count_names(is_entry) == before);
}

/* Replacing an output keeps its permission bits (0600 stays 0600); a new
 * output gets 0666 & ~umask whatever the umask. */
static void test_modes(const float *rgba)
{
    static const mode_t modes[] = {0600, 0640, 0444, 0755};
    char p[256];
    path_in(p, sizeof p, "m.png");
    for (int i = 0; i < 4; i++) {
        CHECK(image_write(p, IMAGE_PNG, W, H, rgba) == 0);
        CHECK(chmod(p, modes[i]) == 0);
        CHECK(image_write(p, IMAGE_PNG, W, H, rgba) == 0);
        struct stat st;
        CHECK(stat(p, &st) == 0);
        expect((st.st_mode & 0777) == modes[i], "line %d: mode %o kept, got %o", __LINE__,
               (unsigned)modes[i], (unsigned)(st.st_mode & 0777));
        unlink(p);
    }
    mode_t saved = umask(027);
    CHECK(image_write(p, IMAGE_PNG, W, H, rgba) == 0);
    umask(saved);
    struct stat st;
    CHECK(stat(p, &st) == 0 && (st.st_mode & 0777) == 0640);
    unlink(p);
}

/* Names of 245 to 255 bytes (NAME_MAX) work: the temporary name is short
 * and its own. */
static void test_long_names(const float *rgba)
{
    int before = count_names(is_entry);
    for (int len = 245; len <= 255; len += 5) {
        char name[256], p[512];
        memset(name, 'n', (size_t)len - 4);
        memcpy(name + len - 4, ".ppm", 5);
        snprintf(p, sizeof p, "%s/%s", dir, name);
        expect(image_write(p, IMAGE_PPM, W, H, rgba) == 0, "line %d: a %d-byte name",
               __LINE__, len);
        expect(access(p, F_OK) == 0, "line %d: a %d-byte name exists", __LINE__, len);
        unlink(p);
    }
    CHECK(count_names(is_entry) == before);
}

/* Outputs that cannot be written are refused by image_writer_open, before
 * a render would start: a missing folder, a folder as the output, a
 * non-regular file; nothing is created, the message names the reason. */
static void test_refused_early(void)
{
    int before = count_names(is_entry);
    char p[256], msg[400];
    path_in(p, sizeof p, "nowhere/out.png");
    capture_begin();
    struct image_writer *w = image_writer_open(p, IMAGE_PNG, W, H);
    char *err = capture_end();
    snprintf(msg, sizeof msg, "tp2: cannot write '%s': %s\n", p, strerror(ENOENT));
    CHECK(w == NULL && strcmp(err, msg) == 0);
    free(err);

    path_in(p, sizeof p, "folder.ppm");
    CHECK(mkdir(p, 0700) == 0);
    capture_begin();
    w = image_writer_open(p, IMAGE_PPM, W, H);
    err = capture_end();
    snprintf(msg, sizeof msg, "tp2: cannot write '%s': %s\n", p, strerror(EISDIR));
    CHECK(w == NULL && strcmp(err, msg) == 0);
    free(err);
    rmdir(p);

    capture_begin();
    w = image_writer_open("/dev/null", IMAGE_PPM, W, H);
    err = capture_end();
    CHECK(w == NULL && strcmp(err, "tp2: cannot write '/dev/null': not a regular file\n") == 0);
    free(err);
    image_writer_abort(w);
    CHECK(count_names(is_entry) == before);
}

/* Bytes outside printable ASCII in a name are shown as \xNN, never raw. */
static void test_escaped_name(void)
{
    char p[256];
    path_in(p, sizeof p, "no\x1b[31mdir\n/out.ppm");
    capture_begin();
    struct image_writer *w = image_writer_open(p, IMAGE_PPM, W, H);
    char *err = capture_end();
    CHECK(w == NULL);
    CHECK(strstr(err, "no\\x1b[31mdir\\x0a/out.ppm': ") != NULL);
    CHECK(strchr(err, '\x1b') == NULL && strchr(err, '\n') == err + strlen(err) - 1);
    free(err);
}

int main(void)
{
    const char *tmp = getenv("TMPDIR");
    snprintf(dir, sizeof dir, "%s/tp2-test-iw-XXXXXX",
             tmp && *tmp && strlen(tmp) < 40 ? tmp : "/tmp");
    if (!mkdtemp(dir)) {
        printf("FAIL: mkdtemp %s: %s\n0 passed, 1 failed\n", dir, strerror(errno));
        return 1;
    }
    float rgba[W * H * 4];
    make_image(rgba);

    test_format_of();
    test_quantize();
    test_formats(rgba);
    test_quantize_files();
    CHECK(count_names(is_temp) == 0);
    test_replace(rgba);
    test_failures(rgba);
    test_streaming(rgba);
    test_rgba8_rows(rgba);
    test_streaming_failures(rgba);
    test_modes(rgba);
    test_long_names(rgba);
    test_refused_early();
    test_escaped_name();
    CHECK(count_names(is_temp) == 0);

    remove_dir();
    return unit_report();
}
