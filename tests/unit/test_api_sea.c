/* The public sea's descriptor and description (include/swell.h, api/api_sea.c) as swell-bake
 * uses them: every sea-state option by name, in order, presets among them; the check without a
 * bake; the --help texts; the measures and tables of a baked sea; a table folder checked file by
 * file. Only swell.h is included: what an application can do. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <cmocka.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "swell.h"

/* small and quick: 32 texel tables, 16 texel displacement, 4 frames */
#define SMALL "--size", "32", "--size-geo", "16", "--frames", "4"

static void progress(void *user, double done, const char *stage)
{
    double *last = user;
    assert_true(done >= *last && done <= 1.0);
    assert_non_null(stage);
    *last = done;
}

static void test_options_in_order(void **state)
{
    (void)state;
    /* the preset first, a later option overrides it; the fields are applied before options */
    const char *opt[] = { "--preset", "calm", "--wind", "7", "--patterns", "2",
                          "--spread", "4", SMALL, NULL };
    double last = 0.0;
    swell_sea_desc d = { .wind_speed_mps = 20.0f, .options = opt, .progress = progress,
                         .progress_user = &last };
    swell_sea *sea = NULL;
    struct swell_err err = { 0 };
    assert_int_equal(swell_sea_bake(&d, &sea, &err), SWELL_OK);
    swell_sea_info info;
    swell_sea_get_info(sea, &info);
    assert_true(info.wind_speed_mps == 7.0f);
    assert_int_equal(info.patterns, 2);
    assert_int_equal(info.table_size, 32);
    assert_int_equal(info.geometry_size, 16);
    assert_int_equal(info.frames, 4);
    assert_string_equal(info.spectrum, "jonswap");
    assert_true(last > 0.99);   /* progress reached the end */
    /* the measures are the bake's: slopes resolved and not, a whitecap fraction */
    assert_true(info.mss_resolved[0] > 0.0 && info.mss_resolved[1] > 0.0);
    assert_true(info.mss_unresolved[0] >= 0.0);
    assert_true(info.whitecap_fraction_model > 0.0f);
    assert_true(info.gpu_bytes_max > 0 && info.gpu_bytes_max <= info.budget_bytes);
    /* the tables, one by one, add up to the whole */
    uint64_t sum = 0;
    for (int i = 0; i < info.tables; i++) {
        swell_table_info t;
        assert_int_equal(swell_sea_get_table(sea, i, &t, &err), SWELL_OK);
        assert_true(strlen(t.name) > 4 && t.bytes > 0 && t.width > 0 && t.levels > 0);
        sum += t.bytes;
    }
    assert_true(info.tables == 2 * 3 + 2);
    assert_true(sum == info.table_bytes);
    swell_table_info t;
    assert_int_equal(swell_sea_get_table(sea, info.tables, &t, &err), SWELL_E_ARG);
    assert_non_null(strstr(err.msg, "no table"));
    swell_sea_destroy(sea);
}

static void test_bad_options(void **state)
{
    (void)state;
    struct swell_err err = { 0 };
    const char *unknown[] = { "--wind", "7", "--frobnicate", "3", NULL };
    swell_sea_desc d = { .options = unknown };
    assert_int_equal(swell_sea_check(&d, &err), SWELL_E_ARG);
    assert_non_null(strstr(err.msg, "--frobnicate"));
    const char *novalue[] = { "--wind", NULL };
    d.options = novalue;
    assert_int_equal(swell_sea_check(&d, &err), SWELL_E_ARG);
    assert_non_null(strstr(err.msg, "no value"));
    /* the first bad value is the one named */
    const char *badvalue[] = { "--spread", "abc", "--wind", "99", NULL };
    d.options = badvalue;
    swell_sea *sea = NULL;
    assert_int_equal(swell_sea_bake(&d, &sea, &err), SWELL_E_ARG);
    assert_null(sea);
    assert_non_null(strstr(err.msg, "--spread"));
    /* a budget too small for the tables asked: found without baking */
    const char *budget[] = { "--budget", "1M", "--size", "512", NULL };
    d.options = budget;
    assert_int_equal(swell_sea_check(&d, &err), SWELL_E_BUDGET);
    const char *good[] = { "--preset", "rough", SMALL, NULL };
    d.options = good;
    assert_int_equal(swell_sea_check(&d, &err), SWELL_OK);
    assert_int_equal(swell_sea_option("--wind"), 1);
    assert_int_equal(swell_sea_option("--preset"), 1);
    assert_int_equal(swell_sea_option("--out"), 0);
    assert_int_equal(swell_sea_option(NULL), 0);
}

