/* tables.h - the baked tables in memory: what the bake makes, the files hold and the renderer
 * uploads. Data flows one way: bake -> tables -> (files) -> upload.
 *
 * Each table is a 2D texture image set: `layers` array elements (the F loop frames for
 * per-pattern tables, 1 otherwise), each with a full mip chain when `levels` > 1.
 * Storage order is KTX 1.1's: for each mip level, for each layer, rows bottom-up as GL
 * uploads them (row 0 first), tightly packed (RGBA8 rows of power-of-two width are 4-aligned).
 *
 * Quantisation (gles2-min): FORMAT_RGBA8 texel value v in [0,255] means
 *     value[c] = bias[c] + scale[c] * (v / 255.0)
 * FORMAT_RGBA16F stores the value itself (scale 1, bias 0).
 */
#ifndef SWELL_TABLES_H
#define SWELL_TABLES_H

#include <stddef.h>
#include <stdint.h>
#include "core/err.h"
#include "core/seastate.h"
#include "tables/foam_bias.h"

#define SWELL_MAX_TABLES   32
#define TABLES_FRESNEL_SIZE 64  /* side of both Fresnel tables (one layer, one level) */

enum table_kind {
    TABLE_DISP = 0,      /* per pattern: (Dx, Dy, Dz, unused) choppy displacement, m. No mips */
    TABLE_SLOPE,         /* per pattern: (sx, sy, sx^2, sy^2) slopes and their squares; mipmapped,
                            so a mip texel holds the footprint's first and second moments
                            (Bruneton 2010 §4.1: resolved slope variance = <s^2> - <s>^2) */
    TABLE_WHITECAP,      /* per pattern: (m_i, m_i^2, 0, k_i) - the foam memory of Dupuy 2012's
                            k_i (eq. 7; whitecap_memory_loop) and its second moment (eq. 8),
                            nothing, k_i itself; mipmapped */
    TABLE_FRESNEL,       /* Hu 2006 §5.1: 2D Fresnel texture indexed by the local view vector;
                            RGB = view vector (for the sun term), A = exact Fresnel (eq. 2) */
    TABLE_FRESNEL_EFF,   /* Bruneton 2010 eq. 24: effective Fresnel F(cos theta_v, sigma_v);
                            R = eq. 24 integrated, G = eq. 26 fit */
    TABLE_KIND_COUNT
};

enum table_format {
    FORMAT_RGBA8 = 0,    /* GL_RGBA / GL_UNSIGNED_BYTE: every tier */
    FORMAT_RGBA16F,      /* GL_RGBA / GL_HALF_FLOAT(_OES): tiers with half-float textures */
    FORMAT_COUNT
};

struct swell_table {
    char name[32];          /* file stem, e.g. "slope_p0"; unique in a set */
    int kind;               /* enum table_kind */
    int pattern;            /* pattern index for per-pattern kinds, -1 otherwise */
    int format;             /* enum table_format */
    int width, height;      /* level 0 size, powers of two */
    int layers;             /* array elements (frames); >= 1 */
    int levels;             /* mip levels; 1 = no mips; full chain = log2(max(w,h)) + 1 */
    float scale[4], bias[4];/* dequantisation, see above */
    uint32_t set_id;        /* tables_set_id of the sea state baked with; set by a save, read
                               from the file (tables_io.h), 0 for a set only in memory */
    uint8_t *data;          /* owned; table_bytes() bytes */
};

/* What the renderer needs besides the images: the bake's parameters and statistics. */
struct swell_pattern_info {
    float size_m;           /* L_i: patch side, m */
    float k_min, k_max;     /* wavenumber band this pattern samples, rad/m (Dupuy §2: no band twice) */
    float lambda;           /* choppiness lambda_i (Dupuy eq. 1) */
    float period_s;         /* T_i = T / m_i (m_i a whole number): this pattern's loop period,
                               short enough that F frames sample its fastest wave (Hu §2.1);
                               every pattern still repeats after the set's loop period T */
    float var_h;            /* height variance kept in the tables, m^2 */
    float mss_x, mss_y;     /* slope variance kept in the tables (resolved by the tables) */
};

