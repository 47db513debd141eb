#include "core/seastate.h"

#include <math.h>
#include <string.h>
#include "core/parse.h"

static const char *const spectrum_names[SPECTRUM_COUNT] = {
    [SPECTRUM_DEFAULT] = "default", [SPECTRUM_PM] = "pm",
    [SPECTRUM_JONSWAP] = "jonswap", [SPECTRUM_TMA] = "tma",
};

static const char *const whitecap_names[WHITECAP_COUNT] = {
    [WHITECAP_DEFAULT] = "default", [WHITECAP_MOM80] = "mom80", [WHITECAP_WU88] = "wu88",
};

void seastate_resolve(struct seastate *s)
{
    if (s->wind_speed_mps == 0.0f) s->wind_speed_mps = 10.0f;
    /* wind_dir_deg: 0 is itself the default (towards +x) */
    if (s->fetch_km == 0.0f) s->fetch_km = 100.0f;
    /* depth_m: 0 is itself the default (deep water) */
    if (s->spectrum == SPECTRUM_DEFAULT) s->spectrum = SPECTRUM_JONSWAP;
    /* s = 2 gives mss_x / mss_y = 1.4, Cox & Munk's up/cross-wind ratio: the slope statistics
     * drive the BRDF and whitecaps (a frequency-dependent s would suit long waves better) */
    if (s->spread == 0.0f) s->spread = 2.0f;
    if (s->seed == 0) s->seed = 1;
    if (s->patterns == 0) s->patterns = 4;
    if (s->loop_period_s == 0.0f) s->loop_period_s = 16.0f;
    /* frames, size_fs, size_geo: 0 stays "chosen by the budget" until the bake resolves it */
    if (s->choppiness == 0.0f) s->choppiness = 1.0f;
    if (s->whitecap_model == WHITECAP_DEFAULT) s->whitecap_model = WHITECAP_MOM80;
    if (s->foam_half_life_s == 0.0f) s->foam_half_life_s = 3.0f;
    if (s->budget_bytes == 0) s->budget_bytes = SWELL_BUDGET_DEFAULT;
}

