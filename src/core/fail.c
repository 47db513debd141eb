/* fail.c - filling a struct swell_err (err.h); apart from err.c's public names so a program
 * can link it beside the public libswell.a (swell-bake: core/args.c, core/fsutil.c need it). */
#include "core/err.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

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
