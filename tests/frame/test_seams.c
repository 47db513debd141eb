/* test_seams.c - no seams (issue 14 item 1): where the renderer changes how it draws the sea
 * from one row of the screen to the next (a pattern no longer fetched, a run of rows at another
 * mip level, whitecap tables no longer fetched), the texture the viewer sees may not jump.
 *
 * The metric: per screen row y, the texture energy E(y), the mean over the row of |dI/dx|
 * (I the luma, 0-255), averaged over TIMES frames of the loop (a seam stays on its row while
 * the waves move). Across every row y of the sea, the 4-row windows on either side,
 * mean E(y-4..y-1) and mean E(y..y+3), may differ by at most SEAM_ISSUE (held: SEAM_MAX_HIGH, SEAM_MAX_LOW).
 *
 * Held on the energy relative to the same view drawn with no transition (every pattern fetched
 * at per-pixel LOD up to its 1x1 level, where trilinear filtering reads its patch's constants
 * alone: renderer_desc keep_resolved, pixel_lod), E(y) / E_ref(y):
 * the scene's own rows of changing texture, a glitter's edge, the haze and foreshortening
 * towards the horizon, are in both and cancel, a transition is in one. The image's own ratio is
 * printed beside it: on these views it exceeds 1.5 where the sun's glitter ends (2-3.4x across a
 * glitter's edge in 4 rows, also in the reference), so it cannot be held alone. Nor the relative
 * ratio alone: it also steps where the image is smooth but has less detail than the reference
 * (both below E_FLOOR on one side, only the reference's above it on the other). A row is held
 * on the smaller of the two ratios: a seam is a step in the image the reference has not.
 * Rows within HORIZON_MARGIN px of the horizon are left out (the silhouette of the waves).
 * Views from 1 m to 10 km, every preset, forced gles2-min, high and low quality, both LOD paths
 * (one level per run of rows, the default on software rasterisers, and per-pixel LOD).
 *
 * And across a pitch sweep no seam may jump: the relative 4-row window energies at pitch p and
 * p + PITCH_STEP may differ by at most JUMP_MAX per window. A seam that moves by a grid row
 * with the pitch (as the run boundaries did) fails it.
 *
 * And no brightness step: the change of the mean luma across a row (4-row windows, log) less
 * the reference's there, at most BRIGHT_MAX; test_sky_levels_continuous holds the row-to-row
 * step where runs read the sky at different levels.
 *
 * test_metric_sees_seams first proves the metric fails a frame with a seam.
 *
 * SWELL_SEAMS_PNG=DIR writes each view for a look; SWELL_SEAMS_ROWS=1 prints the profiles.
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
#include "core/image.h"
#include "platform/platform.h"
#include "core/preset.h"
#include "render/renderer.h"
#include "tables/tables.h"
#include "frame/frame_util.h"

#define W 640
#define H 360
#define WIN 4                  /* rows per window (issue 14) */
#define SEAM_ISSUE 1.5         /* issue 14: windows on either side of a row within 1.5x */
#define SEAM_MAX_HIGH 1.5      /* held: the issue's (measured 1.36; before the fades 6.2) */
#define SEAM_MAX_LOW 1.5       /* held: the issue's (measured 1.37; 1.60 on one view of 70
                                  before a run's level stopped short of a pattern's drop,
                                  renderer.c run_lod_key; before the fades 10.4) */
#define BRIGHT_MAX 0.05         /* brightness step across a row, relative to the reference's:
                                  held (measured 4.4 % high, 4.5 % low, at views from 1 m where
                                  single waves' rows differ between the LOD paths; 5.2 % and
                                  2.5 % at rough 100 m before the run's sky blended two levels;
                                  test_sky_levels_continuous holds that sharply) */
#define HORIZON_MARGIN 12      /* px below the horizon left out */
#define TIMES 2                /* frames per view, averaged */
#define PITCH_STEP 0.05f       /* deg, the sweep's step (issue 14: "pitches 0.05 deg") */
#define PITCH_STEPS 4
#define JUMP_MAX 1.40          /* window energy change between sweep steps (measured 1.30,
                                  before the fades 2.27; 1.36 with the loop gain, renderer.c
                                  loop_gain, whose time-dependent gains differ a little per run:
                                  at the first held row below the horizon, where a 0.05 deg
                                  step moves the row's distance most) */
