/* test_grid.c - the CPU geometry and its helpers against independent references:
 * projected-grid vertices against the camera matrices (camera.c), the eq. 2 weight against its
 * formula, loop blending against a brute-force blend, the sky's closed form against numerical
 * integration of the single-scattering integral, and the sky map's irradiance against a
 * direct integral of sky_radiance.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>
#include "geometry/grid.h"
#include "geometry/kelvin.h"
#include "tables/quantize.h"
#include "optics/sky.h"
#include "tables/stream.h"

#define N 16
#define F 4

/* Flat tables (zero displacement): one pattern, so rest positions are the ray hits. */
static void flat_tables(struct swell_tables *s)
{
    static const int kinds[3] = { TABLE_DISP, TABLE_SLOPE, TABLE_WHITECAP };
    struct swell_err err;
    memset(s, 0, sizeof(*s));
    s->patterns = 1;
    s->frames = F;
    s->loop_period_s = 4.0f;
    s->pattern[0].size_m = 50.0f;
    for (int k = 0; k < 3; k++) {
        struct swell_table *t = &s->table[s->count++];
        int levels = kinds[k] == TABLE_DISP ? 1 : 5;
        float *chain = calloc(quantize_chain_floats(N, N, F, levels), sizeof(float));
        assert_non_null(chain);
        t->kind = kinds[k];
        t->pattern = 0;
        t->format = FORMAT_RGBA8;
        t->width = t->height = N;
        t->layers = F;
        t->levels = levels;
        /* texel value = frame index in every channel: blending is then checkable exactly */
        for (int f = 0; f < F; f++)
            for (int i = 0; i < N * N * 4; i++)
                chain[(size_t)f * N * N * 4 + i] = kinds[k] == TABLE_DISP ? 0.0f : (float)f;
        quantize_build_mips(chain, N, N, F, levels);
        assert_int_equal(quantize_table(t, chain, &err), 0);
        free(chain);
    }
}

/* Each projected-grid vertex on the sea plane, projected with camera.c's matrices, lands on
 * the screen position the grid was built from. */
static void test_projected_grid_hits_its_rays(void **state)
{
    struct swell_tables s;
    struct grid *g;
    struct grid_desc d = { 0 };
    struct camera c;
    struct swell_err err;
    mat4 v, p, vp;
    int w = 21, h = 15, checked = 0;
    double prev_sy = 2.0;
    float aspect = 16.0f / 9.0f;
    (void)state;
    flat_tables(&s);
    d.tables = &s;
    d.w = w;
    d.h = h;
    assert_int_equal(grid_create(&d, &g, &err), 0);
    float *verts = calloc((size_t)grid_vertex_count(g) * GRID_FLOATS, sizeof(float));
    camera_defaults(&c);
    c.pos[2] = 20.0;
    c.heading_deg = 70.0f;
    c.pitch_deg = -35.0f;
    struct camera_frame view;
    camera_frame_make(&c, 1280, 720, &view);     /* aspect 16:9 */
    assert_true(grid_update(g, &view, 1.0, verts) > 0);
    camera_view_rel(&c, v);
    camera_projection(&c, aspect, p);
    glm_mat4_mul(p, v, vp);
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) {
            const float *x = verts + (size_t)(j * w + i) * GRID_FLOATS;
            vec4 in = { x[GRID_A_POS], x[GRID_A_POS + 1], x[GRID_A_POS + 2], 1.0f }, o;
            glm_mat4_mulv(vp, in, o);
            double sx = o[0] / o[3], sy = o[1] / o[3];
            /* a flat sea: the projector is the camera, and the columns are evenly spaced in
             * angle from just left of the screen to just right of it */
            double tx = tan(22.5 * M_PI / 180.0) * aspect, edge = atan(tx) + 0.02;
            assert_true(fabs(atan(sx * tx) - (-edge + 2.0 * edge * i / (w - 1))) < 1e-4);
            if (j == h - 1)
                assert_true(sy < -1.0 && sy > -1.1);   /* the last row just below the screen */
            /* the rest point lies on the sea: the sphere's drop r^2 / (2 R) below the level */
            double r2 = (double)x[GRID_A_REST] * x[GRID_A_REST] +
                        (double)x[GRID_A_REST + 1] * x[GRID_A_REST + 1];
            double drop = r2 / (2.0 * EARTH_RADIUS_M);
            assert_true(fabs(x[GRID_A_POS + 2] + 20.0 + drop) < 1e-4 + 1e-6 * drop);
            /* rows run down the screen from the horizon */
            if (i == 0 && j > 0)
                assert_true(sy < prev_sy);
            if (i == 0)
                prev_sy = sy;
            checked++;
        }
    assert_int_equal(checked, w * h);
    free(verts);
    grid_destroy(g);
    tables_destroy(&s);
}

