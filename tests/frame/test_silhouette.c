/* test_silhouette.c - waves on the horizon (issue 13 item 4): from a boat in a storm the crests
 * rise above the horizon where the sea's geometry says they do.
 *
 * Prediction: for every column, the highest point of the sea the CPU query sees there
 * (sea_displacement at rest points from 0.5 m out to past the horizon along the azimuths of
 * the columns and a tenth of the screen beyond each edge, whose displaced points land inside
 * it; each projected with the camera the renderer draws from, the sphere's drop r^2 / 2R as the
 * grid applies it). The poses: the first ones of a seeded sequence whose prediction has
 * crests on the horizon (g_heights). Rendered: the top sea pixel of each column with no sky drawn and a magenta clear
 * (renderer_desc.no_sky, debug_uncovered), forced gles2-min (CPU geometry). Both are measured as
 * the rise above the flat sea's horizon, px.
 *
 * The grid cannot hold every crest the prediction holds (it drops waves shorter than a few of
 * its cells, Bruneton 2010 eq. 2, and near the horizon one row spans kilometres), so the test
 * asks that the rendered silhouette rises by a good share of the predicted one on average,
 * follows it column by column (correlation) where the crests are near, and never rises above it
 * by more than a few pixels (no crest invented). Eq. 2's Nmin, Nmax (grid.c) at 0.5-1.5,
 * 1-2, 1-2.5, 1.5-3 and 2-4 cells gave 0.43-0.44 of the rise: the row spacing limits the far
 * silhouette, not the weights, so the weights stay at 2-4 (less aliasing).
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
#include "bake/bake.h"
#include "core/camera.h"
#include "gl/gpu.h"
#include "platform/platform.h"
#include "core/preset.h"
#include "render/renderer.h"
#include "geometry/sea.h"
#include "tables/tables.h"
#include "frame/frame_util.h"

#define W 960
#define H 540
#define FOV_Y 45.0

static struct platform_handle g_ph;
static uint8_t g_img[W * H * 4];

struct view { double x, y, z; float heading; double t; };

/* The views: the first pose from a seeded sequence, at each height, where the prediction puts
 * crests on the horizon (its rise varies by >= CREST_SD px over the columns): a calm stretch
 * of sea tests nothing (with the patterns' random offsets, detile.h, the fixed poses used
 * before came out with 1-4 px of crests). */
static const double g_heights[] = { 3.0, 3.0, 5.0, 5.0 };
#define CANDIDATES 16
#define CREST_SD 3.0

/* Screen position of camera-relative point q for heading h (pitch 0): column, row from the top
 * (continuous, pixel edges at integers); 0 when behind the camera. */
static int project(const double q[3], double h_deg, double *col, double *row)
{
    double h = h_deg * M_PI / 180.0, th = tan(FOV_Y * M_PI / 360.0);
    double f = q[0] * cos(h) + q[1] * sin(h), r = q[0] * sin(h) - q[1] * cos(h);
    if (f <= 1.0)
        return 0;
    double x = r / f / (th * W / H), y = q[2] / f / th;
    *col = (x + 1.0) * 0.5 * W;
    *row = (1.0 - y) * 0.5 * H;
    return 1;
}

static int g_detile;   /* renderer_detile of the renderer drawn */

