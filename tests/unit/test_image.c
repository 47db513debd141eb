/* test_image.c - PNG round trip, reading other PNG layouts, atomic write, comparison metrics
 * against hand-computed values. */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <dirent.h>
#include <math.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "core/image.h"

static char dir[512];

static void scratch(char *path, size_t size, const char *name)
{
    snprintf(path, size, "%s/%s", dir, name);
}

static void test_round_trip(void **state)
{
    (void)state;
    enum { WW = 37, HH = 23 };
    uint8_t *px = malloc(WW * HH * 4);
    assert_non_null(px);
    for (int i = 0; i < WW * HH * 4; i++)
        px[i] = (uint8_t)((i * 7919u) >> 3);
    char path[600];
    scratch(path, sizeof path, "rt.png");
    struct swell_err err = { 0 };
    assert_int_equal(image_write_png(path, px, WW, HH, &err), 0);
    uint8_t *back = NULL;
    int w = 0, h = 0;
    assert_int_equal(image_read_png(path, &back, &w, &h, &err), 0);
    assert_int_equal(w, WW);
    assert_int_equal(h, HH);
    assert_memory_equal(back, px, WW * HH * 4);
    free(back);
    free(px);
    /* Atomic write leaves no temporary behind. */
    DIR *d = opendir(dir);
    assert_non_null(d);
    for (struct dirent *e; (e = readdir(d));)
        assert_null(strstr(e->d_name, ".tmp"));
    closedir(d);
}

/* A 16-bit grey PNG written with libpng directly: the reader must expand it to RGBA8. */
static void test_read_grey16(void **state)
{
    (void)state;
    char path[600];
    scratch(path, sizeof path, "grey16.png");
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png_create_info_struct(png);
    png_init_io(png, f);
    png_set_IHDR(png, info, 3, 2, 16, PNG_COLOR_TYPE_GRAY, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    /* big-endian samples; low bytes 0 so 16 -> 8 bits is exact whichever rounding is used */
    uint8_t rows[2][6] = { { 0, 0, 10, 0, 255, 0 }, { 128, 0, 1, 0, 77, 0 } };
    for (int y = 0; y < 2; y++)
        png_write_row(png, rows[y]);
    png_write_end(png, NULL);
    png_destroy_write_struct(&png, &info);
    fclose(f);
    uint8_t *px = NULL;
    int w = 0, h = 0;
    struct swell_err err = { 0 };
    assert_int_equal(image_read_png(path, &px, &w, &h, &err), 0);
    assert_int_equal(w, 3);
    assert_int_equal(h, 2);
    const uint8_t grey[6] = { 0, 10, 255, 128, 1, 77 };
    for (int i = 0; i < 6; i++) {
        assert_int_equal(px[i * 4 + 0], grey[i]);
        assert_int_equal(px[i * 4 + 1], grey[i]);
        assert_int_equal(px[i * 4 + 2], grey[i]);
        assert_int_equal(px[i * 4 + 3], 255);
    }
    free(px);
}

static void test_errors(void **state)
{
    (void)state;
    struct swell_err err = { 0 };
    uint8_t px[4] = { 1, 2, 3, 4 };
    assert_int_equal(image_write_png("/nonexistent-dir/x.png", px, 1, 1, &err), SWELL_E_IO);
    assert_non_null(strstr(err.msg, "/nonexistent-dir/x.png"));
    char path[600];
    scratch(path, sizeof path, "not.png");
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    fputs("this is not a png file at all", f);
    fclose(f);
    uint8_t *out = (uint8_t *)1;
    int w, h;
    assert_int_equal(image_read_png(path, &out, &w, &h, &err), SWELL_E_FORMAT);
    assert_null(out);
    assert_non_null(strstr(err.msg, path));
    assert_int_equal(image_write_png(path, px, 0, 1, &err), SWELL_E_ARG);
}

static void test_compare_metrics(void **state)
{
    (void)state;
    enum { WW = 8, HH = 5, N = WW * HH };
    uint8_t a[N * 4], b[N * 4];
    for (int i = 0; i < N * 4; i++)
        a[i] = b[i] = (uint8_t)(i * 3);
    struct image_diff d;
    image_compare(a, b, WW, HH, 0, &d);
    assert_int_equal(d.max_abs, 0);
    assert_int_equal(d.pixels_over, 0);
    assert_int_equal(d.first_x, -1);
    assert_true(d.rmse == 0.0);
    /* pixels 11..20: green + 3 (within tolerance 3); pixel 30 (x 6, y 3): blue - 200 */
    for (int i = 11; i <= 20; i++)
        b[i * 4 + 1] = (uint8_t)(a[i * 4 + 1] + 3);
    a[30 * 4 + 2] = 210;
    b[30 * 4 + 2] = 10;
    image_compare(a, b, WW, HH, 3, &d);
    assert_int_equal(d.max_abs, 200);
    assert_int_equal(d.pixels_over, 1);
    assert_int_equal(d.first_x, 6);
    assert_int_equal(d.first_y, 3);
    assert_int_equal(d.pixels, N);
    double want = sqrt((10.0 * 9.0 + 200.0 * 200.0) / (4.0 * N));
    assert_true(fabs(d.rmse - want) < 1e-9);
    image_compare(a, b, WW, HH, 2, &d);
    assert_int_equal(d.pixels_over, 11);
    assert_int_equal(d.first_x, 3);
    assert_int_equal(d.first_y, 1);
}

static void test_nonfinite(void **state)
{
    (void)state;
    float v[6] = { 0.0f, 1.0f, -2.0f, 3.0f, 4.0f, 5.0f };
    long first = 0;
    assert_int_equal(image_count_nonfinite(v, 6, &first), 0);
    assert_int_equal(first, -1);
    v[4] = NAN;
    v[2] = INFINITY;
    v[5] = -INFINITY;
    assert_int_equal(image_count_nonfinite(v, 6, &first), 3);
    assert_int_equal(first, 2);
}

int main(void)
{
    const char *base = getenv("SWELL_TMP");
    snprintf(dir, sizeof dir, "%s/test_image.XXXXXX", base && base[0] ? base : "/tmp");
    if (!mkdtemp(dir)) {
        perror(dir);
        return 1;
    }
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_round_trip),
        cmocka_unit_test(test_read_grey16),
        cmocka_unit_test(test_errors),
        cmocka_unit_test(test_compare_metrics),
        cmocka_unit_test(test_nonfinite),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
