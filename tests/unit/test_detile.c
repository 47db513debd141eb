/* test_detile - the random-offset lattice that keeps patterns from repeating (detile.h): the
 * blend keeps a periodic Gaussian field's variance and continuity and removes its repetition;
 * the shaders' constants and their camera-relative cell arithmetic (ocean.frag detile(),
 * emulated here) give the CPU's taps, ordered so a tap's offset changes only at weight 0. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geometry/detile.h"

struct rng { uint64_t s; };

static double rng_uniform(struct rng *r)   /* [0, 1) */
{
    r->s ^= r->s << 13;
    r->s ^= r->s >> 7;
    r->s ^= r->s << 17;
    return (double)(r->s >> 11) * (1.0 / 9007199254740992.0);
}

/* A Gaussian-like random field periodic on the unit tile: 128 Fourier modes of integer wave
 * vectors (up to 32 cycles per tile, as a pattern's band) with random phases, variance 1. */
#define MODES 128
struct field { int kx[MODES], ky[MODES]; double ph[MODES]; };

static void field_init(struct field *f, struct rng *r)
{
    for (int m = 0; m < MODES; m++) {
        do {
            f->kx[m] = (int)(rng_uniform(r) * 65.0) - 32;
            f->ky[m] = (int)(rng_uniform(r) * 65.0) - 32;
        } while (f->kx[m] == 0 && f->ky[m] == 0);
        f->ph[m] = 2.0 * M_PI * rng_uniform(r);
    }
}

static double field_at(const struct field *f, double u, double v)
{
    double s = 0.0;
    for (int m = 0; m < MODES; m++)
        s += cos(2.0 * M_PI * (f->kx[m] * u + f->ky[m] * v) + f->ph[m]);
    return s * sqrt(2.0 / MODES);
}

static double blended(const struct field *f, int pattern, double u, double v)
{
    struct detile_taps t;
    double s = 0.0;
    detile_taps(pattern, u, v, &t);
    for (int j = 0; j < 3; j++)
        s += t.w[j] * field_at(f, u + t.du[j], v + t.dv[j]);
    return s;
}

static void test_weights(void **state)
{
    (void)state;
    struct rng r = { 0x1234567u };
    for (int k = 0; k < 10000; k++) {
        struct detile_taps t;
        double u = (rng_uniform(&r) - 0.5) * 1e4, v = (rng_uniform(&r) - 0.5) * 1e4;
        detile_taps(k & 3, u, v, &t);
        double s2 = 0.0;
        for (int j = 0; j < 3; j++) {
            assert_true(t.w[j] >= 0.0f && t.w[j] <= 1.0f + 1e-6f);
            assert_true(t.du[j] >= 0.0f && t.du[j] < 1.0f);
            assert_true(t.dv[j] >= 0.0f && t.dv[j] < 1.0f);
            s2 += (double)t.w[j] * t.w[j];
        }
        assert_true(fabs(s2 - 1.0) < 1e-5);
    }
}

/* Continuous across every cell edge and diagonal: the leaving vertex's weight is 0 there. */
static void test_continuous(void **state)
{
    (void)state;
    struct rng r = { 0x2468aceu };
    struct field f;
    field_init(&f, &r);
    double worst = 0.0;
    const double eps = 1e-7, cell = 1.0 / DETILE_CELLS;
    for (int k = 0; k < 3000; k++) {
        double u = floor(rng_uniform(&r) * 400.0 - 200.0) * cell;
        double v = (rng_uniform(&r) * 400.0 - 200.0) * cell, d;
        switch (k % 3) {
        case 0:   /* a vertical cell edge u = const */
            d = blended(&f, 1, u - eps, v) - blended(&f, 1, u + eps, v);
            break;
        case 1:   /* a horizontal edge */
            d = blended(&f, 1, v, u - eps) - blended(&f, 1, v, u + eps);
            break;
        default: { /* the diagonal of a cell */
            double a = rng_uniform(&r) * cell;
            d = blended(&f, 1, u + a + eps, u + a - eps + cell * 7) -
                blended(&f, 1, u + a - eps, u + a + eps + cell * 7);
        }
        }
        worst = fmax(worst, fabs(d));
    }
    print_message("largest jump across an edge: %.2e (field rms 1)\n", worst);
    assert_true(worst < 4e-3);
}

