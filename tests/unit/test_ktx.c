/* test_ktx.c - KTX 1.1 writer/reader: round trips, the header checked against the Khronos
 * spec's constants (not against the writer), and every kind of corruption refused with the
 * right code and a message naming the file and the field. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "tables/ktx.h"
#include "tables/tables.h"

#define NAME "test/slope_p1.ktx"

static uint32_t lcg(uint32_t *s)
{
    *s = *s * 1664525u + 1013904223u;
    return *s >> 8;
}

static void make_table(struct swell_table *t, int format, int w, int h, int layers,
                       int levels, uint32_t seed)
{
    memset(t, 0, sizeof *t);
    snprintf(t->name, sizeof t->name, "slope_p1");
    t->kind = TABLE_SLOPE;
    t->pattern = 1;
    t->format = format;
    t->width = w;
    t->height = h;
    t->layers = layers;
    t->levels = levels;
    /* values whose shortest decimal form is long, to exercise the %.9g round trip */
    const float sc[4] = { 0.1f, 1.0f / 3.0f, -1.17549435e-38f, 12345.6789f };
    const float bi[4] = { -0.7f, 3.40282347e38f, 1e-7f, -2.0f / 7.0f };
    memcpy(t->scale, sc, sizeof sc);
    memcpy(t->bias, bi, sizeof bi);
    assert_int_equal(table_alloc(t, NULL), 0);
    for (size_t i = 0; i < table_bytes(t); i++)
        t->data[i] = (uint8_t)lcg(&seed);
}

static uint32_t rd32(const uint8_t *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static void wr32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)v;
    p[1] = (uint8_t)(v >> 8);
    p[2] = (uint8_t)(v >> 16);
    p[3] = (uint8_t)(v >> 24);
}

static void expect_fail(const uint8_t *buf, size_t len, int code, const char *field)
{
    struct swell_table t;
    struct swell_err e;
    swell_err_clear(&e);
    int rc = ktx_read_memory(buf, len, NAME, &t, &e);
    if (rc != code || !strstr(e.msg, NAME) || (field && !strstr(e.msg, field)))
        fail_msg("expected code %d naming '%s', got %d: %s", code, field ? field : "", rc,
                 e.msg);
    assert_null(t.data);
}

static void roundtrip(int format, int w, int h, int layers, int levels)
{
    struct swell_table a, b;
    make_table(&a, format, w, h, layers, levels, (uint32_t)(w * 31 + layers));
    uint8_t *buf = NULL;
    size_t len = 0;
    struct swell_err e;
    assert_int_equal(ktx_write_memory(&a, &buf, &len, &e), 0);
    assert_int_equal(ktx_read_memory(buf, len, NAME, &b, &e), 0);
    assert_string_equal(a.name, b.name);
    assert_int_equal(a.kind, b.kind);
    assert_int_equal(a.pattern, b.pattern);
    assert_int_equal(a.format, b.format);
    assert_int_equal(a.width, b.width);
    assert_int_equal(a.height, b.height);
    assert_int_equal(a.layers, b.layers);
    assert_int_equal(a.levels, b.levels);
    assert_memory_equal(a.scale, b.scale, sizeof a.scale);
    assert_memory_equal(a.bias, b.bias, sizeof a.bias);
    assert_int_equal(table_bytes(&a), table_bytes(&b));
    assert_memory_equal(a.data, b.data, table_bytes(&a));

    /* Header against the spec's constants (KTX 1.1 §2). */
    static const uint8_t id[12] = { 0xAB, 'K', 'T', 'X', ' ', '1', '1', 0xBB, '\r', '\n',
                                    0x1A, '\n' };
    assert_memory_equal(buf, id, 12);
    const uint8_t endian[4] = { 1, 2, 3, 4 };
    assert_memory_equal(buf + 12, endian, 4);
    int f16 = format == FORMAT_RGBA16F;
    assert_int_equal(rd32(buf + 16), f16 ? 0x140B : 0x1401);
    assert_int_equal(rd32(buf + 20), f16 ? 2 : 1);
    assert_int_equal(rd32(buf + 24), 0x1908);
    assert_int_equal(rd32(buf + 28), f16 ? 0x881A : 0x8058);
    assert_int_equal(rd32(buf + 32), 0x1908);
    assert_int_equal(rd32(buf + 36), (uint32_t)w);
    assert_int_equal(rd32(buf + 40), (uint32_t)h);
    assert_int_equal(rd32(buf + 44), 0);
    assert_int_equal(rd32(buf + 48), layers == 1 ? 0u : (uint32_t)layers);
    assert_int_equal(rd32(buf + 52), 1);
    assert_int_equal(rd32(buf + 56), (uint32_t)levels);
    uint32_t kvb = rd32(buf + 60);
    assert_int_equal(kvb % 4, 0);
    /* Walk the key/value pairs independently and find the scale string. */
    int saw_scale = 0;
    for (uint32_t off = 0; off < kvb;) {
        uint32_t sz = rd32(buf + 64 + off);
        const char *k = (const char *)buf + 68 + off;
        if (strcmp(k, "swell.scale") == 0) {
            char want[128];
            snprintf(want, sizeof want, "%.9g %.9g %.9g %.9g", (double)a.scale[0],
                     (double)a.scale[1], (double)a.scale[2], (double)a.scale[3]);
            assert_string_equal(k + strlen(k) + 1, want);
            saw_scale = 1;
        }
        off += 4 + ((sz + 3) & ~3u);
    }
    assert_true(saw_scale);
    /* Image sizes: w*h*texel*layers per level, by the mip rule max(1, n >> l). */
    size_t off = 64 + kvb, texel = f16 ? 8 : 4;
    for (int l = 0; l < levels; l++) {
        size_t lw = (size_t)(w >> l ? w >> l : 1), lh = (size_t)(h >> l ? h >> l : 1);
        assert_int_equal(rd32(buf + off), lw * lh * texel * (size_t)layers);
        off += 4 + lw * lh * texel * (size_t)layers;
    }
    assert_int_equal(off, len);

    /* Determinism: same table, same bytes. */
    uint8_t *buf2 = NULL;
    size_t len2 = 0;
    assert_int_equal(ktx_write_memory(&b, &buf2, &len2, &e), 0);
    assert_int_equal(len, len2);
    assert_memory_equal(buf, buf2, len);
    free(buf);
    free(buf2);
    free(a.data);
    free(b.data);
}