#define E_FLOOR 0.25           /* energies below this (levels of 255) are flat sea: the window
                                  ratio of two such is noise, not a seam */

static struct platform_handle g_ph;
static uint8_t g_img[W * H * 4];

struct profile {
    double e[H];               /* texture energy per row */
    double l[H];               /* mean luma per row */
    int first;                 /* first row held (below the horizon) */
};

static double luma(const uint8_t *p)
{
    return 0.299 * p[0] + 0.587 * p[1] + 0.114 * p[2];
}

static void add_energy(const uint8_t *img, struct profile *p, double weight)
{
    for (int y = 0; y < H; y++) {
        double s = 0.0, m = 0.0;
        const uint8_t *row = img + 4 * (size_t)y * W;
        for (int x = 0; x + 1 < W; x++)
            s += fabs(luma(row + 4 * (x + 1)) - luma(row + 4 * x));
        for (int x = 0; x < W; x++)
            m += luma(row + 4 * x);
        p->e[y] += weight * s / (W - 1);
        p->l[y] += weight * m / W;
    }
}

static double lwindow(const struct profile *p, int y0)
{
    double s = 0.0;
    for (int y = y0; y < y0 + WIN; y++)
        s += p->l[y];
    return fmax(s / WIN, 1.0);
}

/* The worst brightness step of p across any row of its sea: the change of its mean luma from
 * the 4 rows above to the 4 below, relative (log), less the reference's there (its own
 * gradients, the glitter's edge, the haze); the row in *at. */
static double brightness_step(const struct profile *p, const struct profile *ref, int *at)
{
    double worst = 0.0;
    *at = -1;
    for (int y = p->first + WIN; y + WIN <= H; y++) {
        double d = fabs(log(lwindow(p, y) / lwindow(p, y - WIN)) -
                        log(lwindow(ref, y) / lwindow(ref, y - WIN)));
        if (d > worst) {
            worst = d;
            *at = y;
        }
    }
    return worst;
}

static double window(const struct profile *p, int y0)
{
    double s = 0.0;
    for (int y = y0; y < y0 + WIN; y++)
        s += p->e[y];
    return s / WIN;
}

static double ratio(double a, double b)
{
    a = fmax(a, E_FLOOR);
    b = fmax(b, E_FLOOR);
    return a > b ? a / b : b / a;
}

/* The ratio across row y of p's windows. */
static double across(const struct profile *p, int y)
{
    return ratio(window(p, y - WIN), window(p, y));
}

/* The worst ratio across any row of p's sea, and its row; with rel (p relative to the
 * reference's energy), the worst of min(p's, rel's) ratios: a seam is a step in the image the
 * reference does not have. Neither alone: the image's own steps at natural features are in
 * the reference too, and rel steps where p is smooth but the reference has such a feature
 * (or its energy falls below E_FLOOR while p's already has): a loss of detail, not a seam. */
static double seam_metric(const struct profile *p, const struct profile *rel, int *at)
{
    double worst = 1.0;
    *at = -1;
    for (int y = p->first + WIN; y + WIN <= H; y++) {
        double q = across(p, y);
        if (rel)
            q = fmin(q, across(rel, y));
        if (q > worst) {
            worst = q;
            *at = y;
        }
    }
    return worst;
}

/* The screen row of the horizon for camera c (top row 0), the sphere's dip included. */
static int horizon_row(const struct camera *c)
{
    double h = fmax(c->pos[2], 0.5), dip = acos(EARTH_RADIUS_M / (EARTH_RADIUS_M + h));
    double fov = (c->fov_y_deg > 0.0f ? c->fov_y_deg : 45.0) * M_PI / 180.0;
    double y = tan(-dip - c->pitch_deg * M_PI / 180.0) / tan(0.5 * fov);
    int row = (int)ceil(0.5 * (1.0 - y) * H);
    return row < 0 ? 0 : row;
}

/* A frame with a seam: noise whose contrast steps by 3x at row 200, over a smooth ramp (the
 * metric must fail it), and the same with the contrast changing smoothly (it must pass). */
static uint32_t g_rng = 777u;
static double noise(void)
{
    g_rng = g_rng * 1664525u + 1013904223u;
    return (double)(g_rng >> 8) / 16777216.0 - 0.5;
}

