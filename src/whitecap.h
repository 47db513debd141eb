/* whitecap.h - whitecaps from the wind (Tessendorf, Reinhard, Gao 2023; Dupuy & Bruneton 2012).
 *
 * lambda_min: the smaller eigenvalue of the horizontal Jacobian J = I + sum_i lambda_i dD_i/dx
 * (Tessendorf 2023 §2). Breaking where lambda_min < lambda_T; lambda_T is chosen from the CDF of
 * lambda_min so that the whitecap fraction equals a wind-speed model (algorithm 1, eq. 11-13).
 * Foam opacity O decays with a half-life (eq. 7-8); over a loop it is brought to its periodic
 * steady state so frame F equals frame 0. The breaking input per texel is the share of its area
 * that breaks (sub-sampled), not a yes/no at its centre, so foam edges are not the texel grid.
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

/* Sub-texel breaking coverage: the B in [0, 1] that replaces eq. 8's binary
 * Theta(lambda_T - lambda_min) per texel. A texel of a periodic width x height lambda_min table
 * covers the unit square around its centre; between centres lambda_min is bilinear (wrapping at
 * the edges, as the GPU samples the looping table). B(lambda_T) is the share of the texel's
 * sub x sub sub-sample points (the centres of a sub x sub split of the square) where that
 * reconstruction is < lambda_T: a midpoint-rule estimate of the breaking area. sub = 1 is the
 * texel centre alone, i.e. eq. 7's binary test. Each texel keeps its smallest and largest
 * sub-sample, so only texels on a breaking edge recount at a new threshold. */
#define WHITECAP_SUB_DEFAULT 4
#define WHITECAP_SUB_MAX 16

struct whitecap_cover_desc {
    const float *lambda_min;  /* frames x height x width, row-major per frame; borrowed, must
                               * outlive the cover and hold no NaN */
    int width, height;        /* texels, >= 1 */
    int frames;               /* >= 1 */
    int sub;                  /* sub-samples per texel side, 1..WHITECAP_SUB_MAX;
                               * 0 = WHITECAP_SUB_DEFAULT */
};

struct whitecap_cover {
    struct whitecap_cover_desc desc;   /* defaults resolved */
    float *range;                      /* per texel of every frame: smallest, largest sub-sample */
};

/* SWELL_E_ARG for a bad size, sub or a NaN sample (says which), SWELL_E_NOMEM. On failure
 * *out is zeroed. */
int whitecap_cover_create(const struct whitecap_cover_desc *desc, struct whitecap_cover *out,
                          struct swell_err *err);
/* Accepts a zeroed or failed cover. */
void whitecap_cover_destroy(struct whitecap_cover *c);
/* B of every texel of one frame at lambda_t into b[height * width]. */
void whitecap_cover_frame(const struct whitecap_cover *c, int frame, float lambda_t, float *b);
/* Mean B over every texel of every frame: the sub-sample CDF at lambda_t, i.e. eq. 12's
 * <Theta> for the B the foam loop applies (over all samples: negative lambda_min breaks too). */
double whitecap_cover_mean(const struct whitecap_cover *c, float lambda_t);
/* Smallest and largest sub-sample over every texel of every frame. */
void whitecap_cover_extent(const struct whitecap_cover *c, float *lo, float *hi);

/* Foam opacity for a looping sequence: the cover's F frames spaced dt_s; writes
 * opacity[frame * texels + i] in [0, 1], the periodic steady state of eq. 8 with Theta replaced
 * by the coverage B: O' = B + (1 - B) O exp(-dt/T). Its fixed point over the loop is solved per
 * texel, so one update from frame F-1 gives back frame 0 (exactly where some frame has B = 1 or
 * B = 0 throughout, to float rounding elsewhere). For B in {0, 1} (sub = 1) this is eq. 7.
 * half_life_s is a true half-life (opacity halves in half_life_s without breaking): eq. 7's
 * decay time is T = half_life_s / ln 2, so the per-frame factor is
 * exp(-dt/T) = 2^(-dt_s / half_life_s). (The paper calls T a "half life" but writes exp(-dt/T).)
 * SWELL_E_ARG for a bad dt_s or half-life, SWELL_E_NOMEM. */
int whitecap_foam_loop(const struct whitecap_cover *c, float lambda_t, float dt_s,
                       float half_life_s, float *opacity, struct swell_err *err);

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
