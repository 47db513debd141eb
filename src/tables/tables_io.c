#include "tables/tables_io.h"

#include "tables/budget.h"

#include <dirent.h>
#include <float.h>
#include <inttypes.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/fsutil.h"
#include "tables/ktx.h"
#include "core/kv.h"
#include "core/preset.h"
#include "tables/set_check.h"
#include "tables/set_dir.h"

#define KTX_SUFFIX ".ktx"
#define MANIFEST_BUF_BYTES (64u * 1024u)

static int ends_with(const char *s, const char *suffix)
{
    size_t n = strlen(s), m = strlen(suffix);
    return n >= m && strcmp(s + n - m, suffix) == 0;
}

/* ---- manifest text -------------------------------------------------------------------- */

struct text {
    char *buf;
    size_t len, cap;
    int overflow;
};

__attribute__((format(printf, 2, 3)))
static void put(struct text *t, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(t->buf + t->len, t->cap - t->len, fmt, ap);
    va_end(ap);
    if (n < 0 || (size_t)n >= t->cap - t->len)
        t->overflow = 1;
    else
        t->len += (size_t)n;
}

static int manifest_write(const struct swell_tables *s, const struct tables_manifest_entry *e,
                          char **out, size_t *out_len, struct swell_err *err)
{
    struct text t = { malloc(MANIFEST_BUF_BYTES), 0, MANIFEST_BUF_BYTES, 0 };
    if (!t.buf)
        return swell_fail(err, SWELL_E_NOMEM, "cannot allocate the manifest text");
    put(&t, TABLES_MANIFEST_MAGIC " %d\n", TABLES_MANIFEST_VERSION);
    put(&t, "# swell table set: every value is checked on load; do not edit by hand\n");
    int rc = preset_format_state(&s->state, "state.", t.buf, t.cap, &t.len, err);
    if (rc) {
        free(t.buf);
        return rc;
    }
    put(&t, "set.patterns = %d\n", s->patterns);
    put(&t, "set.frames = %d\n", s->frames);
    put(&t, "set.loop_period_s = %.9g\n", (double)s->loop_period_s);
    for (int i = 0; i < SWELL_MAX_PATTERNS; i++) {
        const struct swell_pattern_info *p = &s->pattern[i];
        put(&t, "pattern.%d.size_m = %.9g\n", i, (double)p->size_m);
        put(&t, "pattern.%d.k_min = %.9g\n", i, (double)p->k_min);
        put(&t, "pattern.%d.k_max = %.9g\n", i, (double)p->k_max);
        put(&t, "pattern.%d.lambda = %.9g\n", i, (double)p->lambda);
        put(&t, "pattern.%d.period_s = %.9g\n", i, (double)p->period_s);
        put(&t, "pattern.%d.var_h = %.9g\n", i, (double)p->var_h);
        put(&t, "pattern.%d.mss_x = %.9g\n", i, (double)p->mss_x);
        put(&t, "pattern.%d.mss_y = %.9g\n", i, (double)p->mss_y);
    }
    put(&t, "set.mss_unresolved_x = %.9g\n", (double)s->mss_unresolved_x);
    put(&t, "set.mss_unresolved_y = %.9g\n", (double)s->mss_unresolved_y);
    put(&t, "set.hs_m = %.9g\n", (double)s->hs_m);
    put(&t, "set.whitecap_breaking_fraction = %.9g\n", (double)s->whitecap_breaking_fraction);
    put(&t, "set.foam_recovery_per_s = %.9g\n", (double)s->foam_recovery_per_s);
    put(&t, "set.whitecap_fraction_model = %.9g\n", (double)s->whitecap_fraction_model);
    put(&t, "set.whitecap_fraction_measured = %.9g\n", (double)s->whitecap_fraction_measured);
    put(&t, "set.whitecap_epsilon = %.9g\n", (double)s->whitecap_epsilon);
    put(&t, "set.count = %d\n", s->count);
    for (int i = 0; i < s->count; i++) {
        const struct swell_table *tb = &s->table[i];
        put(&t, "table.%d.name = %s\n", i, tb->name);
        put(&t, "table.%d.kind = %s\n", i, table_kind_name(tb->kind));
        put(&t, "table.%d.pattern = %d\n", i, tb->pattern);
        put(&t, "table.%d.format = %s\n", i, table_format_name(tb->format));
        put(&t, "table.%d.width = %d\n", i, tb->width);
        put(&t, "table.%d.height = %d\n", i, tb->height);
        put(&t, "table.%d.layers = %d\n", i, tb->layers);
        put(&t, "table.%d.levels = %d\n", i, tb->levels);
        put(&t, "table.%d.file_bytes = %" PRIu64 "\n", i, e[i].file_bytes);
        put(&t, "table.%d.file_crc32 = %" PRIu32 "\n", i, e[i].file_crc32);
    }
    if (!t.overflow)
        t.len = manifest_reseal(t.buf, t.len, t.cap);
    if (t.overflow || t.len == 0) {
        free(t.buf);
        return swell_fail(err, SWELL_E_ARG, "manifest text exceeds %u bytes",
                          MANIFEST_BUF_BYTES);
    }
    *out = t.buf;
    *out_len = t.len;
    return 0;
}

