/* test_reflect.c - local reflections (issue 18; Hu et al. 2006 §2.2, §5.2; Bruneton et al. 2010
 * §6) as an embedding application uses them: a red board standing on the sea is drawn into
 * swell's reflection pass with the pass's matrices, and the frame of the sea is compared with
 * the same frame drawn without a pass (the board itself is not drawn, so every change is its
 * reflection). Forced gles2-min unless a test compares tiers.
 *
 * - Where: on a calm sea the reflection lies where the mirror geometry puts it: the board's
 *   corners mirrored in the sea plane and projected by the application's camera give a
 *   rectangle; the reflection's centroid is within a few pixels of its centre (columns) and
 *   inside it (rows), and most of the reflection lies inside it; gles2-min and gles3 alike,
 *   and through an off-axis projection.
 * - Blur: the rougher the sea, the wider the reflection's spread beyond the board's own, as
 *   eq. 27's footprint (2 sigma of the slopes, times the parallax factor) widens.
 * - The sea beyond the objects reflects nothing of them (parallax); an ocean made for
 *   reflections and drawn without a pass draws the sea it draws without them (where units are
 *   spare); the pass restores the state it changes; misuse is refused with a message.
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
#define EYE_Z 6.0
#define PITCH -8.0
#define BOARD_X 40.0             /* the board: 8 m wide, 6 m tall, across the view 40 m ahead */
#define BOARD_HW 4.0
#define BOARD_TOP 6.0

static struct platform_handle g_ph;
static GLuint g_fbo, g_prog;

/* The application's camera: EYE_Z m up at the origin, looking along +x, PITCH deg down; its
 * frustum shifted by g_shift (glFrustum's off-axis P20, P21; 0: symmetric). */
static float g_shift[2];
static void app_view(swell_view *v)
{
    static const double eye[3] = { 0.0, 0.0, EYE_Z };
    frame_app_view(v, eye, 0.0, PITCH, W, H);
    v->proj[8] = g_shift[0];
    v->proj[9] = g_shift[1];
}

/* The board's corners (drawn relative to the pass's eye, in double, as an application would). */
static const double g_board_quad[4][3] = { { BOARD_X, -BOARD_HW, 0.0 }, { BOARD_X, BOARD_HW, 0.0 },
                                           { BOARD_X, -BOARD_HW, BOARD_TOP },
                                           { BOARD_X, BOARD_HW, BOARD_TOP } };

/* The sea drawn into fbo without (a) and with (b) a reflection pass of the quad `corner`. */
static void pass_frames(swell_ocean *o, const swell_view *v, const swell_reflection_desc *rd,
                        const double corner[4][3], GLuint fbo, double t, uint8_t *a, uint8_t *b)
{
    struct swell_err err = { 0 };
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    if (swell_ocean_draw(o, v, t, &err))
        fail_msg("swell_ocean_draw: %s", err.msg);
    glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, a);
    swell_pass pass;
    if (swell_ocean_begin_reflection(o, v, rd, &pass, &err))
        fail_msg("swell_ocean_begin_reflection: %s", err.msg);
    frame_draw_quad(g_prog, pass.view, pass.proj, pass.camera_pos, corner);
    if (swell_ocean_end_reflection(o, &err))
        fail_msg("swell_ocean_end_reflection: %s", err.msg);
    if (swell_ocean_draw(o, v, t, &err))
        fail_msg("swell_ocean_draw: %s", err.msg);
    glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, b);
}

/* The board's mirror image (its corners with z negated) on the screen: columns x0..x1, rows
 * y0..y1 (GL's, from the bottom). */