/* Variance kept, repetition gone: the field one tile over is the same field; the blend's is not. */
static void test_statistics(void **state)
{
    (void)state;
    struct rng r = { 0x13579bdu };
    struct field f;
    field_init(&f, &r);
    const int n = 40000;
    double s0 = 0.0, s00 = 0.0, sb = 0.0, sbb = 0.0, sbt = 0.0, sgt = 0.0;
    for (int k = 0; k < n; k++) {
        double u = (rng_uniform(&r) - 0.5) * 60.0, v = (rng_uniform(&r) - 0.5) * 60.0;
        double g = field_at(&f, u, v), b = blended(&f, 2, u, v);
        double bt = blended(&f, 2, u + 1.0, v), gt = field_at(&f, u + 1.0, v);
        s0 += g;
        s00 += g * g;
        sb += b;
        sbb += b * b;
        sbt += b * bt;
        sgt += g * gt;
    }
    double var_g = s00 / n - (s0 / n) * (s0 / n), var_b = sbb / n - (sb / n) * (sb / n);
    double corr_b = sbt / sbb, corr_g = sgt / s00;
    print_message("variance: field %.4f, blend %.4f; one tile over: field %.3f, blend %.3f\n",
                  var_g, var_b, corr_g, corr_b);
    assert_true(fabs(var_b / var_g - 1.0) < 0.05);
    assert_true(corr_g > 0.999);
    assert_true(fabs(corr_b) < 0.05);
}

static void test_cell_table(void **state)
{
    (void)state;
    static uint8_t cells[4 * DETILE_N * DETILE_N];
    detile_cell_table(cells, 4 * DETILE_N);
    for (int y = 0; y < DETILE_N; y++)
        for (int x = 0; x < DETILE_N; x++) {
            const uint8_t *p = cells + 4 * (y * DETILE_N + x);
            assert_int_equal(p[0], detile_hash(x, y));
            assert_int_equal(p[1], detile_hash(x + 1, y));
            assert_int_equal(p[2], detile_hash(x, y + 1));
            assert_int_equal(p[3], detile_hash(x + 1, y + 1));
        }
    /* the period, and bytes spread over their range */
    int hist[4] = { 0 };
    static uint8_t tab[DETILE_N * DETILE_N];
    detile_hash_table(tab);
    for (int k = 0; k < DETILE_N * DETILE_N; k++) {
        int x = k % DETILE_N, y = k / DETILE_N;
        assert_int_equal(detile_hash(x, y), detile_hash(x + DETILE_N, y - 3 * DETILE_N));
        assert_int_equal(tab[k], detile_hash(x, y));
        assert_true(tab[k] < DETILE_OFFSETS * DETILE_OFFSETS);
        hist[detile_hash(x, y) >> 4]++;
    }
    for (int q = 0; q < 4; q++)
        assert_true(abs(hist[q] - DETILE_N * DETILE_N / 4) < DETILE_N * DETILE_N / 20);
}

/* x rounded to fp16's 11 significant bits (mediump at its least) */
static float fp16(float x)
{
    int e;
    float m = frexpf(x, &e);
    return ldexpf(roundf(m * 2048.0f) / 2048.0f, e);
}

/* common.glsl detile_offsets in C, each step rounded as fp16 would */
static void frag_offsets(float t, float *ox, float *oy)
{
    float b = floorf(fp16(fp16(t * 255.0f) + 0.5f));
    float hi = floorf(fp16(b * (1.0f / DETILE_OFFSETS)));
    *ox = fp16(hi * (1.0f / DETILE_OFFSETS));
    *oy = fp16((b - DETILE_OFFSETS * hi) * (1.0f / DETILE_OFFSETS));
}

