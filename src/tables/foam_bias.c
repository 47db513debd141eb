/* foam_bias.c - eq. 6's coverage over the sea by footprint against the bake's W (foam_bias.h). */
#include <math.h>
#include <stdint.h>
#include "tables/foam_bias.h"
#include "tables/quantize.h"
#include "tables/tables.h"

/* points per knot: a 64 x 64 stratified grid over the largest patch, one pseudo-random point in
 * each cell, each in a loop frame of its own (a binary-like field at small footprints: i.i.d.
 * points needed 8x as many for the same spread) */
#define STRATA 64

/* Dupuy eq. 6: the share of j ~ N(mu, var) below epsilon (bake/whitecap.c
 * whitecap_dupuy_coverage; a step where var is 0) */
static double eq6(double eps, double mu, double var)
{
    if (!(var > 0.0))
        return eps > mu ? 1.0 : 0.0;
    return 0.5 + 0.5 * erf((eps - mu) / sqrt(2.0 * var));
}

static uint32_t next(uint32_t *s)   /* xorshift32: fixed numbers on every run and machine */
{
    uint32_t x = *s;
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    return *s = x;
}

static double unit(uint32_t *s)
{
    return (next(s) >> 8) * (1.0 / 16777216.0);
}

/* Channels 0 and 1 (m, <m^2>) of whitecap table t at level l, layer f, bilinear (GL's
 * texel centres, repeating) at (u, v) in patch units. */
static void bilinear(const struct swell_table *t, int l, int f, double u, double v, double out[2])
{
    int w = table_level_width(t, l), h = table_level_height(t, l);
    const uint8_t *px = t->data + table_offset(t, l, f);
    double x = u * w - 0.5, y = v * h - 0.5;
    double fx = floor(x), fy = floor(y), ax = x - fx, ay = y - fy;
    int x0 = ((int)fx % w + w) % w, y0 = ((int)fy % h + h) % h;
    int x1 = (x0 + 1) % w, y1 = (y0 + 1) % h;
    const uint8_t *p00 = px + 4 * ((size_t)y0 * w + x0), *p10 = px + 4 * ((size_t)y0 * w + x1);
    const uint8_t *p01 = px + 4 * ((size_t)y1 * w + x0), *p11 = px + 4 * ((size_t)y1 * w + x1);
    for (int c = 0; c < 2; c++) {
        double a = quantize_decode(t, c, p00[c]) * (1.0 - ax) + quantize_decode(t, c, p10[c]) * ax;
        double b = quantize_decode(t, c, p01[c]) * (1.0 - ax) + quantize_decode(t, c, p11[c]) * ax;
        out[c] = a * (1.0 - ay) + b * ay;
    }
}

/* The whitecap tables of t that eq. 6 sums (RGBA8, every pattern that has one), the largest
 * patch side and the finest texel; the count. */
static int wc_tables(const struct swell_tables *t, const struct swell_table **wc, float *size,
                     float *l_max, float *texel_min)
{
    int n = 0;
    *l_max = 0.0f;
    *texel_min = INFINITY;
    for (int p = 0; p < t->patterns && n < SWELL_MAX_PATTERNS; p++) {
        const struct swell_table *w = tables_find(t, TABLE_WHITECAP, p);
        if (!w || w->format != FORMAT_RGBA8 || !w->data)
            continue;
        wc[n] = w;
        size[n] = t->pattern[p].size_m;
        *l_max = fmaxf(*l_max, size[n]);
        *texel_min = fminf(*texel_min, size[n] / (float)w->width);
        n++;
    }
    return n;
}