static void predicted_rect(const swell_view *v, double rect[4])
{
    float mvp[16];
    frame_mat_mul(v->proj, v->view, mvp);
    rect[0] = rect[2] = 1e9;
    rect[1] = rect[3] = -1e9;
    for (int i = 0; i < 4; i++) {
        float q[3] = { (float)BOARD_X, (float)(i & 1 ? BOARD_HW : -BOARD_HW),
                       (float)(-(i & 2 ? BOARD_TOP : 0.0) - EYE_Z) };
        float c[4];
        for (int r = 0; r < 4; r++)
            c[r] = mvp[r] * q[0] + mvp[4 + r] * q[1] + mvp[8 + r] * q[2] + mvp[12 + r];
        double x = (c[0] / c[3] * 0.5 + 0.5) * W, y = (c[1] / c[3] * 0.5 + 0.5) * H;
        rect[0] = fmin(rect[0], x);
        rect[1] = fmax(rect[1], x);
        rect[2] = fmin(rect[2], y);
        rect[3] = fmax(rect[3], y);
    }
}

struct refl_stats {
    double weight;               /* the red excess summed, over the frame */
    double cx, cy, sx, sy;       /* its centroid and standard deviations, pixels */
    double inside;               /* the share of it inside the predicted rectangle + 3 px */
    int changed;                 /* pixels that changed by more than 2 of 255 */
    int changed_beyond;          /* ...of them where the flat sea is farther than `beyond` */
    int top;                     /* the highest row whose red excess is half the largest
                                  * row's or more (the reflection's edge at the waterline) */
};

/* The distance to the flat sea along pixel (x, y)'s view ray, m (1e30 above the horizon);
 * off-axis projections too (frame_util.h frame_sea_point). */
static double flat_distance(const swell_view *v, int x, int y)
{
    double e[3] = { ((2.0 * (x + 0.5) / W) - 1.0 + v->proj[8]) / v->proj[0],
                    ((2.0 * (y + 0.5) / H) - 1.0 + v->proj[9]) / v->proj[5], -1.0 };
    double z = v->view[8] * e[0] + v->view[9] * e[1] + v->view[10] * e[2];
    double len = sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
    return z < 0.0 ? EYE_Z * len / -z : 1e30;
}

/* Draw the sea with and without a reflection pass of the board; the red the pass added. */
static void reflect_frames(swell_ocean *o, const swell_view *v, const swell_reflection_desc *rd,
                           double t, double beyond, struct refl_stats *st)
{
    static uint8_t a[W * H * 4], b[W * H * 4];
    pass_frames(o, v, rd, g_board_quad, g_fbo, t, a, b);
    static int dumps;
    if (getenv("REFLECT_DUMP")) {
        char name[512];
        snprintf(name, sizeof name, "%s%d.ppm", getenv("REFLECT_DUMP"), dumps++);
        FILE *f = fopen(name, "wb");
        fprintf(f, "P6 %d %d 255\n", W, 2 * H);
        for (int y = H - 1; y >= 0; y--) for (int x = 0; x < W; x++) fwrite(b + 4 * (y * W + x), 1, 3, f);
        for (int y = H - 1; y >= 0; y--) for (int x = 0; x < W; x++) fwrite(a + 4 * (y * W + x), 1, 3, f);
        fclose(f);
    }
    double rect[4];
    predicted_rect(v, rect);
    double sw = 0, sx = 0, sy = 0, sxx = 0, syy = 0, in = 0, row_w[H] = { 0 };
    int changed = 0, changed_beyond = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            const uint8_t *p = b + 4 * (y * W + x), *q = a + 4 * (y * W + x);
            int d = 0;
            for (int c = 0; c < 3; c++)
                d = abs(p[c] - q[c]) > d ? abs(p[c] - q[c]) : d;
            changed += d > 2;
            changed_beyond += d > 2 && flat_distance(v, x, y) > beyond;
            double w = (double)((p[0] - p[1]) - (q[0] - q[1]));
            if (w <= 0.0)
                continue;
            sw += w;
            row_w[y] += w;
            sx += w * x;
            sy += w * y;
            sxx += w * x * x;
            syy += w * y * y;
            in += w * (x >= rect[0] - 3 && x <= rect[1] + 3 && y >= rect[2] - 3 &&
                       y <= rect[3] + 3);
        }
    memset(st, 0, sizeof *st);
    double row_max = 0.0;
    for (int y = 0; y < H; y++)
        row_max = fmax(row_max, row_w[y]);
    st->top = -1;
    for (int y = 0; y < H; y++)
        if (row_w[y] >= 0.5 * row_max && row_max > 0.0)
            st->top = y;
    st->changed = changed;
    st->changed_beyond = changed_beyond;
    st->weight = sw;
    if (sw > 0) {
        st->cx = sx / sw;
        st->cy = sy / sw;
        st->sx = sqrt(fmax(sxx / sw - st->cx * st->cx, 0.0));
        st->sy = sqrt(fmax(syy / sw - st->cy * st->cy, 0.0));
        st->inside = in / sw;
    }
    printf("  predicted x %.1f..%.1f y %.1f..%.1f; reflection weight %.0f at (%.1f, %.1f) "
           "sd (%.1f, %.1f), top row %d, %.0f %% inside; %d pixels changed, %d beyond %g m\n",
           rect[0], rect[1], rect[2], rect[3], st->weight, st->cx, st->cy, st->sx, st->sy,
           st->top, 100.0 * st->inside, changed, changed_beyond, beyond);
}

