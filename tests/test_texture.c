/* test_texture.c: texture_load and texture_decode_ppm.
 *
 * PPM: P6 and P3, comments anywhere in the header, maxvals 1 to 65535
 * (16-bit samples big-endian) scaled to 8 bits, and every malformed form
 * refused with its reason. Files: an asymmetric 3 x 2 image written as
 * BMP (bottom-up by stb_image_write, top-down by hand), PNG and JPEG
 * (approximately: lossy) must come back with its rows top to bottom and
 * R, G, B in place. JPEG Huffman tables of more than 256 codes, which
 * overflow stb_image 2.27 (found by tests/fuzz/fuzz_image.c; JPEG now
 * goes to libjpeg-turbo), refused wherever they come; PNG (libpng) cut,
 * with a chunk longer than the file or a bad CRC refused; formats that
 * are not SPEC's refused before stb_image. Reading: bytes after an
 * image change nothing, /dev/zero is refused by its first bytes, and a
 * pipe that writes on after a P6 gives the P6. texture_step: the steepest
 * step between neighbouring texels, across the image's wrap too. Prints
 * "N passed, M failed" last. */
#define _DEFAULT_SOURCE /* mkstemps, truncate */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <stb_image_write.h>

#include "texture.h"

#include "unit.h"

/* A 3 x 2 image with no symmetry: rows top to bottom. */
static const uint8_t image[2][3][3] = {
    {{255, 0, 0}, {0, 255, 0}, {0, 0, 255}},
    {{255, 255, 0}, {0, 255, 255}, {40, 80, 120}},
};

static int same_as_image(const struct texture_image *t, int tolerance)
{
    if (t->width != 3 || t->height != 2)
        return 0;
    for (int y = 0; y < 2; y++)
        for (int x = 0; x < 3; x++)
            for (int c = 0; c < 3; c++)
                if (abs((int)t->rgb[(y * 3 + x) * 3 + c] - image[y][x][c]) > tolerance)
                    return 0;
    return 1;
}

static int decode(const char *text, size_t len, struct texture_image *t, char *why)
{
    return texture_decode_ppm((const unsigned char *)text, len, t, why, 128);
}

static void test_ppm(void)
{
    struct texture_image t;
    char why[128];
    /* P3, comments between every header field and in the data. */
    const char *p3 = "P3 # plain\n3 # width\n2\n# maxval next\n255\n"
                     "255 0 0  0 255 0  0 0 255\n255 255 0  0 255 255  40 80 120\n";
    CHECK(decode(p3, strlen(p3), &t, why) == 0 && same_as_image(&t, 0));
    free(t.rgb);
    /* P6 with a comment; binary data begins after one white space byte,
     * even when it looks like white space itself. */
    char p6[64];
    int n = snprintf(p6, sizeof p6, "P6\n#c\n3 2\n255\n");
    memcpy(p6 + n, image, sizeof image);
    CHECK(decode(p6, (size_t)n + sizeof image, &t, why) == 0 && same_as_image(&t, 0));
    free(t.rgb);
    /* maxval 1000: v scaled to round(255 v / 1000). */
    const char *thousand = "P3 1 1 1000 1000 500 2\n";
    CHECK(decode(thousand, strlen(thousand), &t, why) == 0 && t.rgb[0] == 255 &&
          t.rgb[1] == 128 && t.rgb[2] == 1);
    free(t.rgb);
    /* maxval 1: a bilevel image. */
    const char *one = "P3 2 1 1 1 0 1 0 1 0\n";
    CHECK(decode(one, strlen(one), &t, why) == 0 && t.rgb[0] == 255 && t.rgb[1] == 0 &&
          t.rgb[3] == 0 && t.rgb[4] == 255);
    free(t.rgb);
    /* 16-bit P6, big-endian: 0xffff, 0x8000, 0x0101. */
    const unsigned char p16[] = "P6 1 1 65535\n\xff\xff\x80\x00\x01\x01";
    CHECK(decode((const char *)p16, sizeof p16 - 1, &t, why) == 0 && t.rgb[0] == 255 &&
          t.rgb[1] == 128 && t.rgb[2] == 1);
    free(t.rgb);
}

static void expect_refused(const char *text, size_t len, const char *want, int line)
{
    struct texture_image t;
    char why[128] = "";
    int rc = decode(text, len, &t, why);
    expect(rc == -1 && strcmp(why, want) == 0 && t.rgb == NULL,
           "line %d: rc %d, why '%s', want '%s'", line, rc, why, want);
    if (rc == 0)
        free(t.rgb);
}

