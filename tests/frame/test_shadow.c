/* test_shadow.c - the sun's shadows of the application's objects (issue 18; Bruneton et al.
 * 2010 §6; render/shadow.c) as an embedding application draws them: a flat board 10 m square,
 * 5 m above a calm sea, drawn into swell's shadow pass with the pass's matrices (and nowhere
 * else), and the frame of the sea compared with the same frame drawn without a pass, so every
 * changed pixel is the shadow. Forced gles2-min unless a test compares tiers.
 *
 * - Where: each darkened pixel is taken back to the flat sea (the camera's ray met with z = 0);
 *   the shadow's centroid lies where the sun direction puts the board's, within 0.5 m; nearly
 *   all of it inside the predicted square (+ 1 m); its area the board's within 25 %.
 * - Darkness: in the shadow the water body keeps the sky's light only: the mean darkening
 *   there is the sun's share of it (positive, the frame darker).
 * - Tiers: gles3 puts the shadow at the same place (centroids within 0.3 m).
 * - Misuse: an ocean without shadows, two passes at once, an end without a begin are refused.
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
#define BX 40.0                  /* the board's centre, m */
#define BY 0.0
#define BZ 5.0                   /* its height */
#define BH 5.0                   /* half its side */
#define SUN_ELEV 40.0
#define SUN_AZIM 90.0            /* the sun in the north: the shadow falls south */

static struct platform_handle g_ph;
static GLuint g_prog;
static uint8_t g_a[W * H * 4], g_b[W * H * 4];

static swell_ocean *ocean(const swell_sea *sea, int tier, int shadows)
{
    swell_ocean *o = NULL;
    struct swell_err err = { 0 };
    swell_ocean_desc od = { .tier = tier, .sun_elev_deg = (float)SUN_ELEV,
                            .sun_azim_deg = (float)SUN_AZIM, .shadows = shadows };
    if (swell_ocean_create(sea, &od, &o, &err))
        fail_msg("swell_ocean_create: %s", err.msg);
    return o;
}

static swell_sea *bake(void)
{
    swell_sea *sea = NULL;
    struct swell_err err = { 0 };
    swell_sea_desc sd = { .preset = "calm", .wind_speed_mps = 2.0f, .budget_bytes = 4u << 20 };
    if (swell_sea_bake(&sd, &sea, &err))
        fail_msg("swell_sea_bake: %s", err.msg);
    return sea;
}

static void view_of(swell_view *v)
{
    static const double eye[3] = { 0.0, 0.0, 40.0 };
    frame_app_view(v, eye, 0.0, -45.0, W, H);
}

struct shadow_stats {
    int n;                       /* pixels darkened by more than 2 of 255 */
    double cx, cy;               /* their sea points' centroid, m */
    double inside;               /* the share inside the predicted square + 1 m */
    double area;                 /* the sea area they cover, m^2 */
    double dark;                 /* their mean darkening, of 255 */
};

static void shadow_frames(swell_ocean *o, const swell_view *v, struct shadow_stats *st)
{
    struct swell_err err = { 0 };
    if (swell_ocean_draw(o, v, 1.0, &err))
        fail_msg("swell_ocean_draw: %s", err.msg);
    glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, g_a);
    swell_pass pass;
    if (swell_ocean_begin_shadow(o, v, NULL, &pass, &err))
        fail_msg("swell_ocean_begin_shadow: %s", err.msg);
    const double board[4][3] = { { BX - BH, BY - BH, BZ }, { BX + BH, BY - BH, BZ },
                                 { BX - BH, BY + BH, BZ }, { BX + BH, BY + BH, BZ } };
    frame_draw_quad(g_prog, pass.view, pass.proj, pass.camera_pos, board);
    if (swell_ocean_end_shadow(o, &err))
        fail_msg("swell_ocean_end_shadow: %s", err.msg);
    if (swell_ocean_draw(o, v, 1.0, &err))
        fail_msg("swell_ocean_draw: %s", err.msg);
    glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, g_b);
    /* the board's shadow: its centre moved away from the sun by BZ / tan(elevation) */
    double off = BZ / tan(SUN_ELEV * M_PI / 180.0), az = SUN_AZIM * M_PI / 180.0;
    double px = BX - off * cos(az), py = BY - off * sin(az);
    memset(st, 0, sizeof *st);
    double sx = 0, sy = 0, in = 0, dark = 0, area = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            const uint8_t *a = g_a + 4 * (y * W + x), *b = g_b + 4 * (y * W + x);
            double d = ((a[0] - b[0]) + (a[1] - b[1]) + (a[2] - b[2])) / 3.0;
            double p[2], q[2], r[2];
            if (d <= 2.0 || frame_sea_point(v, x, y, p))
                continue;
            st->n++;
            sx += p[0];
            sy += p[1];
            dark += d;
            in += fabs(p[0] - px) <= BH + 1.0 && fabs(p[1] - py) <= BH + 1.0;
            /* the pixel's area on the sea: its neighbours' points */
            if (!frame_sea_point(v, x + 1, y, q) && !frame_sea_point(v, x, y + 1, r))
                area += fabs((q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]));
        }
    if (st->n) {
        st->cx = sx / st->n;
        st->cy = sy / st->n;
        st->inside = in / st->n;
        st->dark = dark / st->n;
        st->area = area;
    }
    printf("  predicted centre (%.2f, %.2f); %d pixels darkened by %.1f of 255 on average, "
           "centroid (%.2f, %.2f), %.1f %% inside, %.1f m^2 (the board's %.0f)\n", px, py,
           st->n, st->dark, st->cx, st->cy, 100.0 * st->inside, st->area, 4.0 * BH * BH);
    assert_true(st->n > 100);
    assert_true(hypot(st->cx - px, st->cy - py) < 0.5);
    assert_true(st->inside > 0.95);
    assert_true(fabs(st->area / (4.0 * BH * BH) - 1.0) < 0.25);
    assert_true(st->dark > 4.0);
}

