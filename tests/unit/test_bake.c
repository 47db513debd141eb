/* The bake as a whole: determinism, the budget, whitecap fraction vs the wind model, and the
 * decision (bake.c, top comment) to give each pattern its own lambda_min and foam map with one
 * shared threshold - checked here against the full multi-pattern Jacobian on a common grid. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <cmocka.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bake.h"
#include "ocean.h"
#include "quantize.h"
#include "whitecap.h"

static struct seastate small_state(float wind)
{
    struct seastate s = { 0 };
    s.wind_speed_mps = wind;
    s.size_fs = 64;
    s.frames = 8;
    seastate_resolve(&s);
    return s;
}

static void test_deterministic(void **state)
{
    (void)state;
    struct seastate s = small_state(12);
    struct swell_tables a, b;
    struct swell_err err = { 0 };
    assert_int_equal(swell_bake(&s, NULL, &a, &err), 0);
    assert_int_equal(swell_bake(&s, NULL, &b, &err), 0);
    assert_int_equal(a.count, b.count);
    assert_int_equal(a.count, 3 * 4 + 2);
    for (int i = 0; i < a.count; i++) {
        assert_string_equal(a.table[i].name, b.table[i].name);
        assert_int_equal(table_bytes(&a.table[i]), table_bytes(&b.table[i]));
        assert_memory_equal(a.table[i].data, b.table[i].data, table_bytes(&a.table[i]));
        assert_memory_equal(a.table[i].scale, b.table[i].scale, sizeof a.table[i].scale);
    }
    assert_true(a.lambda_t == b.lambda_t);
    /* a different seed gives different waves */
    s.seed = 99;
    struct swell_tables c;
    assert_int_equal(swell_bake(&s, NULL, &c, &err), 0);
    assert_true(memcmp(a.table[0].data, c.table[0].data, table_bytes(&a.table[0])) != 0);
    tables_destroy(&a);
    tables_destroy(&b);
    tables_destroy(&c);
}

static void test_budget(void **state)
{
    (void)state;
    struct swell_err err = { 0 };
    uint64_t budgets[] = { SWELL_BUDGET_TINY, SWELL_BUDGET_DEFAULT };
    for (int i = 0; i < 2; i++) {
        struct seastate s = { 0 };
        s.budget_bytes = budgets[i];
        struct swell_tables t;
        assert_int_equal(swell_bake(&s, NULL, &t, &err), 0);
        uint64_t total = tables_bytes(&t) + bake_resident_bytes(t.patterns, t.state.size_fs);
        assert_true(total <= budgets[i]);
        /* the chosen configuration is the one the estimate describes */
        assert_int_equal(tables_bytes(&t), bake_table_bytes(t.patterns, t.state.size_fs,
                                                            t.state.size_geo, t.frames));
        assert_true(t.frames >= 8);
        tables_destroy(&t);
    }
    /* too small: refused with what is needed, nothing allocated */
    struct seastate s = { 0 };
    s.budget_bytes = 1u << 20;
    s.size_fs = 256;
    s.frames = 64;
    struct swell_tables t;
    assert_int_equal(swell_bake(&s, NULL, &t, &err), SWELL_E_BUDGET);
    assert_non_null(strstr(err.msg, "budget"));
    assert_non_null(strstr(err.msg, "--budget"));
    assert_int_equal(t.count, 0);
}

static void test_whitecap_fraction_vs_model(void **state)
{
    (void)state;
    /* The threshold is solved for the model fraction (Tessendorf alg. 1); the measured fraction
     * (eq. 9, mean foam opacity after the loop reaches steady state) must land near it. The
     * steady-state relation eq. 11 assumes breaking uncorrelated between frames, which the
     * looping waves are not, so we allow 35% relative error. */
    float winds[] = { 8, 12, 16, 22 };
    for (int i = 0; i < 4; i++) {
        struct seastate s = small_state(winds[i]);
        struct swell_tables t;
        struct swell_err err = { 0 };
        assert_int_equal(swell_bake(&s, NULL, &t, &err), 0);
        double model = whitecap_model_fraction(WHITECAP_MOM80, winds[i]);
        assert_true(fabs(t.whitecap_fraction_model - model) < 1e-6);
        double rel = fabs(t.whitecap_fraction_measured - model) / model;
        if (rel > 0.35)
            fail_msg("U=%g: measured %g vs model %g (%.0f%%)", winds[i],
                     t.whitecap_fraction_measured, model, rel * 100);
        tables_destroy(&t);
    }
}

