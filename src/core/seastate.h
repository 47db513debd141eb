/* seastate.h - the bake's input: a sea state, with units, defaults and validation.
 *
 * Descriptor rule (STYLE.md 4): every field 0 means "default"; seastate_resolve() fills the
 * defaults (documented beside each field) and seastate_validate() returns the first specific
 * error. Angles are degrees in this struct (user facing), radians inside the numerics.
 * World frame: x east, y north, z up (right-handed), metres, seconds.
 */
#ifndef SWELL_SEASTATE_H
#define SWELL_SEASTATE_H

#include <stdint.h>
#include "core/err.h"

enum spectrum_kind {
    SPECTRUM_DEFAULT = 0,   /* = SPECTRUM_JONSWAP */
    SPECTRUM_PM,            /* Pierson-Moskowitz, fully developed sea (fetch ignored) */
    SPECTRUM_JONSWAP,       /* fetch-limited (Hasselmann et al. 1973) */
    SPECTRUM_TMA,           /* JONSWAP x Kitaigorodskii depth factor (finite depth) */
    SPECTRUM_COUNT
};

enum whitecap_model {
    WHITECAP_DEFAULT = 0,   /* = WHITECAP_MOM80 */
    WHITECAP_MOM80,         /* Monahan & O'Muircheartaigh 1980: W = 3.84e-6 U^3.41 */
    WHITECAP_WU88,          /* Wu 1988: W = 2.0e-6 U^3.75 */
    WHITECAP_COUNT
};

struct seastate {
    float wind_speed_mps;   /* U10, wind speed 10 m above the sea, m/s. default 10. range (0, 40] */
    float wind_dir_deg;     /* direction the wind blows towards, degrees CCW from +x (east). default 0 */
    float fetch_km;         /* fetch, km (JONSWAP/TMA). default 100. range (0, 10000] */
    float depth_m;          /* water depth, m (TMA; dispersion uses it for every spectrum).
                               default 0 = deep water. range 0 or [1, 10000] */
    int   spectrum;         /* enum spectrum_kind. default JONSWAP */
    float spread;           /* directional spreading exponent s of cos^(2s)((theta-theta_w)/2).
                               default 2 (Cox-Munk slope ratio). range [1, 100] */
    uint32_t seed;          /* random seed for the Gaussian amplitudes. default 0 means 1 */
    int   patterns;         /* n wave patterns (Dupuy 2012 §2). default 4. range [1, 4] */
    float loop_period_s;    /* T: every pattern repeats exactly after T seconds (Hu 2006 §2.1).
                               default 16. range [2, 600] */
    int   frames;           /* F frames per loop. default 0 = chosen by the budget. range [4, 256] */
    int   size_fs;          /* N of the per-pattern slope/whitecap tables (power of two).
                               default 0 = chosen by the budget. range [16, 1024] */
    int   size_geo;         /* N of the per-pattern displacement tables (power of two).
                               default 0 = chosen by the budget. range [8, 512] */
    float choppiness;       /* lambda of the choppy wave model (Tessendorf 2001; Dupuy eq. 1).
                               default 1. range [0, 2] */
    int   whitecap_model;   /* enum whitecap_model. default MOM80 */
    float foam_half_life_s; /* half-life of foam (Tessendorf 2023 eq. 7-8): through eq. 13 it
                               sets how much of the model's W is fresh breaking, so how long
                               foam outlasts a break (bake.c). default 3. range (0, 60] */
    uint64_t budget_bytes;  /* memory budget for everything the renderer uploads, bytes.
                               default 0 = 16 MiB ("default" preset). range [1 MiB, 1 GiB] */
};

#define SWELL_BUDGET_TINY    (4u * 1024u * 1024u)
#define SWELL_BUDGET_DEFAULT (16u * 1024u * 1024u)

/* Replace every 0 field by its default. Does not validate. */
void seastate_resolve(struct seastate *s);

/* First problem with a resolved sea state, or 0. Names the field, its value, the range. */
int seastate_validate(const struct seastate *s, struct swell_err *err);

const char *spectrum_name(int kind);         /* "jonswap"; "?" if out of range */
int spectrum_from_name(const char *name);    /* SPECTRUM_* or -1 */
const char *whitecap_model_name(int model);  /* "mom80" */
int whitecap_model_from_name(const char *name);

#endif
