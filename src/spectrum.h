/* spectrum.h - ocean wave spectra with directional spreading (deep and finite depth).
 *
 * Omnidirectional frequency spectra S(omega) in m^2 s/rad: Pierson-Moskowitz, JONSWAP
 * (fetch-limited) and TMA (JONSWAP times the Kitaigorodskii depth function). The directional
 * wavenumber spectrum Psi(kx, ky) in m^4 satisfies  integral Psi d^2k = variance of height.
 * Dispersion: omega^2 = g k tanh(k h) (deep water when depth is 0).
 */
#ifndef SWELL_SPECTRUM_H
#define SWELL_SPECTRUM_H

#include "seastate.h"

#define SWELL_GRAVITY 9.81

double spectrum_omega(double k, double depth_m);           /* rad/s */
double spectrum_domega_dk(double k, double depth_m);       /* group velocity, m/s */
double spectrum_peak_omega(const struct seastate *s);      /* rad/s */
double spectrum_S_omega(const struct seastate *s, double omega);  /* m^2 s/rad */
/* Directional spreading D(theta) normalised so integral over (-pi, pi] is 1. */
double spectrum_spreading(const struct seastate *s, double theta_rad);
/* Psi(kx, ky), m^4: S(omega(k)) domega/dk / k * D(theta). */
double spectrum_psi(const struct seastate *s, double kx, double ky);
/* Capillary cut-off wavenumber for the slope statistics, rad/m. */
double spectrum_k_cutoff(const struct seastate *s);

#endif
