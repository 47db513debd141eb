#include "core/kv.h"

#include <errno.h>
#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void kv_destroy(struct kv *kv)
{
    if (!kv)
        return;
    for (int i = 0; i < kv->count; i++) {
        free(kv->entry[i].key);
        free(kv->entry[i].value);
    }
    free(kv->entry);
    kv->entry = NULL;
    kv->count = 0;
}

static int is_key_char(char c)
{
    return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '.';
}

static int is_blank(char c)
{
    return c == ' ' || c == '\t' || c == '\r';
}

static char *dup_range(const char *a, const char *b)
{
    size_t n = (size_t)(b - a);
    char *s = malloc(n + 1);
    if (s) {
        memcpy(s, a, n);
        s[n] = '\0';
    }
    return s;
}

/* "<magic> <version>" exactly, nothing else on the line but a trailing '\r'. */
static int check_magic(const struct kv *kv, const char *a, const char *b, const char *magic,
                       int version, struct swell_err *err)
{
    while (b > a && is_blank(b[-1]))
        b--;
    size_t m = strlen(magic);
    if ((size_t)(b - a) <= m || memcmp(a, magic, m) != 0 || a[m] != ' ')
        return swell_fail(err, SWELL_E_FORMAT, "%s:1: first line is not '%s %d'; this is not "
                          "a %s file", kv->source, magic, version, magic);
    const char *v = a + m + 1;
    long got = 0;
    int digits = 0;
    for (; v < b && *v >= '0' && *v <= '9' && digits < 9; v++, digits++)
        got = got * 10 + (*v - '0');
    if (digits == 0 || v != b)
        return swell_fail(err, SWELL_E_FORMAT, "%s:1: version after '%s' is not a number",
                          kv->source, magic);
    if (got != version)
        return swell_fail(err, SWELL_E_VERSION, "%s:1: %s version %ld, this build reads "
                          "version %d; re-create the file with this build", kv->source, magic,
                          got, version);
    return 0;
}

static int parse_line(struct kv *kv, int cap, const char *a, const char *b, int line,
                      struct swell_err *err)
{
    while (a < b && is_blank(*a))
        a++;
    while (b > a && is_blank(b[-1]))
        b--;
    if (a == b || *a == '#')
        return 0;
    const char *k = a;
    while (a < b && is_key_char(*a))
        a++;
    const char *ke = a;
    while (a < b && is_blank(*a))
        a++;
    if (ke == k)
        return swell_fail(err, SWELL_E_FORMAT, "%s:%d: expected 'key = value' with a key of "
                          "[a-z0-9_.]", kv->source, line);
    if (a == b || *a != '=')
        return swell_fail(err, SWELL_E_FORMAT, "%s:%d: expected '=' after key '%.*s' (keys "
                          "are lower case [a-z0-9_.])", kv->source, line, (int)(ke - k), k);
    a++;
    while (a < b && is_blank(*a))
        a++;
    if (a == b)
        return swell_fail(err, SWELL_E_FORMAT, "%s:%d: key '%.*s' has no value", kv->source,
                          line, (int)(ke - k), k);
    for (int i = 0; i < kv->count; i++)
        if (strlen(kv->entry[i].key) == (size_t)(ke - k) &&
            memcmp(kv->entry[i].key, k, (size_t)(ke - k)) == 0)
            return swell_fail(err, SWELL_E_FORMAT, "%s:%d: duplicate key '%s' (first set on "
                              "line %d)", kv->source, line, kv->entry[i].key,
                              kv->entry[i].line);
    if (kv->count >= cap)
        return swell_fail(err, SWELL_E_FORMAT, "%s:%d: more than %d entries", kv->source, line,
                          KV_MAX_ENTRIES);
    struct kv_entry *e = &kv->entry[kv->count];
    e->key = dup_range(k, ke);
    e->value = dup_range(a, b);
    e->line = line;
    e->used = 0;
    kv->count++;
    if (!e->key || !e->value)
        return swell_fail(err, SWELL_E_NOMEM, "%s:%d: out of memory", kv->source, line);
    return 0;
}

int kv_parse(const char *text, size_t len, const char *source, const char *magic, int version,
             struct kv *out, struct swell_err *err)
{
    memset(out, 0, sizeof *out);
    snprintf(out->source, sizeof out->source, "%s", source ? source : "(text)");
    int rc = 0;
    int cap = 0;
    for (size_t i = 0; i < len; i++)
        if (text[i] == '\n')
            cap++;
    cap = cap + 1 < KV_MAX_ENTRIES ? cap + 1 : KV_MAX_ENTRIES;
    out->entry = calloc((size_t)cap, sizeof *out->entry);
    if (!out->entry)
        return swell_fail(err, SWELL_E_NOMEM, "%s: out of memory", out->source);
    if (memchr(text, '\0', len)) {
        rc = swell_fail(err, SWELL_E_FORMAT, "%s: contains a NUL byte; not a text file",
                        out->source);
        goto fail;
    }
    const char *p = text, *end = text + len;
    int line = 0;
    while (p < end) {
        const char *nl = memchr(p, '\n', (size_t)(end - p));
        const char *le = nl ? nl : end;
        line++;
        if (le - p > KV_MAX_LINE) {
            rc = swell_fail(err, SWELL_E_FORMAT, "%s:%d: line longer than %d bytes",
                            out->source, line, KV_MAX_LINE);
            goto fail;
        }
        rc = line == 1 && magic ? check_magic(out, p, le, magic, version, err)
                                : parse_line(out, cap, p, le, line, err);
        if (rc)
            goto fail;
        p = nl ? nl + 1 : end;
    }
    if (magic && line == 0) {
        rc = swell_fail(err, SWELL_E_FORMAT, "%s: empty file; expected '%s %d' on line 1",
                        out->source, magic, version);
        goto fail;
    }
    return 0;
fail:
    kv_destroy(out);
    return rc;
}

