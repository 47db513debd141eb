/* set_check.h - a table set's values checked against physics and against each other, the one
 * validation the loader (tables_load_dir) and `swell-bake inspect` (tables_verify_dir) share.
 *
 * The manifest's seal (below) catches a file damaged or edited by hand; the value checks
 * catch what a seal cannot: a manifest written by another program, or edited and resealed.
 * Before them a manifest that parsed could still lie - set.frames = 0 crashed the renderer
 * (a modulo by zero), a patch size of 0 or -300 m or a slope variance of 50 drew a garbage
 * frame and exited 0 (issue 17). Every refusal names the file, the key and its line, the value,
 * what it should be and what to do (re-bake).
 */
#ifndef SWELL_SET_CHECK_H
#define SWELL_SET_CHECK_H

#include "core/err.h"
#include "core/kv.h"
#include "tables/tables.h"
#include "tables/tables_io.h"

/* The parsed manifest m (kv: its text, for line numbers):
 *  - the state is resolved (frames, sizes chosen) and within seastate_fields' ranges;
 *  - set.patterns, set.frames and set.loop_period_s are the state's;
 *  - each used pattern: patch side 0.01..1e5 m, 0 <= k_min <= k_max <= the grid's Nyquist
 *    pi size_fs / size_m, lambda the state's choppiness, period T / m for a whole m in
 *    1..4096, height variance 0..1e4 m^2, slope variances 0..1; unused patterns all 0;
 *  - unresolved slope variances 0..1, hs_m = 4 sqrt(sum var_h), whitecap fractions 0..1,
 *    foam recovery rate in (0, 1e4] per s, whitecap threshold finite within +-100;
 *  - the tables are exactly tables_layout(state): names, kinds, patterns, formats, sizes,
 *    layers and levels. */
int tables_check_manifest(const struct tables_manifest *m, struct kv *kv, struct swell_err *err);

/* One decoded RGBA8 table: every channel's dequantised range [bias, bias + scale] within its
 * kind's physical bounds (displacement within +-1000 m, slopes within +-100, second moments
 * not negative, Fresnel values within [-1, 1] or [0, 1]); path labels the message. */
int tables_check_values(const struct swell_table *t, const char *path, struct swell_err *err);

/* The id each table of a set baked from state carries (swell.set): crc32 of the manifest's
 * "state." lines. */
uint32_t tables_set_id(const struct seastate *state);

/* Replace text's last line if it is a seal ("manifest.crc32 = ..."), else add one, so the
 * text is sealed; text[0..len) ends with '\n', cap is the buffer's size. Returns the new
 * length, 0 when text does not end with '\n' or the seal does not fit. The writer seals
 * this way; the tests and the fuzz target reseal edited text to reach the value checks. */
size_t manifest_reseal(char *text, size_t len, size_t cap);

/* The seal of text[0..len) (kv: text parsed): its last line is "manifest.crc32 = N" and N is
 * the crc32 of the lines above it; SWELL_E_FORMAT without it, SWELL_E_CHECKSUM on a mismatch. */
int tables_check_seal(const char *text, size_t len, struct kv *kv, struct swell_err *err);

#endif