static double eq6_mean(const struct swell_tables *t, const struct swell_table *const *wc,
                       const float *size, int n, float l_max, float f, int strata)
{
    uint32_t s = 0x9e3779b9u;
    double c0[SWELL_MAX_PATTERNS];
    for (int k = 0; k < n; k++)
        c0[k] = table_level_within_var(wc[k], 0, 0, 1);
    double acc = 0.0;
    for (int i = 0; i < strata; i++)
        for (int j = 0; j < strata; j++) {
            double x = (i + unit(&s)) / strata * l_max, y = (j + unit(&s)) / strata * l_max;
            double mu = 0.0, var = 0.0;
            for (int k = 0; k < n; k++) {
                const struct swell_table *w = wc[k];
                int f_layer = (int)(next(&s) % (uint32_t)w->layers);
                /* the level a pixel of footprint 2^f m reads (GL's LOD), trilinear */
                double lod = f - log2(size[k] / (double)w->width);
                lod = fmin(fmax(lod, 0.0), (double)(w->levels - 1));
                int l0 = (int)floor(lod), l1 = l0 + 1 < w->levels ? l0 + 1 : l0;
                double a = lod - l0, m0[2], m1[2];
                bilinear(w, l0, f_layer, x / size[k], y / size[k], m0);
                bilinear(w, l1, f_layer, x / size[k], y / size[k], m1);
                double m = m0[0] + a * (m1[0] - m0[0]), m2 = m0[1] + a * (m1[1] - m0[1]);
                /* the renderer trusts the fetched variance by B, the rest is level 0's mean c0
                 * (render/lod.c wc_trust_terms: B about 0.22 at level 0, 0.78 at level 1, 0 a
                 * little into the magnified level 0, 1 from level 2 on) */
                double b = fmin(fmax(0.22 + 0.56 * (f - log2(size[k] / (double)w->width)), 0.0),
                                1.0);
                mu += m;
                var += b * fmax(m2 - m * m, 0.0) + (1.0 - b) * c0[k];   /* eq. 8, no cross terms */
            }
            acc += eq6(t->whitecap_epsilon, mu, var);
        }
    return acc / ((double)strata * strata);
}

double foam_bias_eq6_mean(const struct swell_tables *t, float f, int points)
{
    const struct swell_table *wc[SWELL_MAX_PATTERNS];
    float size[SWELL_MAX_PATTERNS], l_max, texel_min;
    int n = wc_tables(t, wc, size, &l_max, &texel_min);
    int strata = (int)sqrt((double)(points > 1 ? points : 1));
    return n ? eq6_mean(t, wc, size, n, l_max, f, strata) : 0.0;
}

void foam_bias_compute(const struct swell_tables *t, struct foam_bias *out)
{
    const struct swell_table *wc[SWELL_MAX_PATTERNS];
    float size[SWELL_MAX_PATTERNS], l_max, texel_min;
    int n = wc_tables(t, wc, size, &l_max, &texel_min);
    double target = t->whitecap_fraction_measured;
    out->f0 = n ? floorf(log2f(texel_min)) - 1.0f : 0.0f;
    /* below every texel less 0.4 of a level, every table reads level 0 at trust 0: the knots
     * there are alike */
    double below = -1.0;
    float flat = log2f(texel_min) - 0.4f;
    for (int j = 0; j < FOAM_BIAS_KNOTS; j++) {
        float f = out->f0 + (float)j;
        out->gain[j] = 1.0f;
        if (n == 0 || !(target > 0.0))
            continue;
        double m;
        if (f <= flat && below >= 0.0)
            m = below;
        else
            m = eq6_mean(t, wc, size, n, l_max, f, STRATA);
        if (f <= flat)
            below = m;
        /* within a factor 4 either way: beyond it the tables are not what eq. 6 can draw, and
         * a gain would only paint noise */
        out->gain[j] = m > 0.0 ? (float)fmin(fmax(target / m, 0.25), 4.0) : 1.0f;
    }
}

float foam_bias_at(const struct foam_bias *b, float f)
{
    float x = f - b->f0;
    if (!(x > 0.0f))
        return b->gain[0];
    if (x >= (float)(FOAM_BIAS_KNOTS - 1))
        return b->gain[FOAM_BIAS_KNOTS - 1];
    int i = (int)x;
    float a = x - (float)i;
    return b->gain[i] + a * (b->gain[i + 1] - b->gain[i]);
}