/* Every byte, fetched as fp16(b / 255), gives the CPU's offsets exactly. */
static void test_offsets_fp16(void **state)
{
    (void)state;
    for (int b = 0; b < DETILE_OFFSETS * DETILE_OFFSETS; b++) {
        float ox, oy;
        frag_offsets(fp16((float)b / 255.0f), &ox, &oy);
        assert_true(ox == (float)(b >> 3) / DETILE_OFFSETS);
        assert_true(oy == (float)(b & 7) / DETILE_OFFSETS);
    }
}

/* ocean.frag's detile() in C: the camera-relative uv's cell, the hash cell shifted by
 * detile_camera_shift, the corners' bytes, the weights, then the taps ordered by colour. */
static void frag_detile(const uint8_t *cells, const float sh[3], float u, float v,
                        float w[3], float t[3], float ox[3], float oy[3])
{
    float qx = u * DETILE_CELLS, qy = v * DETILE_CELLS, cx = floorf(qx), cy = floorf(qy);
    float fx = qx - cx, fy = qy - cy;
    float hx = cx + sh[0], hy = cy + sh[1];
    hx -= DETILE_N * floorf(hx / DETILE_N);
    hy -= DETILE_N * floorf(hy / DETILE_N);
    const uint8_t *h = cells + 4 * ((int)hy * DETILE_N + (int)hx);
    float tt[3] = { h[0] / 255.0f, (fy > fx ? h[2] : h[1]) / 255.0f, h[3] / 255.0f };
    float ww[3] = { 1.0f - fmaxf(fx, fy), fabsf(fx - fy), fminf(fx, fy) };
    float s = cx + cy + sh[2];
    s -= 3.0f * floorf((s + 0.5f) / 3.0f);
    int rot = s > 1.5f ? 1 : s > 0.5f ? 2 : 0;   /* .yzx, .zxy, .xyz */
    float n = 1.0f / sqrtf(ww[0] * ww[0] + ww[1] * ww[1] + ww[2] * ww[2]);
    for (int k = 0; k < 3; k++) {
        int j = (k + rot) % 3;
        w[k] = ww[j] * n;
        t[k] = tt[j];
        frag_offsets(t[k], &ox[k], &oy[k]);
    }
}

static void test_shader_stages_agree(void **state)
{
    (void)state;
    static uint8_t cells[4 * DETILE_N * DETILE_N];
    detile_cell_table(cells, 4 * DETILE_N);
    struct rng r = { 0xfeedbeefu };
    for (int k = 0; k < 20000; k++) {
        int pattern = k & 3;
        double l = 7.0 + 500.0 * rng_uniform(&r);
        double cam[2] = { (rng_uniform(&r) - 0.5) * 2e5, (rng_uniform(&r) - 0.5) * 2e5 };
        double rest[2] = { (rng_uniform(&r) - 0.5) * 6.0 * l, (rng_uniform(&r) - 0.5) * 6.0 * l };
        float sh[3], w[3], t[3], ox[3], oy[3];
        detile_camera_shift(pattern, cam[0], cam[1], 1.0 / l, sh);
        /* the vertex stage's uv: frac(camera / L) + rest / L (grid_uv_offset) */
        double ou = cam[0] / l - floor(cam[0] / l), ov = cam[1] / l - floor(cam[1] / l);
        float u = (float)(ou + rest[0] / l), v = (float)(ov + rest[1] / l);
        /* points within float's reach of a cell edge may fall either side: skip them */
        float qx = u * DETILE_CELLS, qy = v * DETILE_CELLS;
        if (fabsf(qx - roundf(qx)) < 1e-4f || fabsf(qy - roundf(qy)) < 1e-4f ||
            fabsf((qx - floorf(qx)) - (qy - floorf(qy))) < 1e-4f)
            continue;
        frag_detile(cells, sh, u, v, w, t, ox, oy);
        struct detile_taps c;
        detile_taps(pattern, (cam[0] + rest[0]) / l, (cam[1] + rest[1]) / l, &c);
        /* the same three (weight, offset) pairs, in some order */
        for (int j = 0; j < 3; j++) {
            int found = 0;
            for (int m = 0; m < 3 && !found; m++)
                found = fabsf(c.w[j] - w[m]) < 2e-3f && c.du[j] == ox[m] && c.dv[j] == oy[m];
            if (!found)
                fail_msg("tap %d: CPU w %.4f t %.4f not among the fragment's (%.4f %.4f) "
                         "(%.4f %.4f) (%.4f %.4f)", j, (double)c.w[j], (double)c.du[j],
                         (double)w[0], (double)t[0], (double)w[1], (double)t[1], (double)w[2],
                         (double)t[2]);
        }
    }
}

