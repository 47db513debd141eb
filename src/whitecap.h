/* whitecap.h - whitecaps from the wind (Tessendorf, Reinhard, Gao 2023; Dupuy & Bruneton 2012).
 *
 * lambda_min: the smaller eigenvalue of the horizontal Jacobian J = I + sum_i lambda_i dD_i/dx
 * (Tessendorf 2023 §2). Breaking where lambda_min < lambda_T; lambda_T is chosen from the CDF of
 * lambda_min so that the whitecap fraction equals a wind-speed model (algorithm 1, eq. 11-13).
 * Foam opacity O decays with a half-life (eq. 7-8); over a loop it is brought to its periodic
 * steady state so frame F equals frame 0.
 */
#ifndef SWELL_WHITECAP_H
#define SWELL_WHITECAP_H

#include <stddef.h>
#include "err.h"

/* Algorithm 1's ensemble decay factor alpha = exp(-0.15) (= 0.861, §5): a model parameter of
 * eq. 11-13 fitted to the phenomenology, not the per-frame decay of eq. 7. */
#define SWELL_WHITECAP_ALPHA 0.86070797642505781

/* W(U10) of a model (enum whitecap_model; DEFAULT = MOM80), a fraction in [0, 1] (clamped).
 * Eq. 1 with U_0 = 0 for both fits, so W > 0 for every U > 0; 0 for U <= 0 or NaN; NaN for an
 * unknown model. MOM80 (eq. 14): 3.84e-6 U^3.41. WU88 (Wu 1988, J. Phys. Oceanogr. 18):
 * 2.0e-6 U^3.75. */
double whitecap_model_fraction(int model, double wind_speed_mps);

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

/* Foam opacity for a looping sequence: lambda_min[frame * texels + i] for F frames spaced dt_s;
 * writes opacity[frame * texels + i] in [0, 1], the periodic steady state of eq. 7-8: the
 * update run once round the loop from frame F-1 gives back frame 0 exactly. half_life_s is a
 * true half-life (opacity halves in half_life_s without breaking): eq. 7's decay time is
 * T = half_life_s / ln 2, so the per-frame factor is exp(-dt/T) = 2^(-dt_s / half_life_s).
 * (The paper calls T a "half life" but writes exp(-dt/T).) */
int whitecap_foam_loop(const float *lambda_min, int frames, size_t texels, float lambda_t,
                       float dt_s, float half_life_s, float *opacity, struct swell_err *err);

/* Measured whitecap fraction (eq. 9): mean opacity over all samples; 0 for count 0. */
double whitecap_measured_fraction(const float *opacity, size_t count);

/* Dupuy & Bruneton 2012. Eq. 7: pattern i's share k_i = 1/n + a_i + b_i + a_i b_i - c_i^2 of the
 * Jacobian determinant j (eq. 4), with a_i = jxx, b_i = jyy, c_i = jxy of that pattern and n the
 * pattern count; the mean of j over a footprint is the sum of the k_i means (eq. 7), its
 * variance the sum of the k_i^2 means minus mu^2 (eq. 8). */
float whitecap_dupuy_k(float jxx, float jyy, float jxy, int patterns);
/* Eq. 6: coverage W = 1/2 + 1/2 erf((epsilon - mu) / (sqrt(2) sigma)) of j ~ N(mu, var);
 * a step at mu when var <= 0. */
double whitecap_dupuy_coverage(double epsilon, double mu, double var);
/* Eq. 6 inverted: epsilon giving coverage W (clamped to [1e-9, 1 - 1e-9] so epsilon is finite;
 * mu when var <= 0). */
double whitecap_dupuy_epsilon(double coverage, double mu, double var);

#endif