static void synthetic(int step, struct profile *p)
{
    memset(p, 0, sizeof *p);
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            double amp = step ? (y < 200 ? 20.0 : 60.0) : 20.0 + 40.0 * y / H;
            double v = 100.0 + 0.2 * y + amp * noise();
            uint8_t *px = g_img + 4 * ((size_t)y * W + x);
            px[0] = px[1] = px[2] = (uint8_t)fmin(fmax(v, 0.0), 255.0);
            px[3] = 255;
        }
    add_energy(g_img, p, 1.0);
    p->first = 40;
}

/* a / ref per row: the texture energy relative to the reference's (E_FLOOR: both flat) */
static void relative(const struct profile *a, const struct profile *ref, struct profile *out)
{
    *out = *a;
    for (int y = 0; y < H; y++)
        out->e[y] = fmax(a->e[y], E_FLOOR) / fmax(ref->e[y], E_FLOOR);
}

static void test_metric_sees_seams(void **state)
{
    struct profile step, smooth, rel;
    int at;
    (void)state;
    synthetic(1, &step);
    synthetic(0, &smooth);
    double with = seam_metric(&step, NULL, &at);
    print_message("synthetic 3x step at row 200: %.2f at row %d\n", with, at);
    assert_true(with > SEAM_MAX_LOW && with > SEAM_ISSUE);
    assert_in_range(at, 197, 203);
    double without = seam_metric(&smooth, NULL, &at);
    print_message("synthetic smooth 1x-3x over the frame: %.2f\n", without);
    assert_true(without < 1.2);
    /* against a reference without the step the step is a seam; against one with it (a
     * feature of the scene) it is not; nor is a smooth image whose reference steps */
    relative(&step, &smooth, &rel);
    double seam = seam_metric(&step, &rel, &at);
    print_message("synthetic step against a smooth reference: %.2f at row %d\n", seam, at);
    assert_true(seam > SEAM_MAX_LOW);
    assert_in_range(at, 197, 203);
    relative(&step, &step, &rel);
    double feature = seam_metric(&step, &rel, &at);
    relative(&smooth, &step, &rel);
    double loss = seam_metric(&smooth, &rel, &at);
    print_message("synthetic step in the reference too: %.2f; smooth against it: %.2f\n",
                  feature, loss);
    assert_true(feature < 1.05 && loss < 1.2);
}

struct view { const char *name; double alt; float pitch; };

/* 1 m to 10 km; the sun (30 deg up) ahead to the left: glitter in every low view. */
static const struct view g_views[] = {
    { "1m", 1.0, -3.0f },       { "10m", 10.0, -2.0f },     { "10m-down", 10.0, -30.0f },
    { "100m", 100.0, -8.0f },   { "1km", 1000.0, -12.0f },  { "1km-down", 1000.0, -45.0f },
    { "10km", 10000.0, -25.0f },
};
#define HEADING 0.0f
#define SUN_AZIM 20.0f

/* The three ways a view is drawn: the reference without transitions, and the two LOD paths. */
enum { WAY_REF, WAY_RUN, WAY_PIXEL, WAYS };
static const char *const g_way_names[WAYS] = { "ref", "run", "pixel" };

struct sea {
    struct swell_tables t;
    struct gpu gpu;
    struct renderer *r[WAYS];
};

static void open_sea(const char *preset, enum render_quality q, struct sea *sea)
{
    struct seastate ss = { 0 };
    struct swell_err err = { 0 };
    if (preset_load(preset, &ss, &err))
        fail_msg("preset %s: %s", preset, err.msg);
    if (swell_bake(&ss, NULL, &sea->t, &err))
        fail_msg("swell_bake %s: %s", preset, err.msg);
    if (gpu_init(&sea->gpu, TIER_GLES2_MIN, 0, &err))
        fail_msg("gpu_init: %s", err.msg);
    for (int w = 0; w < WAYS; w++) {
        struct renderer_desc d = { .tables = &sea->t, .gpu = &sea->gpu, .quality = q };
        d.sun_elev_deg = 30.0f;
        d.sun_azim_deg = SUN_AZIM;
        d.pixel_lod = w != WAY_RUN;
        d.keep_resolved = w == WAY_REF;
        if (renderer_create(&d, &sea->r[w], &err))
            fail_msg("renderer_create: %s", err.msg);
    }
}

static void close_sea(struct sea *sea)
{
    for (int w = 0; w < WAYS; w++)
        renderer_destroy(sea->r[w]);
    gpu_shutdown(&sea->gpu);
    tables_destroy(&sea->t);
}

