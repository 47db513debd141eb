/* test_wake.c - the Kelvin wake (issue 18; Bruneton et al. 2010 §6, local waves;
 * geometry/kelvin.h, render/wake.c) as an embedding application sets it: frames of a calm sea
 * with and without the wake of a 9 m hull, everything else equal, so every changed pixel is
 * the wake's. Forced gles2-min unless a test compares tiers.
 *
 * - The wedge: each changed pixel is taken back to the flat sea (the camera's own ray met with
 *   z = 0) and into the hull's frame; the outermost angle from the track, seen from the bow, of
 *   the changed pixels in each band of distance behind it is the wake's half-angle: 19.5 deg
 *   +- 1.5 at two speeds (the pattern's size scales with U^2, its angle does not).
 * - Resolution: Bruneton's test, the mean of each row of the wake's change (frame with less
 *   frame without) at 480 x 270 and at 960 x 540 box-filtered to 480 x 270, within a stated
 *   share of the row's mean; distant waves average out of the slopes into the variance.
 * - Tiers: gles2-min and gles3 draw the same wake (its angle, the change's mean).
 * - Qualities: low quality draws high's wake, row by row (its variance too).
 * - Misuse: an ocean without wakes, out-of-range speeds and hulls are refused with a message.
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
#define HULL 9.0
#define ANGLE_MIN 18.0            /* issue 18: 19.5 +- 1.5 deg */
#define ANGLE_MAX 21.0

static struct platform_handle g_ph;
static uint8_t g_a[4 * W * H * 4], g_b[4 * W * H * 4];

static swell_sea *bake(void)
{
    swell_sea *sea = NULL;
    struct swell_err err = { 0 };
    swell_sea_desc sd = { .preset = "calm", .wind_speed_mps = 1.0f, .budget_bytes = 4u << 20 };
    if (swell_sea_bake(&sd, &sea, &err))
        fail_msg("swell_sea_bake: %s", err.msg);
    return sea;
}

static int g_quality;   /* enum swell_quality of the oceans made (default high) */
static swell_ocean *ocean_sun(const swell_sea *sea, int tier, int wakes, float elev, float azim)
{
    swell_ocean *o = NULL;
    struct swell_err err = { 0 };
    swell_ocean_desc od = { .tier = tier, .sun_elev_deg = elev, .sun_azim_deg = azim,
                            .wakes = wakes, .quality = g_quality };
    if (swell_ocean_create(sea, &od, &o, &err))
        fail_msg("swell_ocean_create: %s", err.msg);
    return o;
}

static swell_ocean *ocean(const swell_sea *sea, int tier, int wakes)
{
    return ocean_sun(sea, tier, wakes, 35.0f, 200.0f);
}

/* The hull at the origin sailing east at speed; the camera behind its wake, looking along the
 * track at it from above, at a distance and height in proportion to the wake's length (the
 * pattern scales with U^2). Viewport scale x (W x H) / 2. */
static void wake_view(double speed, int scale, swell_view *v)
{
    double lt = 2.0 * M_PI * speed * speed / 9.81;   /* the transverse wavelength */
    double eye[3] = { -28.0 * lt, 0.0, 8.0 * lt };
    frame_app_view(v, eye, 0.0, -18.0, W * scale / 2, H * scale / 2);
}

