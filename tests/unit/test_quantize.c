/* Quantisation (tables.h): the RGBA8 error bound its scale/bias implies, mips equal brute-force
 * footprint means, half-float conversion exact on every representable value. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <cmocka.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "tables/quantize.h"

static float frand(unsigned *s)
{
    *s = *s * 1664525u + 1013904223u;
    return (float)((*s >> 8) & 0xffffff) / 16777216.0f;
}

static void test_rgba8_error_bound(void **state)
{
    (void)state;
    struct swell_table t = { .name = "q", .format = FORMAT_RGBA8, .width = 32, .height = 16,
                             .layers = 3, .levels = 6 };
    size_t n = quantize_chain_floats(t.width, t.height, t.layers, t.levels);
    float *chain = malloc(n * sizeof(float));
    assert_non_null(chain);
    unsigned seed = 7;
    /* channels with very different ranges, one constant */
    for (size_t i = 0; i < n; i++) {
        int c = (int)(i % 4);
        float v = frand(&seed);
        chain[i] = c == 0 ? v * 2.0f - 1.0f : c == 1 ? v * 1e-3f : c == 2 ? 5.0f : 100.0f + 50.0f * v;
    }
    struct swell_err err = { 0 };
    assert_int_equal(quantize_table(&t, chain, &err), 0);
    for (int c = 0; c < 4; c++)
        assert_true(t.scale[c] > 0.0f);
    for (size_t i = 0; i < n; i++) {
        int c = (int)(i % 4);
        float back = quantize_decode(&t, c, t.data[i]);
        float bound = t.scale[c] / 510.0f * 1.0001f + 1e-6f * fabsf(chain[i]);
        assert_true(fabsf(back - chain[i]) <= bound);
    }
    assert_float_equal(quantize_decode(&t, 2, t.data[2]), 5.0f, 1e-6f);
    free(t.data);
    free(chain);
}

static void test_nonfinite_refused(void **state)
{
    (void)state;
    struct swell_table t = { .name = "bad", .format = FORMAT_RGBA8, .width = 2, .height = 2,
                             .layers = 1, .levels = 1 };
    float chain[16] = { 0 };
    chain[5] = NAN;
    struct swell_err err = { 0 };
    assert_int_equal(quantize_table(&t, chain, &err), SWELL_E_ARG);
    assert_non_null(strstr(err.msg, "bad"));
    assert_null(t.data);
}

static void test_mips_are_footprint_means(void **state)
{
    (void)state;
    int w = 16, h = 8, layers = 2, levels = 5;
    size_t n = quantize_chain_floats(w, h, layers, levels);
    float *chain = calloc(n, sizeof(float));
    assert_non_null(chain);
    unsigned seed = 3;
    for (size_t i = 0; i < (size_t)w * h * 4 * layers; i++)
        chain[i] = frand(&seed);
    quantize_build_mips(chain, w, h, layers, levels);
    size_t off = 0;
    for (int l = 0; l < levels; l++) {
        int lw = w >> l > 0 ? w >> l : 1, lh = h >> l > 0 ? h >> l : 1;
        int fx = w / lw, fy = h / lh;  /* footprint of one texel at this level */
        for (int a = 0; a < layers; a++)
            for (int y = 0; y < lh; y++)
                for (int x = 0; x < lw; x++)
                    for (int c = 0; c < 4; c++) {
                        double acc = 0.0;
                        for (int j = 0; j < fy; j++)
                            for (int i = 0; i < fx; i++)
                                acc += chain[((size_t)a * w * h + (size_t)(y * fy + j) * w +
                                              (size_t)(x * fx + i)) * 4 + (size_t)c];
                        float got = chain[off + ((size_t)a * lw * lh + (size_t)y * lw + x) * 4 + c];
                        assert_float_equal(got, acc / (fx * fy), 1e-5);
                    }
        off += (size_t)lw * lh * 4 * layers;
    }
    assert_int_equal(off, n);
    free(chain);
}

static void test_half_roundtrip_all(void **state)
{
    (void)state;
    for (uint32_t h = 0; h < 65536; h++) {
        uint16_t hh = (uint16_t)h;
        float f = quantize_float_from_half(hh);
        if (isnan(f)) {
            assert_true(isnan(quantize_float_from_half(quantize_half_from_float(f))));
            continue;
        }
        assert_int_equal(quantize_half_from_float(f), hh);
    }
    /* rounding: values between two halves go to the nearest (ties to even) */
    assert_int_equal(quantize_half_from_float(1.0f + 1.0f / 2048.0f), 0x3c00);  /* tie -> even */
    assert_int_equal(quantize_half_from_float(1.0f + 3.0f / 2048.0f), 0x3c02);  /* tie -> even */
    assert_int_equal(quantize_half_from_float(65520.0f), 0x7c00);                /* overflow */
    assert_float_equal(quantize_float_from_half(quantize_half_from_float(0.1f)), 0.1f, 1e-4);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_rgba8_error_bound),
        cmocka_unit_test(test_nonfinite_refused),
        cmocka_unit_test(test_mips_are_footprint_means),
        cmocka_unit_test(test_half_roundtrip_all),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
