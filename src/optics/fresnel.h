/* fresnel.h - Fresnel reflectance of water: exact (Hu 2006 eq. 2), the 2D Fresnel texture for
 * Fresnel bump mapping (Hu §5.1) and the effective Fresnel of a rough surface (Bruneton 2010
 * eq. 24) with its analytic fit (eq. 26).
 */
#ifndef SWELL_FRESNEL_H
#define SWELL_FRESNEL_H

#include "core/err.h"
#include "tables/tables.h"

#define SWELL_WATER_IOR 1.333
/* sigma (slope standard deviation in the view direction) at the last row of "fresnel_eff";
 * Bruneton fits eq. 26 for sigma < 0.5 (§5.2, Fig. 7). */
#define SWELL_FRESNEL_EFF_SIGMA_MAX 0.5

/* Unpolarised Fresnel reflectance (Hu eq. 2) for incidence cosine cos_i (clamped to [0, 1])
 * from air into relative index n > 0; 1 at grazing incidence and under total reflection. */
double fresnel_exact(double cos_i, double n);

/* Effective Fresnel of an isotropic Gaussian slope distribution of variance sigma2 (per axis)
 * viewed at cos_v, by numerical integration (Gauss-Legendre, relative error < 1e-6).
 * The weighting is Bruneton's q_evn (eq. 10): the slope pdf p (eq. 7) times the visible
 * projected area max(v.f, 0) / f_z, normalised by (1 + Lambda(a_v)) cos(theta_v) (eq. 8-9) so
 * that it integrates to 1 (eq. 11). v.h = v.f since each facet is a mirror.
 *   fresnel_effective:         eq. 23 with q_vn H ~ q_evn and the exact F of Hu eq. 2 - equal to
 *                              fresnel_exact(cos_v) as sigma2 -> 0;
 *   fresnel_effective_schlick: eq. 24 as printed, R + (1 - R) int q_evn (1 - v.h)^5 with
 *                              R = fresnel_exact(1, n) - what eq. 26 was fitted to;
 *   fresnel_effective_fit:     eq. 26, R + (1 - R) (1 - cos_v)^(5 exp(-2.69 sigma)) /
 *                              (1 + 22.7 sigma^1.5), sigma = sqrt(sigma2).
 * All for n = SWELL_WATER_IOR; cos_v clamped to [0, 1], sigma2 < 0 treated as 0. */
double fresnel_effective(double cos_v, double sigma2);
double fresnel_effective_schlick(double cos_v, double sigma2);
double fresnel_effective_fit(double cos_v, double sigma2);

/* Eq. 26 as the fragment shader evaluates it (common.glsl fresnel_eff, tested against this on
 * the GPU): the view's cos_v unknown per pixel, Schlick's (1 - cos_v)^5 is taken from the exact
 * Fresnel f of the bumped view vector (Hu's texture), (f - R) / (1 - R), and raised to
 * exp(-2.69 sigma): R + (1 - R) ((f - R) / (1 - R))^exp(-2.69 sigma) / (1 + 22.7 sigma^1.5),
 * R = fresnel_exact(1, n); sigma the slope standard deviation in the view direction. */
double fresnel_effective_tex(double f, double sigma);

/* Hu §5.1 Fresnel texture, name "fresnel", size x size RGBA8 (size a power of two in
 * [2, 1024]), 1 layer, 1 level. Index: the unit view vector V = (vx, vy, vz) towards the eye
 * in a frame whose z axis is the (unbumped) surface normal (Hu: the view vector bumped by
 * (-du, -dv)), at polar angle theta = acos(vz), in Hu's (vx, vy) direction at a radius that
 * grows fastest towards grazing, where F does:
 *     (s, t) = 0.5 + 0.5 p,  p = (vx, vy) / |(vx, vy)| r,  r = 1 - sqrt(1 - theta / (pi / 2))
 * so texel (i, j) (row j counted from the first row in memory, GL's t = 0) holds, with
 * p = ((2 i + 1) / size - 1, (2 j + 1) / size - 1), r = min(|p|, 1) and
 * theta = (pi / 2) r (2 - r),
 *     (vx, vy) = sin(theta) p / |p|,  vz = cos(theta);
 * outside the unit disc theta stays pi / 2 (grazing), a continuous extension for bumped
 * look-ups that leave it. Why this radius: F rises from 0.2 to 1 between 80 and 90 degrees.
 * Hu's map (s, t) = 0.5 + 0.5 (vx, vy) squeezed all of that into the outermost texel ring, and
 * even a radius proportional to theta (manifest version 2) left the rise from 0.5 to 1 in the
 * last two texels, straddling the disc's edge: bilinear filtering there depends on how the
 * circle crosses the texel grid, i.e. on the azimuth, and the horizon showed it as bright
 * blobs (vertical streaks before that). Here the last 2 degrees span 15 % of the radius
 * (5 texels of 32 at size 64); normal incidence, where F is flat, gets half the resolution.
 * RGB = V, scale 2 bias -1 (value = 2 byte/255 - 1); A = fresnel_exact(vz, SWELL_WATER_IOR),
 * scale 1 bias 0. Sample with LINEAR filtering and CLAMP_TO_EDGE. */
int fresnel_hu_table(int size, struct swell_table *t, struct swell_err *err);

/* Effective Fresnel table, name "fresnel_eff", size x size RGBA8 (size a power of two in
 * [2, 1024]), 1 layer, 1 level, scale/bias per channel from its min/max (quantize_table).
 * Texel (i, j) holds cos_v = i / (size - 1) and sigma = SWELL_FRESNEL_EFF_SIGMA_MAX j / (size-1)
 * (both ends included), so a shader looks up
 *     s = (0.5 + cos_v (size - 1)) / size,  t = (0.5 + sigma / SIGMA_MAX (size - 1)) / size
 * with LINEAR filtering and CLAMP_TO_EDGE; sigma is the slope standard deviation in the view
 * direction (Bruneton eq. 25: sigma^2 = sigma_x^2 cos^2 phi_v + sigma_y^2 sin^2 phi_v).
 * R = fresnel_effective, G = fresnel_effective_fit (eq. 26), B = fresnel_effective_schlick
 * (eq. 24), A = 1. */
int fresnel_eff_table(int size, struct swell_table *t, struct swell_err *err);

#endif