static int get_f(struct kv *kv, const char *key, float *out, struct swell_err *err)
{
    return kv_get_float(kv, key, -FLT_MAX, FLT_MAX, out, err);
}

static int name_index(const char *value, const char *(*namer)(int), int count)
{
    for (int i = 0; i < count; i++)
        if (strcmp(value, namer(i)) == 0)
            return i;
    return -1;
}

static int read_entry(struct kv *kv, int i, struct swell_table *tb,
                      struct tables_manifest_entry *e, struct swell_err *err)
{
    char key[64];
    const char *str = NULL;
    int rc;
#define KEY(field) (snprintf(key, sizeof key, "table.%d." field, i), key)
    if ((rc = kv_get_str(kv, KEY("name"), &str, err)))
        return rc;
    if (!table_name_valid(str))
        return swell_fail(err, SWELL_E_FORMAT, "%s:%d: %s: '%s' is not 1..31 chars of "
                          "[a-z0-9_]", kv->source, kv_find(kv, key)->line, key, str);
    snprintf(tb->name, sizeof tb->name, "%s", str);
    if ((rc = kv_get_str(kv, KEY("kind"), &str, err)))
        return rc;
    tb->kind = name_index(str, table_kind_name, TABLE_KIND_COUNT);
    if (tb->kind < 0)
        return swell_fail(err, SWELL_E_FORMAT, "%s:%d: %s: unknown table kind '%s'",
                          kv->source, kv_find(kv, key)->line, key, str);
    if ((rc = kv_get_str(kv, KEY("format"), &str, err)))
        return rc;
    tb->format = name_index(str, table_format_name, FORMAT_COUNT);
    if (tb->format < 0)
        return swell_fail(err, SWELL_E_FORMAT, "%s:%d: %s: unknown format '%s'", kv->source,
                          kv_find(kv, key)->line, key, str);
    uint64_t crc = 0;
    if ((rc = kv_get_int(kv, KEY("pattern"), -1, SWELL_MAX_PATTERNS - 1, &tb->pattern, err)) ||
        (rc = kv_get_int(kv, KEY("width"), 1, KTX_MAX_DIM, &tb->width, err)) ||
        (rc = kv_get_int(kv, KEY("height"), 1, KTX_MAX_DIM, &tb->height, err)) ||
        (rc = kv_get_int(kv, KEY("layers"), 1, KTX_MAX_LAYERS, &tb->layers, err)) ||
        (rc = kv_get_int(kv, KEY("levels"), 1, 14, &tb->levels, err)) ||
        (rc = kv_get_u64(kv, KEY("file_bytes"), 64, KTX_MAX_FILE_BYTES, &e->file_bytes, err)) ||
        (rc = kv_get_u64(kv, KEY("file_crc32"), 0, UINT32_MAX, &crc, err)))
        return rc;
#undef KEY
    e->file_crc32 = (uint32_t)crc;
    snprintf(e->name, sizeof e->name, "%s", tb->name);
    e->kind = tb->kind;
    e->pattern = tb->pattern;
    e->format = tb->format;
    e->width = tb->width;
    e->height = tb->height;
    e->layers = tb->layers;
    e->levels = tb->levels;
    return 0;
}

