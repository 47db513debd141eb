/* test_tables_io.c - table set directories: exact round trip of every field and byte,
 * deterministic files, and every inconsistency refused (missing, swapped, modified, unlisted
 * files; corrupt manifests), leftover temporary files never read. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <ftw.h>
#include <unistd.h>
#include <sys/stat.h>
#include <limits.h>

#include <cmocka.h>

#include "core/fsutil.h"
#include "tables/set_check.h"
#include "tables/tables_io.h"

static char scratch[1024];

static uint32_t lcg(uint32_t *s)
{
    *s = *s * 1664525u + 1013904223u;
    return *s >> 8;
}

/* A set shaped as a bake of its state would be (tables_layout) with values that pass
 * set_check.h, random texels and distinct scale and bias per table. */
static void make_set(struct swell_tables *s)
{
    memset(s, 0, sizeof *s);
    s->state = (struct seastate){
        .wind_speed_mps = 13.7f, .wind_dir_deg = -33.3f, .fetch_km = 123.456f,
        .depth_m = 17.25f, .spectrum = SPECTRUM_TMA, .spread = 7.1f, .seed = 4000000000u,
        .patterns = 2, .loop_period_s = 19.9f, .frames = 4, .size_fs = 16, .size_geo = 8,
        .choppiness = 1.3f, .whitecap_model = WHITECAP_WU88, .foam_half_life_s = 2.2f,
        .budget_bytes = 123456789ull,
    };
    s->patterns = 2;
    s->frames = 4;
    s->loop_period_s = 19.9f;
    double var_h = 0.0;
    for (int i = 0; i < s->patterns; i++) {
        s->pattern[i] = (struct swell_pattern_info){
            .size_m = 100.0f / (float)(i + 3), .k_min = 0.01f * (float)i,
            .k_max = 0.5f * (float)(i + 1), .lambda = 1.3f,
            .period_s = 19.9f / (float)(i + 1), .var_h = 1e-5f * (float)(i + 1),
            .mss_x = 0.011f, .mss_y = 0.007f,
        };
        var_h += s->pattern[i].var_h;
    }
    s->mss_unresolved_x = 1.0f / 300.0f;
    s->mss_unresolved_y = 2.0f / 700.0f;
    s->hs_m = (float)(4.0 * sqrt(var_h));
    s->foam_recovery_per_s = 0.0123456789f;
    s->whitecap_breaking_fraction = 0.00234f;
    s->whitecap_fraction_model = 0.0123f;
    s->whitecap_fraction_measured = 0.0119f;
    s->whitecap_epsilon = 0.3333333f;
    s->count = tables_layout(&s->state, s->table);
    for (int n = 0; n < s->count; n++) {
        struct swell_table *t = &s->table[n];
        for (int c = 0; c < 4; c++) {
            t->scale[c] = 1.0f / (float)(4 + c + n);
            t->bias[c] = 0.01f * (float)(c + 1);
        }
        assert_int_equal(table_alloc(t, NULL), 0);
        uint32_t seed = (uint32_t)(n + 1) * 977u;
        for (size_t i = 0; i < table_bytes(t); i++)
            t->data[i] = (uint8_t)lcg(&seed);
    }
}

static void path_in(char *buf, const char *dir, const char *file)
{
    snprintf(buf, 4096, "%s/%s/%s", scratch, dir, file);
}

static void dir_path(char *buf, const char *dir)
{
    snprintf(buf, 4096, "%s/%s", scratch, dir);
}

static void save(const struct swell_tables *s, const char *dir)
{
    char d[4096];
    struct swell_err e;
    dir_path(d, dir);
    if (tables_save_dir(s, d, &e) != 0)
        fail_msg("save: %s", e.msg);
}

static size_t slurp(const char *dir, const char *file, uint8_t **out)
{
    char p[4096];
    size_t len = 0;
    path_in(p, dir, file);
    struct swell_err e;
    if (fs_read_file(p, 1u << 26, out, &len, &e) != 0)
        fail_msg("%s", e.msg);
    return len;
}

