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

/* W(U10) of a model (enum whitecap_model), a fraction in [0, 1]. */
double whitecap_model_fraction(int model, double wind_speed_mps);

/* Smaller eigenvalue of [[1 + jxx, jxy], [jxy, 1 + jyy]]. */
float whitecap_lambda_min(float jxx, float jyy, float jxy);

/* lambda_T with P(lambda_min < lambda_T) = fraction over the samples (CDF inversion). */
int whitecap_threshold(const float *lambda_min, size_t count, double fraction, float *lambda_t,
                       struct swell_err *err);

/* Foam opacity for a looping sequence: lambda_min[frame * texels + i] for F frames spaced dt_s;
 * writes opacity[frame * texels + i] in [0, 1], the periodic steady state of eq. 7-8. */
int whitecap_foam_loop(const float *lambda_min, int frames, size_t texels, float lambda_t,
                       float dt_s, float half_life_s, float *opacity, struct swell_err *err);

/* Measured whitecap fraction (eq. 9): mean opacity over all samples. */
double whitecap_measured_fraction(const float *opacity, size_t count);

#endif
