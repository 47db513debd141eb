/* test_boat.c - the swell program's demo boat (issue 18; src/app/boat.c) on the renderer with
 * every pass it takes (reflection, wake, shadow, refraction), as `swell --boat` draws it.
 *
 * - Floating: its heave and pitch follow the CPU query of the sea (geometry/sea.h) at its
 *   middle, an estimate other than the boat's own (four hull points): over a loop of the sea,
 *   heave within 0.1 of the sea's height's deviation (rms) and correlated above 0.9; pitch
 *   correlated above 0.8 with the surface's slope along the hull (from the query's normal).
 * - At rest, frames with the boat and all its passes repeat with the sea's loop: t and t + T
 *   within 1 of 255 everywhere, while t + T / 3 differs (the frame does move).
 * Forced gles2-min. Exit 77 (skip) only without an EGL device and CI unset (frame_util.h).
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

#include "api/api.h"
#include "app/boat.h"
#include "frame/frame_util.h"
#include "geometry/sea.h"

#define W 320
#define H 180
#define HEADING 30.0

static struct platform_handle g_ph;
static swell_sea *g_sea;        /* its tables: g_sea->tables (api/api.h) */
static struct gpu g_gpu;
static struct renderer *g_r;
static struct boat *g_boat;
static uint8_t g_img[3][W * H * 4];

static int setup(void **state)
{
    (void)state;
    struct swell_err err = { 0 };
    swell_sea_desc sd = { .preset = "moderate" };
    if (swell_sea_bake(&sd, &g_sea, &err) ||
        gpu_init(&g_gpu, TIER_GLES2_MIN, 0, &err)) {
        fprintf(stderr, "test_boat: %s\n", err.msg);
        return -1;
    }
    struct renderer_desc d = { .tables = &g_sea->tables, .gpu = &g_gpu, .sun_elev_deg = 35.0f,
                               .sun_azim_deg = 120.0f, .reflections = 1, .wakes = 1,
                               .shadows = 1, .refractions = 1 };
    struct boat_desc bd = { .x0 = 30.0, .y0 = 0.0, .heading_deg = (float)HEADING };
    if (renderer_create(&d, &g_r, &err) || boat_create(&bd, SWELL_TIER_GLES2_MIN, &g_boat, &err)) {
        fprintf(stderr, "test_boat: %s\n", err.msg);
        return -1;
    }
    return 0;
}

static int teardown(void **state)
{
    (void)state;
    boat_destroy(g_boat);
    renderer_destroy(g_r);
    gpu_shutdown(&g_gpu);
    swell_sea_destroy(g_sea);
    return 0;
}

static double corr(const double *a, const double *b, int n)
{
    double ma = 0, mb = 0, sab = 0, saa = 0, sbb = 0;
    for (int i = 0; i < n; i++) {
        ma += a[i] / n;
        mb += b[i] / n;
    }
    for (int i = 0; i < n; i++) {
        sab += (a[i] - ma) * (b[i] - mb);
        saa += (a[i] - ma) * (a[i] - ma);
        sbb += (b[i] - mb) * (b[i] - mb);
    }
    return sab / sqrt(saa * sbb + 1e-30);
}

static void test_floats_on_the_query(void **state)
{
    (void)state;
    enum { N = 120 };
    double heave[N], sea_h[N], pitch[N], sea_slope[N];
    struct sea_query q;
    sea_query_init(&g_sea->tables, renderer_detile(g_r), BOAT_LENGTH_M, &q);
    double hd = HEADING * M_PI / 180.0, fwd[2] = { cos(hd), sin(hd) };
    double var = 0.0, err2 = 0.0;
    for (int i = 0; i < N; i++) {
        double t = g_sea->tables.loop_period_s * i / N;
        assert_int_equal(boat_pose_at(g_boat, g_sea, renderer_detile(g_r), t, NULL), 0);
        const struct boat_pose *p = boat_pose(g_boat);
        struct sea_point sp;
        sea_query_point(&g_sea->tables, &q, 30.0, 0.0, t, &sp);
        heave[i] = p->pos[2];
        sea_h[i] = sp.height;
        pitch[i] = p->pitch_deg * M_PI / 180.0;
        /* the surface's rise along the hull: -n . fwd / n_z */
        sea_slope[i] = -(sp.normal[0] * fwd[0] + sp.normal[1] * fwd[1]) / sp.normal[2];
    }
    double mh = 0;
    for (int i = 0; i < N; i++)
        mh += sea_h[i] / N;
    for (int i = 0; i < N; i++) {
        var += (sea_h[i] - mh) * (sea_h[i] - mh) / N;
        err2 += (heave[i] - sea_h[i]) * (heave[i] - sea_h[i]) / N;
    }
    double ch = corr(heave, sea_h, N), cp = corr(pitch, sea_slope, N);
    printf("over a loop of %.1f s: the sea's height at the boat's middle varies by %.3f m rms; "
           "heave differs from it by %.3f m rms, correlation %.3f; pitch vs the slope along the "
           "hull: correlation %.3f\n", g_sea->tables.loop_period_s, sqrt(var), sqrt(err2), ch, cp);
    assert_true(sqrt(var) > 0.05);
    assert_true(sqrt(err2) < 0.1 * sqrt(var) + 0.01);
    assert_true(ch > 0.9 && cp > 0.8);
}

