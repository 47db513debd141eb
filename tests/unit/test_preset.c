/* test_preset.c - preset parsing: every seastate field, presets only touch the keys they name,
 * the shipped presets are valid sea states, and each kind of bad input is refused with
 * "file:line: key" and leaves the sea state unchanged. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "core/datadir.h"
#include "core/preset.h"

#define SRC "x.preset"

/* The shipped presets' directory, as swell finds it (core/datadir.h). */
static const char *data_dir(void)
{
    static char dir[4096];
    struct swell_err e = { 0 };
    if (!dir[0] && data_dir_find(DATADIR_PRESETS, dir, sizeof dir, &e))
        fail_msg("%s", e.msg);
    return dir;
}

/* Field by field: struct padding need not survive a struct copy. */
static void assert_same(const struct seastate *a, const struct seastate *b)
{
    assert_true(a->wind_speed_mps == b->wind_speed_mps);
    assert_true(a->wind_dir_deg == b->wind_dir_deg);
    assert_true(a->fetch_km == b->fetch_km);
    assert_true(a->depth_m == b->depth_m);
    assert_int_equal(a->spectrum, b->spectrum);
    assert_true(a->spread == b->spread);
    assert_int_equal(a->seed, b->seed);
    assert_int_equal(a->patterns, b->patterns);
    assert_true(a->loop_period_s == b->loop_period_s);
    assert_int_equal(a->frames, b->frames);
    assert_int_equal(a->size_fs, b->size_fs);
    assert_int_equal(a->size_geo, b->size_geo);
    assert_true(a->choppiness == b->choppiness);
    assert_int_equal(a->whitecap_model, b->whitecap_model);
    assert_true(a->foam_half_life_s == b->foam_half_life_s);
    assert_true(a->budget_bytes == b->budget_bytes);
}

static int parse(const char *text, struct seastate *s, struct swell_err *e)
{
    swell_err_clear(e);
    return preset_parse_memory(text, strlen(text), SRC, s, e);
}

static void test_all_fields(void **st)
{
    (void)st;
    const char *text =
        "# every field\n"
        "wind_speed_mps = 12.5\n"
        "wind_dir_deg = -45\n"
        "fetch_km = 250\n"
        "depth_m = 30.25\n"
        "spectrum = tma\n"
        "spread = 16\n"
        "seed = 4294967295\n"
        "patterns = 3\n"
        "loop_period_s = 20\n"
        "frames = 32\n"
        "size_fs = 128\n"
        "size_geo = 64\n"
        "choppiness = 0.75\n"
        "whitecap_model = wu88\n"
        "foam_half_life_s = 2.5\n"
        "budget_bytes = 8388608\n";
    struct seastate s;
    struct swell_err e;
    memset(&s, 0, sizeof s);
    if (parse(text, &s, &e) != 0)
        fail_msg("%s", e.msg);
    assert_true(s.wind_speed_mps == 12.5f);
    assert_true(s.wind_dir_deg == -45.0f);
    assert_true(s.fetch_km == 250.0f);
    assert_true(s.depth_m == 30.25f);
    assert_int_equal(s.spectrum, SPECTRUM_TMA);
    assert_true(s.spread == 16.0f);
    assert_int_equal(s.seed, 4294967295u);
    assert_int_equal(s.patterns, 3);
    assert_true(s.loop_period_s == 20.0f);
    assert_int_equal(s.frames, 32);
    assert_int_equal(s.size_fs, 128);
    assert_int_equal(s.size_geo, 64);
    assert_true(s.choppiness == 0.75f);
    assert_int_equal(s.whitecap_model, WHITECAP_WU88);
    assert_true(s.foam_half_life_s == 2.5f);
    assert_true(s.budget_bytes == 8388608u);
    /* The formatter used by the manifest writes text this parser reads back exactly. */
    char buf[2048];
    size_t len = 0;
    assert_int_equal(preset_format_state(&s, "", buf, sizeof buf, &len, &e), 0);
    struct seastate t;
    memset(&t, 0, sizeof t);
    assert_int_equal(preset_parse_memory(buf, len, SRC, &t, &e), 0);
    assert_same(&s, &t);
}

static void test_only_named_keys(void **st)
{
    (void)st;
    struct seastate s, before;
    struct swell_err e;
    memset(&s, 0, sizeof s);
    s.fetch_km = 77.0f;
    s.budget_bytes = SWELL_BUDGET_TINY;
    s.patterns = 2;
    before = s;
    assert_int_equal(parse("wind_speed_mps = 15\n", &s, &e), 0);
    assert_true(s.wind_speed_mps == 15.0f);
    s.wind_speed_mps = before.wind_speed_mps;
    assert_same(&s, &before);
    /* empty and comment-only presets change nothing */
    assert_int_equal(parse("", &s, &e), 0);
    assert_int_equal(parse("# nothing\n\n   \n", &s, &e), 0);
    assert_same(&s, &before);
}

static void expect_error(const char *text, int line, const char *what)
{
    struct seastate s, before;
    struct swell_err e;
    memset(&s, 0, sizeof s);
    s.wind_speed_mps = 3.0f;
    s.seed = 9;
    before = s;
    char where[64];
    snprintf(where, sizeof where, SRC ":%d:", line);
    int rc = parse(text, &s, &e);
    if (rc != SWELL_E_FORMAT || !strstr(e.msg, where) || !strstr(e.msg, what))
        fail_msg("for %s expected '%s ... %s', got %d: %s", text, where, what, rc, e.msg);
    assert_same(&s, &before);
}

