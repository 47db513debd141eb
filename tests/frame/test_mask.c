/* test_mask.c - locally varying wave parameters by a coarse mask (issue 18 item 2; Bruneton et
 * al. 2010 §6, "calmer water in the lee of an island"; geometry/mask.h, render/mask.c) as an
 * embedding application sets it. Forced gles2-min unless a test compares tiers.
 *
 * - The calm: a moderate sea with a mask whose middle is still water (a = 0), seen from a
 *   boat's deck 30 m up: the texture energy (mean |dI/dx| of neighbouring pixels) of the
 *   pixels over the still water against the same pixels of the open sea's frame, and of the
 *   pixels where the mask is 1 against theirs: the still water loses its waves, the open sea
 *   keeps them. High and low quality on gles2-min, high on gles3 (its grid on the CPU).
 * - The surface under the camera: a camera 0.1 m above still water is raised to the
 *   clearance above z = 0 exactly (the drawn surface's height there is 0).
 * - The query: swell_sea_sample with the same mask gives still water where a = 0, the open
 *   sea's answers where a = 1, and heights scaled by a where the mask is uniform.
 * - Misuse: an ocean without a mask, bad sizes and origins, a NULL mask's bytes are refused
 *   with a message naming what is wrong.
 * Exit 77 (skip) only without an EGL device and CI unset (frame_util.h).
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include <GLES2/gl2.h>
#include "frame/frame_util.h"
#include "swell.h"

#define W 480
#define H 270
#define MN 16                   /* the mask's texels a side, 50 m each */
#define CALM_MAX 0.30           /* the still water's energy over the open sea's there */
#define OPEN_TOL 0.06           /* the open sea's energy with the mask within this of without */

static struct platform_handle g_ph;
static uint8_t g_open[4 * W * H], g_mask[4 * W * H];
static uint8_t g_amp[MN * MN];
static swell_mask g_m;

static swell_sea *bake(void)
{
    swell_sea *sea = NULL;
    struct swell_err err = { 0 };
    swell_sea_desc sd = { .preset = "moderate", .budget_bytes = 4u << 20 };
    if (swell_sea_bake(&sd, &sea, &err))
        fail_msg("swell_sea_bake: %s", err.msg);
    return sea;
}

static swell_ocean *ocean(const swell_sea *sea, int tier, int quality, int wave_mask)
{
    swell_ocean *o = NULL;
    struct swell_err err = { 0 };
    swell_ocean_desc od = { .tier = tier, .quality = quality, .sun_elev_deg = 40.0f,
                            .sun_azim_deg = 180.0f, .wave_mask = wave_mask };
    if (swell_ocean_create(sea, &od, &o, &err))
        fail_msg("swell_ocean_create: %s", err.msg);
    return o;
}

/* 800 m square about the origin; texels 5..10 across and 7..12 up still water (x in [-125,
 * 125] m, y in [-25, 225] m between their centres; off the middle in y, so a mask drawn upside
 * down fails), the rest the open sea. */
static void make_mask(void)
{
    for (int j = 0; j < MN; j++)
        for (int i = 0; i < MN; i++)
            g_amp[MN * j + i] = i >= 5 && i <= 10 && j >= 7 && j <= 12 ? 0 : 255;
    g_m = (swell_mask){ .amplitude = g_amp, .width = MN, .height = MN,
                        .origin_m = { -400.0, -400.0 }, .size_m = { 800.0, 800.0 } };
}

/* Still water (a = 0, with a 15 m margin) at world (x, y); the open sea (a = 1: past the
 * centres of the ring's texels, 175 and 75 m out, with a margin). */
static int still_at(double x, double y)
{
    return fabs(x) < 110.0 && y > -10.0 && y < 210.0;
}

static int open_at(double x, double y)
{
    return fabs(x) > 190.0 || y < -90.0 || y > 290.0;
}

/* The pixel's class by its flat sea point: 1 over still water, 2 over the open sea, else 0. */
static int pixel_class(const swell_view *v, int x, int y)
{
    double p[2];
    if (frame_sea_point(v, x, y, p))
        return 0;
    return still_at(p[0], p[1]) ? 1 : open_at(p[0], p[1]) ? 2 : 0;
}

/* Mean |dI/dx| (green) of horizontal neighbours both of class c. */
static double energy(const uint8_t *img, const swell_view *v, int c, int *count)
{
    double s = 0.0;
    int n = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x + 1 < W; x++)
            if (pixel_class(v, x, y) == c && pixel_class(v, x + 1, y) == c) {
                s += abs(img[4 * (y * W + x + 1) + 1] - img[4 * (y * W + x) + 1]);
                n++;
            }
    *count = n;
    return n ? s / n : 0.0;
}