/* Frames without (g_a) and with (g_b) the wake at t. */
static void wake_frames(swell_ocean *o, const swell_view *v, double speed, double t)
{
    struct swell_err err = { 0 };
    int n = v->viewport[2] * v->viewport[3] * 4;
    assert_int_equal(swell_ocean_set_wake(o, NULL, &err), 0);
    if (swell_ocean_draw(o, v, t, &err))
        fail_msg("swell_ocean_draw: %s", err.msg);
    glReadPixels(0, 0, v->viewport[2], v->viewport[3], GL_RGBA, GL_UNSIGNED_BYTE, g_a);
    swell_wake wk = { .heading_deg = 0.0f, .speed_mps = (float)speed,
                      .hull_length_m = (float)HULL, .beam_m = 3.0f };
    if (swell_ocean_set_wake(o, &wk, &err))
        fail_msg("swell_ocean_set_wake: %s", err.msg);
    if (swell_ocean_draw(o, v, t, &err))
        fail_msg("swell_ocean_draw: %s", err.msg);
    glReadPixels(0, 0, v->viewport[2], v->viewport[3], GL_RGBA, GL_UNSIGNED_BYTE, g_b);
    (void)n;
    if (getenv("WAKE_DUMP")) {
        static int dumps;
        char name[512];
        snprintf(name, sizeof name, "%s%d.ppm", getenv("WAKE_DUMP"), dumps++);
        FILE *f = fopen(name, "wb");
        int w = v->viewport[2], h = v->viewport[3];
        fprintf(f, "P6 %d %d 255\n", w, 2 * h);
        for (int y = h - 1; y >= 0; y--)
            for (int x = 0; x < w; x++)
                fwrite(g_b + 4 * (y * w + x), 1, 3, f);
        for (int y = h - 1; y >= 0; y--)
            for (int x = 0; x < w; x++)
                fwrite(g_a + 4 * (y * w + x), 1, 3, f);
        fclose(f);
    }
}

static int changed(int i)
{
    int d = 0;
    for (int c = 0; c < 3; c++)
        d = abs(g_a[4 * i + c] - g_b[4 * i + c]) > d ? abs(g_a[4 * i + c] - g_b[4 * i + c]) : d;
    return d;
}

/* The wake's half-angle: per band of distance behind the bow (from 0.2 to 0.7 of the map's
 * length, in 10 bands), the largest angle from the track of a pixel changed by more than 2 of
 * 255; their median. Also the number of changed pixels. */
static double half_angle(const swell_view *v, double speed, int *count)
{
    double lt = 2.0 * M_PI * speed * speed / 9.81, behind = fmax(24.0 * lt, 6.0 * HULL);
    double band_max[10] = { 0 };
    int w = v->viewport[2], h = v->viewport[3], n = 0;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            double p[2];
            if (changed(y * w + x) <= 2 || frame_sea_point(v, x, y, p))
                continue;
            n++;
            double bx = 0.5 * HULL - p[0], by = fabs(p[1]);
            int band = (int)floor((bx / behind - 0.2) / 0.05);
            if (band < 0 || band >= 10)
                continue;
            band_max[band] = fmax(band_max[band], atan2(by, bx) * 180.0 / M_PI);
        }
    /* insertion sort, then the median */
    for (int i = 1; i < 10; i++)
        for (int j = i; j > 0 && band_max[j] < band_max[j - 1]; j--) {
            double t = band_max[j];
            band_max[j] = band_max[j - 1];
            band_max[j - 1] = t;
        }
    printf("  U %.0f m/s: %d pixels changed; edge angle per band %.2f .. %.2f deg, median "
           "%.2f\n", speed, n, band_max[0], band_max[9], 0.5 * (band_max[4] + band_max[5]));
    *count = n;
    return 0.5 * (band_max[4] + band_max[5]);
}

static void wedge(int tier, double *angles)
{
    swell_sea *sea = bake();
    swell_ocean *o = ocean(sea, tier, 1);
    const double speeds[2] = { 3.0, 6.0 };
    printf("tier %d:\n", tier);
    for (int i = 0; i < 2; i++) {
        swell_view v;
        wake_view(speeds[i], 2, &v);
        wake_frames(o, &v, speeds[i], 2.0);
        int n = 0;
        angles[i] = half_angle(&v, speeds[i], &n);
        assert_true(n > W * H / 20);
        assert_true(angles[i] >= ANGLE_MIN && angles[i] <= ANGLE_MAX);
    }
    swell_ocean_destroy(o);
    swell_sea_destroy(sea);
}

static void test_wedge_gles2_min(void **state)
{
    (void)state;
    double a[2];
    wedge(SWELL_TIER_GLES2_MIN, a);
}

/* gles3 (vertex texture fetch, per-pixel LOD) draws the same wake: its angle within 0.5 deg
 * of gles2-min's, and the mean change over the frame within 25 %. */