/* The wake's rise of each vertex of a grid over a flat sea for camera c (the wake's hull
 * `ahead` m ahead of it, sailing at 20 deg), against kelvin_eval's field at the rest positions
 * behind the stern: the correlation and the regression gain; the largest rise; the vertices
 * ahead of the map or well outside the wedge that moved. */
struct wake_fit {
    int inside, outside_moved;
    double corr, gain, dz_max;
};

static void grid_wake_fit(struct grid *g, const struct camera *c, double ahead,
                          const struct kelvin_desc *kd, const struct kelvin_map *m,
                          float *verts, struct wake_fit *out)
{
    struct camera_frame view;
    camera_frame_make(c, 1280, 720, &view);
    double hd = 20.0 * M_PI / 180.0, hx = ahead * cos(c->heading_deg * M_PI / 180.0),
           hy = ahead * sin(c->heading_deg * M_PI / 180.0);
    struct grid_wake w = { .map = m, .hull_xy = { hx, hy }, .fwd = { cos(hd), sin(hd) } };
    grid_set_wake(g, &w);
    assert_true(grid_update(g, &view, 1.0, verts) > 0);
    double sxy = 0.0, sxx = 0.0, syy = 0.0;
    memset(out, 0, sizeof *out);
    for (int k = 0; k < grid_vertex_count(g); k++) {
        const float *b = verts + (size_t)k * GRID_FLOATS;
        /* the flat sea's level there: the camera's height below it less the sphere's drop
         * (the wake's crest widens the grid's range, so these are not the flat grid's
         * vertices) */
        double r2 = (double)b[GRID_A_REST] * b[GRID_A_REST] +
                    (double)b[GRID_A_REST + 1] * b[GRID_A_REST + 1];
        double re = EARTH_RADIUS_M, drop = r2 / (re + sqrt(fmax(re * re - r2, 0.0)));
        double dz = (double)b[GRID_A_POS + 2] - (-c->pos[2] - drop);
        if (fabs(dz) < 1e-6 * (c->pos[2] + drop) + 1e-5)
            dz = 0.0;   /* float rounding of the level */
        double dx = b[GRID_A_REST] - hx, dy = b[GRID_A_REST + 1] - hy;
        double x = dx * w.fwd[0] + dy * w.fwd[1], y = dy * w.fwd[0] - dx * w.fwd[1];
        out->dz_max = fmax(out->dz_max, fabs(dz));
        if (x > 0.5 * kd->hull_length_m + m->ahead_m || fabs(y) > 0.5 * (4.5 - x) + 10.0) {
            out->outside_moved += dz != 0.0;   /* ahead of the map, or well outside the wedge */
            continue;
        }
        if (x < -4.5 - 5.0 && x > -150.0) {   /* behind the stern, where the field is smooth */
            struct kelvin_sample ks;
            kelvin_eval(kd, x, y, &ks);
            sxy += dz * ks.eta;
            sxx += ks.eta * ks.eta;
            syy += dz * dz;
            out->inside++;
        }
    }
    out->corr = sxy / sqrt(sxx * syy + 1e-30);
    out->gain = sxy / (sxx + 1e-30);
}

