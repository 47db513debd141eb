/* Strict value parsing: every malformed, NaN, infinite, huge or out-of-range value is refused
 * with a message naming the option and the text. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <cmocka.h>
#include <string.h>

#include "core/parse.h"
#include "core/seastate.h"

static void bad_double(const char *text)
{
    struct swell_err err = { 0 };
    double v = -7;
    if (parse_double("--wind", text, 0.5, 40, "m/s", &v, &err) != SWELL_E_ARG)
        fail_msg("'%s' accepted as %g", text, v);
    assert_non_null(strstr(err.msg, "--wind"));
    assert_true(v == -7);
}

static void test_double(void **state)
{
    (void)state;
    struct swell_err err = { 0 };
    double v;
    assert_int_equal(parse_double("--wind", "12.5", 0.5, 40, "m/s", &v, &err), 0);
    assert_true(v == 12.5);
    assert_int_equal(parse_double("--wind", "1e1", 0.5, 40, "m/s", &v, &err), 0);
    const char *bad[] = { "", " 3", "3 ", "abc", "12x", "nan", "NaN", "inf", "-inf", "1e999",
                          "-1", "41", "0.4", "0x", "--", "1,2" };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++)
        bad_double(bad[i]);
    bad_double(NULL);
}

static void test_int(void **state)
{
    (void)state;
    struct swell_err err = { 0 };
    int v;
    assert_int_equal(parse_int("--frames", "16", 2, 256, &v, &err), 0);
    assert_int_equal(v, 16);
    const char *bad[] = { "", "1.5", "16a", "1", "257", "99999999999999999999", "-3", " 4" };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        assert_int_equal(parse_int("--frames", bad[i], 2, 256, &v, &err), SWELL_E_ARG);
        assert_non_null(strstr(err.msg, "--frames"));
    }
}

static void test_budget(void **state)
{
    (void)state;
    struct swell_err err = { 0 };
    uint64_t b;
    assert_int_equal(parse_budget("--budget", "tiny", &b, &err), 0);
    assert_int_equal(b, SWELL_BUDGET_TINY);
    assert_int_equal(parse_budget("--budget", "default", &b, &err), 0);
    assert_int_equal(b, SWELL_BUDGET_DEFAULT);
    assert_int_equal(parse_budget("--budget", "8M", &b, &err), 0);
    assert_int_equal(b, 8u << 20);
    assert_int_equal(parse_budget("--budget", "8MiB", &b, &err), 0);
    assert_int_equal(parse_budget("--budget", "1G", &b, &err), 0);
    assert_int_equal(parse_budget("--budget", "2097152", &b, &err), 0);
    assert_int_equal(b, 2097152u);
    const char *bad[] = { "", "huge", "8X", "8MM", "-8M", "2G", "100", "nan", "infM" };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++)
        assert_int_equal(parse_budget("--budget", bad[i], &b, &err), SWELL_E_ARG);
}

static void test_wxh_and_lists(void **state)
{
    (void)state;
    struct swell_err err = { 0 };
    int w, h;
    assert_int_equal(parse_wxh("--size", "1280x720", 16, 8192, &w, &h, &err), 0);
    assert_int_equal(w, 1280);
    assert_int_equal(h, 720);
    const char *bad[] = { "", "12x", "x12", "1280*720", "1280x720x3", "0x0", "99999x10", "-5x5" };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        assert_int_equal(parse_wxh("--size", bad[i], 16, 8192, &w, &h, &err), SWELL_E_ARG);
        assert_non_null(strstr(err.msg, "--size"));
    }
    double v[3];
    assert_int_equal(parse_doubles("--sun", "30,45", 2, -360, 360, v, &err), 0);
    assert_true(v[0] == 30 && v[1] == 45);
    assert_int_equal(parse_doubles("--sun", "30", 2, -360, 360, v, &err), SWELL_E_ARG);
    assert_int_equal(parse_doubles("--sun", "30,45,1", 2, -360, 360, v, &err), SWELL_E_ARG);
    assert_int_equal(parse_doubles("--sun", "30,nan", 2, -360, 360, v, &err), SWELL_E_ARG);
    assert_int_equal(parse_doubles("--sun", "30,", 2, -360, 360, v, &err), SWELL_E_ARG);
    assert_int_equal(parse_doubles("--sun", "999,1", 2, -360, 360, v, &err), SWELL_E_ARG);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_double),
        cmocka_unit_test(test_int),
        cmocka_unit_test(test_budget),
        cmocka_unit_test(test_wxh_and_lists),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
