#include "core/parse.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/seastate.h"

/* strtod over exactly [text, end) with no junk; returns 0 when it is a finite number. */
static int scan_double(const char *text, const char **end, double *v)
{
    if (!text || !*text || isspace((unsigned char)*text))
        return -1;
    char *e = NULL;
    errno = 0;
    *v = strtod(text, &e);
    if (e == text || errno == ERANGE || !isfinite(*v))
        return -1;
    *end = e;
    return 0;
}

int parse_double(const char *opt, const char *text, double lo, double hi, const char *unit,
                 double *out, struct swell_err *err)
{
    const char *end;
    double v;
    /* A unitless option (a spreading exponent) reads "(allowed 1 to 100)", not "(, allowed". */
    const char *sep = unit && *unit ? ", " : "";
    unit = unit ? unit : "";
    if (scan_double(text, &end, &v) || *end)
        return swell_fail(err, SWELL_E_ARG, "%s: '%s' is not a number (%s%sallowed %g to %g)",
                          opt, text ? text : "", unit, sep, lo, hi);
    if (!(v >= lo && v <= hi))
        return swell_fail(err, SWELL_E_ARG, "%s: %s is out of range (%s%sallowed %g to %g)", opt,
                          text, unit, sep, lo, hi);
    *out = v;
    return 0;
}

int parse_float(const char *opt, const char *text, double lo, double hi, const char *unit,
                float *out, struct swell_err *err)
{
    double v;
    int r = parse_double(opt, text, lo, hi, unit, &v, err);
    if (!r)
        *out = (float)v;
    return r;
}

int parse_int(const char *opt, const char *text, long lo, long hi, int *out, struct swell_err *err)
{
    char *e = NULL;
    if (!text || !*text || isspace((unsigned char)*text))
        return swell_fail(err, SWELL_E_ARG, "%s: '%s' is not a whole number (allowed %ld to %ld)",
                          opt, text ? text : "", lo, hi);
    errno = 0;
    long v = strtol(text, &e, 10);
    if (*e || errno == ERANGE)
        return swell_fail(err, SWELL_E_ARG, "%s: '%s' is not a whole number (allowed %ld to %ld)",
                          opt, text, lo, hi);
    if (v < lo || v > hi)
        return swell_fail(err, SWELL_E_ARG, "%s: %s is out of range (allowed %ld to %ld)", opt,
                          text, lo, hi);
    *out = (int)v;
    return 0;
}

int parse_budget(const char *opt, const char *text, uint64_t *out, struct swell_err *err)
{
    if (text && strcmp(text, "tiny") == 0) {
        *out = SWELL_BUDGET_TINY;
        return 0;
    }
    if (text && strcmp(text, "default") == 0) {
        *out = SWELL_BUDGET_DEFAULT;
        return 0;
    }
    const char *end;
    double v;
    if (scan_double(text, &end, &v) || v < 0)
        goto bad;
    double mul = 1.0;
    if (*end) {
        switch (*end) {
        case 'K': case 'k': mul = 1024.0; break;
        case 'M': case 'm': mul = 1024.0 * 1024.0; break;
        case 'G': case 'g': mul = 1024.0 * 1024.0 * 1024.0; break;
        default: goto bad;
        }
        end++;
        if (*end == 'i' && end[1] == 'B')
            end += 2;
        else if (*end == 'B')
            end++;
        if (*end)
            goto bad;
    }
    v *= mul;
    if (v < 1024.0 * 1024.0 || v > 1024.0 * 1024.0 * 1024.0)
        return swell_fail(err, SWELL_E_ARG,
                          "%s: %s is out of range (allowed 1M to 1G bytes, or tiny, default)", opt,
                          text);
    *out = (uint64_t)v;
    return 0;
bad:
    return swell_fail(err, SWELL_E_ARG,
                      "%s: '%s' is not a budget (tiny, default, or bytes such as 8M, 16777216)",
                      opt, text ? text : "");
}

int parse_wxh(const char *opt, const char *text, int lo, int hi, int *w, int *h,
              struct swell_err *err)
{
    char *e1 = NULL, *e2 = NULL;
    long a, b;
    if (!text || !isdigit((unsigned char)text[0]))
        goto bad;
    errno = 0;
    a = strtol(text, &e1, 10);
    if (*e1 != 'x' || !isdigit((unsigned char)e1[1]))
        goto bad;
    b = strtol(e1 + 1, &e2, 10);
    if (*e2 || errno == ERANGE)
        goto bad;
    if (a < lo || a > hi || b < lo || b > hi)
        return swell_fail(err, SWELL_E_ARG, "%s: %s is out of range (each side %d to %d)", opt,
                          text, lo, hi);
    *w = (int)a;
    *h = (int)b;
    return 0;
bad:
    return swell_fail(err, SWELL_E_ARG, "%s: '%s' is not WxH (e.g. 1280x720)", opt,
                      text ? text : "");
}

int parse_doubles(const char *opt, const char *text, int n, double lo, double hi, double *out,
                  struct swell_err *err)
{
    const char *p = text;
    for (int i = 0; i < n; i++) {
        const char *end;
        double v;
        if (scan_double(p, &end, &v) || (i + 1 < n ? *end != ',' : *end != '\0'))
            return swell_fail(err, SWELL_E_ARG, "%s: '%s' is not %d comma-separated numbers",
                              opt, text ? text : "", n);
        if (!(v >= lo && v <= hi))
            return swell_fail(err, SWELL_E_ARG, "%s: value %g in '%s' is out of range (%g to %g)",
                              opt, v, text, lo, hi);
        out[i] = v;
        p = end + 1;
    }
    return 0;
}

int parse_has_token(const char *list, const char *name)
{
    size_t n = strlen(name);
    const char *p = list;
    while (p && *p) {
        while (*p == ' ')
            p++;
        const char *end = strchr(p, ' ');
        size_t len = end ? (size_t)(end - p) : strlen(p);
        if (len == n && memcmp(p, name, n) == 0)
            return 1;
        p += len;
    }
    return 0;
}

int parse_name(const char *const *names, int first, int count, const char *name)
{
    for (int i = first; name && i < count; i++)
        if (strcmp(names[i], name) == 0)
            return i;
    return -1;
}

const char *name_of(const char *const *names, int count, int value)
{
    return value >= 0 && value < count ? names[value] : "?";
}