/* The camera of view v at pitch pitch. */
static void view_camera(const struct view *v, float pitch, struct camera *c)
{
    camera_defaults(c);
    c->pos[0] = 1234.5;
    c->pos[1] = -678.9;
    c->pos[2] = v->alt;
    c->pitch_deg = pitch;
    c->heading_deg = HEADING;
}

/* The profile of view v at pitch pitch, averaged over TIMES frames; the last frame in g_img. */
static void view_profile(struct renderer *r, const struct view *v, float pitch,
                         struct profile *p)
{
    struct swell_err err = { 0 };
    struct camera c;
    memset(p, 0, sizeof *p);
    view_camera(v, pitch, &c);
    for (int i = 0; i < TIMES; i++) {
        if (frame_draw(&g_ph, r, &c, 3.0 + 2.3 * i, W, H, g_img, &err))
            fail_msg("frame: %s", err.msg);
        add_energy(g_img, p, 1.0 / TIMES);
    }
    p->first = horizon_row(&c) + HORIZON_MARGIN;
}

static void write_look(const char *dir, enum render_quality q, int way, const char *preset,
                       const struct view *v)
{
    char path[512];
    struct swell_err err = { 0 };
    snprintf(path, sizeof path, "%s/seams_%s_%s_%s_%s.png", dir,
             q == QUALITY_HIGH ? "high" : "low", g_way_names[way], preset, v->name);
    if (image_write_png(path, g_img, W, H, &err))
        fail_msg("%s", err.msg);
}

static void print_rows(const struct profile *p, const struct profile *rel)
{
    for (int y = p->first + WIN; y + WIN <= H; y++)
        print_message("  row %3d E %7.3f ratio %.3f relative %.3f ratio %.3f\n", y, p->e[y],
                      ratio(window(p, y - WIN), window(p, y)), rel->e[y],
                      ratio(window(rel, y - WIN), window(rel, y)));
}

static const char *const g_presets[] = { "calm", "moderate", "default", "rough", "storm" };
#define PRESETS (sizeof g_presets / sizeof g_presets[0])

static void seams_for(enum render_quality q)
{
    const char *png = getenv("SWELL_SEAMS_PNG"), *rows = getenv("SWELL_SEAMS_ROWS");
    const char *qn = q == QUALITY_HIGH ? "high" : "low";
    const double held_max = q == QUALITY_HIGH ? SEAM_MAX_HIGH : SEAM_MAX_LOW;
    double worst = 0.0, worst_abs = 0.0, worst_b = 0.0;
    int bad = 0, held = 0, over_issue = 0, bright_bad = 0;
    char worst_b_at[96] = "";
    for (size_t ps = 0; ps < PRESETS; ps++) {
        struct sea sea;
        open_sea(g_presets[ps], q, &sea);
        for (size_t v = 0; v < sizeof g_views / sizeof g_views[0]; v++) {
            struct profile ref;
            view_profile(sea.r[WAY_REF], &g_views[v], g_views[v].pitch, &ref);
            if (png)
                write_look(png, q, WAY_REF, g_presets[ps], &g_views[v]);
            for (int w = WAY_RUN; w < WAYS; w++) {
                struct profile p, rel;
                int at, at_abs;
                view_profile(sea.r[w], &g_views[v], g_views[v].pitch, &p);
                relative(&p, &ref, &rel);
                double m = seam_metric(&p, &rel, &at), a = seam_metric(&p, NULL, &at_abs);
                int at_b;
                double b = brightness_step(&p, &ref, &at_b);
                bright_bad += b > BRIGHT_MAX;
                if (b > worst_b) {
                    worst_b = b;
                    snprintf(worst_b_at, sizeof worst_b_at, "%s %s %s row %d", g_way_names[w],
                             g_presets[ps], g_views[v].name, at_b);
                }
                held++;
                bad += m > held_max;
                over_issue += m > SEAM_ISSUE;
                worst = fmax(worst, m);
                worst_abs = fmax(worst_abs, a);
                print_message("%s %-5s %-8s %-8s: relative %.2f at row %d (%.3f -> %.3f); "
                              "image %.2f at row %d; brightness step %.1f %% at row %d%s\n",
                              qn, g_way_names[w], g_presets[ps],
                              g_views[v].name, m, at, at > WIN ? window(&rel, at - WIN) : 0.0,
                              at > 0 ? window(&rel, at) : 0.0, a, at_abs, 100.0 * b, at_b,
                              m > held_max ? "  SEAM" : m > SEAM_ISSUE ? "  over 1.5" : "");
                if (rows)
                    print_rows(&p, &rel);
                if (png)
                    write_look(png, q, w, g_presets[ps], &g_views[v]);
            }
        }
        close_sea(&sea);
    }
    print_message("seams (%s): worst relative %.2f (held %.2f, %d of %d views over; the "
                  "issue's %.2f: %d over); the image's own worst %.2f\n", qn, worst, held_max,
                  bad, held, SEAM_ISSUE, over_issue, worst_abs);
    print_message("brightness steps (%s): worst %.1f %% (%s; held %.1f %%, %d views over)\n",
                  qn, 100.0 * worst_b, worst_b_at, 100.0 * BRIGHT_MAX, bright_bad);
    assert_int_equal(bad, 0);
    assert_int_equal(bright_bad, 0);
}