/* The fragment stage's tap k keeps its offset across every edge except where its weight is 0
 * on both sides: its texture fetch's implicit LOD sees no jump at full weight. */
static void test_taps_ordered_by_colour(void **state)
{
    (void)state;
    static uint8_t cells[4 * DETILE_N * DETILE_N];
    detile_cell_table(cells, 4 * DETILE_N);
    struct rng r = { 0xabcdef1u };
    const float sh[3] = { 5.0f, 17.0f, 2.0f }, eps = 1e-3f, cell = 1.0f / DETILE_CELLS;
    for (int k = 0; k < 5000; k++) {
        float a[2], b[2], e = floorf((float)rng_uniform(&r) * 40.0f - 20.0f) * cell;
        float s = ((float)rng_uniform(&r) * 40.0f - 20.0f) * cell;
        switch (k % 3) {
        case 0: a[0] = e - eps; b[0] = e + eps; a[1] = b[1] = s; break;
        case 1: a[1] = e - eps; b[1] = e + eps; a[0] = b[0] = s; break;
        default: {
            float o = (float)rng_uniform(&r) * 0.8f * cell + 0.1f * cell;
            a[0] = e + o + eps; a[1] = e + o - eps;
            b[0] = e + o - eps; b[1] = e + o + eps;
        }
        }
        float wa[3], ta[3], wb[3], tb[3], o[4][3];
        frag_detile(cells, sh, a[0], a[1], wa, ta, o[0], o[1]);
        frag_detile(cells, sh, b[0], b[1], wb, tb, o[2], o[3]);
        for (int j = 0; j < 3; j++)
            if (ta[j] != tb[j])
                assert_true(wa[j] < 0.01f && wb[j] < 0.01f);
    }
}

/* common.glsl's copies of the constants */
static void test_shader_constants(void **state)
{
    (void)state;
    FILE *f = fopen("shaders_gles/common.glsl", "r");
    char line[256];
    double cells = 0.0, n = 0.0, offs = 0.0;
    assert_non_null(f);
    while (fgets(line, sizeof line, f)) {
        sscanf(line, "#define DETILE_CELLS %lf", &cells);
        sscanf(line, "#define DETILE_N %lf", &n);
        sscanf(line, "#define DETILE_OFFSETS %lf", &offs);
    }
    fclose(f);
    assert_true(cells == DETILE_CELLS);
    assert_true(n == DETILE_N);
    assert_true(offs == DETILE_OFFSETS);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_weights),
        cmocka_unit_test(test_continuous),
        cmocka_unit_test(test_statistics),
        cmocka_unit_test(test_cell_table),
        cmocka_unit_test(test_offsets_fp16),
        cmocka_unit_test(test_shader_stages_agree),
        cmocka_unit_test(test_taps_ordered_by_colour),
        cmocka_unit_test(test_shader_constants),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
