#define _POSIX_C_SOURCE 200809L
#define _FILE_OFFSET_BITS 64 /* PFM offsets beyond 2 GiB on 32-bit hosts */
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

#include "lexer.h"
#include "tempfile.h"

/* The temporary file's name in the output's folder: short, so that an
 * output name of up to NAME_MAX bytes still leaves room for it. */
#define TEMP_NAME ".tp2-XXXXXX"

struct image_writer {
    char *path, *tmp; /* the output, and the temporary file beside it */
    enum image_format format;
    int width, height, next_row;
    int fd;          /* the temporary file; PFM rows are written through it */
    FILE *f;         /* PPM and PNG: a stdio stream on fd */
    png_structp png;
    png_infop info;
    int error;       /* errno of a failed write, 0 when unknown */
    mode_t new_mode; /* 0666 & ~umask: the mode of a new output */
    unsigned char *row; /* one row as the file stores it */
    size_t header;   /* PFM: bytes before the first stored row */
};

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

/* "tp2: cannot write 'PATH': REASON", the name escaped; returns -1. */
static int report(const char *path, const char *reason)
{
    char *shown = lexer_escape(path);
    fprintf(stderr, "tp2: cannot write '%s': %s\n", shown ? shown : "?", reason);
    free(shown);
    return -1;
}

static int report_errno(const char *path, int error)
{
    return report(path, error ? strerror(error) : "write failed");
}

/* path's folder plus TEMP_NAME, in a new string. */
static char *temp_path(const char *path)
{
    const char *slash = strrchr(path, '/');
    size_t dir = slash ? (size_t)(slash - path) + 1 : 0;
    char *tmp = malloc(dir + sizeof TEMP_NAME);
    if (tmp) {
        memcpy(tmp, path, dir);
        memcpy(tmp + dir, TEMP_NAME, sizeof TEMP_NAME);
    }
    return tmp;
}

/* An existing output must be a file that rename can replace. */
static int check_target(const char *path)
{
    struct stat st;
    if (stat(path, &st) != 0 || S_ISREG(st.st_mode))
        return 0; /* missing (or unreadable: creating the temporary says why) */
    return report(path, S_ISDIR(st.st_mode) ? strerror(EISDIR) : "not a regular file");
}

/* libpng reports errors by longjmp; keep errno for the message. */
static void png_on_error(png_structp png, png_const_charp msg)
{
    struct image_writer *w = png_get_error_ptr(png);
    (void)msg;
    w->error = errno;
    png_longjmp(png, 1);
}

static void png_on_warning(png_structp png, png_const_charp msg)
{
    (void)png;
    (void)msg;
}