static void spit(const char *dir, const char *file, const void *buf, size_t len)
{
    char p[4096];
    path_in(p, dir, file);
    FILE *f = fopen(p, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(buf, 1, len, f), len);
    fclose(f);
}

static const char *const files[] = { "disp_p0.ktx", "slope_p0.ktx", "slope_p1.ktx",
                                     "fresnel.ktx", "manifest.swell" };

static void assert_same_state(const struct seastate *a, const struct seastate *b)
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

static void test_roundtrip(void **st)
{
    (void)st;
    struct swell_tables a, b;
    struct swell_err e;
    make_set(&a);
    save(&a, "rt");
    char d[4096];
    dir_path(d, "rt");
    if (tables_load_dir(d, &b, &e) != 0)
        fail_msg("load: %s", e.msg);
    assert_same_state(&a.state, &b.state);
    assert_int_equal(a.patterns, b.patterns);
    assert_int_equal(a.frames, b.frames);
    assert_true(a.loop_period_s == b.loop_period_s);
    for (int i = 0; i < SWELL_MAX_PATTERNS; i++) {
        assert_true(a.pattern[i].size_m == b.pattern[i].size_m);
        assert_true(a.pattern[i].k_min == b.pattern[i].k_min);
        assert_true(a.pattern[i].k_max == b.pattern[i].k_max);
        assert_true(a.pattern[i].lambda == b.pattern[i].lambda);
        assert_true(a.pattern[i].period_s == b.pattern[i].period_s);
        assert_true(a.pattern[i].var_h == b.pattern[i].var_h);
        assert_true(a.pattern[i].mss_x == b.pattern[i].mss_x);
        assert_true(a.pattern[i].mss_y == b.pattern[i].mss_y);
    }
    assert_true(a.mss_unresolved_x == b.mss_unresolved_x);
    assert_true(a.mss_unresolved_y == b.mss_unresolved_y);
    assert_true(a.hs_m == b.hs_m);
    assert_true(a.foam_recovery_per_s == b.foam_recovery_per_s);
    assert_true(a.whitecap_breaking_fraction == b.whitecap_breaking_fraction);
    assert_true(a.whitecap_fraction_model == b.whitecap_fraction_model);
    assert_true(a.whitecap_fraction_measured == b.whitecap_fraction_measured);
    assert_true(a.whitecap_epsilon == b.whitecap_epsilon);
    assert_int_equal(a.count, b.count);
    for (int i = 0; i < a.count; i++) {
        const struct swell_table *x = &a.table[i], *y = &b.table[i];
        assert_string_equal(x->name, y->name);
        assert_int_equal(x->kind, y->kind);
        assert_int_equal(x->pattern, y->pattern);
        assert_int_equal(x->format, y->format);
        assert_int_equal(x->width, y->width);
        assert_int_equal(x->height, y->height);
        assert_int_equal(x->layers, y->layers);
        assert_int_equal(x->levels, y->levels);
        assert_memory_equal(x->scale, y->scale, sizeof x->scale);
        assert_memory_equal(x->bias, y->bias, sizeof x->bias);
        assert_int_equal(table_bytes(x), table_bytes(y));
        assert_memory_equal(x->data, y->data, table_bytes(x));
    }
    uint8_t *m = NULL;
    slurp("rt", "manifest.swell", &m);
    assert_memory_equal(m, "swell-manifest 5\n", 17);
    free(m);
    tables_destroy(&a);
    tables_destroy(&b);
}

