/* fresnel.h - Fresnel reflectance of water: exact (Hu 2006 eq. 2), the 2D Fresnel texture for
 * Fresnel bump mapping (Hu §5.1) and the effective Fresnel of a rough surface (Bruneton 2010
 * eq. 24) with its analytic fit (eq. 26).
 */
#ifndef SWELL_FRESNEL_H
#define SWELL_FRESNEL_H

#include "err.h"
#include "tables.h"

#define SWELL_WATER_IOR 1.333

/* Unpolarised Fresnel reflectance for incidence cosine cos_i from air into index n. */
double fresnel_exact(double cos_i, double n);

/* Effective Fresnel (eq. 24) by numerical integration over the slope distribution of variance
 * sigma2 (isotropic), viewed at cos_v; and the fit of eq. 26. */
double fresnel_effective(double cos_v, double sigma2);
double fresnel_effective_fit(double cos_v, double sigma2);

/* Fill t (geometry set by the callee: size x size RGBA8, 1 layer, 1 level, scale/bias set):
 * Hu's Fresnel texture; name "fresnel". */
int fresnel_hu_table(int size, struct swell_table *t, struct swell_err *err);
/* Effective Fresnel table over (cos_v, sigma): name "fresnel_eff". */
int fresnel_eff_table(int size, struct swell_table *t, struct swell_err *err);

#endif
