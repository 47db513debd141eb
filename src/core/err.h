/* err.h - swell's error codes and the one table that maps them to messages.
 *
 * Errors are returned, never printed by library code; only main() prints and exits.
 * A function that can fail takes a `struct swell_err *` last and returns 0 on success
 * or a SWELL_E_* code, after filling the struct with a specific, actionable message
 * (what failed, where, why, what to do).
 */
#ifndef SWELL_ERR_H
#define SWELL_ERR_H

#define SWELL_ERR_LIST(X) \
    X(SWELL_OK,          "success") \
    X(SWELL_E_NOMEM,     "out of memory") \
    X(SWELL_E_ARG,       "invalid argument") \
    X(SWELL_E_IO,        "input/output error") \
    X(SWELL_E_FORMAT,    "malformed file") \
    X(SWELL_E_VERSION,   "unsupported file version") \
    X(SWELL_E_CHECKSUM,  "checksum mismatch") \
    X(SWELL_E_BUDGET,    "memory budget exceeded") \
    X(SWELL_E_FFT,       "FFT planning failed") \
    X(SWELL_E_EGL,       "EGL error") \
    X(SWELL_E_GL,        "OpenGL ES error") \
    X(SWELL_E_SHADER,    "shader compile/link error") \
    X(SWELL_E_TIER,      "device tier not supported") \
    X(SWELL_E_DRM,       "DRM/KMS error") \
    X(SWELL_E_UNSUPPORTED, "not supported")

enum swell_err_code {
#define SWELL_X_ENUM(name, text) name,
    SWELL_ERR_LIST(SWELL_X_ENUM)
#undef SWELL_X_ENUM
    SWELL_ERR_COUNT
};

struct swell_err {
    int code;          /* SWELL_OK or a SWELL_E_* value */
    char msg[1024];    /* the specific message; "" when code == SWELL_OK */
};

/* Short generic text for a code ("checksum mismatch"). Never NULL. */
const char *swell_err_name(int code);

/* Fill `e` (may be NULL) with code and a printf-formatted message; returns code,
 * so failures read `return swell_fail(e, SWELL_E_IO, "cannot open %s: %s", path, strerror(errno));` */
int swell_fail(struct swell_err *e, int code, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

/* Prepend context to an existing message: "loading tables/x.ktx: <old msg>". Returns e->code. */
int swell_err_context(struct swell_err *e, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));

void swell_err_clear(struct swell_err *e);

#endif