static int png_begin(struct image_writer *w)
{
    w->png = png_create_write_struct(PNG_LIBPNG_VER_STRING, w, png_on_error,
                                     png_on_warning);
    w->info = w->png ? png_create_info_struct(w->png) : NULL;
    if (!w->info || setjmp(png_jmpbuf(w->png)))
        return -1;
    png_init_io(w->png, w->f);
    png_set_IHDR(w->png, w->info, (png_uint_32)w->width, (png_uint_32)w->height, 8,
                 PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    /* The Sub filter alone and zlib level 3, not libpng's all filters at
     * level 6: 3-4x less CPU per image (which a GPU renders in a fraction
     * of that), files 8-40% larger (bench/png_levels.c, docs/decisions.md). */
    png_set_filter(w->png, 0, PNG_FILTER_SUB);
    png_set_compression_level(w->png, 3);
    png_write_info(w->png, w->info);
    return 0;
}

/* write(2) at an offset until all n bytes are written. */
static int pwrite_all(int fd, const void *data, size_t n, off_t at)
{
    const char *p = data;
    while (n > 0) {
        ssize_t k = pwrite(fd, p, n, at);
        if (k < 0 && errno == EINTR)
            continue;
        if (k <= 0)
            return -1;
        p += k;
        n -= (size_t)k;
        at += k;
    }
    return 0;
}

/* The header, and a row buffer in the file's encoding. */
static int begin(struct image_writer *w)
{
    size_t row_bytes = (size_t)w->width * (w->format == IMAGE_PFM ? 12 : 3);
    if (!(w->row = malloc(row_bytes)))
        return -1;
    if (w->format == IMAGE_PFM) {
        char head[64];
        int n = snprintf(head, sizeof head, "PF\n%d %d\n-1.0\n", w->width, w->height);
        w->header = (size_t)n;
        return pwrite_all(w->fd, head, (size_t)n, 0);
    }
    if (!(w->f = fdopen(w->fd, "wb")))
        return -1;
    w->fd = -1; /* the stream owns it now */
    if (w->format == IMAGE_PNG)
        return png_begin(w);
    return fprintf(w->f, "P6\n%d %d\n255\n", w->width, w->height) > 0 ? 0 : -1;
}

struct image_writer *image_writer_open(const char *path, enum image_format format,
                                       int width, int height)
{
    if (format == IMAGE_UNKNOWN) {
        report(path, "unknown image format");
        return NULL;
    }
    if (check_target(path) != 0)
        return NULL;
    struct image_writer *w = calloc(1, sizeof *w);
    if (w)
        w->fd = -1;
    if (!w || !(w->path = strdup(path)) || !(w->tmp = temp_path(path))) {
        report(path, strerror(ENOMEM));
        image_writer_abort(w);
        return NULL;
    }
    w->format = format;
    w->width = width;
    w->height = height;
    /* Read the umask now, while tp2 has one thread: umask() sets it too. */
    mode_t mask = umask(0);
    umask(mask);
    w->new_mode = 0666 & ~mask;
    w->fd = tempfile_create(w->tmp);
    if (w->fd < 0) {
        report_errno(path, errno);
        free(w->tmp); /* nothing was created: nothing to remove */
        w->tmp = NULL;
        image_writer_abort(w);
        return NULL;
    }
    errno = 0;
    if (begin(w) != 0) {
        report_errno(path, w->error ? w->error : errno);
        image_writer_abort(w);
        return NULL;
    }
    return w;
}

/* One row of rgba (width * 4 floats) as 8-bit RGB. */
static void quantize_row(const float *rgba, int width, unsigned char *out)
{
    for (int x = 0; x < width; x++)
        for (int c = 0; c < 3; c++)
            out[x * 3 + c] = image_quantize(rgba[x * 4 + c]);
}

/* Rows handed to the writer: floats (width * 4 per row) or 8-bit values
 * already quantized (width words r | g << 8 | b << 16 per row). */
struct row_source {
    const float *rgba;
    const uint32_t *words;
};

/* Row i of src as 8-bit RGB. */
static void rgb_row(const struct image_writer *w, struct row_source src, int i,
                    unsigned char *out)
{
    if (!src.words) {
        quantize_row(src.rgba + (size_t)i * w->width * 4, w->width, out);
        return;
    }
    const uint32_t *row = src.words + (size_t)i * w->width;
    for (int x = 0; x < w->width; x++)
        for (int c = 0; c < 3; c++)
            out[x * 3 + c] = (unsigned char)(row[x] >> (8 * c));
}

/* PFM stores rows bottom to top: each row goes to its own offset. */
static int pfm_row(struct image_writer *w, const float *rgba, int y)
{
    float *out = (float *)(void *)w->row;
    for (int x = 0; x < w->width; x++)
        memcpy(&out[x * 3], &rgba[x * 4], 3 * sizeof *out);
    size_t bytes = (size_t)w->width * 12;
    off_t at = (off_t)w->header + (off_t)(w->height - 1 - y) * (off_t)bytes;
    return pwrite_all(w->fd, out, bytes, at);
}

static int png_rows(struct image_writer *w, struct row_source src, int rows)
{
    if (setjmp(png_jmpbuf(w->png)))
        return -1;
    for (int i = 0; i < rows; i++) {
        rgb_row(w, src, i, w->row);
        png_write_row(w->png, w->row);
    }
    return 0;
}

static int encode_rows(struct image_writer *w, struct row_source src, int rows)
{
    if (w->format == IMAGE_PNG)
        return png_rows(w, src, rows);
    for (int i = 0; i < rows; i++) {
        if (w->format == IMAGE_PFM) {
            if (pfm_row(w, src.rgba + (size_t)i * w->width * 4, w->next_row + i) != 0)
                return -1;
        } else {
            rgb_row(w, src, i, w->row);
            if (fwrite(w->row, 3, (size_t)w->width, w->f) != (size_t)w->width)
                return -1;
        }
    }
    return 0;
}

static int write_rows(struct image_writer *w, struct row_source src, int rows)
{
    if (rows < 0 || rows > w->height - w->next_row)
        return report(w->path, "more rows than the image has");
    if (src.words && w->format == IMAGE_PFM)
        return report(w->path, "8-bit rows for a PFM file");
    errno = 0;
    if (encode_rows(w, src, rows) != 0)
        return report_errno(w->path, w->error ? w->error : errno);
    w->next_row += rows;
    return 0;
}

int image_writer_rows(struct image_writer *w, const float *rgba, int rows)
{
    return write_rows(w, (struct row_source){rgba, NULL}, rows);
}

int image_writer_rows_rgba8(struct image_writer *w, const uint32_t *words, int rows)
{
    return write_rows(w, (struct row_source){NULL, words}, rows);
}

static int png_end(struct image_writer *w)
{
    if (setjmp(png_jmpbuf(w->png)))
        return -1;
    png_write_end(w->png, NULL);
    return 0;
}

/* The mode the finished file gets: the replaced output's permissions,
 * else a new file's. */
static mode_t final_mode(const struct image_writer *w)
{
    struct stat st;
    if (stat(w->path, &st) == 0 && S_ISREG(st.st_mode))
        return st.st_mode & 0777;
    return w->new_mode;
}

/* Completes the file and closes it; 0 or -1 with errno set. */
static int complete(struct image_writer *w)
{
    int fd = w->f ? fileno(w->f) : w->fd;
    int rc = 0;
    if (w->png && png_end(w) != 0) {
        errno = w->error;
        rc = -1;
    }
    if (rc == 0 && fchmod(fd, final_mode(w)) != 0)
        rc = -1;
    int saved = errno;
    if (w->f ? fclose(w->f) != 0 : close(w->fd) != 0) {
        saved = errno;
        rc = -1;
    }
    w->f = NULL;
    w->fd = -1;
    errno = saved;
    return rc;
}

int image_writer_finish(struct image_writer *w)
{
    if (w->next_row != w->height) {
        report(w->path, "the image is incomplete");
        image_writer_abort(w);
        return -1;
    }
    errno = 0;
    if (complete(w) != 0 || rename(w->tmp, w->path) != 0) {
        report_errno(w->path, errno);
        image_writer_abort(w);
        return -1;
    }
    tempfile_forget(w->tmp);
    free(w->tmp);
    w->tmp = NULL;
    image_writer_abort(w); /* frees the rest */
    return 0;
}

void image_writer_abort(struct image_writer *w)
{
    if (!w)
        return;
    if (w->png)
        png_destroy_write_struct(&w->png, &w->info);
    if (w->f)
        fclose(w->f);
    else if (w->fd >= 0)
        close(w->fd);
    if (w->tmp) {
        unlink(w->tmp);
        tempfile_forget(w->tmp);
    }
    free(w->row);
    free(w->tmp);
    free(w->path);
    free(w);
}

int image_write(const char *path, enum image_format format, int width,
                int height, const float *rgba)
{
    struct image_writer *w = image_writer_open(path, format, width, height);
    if (!w)
        return -1;
    if (image_writer_rows(w, rgba, height) != 0) {
        image_writer_abort(w);
        return -1;
    }
    return image_writer_finish(w);
}