#define REFUSED(text, want) expect_refused((text), strlen(text), (want), __LINE__)

static void test_ppm_errors(void)
{
    const char *header = "malformed PPM header (width, height and a maxval from 1 to 65535 expected)";
    REFUSED("P5 1 1 255 x", "not a P3 or P6 PPM image");
    REFUSED("P3 0 1 255\n", header);
    REFUSED("P3 1 1 0\n", header);
    REFUSED("P3 1 1 65536\n", header);
    REFUSED("P3 1 1\n", header);
    REFUSED("P3 -1 1 255\n", header);
    REFUSED("P3 9999999999 1 255\n", header);
    REFUSED("P3 1 1 255 1 2\n", "PPM data ends early or is malformed");
    REFUSED("P3 1 1 255 1 2 x\n", "PPM data ends early or is malformed");
    REFUSED("P3 1 1 100 1 2 101\n", "PPM value above its maxval");
    REFUSED("P6 2 1 255\nabcde", "PPM data ends early");
    REFUSED("P6 1 1 255", "malformed PPM header");
    REFUSED("P6 100000 100000 255\n", "image too large (at most 32 Mi texels)");
}

/* Writes bytes to a temporary file; its path in path. */
static int temp_file(const void *data, size_t len, char *path, const char *suffix)
{
    snprintf(path, 64, "/tmp/tp2-texture-XXXXXX%s", suffix);
    int fd = mkstemps(path, (int)strlen(suffix));
    if (fd < 0)
        return -1;
    int ok = write(fd, data, len) == (ssize_t)len;
    close(fd);
    return ok ? 0 : -1;
}

/* A 24-bit BMP of the image, rows stored top-down (negative height). */
static size_t top_down_bmp(unsigned char *out)
{
    const int row = 12; /* 3 pixels x 3 bytes = 9, padded to 12 */
    size_t size = 54 + 2 * row;
    memset(out, 0, size);
    out[0] = 'B';
    out[1] = 'M';
    out[2] = (unsigned char)size;
    out[10] = 54;
    out[14] = 40;
    out[18] = 3;
    int32_t h = -2;
    memcpy(out + 22, &h, 4);
    out[26] = 1;
    out[28] = 24;
    for (int y = 0; y < 2; y++)
        for (int x = 0; x < 3; x++)
            for (int c = 0; c < 3; c++) /* BGR */
                out[54 + y * row + x * 3 + c] = image[y][x][2 - c];
    return size;
}

static void test_files(void)
{
    char path[64];
    struct texture_image t;
    char why[128];
    const char *formats[] = {"bmp", "png", "jpg"};
    for (int f = 0; f < 3; f++) {
        snprintf(path, sizeof path, "/tmp/tp2-texture-%d.%s", (int)getpid(), formats[f]);
        int ok = f == 0 ? stbi_write_bmp(path, 3, 2, 3, image)
               : f == 1 ? stbi_write_png(path, 3, 2, 3, image, 9)
                        : stbi_write_jpg(path, 3, 2, 3, image, 100);
        CHECK(ok != 0);
        int rc = texture_load(path, &t, why, sizeof why);
        /* JPEG is lossy and subsamples color: loose. */
        expect(rc == 0 && same_as_image(&t, f == 2 ? 90 : 0), "%s read back: rc %d %s",
               formats[f], rc, rc ? why : "");
        free(t.rgb);
        unlink(path);
    }
    unsigned char bmp[128];
    size_t n = top_down_bmp(bmp);
    if (temp_file(bmp, n, path, ".bmp") == 0) {
        int rc = texture_load(path, &t, why, sizeof why);
        expect(rc == 0 && same_as_image(&t, 0), "top-down BMP: rc %d %s", rc, rc ? why : "");
        free(t.rgb);
        unlink(path);
    }
    /* A file that is no image, a truncated PNG, a missing file. */
    const char junk[] = "GIF87a? no: just text";
    if (temp_file(junk + 6, sizeof junk - 7, path, ".png") == 0) {
        int rc = texture_load(path, &t, why, sizeof why);
        expect(rc == -1 && strcmp(why, "not a BMP, PNG, JPEG or PPM image") == 0,
               "junk: rc %d, %s", rc, why);
        unlink(path);
    }
    snprintf(path, sizeof path, "/tmp/tp2-texture-%d.png", (int)getpid());
    stbi_write_png(path, 3, 2, 3, image, 9);
    FILE *f = fopen(path, "r+b");
    if (f) {
        fseek(f, 0, SEEK_END);
        long len = ftell(f);
        fclose(f);
        CHECK(truncate(path, len / 2) == 0);
    }
    int rc = texture_load(path, &t, why, sizeof why);
    expect(rc == -1 && strcmp(why, "cannot decode the PNG (file ends inside the image)") == 0,
           "truncated PNG: rc %d, %s", rc, why);
    unlink(path);
    rc = texture_load("/tmp/tp2-no-such-texture.ppm", &t, why, sizeof why);
    expect(rc == -1 && strcmp(why, "No such file or directory") == 0, "missing: %s", why);
}