static void test_no_seams_high(void **state)
{
    (void)state;
    seams_for(QUALITY_HIGH);
}

static void test_no_seams_low(void **state)
{
    (void)state;
    seams_for(QUALITY_LOW);
}

/* Views pitched by PITCH_STEP at a time: each relative window's energy may change by at most
 * JUMP_MAX between neighbouring pitches, on both LOD paths. */
static void test_seams_do_not_jump(void **state)
{
    static const struct view sweep[] = { { "1km", 1000.0, -12.0f }, { "10m", 10.0, -2.0f } };
    double worst = 1.0;
    struct sea sea;
    (void)state;
    open_sea("moderate", QUALITY_HIGH, &sea);
    for (size_t v = 0; v < sizeof sweep / sizeof sweep[0]; v++)
        for (int w = WAY_RUN; w < WAYS; w++) {
            struct profile a, b, ref;
            view_profile(sea.r[WAY_REF], &sweep[v], sweep[v].pitch, &ref);
            view_profile(sea.r[w], &sweep[v], sweep[v].pitch, &b);
            relative(&b, &ref, &a);
            for (int s = 1; s <= PITCH_STEPS; s++) {
                struct profile p;
                float pitch = sweep[v].pitch + PITCH_STEP * (float)s;
                view_profile(sea.r[WAY_REF], &sweep[v], pitch, &ref);
                view_profile(sea.r[w], &sweep[v], pitch, &p);
                relative(&p, &ref, &b);
                int first = (a.first > b.first ? a.first : b.first), at = -1;
                double j = 1.0;
                for (int y = first; y + WIN <= H; y += WIN) {
                    double q = ratio(window(&a, y), window(&b, y));
                    if (q > j) {
                        j = q;
                        at = y;
                    }
                }
                print_message("%-5s %s pitch %.2f -> %.2f: largest window change %.3f at row %d\n",
                              g_way_names[w], sweep[v].name, (double)(pitch - PITCH_STEP),
                              (double)pitch, j, at);
                worst = fmax(worst, j);
                a = b;
            }
        }
    close_sea(&sea);
    print_message("pitch sweep: worst window change %.3f (limit %.2f)\n", worst, JUMP_MAX);
    assert_true(worst <= JUMP_MAX);
}

/* Loop playback keeps its detail (issue 14 item 5): the sea's high-pass energy, the mean of
 * E(y) over the sea's rows, at BREATH_TIMES times 0.137 s apart (incommensurate with every
 * pattern's frame interval, so the blends between loop frames are sampled from end to middle),
 * may vary by at most BREATH_MAX (max / min - 1) per view; the default LOD path. From 100 m
 * and 1 km, where many waves are in view: from 10 m a few crests fill the frame and the energy
 * follows them (low, moderate: 2.62 rising to 3.17 over the 1.5 s, blends or not). Measured
 * before renderer.c loop_gain: 24-29 %. */