static void test_roundtrip_rgba8_layers_mips(void **st)
{
    (void)st;
    roundtrip(FORMAT_RGBA8, 8, 4, 3, 4);
    roundtrip(FORMAT_RGBA8, 1, 1, 1, 1);
    roundtrip(FORMAT_RGBA8, 2, 16, 5, 2);
}

static void test_roundtrip_rgba16f(void **st)
{
    (void)st;
    roundtrip(FORMAT_RGBA16F, 16, 16, 1, 5);
    roundtrip(FORMAT_RGBA16F, 4, 8, 2, 1);
}

struct fixture {
    uint8_t *buf;
    size_t len;
    uint32_t kvb;
};

static void fixture_make(struct fixture *f)
{
    struct swell_table t;
    make_table(&t, FORMAT_RGBA8, 8, 4, 3, 4, 7);
    assert_int_equal(ktx_write_memory(&t, &f->buf, &f->len, NULL), 0);
    f->kvb = rd32(f->buf + 60);
    free(t.data);
}

static uint8_t *copy_of(const struct fixture *f, size_t extra)
{
    uint8_t *c = calloc(1, f->len + extra);
    assert_non_null(c);
    memcpy(c, f->buf, f->len);
    return c;
}

static void test_header_fields(void **st)
{
    (void)st;
    struct fixture f;
    fixture_make(&f);
    struct {
        int offset;
        uint32_t value;
        int code;
        const char *field;
    } cases[] = {
        { 12, 0x01020304, SWELL_E_UNSUPPORTED, "endianness" },
        { 12, 0x04030200, SWELL_E_FORMAT, "endianness" },
        { 16, 0x1406, SWELL_E_UNSUPPORTED, "glType" },
        { 16, 0, SWELL_E_UNSUPPORTED, "glType" },
        { 20, 4, SWELL_E_FORMAT, "glTypeSize" },
        { 24, 0x1907, SWELL_E_UNSUPPORTED, "glFormat" },
        { 28, 0x8051, SWELL_E_UNSUPPORTED, "glInternalFormat" },
        { 28, 0x881A, SWELL_E_UNSUPPORTED, "glInternalFormat" },
        { 32, 0x1907, SWELL_E_UNSUPPORTED, "glBaseInternalFormat" },
        { 36, 6, SWELL_E_FORMAT, "pixelWidth" },
        { 36, 0, SWELL_E_FORMAT, "pixelWidth" },
        { 36, 16384, SWELL_E_FORMAT, "pixelWidth" },
        { 36, 0x80000000u, SWELL_E_FORMAT, "pixelWidth" },
        { 36, 16, SWELL_E_FORMAT, "imageSize" },       /* valid alone, sizes disagree */
        { 40, 0, SWELL_E_FORMAT, "pixelHeight" },
        { 40, 0xFFFFFFFFu, SWELL_E_FORMAT, "pixelHeight" },
        { 44, 1, SWELL_E_UNSUPPORTED, "pixelDepth" },
        { 48, 1025, SWELL_E_FORMAT, "numberOfArrayElements" },
        { 48, 0xFFFFFFFFu, SWELL_E_FORMAT, "numberOfArrayElements" },
        { 48, 0, SWELL_E_FORMAT, "imageSize" },        /* 1 layer: sizes disagree */
        { 48, 1024, SWELL_E_FORMAT, "imageSize" },
        { 52, 6, SWELL_E_UNSUPPORTED, "numberOfFaces" },
        { 52, 0, SWELL_E_UNSUPPORTED, "numberOfFaces" },
        { 56, 0, SWELL_E_FORMAT, "numberOfMipmapLevels" },
        { 56, 5, SWELL_E_FORMAT, "numberOfMipmapLevels" },  /* 8x4 has 4 levels */
        { 56, 3, SWELL_E_FORMAT, "trailing" },
        { 60, 2, SWELL_E_FORMAT, "bytesOfKeyValueData" },
        { 60, 0xFFFFFFFCu, SWELL_E_FORMAT, "bytesOfKeyValueData" },
        { 60, 0, SWELL_E_FORMAT, "missing key" },
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        uint8_t *c = copy_of(&f, 0);
        wr32(c + cases[i].offset, cases[i].value);
        expect_fail(c, f.len, cases[i].code, cases[i].field);
        free(c);
    }
    /* imageSize of level 0 itself */
    uint8_t *c = copy_of(&f, 0);
    wr32(c + 64 + f.kvb, rd32(c + 64 + f.kvb) + 4);
    expect_fail(c, f.len, SWELL_E_FORMAT, "imageSize");
    free(c);
    free(f.buf);
}

