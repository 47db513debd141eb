#include "core/err.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

static const char *const err_names[SWELL_ERR_COUNT] = {
    [SWELL_OK] = "success", [SWELL_E_NOMEM] = "out of memory",
    [SWELL_E_ARG] = "invalid argument", [SWELL_E_IO] = "input/output error",
    [SWELL_E_FORMAT] = "malformed file", [SWELL_E_VERSION] = "unsupported file version",
    [SWELL_E_CHECKSUM] = "checksum mismatch", [SWELL_E_BUDGET] = "memory budget exceeded",
    [SWELL_E_FFT] = "FFT planning failed", [SWELL_E_EGL] = "EGL error",
    [SWELL_E_GL] = "OpenGL ES error", [SWELL_E_SHADER] = "shader compile/link error",
    [SWELL_E_TIER] = "device tier not supported", [SWELL_E_DRM] = "DRM/KMS error",
    [SWELL_E_UNSUPPORTED] = "not supported",
};

const char *swell_err_name(int code)
{
    if (code < 0 || code >= SWELL_ERR_COUNT || !err_names[code])
        return "unknown error";
    return err_names[code];
}

uint32_t swell_version(void)
{
    return SWELL_VERSION_NUMBER;
}

int swell_fail(struct swell_err *e, int code, const char *fmt, ...)
{
    if (!e)
        return code;
    e->code = code;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(e->msg, sizeof e->msg, fmt, ap);
    va_end(ap);
    return code;
}

int swell_err_context(struct swell_err *e, const char *fmt, ...)
{
    if (!e)
        return SWELL_E_ARG;
    char buf[sizeof e->msg];
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(buf, sizeof buf - 2, fmt, ap);
    va_end(ap);
    if (n < 0)
        n = 0;
    if ((size_t)n > sizeof buf - 3)
        n = (int)(sizeof buf - 3);
    buf[n++] = ':';
    buf[n++] = ' ';
    size_t room = sizeof buf - (size_t)n - 1;
    size_t old_len = strnlen(e->msg, sizeof e->msg);
    if (old_len > room)
        old_len = room;
    memcpy(buf + n, e->msg, old_len);
    buf[(size_t)n + old_len] = '\0';
    memcpy(e->msg, buf, sizeof buf);
    return e->code;
}

void swell_err_clear(struct swell_err *e)
{
    if (e) {
        e->code = SWELL_OK;
        e->msg[0] = '\0';
    }
}