/* Bilinear sample of a periodic N x N field at position (x, y) metres, patch side L. */
static float sample(const float *f, int n, float L, double x, double y)
{
    double u = x / L * n, v = y / L * n;
    u -= floor(u / n) * n;
    v -= floor(v / n) * n;
    int i0 = (int)u, j0 = (int)v;
    double fu = u - i0, fv = v - j0;
    int i1 = (i0 + 1) % n, j1 = (j0 + 1) % n;
    i0 %= n;
    j0 %= n;
    return (float)((f[j0 * n + i0] * (1 - fu) + f[j0 * n + i1] * fu) * (1 - fv) +
                   (f[j1 * n + i0] * (1 - fu) + f[j1 * n + i1] * fu) * fv);
}

static void test_pattern_union_holds_up(void **state)
{
    (void)state;
    struct seastate s = small_state(18);
    struct swell_tables t;
    struct swell_err err = { 0 };
    assert_int_equal(swell_bake(&s, NULL, &t, &err), 0);
    int np = t.patterns, n = t.state.size_fs;
    struct ocean *oc[SWELL_MAX_PATTERNS] = { 0 };
    struct ocean_fields fl[SWELL_MAX_PATTERNS];
    float *copy[SWELL_MAX_PATTERNS][3];
    for (int i = 0; i < np; i++) {
        struct ocean_desc od = { .state = &t.state, .n = n, .size_m = t.pattern[i].size_m,
                                 .k_min = t.pattern[i].k_min, .k_max = t.pattern[i].k_max,
                                 .frames = t.frames, .period_s = t.loop_period_s,
                                 .lambda = t.pattern[i].lambda,
                                 .seed = t.state.seed + 0x9e3779b9u * (uint32_t)(i + 1) };
        assert_int_equal(ocean_create(&od, &oc[i], &err), 0);
        assert_int_equal(ocean_eval(oc[i], 0, &fl[i], &err), 0);
        for (int c = 0; c < 3; c++) {
            const float *src = c == 0 ? fl[i].jxx : c == 1 ? fl[i].jyy : fl[i].jxy;
            copy[i][c] = malloc(sizeof(float) * n * n);
            memcpy(copy[i][c], src, sizeof(float) * n * n);
        }
    }
    /* common sample points: random positions over the largest pattern's period, where every
     * pattern is sampled (bilinearly, each wrapped with its own period) */
    size_t cnt = 150000;
    float *full = malloc(cnt * sizeof(float));
    unsigned char *uni = malloc(cnt);
    size_t per[SWELL_MAX_PATTERNS] = { 0 };
    uint64_t rng = 12345;
    for (size_t p = 0; p < cnt; p++) {
        double pos[2];
        for (int c = 0; c < 2; c++) {
            rng = rng * 6364136223846793005ull + 1442695040888963407ull;
            pos[c] = (double)(rng >> 11) / 9007199254740992.0 * t.pattern[0].size_m;
        }
        float a = 0, b = 0, c = 0;
        int any = 0;
        for (int i = 0; i < np; i++) {
            float L = t.pattern[i].size_m;
            float ai = sample(copy[i][0], n, L, pos[0], pos[1]);
            float bi = sample(copy[i][1], n, L, pos[0], pos[1]);
            float ci = sample(copy[i][2], n, L, pos[0], pos[1]);
            a += ai; b += bi; c += ci;
            int brk = whitecap_lambda_min(ai, bi, ci) < t.lambda_t;
            per[i] += (size_t)brk;
            any |= brk;
        }
        full[p] = whitecap_lambda_min(a, b, c);
        uni[p] = (unsigned char)any;
    }
    for (int i = 0; i < np; i++)
        print_message("pattern %d (L %.1f m) breaks at %.4f of the points\n", i,
                      t.pattern[i].size_m, (double)per[i] / cnt);
    size_t n_uni = 0;
    for (size_t i = 0; i < cnt; i++)
        n_uni += uni[i];
    double p = (double)n_uni / cnt;
    assert_true(n_uni > 50);
    /* threshold the full Jacobian's lambda_min for the same fraction, then compare masks */
    float thr;
    assert_int_equal(whitecap_threshold(full, cnt, p, &thr, &err), 0);
    size_t both = 0, either = 0;
    for (size_t i = 0; i < cnt; i++) {
        int f = full[i] < thr;
        both += (size_t)(f && uni[i]);
        either += (size_t)(f || uni[i]);
    }
    double iou = (double)both / (double)either;
    double chance = p * p / (2 * p - p * p);
    print_message("union breaking fraction %.4f, IoU with full-Jacobian breaking %.3f "
                  "(independent masks would give %.4f)\n", p, iou, chance);
    if (iou < 0.3 || iou < 5 * chance)
        fail_msg("per-pattern whitecaps do not match the full Jacobian: IoU %.3f", iou);
    for (int i = 0; i < np; i++) {
        for (int c = 0; c < 3; c++)
            free(copy[i][c]);
        ocean_destroy(oc[i]);
    }
    free(full);
    free(uni);
    tables_destroy(&t);
}