static void test_identifier_and_version(void **st)
{
    (void)st;
    struct fixture f;
    fixture_make(&f);
    uint8_t *c = copy_of(&f, 0);
    c[1] = 'k';
    expect_fail(c, f.len, SWELL_E_FORMAT, "identifier");
    memcpy(c, f.buf, f.len);
    c[5] = '2';
    c[6] = '0';
    expect_fail(c, f.len, SWELL_E_VERSION, "identifier");
    memcpy(c, f.buf, f.len);
    c[10] = 0;
    expect_fail(c, f.len, SWELL_E_FORMAT, "identifier");
    free(c);
    free(f.buf);
}

/* Replace the first byte of the value of key in the key/value block. */
static void poke_value(uint8_t *c, size_t len, const char *key, char v)
{
    size_t kl = strlen(key) + 1;
    for (size_t i = 64; i + kl < len; i++)
        if (memcmp(c + i, key, kl) == 0) {
            c[i + kl] = (uint8_t)v;
            return;
        }
    fail_msg("key %s not found", key);
}

static void poke_key(uint8_t *c, size_t len, const char *key, char v)
{
    size_t kl = strlen(key) + 1;
    for (size_t i = 64; i + kl < len; i++)
        if (memcmp(c + i, key, kl) == 0) {
            c[i + kl - 2] = (uint8_t)v;
            return;
        }
    fail_msg("key %s not found", key);
}