int manifest_read_memory(const void *buf, size_t len, const char *name_for_errors,
                         struct tables_manifest *out, struct swell_err *err)
{
    memset(out, 0, sizeof *out);
    struct kv kv;
    const char *name = name_for_errors ? name_for_errors : "(manifest)";
    /* The writer ends every line with '\n'; without it the last value may be cut short and
     * still parse (a crc32 missing digits), so a file not ending in '\n' is truncated. */
    if (len == 0 || ((const char *)buf)[len - 1] != '\n')
        return swell_fail(err, SWELL_E_FORMAT, "%s: truncated (does not end with a newline); "
                          "re-bake the table set", name);
    int rc = kv_parse(buf, len, name, TABLES_MANIFEST_MAGIC, TABLES_MANIFEST_VERSION, &kv, err);
    if (rc)
        return rc;
    struct swell_tables *s = &out->set;
    if ((rc = tables_check_seal(buf, len, &kv, err)))
        goto done;
    if ((rc = preset_apply_kv(&kv, "state.", 1, &s->state, err)))
        goto done;
    if ((rc = kv_get_int(&kv, "set.patterns", 0, SWELL_MAX_PATTERNS, &s->patterns, err)) ||
        (rc = kv_get_int(&kv, "set.frames", 0, KTX_MAX_LAYERS, &s->frames, err)) ||
        (rc = get_f(&kv, "set.loop_period_s", &s->loop_period_s, err)))
        goto done;
    for (int i = 0; i < SWELL_MAX_PATTERNS; i++) {
        struct swell_pattern_info *p = &s->pattern[i];
        char key[64];
#define PKEY(field) (snprintf(key, sizeof key, "pattern.%d." field, i), key)
        if ((rc = get_f(&kv, PKEY("size_m"), &p->size_m, err)) ||
            (rc = get_f(&kv, PKEY("k_min"), &p->k_min, err)) ||
            (rc = get_f(&kv, PKEY("k_max"), &p->k_max, err)) ||
            (rc = get_f(&kv, PKEY("lambda"), &p->lambda, err)) ||
            (rc = get_f(&kv, PKEY("period_s"), &p->period_s, err)) ||
            (rc = get_f(&kv, PKEY("var_h"), &p->var_h, err)) ||
            (rc = get_f(&kv, PKEY("mss_x"), &p->mss_x, err)) ||
            (rc = get_f(&kv, PKEY("mss_y"), &p->mss_y, err)))
            goto done;
#undef PKEY
    }
    if ((rc = get_f(&kv, "set.mss_unresolved_x", &s->mss_unresolved_x, err)) ||
        (rc = get_f(&kv, "set.mss_unresolved_y", &s->mss_unresolved_y, err)) ||
        (rc = get_f(&kv, "set.hs_m", &s->hs_m, err)) ||
        (rc = get_f(&kv, "set.whitecap_breaking_fraction", &s->whitecap_breaking_fraction,
                     err)) ||
        (rc = get_f(&kv, "set.foam_recovery_per_s", &s->foam_recovery_per_s, err)) ||
        (rc = get_f(&kv, "set.whitecap_fraction_model", &s->whitecap_fraction_model, err)) ||
        (rc = get_f(&kv, "set.whitecap_fraction_measured", &s->whitecap_fraction_measured,
                    err)) ||
        (rc = get_f(&kv, "set.whitecap_epsilon", &s->whitecap_epsilon, err)) ||
        (rc = kv_get_int(&kv, "set.count", 0, SWELL_MAX_TABLES, &s->count, err)))
        goto done;
    for (int i = 0; i < s->count; i++) {
        if ((rc = read_entry(&kv, i, &s->table[i], &out->entry[i], err)))
            goto done;
        for (int j = 0; j < i; j++)
            if (strcmp(s->table[j].name, s->table[i].name) == 0) {
                rc = swell_fail(err, SWELL_E_FORMAT, "%s: table.%d.name: '%s' repeats "
                                "table.%d", kv.source, i, s->table[i].name, j);
                goto done;
            }
    }
    if ((rc = kv_check_all_used(&kv, err)) == 0)
        rc = tables_check_manifest(out, &kv, err);
done:
    kv_destroy(&kv);
    if (rc)
        memset(out, 0, sizeof *out);
    return rc;
}