static void test_tiers(void **state)
{
    (void)state;
    double a2[2], a3[2];
    wedge(SWELL_TIER_GLES2_MIN, a2);
    swell_sea *sea = bake();
    double mean[2];
    for (int k = 0; k < 2; k++) {
        swell_ocean *o = ocean(sea, k ? SWELL_TIER_GLES3 : SWELL_TIER_GLES2_MIN, 1);
        swell_view v;
        wake_view(4.0, 2, &v);
        wake_frames(o, &v, 4.0, 2.0);
        double s = 0.0;
        for (int i = 0; i < W * H; i++)
            s += changed(i);
        mean[k] = s / (W * H);
        swell_ocean_destroy(o);
    }
    swell_sea_destroy(sea);
    wedge(SWELL_TIER_GLES3, a3);
    printf("gles2-min vs gles3: angles %.2f / %.2f and %.2f / %.2f deg; mean change %.3f / "
           "%.3f of 255\n", a2[0], a3[0], a2[1], a3[1], mean[0], mean[1]);
    assert_true(fabs(a2[0] - a3[0]) <= 0.5 && fabs(a2[1] - a3[1]) <= 0.5);
    assert_true(mean[1] > 0.75 * mean[0] && mean[1] < 1.25 * mean[0]);
}

/* Bruneton's test with a wake: each row's mean change at 240 x 135 and at 960 x 540
 * box-filtered to it (two mip levels finer), within ROW_TOL of the row's mean where the wake
 * changes the row by 0.5 of 255 or more. */
#define ROW_TOL 0.03
static void row_changes(const swell_view *v, int scale, double *rows, double *level)
{
    int w = v->viewport[2];
    for (int y = 0; y < H / 2; y++) {
        double s = 0.0, l = 0.0;
        for (int yy = 0; yy < scale; yy++)
            for (int x = 0; x < w; x++) {
                int i = (y * scale + yy) * w + x;
                for (int c = 0; c < 3; c++) {
                    s += g_b[4 * i + c] - g_a[4 * i + c];
                    l += g_a[4 * i + c];
                }
            }
        rows[y] = s / (3.0 * w * scale);
        level[y] = l / (3.0 * w * scale);
    }
}

static void rows_resolution(void)
{
    swell_sea *sea = bake();
    /* the sun ahead, low: its glitter along the track, where the wake's unresolved variance
     * widens it */
    swell_ocean *o = ocean_sun(sea, SWELL_TIER_GLES2_MIN, 1, 12.0f, 0.0f);
    double rows[2][H / 2], level[2][H / 2];
    for (int k = 0; k < 2; k++) {
        swell_view v;
        wake_view(4.0, k ? 4 : 1, &v);
        wake_frames(o, &v, 4.0, 2.0);
        row_changes(&v, k ? 4 : 1, rows[k], level[k]);
    }
    double worst = 0.0, biggest = 0.0;
    int at = -1, held = 0;
    for (int y = 0; y < H / 2; y++) {
        if (fabs(rows[1][y]) < 0.5)
            continue;
        held++;
        biggest = fmax(biggest, fabs(rows[1][y]));
        double d = fabs(rows[0][y] - rows[1][y]) / fmax(level[1][y], 1.0);
        if (d > worst) {
            worst = d;
            at = y;
        }
    }
    printf("rows the wake changes by 0.5 of 255 or more: %d (largest row change %.1f); the two "
           "resolutions' row changes differ by %.2f %% of the row's mean at most (row %d: "
           "%.2f vs %.2f)\n", held, biggest, 100.0 * worst, at, at >= 0 ? rows[0][at] : 0.0,
           at >= 0 ? rows[1][at] : 0.0);
    assert_true(held > H / 8);
    assert_true(worst <= ROW_TOL);
    swell_ocean_destroy(o);
    swell_sea_destroy(sea);
}

static void test_rows_resolution(void **state)
{
    (void)state;
    rows_resolution();
}

/* The same in low quality (Hu's single pass, the variance per vertex): the wake's variance
 * within a fetch joins the pixel's there too (ocean.frag), so its glitter widens as high
 * quality's does. */
static void test_rows_resolution_low(void **state)
{
    (void)state;
    g_quality = SWELL_QUALITY_LOW;
    rows_resolution();
    g_quality = SWELL_QUALITY_HIGH;
}

