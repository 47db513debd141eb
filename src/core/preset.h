/* preset.h - sea-state presets: small "key = value" files (src/core/kv.h) in the tables/ directory.
 *
 * Keys are struct seastate field names, units in the name (wind_speed_mps = 15); enums by name
 * (spectrum = jonswap, whitecap_model = mom80). A preset sets only the keys it names, so presets
 * combine ("--preset rough --budget tiny"). Unknown keys, duplicates and bad numbers (empty,
 * trailing junk, NaN, inf, out of the type's range) are refused with "file:line: ...". Ranges
 * are seastate_validate()'s job, not the parser's.
 */
#ifndef SWELL_PRESET_H
#define SWELL_PRESET_H

#include <stddef.h>
#include "core/err.h"
#include "core/kv.h"
#include "core/seastate.h"

#define PRESET_SUFFIX ".preset"
#define PRESET_MAX_BYTES 65536

/* name_or_path: a bare name ("rough", [a-z0-9_-]) is looked up as <data_dir>/<name>.preset,
 * data_dir = swell's tables/ directory (core/datadir.h: $SWELL_DATA_DIR/tables, the source tree
 * or $(PREFIX)/share/swell/tables); anything ending in ".preset" is opened as a path.
 * On failure *s is unchanged. */
int preset_load(const char *name_or_path, struct seastate *s, struct swell_err *err);
/* The same with an explicit directory (NULL = core/datadir.h's). */
int preset_load_from(const char *name_or_path, const char *data_dir, struct seastate *s,
                     struct swell_err *err);
/* Parse preset text; `source` names it in messages. On failure *s is unchanged. */
int preset_parse_memory(const char *text, size_t len, const char *source, struct seastate *s,
                        struct swell_err *err);

/* Every <data_dir>/<name>.preset in name order: fn(user, name, summary) where summary is the
 * text of the file's first "# " comment line ("" if none). */
typedef void (*preset_list_fn)(void *user, const char *name, const char *summary);
int preset_list(const char *data_dir, preset_list_fn fn, void *user, struct swell_err *err);

/* Shared with the table manifest, so the sea state is written and read by one field table.
 * Append "<prefix><field> = <value>\n" for every seastate field (floats %.9g: exact round
 * trip) to buf at *len; SWELL_E_ARG if cap is too small. */
int preset_format_state(const struct seastate *s, const char *prefix, char *buf, size_t cap,
                        size_t *len, struct swell_err *err);
/* Apply the "<prefix><field>" keys found in kv to *s (marking them used). require_all: a
 * missing field is an error (the manifest), else it is left as is (presets). On failure *s may
 * be partly written; callers pass a copy. */
int preset_apply_kv(struct kv *kv, const char *prefix, int require_all, struct seastate *s,
                    struct swell_err *err);

#endif