/* ---- one table file ------------------------------------------------------------------- */

/* Read dir/<name>.ktx, check it against its manifest entry and decode it into *tb (data
 * owned by *tb on success, nothing on failure). */
static int check_table(const char *dir, const struct tables_manifest *m, int i,
                       struct swell_table *tb, struct swell_err *err)
{
    const struct tables_manifest_entry *e = &m->entry[i];
    char file[48], path[4096];
    snprintf(file, sizeof file, "%s" KTX_SUFFIX, e->name);
    memset(tb, 0, sizeof *tb);
    int rc = fs_join(path, sizeof path, dir, file, err);
    if (rc)
        return rc;
    uint8_t *buf = NULL;
    size_t len = 0;
    rc = fs_read_file(path, KTX_MAX_FILE_BYTES, &buf, &len, err);
    if (rc)
        return swell_err_context(err, "%s: table listed in the manifest cannot be read", path);
    if (len != e->file_bytes) {
        rc = swell_fail(err, SWELL_E_FORMAT, "%s: file is %zu bytes, the manifest says %" PRIu64
                        "; the set is inconsistent, re-bake it", path, len, e->file_bytes);
        goto done;
    }
    uint32_t crc = fs_crc32(buf, len);
    if (crc != e->file_crc32) {
        rc = swell_fail(err, SWELL_E_CHECKSUM, "%s: file crc32 is %" PRIu32 ", the manifest "
                        "says %" PRIu32 "; the file is corrupt or from another bake, re-bake "
                        "the set", path, crc, e->file_crc32);
        goto done;
    }
    rc = ktx_read_memory(buf, len, path, tb, err);
    if (rc)
        goto done;
    if (strcmp(tb->name, e->name) != 0 || tb->kind != e->kind || tb->pattern != e->pattern ||
        tb->format != e->format || tb->width != e->width || tb->height != e->height ||
        tb->layers != e->layers || tb->levels != e->levels) {
        rc = swell_fail(err, SWELL_E_FORMAT, "%s: holds table '%s' (%s, pattern %d, %s, %dx%d, "
                        "%d layers, %d levels) but the manifest lists '%s' (%s, pattern %d, %s, "
                        "%dx%d, %d layers, %d levels)", path, tb->name,
                        table_kind_name(tb->kind), tb->pattern, table_format_name(tb->format),
                        tb->width, tb->height, tb->layers, tb->levels, e->name,
                        table_kind_name(e->kind), e->pattern, table_format_name(e->format),
                        e->width, e->height, e->layers, e->levels);
        free(tb->data);
        memset(tb, 0, sizeof *tb);
        goto done;
    }
    uint32_t id = tables_set_id(&m->set.state);
    if (tb->set_id != id) {
        rc = swell_fail(err, SWELL_E_FORMAT, "%s: baked from another sea state (swell.set 0x%08"
                        PRIx32 ", the manifest's state is 0x%08" PRIx32 "): a table of another "
                        "bake; re-bake the set", path, tb->set_id, id);
    } else {
        rc = tables_check_values(tb, path, err);
    }
    if (rc) {
        free(tb->data);
        memset(tb, 0, sizeof *tb);
    }
done:
    free(buf);
    return rc;
}

/* The manifest, checked (set_check.h), and the set's memory (budget.h budget_check: its tables
 * within the budget it was baked for, the renderer's GPU memory within budget, 0: the set's
 * own), before any table is read. */
static int read_manifest(const char *dir, uint64_t budget, struct tables_manifest *m,
                         struct swell_err *err)
{
    char path[4096];
    int rc = fs_join(path, sizeof path, dir, TABLES_MANIFEST_NAME, err);
    if (rc)
        return rc;
    uint8_t *buf = NULL;
    size_t len = 0;
    rc = fs_read_file(path, TABLES_MANIFEST_MAX_BYTES, &buf, &len, err);
    if (rc)
        return swell_err_context(err, "table directory '%s' has no readable manifest (not a "
                                 "table set, or a bake was interrupted: re-bake it)", dir);
    rc = manifest_read_memory(buf, len, path, m, err);
    free(buf);
    if (rc == 0)
        rc = budget_check(&m->set.state, budget, path, err);
    return rc;
}