static void test_deterministic(void **st)
{
    (void)st;
    struct swell_tables a;
    make_set(&a);
    save(&a, "det1");
    uint8_t *first[5];
    size_t len[5];
    for (int i = 0; i < 5; i++)
        len[i] = slurp("det1", files[i], &first[i]);
    save(&a, "det1");       /* over itself */
    save(&a, "det2");       /* fresh */
    for (int i = 0; i < 5; i++) {
        uint8_t *x = NULL, *y = NULL;
        assert_int_equal(slurp("det1", files[i], &x), len[i]);
        assert_int_equal(slurp("det2", files[i], &y), len[i]);
        assert_memory_equal(first[i], x, len[i]);
        assert_memory_equal(first[i], y, len[i]);
        free(x);
        free(y);
        free(first[i]);
    }
    tables_destroy(&a);
}

static void expect_load_fail(const char *dir, int code, const char *what)
{
    char d[4096];
    struct swell_tables t;
    struct swell_err e;
    swell_err_clear(&e);
    dir_path(d, dir);
    memset(&t, 0x55, sizeof t);
    int rc = tables_load_dir(d, &t, &e);
    if (rc != code || !strstr(e.msg, what))
        fail_msg("%s: expected code %d naming '%s', got %d: %s", dir, code, what, rc, e.msg);
    assert_int_equal(t.count, 0);
    for (int i = 0; i < SWELL_MAX_TABLES; i++)
        assert_null(t.table[i].data);
}

static void test_missing_swapped_modified_unlisted(void **st)
{
    (void)st;
    struct swell_tables a;
    make_set(&a);
    char p[4096], q[4096], r[4096];

    save(&a, "missing");
    path_in(p, "missing", "slope_p1.ktx");
    assert_int_equal(unlink(p), 0);
    expect_load_fail("missing", SWELL_E_IO, "slope_p1.ktx");

    save(&a, "swapped");
    path_in(p, "swapped", "slope_p0.ktx");
    path_in(q, "swapped", "slope_p1.ktx");
    path_in(r, "swapped", "x");
    assert_int_equal(rename(p, r), 0);
    assert_int_equal(rename(q, p), 0);
    assert_int_equal(rename(r, q), 0);
    expect_load_fail("swapped", SWELL_E_CHECKSUM, "slope_p0.ktx");

    save(&a, "modified");
    uint8_t *buf = NULL;
    size_t len = slurp("modified", "disp_p0.ktx", &buf);
    buf[len / 2] ^= 0x10;
    spit("modified", "disp_p0.ktx", buf, len);
    expect_load_fail("modified", SWELL_E_CHECKSUM, "disp_p0.ktx");
    spit("modified", "disp_p0.ktx", buf, len - 4);
    expect_load_fail("modified", SWELL_E_FORMAT, "disp_p0.ktx");
    free(buf);

    save(&a, "unlisted");
    spit("unlisted", "slope_p3.ktx", "junk", 4);
    expect_load_fail("unlisted", SWELL_E_FORMAT, "slope_p3.ktx");
    /* saving again replaces the whole folder: the stale table is gone */
    save(&a, "unlisted");
    path_in(p, "unlisted", "slope_p3.ktx");
    assert_int_not_equal(access(p, F_OK), 0);

    expect_load_fail("no_such_dir", SWELL_E_IO, "manifest");
    tables_destroy(&a);
}

/* A save owns only what it writes (set_dir.h): a folder holding anything but a table set is
 * refused untouched; a symlink to a set's folder stays a symlink; folders left by killed saves
 * are cleaned; the new set arrives whole. */