/* stbi_write_*_to_func's sink: appends to a struct jpeg_buf. */
struct jpeg_buf {
    unsigned char data[4096];
    size_t len;
};

static void jpeg_append(void *ctx, void *data, int size)
{
    struct jpeg_buf *b = ctx;
    if (size > 0 && b->len + (size_t)size <= sizeof b->data) {
        memcpy(b->data + b->len, data, (size_t)size);
        b->len += (size_t)size;
    }
}

/* texture_decode on the whole of b: 0, or -1 with why. */
static int decode_any(const struct jpeg_buf *b, char *why)
{
    struct texture_image t;
    int rc = texture_decode(b->data, b->len, &t, why, 128);
    free(t.rgb);
    return rc;
}

static void test_jpeg_huffman(void)
{
    static const char refused[] = "cannot decode the JPEG (Bogus Huffman table definition)";
    struct jpeg_buf good = {.len = 0}, bad;
    char why[128];
    CHECK(stbi_write_jpg_to_func(jpeg_append, &good, 3, 2, 3, image, 90) != 0);
    expect(decode_any(&good, why) == 0, "JPEG: %s", why);
    /* The first DHT's first table given 2 * 255 codes of 16 bits. */
    size_t dht = 2;
    while (dht + 1 < good.len && !(good.data[dht] == 0xFF && good.data[dht + 1] == 0xC4))
        dht++;
    CHECK(dht + 21 < good.len);
    bad = good;
    bad.data[dht + 4 + 15] = 255;
    bad.data[dht + 4 + 16] = 255;
    expect(decode_any(&bad, why) == -1 && strcmp(why, refused) == 0,
           "DHT of 510+ codes in the header: %s", why);
    /* The same behind fill bytes (FF FF C4: stb skips them). */
    bad.len = 0;
    jpeg_append(&bad, good.data, (int)dht);
    jpeg_append(&bad, "\xff\xff", 2);
    jpeg_append(&bad, good.data + dht, (int)(good.len - dht));
    bad.data[dht + 2 + 4 + 16] = 255;
    bad.data[dht + 2 + 4 + 15] = 255;
    expect(decode_any(&bad, why) == -1 && strcmp(why, refused) == 0,
           "DHT behind fill bytes: %s", why);
    /* After the scan, before EOI, where a progressive JPEG has its next
     * tables: stb reads it once the scan's data is decoded. */
    static const unsigned char late[] = {
        0xFF, 0xC4, 0x00, 0x13, 0x00, /* DC table 0 */
        0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 255, 255};
    bad.len = 0;
    jpeg_append(&bad, good.data, (int)good.len - 2);
    jpeg_append(&bad, (void *)late, (int)sizeof late);
    jpeg_append(&bad, "\xff\xd9", 2);
    expect(decode_any(&bad, why) == -1 && strcmp(why, refused) == 0,
           "DHT after the scan: %s", why);
    /* A PNM of 0 x 0, which stb_image 2.27 reads as an image, of 0 x 1,
     * and a 16-bit PGM, which it reads past its buffer (found by
     * tests/fuzz/fuzz_image.c): no format of SPEC's, so stb never sees
     * them, nor a TGA or a GIF. */
    struct texture_image t;
    static const char *others[] = {"P5\n0 0\n255\n", "P5 0 1 255 ",
                                   "P5 2 1 1000 \x01\x02\x03\x04", "GIF89a\x01\x00\x01\x00"};
    for (int i = 0; i < 4; i++) {
        int rc = texture_decode((const unsigned char *)others[i], strlen(others[i]), &t, why,
                                sizeof why);
        expect(rc == -1 && !t.rgb && strcmp(why, "not a BMP, PNG, JPEG or PPM image") == 0,
               "not SPEC's format %d: rc %d, %s", i, rc, why);
    }
    /* After EOI the decoder reads no more. */
    bad = good;
    jpeg_append(&bad, (void *)late, (int)sizeof late);
    expect(decode_any(&bad, why) == 0, "DHT after EOI: %s", why);
}