static int listed(const struct tables_manifest *m, const char *file)
{
    for (int i = 0; i < m->set.count; i++) {
        size_t n = strlen(m->entry[i].name);
        if (strncmp(file, m->entry[i].name, n) == 0 && strcmp(file + n, KTX_SUFFIX) == 0)
            return 1;
    }
    return 0;
}

/* Visit every "*.ktx" in dir the manifest does not list (sorted, so reports are stable). */
static int for_unlisted(const char *dir, const struct tables_manifest *m,
                        int (*fn)(void *user, const char *file), void *user,
                        struct swell_err *err)
{
    struct dirent **list = NULL;
    int n = scandir(dir, &list, NULL, alphasort);
    if (n < 0)
        return swell_fail(err, SWELL_E_IO, "cannot list table directory '%s'", dir);
    int rc = 0;
    for (int i = 0; i < n; i++) {
        const char *f = list[i]->d_name;
        if (rc == 0 && ends_with(f, KTX_SUFFIX) && !listed(m, f))
            rc = fn(user, f);
        free(list[i]);
    }
    free(list);
    return rc;
}

struct unlisted_ctx {
    const char *dir;
    struct swell_err *err;
    tables_verify_fn fn;
    void *user;
    int first_rc;
};

static int refuse_unlisted(void *user, const char *file)
{
    struct unlisted_ctx *c = user;
    return swell_fail(c->err, SWELL_E_FORMAT, "%s/%s: table file not listed in the manifest "
                      "(left from another bake?); remove it or re-bake the set", c->dir, file);
}

/* ---- load / verify -------------------------------------------------------------------- */

int tables_load_dir(const char *dir, struct swell_tables *out, struct swell_err *err)
{
    return tables_load_dir_within(dir, 0, out, err);
}

int tables_load_dir_within(const char *dir, uint64_t budget, struct swell_tables *out,
                           struct swell_err *err)
{
    memset(out, 0, sizeof *out);
    struct tables_manifest *m = calloc(1, sizeof *m);
    if (!m)
        return swell_fail(err, SWELL_E_NOMEM, "cannot allocate the manifest");
    int rc = read_manifest(dir, budget, m, err);
    if (rc)
        goto fail;
    struct unlisted_ctx c = { dir, err, NULL, NULL, 0 };
    rc = for_unlisted(dir, m, refuse_unlisted, &c, err);
    if (rc)
        goto fail;
    *out = m->set;
    for (int i = 0; i < m->set.count; i++) {
        rc = check_table(dir, m, i, &out->table[i], err);
        if (rc)
            goto fail;
    }
    foam_bias_compute(out, &out->foam_bias);
    out->has_foam_bias = 1;
    free(m);
    return 0;
fail:
    tables_destroy(out);
    memset(out, 0, sizeof *out);
    free(m);
    return rc;
}

static void fill_entry(struct tables_verify_entry *v, const struct tables_manifest_entry *e)
{
    memset(v, 0, sizeof *v);
    snprintf(v->file, sizeof v->file, "%s" KTX_SUFFIX, e->name);
    v->listed = 1;
    v->kind = e->kind;
    v->pattern = e->pattern;
    v->format = e->format;
    v->width = e->width;
    v->height = e->height;
    v->layers = e->layers;
    v->levels = e->levels;
    v->bytes = e->file_bytes;
}

static int report_unlisted(void *user, const char *file)
{
    struct unlisted_ctx *c = user;
    struct swell_err e;
    swell_err_clear(&e);
    refuse_unlisted(&(struct unlisted_ctx){ c->dir, &e, NULL, NULL, 0 }, file);
    if (c->first_rc == 0) {
        c->first_rc = e.code;
        if (c->err)
            *c->err = e;
    }
    if (c->fn) {
        struct tables_verify_entry v;
        memset(&v, 0, sizeof v);
        snprintf(v.file, sizeof v.file, "%.47s", file);
        v.kind = v.pattern = v.format = -1;
        v.status = e.code;
        snprintf(v.msg, sizeof v.msg, "%s", e.msg);
        c->fn(c->user, &v);
    }
    return 0;
}