static void draw(swell_ocean *o, const swell_view *v, const swell_mask *m, uint8_t *out)
{
    struct swell_err err = { 0 };
    if (swell_ocean_set_mask(o, m, &err))
        fail_msg("swell_ocean_set_mask: %s", err.msg);
    if (swell_ocean_draw(o, v, 3.0, &err))
        fail_msg("swell_ocean_draw: %s", err.msg);
    glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, out);
    if (getenv("MASK_DUMP")) {
        static int dumps;
        char name[512];
        snprintf(name, sizeof name, "%s%d.ppm", getenv("MASK_DUMP"), dumps++);
        FILE *f = fopen(name, "wb");
        fprintf(f, "P6 %d %d 255\n", W, H);
        for (int y = H - 1; y >= 0; y--)
            for (int x = 0; x < W; x++)
                fwrite(out + 4 * (y * W + x), 1, 3, f);
        fclose(f);
    }
}

static void calm(int tier, int quality, const char *name)
{
    make_mask();
    swell_sea *sea = bake();
    swell_ocean *o = ocean(sea, tier, quality, 1);
    swell_ocean_stats st;
    swell_ocean_get_stats(o, &st);
    assert_int_equal(st.objects, 1);
    swell_view v;
    const double eye[3] = { -250.0, 0.0, 30.0 };
    frame_app_view(&v, eye, 0.0, -15.0, W, H);
    draw(o, &v, NULL, g_open);
    draw(o, &v, &g_m, g_mask);
    int n1, n2, m1, m2;
    double e_calm_open = energy(g_open, &v, 1, &n1), e_calm = energy(g_mask, &v, 1, &m1);
    double e_sea_open = energy(g_open, &v, 2, &n2), e_sea = energy(g_mask, &v, 2, &m2);
    printf("%s: still water (%d pixel pairs): texture energy %.2f of 255 with the mask, %.2f "
           "without (%.3f); open sea (%d pairs): %.2f with, %.2f without (%.3f)\n", name, n1,
           e_calm, e_calm_open, e_calm / e_calm_open, n2, e_sea, e_sea_open,
           e_sea / e_sea_open);
    assert_true(n1 > 2000 && n2 > 2000);
    assert_true(e_calm_open > 0.5);   /* waves there to take away */
    assert_true(e_calm < CALM_MAX * e_calm_open);
    assert_true(fabs(e_sea / e_sea_open - 1.0) < OPEN_TOL);
    assert_int_equal(glGetError(), GL_NO_ERROR);
    swell_ocean_destroy(o);
    swell_sea_destroy(sea);
}

static void test_calm_gles2_min(void **state)
{
    (void)state;
    calm(SWELL_TIER_GLES2_MIN, SWELL_QUALITY_HIGH, "gles2-min high");
}

static void test_calm_low(void **state)
{
    (void)state;
    calm(SWELL_TIER_GLES2_MIN, SWELL_QUALITY_LOW, "gles2-min low");
}

static void test_calm_gles3(void **state)
{
    (void)state;
    calm(SWELL_TIER_GLES3, SWELL_QUALITY_HIGH, "gles3 high");
}

/* The camera 0.1 m above still water: the drawn surface under it is z = 0, so it is raised to
 * the clearance (0.3 m) above it, 0.2 m; without the mask the sea's own height decides. */
static void test_surface_under_camera(void **state)
{
    (void)state;
    make_mask();
    swell_sea *sea = bake();
    swell_ocean *o = ocean(sea, SWELL_TIER_GLES2_MIN, SWELL_QUALITY_HIGH, 1);
    swell_view v;
    const double eye[3] = { 10.0, 100.0, 0.1 };
    frame_app_view(&v, eye, 30.0, -5.0, W, H);
    swell_ocean_stats st[2];
    for (int k = 0; k < 2; k++) {
        draw(o, &v, k ? &g_m : NULL, g_mask);
        swell_ocean_get_stats(o, &st[k]);
    }
    printf("camera 0.1 m up: raised %.4f m on the open sea, %.6f m over still water\n",
           st[0].camera_raise_m, st[1].camera_raise_m);
    assert_float_equal(st[1].camera_raise_m, 0.2, 1e-6);
    assert_true(fabs(st[0].camera_raise_m - 0.2) > 1e-3);
    swell_ocean_destroy(o);
    swell_sea_destroy(sea);
}

/* swell_sea_sample with the mask: still water at a = 0, the open sea's answers at a = 1 (in
 * the mask's ring and outside it), and over a uniform mask of 128 the heights' RMS 128/255 of
 * the open sea's within 3 %. */