struct swell_tables {
    struct seastate state;  /* resolved sea state that produced these tables */
    int patterns;           /* n */
    int frames;             /* F */
    float loop_period_s;    /* T */
    struct swell_pattern_info pattern[SWELL_MAX_PATTERNS];
    float mss_unresolved_x; /* slope variance of components not in the tables (too fast for F
                               frames or beyond the last band): the BRDF's part (Bruneton eq. 4) */
    float mss_unresolved_y;
    float hs_m;             /* significant wave height 4 sqrt(var_h total), m */
    float whitecap_epsilon; /* Dupuy 2012 eq. 3 threshold on the patterns' summed k (eq. 7): the
                               instantaneous breaking {sum k_i < epsilon} covers eq. 13's
                               <Theta> of the model's W (Tessendorf 2023 algorithm 1 on the CDF
                               of the combined field; whitecap.h) */
    float whitecap_breaking_fraction;  /* that <Theta> */
    float foam_recovery_per_s;  /* rate r of the foam memory m' = min(k, m + r dt), k per s,
                                   solved so that {sum m_i < epsilon} covers W */
    float whitecap_fraction_model;     /* W from the wind-speed model */
    float whitecap_fraction_measured;  /* the foam's covered fraction on the baked tables (eq. 9
                                          with coverage for opacity): P(sum m_i < epsilon) */
    int count;
    struct swell_table table[SWELL_MAX_TABLES];
    /* not in the files: eq. 6's gains by footprint (foam_bias.h), filled by the loader and the
     * bake (has_foam_bias 1); a set built otherwise has none, and the renderer finds its own */
    struct foam_bias foam_bias;
    int has_foam_bias;
};

size_t table_bytes(const struct swell_table *t);           /* all levels and layers */
size_t table_level_bytes(const struct swell_table *t, int level);  /* one layer of one level */
/* Byte offset of (level, layer) in t->data. */
size_t table_offset(const struct swell_table *t, int level, int layer);
int table_level_width(const struct swell_table *t, int level);   /* max(1, width >> level) */
int table_level_height(const struct swell_table *t, int level);
/* The mean over level l's texels of the first loop frame of the within-texel variance
 * <m^2> - <m>^2 of channel cm, its second moment in channel cs (floored at 0 per texel); 0
 * where t has no level l or is not RGBA8. */
float table_level_within_var(const struct swell_table *t, int l, int cm, int cs);

/* 1 when name is 1-31 characters of [a-z0-9_] (table names become file names: no paths). */
int table_name_valid(const char *name);

/* Allocate t->data for the geometry already set in t (zeroed). */
int table_alloc(struct swell_table *t, struct swell_err *err);

/* The tables a set baked from the resolved state s holds, in the bake's order: per pattern
 * slope_pN and whitecap_pN (size_fs square, frames layers, full mip chain) and disp_pN
 * (size_geo square, frames layers, one level), then fresnel and fresnel_eff. Fills name, kind,
 * pattern, format (RGBA8), width, height, layers and levels of out[0..n) (no data) and returns
 * n; the bake builds exactly these and a loaded manifest must list exactly these. */
int tables_layout(const struct seastate *s, struct swell_table out[SWELL_MAX_TABLES]);

/* Find a table by kind and pattern (-1 for global tables); NULL when absent. */
const struct swell_table *tables_find(const struct swell_tables *s, int kind, int pattern);

/* Loop period of pattern i's frames: pattern[i].period_s, or the set's T when that is 0. */
float tables_pattern_period(const struct swell_tables *s, int pattern);

/* Total bytes of all tables (what the renderer streams/uploads from). */
size_t tables_bytes(const struct swell_tables *s);

/* Free every table's data; accepts a zeroed or half-built set. */
void tables_destroy(struct swell_tables *s);

const char *table_kind_name(int kind);     /* "slope" */
const char *table_format_name(int format); /* "rgba8" */

#endif
