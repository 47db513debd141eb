#include "tables/ktx.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/fsutil.h"

/* KTX 1.1 §2.1: "«KTX 11»\r\n\x1A\n" */
static const uint8_t ktx_identifier[12] = {
    0xAB, 0x4B, 0x54, 0x58, 0x20, 0x31, 0x31, 0xBB, 0x0D, 0x0A, 0x1A, 0x0A
};

#define KTX_HEADER_BYTES 64
#define KTX_ENDIAN_REF   0x04030201u
#define KTX_MAX_KV_BYTES 65536

/* The header fields after the identifier, in file order (KTX 1.1 §2.2-2.14). */
enum {
    H_ENDIANNESS, H_GL_TYPE, H_GL_TYPE_SIZE, H_GL_FORMAT, H_GL_INTERNAL_FORMAT,
    H_GL_BASE_INTERNAL_FORMAT, H_PIXEL_WIDTH, H_PIXEL_HEIGHT, H_PIXEL_DEPTH,
    H_ARRAY_ELEMENTS, H_FACES, H_MIP_LEVELS, H_KV_BYTES, H_COUNT
};

static const char *const header_names[H_COUNT] = {
    "endianness", "glType", "glTypeSize", "glFormat", "glInternalFormat",
    "glBaseInternalFormat", "pixelWidth", "pixelHeight", "pixelDepth",
    "numberOfArrayElements", "numberOfFaces", "numberOfMipmapLevels", "bytesOfKeyValueData"
};

static void put_u32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)v;
    p[1] = (uint8_t)(v >> 8);
    p[2] = (uint8_t)(v >> 16);
    p[3] = (uint8_t)(v >> 24);
}