/* Predicted top row of the sea per column (+inf where nothing lands) and the flat sea's. */
static void predict(const struct swell_tables *t, const struct camera *c, double t_s,
                    double step, double *top, double *flat)
{
    double h = c->heading_deg * M_PI / 180.0, th = tan(FOV_Y * M_PI / 360.0);
    for (int i = 0; i < W; i++)
        top[i] = INFINITY;
    /* azimuths past the screen's edges too: displaced points land beside their own column */
    for (int col = -W / 10; col < W + W / 10; col++) {
        /* the column's azimuth */
        double x = ((col + 0.5) / W * 2.0 - 1.0) * th * W / H;
        double az = h - atan(x);
        double ca = cos(az), sa = sin(az), best = -INFINITY;
        for (double d = 0.5; d < 40000.0; d += fmax(0.1, d * step)) {
            double p[2] = { c->pos[0] + d * ca, c->pos[1] + d * sa }, disp[3];
            sea_displacement(t, g_detile, p[0], p[1], t_s, disp);
            double q[3] = { p[0] + disp[0] - c->pos[0], p[1] + disp[1] - c->pos[1],
                            disp[2] - d * d / (2.0 * EARTH_RADIUS_M) - c->pos[2] };
            double pc, pr;
            if (project(q, c->heading_deg, &pc, &pr)) {
                int k = (int)floor(pc);
                if (k >= 0 && k < W && pr < top[k])
                    top[k] = pr;
            }
            /* the flat sea: the steepest elevation of the sphere along the azimuth */
            double e = (-d * d / (2.0 * EARTH_RADIUS_M) - c->pos[2]) / d;
            best = e > best ? e : best;
        }
        double f = cos(atan(x));
        if (col >= 0 && col < W)
            flat[col] = (1.0 - best / f / th) * 0.5 * H;   /* y = tan(e) / cos(phi) */
    }
}

/* The predicted rise's mean and sd over the columns where something lands. */
static void rise_stats(const double *top, const double *flat, double *mean, double *sd)
{
    double s = 0.0, ss = 0.0;
    int m = 0;
    for (int col = 2; col < W - 2; col++) {
        if (!isfinite(top[col]))
            continue;
        double rp = flat[col] - top[col];
        s += rp;
        ss += rp * rp;
        m++;
    }
    *mean = m ? s / m : 0.0;
    *sd = m ? sqrt(fmax(ss / m - *mean * *mean, 0.0)) : 0.0;
}

static double rendered_top(const uint8_t *img, int col)
{
    for (int r = 0; r < H; r++) {
        const uint8_t *p = img + 4 * (r * W + col);
        if (!(p[0] == 255 && p[1] == 0 && p[2] == 255))
            return r;
    }
    return H;
}