static void test_usage(void **state)
{
    (void)state;
    size_t n = swell_sea_usage(SWELL_USAGE_SEA, NULL, 0);
    assert_true(n > 100);
    char *buf = malloc(n + 1);
    assert_int_equal(swell_sea_usage(SWELL_USAGE_SEA, buf, n + 1), n);
    assert_int_equal(strlen(buf), n);
    assert_non_null(strstr(buf, "--wind"));
    assert_null(strstr(buf, "--size-geo"));   /* a table option, in the other text */
    char small[16];
    assert_int_equal(swell_sea_usage(SWELL_USAGE_SEA, small, sizeof small), n);
    assert_int_equal(strlen(small), sizeof small - 1);
    assert_memory_equal(small, buf, sizeof small - 1);
    free(buf);
    char t[4096];
    swell_sea_usage(SWELL_USAGE_TABLES, t, sizeof t);
    assert_non_null(strstr(t, "--size-geo"));
    swell_sea_usage(SWELL_USAGE_DATA, t, sizeof t);
    assert_non_null(strstr(t, "Data"));
}

struct rows {
    int n, bad, unlisted;
};

static void row(void *user, const swell_table_info *t, int listed, int status, const char *msg)
{
    struct rows *r = user;
    r->n++;
    r->unlisted += !listed;
    if (status) {
        r->bad++;
        assert_true(strlen(msg) > 0);
    }
    assert_true(strlen(t->name) > 0);
}

static void test_check_dir(void **state)
{
    (void)state;
    char dir[] = "/tmp/swell-api-sea.XXXXXX";
    assert_non_null(mkdtemp(dir));
    char set[4096], file[4200];
    snprintf(set, sizeof set, "%s/set", dir);
    const char *opt[] = { "--patterns", "1", SMALL, NULL };
    swell_sea_desc d = { .options = opt };
    swell_sea *sea = NULL;
    struct swell_err err = { 0 };
    assert_int_equal(swell_sea_bake(&d, &sea, &err), SWELL_OK);
    assert_int_equal(swell_sea_save(sea, set, &err), SWELL_OK);
    swell_sea_info baked, read;
    swell_sea_get_info(sea, &baked);
    struct rows r = { 0 };
    assert_int_equal(swell_sea_check_dir(set, row, &r, &read, &err), SWELL_OK);
    assert_int_equal(r.n, baked.tables);
    assert_int_equal(r.bad, 0);
    assert_int_equal(read.patterns, 1);
    assert_true(read.wind_speed_mps == baked.wind_speed_mps);
    assert_true(read.significant_height_m == baked.significant_height_m);
    assert_true(read.table_bytes >= baked.table_bytes);   /* the files', with their headers */
    /* one table's file damaged: its row says so, the call fails, the manifest still read */
    swell_table_info t;
    assert_int_equal(swell_sea_get_table(sea, 0, &t, &err), SWELL_OK);
    snprintf(file, sizeof file, "%s/%s.ktx", set, t.name);
    FILE *f = fopen(file, "r+b");
    assert_non_null(f);
    fseek(f, -8, SEEK_END);
    fputc(0x5a, f);
    fputc(0xa5, f);
    fclose(f);
    memset(&r, 0, sizeof r);
    assert_int_not_equal(swell_sea_check_dir(set, row, &r, &read, &err), SWELL_OK);
    assert_int_equal(r.bad, 1);
    assert_int_equal(read.patterns, 1);
    /* no folder: nothing read, the info zeroed */
    snprintf(file, sizeof file, "%s/none", dir);
    memset(&r, 0, sizeof r);
    assert_int_not_equal(swell_sea_check_dir(file, row, &r, &read, &err), SWELL_OK);
    assert_int_equal(read.patterns, 0);
    swell_sea_destroy(sea);
    char cmd[4200];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    assert_int_equal(system(cmd), 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_options_in_order),
        cmocka_unit_test(test_bad_options),
        cmocka_unit_test(test_usage),
        cmocka_unit_test(test_check_dir),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
