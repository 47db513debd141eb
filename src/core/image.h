/* image.h - RGBA8 images: PNG write (atomic) and read, and comparison for frame tests.
 * Pixel layout everywhere: rows top first, 4 bytes per pixel (R, G, B, A), tightly packed,
 * as platform read_rgba returns them.
 */
#ifndef SWELL_IMAGE_H
#define SWELL_IMAGE_H

#include <stddef.h>
#include <stdint.h>
#include "core/err.h"

/* Write an 8-bit RGBA PNG atomically (encoded in memory, then fs_write_atomic: temp file in the
 * same directory + rename), so a reader never sees a half-written file. */
int image_write_png(const char *path, const uint8_t *rgba, int width, int height,
                    struct swell_err *err);

/* Read any PNG (palette, grey, 16-bit, with or without alpha) as RGBA8; *rgba is malloc'd. */
int image_read_png(const char *path, uint8_t **rgba, int *width, int *height,
                   struct swell_err *err);

struct image_diff {
    int max_abs;            /* largest |a - b| over every channel of every pixel, 0..255 */
    double rmse;            /* root mean square of a - b over every channel (alpha included) */
    long pixels_over;       /* pixels where any channel differs by more than the tolerance */
    long pixels;            /* width * height */
    int first_x, first_y;   /* first pixel over the tolerance (row-major from the top); -1 none */
};

/* Compare two width x height RGBA8 images with a per-channel tolerance. */
void image_compare(const uint8_t *a, const uint8_t *b, int width, int height, int tolerance,
                   struct image_diff *out);

/* Float read-backs (e.g. a half-float render target): count of NaN/Inf values among n, and the
 * index of the first one (or -1). RGBA8 cannot hold NaN, so this is where NaNs are caught. */
size_t image_count_nonfinite(const float *v, size_t n, long *first);

#endif
