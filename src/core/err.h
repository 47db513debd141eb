/* err.h - how library code fails: swell_fail and its context (the codes are swell.h's).
 *
 * Errors are returned, never printed by library code; only main() prints and exits.
 * A function that can fail takes a `struct swell_err *` last and returns 0 on success
 * or a SWELL_E_* code, after filling the struct with a specific, actionable message
 * (what failed, where, why, what to do).
 */
#ifndef SWELL_ERR_H
#define SWELL_ERR_H

/* The codes, struct swell_err and swell_err_name are the public API's (include/swell.h). */
#include "swell.h"

/* Fill `e` (may be NULL) with code and a printf-formatted message; returns code,
 * so failures read `return swell_fail(e, SWELL_E_IO, "cannot open %s: %s", path, strerror(errno));` */
int swell_fail(struct swell_err *e, int code, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

/* Prepend context to an existing message: "loading tables/x.ktx: <old msg>". Returns e->code. */
int swell_err_context(struct swell_err *e, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));

void swell_err_clear(struct swell_err *e);

#endif