/* Issue 18: the wake's heights in the geometry (grid_set_wake). On a flat sea each vertex
 * rises by the wake's height at its rest position. From 15 m up, the hull 60 m ahead (cells of
 * a metre or two against waves of 6-16 m): the field itself, a little smoothed (measured gain
 * 0.94, correlation 0.997). From 150 m up, the hull 600 m ahead (cells of 10-30 m): the waves
 * mostly averaged out at the cells' footprint, as Bruneton eq. 2 drops waves a grid cannot
 * hold (measured gain 0.09). Nothing moves ahead of the bow or outside the wedge, and the flat
 * grid comes back once the wake is removed. Fails with the wake at the camera instead of the
 * hull (tried: no rise), the course reversed (correlation 0, 230 vertices outside moved) or
 * the footprint ignored (tried: the far view's gain 0.99). */
static void test_grid_wake(void **state)
{
    (void)state;
    struct swell_tables s;
    struct grid *g;
    struct grid_desc d = { 0 };
    struct swell_err err;
    flat_tables(&s);
    d.tables = &s;
    assert_int_equal(grid_create(&d, &g, &err), 0);
    size_t nf = (size_t)grid_vertex_count(g) * GRID_FLOATS;
    float *flat = calloc(nf, sizeof(float)), *wv = calloc(nf, sizeof(float));
    struct kelvin_desc kd = { .speed_mps = 5.0, .hull_length_m = 9.0, .beam_m = 3.0,
                              .foam_half_life_s = 3.0 };
    struct kelvin_map m;
    assert_int_equal(kelvin_map_build(&kd, 512, 256, &m, &err), 0);
    struct camera c;
    camera_defaults(&c);
    c.pos[0] = 1000.0;
    c.pos[1] = -500.0;
    c.pos[2] = 15.0;
    c.heading_deg = 90.0f;
    c.pitch_deg = -30.0f;
    struct camera_frame view;
    camera_frame_make(&c, 1280, 720, &view);
    assert_true(grid_update(g, &view, 1.0, flat) > 0);
    struct wake_fit near, far;
    grid_wake_fit(g, &c, 60.0, &kd, &m, wv, &near);
    c.pos[2] = 150.0;
    c.pitch_deg = -14.0f;
    grid_wake_fit(g, &c, 600.0, &kd, &m, wv, &far);
    print_message("wake on the grid: 60 m ahead, %d vertices in the wedge, largest rise %.3f "
                  "m, against the field: correlation %.3f, regression gain %.3f; 600 m ahead "
                  "from 150 m up: %d vertices, gain %.3f; %d and %d vertices outside moved\n",
                  near.inside, near.dz_max, near.corr, near.gain, far.inside, far.gain,
                  near.outside_moved, far.outside_moved);
    assert_true(near.inside > 50 && far.inside > 20);
    assert_true(near.dz_max > 0.05 && near.dz_max <= m.height_max_m * 1.0001);
    assert_true(near.corr > 0.9 && near.gain > 0.7 && near.gain < 1.1);
    assert_true(far.gain < 0.5);
    assert_int_equal(near.outside_moved + far.outside_moved, 0);
    /* removed: the flat grid again, vertex for vertex */
    c.pos[2] = 15.0;
    c.pitch_deg = -30.0f;
    grid_set_wake(g, NULL);
    assert_true(grid_update(g, &view, 1.0, wv) > 0);
    assert_memory_equal(wv, flat, nf * sizeof(float));
    kelvin_map_free(&m);
    free(flat);
    free(wv);
    grid_destroy(g);
    tables_destroy(&s);
}

static void test_filter_weight(void **state)
{
    (void)state;
    for (int k = 0; k <= 100; k++) {
        float x = 1.0f + 4.0f * k / 100.0f;
        double u = fmin(fmax((x - 2.0) / 2.0, 0.0), 1.0);
        assert_true(fabs(grid_filter_weight(2.0f, 4.0f, x) - (3 * u * u - 2 * u * u * u)) < 1e-6);
    }
}

/* A pattern's phase from the set's loop: t and t + k T agree for k up to 1e8 (over three
 * years at T = 16 s; t mod T_i had drifted within a day, T_i = 16/3 s not being a float), and
 * it is the phase of its own loop T_i. */