static uint32_t get_u32(const uint8_t *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static size_t pad4(size_t n)
{
    return (n + 3) & ~(size_t)3;
}

static int is_pow2(uint32_t v)
{
    return v > 0 && (v & (v - 1)) == 0;
}

static int full_chain(uint32_t w, uint32_t h)
{
    uint32_t m = w > h ? w : h;
    int n = 1;
    while (m > 1) {
        m >>= 1;
        n++;
    }
    return n;
}

/* ---- writer --------------------------------------------------------------------------- */

#define KV_KEYS 9

struct kv_pair {
    const char *key;
    char value[160];
};

static void fmt4(char *buf, size_t cap, const float v[4])
{
    snprintf(buf, cap, "%.9g %.9g %.9g %.9g", (double)v[0], (double)v[1], (double)v[2],
             (double)v[3]);
}

int ktx_write_memory(const struct swell_table *t, uint8_t **out, size_t *out_len,
                     struct swell_err *err)
{
    *out = NULL;
    *out_len = 0;
    if (t->format < 0 || t->format >= FORMAT_COUNT)
        return swell_fail(err, SWELL_E_ARG, "table %s: unknown format %d", t->name, t->format);
    if (!table_name_valid(t->name) || t->kind < 0 || t->kind >= TABLE_KIND_COUNT ||
        t->pattern < -1 || t->pattern >= SWELL_MAX_PATTERNS)
        return swell_fail(err, SWELL_E_ARG, "table '%s': invalid name, kind %d or pattern %d",
                          t->name, t->kind, t->pattern);
    if (!is_pow2((uint32_t)t->width) || !is_pow2((uint32_t)t->height) ||
        t->width > KTX_MAX_DIM || t->height > KTX_MAX_DIM || t->layers < 1 ||
        t->layers > KTX_MAX_LAYERS || t->levels < 1 ||
        t->levels > full_chain((uint32_t)t->width, (uint32_t)t->height))
        return swell_fail(err, SWELL_E_ARG, "table %s: %dx%d, %d layers, %d levels cannot be "
                          "stored (powers of two up to %d, layers up to %d, levels up to the "
                          "full chain)", t->name, t->width, t->height, t->layers, t->levels,
                          KTX_MAX_DIM, KTX_MAX_LAYERS);
    size_t data_bytes = table_bytes(t);
    if (!t->data || data_bytes == 0)
        return swell_fail(err, SWELL_E_ARG, "table %s: no image data", t->name);

    /* Fixed key order, so equal tables give equal files. */
    struct kv_pair kv[KV_KEYS] = {
        {"KTXorientation", "S=r,T=u"},
        {"swell.bias", ""},
        {"swell.crc32", ""},
        {"swell.kind", ""},
        {"swell.name", ""},
        {"swell.pattern", ""},
        {"swell.scale", ""},
        {"swell.set", ""},
        {"swell.version", ""},
    };
    fmt4(kv[1].value, sizeof kv[1].value, t->bias);
    snprintf(kv[2].value, sizeof kv[2].value, "0x%08x", fs_crc32(t->data, data_bytes));
    snprintf(kv[3].value, sizeof kv[3].value, "%s", table_kind_name(t->kind));
    snprintf(kv[4].value, sizeof kv[4].value, "%s", t->name);
    snprintf(kv[5].value, sizeof kv[5].value, "%d", t->pattern);
    fmt4(kv[6].value, sizeof kv[6].value, t->scale);
    snprintf(kv[7].value, sizeof kv[7].value, "0x%08x", t->set_id);
    snprintf(kv[8].value, sizeof kv[8].value, "%d", KTX_SWELL_VERSION);

    size_t kv_bytes = 0;
    for (int i = 0; i < KV_KEYS; i++)
        kv_bytes += 4 + pad4(strlen(kv[i].key) + 1 + strlen(kv[i].value) + 1);
    size_t total = KTX_HEADER_BYTES + kv_bytes;
    for (int l = 0; l < t->levels; l++)
        total += 4 + pad4(table_level_bytes(t, l) * (size_t)t->layers);

    uint8_t *buf = calloc(total, 1);
    if (!buf)
        return swell_fail(err, SWELL_E_NOMEM, "table %s: cannot allocate %zu bytes for its "
                          "KTX file", t->name, total);
    int f16 = t->format == FORMAT_RGBA16F;
    uint32_t h[H_COUNT] = {
        [H_ENDIANNESS] = KTX_ENDIAN_REF,
        [H_GL_TYPE] = f16 ? KTX_GL_HALF_FLOAT : KTX_GL_UNSIGNED_BYTE,
        [H_GL_TYPE_SIZE] = f16 ? 2 : 1,
        [H_GL_FORMAT] = KTX_GL_RGBA,
        [H_GL_INTERNAL_FORMAT] = f16 ? KTX_GL_RGBA16F : KTX_GL_RGBA8,
        [H_GL_BASE_INTERNAL_FORMAT] = KTX_GL_RGBA,
        [H_PIXEL_WIDTH] = (uint32_t)t->width,
        [H_PIXEL_HEIGHT] = (uint32_t)t->height,
        [H_PIXEL_DEPTH] = 0,
        /* §2.10: 0 means "not an array texture" */
        [H_ARRAY_ELEMENTS] = t->layers == 1 ? 0 : (uint32_t)t->layers,
        [H_FACES] = 1,
        [H_MIP_LEVELS] = (uint32_t)t->levels,
        [H_KV_BYTES] = (uint32_t)kv_bytes,
    };
    memcpy(buf, ktx_identifier, sizeof ktx_identifier);
    for (int i = 0; i < H_COUNT; i++)
        put_u32(buf + 12 + 4 * i, h[i]);
    uint8_t *p = buf + KTX_HEADER_BYTES;
    for (int i = 0; i < KV_KEYS; i++) {
        size_t kl = strlen(kv[i].key) + 1, vl = strlen(kv[i].value) + 1;
        put_u32(p, (uint32_t)(kl + vl));
        memcpy(p + 4, kv[i].key, kl);
        memcpy(p + 4 + kl, kv[i].value, vl);
        p += 4 + pad4(kl + vl);     /* valuePadding is zero bytes (calloc) */
    }
    for (int l = 0; l < t->levels; l++) {
        /* §2.16: for a non-cubemap texture imageSize covers every array element of the level */
        size_t n = table_level_bytes(t, l) * (size_t)t->layers;
        put_u32(p, (uint32_t)n);
        memcpy(p + 4, t->data + table_offset(t, l, 0), n);
        p += 4 + pad4(n);
    }
    *out = buf;
    *out_len = total;
    return 0;
}

/* ---- reader --------------------------------------------------------------------------- */

struct found {
    const char *value[KV_KEYS];
};

static const char *const read_keys[KV_KEYS] = {
    "KTXorientation", "swell.bias", "swell.crc32", "swell.kind", "swell.name", "swell.pattern",
    "swell.scale", "swell.set", "swell.version",
};

static int parse_floats4(const char *s, float v[4])
{
    const char *p = s;
    for (int i = 0; i < 4; i++) {
        if (i > 0) {
            if (*p != ' ')
                return -1;
            p++;
        }
        if (*p == ' ' || *p == '\0')
            return -1;
        char *end = NULL;
        errno = 0;
        double d = strtod(p, &end);
        if (end == p || errno == ERANGE || !isfinite(d) || !isfinite((float)d))
            return -1;
        v[i] = (float)d;
        p = end;
    }
    return *p == '\0' ? 0 : -1;
}

static int parse_long(const char *s, long lo, long hi, long *out)
{
    const char *d = s[0] == '-' ? s + 1 : s;
    if (*d < '0' || *d > '9' || strlen(s) > 12)
        return -1;
    char *end = NULL;
    long v = strtol(s, &end, 10);
    if (*end != '\0' || v < lo || v > hi)
        return -1;
    *out = v;
    return 0;
}

/* Walk the key/value block (§2.15): every pair inside the block, key NUL-terminated, padding
 * rules kept; swell's values must be strings with exactly one terminating NUL. */
static int read_kv(const uint8_t *p, uint32_t n, const char *name, struct found *f,
                   struct swell_err *err)
{
    uint32_t off = 0;
    while (off < n) {
        if (n - off < 4)
            return swell_fail(err, SWELL_E_FORMAT, "%s: key/value data: %u bytes left at "
                              "offset %u, too few for keyAndValueByteSize", name, n - off, off);
        uint32_t sz = get_u32(p + off);
        if (sz == 0 || sz > n - off - 4 || pad4(sz) > n - off - 4)
            return swell_fail(err, SWELL_E_FORMAT, "%s: key/value data: keyAndValueByteSize "
                              "%u at offset %u overruns bytesOfKeyValueData %u", name, sz, off,
                              n);
        const char *kvp = (const char *)p + off + 4;
        const char *nul = memchr(kvp, '\0', sz);
        if (!nul || nul == kvp)
            return swell_fail(err, SWELL_E_FORMAT, "%s: key/value data: key at offset %u is "
                              "empty or not NUL-terminated", name, off);
        size_t vlen = sz - (size_t)(nul - kvp) - 1;
        const char *val = nul + 1;
        int idx = -1;
        for (int i = 0; i < KV_KEYS; i++)
            if (strcmp(kvp, read_keys[i]) == 0)
                idx = i;
        if (idx < 0 && strncmp(kvp, "swell.", 6) == 0)
            return swell_fail(err, SWELL_E_FORMAT, "%s: key/value data: unknown key '%.64s'",
                              name, kvp);
        if (idx >= 0) {
            if (f->value[idx])
                return swell_fail(err, SWELL_E_FORMAT, "%s: key/value data: key '%s' appears "
                                  "twice", name, read_keys[idx]);
            if (vlen == 0 || memchr(val, '\0', vlen) != val + vlen - 1)
                return swell_fail(err, SWELL_E_FORMAT, "%s: key/value data: value of '%s' is "
                                  "not one NUL-terminated string", name, read_keys[idx]);
            f->value[idx] = val;
        }
        for (size_t i = sz; i < pad4(sz); i++)
            if (p[off + 4 + i] != 0)
                return swell_fail(err, SWELL_E_FORMAT, "%s: key/value data: valuePadding after "
                                  "'%.64s' is not zero", name, kvp);
        off += 4 + (uint32_t)pad4(sz);
    }
    return 0;
}

/* "0x" and exactly 8 lower-case hex digits, as the writer puts them. */
static int parse_hex32(const char *c, uint32_t *out)
{
    if (strlen(c) != 10 || c[0] != '0' || c[1] != 'x' || strspn(c + 2, "0123456789abcdef") != 8)
        return -1;
    *out = (uint32_t)strtoul(c + 2, NULL, 16);
    return 0;
}

static int check_meta(const struct found *f, const char *name, struct swell_table *t,
                      uint32_t *crc_out, struct swell_err *err)
{
    long v = 0;   /* the version first: another version may have other keys */
    if (f->value[8] && parse_long(f->value[8], 0, 1000000, &v) != 0)
        return swell_fail(err, SWELL_E_FORMAT, "%s: swell.version: '%.32s' is not a number",
                          name, f->value[8]);
    if (f->value[8] && v != KTX_SWELL_VERSION)
        return swell_fail(err, SWELL_E_VERSION, "%s: swell.version is %ld, this build reads "
                          "%d; re-bake the tables with this swell-bake", name, v,
                          KTX_SWELL_VERSION);
    for (int i = 1; i < KV_KEYS; i++)
        if (!f->value[i])
            return swell_fail(err, SWELL_E_FORMAT, "%s: key/value data: missing key '%s'; not "
                              "a swell table file", name, read_keys[i]);
    if (f->value[0] && strcmp(f->value[0], "S=r,T=u") != 0)
        return swell_fail(err, SWELL_E_FORMAT, "%s: KTXorientation: '%.32s', expected "
                          "'S=r,T=u'", name, f->value[0]);
    if (!table_name_valid(f->value[4]))
        return swell_fail(err, SWELL_E_FORMAT, "%s: swell.name: '%.40s' is not 1..31 chars of "
                          "[a-z0-9_]", name, f->value[4]);
    snprintf(t->name, sizeof t->name, "%s", f->value[4]);
    t->kind = -1;
    for (int k = 0; k < TABLE_KIND_COUNT; k++)
        if (strcmp(f->value[3], table_kind_name(k)) == 0)
            t->kind = k;
    if (t->kind < 0)
        return swell_fail(err, SWELL_E_FORMAT, "%s: swell.kind: unknown kind '%.32s'", name,
                          f->value[3]);
    if (parse_long(f->value[5], -1, SWELL_MAX_PATTERNS - 1, &v) != 0)
        return swell_fail(err, SWELL_E_FORMAT, "%s: swell.pattern: '%.32s' is not in [-1, %d]",
                          name, f->value[5], SWELL_MAX_PATTERNS - 1);
    t->pattern = (int)v;
    int per_pattern = t->kind == TABLE_DISP || t->kind == TABLE_SLOPE ||
                      t->kind == TABLE_WHITECAP;
    if (per_pattern != (t->pattern >= 0))
        return swell_fail(err, SWELL_E_FORMAT, "%s: swell.pattern: %d does not fit kind '%s' "
                          "(%s)", name, t->pattern, f->value[3],
                          per_pattern ? "per-pattern, needs 0..3" : "global, needs -1");
    if (parse_floats4(f->value[6], t->scale) != 0)
        return swell_fail(err, SWELL_E_FORMAT, "%s: swell.scale: '%.80s' is not four finite "
                          "floats", name, f->value[6]);
    if (parse_floats4(f->value[1], t->bias) != 0)
        return swell_fail(err, SWELL_E_FORMAT, "%s: swell.bias: '%.80s' is not four finite "
                          "floats", name, f->value[1]);
    if (parse_hex32(f->value[2], crc_out) != 0)
        return swell_fail(err, SWELL_E_FORMAT, "%s: swell.crc32: '%.32s' is not 0x + 8 lower "
                          "case hex digits", name, f->value[2]);
    if (parse_hex32(f->value[7], &t->set_id) != 0)
        return swell_fail(err, SWELL_E_FORMAT, "%s: swell.set: '%.32s' is not 0x + 8 lower "
                          "case hex digits", name, f->value[7]);
    return 0;
}

static int read_header(const uint8_t *b, size_t len, const char *name, struct swell_table *t,
                       uint32_t *kv_bytes, struct swell_err *err)
{
    if (len < sizeof ktx_identifier)
        return swell_fail(err, SWELL_E_FORMAT, "%s: identifier: file is %zu bytes, too short "
                          "for a KTX file", name, len);
    if (memcmp(b, ktx_identifier, sizeof ktx_identifier) != 0) {
        /* Same frame, other digits: a KTX of another version (e.g. KTX 2). */
        if (memcmp(b, ktx_identifier, 5) == 0 && memcmp(b + 7, ktx_identifier + 7, 5) == 0)
            return swell_fail(err, SWELL_E_VERSION, "%s: identifier: KTX version '%c%c', only "
                              "KTX 1.1 ('11') is read", name, b[5], b[6]);
        return swell_fail(err, SWELL_E_FORMAT, "%s: identifier: not a KTX file (bad magic "
                          "bytes)", name);
    }
    if (len < KTX_HEADER_BYTES)
        return swell_fail(err, SWELL_E_FORMAT, "%s: header: truncated, %zu of %d bytes", name,
                          len, KTX_HEADER_BYTES);
    uint32_t h[H_COUNT];
    for (int i = 0; i < H_COUNT; i++)
        h[i] = get_u32(b + 12 + 4 * i);
    if (h[H_ENDIANNESS] == 0x01020304u)
        return swell_fail(err, SWELL_E_UNSUPPORTED, "%s: endianness: big-endian file; only "
                          "little-endian KTX files are read", name);
    if (h[H_ENDIANNESS] != KTX_ENDIAN_REF)
        return swell_fail(err, SWELL_E_FORMAT, "%s: endianness: 0x%08x, expected 0x04030201",
                          name, h[H_ENDIANNESS]);
    int f16;
    if (h[H_GL_TYPE] == KTX_GL_UNSIGNED_BYTE)
        f16 = 0;
    else if (h[H_GL_TYPE] == KTX_GL_HALF_FLOAT)
        f16 = 1;
    else
        return swell_fail(err, SWELL_E_UNSUPPORTED, "%s: glType: 0x%04x is not supported "
                          "(GL_UNSIGNED_BYTE 0x1401 or GL_HALF_FLOAT 0x140B)", name,
                          h[H_GL_TYPE]);
    uint32_t want[H_COUNT] = {
        [H_GL_TYPE_SIZE] = f16 ? 2 : 1,
        [H_GL_FORMAT] = KTX_GL_RGBA,
        [H_GL_INTERNAL_FORMAT] = f16 ? KTX_GL_RGBA16F : KTX_GL_RGBA8,
        [H_GL_BASE_INTERNAL_FORMAT] = KTX_GL_RGBA,
    };
    for (int i = H_GL_TYPE_SIZE; i <= H_GL_BASE_INTERNAL_FORMAT; i++)
        if (h[i] != want[i])
            return swell_fail(err, i == H_GL_TYPE_SIZE ? SWELL_E_FORMAT : SWELL_E_UNSUPPORTED,
                              "%s: %s: 0x%04x is not supported with glType 0x%04x (expected "
                              "0x%04x)", name, header_names[i], h[i], h[H_GL_TYPE], want[i]);
    for (int i = H_PIXEL_WIDTH; i <= H_PIXEL_HEIGHT; i++)
        if (!is_pow2(h[i]) || h[i] > KTX_MAX_DIM)
            return swell_fail(err, SWELL_E_FORMAT, "%s: %s: %u is not a power of two in [1, %d]",
                              name, header_names[i], h[i], KTX_MAX_DIM);
    if (h[H_PIXEL_DEPTH] != 0)
        return swell_fail(err, SWELL_E_UNSUPPORTED, "%s: pixelDepth: %u, only 2D textures (0) "
                          "are read", name, h[H_PIXEL_DEPTH]);
    if (h[H_ARRAY_ELEMENTS] > KTX_MAX_LAYERS)
        return swell_fail(err, SWELL_E_FORMAT, "%s: numberOfArrayElements: %u, more than %d",
                          name, h[H_ARRAY_ELEMENTS], KTX_MAX_LAYERS);
    if (h[H_FACES] != 1)
        return swell_fail(err, SWELL_E_UNSUPPORTED, "%s: numberOfFaces: %u, only 1 (no "
                          "cubemaps) is read", name, h[H_FACES]);
    int full = full_chain(h[H_PIXEL_WIDTH], h[H_PIXEL_HEIGHT]);
    if (h[H_MIP_LEVELS] < 1 || h[H_MIP_LEVELS] > (uint32_t)full)
        return swell_fail(err, SWELL_E_FORMAT, "%s: numberOfMipmapLevels: %u, expected 1..%d "
                          "for %ux%u", name, h[H_MIP_LEVELS], full, h[H_PIXEL_WIDTH],
                          h[H_PIXEL_HEIGHT]);
    if (h[H_KV_BYTES] % 4 != 0 || h[H_KV_BYTES] > KTX_MAX_KV_BYTES ||
        h[H_KV_BYTES] > len - KTX_HEADER_BYTES)
        return swell_fail(err, SWELL_E_FORMAT, "%s: bytesOfKeyValueData: %u is not a multiple "
                          "of 4 within the %zu bytes after the header (max %d)", name,
                          h[H_KV_BYTES], len - KTX_HEADER_BYTES, KTX_MAX_KV_BYTES);
    t->format = f16 ? FORMAT_RGBA16F : FORMAT_RGBA8;
    t->width = (int)h[H_PIXEL_WIDTH];
    t->height = (int)h[H_PIXEL_HEIGHT];
    t->layers = h[H_ARRAY_ELEMENTS] == 0 ? 1 : (int)h[H_ARRAY_ELEMENTS];
    t->levels = (int)h[H_MIP_LEVELS];
    *kv_bytes = h[H_KV_BYTES];
    return 0;
}

int ktx_read_memory(const void *buf, size_t len, const char *name_for_errors,
                    struct swell_table *out, struct swell_err *err)
{
    const char *name = name_for_errors ? name_for_errors : "(memory)";
    const uint8_t *b = buf;
    struct swell_table t;
    memset(&t, 0, sizeof t);
    memset(out, 0, sizeof *out);
    uint32_t kv_bytes = 0, crc_want = 0;
    struct found f;
    memset(&f, 0, sizeof f);
    int rc = read_header(b, len, name, &t, &kv_bytes, err);
    if (rc)
        return rc;
    rc = read_kv(b + KTX_HEADER_BYTES, kv_bytes, name, &f, err);
    if (rc)
        return rc;
    rc = check_meta(&f, name, &t, &crc_want, err);
    if (rc)
        return rc;
    /* Every size below is bounded (8192^2 * 8 B * 1024 layers < 2^40), so 64-bit sums cannot
     * wrap; the whole layout is checked against len before anything is allocated. */
    size_t off = KTX_HEADER_BYTES + kv_bytes;
    for (int l = 0; l < t.levels; l++) {
        uint64_t want = (uint64_t)table_level_bytes(&t, l) * (uint64_t)t.layers;
        if (len - off < 4)
            return swell_fail(err, SWELL_E_FORMAT, "%s: level %d imageSize: file truncated at "
                              "%zu bytes", name, l, len);
        uint32_t got = get_u32(b + off);
        if (got != want)
            return swell_fail(err, SWELL_E_FORMAT, "%s: level %d imageSize: %u, expected %llu "
                              "for %dx%d, %d layers", name, l, got, (unsigned long long)want,
                              table_level_width(&t, l), table_level_height(&t, l), t.layers);
        uint64_t padded = (want + 3) & ~(uint64_t)3;
        if ((uint64_t)(len - off - 4) < padded)
            return swell_fail(err, SWELL_E_FORMAT, "%s: level %d image data: file truncated "
                              "(%zu bytes, level needs %llu more)", name, l, len,
                              (unsigned long long)(padded - (len - off - 4)));
        off += 4 + (size_t)padded;
    }
    if (off != len)
        return swell_fail(err, SWELL_E_FORMAT, "%s: trailing data: %zu bytes after the last "
                          "mip level", name, len - off);
    size_t n = table_bytes(&t);
    t.data = malloc(n);
    if (!t.data)
        return swell_fail(err, SWELL_E_NOMEM, "%s: cannot allocate %zu bytes of image data",
                          name, n);
    off = KTX_HEADER_BYTES + kv_bytes;
    for (int l = 0; l < t.levels; l++) {
        size_t m = table_level_bytes(&t, l) * (size_t)t.layers;
        memcpy(t.data + table_offset(&t, l, 0), b + off + 4, m);
        for (size_t i = m; i < pad4(m); i++)
            if (b[off + 4 + i] != 0) {
                free(t.data);
                return swell_fail(err, SWELL_E_FORMAT, "%s: level %d mipPadding is not zero",
                                  name, l);
            }
        off += 4 + pad4(m);
    }
    uint32_t crc = fs_crc32(t.data, n);
    if (crc != crc_want) {
        free(t.data);
        return swell_fail(err, SWELL_E_CHECKSUM, "%s: swell.crc32: image data has crc32 "
                          "0x%08x, the file says 0x%08x; the file is corrupt, re-bake it",
                          name, crc, crc_want);
    }
    *out = t;
    return 0;
}

int ktx_write_file(const struct swell_table *t, const char *path, struct swell_err *err)
{
    uint8_t *buf = NULL;
    size_t len = 0;
    int rc = ktx_write_memory(t, &buf, &len, err);
    if (rc == 0)
        rc = fs_write_atomic(path, buf, len, err);
    free(buf);
    return rc;
}

int ktx_read_file(const char *path, struct swell_table *out, struct swell_err *err)
{
    uint8_t *buf = NULL;
    size_t len = 0;
    memset(out, 0, sizeof *out);
    int rc = fs_read_file(path, KTX_MAX_FILE_BYTES, &buf, &len, err);
    if (rc == 0)
        rc = ktx_read_memory(buf, len, path, out, err);
    free(buf);
    return rc;
}