static void test_metadata(void **st)
{
    (void)st;
    struct fixture f;
    fixture_make(&f);
    struct {
        const char *key;
        char v;
        int code;
        const char *field;
    } vals[] = {
        { "swell.version", '3', SWELL_E_VERSION, "swell.version" },
        { "swell.version", 'x', SWELL_E_FORMAT, "swell.version" },
        { "swell.kind", 'x', SWELL_E_FORMAT, "swell.kind" },
        { "swell.pattern", '7', SWELL_E_FORMAT, "swell.pattern" },
        { "swell.pattern", '\0', SWELL_E_FORMAT, "swell.pattern" },
        { "swell.scale", 'z', SWELL_E_FORMAT, "swell.scale" },
        { "swell.bias", ' ', SWELL_E_FORMAT, "swell.bias" },
        { "swell.crc32", 'X', SWELL_E_FORMAT, "swell.crc32" },
        { "swell.name", 'A', SWELL_E_FORMAT, "swell.name" },
        { "KTXorientation", 'T', SWELL_E_FORMAT, "KTXorientation" },
    };
    for (size_t i = 0; i < sizeof vals / sizeof vals[0]; i++) {
        uint8_t *c = copy_of(&f, 0);
        poke_value(c, f.len, vals[i].key, vals[i].v);
        expect_fail(c, f.len, vals[i].code, vals[i].field);
        free(c);
    }
    uint8_t *c = copy_of(&f, 0);
    poke_key(c, f.len, "swell.kind", 'x');            /* "swell.kinx": unknown */
    expect_fail(c, f.len, SWELL_E_FORMAT, "swell.kinx");
    memcpy(c, f.buf, f.len);
    poke_key(c, f.len, "swell.crc32", 'x');           /* "swell.crc3x": unknown */
    expect_fail(c, f.len, SWELL_E_FORMAT, "swell.crc3x");
    memcpy(c, f.buf, f.len);
    for (size_t i = 64; i < 64 + f.kvb; i++)          /* "swell.scale" -> "xwell.scale": a */
        if (memcmp(c + i, "swell.scale", 12) == 0)    /* foreign key, so scale is missing */
            c[i] = 'x';
    expect_fail(c, f.len, SWELL_E_FORMAT, "missing key 'swell.scale'");
    memcpy(c, f.buf, f.len);
    poke_key(c, f.len, "swell.bias", 'e');            /* "swell.biae" unknown */
    expect_fail(c, f.len, SWELL_E_FORMAT, "swell.biae");
    memcpy(c, f.buf, f.len);
    wr32(c + 64, 0xFFFFFFF0u);                        /* keyAndValueByteSize overrun */
    expect_fail(c, f.len, SWELL_E_FORMAT, "keyAndValueByteSize");
    free(c);
    free(f.buf);
}

static void test_data_crc_truncation_trailing(void **st)
{
    (void)st;
    struct fixture f;
    fixture_make(&f);
    uint8_t *c = copy_of(&f, 8);
    c[f.len - 3] ^= 0x40;                             /* last level's data */
    expect_fail(c, f.len, SWELL_E_CHECKSUM, "swell.crc32");
    memcpy(c, f.buf, f.len);
    c[64 + f.kvb + 4 + 17] ^= 1;                      /* level 0 data */
    expect_fail(c, f.len, SWELL_E_CHECKSUM, "swell.crc32");
    memcpy(c, f.buf, f.len);
    expect_fail(c, f.len + 4, SWELL_E_FORMAT, "trailing");
    expect_fail(c, f.len + 1, SWELL_E_FORMAT, "trailing");
    for (size_t n = 0; n < f.len; n++) {
        struct swell_table t;
        struct swell_err e;
        swell_err_clear(&e);
        int rc = ktx_read_memory(f.buf, n, NAME, &t, &e);
        if (rc == 0 || !strstr(e.msg, NAME))
            fail_msg("truncated at %zu: rc %d, %s", n, rc, e.msg);
        assert_null(t.data);
    }
    free(c);
    free(f.buf);
}

/* Random mutations of the header, metadata and data, some also truncated: no crash, no leak
 * (run under valgrind), and every refusal names the file. */
static void test_mutations(void **st)
{
    (void)st;
    struct fixture f;
    fixture_make(&f);
    uint32_t seed = 12345;
    uint8_t *c = copy_of(&f, 0);
    for (int it = 0; it < 3000; it++) {
        memcpy(c, f.buf, f.len);
        int flips = 1 + (int)(lcg(&seed) % 4);
        for (int k = 0; k < flips; k++) {
            size_t at = lcg(&seed) % (it % 3 == 0 ? 64 + f.kvb : f.len);
            c[at] = (uint8_t)lcg(&seed);
        }
        size_t n = it % 5 == 0 ? lcg(&seed) % f.len : f.len;
        struct swell_table t;
        struct swell_err e;
        if (ktx_read_memory(c, n, NAME, &t, &e) == 0)
            free(t.data);
        else
            assert_non_null(strstr(e.msg, NAME));
    }
    free(c);
    free(f.buf);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_roundtrip_rgba8_layers_mips),
        cmocka_unit_test(test_roundtrip_rgba16f),
        cmocka_unit_test(test_header_fields),
        cmocka_unit_test(test_identifier_and_version),
        cmocka_unit_test(test_metadata),
        cmocka_unit_test(test_data_crc_truncation_trailing),
        cmocka_unit_test(test_mutations),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
