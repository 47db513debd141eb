/* Sea-state descriptor: defaults resolved in one place, every field validated with a message
 * naming it, NaN never slips through. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <cmocka.h>
#include <math.h>
#include <string.h>

#include "core/seastate.h"

static void test_defaults(void **state)
{
    (void)state;
    struct seastate s = { 0 };
    seastate_resolve(&s);
    assert_float_equal(s.wind_speed_mps, 10.0, 0);
    assert_int_equal(s.spectrum, SPECTRUM_JONSWAP);
    assert_int_equal(s.patterns, 4);
    assert_int_equal(s.whitecap_model, WHITECAP_MOM80);
    assert_int_equal(s.budget_bytes, SWELL_BUDGET_DEFAULT);
    struct swell_err err = { 0 };
    assert_int_equal(seastate_validate(&s, &err), 0);
}

static void expect_bad(struct seastate s, const char *field)
{
    struct swell_err err = { 0 };
    assert_int_equal(seastate_validate(&s, &err), SWELL_E_ARG);
    if (!strstr(err.msg, field))
        fail_msg("message '%s' does not name '%s'", err.msg, field);
}

static void test_each_field_checked(void **state)
{
    (void)state;
    struct seastate ok = { 0 };
    seastate_resolve(&ok);
    struct seastate s;
    s = ok; s.wind_speed_mps = NAN;            expect_bad(s, "wind_speed_mps");
    s = ok; s.wind_speed_mps = -3;             expect_bad(s, "wind_speed_mps");
    s = ok; s.wind_speed_mps = 1e30f;          expect_bad(s, "wind_speed_mps");
    s = ok; s.wind_dir_deg = INFINITY;         expect_bad(s, "wind_dir_deg");
    s = ok; s.fetch_km = -1;                   expect_bad(s, "fetch_km");
    s = ok; s.depth_m = 0.5f;                  expect_bad(s, "depth_m");
    s = ok; s.spectrum = 99;                   expect_bad(s, "spectrum");
    s = ok; s.spread = NAN;                    expect_bad(s, "spread");
    s = ok; s.patterns = 5;                    expect_bad(s, "patterns");
    s = ok; s.loop_period_s = 1;               expect_bad(s, "loop_period_s");
    s = ok; s.frames = 1;                      expect_bad(s, "frames");
    s = ok; s.size_fs = 100;                   expect_bad(s, "size_fs");
    s = ok; s.size_geo = 4;                    expect_bad(s, "size_geo");
    s = ok; s.choppiness = 3;                  expect_bad(s, "choppiness");
    s = ok; s.whitecap_model = -2;             expect_bad(s, "whitecap_model");
    s = ok; s.foam_half_life_s = NAN;          expect_bad(s, "foam_half_life_s");
    s = ok; s.budget_bytes = 1000;             expect_bad(s, "budget_bytes");
}

static void test_names(void **state)
{
    (void)state;
    for (int k = 1; k < SPECTRUM_COUNT; k++)
        assert_int_equal(spectrum_from_name(spectrum_name(k)), k);
    for (int k = 1; k < WHITECAP_COUNT; k++)
        assert_int_equal(whitecap_model_from_name(whitecap_model_name(k)), k);
    assert_int_equal(spectrum_from_name("default"), -1);
    assert_int_equal(spectrum_from_name("jonswapx"), -1);
    assert_int_equal(spectrum_from_name(NULL), -1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_defaults),
        cmocka_unit_test(test_each_field_checked),
        cmocka_unit_test(test_names),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
