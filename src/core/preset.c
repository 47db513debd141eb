#include "core/preset.h"

#include <dirent.h>
#include <errno.h>
#include <float.h>
#include <inttypes.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/datadir.h"
#include "core/fsutil.h"

/* The presets' and the manifest's keys are the members of struct seastate by name, every one
 * in declaration order (core/seastate.h seastate_fields). */
int preset_format_state(const struct seastate *s, const char *prefix, char *buf, size_t cap,
                        size_t *len, struct swell_err *err)
{
    for (int i = 0; i < seastate_field_count; i++) {
        const char *p = (const char *)s + seastate_fields[i].offset;
        char val[64];
        switch (seastate_fields[i].type) {
        case SS_FLOAT: {
            float f;
            memcpy(&f, p, sizeof f);
            snprintf(val, sizeof val, "%.9g", (double)f);
            break;
        }
        case SS_INT: {
            int v;
            memcpy(&v, p, sizeof v);
            snprintf(val, sizeof val, "%d", v);
            break;
        }
        case SS_U32: {
            uint32_t v;
            memcpy(&v, p, sizeof v);
            snprintf(val, sizeof val, "%" PRIu32, v);
            break;
        }
        case SS_U64: {
            uint64_t v;
            memcpy(&v, p, sizeof v);
            snprintf(val, sizeof val, "%" PRIu64, v);
            break;
        }
        case SS_SPECTRUM:
        case SS_WHITECAP: {
            int v;
            memcpy(&v, p, sizeof v);
            snprintf(val, sizeof val, "%s", seastate_fields[i].type == SS_SPECTRUM ?
                     spectrum_name(v) : whitecap_model_name(v));
            break;
        }
        }
        int n = snprintf(buf + *len, cap - *len, "%s%s = %s\n", prefix, seastate_fields[i].key,
                         val);
        if (n < 0 || (size_t)n >= cap - *len)
            return swell_fail(err, SWELL_E_ARG, "sea state text does not fit %zu bytes", cap);
        *len += (size_t)n;
    }
    return 0;
}

static int apply_one(struct kv *kv, struct kv_entry *e, const struct seastate_field *f,
                     struct seastate *s, struct swell_err *err)
{
    char *p = (char *)s + f->offset;
    switch (f->type) {
    case SS_FLOAT: {
        double d = 0;
        int rc = kv_entry_double(kv, e, -FLT_MAX, FLT_MAX, &d, err);
        if (rc)
            return rc;
        float v = (float)d;
        memcpy(p, &v, sizeof v);
        return 0;
    }
    case SS_INT: {
        int v = 0;
        int rc = kv_entry_int(kv, e, INT32_MIN, INT32_MAX, &v, err);
        if (rc == 0)
            memcpy(p, &v, sizeof v);
        return rc;
    }
    case SS_U32:
    case SS_U64: {
        uint64_t v = 0;
        int rc = kv_entry_u64(kv, e, 0, f->type == SS_U32 ? UINT32_MAX : UINT64_MAX, &v, err);
        if (rc)
            return rc;
        if (f->type == SS_U32) {
            uint32_t v32 = (uint32_t)v;
            memcpy(p, &v32, sizeof v32);
        } else {
            memcpy(p, &v, sizeof v);
        }
        return 0;
    }
    default: {
        int spec = f->type == SS_SPECTRUM;
        int v = spec ? spectrum_from_name(e->value) : whitecap_model_from_name(e->value);
        if (v < 0)
            return swell_fail(err, SWELL_E_FORMAT, "%s:%d: %s: '%s' is not one of %s",
                              kv->source, e->line, e->key, e->value,
                              spec ? "default, pm, jonswap, tma" : "default, mom80, wu88");
        memcpy(p, &v, sizeof v);
        return 0;
    }
    }
}

int preset_apply_kv(struct kv *kv, const char *prefix, int require_all, struct seastate *s,
                    struct swell_err *err)
{
    for (int i = 0; i < seastate_field_count; i++) {
        char key[96];
        snprintf(key, sizeof key, "%s%s", prefix, seastate_fields[i].key);
        struct kv_entry *e = kv_find(kv, key);
        if (!e) {
            if (require_all)
                return swell_fail(err, SWELL_E_FORMAT, "%s: missing key '%s'", kv->source, key);
            continue;
        }
        int rc = apply_one(kv, e, &seastate_fields[i], s, err);
        if (rc)
            return rc;
    }
    return 0;
}

int preset_parse_memory(const char *text, size_t len, const char *source, struct seastate *s,
                        struct swell_err *err)
{
    struct kv kv;
    int rc = kv_parse(text, len, source, NULL, 0, &kv, err);
    if (rc)
        return rc;
    struct seastate copy = *s;
    rc = preset_apply_kv(&kv, "", 0, &copy, err);
    if (rc == 0)
        rc = kv_check_all_used(&kv, err);
    if (rc == 0)
        *s = copy;
    kv_destroy(&kv);
    return rc;
}

