/* spectrum.c - wave spectra, directional spreading, dispersion and their moments.
 *
 * Conventions: omega in rad/s, k in rad/m, S(omega) in m^2 s/rad with integral S d omega =
 * height variance; Psi(kx, ky) in m^4 with integral Psi d^2k = height variance. theta is the
 * direction a component travels towards, CCW from +x; the wind blows towards wind_dir_deg.
 */
#include "bake/spectrum.h"

#include <math.h>
#include <stddef.h>

#define G SWELL_GRAVITY
#define TWO_PI 6.283185307179586

/* Pierson & Moskowitz 1964: S = alpha g^2 omega^-5 exp(-beta (g / (U19.5 omega))^4). Their wind
 * is measured 19.5 m up; U19.5 = 1.026 U10 for the neutral log profile they assumed. */
#define PM_ALPHA 8.1e-3
#define PM_BETA 0.74
#define PM_U195_PER_U10 1.026

/* JONSWAP (Hasselmann et al. 1973) with U10 and dimensionless fetch X = g F / U10^2:
 * omega_p = 22 (g^2 / (U10 F))^(1/3) = 22 (g / U10) X^(-1/3), and the height from their energy
 * law g^2 m0 / U10^4 = 1.6e-7 X, at most Pierson-Moskowitz's fully developed m0.
 * Their alpha = 0.076 X^-0.22 is not used: with gamma 3.3 and that omega_p it integrates to
 * 1.30-1.36x the law's Hs at the presets' fetches (and 1.29x PM's at full development), the
 * parameters having been fitted separately. Instead alpha = m0 omega_p^4 / (g^2 J), as
 * DNV-RP-C205 §3.5.5 parameterises JONSWAP by Hs and Tp (its A_gamma = 1 - 0.287 ln gamma
 * is 5 J's reciprocal within 0.3 %), with J = the integral over x = omega / omega_p of
 * x^-5 exp(-5/4 x^-4) gamma^r(x) (test_spectrum computes it by quadrature). */
#define JONSWAP_GAMMA 3.3
#define JONSWAP_SIGMA_LOW 0.07
#define JONSWAP_SIGMA_HIGH 0.09
#define JONSWAP_J 0.3049897
#define JONSWAP_ENERGY_LAW 1.6e-7

/* Cut-off search range, rad/m. Below 100 rad/m (6 cm) the cut-off would remove short gravity
 * waves that the tables resolve; above 1e4 rad/m (0.6 mm) viscosity damps capillary waves
 * within a few periods, so no physical slope lives there. */
#define K_CUTOFF_LO 100.0
#define K_CUTOFF_HI 1.0e4

/* Radial quadrature step in ln k: the JONSWAP peak has relative width sigma = 0.07 in omega,
 * i.e. 0.14 in ln k; 0.004 resolves it with ~35 points (midpoint rule error << 1e-4). */
#define LNK_STEP 0.004

double spectrum_omega(double k, double depth_m)
{
    if (k <= 0.0)
        return 0.0;
    if (depth_m <= 0.0)
        return sqrt(G * k);
    return sqrt(G * k * tanh(k * depth_m));
}

double spectrum_domega_dk(double k, double depth_m)
{
    if (depth_m <= 0.0)
        return k > 0.0 ? 0.5 * sqrt(G / k) : HUGE_VAL;
    if (k <= 0.0)
        return sqrt(G * depth_m);       /* shallow-water limit c = sqrt(g h) */
    double kh = k * depth_m, th = tanh(kh);
    /* d/dk sqrt(g k tanh(kh)) = g (tanh(kh) + kh sech^2(kh)) / (2 omega) */
    return G * (th + kh * (1.0 - th * th)) / (2.0 * spectrum_omega(k, depth_m));
}