struct kv_entry *kv_find(struct kv *kv, const char *key)
{
    for (int i = 0; i < kv->count; i++)
        if (strcmp(kv->entry[i].key, key) == 0) {
            kv->entry[i].used = 1;
            return &kv->entry[i];
        }
    return NULL;
}

static int missing(const struct kv *kv, const char *key, struct swell_err *err)
{
    return swell_fail(err, SWELL_E_FORMAT, "%s: missing key '%s'", kv->source, key);
}

int kv_entry_double(const struct kv *kv, const struct kv_entry *e, double lo, double hi,
                    double *out, struct swell_err *err)
{
    char *end = NULL;
    errno = 0;
    double v = strtod(e->value, &end);
    if (end == e->value || *end != '\0')
        return swell_fail(err, SWELL_E_FORMAT, "%s:%d: %s: '%s' is not a number", kv->source,
                          e->line, e->key, e->value);
    if (!isfinite(v) || errno == ERANGE)
        return swell_fail(err, SWELL_E_FORMAT, "%s:%d: %s: '%s' is not a finite number in "
                          "range", kv->source, e->line, e->key, e->value);
    if (v < lo || v > hi)
        return swell_fail(err, SWELL_E_FORMAT, "%s:%d: %s: %s is outside [%.9g, %.9g]",
                          kv->source, e->line, e->key, e->value, lo, hi);
    *out = v;
    return 0;
}

/* Integers are plain decimal (optional '-'); hex and leading '+' are refused so a value
 * means one thing. */
static int entry_ll(const struct kv *kv, const struct kv_entry *e, int allow_neg,
                    long long *sv, unsigned long long *uv, struct swell_err *err)
{
    const char *s = e->value;
    int neg = s[0] == '-';
    const char *d = s + neg;
    if (*d < '0' || *d > '9' || (neg && !allow_neg))
        return swell_fail(err, SWELL_E_FORMAT, "%s:%d: %s: '%s' is not a%s integer",
                          kv->source, e->line, e->key, s, allow_neg ? "n" : " non-negative");
    char *end = NULL;
    errno = 0;
    if (allow_neg)
        *sv = strtoll(s, &end, 10);
    else
        *uv = strtoull(s, &end, 10);
    if (*end != '\0')
        return swell_fail(err, SWELL_E_FORMAT, "%s:%d: %s: '%s' is not an integer", kv->source,
                          e->line, e->key, s);
    if (errno == ERANGE)
        return swell_fail(err, SWELL_E_FORMAT, "%s:%d: %s: '%s' is out of range", kv->source,
                          e->line, e->key, s);
    return 0;
}

int kv_entry_int(const struct kv *kv, const struct kv_entry *e, long long lo, long long hi,
                 int *out, struct swell_err *err)
{
    long long v = 0;
    int rc = entry_ll(kv, e, 1, &v, NULL, err);
    if (rc)
        return rc;
    if (v < lo || v > hi)
        return swell_fail(err, SWELL_E_FORMAT, "%s:%d: %s: %lld is outside [%lld, %lld]",
                          kv->source, e->line, e->key, v, lo, hi);
    *out = (int)v;
    return 0;
}

int kv_entry_u64(const struct kv *kv, const struct kv_entry *e, uint64_t lo, uint64_t hi,
                 uint64_t *out, struct swell_err *err)
{
    unsigned long long v = 0;
    int rc = entry_ll(kv, e, 0, NULL, &v, err);
    if (rc)
        return rc;
    if (v < lo || v > hi)
        return swell_fail(err, SWELL_E_FORMAT, "%s:%d: %s: %llu is outside [%" PRIu64 ", %"
                          PRIu64 "]", kv->source, e->line, e->key, v, lo, hi);
    *out = (uint64_t)v;
    return 0;
}

int kv_get_double(struct kv *kv, const char *key, double lo, double hi, double *out,
                  struct swell_err *err)
{
    struct kv_entry *e = kv_find(kv, key);
    return e ? kv_entry_double(kv, e, lo, hi, out, err) : missing(kv, key, err);
}

int kv_get_float(struct kv *kv, const char *key, double lo, double hi, float *out,
                 struct swell_err *err)
{
    double v = 0;
    int rc = kv_get_double(kv, key, lo, hi, &v, err);
    if (rc == 0)
        *out = (float)v;
    return rc;
}

int kv_get_int(struct kv *kv, const char *key, long long lo, long long hi, int *out,
               struct swell_err *err)
{
    struct kv_entry *e = kv_find(kv, key);
    return e ? kv_entry_int(kv, e, lo, hi, out, err) : missing(kv, key, err);
}

int kv_get_u64(struct kv *kv, const char *key, uint64_t lo, uint64_t hi, uint64_t *out,
               struct swell_err *err)
{
    struct kv_entry *e = kv_find(kv, key);
    return e ? kv_entry_u64(kv, e, lo, hi, out, err) : missing(kv, key, err);
}

int kv_get_str(struct kv *kv, const char *key, const char **out, struct swell_err *err)
{
    struct kv_entry *e = kv_find(kv, key);
    if (!e)
        return missing(kv, key, err);
    *out = e->value;
    return 0;
}

int kv_check_all_used(const struct kv *kv, struct swell_err *err)
{
    for (int i = 0; i < kv->count; i++)
        if (!kv->entry[i].used)
            return swell_fail(err, SWELL_E_FORMAT, "%s:%d: unknown key '%s'", kv->source,
                              kv->entry[i].line, kv->entry[i].key);
    return 0;
}
