/* parse.h - strict parsing of command-line and preset values, shared by both programs.
 * Each returns 0 or SWELL_E_ARG with a message naming the option, the text, and what is allowed:
 *     --wind: 'abc' is not a number (m/s, allowed 0.5 to 40)
 * NaN, infinities, empty strings, trailing junk and out-of-range values are all refused.
 */
#ifndef SWELL_PARSE_H
#define SWELL_PARSE_H

#include <stdint.h>
#include "core/err.h"

int parse_double(const char *opt, const char *text, double lo, double hi, const char *unit,
                 double *out, struct swell_err *err);
int parse_float(const char *opt, const char *text, double lo, double hi, const char *unit,
                float *out, struct swell_err *err);
int parse_int(const char *opt, const char *text, long lo, long hi, int *out, struct swell_err *err);
/* "tiny" (4 MiB), "default" (16 MiB), or a byte count with optional K/M/G suffix (binary). */
int parse_budget(const char *opt, const char *text, uint64_t *out, struct swell_err *err);
/* "1280x720" -> w, h each in [lo, hi] */
int parse_wxh(const char *opt, const char *text, int lo, int hi, int *w, int *h,
              struct swell_err *err);
/* "a,b" or "a,b,c": exactly n comma-separated numbers, each in [lo, hi] */
int parse_doubles(const char *opt, const char *text, int n, double lo, double hi, double *out,
                  struct swell_err *err);

/* Enum names through a table names[count]: the value named `name` from index `first` on (a
 * table's "default" at 0 can be skipped), or -1; and a value's name, "?" outside the table. */
int parse_name(const char *const *names, int first, int count, const char *name);
const char *name_of(const char *const *names, int count, int value);

/* 1 when `name` is a whole space-separated token of `list` (EGL/GL extension strings: exact
 * names, never substrings - "GL_OES_texture_half_float" must not match "..._linear"). */
int parse_has_token(const char *list, const char *name);

#endif
