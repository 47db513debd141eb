#include "tables/tables.h"
#include "tables/quantize.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const kind_names[TABLE_KIND_COUNT] = {
    [TABLE_DISP] = "disp",
    [TABLE_SLOPE] = "slope",
    [TABLE_WHITECAP] = "whitecap",
    [TABLE_FRESNEL] = "fresnel",
    [TABLE_FRESNEL_EFF] = "fresnel_eff",
};

static const char *const format_names[FORMAT_COUNT] = {
    [FORMAT_RGBA8] = "rgba8",
    [FORMAT_RGBA16F] = "rgba16f",
};

const char *table_kind_name(int kind)
{
    return kind >= 0 && kind < TABLE_KIND_COUNT ? kind_names[kind] : "?";
}

const char *table_format_name(int format)
{
    return format >= 0 && format < FORMAT_COUNT ? format_names[format] : "?";
}

/* Bytes per texel: RGBA8 4, RGBA16F 8 (four IEEE halves); 0 for an unknown format so every
 * size derived from a bad table is 0 rather than garbage. */
static size_t texel_bytes(int format)
{
    switch (format) {
    case FORMAT_RGBA8: return 4;
    case FORMAT_RGBA16F: return 8;
    default: return 0;
    }
}

int table_level_width(const struct swell_table *t, int level)
{
    int w = level >= 0 && level < 31 ? t->width >> level : 0;
    return w > 0 ? w : 1;
}

int table_level_height(const struct swell_table *t, int level)
{
    int h = level >= 0 && level < 31 ? t->height >> level : 0;
    return h > 0 ? h : 1;
}

size_t table_level_bytes(const struct swell_table *t, int level)
{
    return (size_t)table_level_width(t, level) * (size_t)table_level_height(t, level) *
           texel_bytes(t->format);
}

/* KTX 1.1 order: all layers of level 0, then all layers of level 1, ... */
size_t table_offset(const struct swell_table *t, int level, int layer)
{
    size_t off = 0;
    for (int l = 0; l < level; l++)
        off += table_level_bytes(t, l) * (size_t)t->layers;
    return off + table_level_bytes(t, level) * (size_t)layer;
}

size_t table_bytes(const struct swell_table *t)
{
    if (t->layers < 1 || t->levels < 1)
        return 0;
    return table_offset(t, t->levels, 0);
}

static int is_pow2(int v)
{
    return v > 0 && (v & (v - 1)) == 0;
}

static int full_chain_levels(int w, int h)
{
    int m = w > h ? w : h, n = 1;
    while (m > 1) {
        m >>= 1;
        n++;
    }
    return n;
}

int table_alloc(struct swell_table *t, struct swell_err *err)
{
    if (t->data)
        return swell_fail(err, SWELL_E_ARG,
                          "table %s: data is already allocated; destroy the table set before "
                          "filling it again", t->name);
    if (t->format < 0 || t->format >= FORMAT_COUNT)
        return swell_fail(err, SWELL_E_ARG, "table %s: unknown format %d (expected 0..%d)",
                          t->name, t->format, FORMAT_COUNT - 1);
    /* The gles2-min tier needs power-of-two textures for mipmaps and REPEAT wrapping. */
    if (!is_pow2(t->width) || !is_pow2(t->height) || t->width > 16384 || t->height > 16384)
        return swell_fail(err, SWELL_E_ARG,
                          "table %s: size %dx%d is not a power of two in [1, 16384]",
                          t->name, t->width, t->height);
    if (t->layers < 1 || t->layers > 4096)
        return swell_fail(err, SWELL_E_ARG, "table %s: %d layers, expected 1..4096",
                          t->name, t->layers);
    int full = full_chain_levels(t->width, t->height);
    if (t->levels < 1 || t->levels > full)
        return swell_fail(err, SWELL_E_ARG,
                          "table %s: %d mip levels, expected 1..%d for %dx%d", t->name,
                          t->levels, full, t->width, t->height);
    /* 16384^2 * 8 B * 4096 layers * 4/3 fits in 64 bits, so the size cannot wrap here. */
    size_t n = table_bytes(t);
    if (n > SIZE_MAX / 2)
        return swell_fail(err, SWELL_E_NOMEM, "table %s: %zu bytes is not addressable",
                          t->name, n);
    t->data = calloc(n, 1);
    if (!t->data)
        return swell_fail(err, SWELL_E_NOMEM,
                          "table %s: cannot allocate %zu bytes (%dx%d, %d layers, %d levels); "
                          "lower size_fs/frames or the budget", t->name, n, t->width,
                          t->height, t->layers, t->levels);
    return 0;
}

