/* test_tables - table geometry helpers (tables.h) against brute-force sums of level sizes. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdlib.h>
#include <string.h>

#include "tables/tables.h"

static void set_geometry(struct swell_table *t, int w, int h, int layers, int levels, int fmt)
{
    memset(t, 0, sizeof *t);
    strcpy(t->name, "t");
    t->width = w;
    t->height = h;
    t->layers = layers;
    t->levels = levels;
    t->format = fmt;
    t->pattern = -1;
}

/* Level sizes by repeated halving (not by shifting), texel size from the format's definition. */
static size_t ref_level_bytes(int w, int h, int level, int fmt)
{
    for (int i = 0; i < level; i++) {
        w = w / 2 < 1 ? 1 : w / 2;
        h = h / 2 < 1 ? 1 : h / 2;
    }
    return (size_t)w * (size_t)h * (fmt == FORMAT_RGBA8 ? 4u : 4u * sizeof(uint16_t));
}

static void test_offsets_vs_brute_force(void **state)
{
    (void)state;
    const int sizes[][2] = { { 1, 1 }, { 8, 8 }, { 16, 4 }, { 2, 64 }, { 256, 256 } };
    for (size_t s = 0; s < sizeof sizes / sizeof sizes[0]; s++)
        for (int fmt = 0; fmt < FORMAT_COUNT; fmt++)
            for (int layers = 1; layers <= 5; layers += 2) {
                int w = sizes[s][0], h = sizes[s][1];
                int full = 1;
                for (int m = w > h ? w : h; m > 1; m /= 2)
                    full++;
                for (int levels = 1; levels <= full; levels++) {
                    struct swell_table t;
                    set_geometry(&t, w, h, layers, levels, fmt);
                    /* walk the file order texel block by block */
                    size_t running = 0;
                    for (int l = 0; l < levels; l++) {
                        assert_int_equal(table_level_bytes(&t, l), ref_level_bytes(w, h, l, fmt));
                        for (int a = 0; a < layers; a++) {
                            assert_int_equal(table_offset(&t, l, a), running);
                            running += ref_level_bytes(w, h, l, fmt);
                        }
                    }
                    assert_int_equal(table_bytes(&t), running);
                }
            }
}

static void test_level_dims(void **state)
{
    (void)state;
    struct swell_table t;
    set_geometry(&t, 64, 4, 1, 7, FORMAT_RGBA8);
    const int ew[] = { 64, 32, 16, 8, 4, 2, 1 }, eh[] = { 4, 2, 1, 1, 1, 1, 1 };
    for (int l = 0; l < 7; l++) {
        assert_int_equal(table_level_width(&t, l), ew[l]);
        assert_int_equal(table_level_height(&t, l), eh[l]);
    }
}

static void test_alloc_rejects_bad_geometry(void **state)
{
    (void)state;
    struct swell_err err = { 0 };
    struct swell_table t;
    set_geometry(&t, 24, 16, 1, 1, FORMAT_RGBA8);
    assert_int_equal(table_alloc(&t, &err), SWELL_E_ARG);
    assert_null(t.data);
    assert_true(strlen(err.msg) > 0);
    set_geometry(&t, 16, 16, 0, 1, FORMAT_RGBA8);
    assert_int_equal(table_alloc(&t, &err), SWELL_E_ARG);
    set_geometry(&t, 16, 16, 1, 6, FORMAT_RGBA8);   /* full chain is 5 */
    assert_int_equal(table_alloc(&t, &err), SWELL_E_ARG);
    set_geometry(&t, 16, 16, 1, 1, FORMAT_COUNT);
    assert_int_equal(table_alloc(&t, &err), SWELL_E_ARG);
    set_geometry(&t, 16, 16, 2, 5, FORMAT_RGBA16F);
    assert_int_equal(table_alloc(&t, &err), 0);
    assert_non_null(t.data);
    for (size_t i = 0; i < table_bytes(&t); i++)
        assert_int_equal(t.data[i], 0);
    uint8_t *keep = t.data;
    assert_int_equal(table_alloc(&t, &err), SWELL_E_ARG);   /* would leak */
    assert_ptr_equal(t.data, keep);
    free(t.data);
}