double spectrum_k_of_omega(double omega, double depth_m)
{
    if (omega <= 0.0)
        return 0.0;
    double k_deep = omega * omega / G;
    if (depth_m <= 0.0)
        return k_deep;
    /* Eckart's approximation as the start, then Newton on f(k) = g k tanh(kh) - omega^2, which
     * is increasing and convex in k, so Newton from either side converges monotonically after
     * the first step. */
    double k = k_deep / sqrt(tanh(k_deep * depth_m));
    for (int i = 0; i < 50; i++) {
        double th = tanh(k * depth_m);
        double f = G * k * th - omega * omega;
        double df = G * (th + k * depth_m * (1.0 - th * th));
        double step = f / df;
        k -= step;
        if (fabs(step) <= 1e-15 * k)
            break;
    }
    return k;
}

/* Dimensionless fetch, capped at full development: beyond X_fd the JONSWAP peak would fall
 * below the Pierson-Moskowitz peak, which no fetch can reach (the sea is fully developed). */
static double jonswap_fetch(const struct seastate *s)
{
    double u = s->wind_speed_mps;
    double x = G * s->fetch_km * 1000.0 / (u * u);
    double pm_peak = pow(0.8 * PM_BETA, 0.25) / PM_U195_PER_U10;   /* omega_p U10 / g */
    double x_fd = pow(22.0 / pm_peak, 3.0);
    return x < x_fd ? x : x_fd;
}

double spectrum_peak_omega(const struct seastate *s)
{
    double u = s->wind_speed_mps;
    if (s->spectrum == SPECTRUM_PM) {
        /* dS/domega = 0 at omega^4 = (4 beta / 5) (g / U19.5)^4 */
        return pow(0.8 * PM_BETA, 0.25) * G / (PM_U195_PER_U10 * u);
    }
    return 22.0 * (G / u) * pow(jonswap_fetch(s), -1.0 / 3.0);
}

double spectrum_peak_k(const struct seastate *s)
{
    return spectrum_k_of_omega(spectrum_peak_omega(s), s->depth_m);
}

/* Kitaigorodskii et al. 1975 depth function Phi(omega_h), omega_h = omega sqrt(h / g) (the TMA
 * spectrum of Bouws et al. 1985 is JONSWAP times Phi). */
static double kitaigorodskii(double omega, double depth_m)
{
    if (depth_m <= 0.0)
        return 1.0;
    double wh = omega * sqrt(depth_m / G);
    if (wh <= 1.0)
        return 0.5 * wh * wh;
    if (wh < 2.0)
        return 1.0 - 0.5 * (2.0 - wh) * (2.0 - wh);
    return 1.0;
}

double spectrum_jonswap_m0(const struct seastate *s)
{
    double u = s->wind_speed_mps;
    double x = G * s->fetch_km * 1000.0 / (u * u);
    double u195 = PM_U195_PER_U10;   /* U19.5 / U10: PM's m0 = alpha U19.5^4 / (4 beta g^2) */
    double full = PM_ALPHA * u195 * u195 * u195 * u195 / (4.0 * PM_BETA);
    double e = JONSWAP_ENERGY_LAW * x;
    return (e < full ? e : full) * u * u * u * u / (G * G);
}

double spectrum_S_omega(const struct seastate *s, double omega)
{
    if (!(omega > 0.0))
        return 0.0;
    double wp = spectrum_peak_omega(s);
    double r4 = pow(wp / omega, 4.0);
    if (s->spectrum == SPECTRUM_PM)
        return PM_ALPHA * G * G * pow(omega, -5.0) * exp(-1.25 * r4);
    double alpha = spectrum_jonswap_m0(s) * wp * wp * wp * wp / (G * G * JONSWAP_J);
    double sigma = omega <= wp ? JONSWAP_SIGMA_LOW : JONSWAP_SIGMA_HIGH;
    double d = (omega - wp) / (sigma * wp);
    double peak = pow(JONSWAP_GAMMA, exp(-0.5 * d * d));
    double S = alpha * G * G * pow(omega, -5.0) * exp(-1.25 * r4) * peak;
    if (s->spectrum == SPECTRUM_TMA)
        S *= kitaigorodskii(omega, s->depth_m);
    return S;
}