static swell_sea *bake(float wind)
{
    swell_sea *sea = NULL;
    struct swell_err err = { 0 };
    swell_sea_desc sd = { .preset = "calm", .wind_speed_mps = wind, .budget_bytes = 4u << 20 };
    if (swell_sea_bake(&sd, &sea, &err))
        fail_msg("swell_sea_bake: %s", err.msg);
    return sea;
}

static swell_ocean *ocean(const swell_sea *sea, int tier, int reflections)
{
    swell_ocean *o = NULL;
    struct swell_err err = { 0 };
    swell_ocean_desc od = { .tier = tier, .sun_elev_deg = 40.0f, .sun_azim_deg = 180.0f,
                            .reflections = reflections };
    if (swell_ocean_create(sea, &od, &o, &err))
        fail_msg("swell_ocean_create: %s", err.msg);
    return o;
}

static const swell_reflection_desc g_board = { .object_distance_m = (float)BOARD_X };

static void mirror_position(int tier)
{
    swell_sea *sea = bake(1.0f);
    swell_ocean *o = ocean(sea, tier, 1);
    swell_view v;
    app_view(&v);
    double rect[4];
    predicted_rect(&v, rect);
    struct refl_stats st;
    printf("tier %d, calm 1 m/s:\n", tier);
    reflect_frames(o, &v, &g_board, 1.0, 1e30, &st);
    /* a red of 100 over a third of the rectangle at least; centred on it within 3 px across;
     * its edge at the waterline (where the sea stands at the board's distance: no parallax,
     * no blur) within 3 px of the mirror's; half of it or more inside (the board's top,
     * mirrored nearer the camera, moves and blurs with the waves: it spreads towards the
     * camera, where the parallax grows) */
    assert_true(st.weight > 100.0 * (rect[1] - rect[0]) * (rect[3] - rect[2]) / 3.0);
    assert_true(fabs(st.cx - 0.5 * (rect[0] + rect[1])) < 3.0);
    assert_true(fabs(st.top - rect[3]) < 3.0);
    assert_true(st.inside > 0.5);
    swell_ocean_destroy(o);
    swell_sea_destroy(sea);
}

static void test_mirror_position_gles2_min(void **state)
{
    (void)state;
    mirror_position(SWELL_TIER_GLES2_MIN);
}

static void test_mirror_position_gles3(void **state)
{
    (void)state;
    mirror_position(SWELL_TIER_GLES3);
}