static void test_pattern_phase_exact(void **state)
{
    (void)state;
    struct swell_tables s;
    memset(&s, 0, sizeof s);
    s.loop_period_s = 16.0f;
    s.pattern[0].period_s = 16.0f;
    s.pattern[1].period_s = 16.0f / 3.0f;
    s.pattern[2].period_s = 16.0f / 7.0f;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 40; j++) {
            double t = 0.391 * j;
            struct stream_phase a, b, own;
            stream_pattern_phase(&s, i, t, 16, &a);
            for (double k = 1.0; k <= 1e8; k *= 10.0) {
                stream_pattern_phase(&s, i, t + k * 16.0, 16, &b);
                assert_int_equal(a.f0, b.f0);
                assert_int_equal(a.w, b.w);
            }
            stream_loop_phase(t, 16.0 / (i == 0 ? 1 : i == 1 ? 3 : 7), 16, &own);
            int qa = a.f0 * STREAM_W_ONE + a.w, qo = own.f0 * STREAM_W_ONE + own.w;
            int d = abs(qa - qo);
            assert_true(d <= 1 || d >= 16 * STREAM_W_ONE - 1);
        }
}

/* Blend against a brute-force blend, and t vs t + k T. */
static void test_stream_blend(void **state)
{
    struct swell_tables s;
    struct stream_phase a, b;
    (void)state;
    flat_tables(&s);
    const struct swell_table *t = tables_find(&s, TABLE_SLOPE, 0);
    uint8_t *dst = malloc(stream_blended_bytes(t));
    for (int k = 0; k < 50; k++) {
        double ts = 0.173 * k;
        stream_loop_phase(ts, 4.0, F, &a);
        stream_loop_phase(ts + 7 * 4.0, 4.0, F, &b);
        assert_int_equal(a.f0, b.f0);
        assert_int_equal(a.w, b.w);
        assert_int_equal(a.f1, (a.f0 + 1) % F);
        /* phase (frames) from the definition */
        double ph = fmod(ts, 4.0) / 4.0 * F;
        assert_true(fabs(a.f0 + a.w / 256.0 - ph) <= 0.5 / 256.0 + 1e-9 ||
                     fabs(a.f0 + a.w / 256.0 + F - ph) <= 0.5 / 256.0 + 1e-9);
        stream_blend(t, &a, dst);
        for (int l = 0; l < t->levels; l++) {
            const uint8_t *x0 = t->data + table_offset(t, l, a.f0);
            const uint8_t *x1 = t->data + table_offset(t, l, a.f1);
            const uint8_t *d = dst + stream_level_offset(t, l);
            for (size_t i = 0; i < table_level_bytes(t, l); i++) {
                double ref = x0[i] + (x1[i] - x0[i]) * (a.w / 256.0);
                assert_true(fabs(d[i] - ref) <= 0.5 + 1e-9);
            }
        }
    }
    free(dst);
    tables_destroy(&s);
}

/* The closed form in sky.c against the single-scattering integral done numerically:
 * L = E0 sum_s tau_s p_s m_v int_0^1 exp(-tau x m_s) exp(-tau (1-x) m_v) dx. For the zenith
 * (m_v = 1) and a sun at the zenith (m_s = 1) the two attenuations multiply to exp(-tau), and the
 * Rayleigh + Mie phase at gamma = 0 is known, so the radiance is (tau_R 3/(8 pi) + tau_M p_M(0))
 * exp(-tau) with tau = tau_R + 1.1 tau_M, times the ozone layer's exp(-tau_O3 m_O3) for the
 * sun overhead (m_O3 = 1: a thin shell's air mass at the zenith). */