/* Bilinear reconstruction of a periodic n x n texel table at texel coordinates (u, v), texel
 * (x, y)'s centre at (x, y): how the GPU magnifies the foam, and how the bake reconstructs
 * lambda_min between centres. */
static double texel_bilinear(const float *f, int n, double u, double v)
{
    double fu = floor(u), fv = floor(v), tu = u - fu, tv = v - fv;
    int x0 = (((int)fu % n) + n) % n, y0 = (((int)fv % n) + n) % n;
    int x1 = (x0 + 1) % n, y1 = (y0 + 1) % n;
    return (1 - tv) * ((1 - tu) * f[y0 * n + x0] + tu * f[y0 * n + x1]) +
           tv * ((1 - tu) * f[y1 * n + x0] + tu * f[y1 * n + x1]);
}

/* The baked foam of the largest pattern comes from sub-texel coverage: its opacity channel is
 * the 4 x 4 foam loop rebuilt here from the pattern's own fields, not eq. 7's binary one, and by
 * two blockiness measures it is less blocky than the binary loop at the same threshold:
 * (a) breaking-edge texels (a 16 x 16 reference says part of their area breaks now) holding an
 * opacity of exactly 0 or 1; (b) the area misclassified by the 0.5 contour of the breaking
 * input B magnified bilinearly, as the GPU draws it, against the breaking region itself
 * (lambda_min < lambda_T on an 8 x 8 grid per texel) - a binary B draws texel-grid diamonds. */