/* An off-axis projection (issue 16: a lens-shifted view, a tiled display's or a stereo eye's):
 * the reflection still lies where the mirror geometry puts it (the pass takes the view's P20
 * and P21, reflect.c; the prediction projects with them). The frustum shifted a fifth of its
 * width right and a tenth of its height down (the board moves 48 px left, 14 up). */
static void test_mirror_position_off_axis(void **state)
{
    (void)state;
    g_shift[0] = 0.2f;
    g_shift[1] = -0.1f;
    mirror_position(SWELL_TIER_GLES2_MIN);
    g_shift[0] = g_shift[1] = 0.0f;
}

/* The reflection's spread grows with the wind (eq. 27's footprint with the slopes' sigma):
 * across the view, where the board's own width is fixed and no horizon cuts it; the spread
 * beyond the board's own image (its width's variance, w^2 / 12, taken out). */
static void test_blur_with_roughness(void **state)
{
    (void)state;
    static const float winds[3] = { 1.0f, 4.0f, 8.0f };
    double spread[3];
    swell_view v;
    app_view(&v);
    for (int i = 0; i < 3; i++) {
        swell_sea *sea = bake(winds[i]);
        swell_ocean *o = ocean(sea, SWELL_TIER_GLES2_MIN, 1);
        struct refl_stats st;
        printf("wind %.0f m/s:\n", (double)winds[i]);
        reflect_frames(o, &v, &g_board, 1.0, 1e30, &st);
        double own = 2.0 * BOARD_HW / BOARD_X * 0.5 * W * v.proj[0];
        spread[i] = sqrt(fmax(st.sx * st.sx - own * own / 12.0, 0.0));
        printf("  beyond the board's own width: %.1f px\n", spread[i]);
        assert_true(st.weight > 0.0);
        swell_ocean_destroy(o);
        swell_sea_destroy(sea);
    }
    assert_true(spread[1] > 1.15 * spread[0]);
    assert_true(spread[2] > 1.15 * spread[1]);
}

/* Eq. 27's width against the width it predicts (issue 18's proof), on both axes of its
 * ellipse. A slope deviation s turns the ray reflected at depression delta: along the view
 * by 2 s in elevation, across it by 2 s sin(delta) (r = v - 2 (v.n) n, as the screen sees the
 * azimuth's turn); the ray meets the objects' plane, 40 m out, (40 - x) m past the sea point x
 * m out, and the camera sees that offset at 40 m: spreads of 2 sigma k rad, k = 1 - x / 40
 * (the parallax factor), with sigma^2 the sea's whole slope variance on that axis (resolved
 * waves move the image, eq. 27's filter blurs it; the slope budget reaches Cox & Munk's,
 * test_spectrum test_cox_munk_budget). The wind blows along the view: Cox & Munk 1954's
 * upwind 3.16e-3 U along it, crosswind 0.003 + 1.92e-3 U across.
 * - Across: a pole 1.5 m wide; per row, from a tenth to seven tenths of the way from the
 *   waterline to its mirrored top, the reflection's variance across the view about the mirror's
 *   column, less the pole's own image's (w^2 / 12), where the prediction is 3.5 px or more
 *   (below, the pole's own width and the map's texels, 4.7 px, hide it). Measured 1.02-1.14
 *   of the prediction on both tiers at 3 and 8 m/s, held within [0.7, 1.4]; before this
 *   build's anisotropic atlas (reflect.c) over 5.
 * - Along: a bar 0.3 m tall, 8 m wide, 2 m up; over the middle 40 columns, the reflection's
 *   variance over rows about its mean, less the bar's own. Measured 1.11 of the prediction
 *   at 8 m/s, 1.42-1.43 at 3 m/s, held within [0.7, 1.6]. Not explained. Not the slope
 *   budget's split at low wind: the sea's own variance along the view is Cox & Munk's (3 m/s
 *   0.00968 against 0.00948, 8 m/s 0.0256 against 0.0253; printed). The blend of versions
 *   widens a kernel by up to 12 %, not 42 %. Taken apart at 3 m/s on gles2-min by editing
 *   ocean.frag (not kept): without eq. 27's filter 14.1 px (the resolved slopes' motion; the
 *   tables hold 0.00795 of the 0.00968, 15.4 px), without the pixel's slopes 21.1 px, both
 *   23.8 px against 16.7: the filter alone is about as wide as the whole variance, while the
 *   resolved slopes still move the image - across, they move it 0.09 of the prediction and the
 *   filter carries it all. The shader's own variance along the view at the bar's rows
 *   (written out instead of the colour by the swell program: the same camera, no reflection
 *   pass) is 0.0064-0.0077 of the whole 0.0094 - LEAN's within-texel share, which leaves the
 *   fetched means' motion sigma about 0.05 (9 px), not the 14.1 px measured: the motion
 *   along the view is what is too large, 1.5x, not the filter. Not found further.
 * Measured in linear radiance (the tone map inverted: its square root widens a blurred
 * profile's tails), in an RGBA8 target, over four times of the loop. */
