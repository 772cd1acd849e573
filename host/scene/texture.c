/* texture.c: image files to 8-bit RGB texels (see texture.h). */
#define _POSIX_C_SOURCE 200809L /* fileno, fstat */
#include "texture.h"

#include <errno.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <setjmp.h>
#include <sys/stat.h>

#include <jpeglib.h>
#include <png.h>
#include <stb_image.h>

/* Largest image file read (a larger one is refused: "File too large"):
 * far above any real texture (a 32 Mi-texel image as 16-bit ASCII PPM is
 * about 600 MB). */
#define TEXTURE_MAX_FILE ((size_t)1 << 30)

static int why_said(char *why, size_t size, const char *text)
{
    if (why && size > 0)
        snprintf(why, size, "%s", text);
    return -1;
}

/* ---- PPM --------------------------------------------------------------- */

struct ppm_cursor {
    const unsigned char *p, *end;
};

static bool ppm_space(unsigned char c)
{
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
}

/* Skips white space and '#' comments (to the end of the line). */
static void ppm_skip(struct ppm_cursor *c)
{
    while (c->p < c->end) {
        if (ppm_space(*c->p)) {
            c->p++;
        } else if (*c->p == '#') {
            while (c->p < c->end && *c->p != '\n' && *c->p != '\r')
                c->p++;
        } else {
            break;
        }
    }
}

/* Reads a decimal number of at most 9 digits; -1 if there is none. */
static long ppm_number(struct ppm_cursor *c)
{
    ppm_skip(c);
    long v = 0;
    int digits = 0;
    while (c->p < c->end && *c->p >= '0' && *c->p <= '9' && digits < 10) {
        v = v * 10 + (*c->p++ - '0');
        digits++;
    }
    if (digits == 0 || digits > 9)
        return -1;
    return v;
}

int texture_decode_ppm(const unsigned char *data, size_t len,
                       struct texture_image *out, char *why, size_t whysize)
{
    memset(out, 0, sizeof *out);
    struct ppm_cursor c = {data, data + len};
    if (len < 2 || data[0] != 'P' || (data[1] != '3' && data[1] != '6'))
        return why_said(why, whysize, "not a P3 or P6 PPM image");
    bool ascii = data[1] == '3';
    c.p += 2;
    long w = ppm_number(&c), h = ppm_number(&c), maxval = ppm_number(&c);
    if (w < 1 || h < 1 || maxval < 1 || maxval > 65535)
        return why_said(why, whysize, "malformed PPM header (width, height and "
                                      "a maxval from 1 to 65535 expected)");
    if ((size_t)w * (size_t)h > TEXTURE_MAX_TEXELS)
        return why_said(why, whysize, "image too large (at most 32 Mi texels)");
    /* Binary data starts after exactly one white space byte. */
    if (!ascii && (c.p >= c.end || !ppm_space(*c.p++)))
        return why_said(why, whysize, "malformed PPM header");
    size_t n = (size_t)w * (size_t)h * 3;
    out->rgb = malloc(n);
    if (!out->rgb)
        return why_said(why, whysize, "out of memory");
    int bytes = maxval > 255 ? 2 : 1;
    if (!ascii && (size_t)(c.end - c.p) / (size_t)bytes < n) {
        free(out->rgb);
        out->rgb = NULL;
        return why_said(why, whysize, "PPM data ends early");
    }
    for (size_t i = 0; i < n; i++) {
        long v;
        if (ascii) {
            v = ppm_number(&c);
        } else {
            v = bytes == 2 ? (long)c.p[0] << 8 | c.p[1] : c.p[0];
            c.p += bytes;
        }
        if (v < 0 || v > maxval) {
            free(out->rgb);
            out->rgb = NULL;
            return why_said(why, whysize, v < 0 ? "PPM data ends early or is malformed"
                                                : "PPM value above its maxval");
        }
        out->rgb[i] = (uint8_t)((v * 255 * 2 + maxval) / (2 * maxval));
    }
    out->width = (int)w;
    out->height = (int)h;
    return 0;
}

/* ---- files ------------------------------------------------------------- */

/* The whole file in a new buffer, or NULL with errno set. */
static unsigned char *read_file(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    struct stat st; /* a file known to be too large is refused unread */
    if (fstat(fileno(f), &st) == 0 && S_ISREG(st.st_mode) &&
        (uintmax_t)st.st_size >= TEXTURE_MAX_FILE) {
        fclose(f);
        errno = EFBIG;
        return NULL;
    }
    size_t cap = 1 << 16, n = 0;
    unsigned char *buf = malloc(cap);
    while (buf) {
        n += fread(buf + n, 1, cap - n, f);
        if (ferror(f)) {
            int saved = errno ? errno : EIO;
            free(buf);
            fclose(f);
            errno = saved;
            return NULL;
        }
        if (n < cap)
            break;
        unsigned char *bigger = cap < TEXTURE_MAX_FILE ? realloc(buf, cap * 2) : NULL;
        if (!bigger) {
            free(buf);
            fclose(f);
            errno = cap < TEXTURE_MAX_FILE ? ENOMEM : EFBIG;
            return NULL;
        }
        buf = bigger;
        cap *= 2;
    }
    fclose(f);
    if (!buf)
        errno = ENOMEM;
    *len = n;
    return buf;
}