int tables_verify_dir(const char *dir, tables_verify_fn fn, void *user,
                      struct tables_manifest *manifest_out, struct swell_err *err)
{
    struct tables_manifest *m = calloc(1, sizeof *m);
    if (!m)
        return swell_fail(err, SWELL_E_NOMEM, "cannot allocate the manifest");
    int rc = read_manifest(dir, 0, m, err);
    if (rc)
        goto done;
    int first = 0;
    for (int i = 0; i < m->set.count; i++) {
        struct tables_verify_entry v;
        struct swell_table tb;
        struct swell_err e;
        swell_err_clear(&e);
        fill_entry(&v, &m->entry[i]);
        v.status = check_table(dir, m, i, &tb, &e);
        free(tb.data);
        if (v.status) {
            snprintf(v.msg, sizeof v.msg, "%s", e.msg);
            if (!first) {
                first = v.status;
                if (err)
                    *err = e;
            }
        }
        if (fn)
            fn(user, &v);
    }
    struct unlisted_ctx c = { dir, first ? NULL : err, fn, user, 0 };
    rc = for_unlisted(dir, m, report_unlisted, &c, err);
    if (rc == 0)
        rc = first ? first : c.first_rc;
done:
    if (manifest_out)
        *manifest_out = *m;
    free(m);
    return rc;
}

/* ---- save ----------------------------------------------------------------------------- */

int tables_save_dir(const struct swell_tables *t, const char *dir, struct swell_err *err)
{
    if (t->count < 0 || t->count > SWELL_MAX_TABLES)
        return swell_fail(err, SWELL_E_ARG, "table set has %d tables, expected 0..%d",
                          t->count, SWELL_MAX_TABLES);
    for (int i = 0; i < t->count; i++) {
        if (!table_name_valid(t->table[i].name))
            return swell_fail(err, SWELL_E_ARG, "table %d: name '%.32s' is not 1..31 chars of "
                              "[a-z0-9_]", i, t->table[i].name);
        for (int j = 0; j < i; j++)
            if (strcmp(t->table[i].name, t->table[j].name) == 0)
                return swell_fail(err, SWELL_E_ARG, "tables %d and %d are both named '%s'",
                                  j, i, t->table[i].name);
    }
    struct tables_manifest *m = calloc(1, sizeof *m);
    if (!m)
        return swell_fail(err, SWELL_E_NOMEM, "cannot allocate the manifest");
    struct set_dir pub;
    int rc = set_dir_begin(&pub, dir, err);   /* dir may be replaced; a folder beside it */
    if (rc) {
        free(m);
        return rc;
    }
    char *text = NULL;
    char path[4096];
    uint32_t id = tables_set_id(&t->state);
    for (int i = 0; i < t->count; i++) {
        const struct swell_table *tb = &t->table[i];
        struct swell_table stamped = *tb;   /* shares the data; carries the set's id */
        stamped.set_id = id;
        uint8_t *buf = NULL;
        size_t len = 0;
        char file[48];
        snprintf(file, sizeof file, "%s" KTX_SUFFIX, tb->name);
        if ((rc = ktx_write_memory(&stamped, &buf, &len, err)))
            goto done;
        snprintf(m->entry[i].name, sizeof m->entry[i].name, "%s", tb->name);
        m->entry[i].file_bytes = len;
        m->entry[i].file_crc32 = fs_crc32(buf, len);
        rc = fs_join(path, sizeof path, pub.tmp, file, err);
        if (rc == 0)
            rc = fs_write_atomic(path, buf, len, err);
        free(buf);
        if (rc)
            goto done;
    }
    size_t len = 0;
    if ((rc = manifest_write(t, m->entry, &text, &len, err)) ||
        (rc = fs_join(path, sizeof path, pub.tmp, TABLES_MANIFEST_NAME, err)) ||
        (rc = fs_write_atomic(path, text, len, err)))
        goto done;
    rc = set_dir_commit(&pub, err);   /* swaps the whole set in at once */
done:
    if (rc)
        set_dir_abort(&pub);
    free(text);
    free(m);
    return rc;
}