static void test_foam_subtexel_baked(void **state)
{
    (void)state;
    struct seastate s = small_state(18);
    struct swell_tables t;
    struct swell_err err = { 0 };
    assert_int_equal(swell_bake(&s, NULL, &t, &err), 0);
    int n = t.state.size_fs, F = t.frames;
    size_t texels = (size_t)n * n, count = texels * F;
    struct ocean_desc od = { .state = &t.state, .n = n, .size_m = t.pattern[0].size_m,
                             .k_min = t.pattern[0].k_min, .k_max = t.pattern[0].k_max,
                             .frames = F, .period_s = t.pattern[0].period_s,
                             .lambda = t.pattern[0].lambda,
                             .seed = t.state.seed + 0x9e3779b9u };
    struct ocean *oc;
    assert_int_equal(ocean_create(&od, &oc, &err), 0);
    float *lm = malloc(count * sizeof *lm), *op4 = malloc(count * sizeof *op4);
    float *op1 = malloc(count * sizeof *op1), *b4 = malloc(texels * sizeof *b4);
    float *b1 = malloc(texels * sizeof *b1);
    assert_true(lm && op4 && op1 && b4 && b1);
    for (int f = 0; f < F; f++) {
        struct ocean_fields fl;
        assert_int_equal(ocean_eval(oc, f, &fl, &err), 0);
        for (size_t i = 0; i < texels; i++)
            lm[(size_t)f * texels + i] = whitecap_lambda_min(fl.jxx[i], fl.jyy[i], fl.jxy[i]);
    }
    ocean_destroy(oc);
    struct whitecap_cover c4, c1;
    struct whitecap_cover_desc d = { .lambda_min = lm, .width = n, .height = n, .frames = F };
    assert_int_equal(whitecap_cover_create(&d, &c4, &err), 0);
    d.sub = 1;
    assert_int_equal(whitecap_cover_create(&d, &c1, &err), 0);
    float lt = t.lambda_t, dt = t.pattern[0].period_s / F;
    assert_int_equal(whitecap_foam_loop(&c4, lt, dt, t.state.foam_half_life_s, op4, &err), 0);
    assert_int_equal(whitecap_foam_loop(&c1, lt, dt, t.state.foam_half_life_s, op1, &err), 0);

    const struct swell_table *wt = NULL;
    for (int i = 0; i < t.count; i++)
        if (strcmp(t.table[i].name, "whitecap_p0") == 0)
            wt = &t.table[i];
    assert_non_null(wt);
    float tol = wt->scale[2] / 510.0f + 1e-6f;
    size_t off1 = 0;
    for (size_t i = 0; i < count; i++) {
        float baked = quantize_decode(wt, 2, wt->data[i * 4 + 2]);   /* level 0 first */
        if (fabsf(baked - op4[i]) > tol)
            fail_msg("texel %zu: baked opacity %g, 4 x 4 foam loop %g", i, baked, op4[i]);
        off1 += fabsf(baked - op1[i]) > tol;
    }

    size_t edge = 0, hard4 = 0, hard1 = 0, fine_pts = 0, miss4 = 0, miss1 = 0;
    for (int f = 0; f < F; f++) {
        const float *l = lm + (size_t)f * texels;
        whitecap_cover_frame(&c4, f, lt, b4);
        whitecap_cover_frame(&c1, f, lt, b1);
        for (int y = 0; y < n; y++)
            for (int x = 0; x < n; x++) {
                int below = 0;
                for (int j = 0; j < 16; j++)
                    for (int i = 0; i < 16; i++)
                        below += texel_bilinear(l, n, x - 0.5 + (i + 0.5) / 16,
                                                y - 0.5 + (j + 0.5) / 16) < lt;
                if (below == 0 || below == 256)
                    continue;
                size_t k = (size_t)f * texels + (size_t)y * n + x;
                edge++;
                hard4 += op4[k] == 0.0f || op4[k] == 1.0f;
                hard1 += op1[k] == 0.0f || op1[k] == 1.0f;
                for (int j = 0; j < 8; j++)
                    for (int i = 0; i < 8; i++) {
                        double u = x - 0.5 + (i + 0.5) / 8, v = y - 0.5 + (j + 0.5) / 8;
                        int brk = texel_bilinear(l, n, u, v) < lt;
                        fine_pts++;
                        miss4 += (texel_bilinear(b4, n, u, v) >= 0.5) != brk;
                        miss1 += (texel_bilinear(b1, n, u, v) >= 0.5) != brk;
                    }
            }
    }
    print_message("pattern 0, %zu breaking-edge texels over %d frames: opacity exactly 0 or 1 "
                  "%.3f (binary) -> %.3f (4x4); 0.5-contour misclassifies %.3f -> %.3f of their "
                  "area; %zu of %zu baked texels differ from the binary loop\n",
                  edge, F, (double)hard1 / edge, (double)hard4 / edge,
                  (double)miss1 / fine_pts, (double)miss4 / fine_pts, off1, count);
    assert_true(edge > 100);
    assert_true(off1 > edge / 4);
    assert_true(hard4 * 3 < hard1);
    assert_true(miss4 * 3 < miss1 * 2);
    whitecap_cover_destroy(&c4);
    whitecap_cover_destroy(&c1);
    free(lm);
    free(op4);
    free(op1);
    free(b4);
    free(b1);
    tables_destroy(&t);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_deterministic),
        cmocka_unit_test(test_budget),
        cmocka_unit_test(test_whitecap_fraction_vs_model),
        cmocka_unit_test(test_pattern_union_holds_up),
        cmocka_unit_test(test_foam_subtexel_baked),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
