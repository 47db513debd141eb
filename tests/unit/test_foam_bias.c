/* foam_bias (tables/foam_bias.h): eq. 6's gains by footprint.
 * - The farthest knot, where every table reads its 1 x 1 level, against eq. 6 of the patch
 *   moments computed here from the tables' top levels over every combination of loop frames.
 * - The gains: the same on every run, within their clamp, 1 without whitecaps or without W;
 *   each knot's gain times eq. 6's mean there is W.
 * - foam_bias_at: the knots, linear between them, the end knots beyond.
 * - The loader finds what the bake found (a set read back holds the same gains).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bake/bake.h"
#include "core/seastate.h"
#include "tables/foam_bias.h"
#include "tables/quantize.h"
#include "tables/tables.h"
#include "tables/tables_io.h"

static struct swell_tables g_set;   /* 15 m/s, 64^2 tables, 8 frames: foam in every pattern */

static int setup(void **state)
{
    (void)state;
    struct seastate s = { 0 };
    struct swell_err err = { 0 };
    s.wind_speed_mps = 15.0f;
    s.size_fs = 64;
    s.frames = 8;
    seastate_resolve(&s);
    if (swell_bake(&s, NULL, &g_set, &err)) {
        fprintf(stderr, "bake: %s\n", err.msg);
        return 1;
    }
    return 0;
}

static int teardown(void **state)
{
    (void)state;
    tables_destroy(&g_set);
    return 0;
}

/* Channel c of a table's last level (1 x 1) in layer f. */
static double top(const struct swell_table *t, int f, int c)
{
    return quantize_decode(t, c, t->data[table_offset(t, t->levels - 1, f) + (size_t)c]);
}

static void test_far_knot(void **state)
{
    (void)state;
    const struct swell_tables *t = &g_set;
    const struct swell_table *wc[SWELL_MAX_PATTERNS] = { 0 };
    int n = 0;
    for (int p = 0; p < t->patterns; p++)
        if ((wc[n] = tables_find(t, TABLE_WHITECAP, p)))
            n++;
    assert_true(n >= 2);
    /* every combination of the patterns' loop frames (the sampler draws each pattern's frame
     * apart): eq. 6 of the summed patch means and variances (eq. 7-8) */
    int layers = wc[0]->layers, combos = 1;
    for (int k = 0; k < n; k++)
        combos *= layers;
    assert_true(combos <= 1 << 20);
    double acc = 0.0;
    for (int c = 0; c < combos; c++) {
        double mu = 0.0, var = 0.0;
        for (int k = 0, r = c; k < n; k++, r /= layers) {
            double m = top(wc[k], r % layers, 0), m2 = top(wc[k], r % layers, 1);
            mu += m;
            var += fmax(m2 - m * m, 0.0);
        }
        acc += var > 0.0 ? 0.5 + 0.5 * erf((t->whitecap_epsilon - mu) / sqrt(2.0 * var))
                         : (t->whitecap_epsilon > mu ? 1.0 : 0.0);
    }
    acc /= combos;
    double far = foam_bias_eq6_mean(t, t->foam_bias.f0 + FOAM_BIAS_KNOTS - 1, 4096);
    printf("eq. 6 of the patch moments %.5f, sampled at the farthest knot %.5f; W %.5f\n", acc,
           far, (double)t->whitecap_fraction_measured);
    assert_true(fabs(far - acc) <= 0.03 * acc + 1e-5);
    assert_true(fabs(foam_bias_at(&t->foam_bias, 1e6f) * far - t->whitecap_fraction_measured) <=
                0.01 * t->whitecap_fraction_measured);
}

static void test_gains(void **state)
{
    (void)state;
    struct foam_bias a, b;
    foam_bias_compute(&g_set, &a);
    foam_bias_compute(&g_set, &b);
    assert_memory_equal(&a, &b, sizeof a);
    assert_memory_equal(&a, &g_set.foam_bias, sizeof a);   /* the bake's */
    assert_true(g_set.has_foam_bias);
    int not_one = 0;
    for (int j = 0; j < FOAM_BIAS_KNOTS; j++) {
        assert_true(a.gain[j] >= 0.25f && a.gain[j] <= 4.0f);
        not_one += fabsf(a.gain[j] - 1.0f) > 0.01f;
        double m = foam_bias_eq6_mean(&g_set, a.f0 + (float)j, 4096);
        assert_true(fabs(a.gain[j] * m - g_set.whitecap_fraction_measured) <=
                    0.001 * g_set.whitecap_fraction_measured);
    }
    printf("gains from %.3f m: near %.3f, far %.3f; %d of %d knots off 1\n", exp2f(a.f0),
           (double)a.gain[0], (double)a.gain[FOAM_BIAS_KNOTS - 1], not_one, FOAM_BIAS_KNOTS);
    assert_true(not_one > 0);   /* the memory is skewed: eq. 6 is biased somewhere */
    /* no W, or no whitecap tables: every gain 1 */
    struct swell_tables t = g_set;
    t.whitecap_fraction_measured = 0.0f;
    foam_bias_compute(&t, &a);
    for (int j = 0; j < FOAM_BIAS_KNOTS; j++)
        assert_true(a.gain[j] == 1.0f);
    t = g_set;
    for (int i = 0; i < t.count; i++)
        if (t.table[i].kind == TABLE_WHITECAP)
            t.table[i].kind = TABLE_KIND_COUNT;   /* not found as whitecaps */
    foam_bias_compute(&t, &a);
    for (int j = 0; j < FOAM_BIAS_KNOTS; j++)
        assert_true(a.gain[j] == 1.0f);
}

static void test_at(void **state)
{
    (void)state;
    struct foam_bias b = { .f0 = -3.0f };
    for (int j = 0; j < FOAM_BIAS_KNOTS; j++)
        b.gain[j] = 1.0f + 0.1f * (float)(j * j);
    assert_true(foam_bias_at(&b, -3.0f) == b.gain[0]);
    assert_true(foam_bias_at(&b, -100.0f) == b.gain[0]);
    assert_true(foam_bias_at(&b, 1e9f) == b.gain[FOAM_BIAS_KNOTS - 1]);
    assert_true(fabsf(foam_bias_at(&b, -3.0f + 4.0f) - b.gain[4]) < 1e-6f);
    assert_true(fabsf(foam_bias_at(&b, -3.0f + 4.25f) -
                      (0.75f * b.gain[4] + 0.25f * b.gain[5])) < 1e-6f);
    assert_true(foam_bias_at(&b, NAN) == b.gain[0]);   /* never a NaN gain */
}

static void test_loader(void **state)
{
    (void)state;
    const char *base = getenv("SWELL_TMP");
    char dir[512];
    snprintf(dir, sizeof dir, "%s/foam_bias_set", base ? base : "/tmp");
    struct swell_err err = { 0 };
    assert_int_equal(tables_save_dir(&g_set, dir, &err), 0);
    struct swell_tables back;
    assert_int_equal(tables_load_dir(dir, &back, &err), 0);
    assert_true(back.has_foam_bias);
    assert_memory_equal(&back.foam_bias, &g_set.foam_bias, sizeof back.foam_bias);
    tables_destroy(&back);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_far_knot),
        cmocka_unit_test(test_gains),
        cmocka_unit_test(test_at),
        cmocka_unit_test(test_loader),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
