/* spectrum.h - ocean wave spectra with directional spreading (deep and finite depth).
 *
 * Omnidirectional frequency spectra S(omega) in m^2 s/rad: Pierson-Moskowitz, JONSWAP
 * (fetch-limited) and TMA (JONSWAP times the Kitaigorodskii depth function). The directional
 * wavenumber spectrum Psi(kx, ky) in m^4 satisfies  integral Psi d^2k = variance of height.
 * Dispersion: omega^2 = g k tanh(k h) (deep water when depth is 0).
 */
#ifndef SWELL_SPECTRUM_H
#define SWELL_SPECTRUM_H

#include "core/seastate.h"

#define SWELL_GRAVITY 9.81

double spectrum_omega(double k, double depth_m);           /* rad/s */
double spectrum_domega_dk(double k, double depth_m);       /* group velocity, m/s */
double spectrum_peak_omega(const struct seastate *s);      /* rad/s */
double spectrum_S_omega(const struct seastate *s, double omega);  /* m^2 s/rad */
/* The height variance JONSWAP and TMA (before its depth function) are scaled to, m^2:
 * Hasselmann et al. 1973's fetch law g^2 m0 / U10^4 = 1.6e-7 X, at most Pierson-Moskowitz's
 * fully developed sea (Hs = 4 sqrt(m0)). */
double spectrum_jonswap_m0(const struct seastate *s);
/* Directional spreading D(theta) normalised so integral over (-pi, pi] is 1. */
double spectrum_spreading(const struct seastate *s, double theta_rad);
/* Psi(kx, ky), m^4: S(omega(k)) domega/dk / k * D(theta). */
double spectrum_psi(const struct seastate *s, double kx, double ky);
/* Capillary cut-off wavenumber for the slope statistics, rad/m. */
double spectrum_k_cutoff(const struct seastate *s);

/* Inverse dispersion: the k > 0 with spectrum_omega(k, depth) = omega, rad/m (0 for omega <= 0). */
double spectrum_k_of_omega(double omega, double depth_m);
/* Wavenumber of the spectral peak, rad/m: spectrum_k_of_omega(spectrum_peak_omega(s)). */
double spectrum_peak_k(const struct seastate *s);
/* Cox & Munk 1954 clean-surface total mean-square slope, 0.003 + 5.12e-3 U (U in m/s). */
double spectrum_mss_cox_munk(double wind_speed_mps);
/* ...and its split along world x and y for the sea state's wind direction: upwind 3.16e-3 U,
 * crosswind 0.003 + 1.92e-3 U (Cox & Munk 1954's clean-surface fits), scaled to sum to the
 * total's fit. */
void spectrum_mss_cox_munk_xy(const struct seastate *s, double *mss_x, double *mss_y);
/* The slope variance the spectrum up to spectrum_k_cutoff lacks of Cox & Munk's, per axis
 * (>= 0): in strong wind the omega^-5 tail, cut at 1e4 rad/m where viscosity damps the
 * capillaries, saturates below the measured total; the renderer carries it as unresolved
 * variance (Bruneton 2010 eq. 4), as it does the tail beyond the last pattern. */
void spectrum_mss_deficit(const struct seastate *s, double *dx, double *dy);

/* Moments of Psi over the annulus k0 <= |k| < k1 (rad/m), by quadrature: var = integral Psi,
 * mss_x = integral kx^2 Psi, mss_y = integral ky^2 Psi (world x east, y north; Bruneton 2010
 * eq. 4 for a continuous spectrum). Any output pointer may be NULL. */
void spectrum_band_moments(const struct seastate *s, double k0, double k1, double *var,
                           double *mss_x, double *mss_y);

#endif
