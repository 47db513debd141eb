/* err.c - the public error names and version (swell.h); filling an error is fail.c's. */
#include "core/err.h"

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