const struct swell_table *tables_find(const struct swell_tables *s, int kind, int pattern)
{
    int n = s->count < SWELL_MAX_TABLES ? s->count : SWELL_MAX_TABLES;
    for (int i = 0; i < n; i++)
        if (s->table[i].kind == kind && s->table[i].pattern == pattern)
            return &s->table[i];
    return NULL;
}

size_t tables_bytes(const struct swell_tables *s)
{
    size_t total = 0;
    int n = s->count < SWELL_MAX_TABLES ? s->count : SWELL_MAX_TABLES;
    for (int i = 0; i < n; i++)
        total += table_bytes(&s->table[i]);
    return total;
}

/* Every slot, not just [0, count): a builder that failed between table_alloc and count++
 * leaves an allocation past count. */
void tables_destroy(struct swell_tables *s)
{
    if (!s)
        return;
    for (int i = 0; i < SWELL_MAX_TABLES; i++) {
        free(s->table[i].data);
        s->table[i].data = NULL;
    }
    s->count = 0;
}

float tables_pattern_period(const struct swell_tables *s, int pattern)
{
    float p = pattern >= 0 && pattern < SWELL_MAX_PATTERNS ? s->pattern[pattern].period_s : 0.0f;
    return p > 0.0f ? p : s->loop_period_s;
}

int table_name_valid(const char *name)
{
    size_t n = strnlen(name, 32);
    if (n == 0 || n > 31)
        return 0;
    return strspn(name, "abcdefghijklmnopqrstuvwxyz0123456789_") == n;
}

float table_level_within_var(const struct swell_table *t, int l, int cm, int cs)
{
    if (l >= t->levels || t->format != FORMAT_RGBA8)
        return 0.0f;
    const uint8_t *px = t->data + table_offset(t, l, 0);
    size_t n = (size_t)table_level_width(t, l) * (size_t)table_level_height(t, l);
    double acc = 0.0;
    for (size_t i = 0; i < n; i++) {
        double m = quantize_decode(t, cm, px[4 * i + cm]);
        double m2 = quantize_decode(t, cs, px[4 * i + cs]);
        acc += m2 - m * m > 0.0 ? m2 - m * m : 0.0;
    }
    return (float)(acc / (double)n);
}

static void layout_one(struct swell_table *t, const char *stem, int kind, int pattern, int size,
                       int layers, int levels)
{
    memset(t, 0, sizeof *t);
    if (pattern >= 0)
        snprintf(t->name, sizeof t->name, "%s_p%d", stem, pattern);
    else
        snprintf(t->name, sizeof t->name, "%s", stem);
    t->kind = kind;
    t->pattern = pattern;
    t->format = FORMAT_RGBA8;
    t->width = t->height = size;
    t->layers = layers;
    t->levels = levels;
}

int tables_layout(const struct seastate *s, struct swell_table out[SWELL_MAX_TABLES])
{
    int n = 0, chain = 1;
    while ((1 << (chain - 1)) < s->size_fs && chain < 31)
        chain++;
    for (int i = 0; i < s->patterns && i < SWELL_MAX_PATTERNS; i++) {
        layout_one(&out[n++], "slope", TABLE_SLOPE, i, s->size_fs, s->frames, chain);
        layout_one(&out[n++], "whitecap", TABLE_WHITECAP, i, s->size_fs, s->frames, chain);
        layout_one(&out[n++], "disp", TABLE_DISP, i, s->size_geo, s->frames, 1);
    }
    layout_one(&out[n++], "fresnel", TABLE_FRESNEL, -1, TABLES_FRESNEL_SIZE, 1, 1);
    layout_one(&out[n++], "fresnel_eff", TABLE_FRESNEL_EFF, -1, TABLES_FRESNEL_SIZE, 1, 1);
    return n;
}