static void test_errors(void **st)
{
    (void)st;
    expect_error("fetch_km = 10\nwind_speed = 5\n", 2, "unknown key 'wind_speed'");
    expect_error("# c\nwind_speed_mps = 5\nfetch_km = 1\nwind_speed_mps = 6\n", 4,
                 "duplicate key 'wind_speed_mps' (first set on line 2)");
    expect_error("wind_speed_mps = abc\n", 1, "wind_speed_mps");
    expect_error("wind_speed_mps = 1.5x\n", 1, "'1.5x' is not a number");
    expect_error("fetch_km = nan\n", 1, "fetch_km");
    expect_error("fetch_km = inf\n", 1, "fetch_km");
    expect_error("fetch_km = -infinity\n", 1, "fetch_km");
    expect_error("fetch_km = 1e999\n", 1, "fetch_km");
    expect_error("fetch_km = 1e300\n", 1, "outside");   /* finite double, not a float */
    expect_error("\n\nfetch_km =\n", 3, "has no value");
    expect_error("fetch_km 10\n", 1, "expected '='");
    expect_error("Fetch_km = 10\n", 1, "key");
    expect_error("patterns = 2.5\n", 1, "patterns");
    expect_error("frames = 99999999999\n", 1, "frames");
    expect_error("seed = -1\n", 1, "seed");
    expect_error("seed = 4294967296\n", 1, "seed");
    expect_error("budget_bytes = 18446744073709551616\n", 1, "out of range");
    expect_error("spectrum = jonswap2\n", 1, "spectrum");
    expect_error("whitecap_model = 1\n", 1, "whitecap_model");
    expect_error("wind_speed_mps = 5 m/s\n", 1, "wind_speed_mps");
}

struct listed {
    int n;
    char names[16][32];
};

static void on_preset(void *user, const char *name, const char *summary)
{
    struct listed *l = user;
    assert_true(summary[0] != '\0');
    if (l->n < 16)
        snprintf(l->names[l->n], sizeof l->names[0], "%s", name);
    l->n++;
}

/* The shipped presets: each resolves to a valid sea state; winds increase calm -> storm;
 * sea-state and budget presets combine. */
static void test_shipped(void **st)
{
    (void)st;
    const char *sea[] = { "calm", "moderate", "rough", "storm" };
    float last = 0.0f;
    struct swell_err e;
    for (int i = 0; i < 4; i++) {
        struct seastate s;
        memset(&s, 0, sizeof s);
        if (preset_load_from(sea[i], data_dir(), &s, &e) != 0)
            fail_msg("%s", e.msg);
        assert_true(s.wind_speed_mps > last);
        last = s.wind_speed_mps;
        assert_int_equal(s.budget_bytes, 0);
        seastate_resolve(&s);
        if (seastate_validate(&s, &e) != 0)
            fail_msg("%s: %s", sea[i], e.msg);
    }
    struct seastate s;
    memset(&s, 0, sizeof s);
    assert_int_equal(preset_load_from("rough", data_dir(), &s, &e), 0);
    assert_int_equal(preset_load_from("tiny", data_dir(), &s, &e), 0);
    assert_true(s.wind_speed_mps == 15.0f);
    assert_true(s.budget_bytes == SWELL_BUDGET_TINY);
    assert_int_equal(preset_load_from("default", data_dir(), &s, &e), 0);
    assert_true(s.budget_bytes == SWELL_BUDGET_DEFAULT);

    struct listed l = { 0 };
    assert_int_equal(preset_list(data_dir(), on_preset, &l, &e), 0);
    const char *want[] = { "calm", "default", "moderate", "rough", "storm", "tiny" };
    assert_int_equal(l.n, 6);
    for (int i = 0; i < 6; i++)
        assert_string_equal(l.names[i], want[i]);
}

static void test_names_and_paths(void **st)
{
    (void)st;
    struct seastate s;
    struct swell_err e;
    memset(&s, 0, sizeof s);
    assert_int_equal(preset_load_from("../etc/passwd", data_dir(), &s, &e), SWELL_E_ARG);
    assert_int_equal(preset_load_from("", data_dir(), &s, &e), SWELL_E_ARG);
    assert_int_equal(preset_load_from("no_such_preset", data_dir(), &s, &e), SWELL_E_IO);
    assert_non_null(strstr(e.msg, "no_such_preset"));

    const char *base = getenv("SWELL_TMP");
    char path[1100];
    snprintf(path, sizeof path, "%s/test_preset_%d.preset", base && base[0] ? base : "/tmp",
             (int)getpid());
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs("# a user preset\nchoppiness = 1.5\nbogus = 1\n", f);
    fclose(f);
    assert_int_equal(preset_load(path, &s, &e), SWELL_E_FORMAT);
    char where[1200];
    snprintf(where, sizeof where, "%s:3: unknown key 'bogus'", path);
    assert_string_equal(e.msg, where);
    f = fopen(path, "w");
    assert_non_null(f);
    fputs("choppiness = 1.5\n", f);
    fclose(f);
    assert_int_equal(preset_load(path, &s, &e), 0);
    assert_true(s.choppiness == 1.5f);
    remove(path);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_all_fields),
        cmocka_unit_test(test_only_named_keys),
        cmocka_unit_test(test_errors),
        cmocka_unit_test(test_shipped),
        cmocka_unit_test(test_names_and_paths),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