static void test_ownership(void **st)
{
    (void)st;
    struct swell_tables a, b;
    struct swell_err e;
    char d[4096], p[4096], q[4096];
    make_set(&a);
    const char *intruders[] = { "notes.ktx", "readme.txt", "stale_p3.ktx" };
    for (int i = 0; i < 3; i++) {
        save(&a, "own");
        spit("own", intruders[i], "mine", 4);
        dir_path(d, "own");
        swell_err_clear(&e);
        assert_int_equal(tables_save_dir(&a, d, &e), SWELL_E_ARG);
        assert_non_null(strstr(e.msg, intruders[i]));
        path_in(p, "own", intruders[i]);
        assert_int_equal(access(p, F_OK), 0);   /* untouched */
        assert_int_equal(unlink(p), 0);
        assert_int_equal(tables_load_dir(d, &b, &e), 0);   /* and the set still whole */
        tables_destroy(&b);
    }
    /* a folder or a symlink inside is not ours either */
    path_in(p, "own", "sub");
    assert_int_equal(mkdir(p, 0755), 0);
    assert_int_equal(tables_save_dir(&a, d, &e), SWELL_E_ARG);
    assert_int_equal(rmdir(p), 0);
    path_in(p, "own", "fresnel_link.ktx");
    assert_int_equal(symlink("/etc/hostname", p), 0);
    assert_int_equal(tables_save_dir(&a, d, &e), SWELL_E_ARG);
    assert_int_equal(unlink(p), 0);
    /* through a symlink: the folder it points to is replaced, the link kept */
    dir_path(q, "own_link");
    char abs[PATH_MAX];
    assert_non_null(realpath(d, abs));
    assert_int_equal(symlink(abs, q), 0);
    assert_true(snprintf(p, sizeof p, "%s/", q) < (int)sizeof p);   /* a trailing '/' names the same folder */
    if (tables_save_dir(&a, p, &e) != 0)
        fail_msg("save through a symlink: %s", e.msg);
    struct stat sb;
    assert_int_equal(lstat(q, &sb), 0);
    assert_true(S_ISLNK(sb.st_mode));
    assert_int_equal(tables_load_dir(q, &b, &e), 0);
    tables_destroy(&b);
    /* a folder a killed save left beside (no process holds it) goes with the next save */
    assert_true(snprintf(p, sizeof p, "%s.tmp.AbCdEf", d) < (int)sizeof p);
    assert_int_equal(mkdir(p, 0755), 0);
    assert_true(snprintf(q, sizeof q, "%s/slope_p0.ktx", p) < (int)sizeof q);
    FILE *f = fopen(q, "wb");
    assert_non_null(f);
    fclose(f);
    save(&a, "own");
    assert_int_not_equal(access(p, F_OK), 0);
    tables_destroy(&a);
}

/* A write killed before its rename leaves "<file>.tmp.XXXXXX": never read, never accepted. */
static void test_leftover_temp_files(void **st)
{
    (void)st;
    struct swell_tables a, b;
    struct swell_err e;
    make_set(&a);
    save(&a, "temp");
    spit("temp", "slope_p0.ktx" FS_TEMP_MARKER "Ab12Cd", "partial", 7);
    spit("temp", "manifest.swell" FS_TEMP_MARKER "Zz99Yy", "swell-manifest 3\nset.co", 22);
    char d[4096], p[4096];
    dir_path(d, "temp");
    if (tables_load_dir(d, &b, &e) != 0)
        fail_msg("temp files must be ignored: %s", e.msg);
    tables_destroy(&b);
    /* A save killed after removing the old manifest: only a temp manifest remains. */
    path_in(p, "temp", "manifest.swell");
    assert_int_equal(unlink(p), 0);
    expect_load_fail("temp", SWELL_E_IO, "manifest");
    /* fs_write_atomic leaves no temp file behind and replaces the target. */
    path_in(p, "temp", "atomic.bin");
    assert_int_equal(fs_write_atomic(p, "one", 3, &e), 0);
    assert_int_equal(fs_write_atomic(p, "second", 6, &e), 0);
    uint8_t *buf = NULL;
    assert_int_equal(slurp("temp", "atomic.bin", &buf), 6);
    assert_memory_equal(buf, "second", 6);
    free(buf);
    tables_destroy(&a);
}

struct seen {
    int n, bad;
    char bad_file[64];
};

static void on_entry(void *user, const struct tables_verify_entry *v)
{
    struct seen *s = user;
    s->n++;
    if (v->status) {
        s->bad++;
        snprintf(s->bad_file, sizeof s->bad_file, "%s", v->file);
        assert_non_null(strstr(v->msg, v->file));
    }
}