/* Longuet-Higgins et al. 1963: D = Q(s) cos^(2s)(theta / 2), and
 * integral over (-pi, pi] of cos^(2s)(theta/2) = 2 sqrt(pi) Gamma(s + 1/2) / Gamma(s + 1). */
static double spreading_norm(double sp)
{
    return exp(lgamma(sp + 1.0) - lgamma(sp + 0.5)) / (2.0 * sqrt(M_PI));
}

static double spreading_rel(double sp, double q, double rel)
{
    rel = remainder(rel, TWO_PI);           /* (-pi, pi], where cos(rel/2) >= 0 */
    return q * pow(fabs(cos(0.5 * rel)), 2.0 * sp);
}

static double wind_dir_rad(const struct seastate *s)
{
    return s->wind_dir_deg * (M_PI / 180.0);
}

double spectrum_spreading(const struct seastate *s, double theta_rad)
{
    double sp = s->spread;
    return spreading_rel(sp, spreading_norm(sp), theta_rad - wind_dir_rad(s));
}

/* Psi in polar form: Psi(k, theta) = R(k) D(theta), R(k) = S(omega(k)) domega/dk / k, since
 * S d omega = S domega/dk dk and d^2k = k dk dtheta. */
static double radial(const struct seastate *s, double k)
{
    if (k <= 0.0)
        return 0.0;
    double w = spectrum_omega(k, s->depth_m);
    return spectrum_S_omega(s, w) * spectrum_domega_dk(k, s->depth_m) / k;
}

double spectrum_psi(const struct seastate *s, double kx, double ky)
{
    double k = sqrt(kx * kx + ky * ky);
    if (k <= 0.0)
        return 0.0;
    return radial(s, k) * spectrum_spreading(s, atan2(ky, kx));
}

double spectrum_mss_cox_munk(double wind_speed_mps)
{
    return 0.003 + 5.12e-3 * wind_speed_mps;
}

void spectrum_mss_cox_munk_xy(const struct seastate *s, double *mss_x, double *mss_y)
{
    double u = s->wind_speed_mps, up = 3.16e-3 * u, cross = 0.003 + 1.92e-3 * u;
    /* the two fits sum to 0.003 + 5.08e-3 U: scaled to the total's fit */
    double k = spectrum_mss_cox_munk(u) / (up + cross);
    double c = cos(wind_dir_rad(s)), sn = sin(wind_dir_rad(s));
    up *= k;
    cross *= k;
    *mss_x = up * c * c + cross * sn * sn;
    *mss_y = up * sn * sn + cross * c * c;
}

void spectrum_mss_deficit(const struct seastate *s, double *dx, double *dy)
{
    double cx, cy, tx, ty;
    spectrum_mss_cox_munk_xy(s, &cx, &cy);
    spectrum_band_moments(s, 0.0, spectrum_k_cutoff(s), NULL, &tx, &ty);
    *dx = cx > tx ? cx - tx : 0.0;
    *dy = cy > ty ? cy - ty : 0.0;
}

/* Lowest wavenumber worth integrating from: at k_p / 20 (omega_p / omega >= 4.4) the factor
 * exp(-1.25 (omega_p / omega)^4) < 1e-200. */
static double k_floor(const struct seastate *s)
{
    return spectrum_peak_k(s) / 20.0;
}

/* Fraction of the slope variance along x: integral cos^2(theta) D(theta) d theta
 * = 1/2 + 1/2 cos(2 theta_w) <cos 2 phi>, phi relative to the wind; <cos 2 phi> by the
 * trapezoid rule, exact to rounding for a smooth periodic integrand. */
static double x_fraction(const struct seastate *s)
{
    enum { STEPS = 2048 };
    double sp = s->spread, q = spreading_norm(sp), m = 0.0;
    for (int i = 0; i < STEPS; i++) {
        double phi = -M_PI + TWO_PI * i / STEPS;
        m += cos(2.0 * phi) * spreading_rel(sp, q, phi);
    }
    m *= TWO_PI / STEPS;
    return 0.5 + 0.5 * cos(2.0 * wind_dir_rad(s)) * m;
}

