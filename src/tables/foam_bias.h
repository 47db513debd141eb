/* foam_bias.h - how much foam Dupuy eq. 6 draws from a set's whitecap tables, against what the
 * bake made, by footprint (issue 14).
 *
 * A pixel (or a vertex) that reads the whitecap tables at the mip level of its footprint gets
 * the patterns' summed foam memory's mean mu and variance (eq. 7-8, each pattern's <m^2> - <m>^2
 * from its level) and takes eq. 6's Gaussian coverage P(m < epsilon). The memory is not
 * Gaussian (a floor of unbroken sea with a skewed tail of foam), so the mean of that coverage
 * over the sea differs from the fraction the bake measured on its full field
 * (tables.h whitecap_fraction_measured: Tessendorf 2023's W from the wind), and by a factor that
 * changes with the footprint: with the renderer's trust at level 0, 0.85-0.89 W under a texel,
 * and beyond a kilometre 0.80 W at 15 m/s, 0.38 W at 8 m/s. foam_bias_compute finds that
 * factor's inverse, the gain that brings the mean back to W, at every whole level of footprint;
 * the renderer multiplies eq. 6's coverage by it (foam_bias_at), in both qualities. Drawn
 * coverage read back (test_render test_foam_amount, six views): 0.86-1.05 W at 15 m/s from 20 m,
 * 300 m and 3 km up, 0.93-1.02 W at 8 m/s from 300 m and 3 km; from 20 m at 8 m/s 0.54-0.64 W,
 * where the loop-frame blend, outside this model, takes a third (0.82-0.86 W on one frame).
 */
#ifndef SWELL_FOAM_BIAS_H
#define SWELL_FOAM_BIAS_H

struct swell_tables;

#define FOAM_BIAS_KNOTS 20          /* whole levels of footprint, from f0 */

struct foam_bias {
    float f0;                       /* log2 of the first knot's footprint, m */
    float gain[FOAM_BIAS_KNOTS];    /* W over eq. 6's mean coverage at each (1 without foam) */
};

/* The gains of set t: its whitecap tables at every level, sampled at fixed pseudo-random
 * points of every loop frame (the same numbers on every run and machine). The loader and the
 * bake store them in the set (tables.h foam_bias); about 40 ms. */
void foam_bias_compute(const struct swell_tables *t, struct foam_bias *out);

/* The gain at log2 footprint f (m), linear between knots, the end knots' beyond them. */
float foam_bias_at(const struct foam_bias *b, float f);

/* eq. 6's mean coverage over the sea at log2 footprint f, as foam_bias_compute measures it
 * before the gain (for tests): points sampled per knot as there. */
double foam_bias_eq6_mean(const struct swell_tables *t, float f, int points);

#endif