/* A PNG chunk claiming more bytes than the file has, for which stb_image
 * 2.27 asked for 2 GiB (found by tests/fuzz/fuzz_image.c), a cut file,
 * and a bad CRC, which stb never checked: libpng refuses them. */
static void test_png_chunks(void)
{
    static const char refused[] = "cannot decode the PNG (file ends inside the image)";
    struct jpeg_buf good = {.len = 0}, bad;
    char why[128];
    CHECK(stbi_write_png_to_func(jpeg_append, &good, 3, 2, 3, image, 9) != 0);
    expect(decode_any(&good, why) == 0, "PNG: %s", why);
    size_t idat = 8;
    while (idat + 8 < good.len && memcmp(good.data + idat + 4, "IDAT", 4) != 0)
        idat += 12 + ((size_t)good.data[idat + 2] << 8 | good.data[idat + 3]);
    CHECK(idat + 8 < good.len);
    bad = good;
    memcpy(bad.data + idat, "\x66\x6e\x6f\x38", 4); /* 1718513720 bytes */
    expect(decode_any(&bad, why) == -1 && strcmp(why, refused) == 0,
           "IDAT claiming 1.7 GB: %s", why);
    bad = good;
    bad.len = idat + 10; /* cut inside the IDAT */
    expect(decode_any(&bad, why) == -1 && strcmp(why, refused) == 0, "cut PNG: %s", why);
    bad = good;
    size_t idat_len = (size_t)good.data[idat + 2] << 8 | good.data[idat + 3];
    bad.data[idat + 8 + idat_len] ^= 1; /* the IDAT's CRC */
    expect(decode_any(&bad, why) == -1 && strcmp(why, "cannot decode the PNG (IDAT: CRC error)") == 0,
           "PNG with a bad CRC: %s", why);
}

/* texture_step: neighbours side by side and one above the other, the
 * last column beside the first and the last row above the first. */
/* A BMP of the image with an OS/2 header (12 bytes, 16-bit sizes), 24 bits
 * bottom-up; or, palette != 0, a 40-byte header and 8-bit indices into a
 * palette of its 6 colors. Rows are padded to 4 bytes. */
static size_t other_bmp(unsigned char *out, int palette)
{
    size_t header = palette ? 54 + 6 * 4 : 14 + 12, row = palette ? 4 : 12;
    size_t size = header + 2 * row;
    memset(out, 0, size);
    out[0] = 'B';
    out[1] = 'M';
    out[2] = (unsigned char)size;
    out[10] = (unsigned char)header;
    out[14] = palette ? 40 : 12;
    out[18] = 3;
    out[palette ? 22 : 20] = 2;
    out[palette ? 26 : 22] = 1;
    out[palette ? 28 : 24] = palette ? 8 : 24;
    for (int y = 0; y < 2; y++)
        for (int x = 0; x < 3; x++) {
            unsigned char *at = out + header + (size_t)(1 - y) * row; /* bottom-up */
            if (palette)
                at[x] = (unsigned char)(y * 3 + x);
            for (int c = 0; c < 3; c++) /* BGR */
                (palette ? out + 54 + (y * 3 + x) * 4 : at + x * 3)[c] = image[y][x][2 - c];
        }
    return size;
}

/* A texture is read no further than it needs: every format gives the
 * same texels with bytes after the image (the header says where a PPM's
 * or a BMP's data ends; libpng and libjpeg stop at its end) as without,
 * from memory and from a file; an OS/2 and a palette BMP read their rows;
 * /dev/zero is refused by its first bytes; a pipe that goes on writing
 * after a P6 gives the P6. */