/* Low quality draws the wake high quality draws (issue 14's rule: the same sea, cheaper):
 * with the sun low ahead, its glitter along the track, each row's change by the wake at
 * 240 x 135 in low quality against high's, over the rows high's changes by 0.5 of 255 or
 * more: the mean |low - high| within LOW_TOL of the mean |high|. Measured 1.8 %; before low
 * quality took the wake's variance (ocean.frag), 23.6 %: the rows near the horizon, where the
 * wake's waves average out of the slopes, lost their widened glitter (changes of +1-2.5 of
 * 255 drawn as -1-0). */
#define LOW_TOL 0.05
static void test_low_quality(void **state)
{
    (void)state;
    swell_sea *sea = bake();
    double rows[2][H / 2], level[2][H / 2];
    for (int q = 0; q < 2; q++) {
        g_quality = q ? SWELL_QUALITY_LOW : SWELL_QUALITY_HIGH;
        swell_ocean *o = ocean_sun(sea, SWELL_TIER_GLES2_MIN, 1, 12.0f, 0.0f);
        swell_view v;
        wake_view(4.0, 1, &v);
        wake_frames(o, &v, 4.0, 2.0);
        row_changes(&v, 1, rows[q], level[q]);
        swell_ocean_destroy(o);
    }
    g_quality = SWELL_QUALITY_HIGH;
    double diff = 0.0, size = 0.0;
    int held = 0;
    for (int y = 0; y < H / 2; y++) {
        if (fabs(rows[0][y]) < 0.5)
            continue;
        held++;
        diff += fabs(rows[0][y] - rows[1][y]);
        size += fabs(rows[0][y]);
        if (getenv("WAKE_ROWS"))
            printf("  row %d: the wake's change high %.2f low %.2f (the row's mean %.1f)\n", y,
                   rows[0][y], rows[1][y], level[0][y]);
    }
    printf("low vs high quality, the wake's change per row over %d rows: mean |low - high| "
           "%.3f of 255, %.1f %% of the mean change %.3f\n", held, diff / held,
           100.0 * diff / size, size / held);
    assert_true(held > H / 8);
    assert_true(diff <= LOW_TOL * size);
    swell_sea_destroy(sea);
}

static void test_misuse(void **state)
{
    (void)state;
    swell_sea *sea = bake();
    swell_ocean *o = ocean(sea, SWELL_TIER_GLES2_MIN, 1), *plain = ocean(sea, SWELL_TIER_GLES2_MIN, 0);
    struct swell_err err = { 0 };
    swell_wake wk = { .speed_mps = 5.0f };
    assert_int_equal(swell_ocean_set_wake(plain, &wk, &err), SWELL_E_ARG);
    printf("an ocean without wakes: %s\n", err.msg);
    assert_non_null(strstr(err.msg, "wakes = 1"));
    wk.speed_mps = 45.0f;
    assert_int_equal(swell_ocean_set_wake(o, &wk, &err), SWELL_E_ARG);
    printf("45 m/s: %s\n", err.msg);
    assert_non_null(strstr(err.msg, "speed 45"));
    wk.speed_mps = 5.0f;
    wk.hull_length_m = 1000.0f;
    assert_int_equal(swell_ocean_set_wake(o, &wk, &err), SWELL_E_ARG);
    printf("a 1 km hull: %s\n", err.msg);
    wk.hull_length_m = 0.0f;
    wk.position_m[0] = NAN;
    assert_int_equal(swell_ocean_set_wake(o, &wk, &err), SWELL_E_ARG);
    printf("position NaN: %s\n", err.msg);
    wk.position_m[0] = 0.0;
    assert_int_equal(swell_ocean_set_wake(o, &wk, &err), 0);
    assert_int_equal(swell_ocean_set_wake(o, NULL, &err), 0);
    assert_int_equal(glGetError(), GL_NO_ERROR);
    swell_ocean_destroy(plain);
    swell_ocean_destroy(o);
    swell_sea_destroy(sea);
}

int main(void)
{
    int rc = frame_open("test_wake", 2 * W, 2 * H, &g_ph);
    if (rc)
        return rc;
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_wedge_gles2_min),
        cmocka_unit_test(test_tiers),
        cmocka_unit_test(test_rows_resolution),
        cmocka_unit_test(test_rows_resolution_low),
        cmocka_unit_test(test_low_quality),
        cmocka_unit_test(test_misuse),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
