#include "core/seastate.h"

#include <math.h>
#include <string.h>

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

static int is_pow2(int v) { return v > 0 && (v & (v - 1)) == 0; }

/* One range check: NaN fails every comparison, so test for being inside. */
static int check_range(const char *field, const char *unit, double v, double lo, double hi,
                       struct swell_err *err)
{
    if (v >= lo && v <= hi)
        return 0;
    return swell_fail(err, SWELL_E_ARG, "%s = %g %s is out of range: allowed [%g, %g] %s",
                      field, v, unit, lo, hi, unit);
}

int seastate_validate(const struct seastate *s, struct swell_err *err)
{
    int r;
    if ((r = check_range("wind_speed_mps", "m/s", s->wind_speed_mps, 0.5, 40.0, err))) return r;
    if ((r = check_range("wind_dir_deg", "deg", s->wind_dir_deg, -360.0, 360.0, err))) return r;
    if ((r = check_range("fetch_km", "km", s->fetch_km, 0.1, 10000.0, err))) return r;
    if (s->depth_m != 0.0f &&
        (r = check_range("depth_m", "m (0 = deep water)", s->depth_m, 1.0, 10000.0, err)))
        return r;
    if (s->spectrum <= SPECTRUM_DEFAULT || s->spectrum >= SPECTRUM_COUNT)
        return swell_fail(err, SWELL_E_ARG, "spectrum = %d is not one of pm, jonswap, tma",
                          s->spectrum);
    if ((r = check_range("spread", "", s->spread, 1.0, 100.0, err))) return r;
    if ((r = check_range("patterns", "", s->patterns, 1, 4, err))) return r;
    if ((r = check_range("loop_period_s", "s", s->loop_period_s, 2.0, 600.0, err))) return r;
    /* F frames carry harmonics up to F/2 - 1 of a pattern's loop (bake.c pattern_period, Hu
     * 2006 §2.1): F = 2 or 3 carries none and would bake a flat sea, so F starts at 4. */
    if (s->frames != 0 && (r = check_range("frames", "", s->frames, 4, 256, err))) return r;
    if (s->size_fs != 0 && (!is_pow2(s->size_fs) || s->size_fs < 16 || s->size_fs > 1024))
        return swell_fail(err, SWELL_E_ARG,
                          "size_fs = %d must be a power of two in [16, 1024] (or 0 = by budget)",
                          s->size_fs);
    if (s->size_geo != 0 && (!is_pow2(s->size_geo) || s->size_geo < 8 || s->size_geo > 512))
        return swell_fail(err, SWELL_E_ARG,
                          "size_geo = %d must be a power of two in [8, 512] (or 0 = by budget)",
                          s->size_geo);
    if ((r = check_range("choppiness", "", s->choppiness, 0.0, 2.0, err))) return r;
    if (s->whitecap_model <= WHITECAP_DEFAULT || s->whitecap_model >= WHITECAP_COUNT)
        return swell_fail(err, SWELL_E_ARG, "whitecap_model = %d is not one of mom80, wu88",
                          s->whitecap_model);
    if ((r = check_range("foam_half_life_s", "s", s->foam_half_life_s, 0.05, 60.0, err)))
        return r;
    if (s->budget_bytes < (1u << 20) || s->budget_bytes > (1ull << 30))
        return swell_fail(err, SWELL_E_ARG,
                          "budget_bytes = %llu is out of range: allowed [1 MiB, 1 GiB]",
                          (unsigned long long)s->budget_bytes);
    return 0;
}

static int name_lookup(const char *const *names, int count, const char *name)
{
    if (!name)
        return -1;
    for (int i = 1; i < count; i++)
        if (strcmp(names[i], name) == 0)
            return i;
    return -1;
}

const char *spectrum_name(int kind)
{
    return kind >= 0 && kind < SPECTRUM_COUNT ? spectrum_names[kind] : "?";
}

int spectrum_from_name(const char *name)
{
    return name_lookup(spectrum_names, SPECTRUM_COUNT, name);
}

const char *whitecap_model_name(int model)
{
    return model >= 0 && model < WHITECAP_COUNT ? whitecap_names[model] : "?";
}

int whitecap_model_from_name(const char *name)
{
    return name_lookup(whitecap_names, WHITECAP_COUNT, name);
}