/* ---- JPEG ------------------------------------------------------------- */

/* JPEG goes to libjpeg-turbo, not to stb_image: fuzzing stb_image 2.27
 * (Debian 12's) found a Huffman table overflowing its arrays and shifts
 * past 32 bits on corrupt entropy-coded data (upstream 2.28 fixed both;
 * tests/fuzz/fuzz_image.c), while libjpeg-turbo checks its input and is
 * fuzzed continuously upstream. Its errors jump back here. */
struct jpeg_failure {
    struct jpeg_error_mgr mgr;
    jmp_buf back;
    char message[JMSG_LENGTH_MAX];
};

static void jpeg_fail(j_common_ptr info)
{
    struct jpeg_failure *f = (struct jpeg_failure *)info->err;
    f->mgr.format_message(info, f->message);
    longjmp(f->back, 1);
}

/* Warnings (a corrupt but readable stream) are not printed: the decode
 * goes on as libjpeg intends. */
static void jpeg_quiet(j_common_ptr info)
{
    (void)info;
}

static int texture_decode_jpeg(const unsigned char *data, size_t len,
                               struct texture_image *out, char *why, size_t whysize)
{
    struct jpeg_decompress_struct info;
    struct jpeg_failure failure;
    /* volatile: set after setjmp and read after a longjmp back to it */
    unsigned char *volatile rgb = NULL;
    info.err = jpeg_std_error(&failure.mgr);
    failure.mgr.error_exit = jpeg_fail;
    failure.mgr.output_message = jpeg_quiet;
    if (setjmp(failure.back)) {
        jpeg_destroy_decompress(&info);
        free(rgb);
        if (why && whysize > 0)
            snprintf(why, whysize, "cannot decode the JPEG (%s)", failure.message);
        return -1;
    }
    jpeg_create_decompress(&info);
    jpeg_mem_src(&info, data, (unsigned long)len);
    jpeg_read_header(&info, TRUE);
    if ((size_t)info.image_width * info.image_height > TEXTURE_MAX_TEXELS) {
        jpeg_destroy_decompress(&info);
        return why_said(why, whysize, "image too large (at most 32 Mi texels)");
    }
    info.out_color_space = JCS_RGB;
    jpeg_start_decompress(&info);
    size_t row = (size_t)info.output_width * 3;
    rgb = malloc(row * info.output_height);
    if (!rgb) {
        jpeg_destroy_decompress(&info);
        return why_said(why, whysize, "out of memory");
    }
    while (info.output_scanline < info.output_height) {
        JSAMPROW at = rgb + row * info.output_scanline;
        jpeg_read_scanlines(&info, &at, 1);
    }
    jpeg_finish_decompress(&info);
    out->width = (int)info.output_width;
    out->height = (int)info.output_height;
    out->rgb = rgb;
    jpeg_destroy_decompress(&info);
    return 0;
}

/* ---- PNG --------------------------------------------------------------- */

/* PNG goes to libpng (already tp2's PNG writer), not to stb_image: fuzzing
 * stb_image 2.27 found it sizing its buffer by a chunk's claimed length
 * before reading it (2 GiB for 94 bytes) and doing arithmetic on a null
 * pointer for an empty first IDAT (tests/fuzz/fuzz_image.c); libpng checks
 * lengths and CRCs and is fuzzed upstream. Errors jump back here. Like
 * stb, it keeps 8 bits of 16 (the high byte), expands palettes and gray,
 * drops alpha and applies no gamma. */
struct png_source {
    const unsigned char *data;
    size_t len, at;
    char message[128];
};

static void png_read_bytes(png_structp png, png_bytep out, size_t n)
{
    struct png_source *src = png_get_io_ptr(png);
    if (n > src->len - src->at)
        png_error(png, "file ends inside the image");
    memcpy(out, src->data + src->at, n);
    src->at += n;
}

static void png_fail(png_structp png, png_const_charp message)
{
    struct png_source *src = png_get_error_ptr(png);
    snprintf(src->message, sizeof src->message, "%s", message);
    png_longjmp(png, 1);
}

static void png_quiet(png_structp png, png_const_charp message)
{
    (void)png;
    (void)message;
}