static void test_where_gles2_min(void **state)
{
    (void)state;
    swell_sea *sea = bake();
    swell_ocean *o = ocean(sea, SWELL_TIER_GLES2_MIN, 1);
    swell_view v;
    view_of(&v);
    struct shadow_stats st;
    printf("gles2-min:\n");
    shadow_frames(o, &v, &st);
    swell_ocean_destroy(o);
    swell_sea_destroy(sea);
}

static void test_tiers(void **state)
{
    (void)state;
    swell_sea *sea = bake();
    struct shadow_stats st[2];
    for (int k = 0; k < 2; k++) {
        swell_ocean *o = ocean(sea, k ? SWELL_TIER_GLES3 : SWELL_TIER_GLES2_MIN, 1);
        swell_view v;
        view_of(&v);
        printf("%s:\n", k ? "gles3" : "gles2-min");
        shadow_frames(o, &v, &st[k]);
        swell_ocean_destroy(o);
    }
    printf("centroids %.2f m apart\n", hypot(st[0].cx - st[1].cx, st[0].cy - st[1].cy));
    assert_true(hypot(st[0].cx - st[1].cx, st[0].cy - st[1].cy) < 0.3);
    swell_sea_destroy(sea);
}

static void test_misuse(void **state)
{
    (void)state;
    swell_sea *sea = bake();
    swell_ocean *plain = ocean(sea, SWELL_TIER_GLES2_MIN, 0);
    swell_ocean_desc od = { .tier = SWELL_TIER_GLES3, .shadows = 1, .reflections = 1 };
    swell_ocean *o = NULL;
    struct swell_err err = { 0 };
    assert_int_equal(swell_ocean_create(sea, &od, &o, &err), 0);
    swell_view v;
    view_of(&v);
    swell_pass pass;
    assert_int_equal(swell_ocean_begin_shadow(plain, &v, NULL, &pass, &err), SWELL_E_ARG);
    printf("an ocean without shadows: %s\n", err.msg);
    assert_non_null(strstr(err.msg, "shadows = 1"));
    assert_int_equal(swell_ocean_end_shadow(o, &err), SWELL_E_ARG);
    printf("end without begin: %s\n", err.msg);
    assert_int_equal(swell_ocean_begin_shadow(o, &v, NULL, &pass, &err), 0);
    assert_int_equal(swell_ocean_begin_reflection(o, &v, NULL, &pass, &err), SWELL_E_ARG);
    printf("a reflection pass inside a shadow pass: %s\n", err.msg);
    assert_int_equal(swell_ocean_end_shadow(o, &err), 0);
    swell_shadow_desc bad = { .distance_m = -5.0f };
    assert_int_equal(swell_ocean_begin_shadow(o, &v, &bad, &pass, &err), SWELL_E_ARG);
    printf("a negative distance: %s\n", err.msg);
    assert_int_equal(glGetError(), GL_NO_ERROR);
    swell_ocean_destroy(o);
    swell_ocean_destroy(plain);
    swell_sea_destroy(sea);
}

int main(void)
{
    int rc = frame_open("test_shadow", W, H, &g_ph);
    if (rc)
        return rc;
    g_prog = frame_flat_program(0.2f, 0.2f, 0.2f);
    if (!g_prog) {
        fprintf(stderr, "test_shadow: the application's program failed\n");
        return 1;
    }
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_where_gles2_min),
        cmocka_unit_test(test_tiers),
        cmocka_unit_test(test_misuse),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
