/* image_write.h: the rendered image to a file, streamed and atomic.
 *
 * An image_writer creates a temporary file beside the output before the
 * render starts (so an output that cannot be written is found at once),
 * takes the rows top to bottom as the render produces them, and on finish
 * renames the temporary file over the output: the output is never left
 * half-written, and the whole image is never held in memory. */
#ifndef TP2_IMAGE_WRITE_H
#define TP2_IMAGE_WRITE_H

#include <stdint.h>

enum image_format { IMAGE_PPM, IMAGE_PNG, IMAGE_PFM, IMAGE_UNKNOWN };

/* The format named by path's extension (case-insensitive). */
enum image_format image_format_of(const char *path);

/* 8-bit value of a linear channel: clamped to [0, 1], round(255 c); NaN
 * gives 0. */
unsigned char image_quantize(float c);

struct image_writer;

/* Starts writing a width x height image to path: refuses a path that is a
 * directory or another non-regular file, then creates the temporary file
 * ".tp2-XXXXXX" in path's folder (short, so any name that fits NAME_MAX
 * works), registered for removal on SIGINT/SIGTERM/SIGHUP (tempfile.h).
 * Returns the writer, or NULL after printing
 * "tp2: cannot write 'PATH': REASON" (nothing left behind). */
struct image_writer *image_writer_open(const char *path, enum image_format format,
                                       int width, int height);

/* Writes the next `rows` rows of rgba (width * 4 floats each, alpha
 * ignored), in order from the top. Returns 0, or -1 after a message; then
 * only image_writer_abort remains to be called. */
int image_writer_rows(struct image_writer *w, const float *rgba, int rows);

/* The same for rows of 8-bit values already quantized (width words
 * r | g << 8 | b << 16 each; the renderer's, quantized on the device),
 * into a PPM or PNG file. */
int image_writer_rows_rgba8(struct image_writer *w, const uint32_t *words, int rows);

/* After all rows: completes and closes the file, gives it the mode of the
 * output it replaces (a new file: 0666 & ~umask), renames it over the
 * output and frees w. Returns 0, or -1 after a message (the temporary file
 * removed, an existing output untouched). */
int image_writer_finish(struct image_writer *w);

/* Removes the temporary file and frees w; w may be NULL. */
void image_writer_abort(struct image_writer *w);

/* The whole image at once (rgba: width * height * 4 floats, rows top to
 * bottom) through the calls above. Returns 0 or -1 after a message. */
int image_write(const char *path, enum image_format format, int width,
                int height, const float *rgba);

#endif
