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
#include <jerror.h>
#include <png.h>
#include <stb_image.h>

/* Most bytes of an image file read (a larger one is refused: "File too
 * large"): far above any real texture (a 32 Mi-texel image as 16-bit
 * ASCII PPM is about 600 MB). */
#define TEXTURE_MAX_FILE ((size_t)1 << 30)

static int why_said(char *why, size_t size, const char *text)
{
    if (why && size > 0)
        snprintf(why, size, "%s", text);
    return -1;
}

/* ---- reading ----------------------------------------------------------- */

/* An image's bytes in order, from a file or from memory. A file is read
 * only as far as its decoder asks: its header says how far that is (PPM,
 * BMP) or the library stops where the image ends (PNG, JPEG), so an
 * endless file (a FIFO, a device) costs no more than its image; what no
 * header bounds (an ASCII P3's text, a stream that never ends the image)
 * stops at TEXTURE_MAX_FILE bytes. */
struct source {
    FILE *file;                /* NULL: the bytes are mem */
    const unsigned char *mem;
    size_t len;                /* mem's size */
    size_t at;                 /* bytes taken so far */
    unsigned char head[8];     /* a file's first bytes, read to know its format */
    size_t head_len;
    int back;                  /* the byte source_unget gave back, or -1 */
    bool too_large;            /* a read went past TEXTURE_MAX_FILE */
    int error;                 /* errno of a failed read, or 0 */
};

static void source_failed(struct source *s)
{
    if (ferror(s->file) && !s->error)
        s->error = errno ? errno : EIO;
}

static int source_getc(struct source *s)
{
    int c;
    if (s->back >= 0) {
        c = s->back;
        s->back = -1;
    } else if (!s->file) {
        if (s->at >= s->len)
            return EOF;
        c = s->mem[s->at];
    } else if (s->at < s->head_len) {
        c = s->head[s->at];
    } else if (s->at >= TEXTURE_MAX_FILE) {
        s->too_large = true;
        return EOF;
    } else if ((c = getc(s->file)) == EOF) {
        source_failed(s);
        return EOF;
    }
    s->at++;
    return c;
}

/* Gives back c, the byte source_getc returned last (EOF: nothing). */
static void source_unget(struct source *s, int c)
{
    if (c != EOF) {
        s->back = c;
        s->at--;
    }
}

/* Up to n bytes into buf; fewer at the end of the data. */
static size_t source_read(struct source *s, unsigned char *buf, size_t n)
{
    size_t got = 0;
    if (n > 0 && s->back >= 0) {
        buf[got++] = (unsigned char)s->back;
        s->back = -1;
        s->at++;
    }
    if (!s->file) {
        size_t k = n - got < s->len - s->at ? n - got : s->len - s->at;
        memcpy(buf + got, s->mem + s->at, k);
        s->at += k;
        return got + k;
    }
    while (got < n && s->at < s->head_len)
        buf[got++] = s->head[s->at++];
    size_t want = n - got, room = TEXTURE_MAX_FILE - s->at;
    size_t k = fread(buf + got, 1, want < room ? want : room, s->file);
    s->at += k;
    if (k < (want < room ? want : room))
        source_failed(s);
    else if (want > room)
        s->too_large = true;
    return got + k;
}

/* Reads on until *buf holds want bytes (or the data ends), growing it as
 * the bytes come rather than by what a header claims. 0, or -1 when out
 * of memory. */
static int source_take(struct source *s, unsigned char **buf, size_t *len, size_t want)
{
    size_t cap = *len;
    while (*len < want) {
        if (*len == cap) {
            size_t bigger = cap < 4096 ? 4096 : cap * 2;
            bigger = bigger < want ? bigger : want;
            unsigned char *grown = realloc(*buf, bigger);
            if (!grown)
                return -1;
            *buf = grown;
            cap = bigger;
        }
        size_t k = source_read(s, *buf + *len, cap - *len);
        *len += k;
        if (k == 0)
            break;
    }
    return 0;
}