static void test_reads_as_needed(void)
{
    static unsigned char data[4096 + 1000];
    size_t lens[6];
    unsigned char *starts[6];
    struct jpeg_buf png = {.len = 0}, jpg = {.len = 0};
    CHECK(stbi_write_png_to_func(jpeg_append, &png, 3, 2, 3, image, 9) != 0);
    CHECK(stbi_write_jpg_to_func(jpeg_append, &jpg, 3, 2, 3, image, 100) != 0);
    static unsigned char bmps[3][128], p6[64];
    int n = snprintf((char *)p6, sizeof p6, "P6\n#c\n3 2\n255\n");
    memcpy(p6 + n, image, sizeof image);
    starts[0] = p6, lens[0] = (size_t)n + sizeof image;
    starts[1] = bmps[0], lens[1] = top_down_bmp(bmps[0]);
    starts[2] = bmps[1], lens[2] = other_bmp(bmps[1], 0);
    starts[3] = bmps[2], lens[3] = other_bmp(bmps[2], 1);
    starts[4] = png.data, lens[4] = png.len;
    starts[5] = jpg.data, lens[5] = jpg.len;
    for (int f = 0; f < 6; f++) {
        for (int trail = 0; trail < 2; trail++) {
            memcpy(data, starts[f], lens[f]);
            memset(data + lens[f], trail ? 0xFF : 0, 1000);
            struct texture_image t;
            char why[128] = "", path[64];
            int rc = texture_decode(data, lens[f] + 1000 * (size_t)trail, &t, why, sizeof why);
            expect(rc == 0 && same_as_image(&t, f == 5 ? 90 : 0), "format %d, %d trailing: %s",
                   f, 1000 * trail, why);
            free(t.rgb);
            if (temp_file(data, lens[f] + 1000 * (size_t)trail, path, "") != 0)
                continue;
            rc = texture_load(path, &t, why, sizeof why);
            expect(rc == 0 && same_as_image(&t, f == 5 ? 90 : 0), "file %d, %d trailing: %s",
                   f, 1000 * trail, why);
            free(t.rgb);
            unlink(path);
        }
    }
    struct texture_image t;
    char why[128] = "";
    int rc = texture_load("/dev/zero", &t, why, sizeof why);
    expect(rc == -1 && strcmp(why, "not a BMP, PNG, JPEG or PPM image") == 0, "/dev/zero: %s",
           why);
    rc = texture_load("/tmp", &t, why, sizeof why);
    expect(rc == -1 && strcmp(why, "Is a directory") == 0, "a folder: %s", why);
    /* The pipe's writer: the P6, then zeros until the reader closes it
     * (SIGPIPE) or 10 s pass (SIGALRM). */
    int fds[2];
    CHECK(pipe(fds) == 0);
    pid_t child = fork();
    CHECK(child >= 0);
    if (child == 0) {
        close(fds[0]);
        alarm(10);
        static const unsigned char zeros[4096];
        if (write(fds[1], p6, lens[0]) == (ssize_t)lens[0])
            while (write(fds[1], zeros, sizeof zeros) > 0)
                ;
        _exit(0);
    }
    close(fds[1]);
    char path[64];
    snprintf(path, sizeof path, "/dev/fd/%d", fds[0]);
    rc = texture_load(path, &t, why, sizeof why);
    expect(rc == 0 && same_as_image(&t, 0), "P6 from a pipe: %s", rc ? why : "");
    free(t.rgb);
    close(fds[0]);
    int status = 0;
    waitpid(child, &status, 0);
    expect(WIFSIGNALED(status) && WTERMSIG(status) == SIGPIPE,
           "the pipe's writer ended otherwise than by SIGPIPE: %d", status);
}

static void test_step(void)
{
    uint8_t flat[2 * 3 * 3];
    memset(flat, 90, sizeof flat);
    struct texture_image t = {3, 2, flat};
    expect(texture_step(&t) == 0.0, "flat image: step %g", texture_step(&t));
    flat[(0 * 3 + 1) * 3 + 2] = 100; /* blue, middle of the top row: 10 */
    expect(texture_step(&t) == 10 / 255.0, "one texel 10 up: %g", texture_step(&t));
    for (int y = 0; y < 2; y++) /* red 0, 50, 100 across: 100 by the wrap */
        for (int x = 0; x < 3; x++)
            flat[(y * 3 + x) * 3 + 0] = (uint8_t)(50 * x);
    expect(texture_step(&t) == 100 / 255.0, "wrapped columns: %g", texture_step(&t));
    uint8_t tall[4 * 1 * 3] = {0, 0, 0, 0, 40, 0, 0, 80, 0, 0, 120, 0};
    struct texture_image column = {1, 4, tall}; /* green 0..120 down: 120 by the wrap */
    expect(texture_step(&column) == 120 / 255.0, "wrapped rows: %g", texture_step(&column));
    struct texture_image one = {3, 2, (uint8_t *)image};
    expect(texture_step(&one) == 1.0, "full steps: %g", texture_step(&one));
    uint8_t single[3] = {7, 8, 9};
    struct texture_image dot = {1, 1, single};
    expect(texture_step(&dot) == 0.0, "1 x 1: %g", texture_step(&dot));
}

int main(void)
{
    test_step();
    test_ppm();
    test_ppm_errors();
    test_files();
    test_jpeg_huffman();
    test_png_chunks();
    test_reads_as_needed();
    return unit_report();
}