static void test_verify(void **st)
{
    (void)st;
    struct swell_tables a;
    struct swell_err e;
    make_set(&a);
    save(&a, "verify");
    char d[4096];
    dir_path(d, "verify");
    struct seen s = { 0 };
    assert_int_equal(tables_verify_dir(d, on_entry, &s, NULL, &e), 0);
    assert_int_equal(s.n, 8);
    assert_int_equal(s.bad, 0);
    uint8_t *buf = NULL;
    size_t len = slurp("verify", "fresnel.ktx", &buf);
    buf[len - 1] ^= 1;
    spit("verify", "fresnel.ktx", buf, len);
    free(buf);
    memset(&s, 0, sizeof s);
    assert_int_equal(tables_verify_dir(d, on_entry, &s, NULL, &e), SWELL_E_CHECKSUM);
    assert_int_equal(s.n, 8);
    assert_int_equal(s.bad, 1);
    assert_string_equal(s.bad_file, "fresnel.ktx");
    assert_non_null(strstr(e.msg, "fresnel.ktx"));
    tables_destroy(&a);
}

#define MNAME "dir/manifest.swell"

static void expect_manifest_fail(const char *text, size_t len, int code, const char *what)
{
    struct tables_manifest *m = malloc(sizeof *m);
    struct swell_err e;
    swell_err_clear(&e);
    int rc = manifest_read_memory(text, len, MNAME, m, &e);
    if (rc != code || !strstr(e.msg, MNAME) || (what && !strstr(e.msg, what)))
        fail_msg("expected %d naming '%s', got %d: %s", code, what ? what : "", rc, e.msg);
    assert_int_equal(m->set.count, 0);
    free(m);
}

/* As expect_manifest_fail, after sealing text again (set_check.h manifest_reseal): what an
 * edit by another program looks like, to reach the checks behind the seal. */
static void expect_resealed_fail(const char *text, size_t len, int code, const char *what)
{
    char *c = malloc(len + 64);
    memcpy(c, text, len);
    size_t n = manifest_reseal(c, len, len + 64);
    assert_true(n > 0);
    expect_manifest_fail(c, n, code, what);
    free(c);
}

/* Every line removed, every value damaged, the magic and version changed, truncations,
 * duplicates and unknown keys: each refused with the manifest's name (and the key); every
 * edit left unsealed refused by the seal. */