/* ---- PPM --------------------------------------------------------------- */

static bool ppm_space(int c)
{
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
}

/* Skips white space and '#' comments (to the end of the line). */
static void ppm_skip(struct source *s)
{
    int c;
    while ((c = source_getc(s)) != EOF) {
        if (c == '#') {
            while ((c = source_getc(s)) != EOF && c != '\n' && c != '\r')
                ;
        } else if (!ppm_space(c)) {
            source_unget(s, c);
            return;
        }
    }
}

/* Reads a decimal number of at most 9 digits; -1 if there is none. */
static long ppm_number(struct source *s)
{
    ppm_skip(s);
    long v = 0;
    int digits = 0, c;
    while (digits < 10 && (c = source_getc(s)) != EOF) {
        if (c < '0' || c > '9') {
            source_unget(s, c);
            break;
        }
        v = v * 10 + (c - '0');
        digits++;
    }
    if (digits == 0 || digits > 9)
        return -1;
    return v;
}

static uint8_t ppm_scaled(long v, long maxval)
{
    return (uint8_t)((v * 255 * 2 + maxval) / (2 * maxval));
}

/* A P6's samples: the header says how many bytes follow, and no more are
 * read. Their length is checked before their values. */
static const char *ppm_binary(struct source *s, long maxval, size_t n, uint8_t *rgb)
{
    unsigned char chunk[1 << 15]; /* an even size: 16-bit samples stay whole */
    size_t bytes = maxval > 255 ? 2 : 1;
    const char *bad = NULL;
    for (size_t i = 0; i < n;) {
        size_t want = (n - i) * bytes < sizeof chunk ? (n - i) * bytes : sizeof chunk;
        if (source_read(s, chunk, want) < want)
            return "PPM data ends early";
        for (size_t k = 0; k < want; k += bytes, i++) {
            long v = bytes == 2 ? (long)chunk[k] << 8 | chunk[k + 1] : chunk[k];
            if (v > maxval)
                bad = "PPM value above its maxval";
            else
                rgb[i] = ppm_scaled(v, maxval);
        }
    }
    return bad;
}

static int ppm_read(struct source *s, struct texture_image *out, char *why, size_t whysize)
{
    int m0 = source_getc(s), m1 = source_getc(s);
    if (m0 != 'P' || (m1 != '3' && m1 != '6'))
        return why_said(why, whysize, "not a P3 or P6 PPM image");
    bool ascii = m1 == '3';
    long w = ppm_number(s), h = ppm_number(s), maxval = ppm_number(s);
    if (w < 1 || h < 1 || maxval < 1 || maxval > 65535)
        return why_said(why, whysize, "malformed PPM header (width, height and "
                                      "a maxval from 1 to 65535 expected)");
    if ((size_t)w * (size_t)h > TEXTURE_MAX_TEXELS)
        return why_said(why, whysize, "image too large (at most 32 Mi texels)");
    /* Binary data starts after exactly one white space byte. */
    if (!ascii && !ppm_space(source_getc(s)))
        return why_said(why, whysize, "malformed PPM header");
    size_t n = (size_t)w * (size_t)h * 3;
    uint8_t *rgb = malloc(n);
    if (!rgb)
        return why_said(why, whysize, "out of memory");
    const char *bad = NULL;
    if (!ascii)
        bad = ppm_binary(s, maxval, n, rgb);
    for (size_t i = 0; ascii && i < n && !bad; i++) {
        long v = ppm_number(s);
        if (v < 0 || v > maxval)
            bad = v < 0 ? "PPM data ends early or is malformed" : "PPM value above its maxval";
        else
            rgb[i] = ppm_scaled(v, maxval);
    }
    if (bad) {
        free(rgb);
        return why_said(why, whysize, bad);
    }
    out->width = (int)w;
    out->height = (int)h;
    out->rgb = rgb;
    return 0;
}

