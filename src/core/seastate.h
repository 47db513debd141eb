/* seastate.h - the bake's input: a sea state, with units, defaults and validation.
 *
 * Descriptor rule (STYLE.md 4): every field 0 means "default"; seastate_resolve() fills the
 * defaults (documented beside each field) and seastate_validate() returns the first specific
 * error. Each field's range, unit and option are in seastate_fields (below), and only there. Angles are degrees in this struct (user facing), radians inside the numerics.
 * World frame: x east, y north, z up (right-handed), metres, seconds.
 */
#ifndef SWELL_SEASTATE_H
#define SWELL_SEASTATE_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include "core/err.h"

/* Wave patterns of incommensurate sizes, at most (Dupuy 2012 §2: n = 4). */
#define SWELL_MAX_PATTERNS 4

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
    float wind_speed_mps;   /* U10, wind speed 10 m above the sea, m/s. default 10 */
    float wind_dir_deg;     /* direction the wind blows towards, degrees CCW from +x (east). default 0 */
    float fetch_km;         /* fetch, km (JONSWAP/TMA). default 100 */
    float depth_m;          /* water depth, m (TMA; dispersion uses it for every spectrum).
                               default 0 = deep water */
    int   spectrum;         /* enum spectrum_kind. default JONSWAP */
    float spread;           /* directional spreading exponent s of cos^(2s)((theta-theta_w)/2).
                               default 2 (Cox-Munk slope ratio) */
    uint32_t seed;          /* random seed for the Gaussian amplitudes. default 0 means 1 */
    int   patterns;         /* n wave patterns (Dupuy 2012 §2). default 4 */
    float loop_period_s;    /* T: every pattern repeats exactly after T seconds (Hu 2006 §2.1).
                               default 16 */
    int   frames;           /* F frames per loop. default 0 = chosen by the budget */
    int   size_fs;          /* N of the per-pattern slope/whitecap tables (power of two).
                               default 0 = chosen by the budget */
    int   size_geo;         /* N of the per-pattern displacement tables (power of two).
                               default 0 = chosen by the budget */
    float choppiness;       /* lambda of the choppy wave model (Tessendorf 2001; Dupuy eq. 1).
                               default 1 */
    int   whitecap_model;   /* enum whitecap_model. default MOM80 */
    float foam_half_life_s; /* half-life of foam (Tessendorf 2023 eq. 7-8): through eq. 13 it
                               sets how much of the model's W is fresh breaking, so how long
                               foam outlasts a break (bake.c). default 3 */
    uint64_t budget_bytes;  /* memory budget for everything the renderer uploads, bytes.
                               default 0 = 16 MiB ("default" preset) */
};

#define SWELL_BUDGET_TINY    (4u * 1024u * 1024u)
#define SWELL_BUDGET_DEFAULT (16u * 1024u * 1024u)

/* Every field of struct seastate in declaration order, with all that is known of it: the key
 * presets and the table manifest use (the member's name), swell-bake's option, the unit and
 * range, the help line. seastate_validate, presets (preset.c) and both programs' options read
 * it: the ranges are written here alone. */
enum seastate_type { SS_FLOAT, SS_INT, SS_U32, SS_U64, SS_SPECTRUM, SS_WHITECAP };
enum {
    SS_ZERO_OK = 1,         /* 0 is valid besides the range (deep water; chosen by the budget) */
    SS_OPTION_ZERO = 2,     /* ...and the option takes 0 too (--depth 0) */
    SS_POW2 = 4,            /* a power of two */
    SS_TABLES = 8,          /* describes the tables more than the sea (--help's "Tables:") */
};
struct seastate_field {
    const char *key;        /* member and preset/manifest key: "wind_speed_mps" */
    const char *option;     /* swell-bake's option: "--wind" */
    const char *arg;        /* its argument in --help: "U" */
    int type;               /* enum seastate_type */
    size_t offset;          /* in struct seastate */
    double lo, hi;          /* range, in unit (for SS_U64 bytes) */
    const char *unit;       /* "m/s"; "" for none */
    int flags;
    const char *zero_means; /* SS_ZERO_OK: what 0 means, "deep water" */
    const char *help;       /* --help text */
    const char *dflt;       /* the default as --help shows it: "10" */
};
extern const struct seastate_field seastate_fields[];
extern const int seastate_field_count;

/* The field whose option is `option` ("--wind"), or NULL. */
const struct seastate_field *seastate_option(const char *option);
/* Parse an option's text into its field of *s: "--wind: 'abc' is not a number (m/s, allowed
 * 0.5 to 40)" and the like (core/parse.h). *s is unchanged on failure. */
int seastate_set_option(struct seastate *s, const struct seastate_field *f, const char *text,
                        struct swell_err *err);
/* One --help line per field, option, argument, help, default and range: the sea's fields, or
 * with tables != 0 those flagged SS_TABLES. */
void seastate_usage(FILE *out, int tables);

/* Replace every 0 field by its default. Does not validate. */
void seastate_resolve(struct seastate *s);

/* First problem with a resolved sea state, or 0. Names the field, its value, the range. */
int seastate_validate(const struct seastate *s, struct swell_err *err);

const char *spectrum_name(int kind);         /* "jonswap"; "?" if out of range */
int spectrum_from_name(const char *name);    /* SPECTRUM_* or -1 */
const char *whitecap_model_name(int model);  /* "mom80" */
int whitecap_model_from_name(const char *name);

#endif
