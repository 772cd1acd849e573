/* image_write.h: the rendered image to a file, atomically. */
#ifndef TP2_IMAGE_WRITE_H
#define TP2_IMAGE_WRITE_H

enum image_format { IMAGE_PPM, IMAGE_PNG, IMAGE_PFM, IMAGE_UNKNOWN };

/* The format named by path's extension (case-insensitive). */
enum image_format image_format_of(const char *path);

/* 8-bit value of a linear channel: clamped to [0, 1], round(255 c); NaN
 * gives 0. */
unsigned char image_quantize(float c);

/* Writes width x height pixels of rgba (4 floats each, rows top to bottom)
 * to path in the given format: first to a temporary file beside it, then
 * renamed over it, so path is never left half-written. Returns 0, or -1
 * after printing a "tp2: ..." message (the temporary file removed). */
int image_write(const char *path, enum image_format format, int width,
                int height, const float *rgba);

#endif
