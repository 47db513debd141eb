/* image.c - PNG via libpng, atomic writes, image comparison (image.h). */
#include "core/image.h"

#include <errno.h>
#include <math.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/fsutil.h"

/* PNG bytes accumulate in memory, then fs_write_atomic replaces the file in one step
 * (STYLE.md 10): a reader never sees a half-written image. */
static void mem_write(png_structp png, png_bytep data, size_t len)
{
    membuf_add(png_get_io_ptr(png), data, len);
}

static void mem_flush(png_structp png)
{
    (void)png;
}

/* libpng reports failure by longjmp; the setjmp lives in a function whose locals do not change
 * after it. Returns 0 on success. Rows are already top first. */
static int png_encode(struct membuf *m, png_bytep *rows, int width, int height, char *why,
                      size_t why_size)
{
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    if (!png) {
        snprintf(why, why_size, "png_create_write_struct failed");
        return -1;
    }
    png_infop info = png_create_info_struct(png);
    if (!info) {
        png_destroy_write_struct(&png, NULL);
        snprintf(why, why_size, "png_create_info_struct failed");
        return -1;
    }
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        snprintf(why, why_size, "libpng error while encoding");
        return -1;
    }
    png_set_write_fn(png, m, mem_write, mem_flush);
    png_set_IHDR(png, info, (png_uint_32)width, (png_uint_32)height, 8, PNG_COLOR_TYPE_RGBA,
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    png_write_image(png, rows);
    png_write_end(png, NULL);
    png_destroy_write_struct(&png, &info);
    if (m->oom) {
        snprintf(why, why_size, "out of memory");
        return -1;
    }
    return 0;
}

int image_write_png(const char *path, const uint8_t *rgba, int width, int height,
                    struct swell_err *err)
{
    if (!path || !rgba || width < 1 || height < 1 || width > 32768 || height > 32768)
        return swell_fail(err, SWELL_E_ARG, "image: nothing to write to %s (%dx%d)",
                          path ? path : "NULL", width, height);
    png_bytep *rows = malloc((size_t)height * sizeof *rows);
    if (!rows)
        return swell_fail(err, SWELL_E_NOMEM, "image: no memory for %d row pointers", height);
    for (int y = 0; y < height; y++)
        rows[y] = (png_bytep)(rgba + (size_t)y * (size_t)width * 4);
    struct membuf m = { 0 };
    char why[128];
    int rc = SWELL_OK;
    if (png_encode(&m, rows, width, height, why, sizeof why) != 0)
        rc = swell_fail(err, SWELL_E_IO, "image: encoding %s: %s", path, why);
    else
        rc = fs_write_atomic(path, m.p, m.n, err);
    free(m.p);
    free(rows);
    return rc;
}

static int png_decode(FILE *f, uint8_t **out, int *width, int *height, char *why, size_t why_size)
{
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    if (!png) {
        snprintf(why, why_size, "png_create_read_struct failed");
        return -1;
    }
    png_infop info = png_create_info_struct(png);
    /* Volatile: assigned after setjmp and needed by the longjmp path. */
    uint8_t *volatile pixels = NULL;
    png_bytep *volatile rows = NULL;
    if (!info || setjmp(png_jmpbuf(png))) {
        png_destroy_read_struct(&png, info ? &info : NULL, NULL);
        free(pixels);
        free(rows);
        snprintf(why, why_size, "not a PNG, or a damaged one");
        return -1;
    }
    png_init_io(png, f);
    png_read_info(png, info);
    png_uint_32 w = png_get_image_width(png, info), h = png_get_image_height(png, info);
    if (w == 0 || h == 0 || w > 32768 || h > 32768) {
        png_destroy_read_struct(&png, &info, NULL);
        snprintf(why, why_size, "size %ux%u outside 1..32768", (unsigned)w, (unsigned)h);
        return -1;
    }
    /* Normalise every colour type and depth to 8-bit RGBA. */
    png_set_expand(png);
    png_set_strip_16(png);
    png_set_gray_to_rgb(png);
    png_set_add_alpha(png, 0xff, PNG_FILLER_AFTER);
    png_read_update_info(png, info);
    pixels = malloc((size_t)w * h * 4);
    rows = malloc((size_t)h * sizeof(png_bytep));
    if (!pixels || !rows) {
        png_destroy_read_struct(&png, &info, NULL);
        free(pixels);
        free(rows);
        snprintf(why, why_size, "no memory for %ux%u pixels", (unsigned)w, (unsigned)h);
        return -1;
    }
    for (png_uint_32 y = 0; y < h; y++)
        rows[y] = pixels + (size_t)y * w * 4;
    png_read_image(png, rows);
    png_read_end(png, NULL);
    png_destroy_read_struct(&png, &info, NULL);
    free(rows);
    *out = pixels;
    *width = (int)w;
    *height = (int)h;
    return 0;
}

int image_read_png(const char *path, uint8_t **rgba, int *width, int *height,
                   struct swell_err *err)
{
    *rgba = NULL;
    *width = *height = 0;
    FILE *f = fopen(path, "rb");
    if (!f)
        return swell_fail(err, SWELL_E_IO, "image: cannot open %s: %s", path, strerror(errno));
    char why[128];
    int bad = png_decode(f, rgba, width, height, why, sizeof why);
    fclose(f);
    if (bad)
        return swell_fail(err, SWELL_E_FORMAT, "image: reading %s: %s", path, why);
    return SWELL_OK;
}

void image_compare(const uint8_t *a, const uint8_t *b, int width, int height, int tolerance,
                   struct image_diff *out)
{
    memset(out, 0, sizeof *out);
    out->first_x = out->first_y = -1;
    out->pixels = (long)width * height;
    double sum_sq = 0.0;
    for (long i = 0; i < out->pixels; i++) {
        int over = 0;
        for (int c = 0; c < 4; c++) {
            int d = abs((int)a[i * 4 + c] - (int)b[i * 4 + c]);
            sum_sq += (double)d * d;
            if (d > out->max_abs)
                out->max_abs = d;
            if (d > tolerance)
                over = 1;
        }
        if (over) {
            if (out->pixels_over == 0) {
                out->first_x = (int)(i % width);
                out->first_y = (int)(i / width);
            }
            out->pixels_over++;
        }
    }
    out->rmse = out->pixels ? sqrt(sum_sq / (4.0 * (double)out->pixels)) : 0.0;
}

size_t image_count_nonfinite(const float *v, size_t n, long *first)
{
    size_t count = 0;
    if (first)
        *first = -1;
    for (size_t i = 0; i < n; i++) {
        if (!isfinite(v[i])) {
            if (count == 0 && first)
                *first = (long)i;
            count++;
        }
    }
    return count;
}