static void test_find_and_total(void **state)
{
    (void)state;
    struct swell_tables s;
    memset(&s, 0, sizeof s);
    struct swell_err err = { 0 };
    size_t expect = 0;
    for (int p = 0; p < 3; p++) {
        struct swell_table *t = &s.table[s.count];
        set_geometry(t, 32, 32, 4, 6, FORMAT_RGBA8);
        t->kind = TABLE_SLOPE;
        t->pattern = p;
        assert_int_equal(table_alloc(t, &err), 0);
        expect += table_bytes(t);
        s.count++;
    }
    struct swell_table *f = &s.table[s.count];
    set_geometry(f, 64, 64, 1, 1, FORMAT_RGBA8);
    f->kind = TABLE_FRESNEL;
    assert_int_equal(table_alloc(f, &err), 0);
    expect += 64 * 64 * 4;
    s.count++;

    assert_int_equal(tables_bytes(&s), expect);
    assert_ptr_equal(tables_find(&s, TABLE_SLOPE, 2), &s.table[2]);
    assert_ptr_equal(tables_find(&s, TABLE_FRESNEL, -1), f);
    assert_null(tables_find(&s, TABLE_SLOPE, 3));
    assert_null(tables_find(&s, TABLE_FRESNEL_EFF, -1));
    tables_destroy(&s);
    assert_int_equal(s.count, 0);
    for (int i = 0; i < SWELL_MAX_TABLES; i++)
        assert_null(s.table[i].data);
    tables_destroy(&s);   /* twice is harmless */
}

/* A builder that failed after allocating table[count] but before count++ (run under
 * valgrind/ASan to see the leak this guards against). */
static void test_destroy_half_built(void **state)
{
    (void)state;
    struct swell_tables s;
    memset(&s, 0, sizeof s);
    struct swell_err err = { 0 };
    set_geometry(&s.table[0], 8, 8, 1, 1, FORMAT_RGBA8);
    assert_int_equal(table_alloc(&s.table[0], &err), 0);
    s.count = 1;
    set_geometry(&s.table[1], 8, 8, 1, 1, FORMAT_RGBA8);
    assert_int_equal(table_alloc(&s.table[1], &err), 0);
    tables_destroy(&s);
    assert_null(s.table[0].data);
    assert_null(s.table[1].data);

    struct swell_tables zero;
    memset(&zero, 0, sizeof zero);
    tables_destroy(&zero);
    tables_destroy(NULL);
}

static void test_names(void **state)
{
    (void)state;
    assert_string_equal(table_kind_name(TABLE_SLOPE), "slope");
    assert_string_equal(table_kind_name(TABLE_FRESNEL_EFF), "fresnel_eff");
    assert_string_equal(table_kind_name(-1), "?");
    assert_string_equal(table_kind_name(TABLE_KIND_COUNT), "?");
    assert_string_equal(table_format_name(FORMAT_RGBA8), "rgba8");
    assert_string_equal(table_format_name(FORMAT_RGBA16F), "rgba16f");
    assert_string_equal(table_format_name(FORMAT_COUNT), "?");
    for (int k = 0; k < TABLE_KIND_COUNT; k++)
        for (int j = k + 1; j < TABLE_KIND_COUNT; j++)
            assert_string_not_equal(table_kind_name(k), table_kind_name(j));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_offsets_vs_brute_force),
        cmocka_unit_test(test_level_dims),
        cmocka_unit_test(test_alloc_rejects_bad_geometry),
        cmocka_unit_test(test_find_and_total),
        cmocka_unit_test(test_destroy_half_built),
        cmocka_unit_test(test_names),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
