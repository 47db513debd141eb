/* ross.h - the shadowing/masking of the Ross BRDF (Bruneton 2010 eq. 15-16), the C reference of
 * common.glsl ross_lambda (test_glsl compares the two).
 *
 * For a Gaussian slope distribution of variance var seen at angle theta (cos_t = cos theta),
 * Smith's Lambda(a) = (e^{-a^2} / (a sqrt(pi)) - erfc(a)) / 2 with a = 1 / (sqrt(2 var) tan theta)
 * (Bruneton eq. 16's denominator is 1 + Lambda(v) + Lambda(l)). */
#ifndef SWELL_ROSS_H
#define SWELL_ROSS_H

#include <math.h>

static inline double ross_lambda_exact(double cos_t, double var)
{
    double s = sqrt(fmax(1.0 - cos_t * cos_t, 0.0));
    if (s <= 0.0)
        return 0.0;
    double a = cos_t / (s * sqrt(2.0 * var));
    return 0.5 * (exp(-a * a) / (a * sqrt(M_PI)) - erfc(a));
}

#endif