/* Midpoint rule in u = ln k: integral f dk = integral f k du. */
static void radial_moments(const struct seastate *s, double k0, double k1, double *var,
                           double *mss)
{
    *var = 0.0;
    *mss = 0.0;
    double lo = k_floor(s);
    if (k0 < lo)
        k0 = lo;
    if (!(k1 > k0))
        return;
    double u0 = log(k0), u1 = log(k1);
    int steps = (int)ceil((u1 - u0) / LNK_STEP);
    double h = (u1 - u0) / steps;
    for (int i = 0; i < steps; i++) {
        double k = exp(u0 + (i + 0.5) * h);
        double rk2 = radial(s, k) * k * k;      /* R(k) k dk = R k^2 du */
        *var += rk2;
        *mss += rk2 * k * k;
    }
    *var *= h;
    *mss *= h;
}

void spectrum_band_moments(const struct seastate *s, double k0, double k1, double *var,
                           double *mss_x, double *mss_y)
{
    double v, m;
    radial_moments(s, k0, k1, &v, &m);
    double fx = x_fraction(s);
    if (var)
        *var = v;
    if (mss_x)
        *mss_x = m * fx;
    if (mss_y)
        *mss_y = m * (1.0 - fx);
}

/* Why a wind-dependent cut-off: PM, JONSWAP and TMA describe gravity waves; their omega^-5
 * tail gives a slope variance growing only like alpha/2 ln k, which misses the wind-driven
 * short gravity and capillary waves that carry most of the slope (Cox & Munk 1954 measured
 * mss = 0.003 + 5.12e-3 U, rising linearly with wind). Rather than bolting on a second
 * (capillary) spectrum, the gravity spectrum's tail is integrated up to the k_c at which the
 * mss along one axis equals Cox & Munk's share, clamped to [K_CUTOFF_LO, K_CUTOFF_HI]; the rest
 * of their total is spectrum_mss_deficit. The renderer's BRDF
 * then carries everything between the last pattern's band and k_c (Bruneton 2010 eq. 4), so
 * the total slope variance the image sees matches the measured sea surface. */
double spectrum_k_cutoff(const struct seastate *s)
{
    /* The spectrum's slope splits between x and y in a fixed ratio (x_fraction); the cut-off
     * fills the axis that reaches Cox & Munk's share first, so neither exceeds it and
     * spectrum_mss_deficit tops up the other: the total and the up/crosswind split both match
     * wherever the cut-off lies within its range. */
    double cx, cy, fx = x_fraction(s);
    spectrum_mss_cox_munk_xy(s, &cx, &cy);
    double target = fmin(fx > 0.0 ? cx / fx : HUGE_VAL, fx < 1.0 ? cy / (1.0 - fx) : HUGE_VAL);
    double lo = k_floor(s);
    if (lo >= K_CUTOFF_HI)
        return K_CUTOFF_HI;
    double u0 = log(lo), u1 = log(K_CUTOFF_HI);
    int steps = (int)ceil((u1 - u0) / LNK_STEP);
    double h = (u1 - u0) / steps, acc = 0.0;
    for (int i = 0; i < steps; i++) {
        double ka = exp(u0 + i * h), kb = exp(u0 + (i + 1) * h);
        double k = exp(u0 + (i + 0.5) * h);
        double inc = radial(s, k) * k * k * k * k * h;
        if (acc + inc >= target && kb > K_CUTOFF_LO) {
            /* linear in ln k inside the step */
            double f = (target - acc) / inc;
            double kc = exp(log(ka) + f * h);
            return kc < K_CUTOFF_LO ? K_CUTOFF_LO : kc;
        }
        acc += inc;
    }
    return K_CUTOFF_HI;
}