#define POLE_HW 0.75
#define POLE_TOP 6.0
#define BAR_Z 2.0
#define BAR_H 0.3

/* pixel p's linear red less green, by tonemap.h's inverse: x = o^2 (1 + M) */
static double linear_red_excess(const uint8_t *p)
{
    double m = 0.0, o[3];
    for (int c = 0; c < 3; c++) {
        o[c] = p[c] / 255.0;
        m = fmax(m, o[c]);
    }
    m = fmin(m * m, 0.96);
    double s = 1.0 + m / (1.0 - m);
    return (o[0] * o[0] - o[1] * o[1]) * s;
}

/* The linear red excess the pass adds with the quad `corner`, summed into acc (W x H). */
static void excess_frames(swell_ocean *o, const swell_view *v, const double corner[4][3],
                          GLuint fbo, double t, double *acc)
{
    static uint8_t a[W * H * 4], b[W * H * 4];
    pass_frames(o, v, &g_board, corner, fbo, t, a, b);
    for (int i = 0; i < W * H; i++)
        acc[i] += linear_red_excess(b + 4 * i) - linear_red_excess(a + 4 * i);
}

/* measured / predicted spread for wind U: across (the pole) into *across, along (the bar)
 * into *along */
static void blur_width(GLuint fbo, int tier, float wind, double *across, double *along)
{
    static const double pole[4][3] = { { BOARD_X, -POLE_HW, 0.0 }, { BOARD_X, POLE_HW, 0.0 },
                                       { BOARD_X, -POLE_HW, POLE_TOP },
                                       { BOARD_X, POLE_HW, POLE_TOP } };
    static const double bar[4][3] = { { BOARD_X, -BOARD_HW, BAR_Z }, { BOARD_X, BOARD_HW, BAR_Z },
                                      { BOARD_X, -BOARD_HW, BAR_Z + BAR_H },
                                      { BOARD_X, BOARD_HW, BAR_Z + BAR_H } };
    static double acc[W * H];
    swell_view v;
    app_view(&v);
    double px_per_rad = 0.5 * W * v.proj[0];   /* at the centre (square pixels) */
    double sig_c = sqrt(0.003 + 1.92e-3 * wind), sig_u = sqrt(3.16e-3 * wind);
    swell_sea *sea = bake(wind);
    swell_ocean *o = ocean(sea, tier, 1);

    memset(acc, 0, sizeof acc);
    for (int k = 0; k < 4; k++)
        excess_frames(o, &v, pole, fbo, 1.0 + 2.3 * k, acc);
    double own = 2.0 * POLE_HW / BOARD_X * px_per_rad, top_x = EYE_Z * BOARD_X / (EYE_Z + POLE_TOP);
    double num = 0.0, den = 0.0;
    for (int y = 0; y < H; y++) {
        double d = flat_distance(&v, W / 2, y), ws = 0.0, wxx = 0.0;
        if (d > 1e29)
            continue;
        double x = sqrt(d * d - EYE_Z * EYE_Z), f = (BOARD_X - x) / (BOARD_X - top_x);
        if (f < 0.1 || f > 0.7)
            continue;
        for (int i = 0; i < W; i++) {
            double w = acc[y * W + i], dx = i + 0.5 - 0.5 * W;
            if (w > 0.0) {
                ws += w;
                wxx += w * dx * dx;
            }
        }
        double k = 1.0 - x / BOARD_X, dep = asin(EYE_Z / d);
        double pred = 2.0 * sig_c * sin(dep) * k * px_per_rad;
        double meas = ws > 0.0 ? sqrt(fmax(wxx / ws - own * own / 12.0, 0.0)) : 0.0;
        if (pred < 3.5)
            continue;   /* below the pole's own width and the map's texel: not resolved */
        num += meas;
        den += pred;
        if (getenv("BLUR_ROWS"))
            printf("  row %d: x %.1f m, k %.2f: across %.2f px, predicted %.2f\n", y, x, k,
                   meas, pred);
    }
    *across = den > 0.0 ? num / den : 0.0;

    memset(acc, 0, sizeof acc);
    for (int k = 0; k < 4; k++)
        excess_frames(o, &v, bar, fbo, 1.0 + 2.3 * k, acc);
    double ws = 0.0, wy = 0.0, wyy = 0.0;
    for (int y = 0; y < H; y++)
        for (int i = W / 2 - 20; i < W / 2 + 20; i++) {
            double w = acc[y * W + i];
            if (w > 0.0) {
                ws += w;
                wy += w * y;
                wyy += w * (double)y * y;
            }
        }
    double cy = ws > 0.0 ? wy / ws : 0.0;
    /* the mirrored bar's middle on the sea: the ray to (40, 0, -(z + h/2)) meets it x m out */
    double x = EYE_Z * BOARD_X / (EYE_Z + BAR_Z + 0.5 * BAR_H), k = 1.0 - x / BOARD_X;
    double own_v = BAR_H / BOARD_X * px_per_rad;
    double meas = ws > 0.0 ? sqrt(fmax(wyy / ws - cy * cy - own_v * own_v / 12.0, 0.0)) : 0.0;
    double pred = 2.0 * sig_u * k * px_per_rad;
    *along = meas / pred;
    /* the sea's own variances (resolved and unresolved) against Cox & Munk's */
    swell_sea_info si;
    swell_sea_get_info(sea, &si);
    double vx = si.mss_resolved[0] + si.mss_unresolved[0];
    double vy = si.mss_resolved[1] + si.mss_unresolved[1];
    printf("  the sea's own slope variances: along %.5f (Cox & Munk %.5f; the tables' %.5f), "
           "across %.5f (%.5f; %.5f); along from its own: %.2f\n", vx, sig_u * sig_u,
           si.mss_resolved[0], vy, sig_c * sig_c, si.mss_resolved[1],
           meas / (2.0 * sqrt(vx) * k * px_per_rad));
    printf("eq. 27's width, %s, %.0f m/s (sigma across %.3f, along %.3f): across the view "
           "%.2f of the prediction; along it %.1f px against %.1f (%.2f)\n",
           tier == SWELL_TIER_GLES2_MIN ? "gles2-min" : "gles3", (double)wind, sig_c, sig_u,
           *across, meas, pred, *along);
    swell_ocean_destroy(o);
    swell_sea_destroy(sea);
}