static void test_storm_silhouette(void **state)
{
    (void)state;
    struct seastate ss = { 0 };
    struct swell_tables t;
    struct swell_err err = { 0 };
    struct gpu gpu;
    struct renderer *r = NULL;
    if (preset_load("storm", &ss, &err))
        fail_msg("preset storm: %s", err.msg);
    if (swell_bake(&ss, NULL, &t, &err))
        fail_msg("swell_bake: %s", err.msg);
    if (gpu_init(&gpu, TIER_GLES2_MIN, 0, &err))
        fail_msg("gpu_init: %s", err.msg);
    /* the lattice on (low quality's auto is off): the seeded poses were chosen with it; the
     * prediction takes the renderer's own setting */
    struct renderer_desc d = { .tables = &t, .gpu = &gpu, .quality = QUALITY_LOW,
                               .detile = DETILE_MODE_ON };
    d.sun_elev_deg = 30.0f;
    d.sun_azim_deg = 20.0f;
    d.no_sky = 1;
    d.debug_uncovered = 1;
    if (renderer_create(&d, &r, &err))
        fail_msg("renderer_create: %s", err.msg);
    g_detile = renderer_detile(r);
    static double top[W], flat[W];
    double sum_p = 0.0, sum_r = 0.0, over_max = 0.0, corr_min = 1.0;
    int n = 0, cand = 0;
    struct view g_views[sizeof g_heights / sizeof g_heights[0]];
    for (size_t v = 0; v < sizeof g_views / sizeof g_views[0]; v++) {
        /* the next candidate pose with crests on the horizon */
        int found = 0;
        for (int k = 0; k < CANDIDATES && !found; k++, cand++) {
            struct camera c;
            double mean, sd;
            camera_defaults(&c);
            g_views[v] = (struct view){ 4321.0 + 1777.7 * cand, -987.0 - 1313.1 * cand,
                                        g_heights[v], (float)fmod(37.0 * cand, 360.0),
                                        fmod(3.7 * cand, 20.0) };
            c.pos[0] = g_views[v].x;
            c.pos[1] = g_views[v].y;
            c.pos[2] = g_views[v].z;
            c.heading_deg = g_views[v].heading;
            /* the camera the renderer draws from: CAMERA_CLEARANCE_M above the surface */
            c.pos[2] = fmax(c.pos[2], sea_surface_height(&t, g_detile, c.pos[0], c.pos[1], g_views[v].t) +
                                      CAMERA_CLEARANCE_M);
            predict(&t, &c, g_views[v].t, 0.01, top, flat);   /* a coarser screen */
            rise_stats(top, flat, &mean, &sd);
            found = sd >= CREST_SD;
        }
        if (!found)
            fail_msg("no pose at %.0f m with crests on the horizon in %d candidates", g_views[v].z,
                     CANDIDATES);
    }
    for (size_t v = 0; v < sizeof g_views / sizeof g_views[0]; v++) {
        struct camera c;
        struct renderer_stats st;
        camera_defaults(&c);
        c.pos[0] = g_views[v].x;
        c.pos[1] = g_views[v].y;
        c.pos[2] = g_views[v].z;
        c.pitch_deg = 0.0f;
        c.heading_deg = g_views[v].heading;
        if (frame_draw(&g_ph, r, &c, g_views[v].t, W, H, g_img, &err))
            fail_msg("frame: %s", err.msg);
        renderer_get_stats(r, &st);
        c.pos[2] += st.camera_raise_m;   /* the prediction's camera is the drawn one */
        predict(&t, &c, g_views[v].t, 0.002, top, flat);
        double sp = 0.0, sr = 0.0, spp = 0.0, srr = 0.0, spr = 0.0, over = 0.0;
        int over_col = -1;
        int m = 0;
        for (int col = 2; col < W - 2; col++) {
            if (!isfinite(top[col]))
                continue;
            double rp = flat[col] - top[col], rr = flat[col] - rendered_top(g_img, col);
            sp += rp; sr += rr; spp += rp * rp; srr += rr * rr; spr += rp * rr;
            if (rr - rp > over)
                over_col = col;
            over = fmax(over, rr - rp);
            m++;
        }
        assert_true(m > W / 2);
        double mp = sp / m, mr = sr / m;
        double cov = spr / m - mp * mr, vp = spp / m - mp * mp, vr = srr / m - mr * mr;
        double corr = cov / sqrt(fmax(vp * vr, 1e-12));
        print_message("z %4.0f m heading %3.0f t %4.1f: rise above the flat horizon: predicted "
                      "%.1f px (sd %.1f), rendered %.1f px (sd %.1f), correlation %.2f, rendered "
                      "above predicted by at most %.1f px (column %d)\n", g_views[v].z,
                      (double)g_views[v].heading, g_views[v].t, mp, sqrt(fmax(vp, 0.0)), mr,
                      sqrt(fmax(vr, 0.0)), corr, over, over_col);
        sum_p += mp;
        sum_r += mr;
        over_max = fmax(over_max, over);
        if (g_views[v].z < 4.0)   /* crests within a few hundred metres, which the grid holds */
            corr_min = fmin(corr_min, corr);
        n++;
    }
    print_message("storm silhouette: rendered rise %.2f of the predicted on average, correlation "
                  ">= %.2f from 3 m, at most %.1f px above it\n", sum_r / sum_p, corr_min,
                  over_max);
    /* measured: 0.65 of the rise, correlation 0.69-0.80 from 3 m, 1.3 px (on the fixed poses
     * of the sea before its random offsets, detile.h: 0.42, 0.75-0.98, 2.4 px); the crests
     * beyond a few hundred metres stay flat (one grid row spans kilometres there) */
    assert_true(n == (int)(sizeof g_views / sizeof g_views[0]));
    assert_true(sum_r / sum_p > 0.35);
    assert_true(corr_min > 0.6);
    assert_true(over_max < 3.0);
    renderer_destroy(r);
    gpu_shutdown(&gpu);
    tables_destroy(&t);
}

int main(void)
{
    int open_rc = frame_open("test_silhouette", W, H, &g_ph);
    if (open_rc)
        return open_rc;
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_storm_silhouette),
    };
    int rc = cmocka_run_group_tests(tests, NULL, NULL);
    platform_close(&g_ph);
    return rc;
}