static void test_sky_zenith_closed_form(void **state)
{
    struct sky s;
    struct swell_err err;
    static const double tau_r[3] = { 0.0464, 0.108, 0.265 };
    static const double tau_o3[3] = { 0.0098, 0.0282, 0.0013 };
    const double tau_m = 0.0252, g = 0.76;
    float up[3] = { 0.0f, 0.0f, 1.0f }, rgb[3];
    (void)state;
    assert_int_equal(sky_bake(90.0f, 0.0f, 16, &s, &err), 0);
    sky_radiance(&s, up, rgb);
    double pm = (1 - g * g) / (4 * M_PI * pow(1 + g * g - 2 * g, 1.5));
    double m = 1.0 / (1.0 + 0.50572 * pow(96.07995, -1.6364));   /* Kasten-Young at 90 deg */
    for (int c = 0; c < 3; c++) {
        double tau = tau_r[c] + 1.1 * tau_m;
        double ref = (tau_r[c] * 3.0 / (8.0 * M_PI) + tau_m * pm) * m * exp(-tau * m) *
                     exp(-tau_o3[c]);
        assert_true(fabs(rgb[c] - ref) < 1e-3 * ref);
    }
    sky_destroy(&s);
}

/* Sky irradiance from the map's stereographic quadrature against a direct (theta, phi)
 * midpoint integral of sky_radiance. */
static void test_sky_irradiance(void **state)
{
    struct sky s;
    struct swell_err err;
    double e[3] = { 0, 0, 0 };
    int nt = 200, np = 400;
    (void)state;
    assert_int_equal(sky_bake(20.0f, 45.0f, 256, &s, &err), 0);
    for (int i = 0; i < nt; i++)
        for (int j = 0; j < np; j++) {
            double th = (i + 0.5) * (M_PI / 2) / nt, ph = (j + 0.5) * 2 * M_PI / np;
            float d[3] = { (float)(sin(th) * cos(ph)), (float)(sin(th) * sin(ph)), (float)cos(th) }, l[3];
            sky_radiance(&s, d, l);
            for (int c = 0; c < 3; c++)
                e[c] += l[c] * cos(th) * sin(th) * (M_PI / 2 / nt) * (2 * M_PI / np);
        }
    for (int c = 0; c < 3; c++)
        assert_true(fabs(s.sky_irr[c] - e[c]) < 0.02 * e[c]);
    /* the map's level 0 texel at the centre is the zenith radiance, within quantisation */
    {
        float up[3] = { 0.0f, 0.0f, 1.0f }, l[3];
        const uint8_t *t = s.data + 4 * ((size_t)(s.size / 2) * s.size + s.size / 2);
        float tv[3];
        sky_radiance(&s, up, l);
        sky_texel_radiance(&s, t, tv);
        for (int c = 0; c < 3; c++)
            assert_true(fabs(tv[c] - l[c]) < 0.02 * s.map_scale[c]);
    }
    /* the half-float chain holds the same radiances' square roots unscaled (sky.h): every
     * texel of every level within half of the RGBA8 step (its rounding, in the square root)
     * plus half precision (2^-11 relative); A, the level index of ocean.frag's own-LOD probe,
     * as the RGBA8 chain's */
    for (int l = 0; l < s.levels; l++) {
        int m = s.size >> l;
        const uint8_t *q = s.data + sky_level_offset(&s, l);
        const uint16_t *h = s.half + sky_level_offset(&s, l);
        for (int i = 0; i < m * m; i++)
            for (int c = 0; c < 4; c++) {
                float v = quantize_float_from_half(h[4 * i + c]), ref, tol;
                if (c == 3) {
                    ref = q[4 * i + 3] / 255.0f;
                    tol = ref / 2048.0f;
                } else {   /* both as square roots of the radiance */
                    float rs = sqrtf(s.map_scale[c]);
                    ref = q[4 * i + c] / 255.0f * rs;
                    tol = 0.5f / 255.0f * rs + ref / 2048.0f;
                }
                assert_true(fabsf(v - ref) <= tol + 1e-7f);
            }
    }
    sky_destroy(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_projected_grid_hits_its_rays),
        cmocka_unit_test(test_grid_wake),
        cmocka_unit_test(test_filter_weight),
        cmocka_unit_test(test_stream_blend),
        cmocka_unit_test(test_pattern_phase_exact),
        cmocka_unit_test(test_sky_zenith_closed_form),
        cmocka_unit_test(test_sky_irradiance),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
