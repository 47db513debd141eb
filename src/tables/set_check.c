#include "tables/set_check.h"

#include <inttypes.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "core/fsutil.h"
#include "core/preset.h"

#define REBAKE "the manifest's values are inconsistent (written by another program, or edited " \
               "and resealed); re-bake the table set"

/* "file:line: key = value: why; <REBAKE>" */
__attribute__((format(printf, 4, 5)))
static int bad(struct kv *kv, const char *key, struct swell_err *err, const char *fmt, ...)
{
    char why[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(why, sizeof why, fmt, ap);
    va_end(ap);
    const struct kv_entry *e = kv_find(kv, key);
    return swell_fail(err, SWELL_E_FORMAT, "%s:%d: %s = %s: %s; " REBAKE, kv->source,
                      e ? e->line : 0, key, e ? e->value : "?", why);
}

static int in_range(struct kv *kv, const char *key, double v, double lo, double hi,
                    const char *unit, struct swell_err *err)
{
    if (isfinite(v) && v >= lo && v <= hi)
        return 0;
    return bad(kv, key, err, "must be %g to %g%s", lo, hi, unit);
}

static int check_state(const struct tables_manifest *m, struct kv *kv, struct swell_err *err)
{
    const struct seastate *st = &m->set.state;
    const struct swell_tables *s = &m->set;
    int rc = seastate_validate(st, err);
    if (rc)
        return swell_err_context(err, "%s: state.*: " REBAKE, kv->source);
    if (st->frames == 0 || st->size_fs == 0 || st->size_geo == 0)
        return bad(kv, st->frames == 0 ? "state.frames" : st->size_fs == 0 ? "state.size_fs"
                   : "state.size_geo", err, "a baked set has its frames and sizes chosen (0 "
                   "means 'by budget' only before the bake)");
    if (st->size_geo > st->size_fs)
        return bad(kv, "state.size_geo", err, "the displacement table cannot be larger than "
                   "the slope table (state.size_fs = %d)", st->size_fs);
    if (s->patterns != st->patterns)
        return bad(kv, "set.patterns", err, "must be state.patterns, %d", st->patterns);
    if (s->frames != st->frames)
        return bad(kv, "set.frames", err, "must be state.frames, %d", st->frames);
    if (s->loop_period_s != st->loop_period_s)
        return bad(kv, "set.loop_period_s", err, "must be state.loop_period_s, %.9g s",
                   (double)st->loop_period_s);
    return 0;
}

static int check_pattern(const struct tables_manifest *m, int i, struct kv *kv,
                         struct swell_err *err)
{
    const struct swell_tables *s = &m->set;
    const struct swell_pattern_info *p = &s->pattern[i];
    char key[64];
    int rc;
#define PKEY(field) (snprintf(key, sizeof key, "pattern.%d." field, i), key)
    if (i >= s->patterns) {
        const float v[8] = { p->size_m, p->k_min, p->k_max, p->lambda, p->period_s, p->var_h,
                             p->mss_x, p->mss_y };
        for (int j = 0; j < 8; j++)
            if (v[j] != 0.0f)
                return bad(kv, PKEY("size_m"), err, "pattern %d is unused (set.patterns = %d) "
                           "and every value of it must be 0", i, s->patterns);
        return 0;
    }
    if ((rc = in_range(kv, PKEY("size_m"), p->size_m, 0.01, 1e5, " m", err)) ||
        (rc = in_range(kv, PKEY("k_min"), p->k_min, 0.0, 1e6, " rad/m", err)))
        return rc;
    /* the band a grid of size_fs samples over size_m: up to its Nyquist pi N / L */
    double nyquist = M_PI * s->state.size_fs / p->size_m * (1.0 + 1e-4);
    if ((rc = in_range(kv, PKEY("k_max"), p->k_max, p->k_min, nyquist,
                       " rad/m (from k_min to the grid's Nyquist pi size_fs / size_m)", err)))
        return rc;
    if (p->lambda != s->state.choppiness)
        return bad(kv, PKEY("lambda"), err, "must be state.choppiness, %.9g",
                   (double)s->state.choppiness);
    double mult = (double)s->loop_period_s / p->period_s;   /* T / T_i, a whole number */
    if (!(p->period_s > 0.0f) || !isfinite(mult) || mult < 0.999 || mult > 4096.001 ||
        fabs(mult - floor(mult + 0.5)) > 1e-3)
        return bad(kv, PKEY("period_s"), err, "must be the loop period %.9g s divided by a "
                   "whole number 1..4096", (double)s->loop_period_s);
    if ((rc = in_range(kv, PKEY("var_h"), p->var_h, 0.0, 1e4, " m^2", err)) ||
        (rc = in_range(kv, PKEY("mss_x"), p->mss_x, 0.0, 1.0, "", err)) ||
        (rc = in_range(kv, PKEY("mss_y"), p->mss_y, 0.0, 1.0, "", err)))
        return rc;
#undef PKEY
    return 0;
}

static int check_statistics(const struct swell_tables *s, struct kv *kv, struct swell_err *err)
{
    int rc;
    if ((rc = in_range(kv, "set.mss_unresolved_x", s->mss_unresolved_x, 0.0, 1.0, "", err)) ||
        (rc = in_range(kv, "set.mss_unresolved_y", s->mss_unresolved_y, 0.0, 1.0, "", err)) ||
        (rc = in_range(kv, "set.whitecap_breaking_fraction", s->whitecap_breaking_fraction,
                       0.0, 1.0, "", err)) ||
        (rc = in_range(kv, "set.whitecap_fraction_model", s->whitecap_fraction_model, 0.0,
                       1.0, "", err)) ||
        (rc = in_range(kv, "set.whitecap_fraction_measured", s->whitecap_fraction_measured,
                       0.0, 1.0, "", err)) ||
        (rc = in_range(kv, "set.whitecap_epsilon", s->whitecap_epsilon, -100.0, 100.0, "",
                       err)))
        return rc;
    if (!(s->foam_recovery_per_s > 0.0f) || !(s->foam_recovery_per_s <= 1e4f))
        return bad(kv, "set.foam_recovery_per_s", err, "must be more than 0 and at most 1e4 "
                   "per s");
    double var_h = 0.0;   /* as the bake sums it (bake.c) */
    for (int i = 0; i < s->patterns; i++)
        var_h += s->pattern[i].var_h;
    double hs = 4.0 * sqrt(var_h);
    if (!(fabs(s->hs_m - hs) <= 1e-5 * hs + 1e-9))
        return bad(kv, "set.hs_m", err, "must be 4 sqrt(sum of pattern.N.var_h) = %.9g m", hs);
    return 0;
}

static int check_tables(const struct tables_manifest *m, struct kv *kv, struct swell_err *err)
{
    const struct swell_tables *s = &m->set;
    struct swell_table want[SWELL_MAX_TABLES];
    int n = tables_layout(&s->state, want);
    if (s->count != n)
        return bad(kv, "set.count", err, "a set baked from this state holds %d tables (3 per "
                   "pattern and 2 Fresnel tables)", n);
    for (int i = 0; i < n; i++) {
        const struct swell_table *g = &s->table[i], *w = &want[i];
        const char *field = strcmp(g->name, w->name) != 0 ? "name"
                            : g->kind != w->kind ? "kind"
                            : g->pattern != w->pattern ? "pattern"
                            : g->format != w->format ? "format"
                            : g->width != w->width ? "width"
                            : g->height != w->height ? "height"
                            : g->layers != w->layers ? "layers"
                            : g->levels != w->levels ? "levels" : NULL;
        if (!field)
            continue;
        char key[64];
        snprintf(key, sizeof key, "table.%d.%s", i, field);
        return bad(kv, key, err, "lists '%s' (%s, pattern %d, %s, %dx%d, %d layers, %d levels) "
                   "where a set baked from this state holds '%s' (%s, pattern %d, %s, %dx%d, "
                   "%d layers, %d levels)", g->name, table_kind_name(g->kind), g->pattern,
                   table_format_name(g->format), g->width, g->height, g->layers, g->levels,
                   w->name, table_kind_name(w->kind), w->pattern, table_format_name(w->format),
                   w->width, w->height, w->layers, w->levels);
    }
    return 0;
}

int tables_check_manifest(const struct tables_manifest *m, struct kv *kv, struct swell_err *err)
{
    int rc = check_state(m, kv, err);
    for (int i = 0; rc == 0 && i < SWELL_MAX_PATTERNS; i++)
        rc = check_pattern(m, i, kv, err);
    if (rc == 0)
        rc = check_statistics(&m->set, kv, err);
    if (rc == 0)
        rc = check_tables(m, kv, err);
    return rc;
}

/* Physical bounds of each kind's four channels (tables.h), with room for a constant channel,
 * which quantises to [v, v + 1] (quantize.h). */
static const struct {
    float lo[4], hi[4];
    const char *what;
} bounds[TABLE_KIND_COUNT] = {
    [TABLE_DISP] = { { -1000, -1000, -1000, -1000 }, { 1000, 1000, 1000, 1000 },
                     "displacement within +-1000 m" },
    [TABLE_SLOPE] = { { -100, -100, -1e-3f, -1e-3f }, { 100, 100, 1e4f, 1e4f },
                      "slopes within +-100, their squares not negative" },
    [TABLE_WHITECAP] = { { -100, -1e-3f, -1e-3f, -100 }, { 100, 1e4f, 2, 100 },
                         "foam memory and k within +-100, its square not negative" },
    [TABLE_FRESNEL] = { { -1.001f, -1.001f, -1.001f, -1e-3f }, { 1.001f, 1.001f, 1.001f, 1.001f },
                        "view vector within [-1, 1], Fresnel within [0, 1]" },
    [TABLE_FRESNEL_EFF] = { { -1e-3f, -1e-3f, -1e-3f, -1e-3f }, { 1.001f, 1.001f, 1.001f, 2.001f },
                            "effective Fresnel within [0, 1]" },
};

int tables_check_values(const struct swell_table *t, const char *path, struct swell_err *err)
{
    if (t->format != FORMAT_RGBA8 || t->kind < 0 || t->kind >= TABLE_KIND_COUNT)
        return 0;   /* RGBA16F holds values, not scale and bias; the manifest refuses it */
    for (int c = 0; c < 4; c++) {
        double a = t->bias[c], b = (double)t->bias[c] + t->scale[c];
        double lo = a < b ? a : b, hi = a < b ? b : a;
        if (lo >= bounds[t->kind].lo[c] && hi <= bounds[t->kind].hi[c])
            continue;
        return swell_fail(err, SWELL_E_FORMAT, "%s: channel %d holds %.9g to %.9g (swell.bias "
                          "and swell.scale), outside a %s table's physical range (%s); the file "
                          "was not written by swell-bake: re-bake the table set", path, c, lo,
                          hi, table_kind_name(t->kind), bounds[t->kind].what);
    }
    return 0;
}

/* ---- the seal: the manifest's crc32 of its own content -------------------------------- */

#define SEAL_KEY "manifest.crc32"

/* Where the last line of text[0..len) starts (text ends with '\n'). */
static size_t last_line_start(const char *text, size_t len)
{
    size_t i = len > 0 ? len - 1 : 0;
    while (i > 0 && text[i - 1] != '\n')
        i--;
    return i;
}

/* crc32 of text[0..n) with each "\r\n" counted as "\n": a manifest whose line ends were
 * converted (a copy through another system) keeps its seal. */
static uint32_t content_crc(const char *text, size_t n)
{
    uint32_t crc = 0;
    size_t from = 0;
    for (size_t i = 0; i + 1 < n; i++)
        if (text[i] == '\r' && text[i + 1] == '\n') {
            crc = fs_crc32_more(crc, text + from, i - from);
            from = i + 1;
        }
    return fs_crc32_more(crc, text + from, n - from);
}

static int is_seal_line(const char *line, size_t n)
{
    return n >= sizeof SEAL_KEY - 1 && memcmp(line, SEAL_KEY, sizeof SEAL_KEY - 1) == 0;
}

size_t manifest_reseal(char *text, size_t len, size_t cap)
{
    if (len == 0 || text[len - 1] != '\n')
        return 0;
    size_t start = last_line_start(text, len);
    if (is_seal_line(text + start, len - start))
        len = start;
    char line[64];
    int n = snprintf(line, sizeof line, SEAL_KEY " = %" PRIu32 "\n", content_crc(text, len));
    if (n < 0 || (size_t)n > cap - len)
        return 0;
    memcpy(text + len, line, (size_t)n);
    return len + (size_t)n;
}

int tables_check_seal(const char *text, size_t len, struct kv *kv, struct swell_err *err)
{
    size_t start = last_line_start(text, len);
    struct kv_entry *e = kv_find(kv, SEAL_KEY);
    if (!e || !is_seal_line(text + start, len - start))
        return swell_fail(err, SWELL_E_FORMAT, "%s: the last line is not '" SEAL_KEY " = N' "
                          "(the manifest's checksum of its own content): the file is cut short "
                          "or was edited; re-bake the table set", kv->source);
    uint64_t want = 0;
    int rc = kv_entry_u64(kv, e, 0, UINT32_MAX, &want, err);
    if (rc)
        return rc;
    uint32_t got = content_crc(text, start);
    if (got != want)
        return swell_fail(err, SWELL_E_CHECKSUM, "%s:%d: " SEAL_KEY " says %" PRIu64 " but the "
                          "lines above it have crc32 %" PRIu32 ": the manifest was edited or is "
                          "damaged (its values cannot be trusted); re-bake the table set",
                          kv->source, e->line, want, got);
    return 0;
}

uint32_t tables_set_id(const struct seastate *state)
{
    char buf[4096];
    size_t len = 0;
    if (preset_format_state(state, "state.", buf, sizeof buf, &len, NULL) != 0)
        return 0;
    return fs_crc32(buf, len);
}