#define F(key, opt, arg, type, lo, hi, unit, flags, zero, help, dflt) \
    { #key, opt, arg, type, offsetof(struct seastate, key), lo, hi, unit, flags, zero, help, dflt }
const struct seastate_field seastate_fields[] = {
    F(wind_speed_mps, "--wind", "U", SS_FLOAT, SWELL_WIND_SPEED_MIN_MPS,
      SWELL_WIND_SPEED_MAX_MPS, "m/s", 0, NULL, "wind speed U10 at 10 m, m/s", "10"),
    F(wind_dir_deg, "--wind-dir", "DEG", SS_FLOAT, -360, 360, "deg", 0, NULL,
      "direction the wind blows towards, deg CCW from east", "0"),
    F(fetch_km, "--fetch", "KM", SS_FLOAT, 0.1, 10000, "km", 0, NULL,
      "fetch, km (jonswap, tma)", "100"),
    F(depth_m, "--depth", "M", SS_FLOAT, 1, 10000, "m", SS_ZERO_OK | SS_OPTION_ZERO,
      "deep water", "water depth, m; 0 = deep water", "0"),
    F(spectrum, "--spectrum", "NAME", SS_SPECTRUM, 0, 0, "", 0, NULL,
      "pm | jonswap | tma", "jonswap"),
    F(spread, "--spread", "S", SS_FLOAT, 1, 100, "", 0, NULL,
      "directional spreading exponent of cos^2s", "2"),
    /* any seed is valid; the option takes 1..2^31 - 1 */
    F(seed, "--seed", "N", SS_U32, 1, 2147483647, "", 0, NULL, "random seed", "1"),
    F(patterns, "--patterns", "N", SS_INT, 1, SWELL_MAX_PATTERNS, "", SS_TABLES, NULL,
      "wave patterns of different periods (Dupuy 2012 §2)", "4"),
    F(loop_period_s, "--period", "S", SS_FLOAT, 2, 600, "s", SS_TABLES, NULL,
      "loop period T: every table repeats after T seconds", "16"),
    /* F frames carry harmonics up to F/2 - 1 of a pattern's loop (bake.c pattern_period, Hu
     * 2006 §2.1): F = 2 or 3 carries none and would bake a flat sea, so F starts at 4. */
    F(frames, "--frames", "F", SS_INT, 4, 256, "", SS_ZERO_OK | SS_TABLES, "by budget",
      "frames per loop", "by budget"),
    F(size_fs, "--size", "N", SS_INT, 16, 1024, "", SS_ZERO_OK | SS_POW2 | SS_TABLES,
      "by budget", "slope/whitecap table size, power of two", "by budget"),
    F(size_geo, "--size-geo", "N", SS_INT, 8, 512, "", SS_ZERO_OK | SS_POW2 | SS_TABLES,
      "by budget", "displacement table size, power of two", "by budget"),
    F(choppiness, "--choppiness", "L", SS_FLOAT, 0, 2, "", 0, NULL,
      "choppy-wave lambda (Dupuy 2012 eq. 1)", "1"),
    F(whitecap_model, "--whitecap-model", "NAME", SS_WHITECAP, 0, 0, "", 0, NULL,
      "mom80 (3.84e-6 U^3.41) | wu88 (2.0e-6 U^3.75)", "mom80"),
    F(foam_half_life_s, "--foam-half-life", "S", SS_FLOAT, 0.05, 60, "s", 0, NULL,
      "foam half-life, s (Tessendorf eq. 7-8, 13)", "3"),
    F(budget_bytes, "--budget", "B", SS_U64, 1 << 20, 1 << 30, "bytes", SS_TABLES, NULL,
      "GPU memory budget: tiny (4 MiB) | default (16 MiB) | bytes", "16M"),
};
#undef F
const int seastate_field_count = (int)(sizeof seastate_fields / sizeof seastate_fields[0]);

static int is_pow2(long v) { return v > 0 && (v & (v - 1)) == 0; }

static double field_value(const struct seastate *s, const struct seastate_field *f)
{
    const char *p = (const char *)s + f->offset;
    float fl;
    int i;
    uint32_t u;
    uint64_t u64;
    switch (f->type) {
    case SS_FLOAT: memcpy(&fl, p, sizeof fl); return fl;
    case SS_U32: memcpy(&u, p, sizeof u); return u;
    case SS_U64: memcpy(&u64, p, sizeof u64); return (double)u64;
    default: memcpy(&i, p, sizeof i); return i;
    }
}

static const char *enum_list(int type)
{
    return type == SS_SPECTRUM ? "pm, jonswap, tma" : "mom80, wu88";
}

/* The first problem with one field, naming it, its value and what is allowed. NaN fails every
 * comparison, so the test is for being inside. */
static int check_field(const struct seastate *s, const struct seastate_field *f,
                       struct swell_err *err)
{
    double v = field_value(s, f);
    if (f->type == SS_U32)
        return 0;
    if (f->type == SS_SPECTRUM || f->type == SS_WHITECAP) {
        int count = f->type == SS_SPECTRUM ? SPECTRUM_COUNT : WHITECAP_COUNT;
        if (v > 0 && v < count)
            return 0;
        return swell_fail(err, SWELL_E_ARG, "%s = %d is not one of %s", f->key, (int)v,
                          enum_list(f->type));
    }
    if ((f->flags & SS_ZERO_OK) && v == 0)
        return 0;
    if (f->type == SS_U64) {
        if (v >= f->lo && v <= f->hi)
            return 0;
        return swell_fail(err, SWELL_E_ARG, "%s = %.0f is out of range: allowed [%.0f MiB, "
                          "%.0f GiB]", f->key, v, f->lo / (1 << 20), f->hi / (1 << 30));
    }
    if (f->flags & SS_POW2) {
        if (v >= f->lo && v <= f->hi && is_pow2((long)v))
            return 0;
        return swell_fail(err, SWELL_E_ARG, "%s = %d must be a power of two in [%g, %g] (or "
                          "0 = %s)", f->key, (int)v, f->lo, f->hi, f->zero_means);
    }
    if (v >= f->lo && v <= f->hi)
        return 0;
    if (f->flags & SS_ZERO_OK)
        return swell_fail(err, SWELL_E_ARG, "%s = %g %s is out of range: allowed [%g, %g] %s, "
                          "or 0 = %s", f->key, v, f->unit, f->lo, f->hi, f->unit, f->zero_means);
    return swell_fail(err, SWELL_E_ARG, "%s = %g %s is out of range: allowed [%g, %g] %s",
                      f->key, v, f->unit, f->lo, f->hi, f->unit);
}

int seastate_validate(const struct seastate *s, struct swell_err *err)
{
    for (int i = 0; i < seastate_field_count; i++) {
        int r = check_field(s, &seastate_fields[i], err);
        if (r)
            return r;
    }
    return 0;
}

const struct seastate_field *seastate_option(const char *option)
{
    for (int i = 0; option && i < seastate_field_count; i++)
        if (strcmp(seastate_fields[i].option, option) == 0)
            return &seastate_fields[i];
    return NULL;
}

int seastate_set_option(struct seastate *s, const struct seastate_field *f, const char *text,
                        struct swell_err *err)
{
    const char *opt = f->option;
    char *p = (char *)s + f->offset;
    int r = 0;
    switch (f->type) {
    case SS_FLOAT: {
        float v;
        double lo = (f->flags & SS_OPTION_ZERO) ? 0.0 : f->lo;
        if ((r = parse_float(opt, text, lo, f->hi, f->unit, &v, err)))
            return r;
        if (v != 0.0f && v < f->lo)
            return swell_fail(err, SWELL_E_ARG, "%s: %s %s is too small (0 = %s, or %g..%g %s)",
                              opt, text, f->unit, f->zero_means, f->lo, f->hi, f->unit);
        memcpy(p, &v, sizeof v);
        return 0;
    }
    case SS_INT:
    case SS_U32: {
        int v;
        if ((r = parse_int(opt, text, (long)f->lo, (long)f->hi, &v, err)))
            return r;
        if ((f->flags & SS_POW2) && !is_pow2(v))
            return swell_fail(err, SWELL_E_ARG, "%s: %s is not a power of two (%s: %g, %g, ... "
                              "%g)", opt, text, f->key, f->lo, 2 * f->lo, f->hi);
        if (f->type == SS_U32) {
            uint32_t u = (uint32_t)v;
            memcpy(p, &u, sizeof u);
        } else {
            memcpy(p, &v, sizeof v);
        }
        return 0;
    }
    case SS_U64: {
        uint64_t v;
        if ((r = parse_budget(opt, text, &v, err)))
            return r;
        memcpy(p, &v, sizeof v);
        return 0;
    }
    default: {
        int v = f->type == SS_SPECTRUM ? spectrum_from_name(text) : whitecap_model_from_name(text);
        if (v < 0)
            return swell_fail(err, SWELL_E_ARG, "%s: '%s' is not one of %s", opt, text,
                              enum_list(f->type));
        memcpy(p, &v, sizeof v);
        return 0;
    }
    }
}

void seastate_usage(FILE *out, int tables)
{
    for (int i = 0; i < seastate_field_count; i++) {
        const struct seastate_field *f = &seastate_fields[i];
        if (!(f->flags & SS_TABLES) != !tables)
            continue;
        char head[40], range[48] = "";
        snprintf(head, sizeof head, "%s %s", f->option, f->arg);
        if (f->type == SS_FLOAT || f->type == SS_INT)
            snprintf(range, sizeof range, "%s%g..%g", (f->flags & SS_OPTION_ZERO) ? "0 or " : "",
                     f->lo, f->hi);
        char dflt[16], line[256];
        snprintf(dflt, sizeof dflt, "[%s]", f->dflt);
        int over = (int)strlen(head) - 17;    /* a long head pushes the help, not the rest */
        snprintf(line, sizeof line, "  %-17s %-*s %-11s %s", head, 50 - (over > 0 ? over : 0),
                 f->help, dflt, range);
        size_t n = strlen(line);
        while (n > 0 && line[n - 1] == ' ')
            line[--n] = '\0';
        fprintf(out, "%s\n", line);
    }
}

const char *spectrum_name(int kind)
{
    return name_of(spectrum_names, SPECTRUM_COUNT, kind);
}

int spectrum_from_name(const char *name)
{
    return parse_name(spectrum_names, 1, SPECTRUM_COUNT, name);
}

const char *whitecap_model_name(int model)
{
    return name_of(whitecap_names, WHITECAP_COUNT, model);
}

int whitecap_model_from_name(const char *name)
{
    return parse_name(whitecap_names, 1, WHITECAP_COUNT, name);
}