/* A frame with the boat and its passes, as swell.c draws it, read back into img. */
static void boat_frame(double t, uint8_t *img)
{
    struct swell_err err = { 0 };
    struct camera cam = { .pos = { 0.0, -6.0, 5.0 }, .heading_deg = 10.0f, .pitch_deg = -8.0f };
    struct renderer_view v;
    float sun[3] = { (float)(cos(35 * M_PI / 180) * cos(120 * M_PI / 180)),
                     (float)(cos(35 * M_PI / 180) * sin(120 * M_PI / 180)),
                     (float)sin(35 * M_PI / 180) };
    renderer_frame_view(g_r, &cam, W, H, &v);
    assert_int_equal(boat_pose_at(g_boat, g_sea, renderer_detile(g_r), t, NULL), 0);
    const struct boat_pose *p = boat_pose(g_boat);
    struct renderer_pass pass;
    struct renderer_reflection rr = { .distance_m = 30.0f };
    struct renderer_shadow sh = { .distance_m = 60.0f };
    struct renderer_refraction rf = { .depth_m = 0.5f, .distance_m = 30.0f };
    struct renderer_wake wk = { .pos = { p->pos[0], p->pos[1] }, .heading_deg = (float)HEADING,
                                .speed_mps = 0.0f };   /* at rest: none */
    int rc = g_ph.be->begin_frame(g_ph.p, &err);
    if (!rc)
        rc = renderer_set_wake(g_r, &wk, &err);
    if (!rc && !(rc = renderer_reflection_begin(g_r, &v, &rr, &pass, &err))) {
        boat_draw(g_boat, pass.view, pass.proj, pass.camera_pos, sun, 0.0f);
        rc = renderer_reflection_end(g_r, &err);
    }
    if (!rc && !(rc = renderer_shadow_begin(g_r, &v, &sh, &pass, &err))) {
        boat_draw(g_boat, pass.view, pass.proj, pass.camera_pos, sun, 0.0f);
        rc = renderer_shadow_end(g_r, &err);
    }
    if (!rc && !(rc = renderer_refraction_begin(g_r, &v, &rf, &pass, &err))) {
        boat_draw(g_boat, pass.view, pass.proj, pass.camera_pos, sun, pass.attenuation_per_m);
        rc = renderer_refraction_end(g_r, &err);
    }
    if (!rc)
        rc = renderer_frame(g_r, &cam, t, W, H, &err);
    if (!rc) {
        struct camera_frame cf;
        camera_frame_make(&v.cam, W, H, &cf);
        boat_draw(g_boat, (const float *)cf.view_rel, (const float *)cf.proj, cam.pos, sun, 0.0f);
        rc = g_ph.be->present(g_ph.p, &err);
    }
    if (!rc)
        rc = g_ph.be->read_rgba(g_ph.p, img, &err);
    if (rc)
        fail_msg("the boat's frame at %g s: %s", t, err.msg);
}

static int max_diff(const uint8_t *a, const uint8_t *b, int *count)
{
    int worst = 0;
    *count = 0;
    for (int i = 0; i < W * H * 4; i++) {
        int d = abs(a[i] - b[i]);
        worst = d > worst ? d : worst;
        *count += d > 1;
    }
    return worst;
}

static void test_loop_at_rest(void **state)
{
    (void)state;
    double t = 2.0, T = g_sea->tables.loop_period_s;
    boat_frame(t, g_img[0]);
    boat_frame(t + T, g_img[1]);
    boat_frame(t + T / 3.0, g_img[2]);
    int n_loop, n_third;
    int loop = max_diff(g_img[0], g_img[1], &n_loop);
    int third = max_diff(g_img[0], g_img[2], &n_third);
    printf("the loop %.2f s: t and t + T differ by %d of 255 at most (%d values by more than 1); "
           "t + T/3 by %d (%d values)\n", T, loop, n_loop, third, n_third);
    assert_true(loop <= 1);
    assert_true(n_third > W * H / 10);
}

int main(void)
{
    int rc = frame_open("test_boat", W, H, &g_ph);
    if (rc)
        return rc;
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_floats_on_the_query),
        cmocka_unit_test(test_loop_at_rest),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