#define BREATH_TIMES 12
#define BREATH_MAX 0.10
static void test_detail_steady(void **state)
{
    static const struct view views[] = { { "100m", 100.0, -15.0f }, { "1km", 1000.0, -20.0f } };
    static const char *const presets[] = { "moderate", "rough" };
    double worst = 0.0;
    (void)state;
    for (int q = 0; q < 2; q++)
        for (size_t ps = 0; ps < 2; ps++) {
            struct sea sea;
            open_sea(presets[ps], q ? QUALITY_LOW : QUALITY_HIGH, &sea);
            for (size_t v = 0; v < 2; v++) {
                struct swell_err err = { 0 };
                struct camera c;
                view_camera(&views[v], views[v].pitch, &c);
                int first = horizon_row(&c) + HORIZON_MARGIN;
                double lo = INFINITY, hi = 0.0;
                for (int i = 0; i < BREATH_TIMES; i++) {
                    struct profile e;
                    double sum = 0.0;
                    memset(&e, 0, sizeof e);
                    if (frame_draw(&g_ph, sea.r[WAY_RUN], &c, 3.0 + 0.137 * i, W, H, g_img,
                                   &err))
                        fail_msg("frame: %s", err.msg);
                    add_energy(g_img, &e, 1.0);
                    for (int y = first; y < H; y++)
                        sum += e.e[y];
                    sum /= (double)(H - first);
                    lo = fmin(lo, sum);
                    hi = fmax(hi, sum);
                    if (getenv("SWELL_SEAMS_ROWS"))
                        print_message("  t %.3f: %.3f\n", 3.0 + 0.137 * i, sum);
                }
                double b = hi / lo - 1.0;
                print_message("%s %-8s %-5s: sea texture energy %.3f-%.3f over %d times: "
                              "varies %.1f %%\n", q ? "low " : "high", presets[ps],
                              views[v].name, lo, hi, BREATH_TIMES, 100.0 * b);
                worst = fmax(worst, b);
            }
            close_sea(&sea);
        }
    print_message("detail over the loop: varies by at most %.1f %% (limit %.0f %%)\n",
                  100.0 * worst, 100.0 * BREATH_MAX);
    assert_true(worst <= BREATH_MAX);
}

/* The sky map across runs of rows (SWELL_RUN_LOD): each run reads the sky at eq. 27's footprint,
 * blending two levels by the pixel's footprint. A run reading one whole level stepped the
 * brightness where the next run read another: calm sea from 1 km, 45 deg down, the sun behind
 * the camera (the sky's reflection fills the view), a step of 8 levels of 255 in one row at
 * row 12 (the run boundary). Held: no row's mean luma differs from the row above by more than
 * SKY_ROW_STEP_MAX levels, in both qualities (measured 0.7 high, 1.6 low; the per-pixel path
 * on the same view 0.9 and 1.1). */
#define SKY_ROW_STEP_MAX 2.5

static void test_sky_levels_continuous(void **state)
{
    (void)state;
    static const struct view v = { "1km-down", 1000.0, -45.0f };
    for (int q = 0; q < 2; q++) {
        struct sea sea;
        struct swell_err err = { 0 };
        struct camera c;
        struct profile p;
        open_sea("calm", q ? QUALITY_LOW : QUALITY_HIGH, &sea);
        if (renderer_set_sun(sea.r[WAY_RUN], 30.0f, SUN_AZIM + 180.0f, &err))
            fail_msg("renderer_set_sun: %s", err.msg);
        view_camera(&v, v.pitch, &c);
        memset(&p, 0, sizeof p);
        if (frame_draw(&g_ph, sea.r[WAY_RUN], &c, 3.0, W, H, g_img, &err))
            fail_msg("frame: %s", err.msg);
        add_energy(g_img, &p, 1.0);
        double worst = 0.0;
        int at = -1;
        for (int y = 1; y < H; y++)
            if (fabs(p.l[y] - p.l[y - 1]) > worst) {
                worst = fabs(p.l[y] - p.l[y - 1]);
                at = y;
            }
        print_message("%s calm 1km-down, sun behind, run LOD: largest row-to-row step of the "
                      "mean luma %.2f at row %d (held %.1f)\n", q ? "low" : "high", worst, at,
                      SKY_ROW_STEP_MAX);
        close_sea(&sea);
        assert_true(worst <= SKY_ROW_STEP_MAX);
    }
}

int main(void)
{
    int open_rc = frame_open("test_seams", W, H, &g_ph);
    if (open_rc)
        return open_rc;
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_metric_sees_seams),
        cmocka_unit_test(test_no_seams_high),
        cmocka_unit_test(test_no_seams_low),
        cmocka_unit_test(test_seams_do_not_jump),
        cmocka_unit_test(test_detail_steady),
        cmocka_unit_test(test_sky_levels_continuous),
    };
    int rc = cmocka_run_group_tests(tests, NULL, NULL);
    platform_close(&g_ph);
    return rc;
}
