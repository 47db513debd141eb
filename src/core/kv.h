/* kv.h - a small strict "key = value" text format, used by the manifest and the presets.
 *
 *     swell-manifest 1          <- optional magic line "<word> <version>" (caller decides)
 *     # comment                 <- '#' lines and blank lines are ignored
 *     wind_speed_mps = 15       <- key: [a-z0-9_.]+, value: the rest of the line, trimmed
 *
 * Refused, with "source:line: ..." messages: a line without '=', an empty key or value, a key
 * with other characters, a duplicate key, NUL bytes, lines over KV_MAX_LINE bytes. Lookups mark
 * entries used so kv_check_all_used() can refuse unknown keys with their line number.
 */
#ifndef SWELL_KV_H
#define SWELL_KV_H

#include <stddef.h>
#include <stdint.h>
#include "core/err.h"

#define KV_MAX_LINE    1024
#define KV_MAX_ENTRIES 4096

struct kv_entry {
    char *key, *value;  /* NUL-terminated copies */
    int line;           /* 1-based line number in the source */
    int used;
};

struct kv {
    char source[256];   /* file name for messages */
    int count;
    struct kv_entry *entry;
};

/* Parse `len` bytes. If magic is non-NULL the first line must be "<magic> <version>": another
 * first word is SWELL_E_FORMAT, the right word with another version is SWELL_E_VERSION.
 * On failure *out is empty (kv_destroy is still safe). */
int kv_parse(const char *text, size_t len, const char *source, const char *magic, int version,
             struct kv *out, struct swell_err *err);
void kv_destroy(struct kv *kv);

/* The entry for key (marked used) or NULL. */
struct kv_entry *kv_find(struct kv *kv, const char *key);

/* Typed getters: missing key -> SWELL_E_FORMAT "source: missing key 'k'"; unparsable or out of
 * [lo, hi] -> SWELL_E_FORMAT "source:line: k: ...". Numbers: strtod/strtoll with full checks
 * (empty, trailing junk, NaN, inf, overflow refused). */
int kv_get_double(struct kv *kv, const char *key, double lo, double hi, double *out,
                  struct swell_err *err);
int kv_get_float(struct kv *kv, const char *key, double lo, double hi, float *out,
                 struct swell_err *err);
int kv_get_int(struct kv *kv, const char *key, long long lo, long long hi, int *out,
               struct swell_err *err);
int kv_get_u64(struct kv *kv, const char *key, uint64_t lo, uint64_t hi, uint64_t *out,
               struct swell_err *err);
int kv_get_str(struct kv *kv, const char *key, const char **out, struct swell_err *err);

/* Value parsers for an entry already found (the same checks and messages). */
int kv_entry_double(const struct kv *kv, const struct kv_entry *e, double lo, double hi,
                    double *out, struct swell_err *err);
int kv_entry_u64(const struct kv *kv, const struct kv_entry *e, uint64_t lo, uint64_t hi,
                 uint64_t *out, struct swell_err *err);
int kv_entry_int(const struct kv *kv, const struct kv_entry *e, long long lo, long long hi,
                 int *out, struct swell_err *err);

/* The first entry never looked up: SWELL_E_FORMAT "source:line: unknown key 'k'". */
int kv_check_all_used(const struct kv *kv, struct swell_err *err);

#endif