static void test_blur_width(void **state)
{
    (void)state;
    /* an RGBA8 target (GL_RGBA textures render on every GPU swell targets), not the RGBA4
     * application framebuffer of the other tests: the blur's tails are faint */
    GLuint fbo = frame_rgba8_framebuffer(W, H);
    assert_true(fbo != 0);
    static const float winds[2] = { 3.0f, 8.0f };
    for (int i = 0; i < 2; i++) {
        double across, along;
        for (int t = 0; t < 2; t++) {
            blur_width(fbo, t ? SWELL_TIER_GLES3 : SWELL_TIER_GLES2_MIN, winds[i], &across,
                       &along);
            assert_true(across > 0.7 && across < 1.4);
            assert_true(along > 0.7 && along < 1.6);
        }
    }
    glDeleteFramebuffers(1, &fbo);
}

/* The sea at and beyond the objects reflects them as a flat mirror would: nothing of the
 * board shows beyond it (with the board's distance given; without, as if it stood at infinity,
 * the waves' blur carries its reflection there); a draw without a pass is the sea without
 * reflections. */
static void test_distance_and_no_pass(void **state)
{
    (void)state;
    swell_sea *sea = bake(4.0f);
    swell_ocean *o = ocean(sea, SWELL_TIER_GLES2_MIN, 1), *plain = ocean(sea, SWELL_TIER_GLES2_MIN, 0);
    swell_view v;
    app_view(&v);
    struct refl_stats st, st_far;
    const swell_reflection_desc far = { 0 };
    printf("the board's distance given:\n");
    reflect_frames(o, &v, &g_board, 1.0, BOARD_X + 2.0, &st);
    printf("the board taken as far away:\n");
    reflect_frames(o, &v, &far, 1.0, BOARD_X + 2.0, &st_far);
    assert_int_equal(st.changed_beyond, 0);
    assert_true(st_far.changed_beyond > 100);
    /* and nearer the camera it moves and blurs less than at infinity */
    assert_true(st.sy < st_far.sy);

    swell_ocean_destroy(plain);
    swell_ocean_destroy(o);
    /* on a tier with units to spare (gles2-min's 8 are all in use: there the map's unit costs
     * a slot's whitecap table, its whitecaps then from its patch's constants) */
    o = ocean(sea, SWELL_TIER_GLES3, 1);
    plain = ocean(sea, SWELL_TIER_GLES3, 0);
    static uint8_t a[W * H * 4], b[W * H * 4];
    struct swell_err err = { 0 };
    glBindFramebuffer(GL_FRAMEBUFFER, g_fbo);
    assert_int_equal(swell_ocean_draw(plain, &v, 1.0, &err), 0);
    glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, a);
    assert_int_equal(swell_ocean_draw(o, &v, 1.0, &err), 0);
    glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, b);
    int worst = 0;
    for (int i = 0; i < W * H * 4; i++)
        worst = abs(a[i] - b[i]) > worst ? abs(a[i] - b[i]) : worst;
    printf("gles3: reflections on, no pass, vs off: largest difference %d of 255\n", worst);
    assert_true(worst <= 1);
    swell_ocean_destroy(plain);
    swell_ocean_destroy(o);
    swell_sea_destroy(sea);
}