/* data_dir, or the presets' directory found by core/datadir.h into buf. */
static int data_dir_or_default(const char *data_dir, char *buf, size_t cap, const char **dir,
                               struct swell_err *err)
{
    *dir = data_dir;
    if (data_dir)
        return 0;
    *dir = buf;
    return data_dir_find(DATADIR_PRESETS, buf, cap, err);
}

static int ends_with(const char *s, const char *suffix)
{
    size_t n = strlen(s), m = strlen(suffix);
    return n >= m && strcmp(s + n - m, suffix) == 0;
}

static int is_bare_name(const char *s)
{
    size_t n = strlen(s);
    if (n == 0 || n > 64)
        return 0;
    return strspn(s, "abcdefghijklmnopqrstuvwxyz0123456789_-") == n;
}

int preset_load_from(const char *name_or_path, const char *data_dir, struct seastate *s,
                     struct swell_err *err)
{
    char path[4096], found[4096];
    const char *dir = data_dir;
    if (ends_with(name_or_path, PRESET_SUFFIX)) {
        snprintf(path, sizeof path, "%s", name_or_path);
    } else if (is_bare_name(name_or_path)) {
        if (data_dir_or_default(data_dir, found, sizeof found, &dir, err))
            return swell_err_context(err, "preset '%s'", name_or_path);
        int n = snprintf(path, sizeof path, "%s/%s" PRESET_SUFFIX, dir, name_or_path);
        if (n < 0 || (size_t)n >= sizeof path)
            return swell_fail(err, SWELL_E_ARG, "preset directory '%s' is too long", dir);
    } else {
        return swell_fail(err, SWELL_E_ARG, "preset '%s' is neither a name ([a-z0-9_-], looked "
                          "up in swell's " DATADIR_PRESETS "/ directory) nor a path ending in "
                          PRESET_SUFFIX, name_or_path);
    }
    uint8_t *buf = NULL;
    size_t len = 0;
    int rc = fs_read_file(path, PRESET_MAX_BYTES, &buf, &len, err);
    if (rc) {
        if (!ends_with(name_or_path, PRESET_SUFFIX))
            swell_err_context(err, "preset '%s' (`swell --help` lists the presets in %s)",
                              name_or_path, dir);
        return rc;
    }
    rc = preset_parse_memory((const char *)buf, len, path, s, err);
    free(buf);
    return rc;
}

int preset_load(const char *name_or_path, struct seastate *s, struct swell_err *err)
{
    return preset_load_from(name_or_path, NULL, s, err);
}

static int preset_filter(const struct dirent *d)
{
    return ends_with(d->d_name, PRESET_SUFFIX) && strlen(d->d_name) > strlen(PRESET_SUFFIX);
}

/* The first "# " line of the file, newline stripped; "" when there is none. */
static void read_summary(const char *path, char *out, size_t cap)
{
    out[0] = '\0';
    uint8_t *buf = NULL;
    size_t len = 0;
    if (fs_read_file(path, PRESET_MAX_BYTES, &buf, &len, NULL) != 0)
        return;
    const char *p = (const char *)buf, *end = p + len;
    while (p < end) {
        const char *nl = memchr(p, '\n', (size_t)(end - p));
        const char *le = nl ? nl : end;
        if (le - p >= 2 && p[0] == '#' && p[1] == ' ') {
            size_t n = (size_t)(le - p - 2);
            if (n >= cap)
                n = cap - 1;
            memcpy(out, p + 2, n);
            out[n] = '\0';
            break;
        }
        p = nl ? nl + 1 : end;
    }
    free(buf);
}

int preset_list(const char *data_dir, preset_list_fn fn, void *user, struct swell_err *err)
{
    char found[4096];
    const char *dir;
    if (data_dir_or_default(data_dir, found, sizeof found, &dir, err))
        return swell_err_context(err, "listing presets");
    struct dirent **list = NULL;
    int n = scandir(dir, &list, preset_filter, alphasort);
    if (n < 0)
        return swell_fail(err, SWELL_E_IO, "cannot list presets in '%s': %s", dir,
                          strerror(errno));
    for (int i = 0; i < n; i++) {
        char name[256], path[4096], summary[256];
        size_t m = strlen(list[i]->d_name) - strlen(PRESET_SUFFIX);
        if (m >= sizeof name)
            m = sizeof name - 1;
        memcpy(name, list[i]->d_name, m);
        name[m] = '\0';
        struct swell_err ignored;
        if (fs_join(path, sizeof path, dir, list[i]->d_name, &ignored))
            summary[0] = '\0';
        else
            read_summary(path, summary, sizeof summary);
        fn(user, name, summary);
        free(list[i]);
    }
    free(list);
    return 0;
}
