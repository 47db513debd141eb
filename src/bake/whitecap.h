/* whitecap.h - whitecaps from the wind (Tessendorf, Reinhard, Gao 2023; Dupuy & Bruneton 2012).
 *
 * lambda_min: the smaller eigenvalue of the horizontal Jacobian J = I + sum_i lambda_i dD_i/dx
 * (Tessendorf 2023 §2). Breaking where lambda_min < lambda_T; lambda_T is chosen from the CDF of
 * lambda_min so that the whitecap fraction equals a wind-speed model (algorithm 1, eq. 11-13).
 * swell breaks and keeps foam on Dupuy's k of all patterns combined (whitecap_memory_loop), with
 * the thresholds of algorithm 1's role: eq. 13's breaking fraction and the model's W.
 */
#ifndef SWELL_WHITECAP_H
#define SWELL_WHITECAP_H

#include <stddef.h>
#include "core/err.h"

/* Algorithm 1's ensemble decay factor alpha = exp(-0.15) (= 0.861, §5): a model parameter of
 * eq. 11-13 fitted to the phenomenology, not the per-frame decay of eq. 7. */
#define SWELL_WHITECAP_ALPHA 0.86070797642505781

/* W(U10) of a model (enum whitecap_model; DEFAULT = MOM80), a fraction in [0, 1] (clamped).
 * Eq. 1 with U_0 = 0 for both fits, so W > 0 for every U > 0; 0 for U <= 0 or NaN; NaN for an
 * unknown model. MOM80 (eq. 14): 3.84e-6 U^3.41. WU88 (Wu 1988, J. Phys. Oceanogr. 18):
 * 2.0e-6 U^3.75. */
double whitecap_model_fraction(int model, double wind_speed_mps);
/* That model's exponent b of U (NaN for an unknown model). */
double whitecap_model_exponent(int model);

/* Smaller eigenvalue of [[1 + jxx, jxy], [jxy, 1 + jyy]] (the J of eq. 6, symmetric because the
 * displacement of eq. 4 is a gradient). */
float whitecap_lambda_min(float jxx, float jyy, float jxy);

/* Eq. 13: the breaking fraction <Theta> = CDF(lambda_T) that makes the ensemble whitecap
 * fraction eq. 11 equal w:  <Theta> = w (1 - alpha) / (1 - alpha w). w clamped to [0, 1]. */
double whitecap_breaking_fraction(double w, double alpha);
/* Eq. 11, the inverse: <W> = <Theta> / (1 - alpha (1 - <Theta>)). */
double whitecap_ensemble_fraction(double theta, double alpha);

/* Empirical CDF of eq. 12 at lambda_t: the share of the samples with lambda_min >= 0 that are
 * < lambda_t (eq. 12 integrates from 0: negative lambda_min, the surface passing through itself,
 * is excluded as unphysical - §4). 0 when no sample is >= 0. */
double whitecap_cdf(const float *lambda_min, size_t count, float lambda_t);

/* Algorithm 1 step 7: lambda_T with CDF(lambda_T) = fraction (the <Theta> of eq. 13, NOT W) for
 * the CDF of whitecap_cdf(). Exact order statistics (sorted copy, deterministic): with m
 * samples >= 0, k = round(fraction m) of them lie below lambda_T, which is the midpoint between
 * the k-th and (k+1)-th smallest. SWELL_E_ARG for NaN samples, fraction outside [0, 1] or no
 * sample >= 0; SWELL_E_NOMEM. */
int whitecap_threshold(const float *lambda_min, size_t count, double fraction, float *lambda_t,
                       struct swell_err *err);

/* Foam that lasts, on the patterns combined (issue 13: foam baked per pattern repeated on
 * each pattern's tile). Eq. 8 keeps foam where a texel broke recently: O' = max(B, a O) for a
 * binary B. Its (min, +) analogue keeps, per texel, the lowest breaking measure reached
 * recently, rising at a fixed rate since: m(t) = min(k(t), m(t - dt) + r dt). m is additive
 * over independent patterns like Dupuy's k (a sum of per-pattern memories, each looping on its
 * own tile), so foam = {sum_i m_i < epsilon} is not periodic in any one tile, and prefilters as
 * k does (its mean and second moment in mipmaps, eq. 7-8). A deeper break (lower k) stays
 * below epsilon longer; r is solved so that the area this foam covers equals the wind model's
 * W, while epsilon makes the instantaneous breaking {sum_i k_i < epsilon} the eq. 13 fraction.
 *
 * The periodic steady state of m over a loop of `frames` frames: min over n in [0, frames) of
 * k(f - n) + n step, written to m[frame * texels + i] (k in the same layout; step >= 0, the
 * rise per frame). SWELL_E_NOMEM. */
int whitecap_memory_loop(const float *k, size_t texels, int frames, float step, float *m,
                         struct swell_err *err);

/* The distribution of S = offset + sum_i X_i for independent X_i, each given by its samples
 * (every sample equally likely): each histogram on one grid (spacing h = the widest sample
 * range / WHITECAP_SUM_BINS, mass split linearly between the two nearest grid points), the
 * histograms convolved. P(S < x) is then within the mass of about n grid spacings of the true
 * empirical one. */
#define WHITECAP_SUM_BINS 512
#define SWELL_WHITECAP_SUM_MAX 4      /* variables (patterns) */

struct whitecap_sum {
    double lo, h;       /* grid point j is at lo + j h */
    int points;
    double *cum;        /* cum[j]: mass at grid points 0..j (cum[points - 1] = 1) */
};

/* SWELL_E_ARG for no variable, an empty one or a NaN / infinite sample (says which),
 * SWELL_E_NOMEM. On failure *out is zeroed. */
int whitecap_sum_create(const float *const *samples, const size_t *counts, int n, double offset,
                        struct whitecap_sum *out, struct swell_err *err);
void whitecap_sum_destroy(struct whitecap_sum *s);   /* accepts a zeroed one */
/* P(S < x): each grid point's mass spread evenly over the spacing around it. */
double whitecap_sum_cdf(const struct whitecap_sum *s, double x);
/* The x with P(S < x) = p (p clamped to [0, 1]); the inverse of whitecap_sum_cdf where the
 * mass is not zero. */
double whitecap_sum_quantile(const struct whitecap_sum *s, double p);

/* Dupuy & Bruneton 2012. Eq. 7: pattern i's share k_i = 1/n + a_i + b_i + a_i b_i - c_i^2 of the
 * Jacobian determinant j (eq. 4), with a_i = jxx, b_i = jyy, c_i = jxy of that pattern and n the
 * pattern count; the mean of j over a footprint is the sum of the k_i means (eq. 7), its
 * variance the sum of the k_i^2 means minus mu^2 (eq. 8). */
float whitecap_dupuy_k(float jxx, float jyy, float jxy, int patterns);
/* Eq. 6: coverage W = 1/2 + 1/2 erf((epsilon - mu) / (sqrt(2) sigma)) of j ~ N(mu, var);
 * a step at mu when var <= 0. */
double whitecap_dupuy_coverage(double epsilon, double mu, double var);

#endif