/* The pass restores what it changes; misuse is refused with a message. */
static void test_state_and_misuse(void **state)
{
    (void)state;
    swell_sea *sea = bake(4.0f);
    swell_ocean *o = ocean(sea, SWELL_TIER_GLES2_MIN, 1), *plain = ocean(sea, SWELL_TIER_GLES2_MIN, 0);
    swell_view v;
    app_view(&v);
    struct swell_err err = { 0 };
    swell_pass pass;
    glBindFramebuffer(GL_FRAMEBUFFER, g_fbo);
    glViewport(3, 4, 100, 50);
    glFrontFace(GL_CCW);
    glClearColor(0.25f, 0.5f, 0.75f, 1.0f);
    glDepthMask(GL_FALSE);
    glEnable(GL_SCISSOR_TEST);
    assert_int_equal(swell_ocean_begin_reflection(o, &v, NULL, &pass, &err), 0);
    GLint fb = 0, ff = 0, vp[4];
    glGetIntegerv(GL_FRAMEBUFFER_BINDING, &fb);
    glGetIntegerv(GL_FRONT_FACE, &ff);
    assert_int_not_equal(fb, (GLint)g_fbo);
    assert_int_equal(ff, GL_CW);
    assert_true(pass.viewport[2] >= 32 && pass.viewport[3] >= 32);
    /* the mirror: the view's third column negated, the eye below the sea */
    assert_true(pass.camera_pos[2] == -EYE_Z);
    assert_true(fabsf(pass.view[8] + v.view[8]) < 1e-6f && fabsf(pass.view[0] - v.view[0]) < 1e-6f);
    assert_int_equal(swell_ocean_begin_reflection(o, &v, NULL, &pass, &err), SWELL_E_ARG);
    printf("begin twice: %s\n", err.msg);
    assert_int_equal(swell_ocean_end_reflection(o, &err), 0);
    GLfloat cc[4];
    GLboolean dm = GL_TRUE;
    glGetIntegerv(GL_FRAMEBUFFER_BINDING, &fb);
    glGetIntegerv(GL_FRONT_FACE, &ff);
    glGetIntegerv(GL_VIEWPORT, vp);
    glGetFloatv(GL_COLOR_CLEAR_VALUE, cc);
    glGetBooleanv(GL_DEPTH_WRITEMASK, &dm);
    assert_int_equal(fb, (GLint)g_fbo);
    assert_int_equal(ff, GL_CCW);
    assert_true(vp[0] == 3 && vp[1] == 4 && vp[2] == 100 && vp[3] == 50);
    assert_true(cc[0] == 0.25f && cc[1] == 0.5f && cc[2] == 0.75f);
    assert_true(dm == GL_FALSE);
    assert_true(glIsEnabled(GL_SCISSOR_TEST));
    glDisable(GL_SCISSOR_TEST);
    glDepthMask(GL_TRUE);
    glViewport(0, 0, W, H);
    assert_int_equal(glGetError(), GL_NO_ERROR);

    assert_int_equal(swell_ocean_end_reflection(o, &err), SWELL_E_ARG);
    printf("end without begin: %s\n", err.msg);
    assert_int_equal(swell_ocean_begin_reflection(plain, &v, NULL, &pass, &err), SWELL_E_ARG);
    printf("an ocean without reflections: %s\n", err.msg);
    assert_non_null(strstr(err.msg, "reflections = 1"));
    swell_reflection_desc bad = { .object_distance_m = -1.0f };
    assert_int_equal(swell_ocean_begin_reflection(o, &v, &bad, &pass, &err), SWELL_E_ARG);
    printf("a negative distance: %s\n", err.msg);
    bad.object_distance_m = NAN;
    assert_int_equal(swell_ocean_begin_reflection(o, &v, &bad, &pass, &err), SWELL_E_ARG);
    swell_ocean_destroy(plain);
    swell_ocean_destroy(o);
    swell_sea_destroy(sea);
}

int main(void)
{
    int rc = frame_open("test_reflect", W, H, &g_ph);
    if (rc)
        return rc;
    g_fbo = frame_app_framebuffer(W, H);
    g_prog = frame_flat_program(1.0f, 0.1f, 0.1f);
    if (!g_fbo || !g_prog) {
        fprintf(stderr, "test_reflect: the application's framebuffer or program failed\n");
        return 1;
    }
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_mirror_position_gles2_min),
        cmocka_unit_test(test_mirror_position_gles3),
        cmocka_unit_test(test_mirror_position_off_axis),
        cmocka_unit_test(test_blur_with_roughness),
        cmocka_unit_test(test_blur_width),
        cmocka_unit_test(test_distance_and_no_pass),
        cmocka_unit_test(test_state_and_misuse),
    };
    rc = cmocka_run_group_tests(tests, NULL, NULL);
    platform_close(&g_ph);
    return rc;
}