static void test_manifest_corruption(void **st)
{
    (void)st;
    struct swell_tables a;
    make_set(&a);
    save(&a, "man");
    tables_destroy(&a);
    uint8_t *buf = NULL;
    size_t len = slurp("man", "manifest.swell", &buf);
    const char *text = (const char *)buf;
    struct tables_manifest *m = malloc(sizeof *m);
    struct swell_err e;
    assert_int_equal(manifest_read_memory(text, len, MNAME, m, &e), 0);
    assert_int_equal(m->set.count, 8);
    free(m);
    char *c = malloc(len + 64);
    int lines = 0;
    for (size_t i = 0; i < len; i++) {
        if (i != 0 && text[i - 1] != '\n')
            continue;
        const char *nl = memchr(text + i, '\n', len - i);
        size_t end = nl ? (size_t)(nl - text) + 1 : len;
        lines++;
        if (text[i] == '#')
            continue;
        if (end == len) {   /* the seal: dropped, damaged, wrong */
            assert_memory_equal(text + i, "manifest.crc32 = ", 17);
            expect_manifest_fail(text, i, SWELL_E_FORMAT, "last line is not 'manifest.crc32");
            memcpy(c, text, len);
            c[i + 17] = '?';
            expect_manifest_fail(c, len, SWELL_E_FORMAT, "manifest.crc32");
            c[i + 17] = text[i + 17] == '1' ? '2' : '1';
            expect_manifest_fail(c, len, SWELL_E_CHECKSUM, "edited or is damaged");
            continue;
        }
        /* drop the line */
        memcpy(c, text, i);
        memcpy(c + i, text + end, len - end);
        expect_resealed_fail(c, len - (end - i), SWELL_E_FORMAT,
                             lines == 1 ? "swell-manifest" : "missing key");
        if (lines == 1)
            continue;
        expect_manifest_fail(c, len - (end - i), SWELL_E_CHECKSUM, "manifest.crc32");
        /* damage the value: "= x..." */
        memcpy(c, text, len);
        const char *eq = memchr(text + i, '=', end - i);
        assert_non_null(eq);
        c[eq - text + 2] = '?';
        char key[96];
        snprintf(key, sizeof key, "%.*s", (int)(eq - text - 1 - (long)i), text + i);
        expect_resealed_fail(c, len, SWELL_E_FORMAT, key);
        expect_manifest_fail(c, len, SWELL_E_CHECKSUM, "manifest.crc32");
        /* the line twice */
        memcpy(c, text, end);
        memcpy(c + end, text + i, len - i);
        expect_resealed_fail(c, len + (end - i), SWELL_E_FORMAT, "duplicate key");
    }
    assert_true(lines > 60);
    memcpy(c, text, len);
    c[15] = '1';   /* a manifest of the previous format */
    expect_manifest_fail(c, len, SWELL_E_VERSION, "version 1");
    c[15] = 'x';
    expect_manifest_fail(c, len, SWELL_E_FORMAT, "version");
    memcpy(c, text, len);
    c[0] = 'S';
    expect_manifest_fail(c, len, SWELL_E_FORMAT, "swell-manifest");
    memcpy(c, text, len);
    memcpy(c + len, "bogus.key = 1\n", 14);
    expect_manifest_fail(c, len + 14, SWELL_E_FORMAT, "last line is not 'manifest.crc32");
    const char *seal = strstr(text, "\nmanifest.crc32 = ");
    assert_non_null(seal);
    size_t body = (size_t)(seal - text) + 1;   /* the lines above the seal */
    memcpy(c + body, "bogus.key = 1\n", 14);
    expect_resealed_fail(c, body + 14, SWELL_E_FORMAT, "unknown key 'bogus.key'");
    memcpy(c + body, "set.count 4\n", 12);
    expect_resealed_fail(c, body + 12, SWELL_E_FORMAT, "expected '='");
    /* Truncations: only whole lines can succeed, and only the whole file has every key. */
    for (size_t n = 0; n < len - 1; n++) {
        struct tables_manifest *t = malloc(sizeof *t);
        swell_err_clear(&e);
        if (manifest_read_memory(text, n, MNAME, t, &e) == 0)
            fail_msg("truncated manifest (%zu of %zu bytes) accepted", n, len);
        assert_non_null(strstr(e.msg, MNAME));
        free(t);
    }
    free(c);
    free(buf);
}

static int remove_entry(const char *path, const struct stat *sb, int flag, struct FTW *ftw)
{
    (void)sb;
    (void)flag;
    (void)ftw;
    return remove(path);
}

int main(void)
{
    const char *base = getenv("SWELL_TMP");
    snprintf(scratch, sizeof scratch, "%s/test_tables_io.XXXXXX", base && base[0] ? base : "/tmp");
    struct swell_err e;
    if (base && base[0] && fs_mkdir_p(base, &e) != 0) {
        fprintf(stderr, "%s\n", e.msg);
        return 1;
    }
    if (!mkdtemp(scratch)) {
        perror(scratch);
        return 1;
    }
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_roundtrip),
        cmocka_unit_test(test_deterministic),
        cmocka_unit_test(test_missing_swapped_modified_unlisted),
        cmocka_unit_test(test_leftover_temp_files),
        cmocka_unit_test(test_ownership),
        cmocka_unit_test(test_verify),
        cmocka_unit_test(test_manifest_corruption),
    };
    int failed = cmocka_run_group_tests(tests, NULL, NULL);
    /* Keep the evidence when something failed. */
    if (!failed)
        nftw(scratch, remove_entry, 16, FTW_DEPTH | FTW_PHYS);
    return failed;
}