static void test_query(void **state)
{
    (void)state;
    make_mask();
    swell_sea *sea = bake();
    struct swell_err err = { 0 };
    enum { N = 400 };
    static double xy[2 * N];
    static swell_sample open[N], masked[N];
    for (int i = 0; i < N; i++) {
        xy[2 * i] = -600.0 + 3.0 * i;          /* across the still water and out */
        xy[2 * i + 1] = 40.0 + 0.37 * i;
    }
    assert_true(still_at(0.0, 110.0) && open_at(0.0, -100.0));
    swell_sample_desc d = { 0 };
    assert_int_equal(swell_sea_sample(sea, &d, xy, N, 2.5, open, &err), 0);
    d.mask = &g_m;
    assert_int_equal(swell_sea_sample(sea, &d, xy, N, 2.5, masked, &err), 0);
    int still = 0, same = 0;
    for (int i = 0; i < N; i++) {
        if (still_at(xy[2 * i], xy[2 * i + 1])) {
            still++;
            assert_float_equal(masked[i].height_m, 0.0, 0.0);
            assert_float_equal(masked[i].normal[2], 1.0f, 1e-7);
            assert_float_equal(masked[i].velocity[0], 0.0f, 0.0f);
            assert_float_equal(masked[i].displacement[0], 0.0, 0.0);
        } else if (open_at(xy[2 * i], xy[2 * i + 1])) {
            same++;
            assert_memory_equal(&masked[i], &open[i], sizeof open[i]);
        }
    }
    /* uniform 128 over the whole line */
    static uint8_t half[4];
    memset(half, 128, sizeof half);
    swell_mask hm = { .amplitude = half, .width = 2, .height = 2,
                      .origin_m = { -5000.0, -5000.0 }, .size_m = { 10000.0, 10000.0 } };
    d.mask = &hm;
    assert_int_equal(swell_sea_sample(sea, &d, xy, N, 2.5, masked, &err), 0);
    double s0 = 0.0, s1 = 0.0;
    for (int i = 0; i < N; i++) {
        s0 += open[i].height_m * open[i].height_m;
        s1 += masked[i].height_m * masked[i].height_m;
    }
    double ratio = sqrt(s1 / s0);
    printf("query: %d points still, %d the open sea's; a uniform 128/255 = %.4f: the heights' "
           "RMS %.4f of the open sea's\n", still, same, 128.0 / 255.0, ratio);
    assert_true(still > 50 && same > 150);
    assert_float_equal(ratio, 128.0 / 255.0, 0.03 * 128.0 / 255.0);
    swell_sea_destroy(sea);
}

static void test_misuse(void **state)
{
    (void)state;
    make_mask();
    swell_sea *sea = bake();
    swell_ocean *o = ocean(sea, SWELL_TIER_GLES2_MIN, SWELL_QUALITY_HIGH, 1);
    swell_ocean *plain = ocean(sea, SWELL_TIER_GLES2_MIN, SWELL_QUALITY_HIGH, 0);
    struct swell_err err = { 0 };
    assert_int_equal(swell_ocean_set_mask(plain, &g_m, &err), SWELL_E_ARG);
    printf("an ocean without a mask: %s\n", err.msg);
    assert_non_null(strstr(err.msg, "wave_mask = 1"));
    swell_mask m = g_m;
    m.width = 300;
    assert_int_equal(swell_ocean_set_mask(o, &m, &err), SWELL_E_ARG);
    printf("300 texels: %s\n", err.msg);
    assert_non_null(strstr(err.msg, "300 x 16"));
    m = g_m;
    m.size_m[1] = -5.0;
    assert_int_equal(swell_ocean_set_mask(o, &m, &err), SWELL_E_ARG);
    printf("size -5 m: %s\n", err.msg);
    assert_non_null(strstr(err.msg, "size_m[1]"));
    m = g_m;
    m.origin_m[0] = NAN;
    assert_int_equal(swell_ocean_set_mask(o, &m, &err), SWELL_E_ARG);
    printf("origin NaN: %s\n", err.msg);
    assert_non_null(strstr(err.msg, "origin"));
    m = g_m;
    m.amplitude = NULL;
    assert_int_equal(swell_ocean_set_mask(o, &m, &err), SWELL_E_ARG);
    printf("no bytes: %s\n", err.msg);
    swell_sample_desc d = { .mask = &m };
    double xy[2] = { 0.0, 0.0 };
    swell_sample s;
    assert_int_equal(swell_sea_sample(sea, &d, xy, 1, 0.0, &s, &err), SWELL_E_ARG);
    printf("query, no bytes: %s\n", err.msg);
    assert_non_null(strstr(err.msg, "swell_sea_sample"));
    assert_int_equal(swell_ocean_set_mask(o, &g_m, &err), 0);
    assert_int_equal(swell_ocean_set_mask(o, NULL, &err), 0);
    assert_int_equal(glGetError(), GL_NO_ERROR);
    swell_ocean_destroy(plain);
    swell_ocean_destroy(o);
    swell_sea_destroy(sea);
}

int main(void)
{
    int rc = frame_open("test_mask", W, H, &g_ph);
    if (rc)
        return rc;
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_calm_gles2_min),
        cmocka_unit_test(test_calm_low),
        cmocka_unit_test(test_calm_gles3),
        cmocka_unit_test(test_surface_under_camera),
        cmocka_unit_test(test_query),
        cmocka_unit_test(test_misuse),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