int texture_decode_ppm(const unsigned char *data, size_t len,
                       struct texture_image *out, char *why, size_t whysize)
{
    memset(out, 0, sizeof *out);
    struct source s = {.mem = data, .len = len, .back = -1};
    return ppm_read(&s, out, why, whysize);
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

/* libjpeg's source of bytes: the image's source, as jpeg_mem_src and
 * jpeg_stdio_src do it (at the end, a warning and a made-up EOI marker). */
struct jpeg_stream {
    struct jpeg_source_mgr mgr;
    struct source *from;
    JOCTET buf[4096];
};

static void jpeg_stream_start(j_decompress_ptr info)
{
    (void)info;
}

static boolean jpeg_stream_fill(j_decompress_ptr info)
{
    struct jpeg_stream *js = (struct jpeg_stream *)info->src;
    size_t n = source_read(js->from, js->buf, sizeof js->buf);
    if (n == 0) {
        WARNMS(info, JWRN_JPEG_EOF);
        js->buf[0] = 0xFF;
        js->buf[1] = JPEG_EOI;
        n = 2;
    }
    js->mgr.next_input_byte = js->buf;
    js->mgr.bytes_in_buffer = n;
    return TRUE;
}

static void jpeg_stream_skip(j_decompress_ptr info, long count)
{
    struct jpeg_source_mgr *src = info->src;
    if (count <= 0)
        return;
    while (count > (long)src->bytes_in_buffer) {
        count -= (long)src->bytes_in_buffer;
        src->fill_input_buffer(info);
    }
    src->next_input_byte += count;
    src->bytes_in_buffer -= (size_t)count;
}

static int jpeg_read(struct source *s, struct texture_image *out, char *why, size_t whysize)
{
    struct jpeg_decompress_struct info;
    struct jpeg_stream stream = {
        .mgr = {.init_source = jpeg_stream_start, .fill_input_buffer = jpeg_stream_fill,
                .skip_input_data = jpeg_stream_skip, .resync_to_restart = jpeg_resync_to_restart,
                .term_source = jpeg_stream_start},
        .from = s};
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
    info.src = &stream.mgr;
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
    struct source *from;
    char message[128];
};

static void png_read_bytes(png_structp png, png_bytep out, size_t n)
{
    struct png_source *src = png_get_io_ptr(png);
    if (source_read(src->from, out, n) < n)
        png_error(png, "file ends inside the image");
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

static int png_read(struct source *s, struct texture_image *out, char *why, size_t whysize)
{
    struct png_source src = {s, "out of memory"};
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

/* ---- BMP --------------------------------------------------------------- */

static uint32_t le_bytes(const unsigned char *p, int n)
{
    uint32_t v = 0;
    for (int i = n - 1; i >= 0; i--)
        v = v << 8 | p[i];
    return v;
}

/* stb_image decodes BMP here, and only BMP: its other decoders (GIF, PSD,
 * TGA, PNM, ...) are no format of SPEC's, and its 2.27 has bugs fuzzing
 * finds. It gets the file's bytes in memory, read as far as stb reads:
 * the header (stb reads 3 masks after one of 40 or 56 bytes), then to the
 * pixel data's offset and its rows. */
static int bmp_read(struct source *s, struct texture_image *out, char *why, size_t whysize)
{
    unsigned char *data = NULL;
    size_t len = 0;
    int rc = -1;
    if (source_take(s, &data, &len, 18) != 0)
        return why_said(why, whysize, "out of memory");
    uint32_t hsz = len >= 18 ? le_bytes(data + 14, 4) : 0;
    size_t header = 14 + (hsz < 124 ? hsz : 124) + (hsz == 40 || hsz == 56 ? 12 : 0);
    int w = 0, h = 0, comp = 0;
    if (source_take(s, &data, &len, header) != 0) {
        why_said(why, whysize, "out of memory");
    } else if (!stbi_info_from_memory(data, (int)len, &w, &h, &comp)) {
        why_said(why, whysize, "not a BMP, PNG, JPEG or PPM image");
    } else if (w == 0 || h == 0) { /* the height of a top-down BMP comes negative */
        why_said(why, whysize, "image of no texels (a width or height of 0)");
    } else if ((size_t)abs(w) * (size_t)abs(h) > TEXTURE_MAX_TEXELS) {
        why_said(why, whysize, "image too large (at most 32 Mi texels)");
    } else {
        size_t at = hsz == 12 ? 24 : 28; /* bits per pixel */
        size_t bpp = len >= at + 2 ? le_bytes(data + at, 2) : 0;
        size_t stride = ((size_t)abs(w) * bpp + 31) / 32 * 4;
        size_t need = le_bytes(data + 10, 4) + stride * (size_t)abs(h);
        if (source_take(s, &data, &len, need < TEXTURE_MAX_FILE ? need : TEXTURE_MAX_FILE) != 0)
            why_said(why, whysize, "out of memory");
        else
            rc = 0;
    }
    if (rc != 0) {
        free(data);
        return -1;
    }
    /* Copied so that rgb is always ours to free(). */
    stbi_uc *img = stbi_load_from_memory(data, (int)len, &w, &h, &comp, 3);
    free(data);
    size_t n = (size_t)w * (size_t)h * 3;
    rc = -1;
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

/* ---- any format -------------------------------------------------------- */

/* Decodes the image s holds, its format known by its first bytes: what
 * is no BMP, PNG, JPEG or PPM is refused before any more is read. A read
 * error or a file past TEXTURE_MAX_FILE bytes is the reason given, over
 * whatever the decoder made of the bytes it got. */
static int source_decode(struct source *s, struct texture_image *out, char *why,
                         size_t whysize)
{
    memset(out, 0, sizeof *out);
    const unsigned char *head = s->file ? s->head : s->mem;
    size_t n = s->file ? s->head_len : s->len;
    static const unsigned char png_signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    int rc;
    if (n >= 2 && head[0] == 'P' && (head[1] == '3' || head[1] == '6'))
        rc = ppm_read(s, out, why, whysize);
    /* stb_image took any data whose first byte is FF for a JPEG (fill
     * bytes may precede the start marker); libjpeg-turbo gets all of it. */
    else if (n >= 1 && head[0] == 0xFF)
        rc = jpeg_read(s, out, why, whysize);
    else if (n >= 8 && memcmp(head, png_signature, 8) == 0)
        rc = png_read(s, out, why, whysize);
    else if (n >= 2 && head[0] == 'B' && head[1] == 'M')
        rc = bmp_read(s, out, why, whysize);
    else
        rc = why_said(why, whysize, "not a BMP, PNG, JPEG or PPM image");
    if (s->error || s->too_large) {
        free(out->rgb);
        memset(out, 0, sizeof *out);
        rc = why_said(why, whysize, strerror(s->error ? s->error : EFBIG));
    }
    return rc;
}

int texture_decode(const unsigned char *data, size_t len, struct texture_image *out,
                   char *why, size_t whysize)
{
    struct source s = {.mem = data, .len = len, .back = -1};
    return source_decode(&s, out, why, whysize);
}

int texture_load(const char *path, struct texture_image *out, char *why,
                 size_t whysize)
{
    memset(out, 0, sizeof *out);
    errno = 0;
    FILE *f = fopen(path, "rb");
    if (!f)
        return why_said(why, whysize, strerror(errno ? errno : EIO));
    struct stat st; /* a file known to be too large is refused unread */
    if (fstat(fileno(f), &st) == 0 && S_ISREG(st.st_mode) &&
        (uintmax_t)st.st_size >= TEXTURE_MAX_FILE) {
        fclose(f);
        return why_said(why, whysize, strerror(EFBIG));
    }
    struct source s = {.file = f, .back = -1};
    s.head_len = fread(s.head, 1, sizeof s.head, f);
    if (s.head_len < sizeof s.head)
        source_failed(&s);
    int rc = source_decode(&s, out, why, whysize);
    fclose(f);
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