static int texture_decode_png(const unsigned char *data, size_t len,
                              struct texture_image *out, char *why, size_t whysize)
{
    struct png_source src = {data, len, 0, "out of memory"};
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &src, png_fail, png_quiet);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    /* volatile: set after setjmp and read after a longjmp back to it */
    unsigned char *volatile rgb = NULL;
    png_bytep *volatile rows = NULL;
    if (!info || setjmp(png_jmpbuf(png))) {
        png_destroy_read_struct(&png, &info, NULL);
        free(rgb);
        free(rows);
        if (why && whysize > 0)
            snprintf(why, whysize, "cannot decode the PNG (%s)", src.message);
        return -1;
    }
    png_set_read_fn(png, &src, png_read_bytes);
    png_read_info(png, info);
    size_t w = png_get_image_width(png, info), h = png_get_image_height(png, info);
    if (w * h > TEXTURE_MAX_TEXELS) {
        png_destroy_read_struct(&png, &info, NULL);
        return why_said(why, whysize, "image too large (at most 32 Mi texels)");
    }
    png_set_strip_16(png);
    png_set_palette_to_rgb(png);
    png_set_expand_gray_1_2_4_to_8(png);
    png_set_gray_to_rgb(png);
    png_set_strip_alpha(png);
    png_set_interlace_handling(png);
    png_read_update_info(png, info);
    if (png_get_rowbytes(png, info) != w * 3)
        png_error(png, "unexpected row size");
    rgb = malloc(w * h * 3);
    rows = malloc(h * sizeof *rows);
    if (!rgb || !rows)
        png_error(png, "out of memory");
    for (size_t y = 0; y < h; y++)
        rows[y] = rgb + y * w * 3;
    png_read_image(png, rows);
    free(rows);
    png_destroy_read_struct(&png, &info, NULL);
    out->width = (int)w;
    out->height = (int)h;
    out->rgb = rgb;
    return 0;
}

/* ---- any format -------------------------------------------------------- */

int texture_decode(const unsigned char *data, size_t len, struct texture_image *out,
                   char *why, size_t whysize)
{
    memset(out, 0, sizeof *out);
    if (len >= 2 && data[0] == 'P' && (data[1] == '3' || data[1] == '6'))
        return texture_decode_ppm(data, len, out, why, whysize);
    /* stb_image takes any data whose first byte is FF for a JPEG (fill
     * bytes may precede the start marker); libjpeg-turbo gets all of it. */
    if (len >= 1 && data[0] == 0xFF)
        return texture_decode_jpeg(data, len, out, why, whysize);
    static const unsigned char png_signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    if (len >= 8 && memcmp(data, png_signature, 8) == 0)
        return texture_decode_png(data, len, out, why, whysize);
    /* stb_image decodes BMP here, and only BMP: its other decoders (GIF,
     * PSD, TGA, PNM, ...) are no format of SPEC's, and its 2.27 has bugs
     * fuzzing finds. */
    if (len < 2 || data[0] != 'B' || data[1] != 'M')
        return why_said(why, whysize, "not a BMP, PNG, JPEG or PPM image");
    int w = 0, h = 0, comp = 0;
    if (len > (size_t)0x7fffffff || !stbi_info_from_memory(data, (int)len, &w, &h, &comp))
        return why_said(why, whysize, "not a BMP, PNG, JPEG or PPM image");
    /* The height of a top-down BMP comes negative here. */
    if (w == 0 || h == 0)
        return why_said(why, whysize, "image of no texels (a width or height of 0)");
    if ((size_t)abs(w) * (size_t)abs(h) > TEXTURE_MAX_TEXELS)
        return why_said(why, whysize, "image too large (at most 32 Mi texels)");
    /* Copied so that rgb is always ours to free(). */
    stbi_uc *img = stbi_load_from_memory(data, (int)len, &w, &h, &comp, 3);
    size_t n = (size_t)w * (size_t)h * 3;
    int rc = -1;
    if (img && (w < 1 || h < 1)) {
        why_said(why, whysize, "image of no texels (a width or height of 0)");
    } else if (!img) {
        if (why && whysize > 0)
            snprintf(why, whysize, "cannot decode the image (%s)", stbi_failure_reason());
    } else if (!(out->rgb = malloc(n))) {
        why_said(why, whysize, "out of memory");
    } else {
        memcpy(out->rgb, img, n);
        out->width = w;
        out->height = h;
        rc = 0;
    }
    stbi_image_free(img);
    return rc;
}

int texture_load(const char *path, struct texture_image *out, char *why,
                 size_t whysize)
{
    memset(out, 0, sizeof *out);
    size_t len = 0;
    errno = 0;
    unsigned char *data = read_file(path, &len);
    if (!data)
        return why_said(why, whysize, strerror(errno ? errno : EIO));
    int rc = texture_decode(data, len, out, why, whysize);
    free(data);
    return rc;
}

double texture_step(const struct texture_image *img)
{
    int most = 0;
    for (int y = 0; y < img->height; y++) {
        const uint8_t *row = img->rgb + (size_t)y * img->width * 3;
        const uint8_t *next = img->rgb + (size_t)((y + 1) % img->height) * img->width * 3;
        for (int x = 0; x < img->width; x++) {
            const uint8_t *right = row + (size_t)((x + 1) % img->width) * 3;
            for (int c = 0; c < 3; c++) {
                int here = row[3 * x + c];
                int across = abs(here - right[c]), down = abs(here - next[3 * x + c]);
                most = across > most ? across : most;
                most = down > most ? down : most;
            }
        }
    }
    return most / 255.0;
}
