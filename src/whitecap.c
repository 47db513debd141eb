#include "whitecap.h"

#include <math.h>
#include <stdlib.h>

#include "seastate.h"

double whitecap_model_fraction(int model, double wind_speed_mps)
{
    double a, b;
    switch (model) {
    case WHITECAP_DEFAULT:
    case WHITECAP_MOM80:   /* Tessendorf 2023 eq. 14 (Monahan & O'Muircheartaigh 1980) */
        a = 3.84e-6;
        b = 3.41;
        break;
    case WHITECAP_WU88:    /* Wu 1988 */
        a = 2.0e-6;
        b = 3.75;
        break;
    default:
        return NAN;
    }
    /* eq. 1 with U_0 = 0: both fits start at calm water */
    if (!(wind_speed_mps > 0.0))
        return 0.0;
    double w = a * pow(wind_speed_mps, b);
    return w < 1.0 ? w : 1.0;
}

float whitecap_lambda_min(float jxx, float jyy, float jxy)
{
    /* eigenvalues of a symmetric 2x2 matrix: centre -+ radius of its Mohr circle; hypot keeps
     * the radius exact when the off-diagonal dominates */
    double mid = 1.0 + 0.5 * ((double)jxx + (double)jyy);
    double rad = hypot(0.5 * ((double)jxx - (double)jyy), (double)jxy);
    return (float)(mid - rad);
}

double whitecap_breaking_fraction(double w, double alpha)
{
    w = w < 0.0 ? 0.0 : w > 1.0 ? 1.0 : w;
    return w * (1.0 - alpha) / (1.0 - alpha * w);   /* eq. 13 */
}

double whitecap_ensemble_fraction(double theta, double alpha)
{
    return theta / (1.0 - alpha * (1.0 - theta));   /* eq. 11 */
}

double whitecap_cdf(const float *lambda_min, size_t count, float lambda_t)
{
    size_t kept = 0, below = 0;
    for (size_t i = 0; i < count; i++) {
        float l = lambda_min[i];
        if (l >= 0.0f) {   /* eq. 12's lower limit */
            kept++;
            below += l < lambda_t;
        }
    }
    return kept ? (double)below / (double)kept : 0.0;
}

static int cmp_float(const void *pa, const void *pb)
{
    float a = *(const float *)pa, b = *(const float *)pb;
    return (a > b) - (a < b);
}

int whitecap_threshold(const float *lambda_min, size_t count, double fraction, float *lambda_t,
                       struct swell_err *err)
{
    if (!(fraction >= 0.0 && fraction <= 1.0))
        return swell_fail(err, SWELL_E_ARG,
                          "whitecap threshold: breaking fraction %g is outside [0, 1] (pass "
                          "eq. 13's <Theta>, e.g. whitecap_breaking_fraction(W, alpha))",
                          fraction);
    size_t m = 0;
    for (size_t i = 0; i < count; i++) {
        if (isnan(lambda_min[i]))
            return swell_fail(err, SWELL_E_ARG,
                              "whitecap threshold: lambda_min sample %zu of %zu is NaN; the "
                              "Jacobian fields hold NaN (check the spectrum and choppiness)",
                              i, count);
        m += lambda_min[i] >= 0.0f;
    }
    if (m == 0)
        return swell_fail(err, SWELL_E_ARG,
                          "whitecap threshold: none of the %zu lambda_min samples is >= 0 "
                          "(Tessendorf 2023 eq. 12 excludes negative values); the surface "
                          "folds everywhere: lower the choppiness", count);
    float *s = malloc(m * sizeof *s);
    if (!s)
        return swell_fail(err, SWELL_E_NOMEM,
                          "whitecap threshold: cannot allocate %zu floats for the sorted "
                          "lambda_min samples", m);
    size_t j = 0;
    for (size_t i = 0; i < count; i++)
        if (lambda_min[i] >= 0.0f)
            s[j++] = lambda_min[i];
    qsort(s, m, sizeof *s, cmp_float);

    /* CDF(x) = #(s < x) / m is a step function; any x in (s[k-1], s[k]] gives exactly k/m.
     * The midpoint sits clear of both samples unless they are adjacent floats, where it rounds
     * onto s[k-1]; s[k] is then the only choice. Tied samples cannot be split: s[k] puts the
     * whole tie above the threshold. */
    size_t k = (size_t)llround(fraction * (double)m);
    if (k == 0) {
        *lambda_t = s[0];
    } else if (k >= m) {
        *lambda_t = nextafterf(s[m - 1], INFINITY);
    } else {
        float mid = (float)(0.5 * ((double)s[k - 1] + (double)s[k]));
        *lambda_t = mid > s[k - 1] ? mid : s[k];
    }
    free(s);
    return 0;
}

/* One step of eq. 7 (equivalently eq. 8) for every texel; the case form avoids eq. 8's
 * O a + (1 - O a), which is not always exactly 1 in floating point. */
static void foam_step(const float *lambda_min, const float *prev, float *next, size_t texels,
                      float lambda_t, float decay)
{
    for (size_t i = 0; i < texels; i++)
        next[i] = lambda_min[i] < lambda_t ? 1.0f : prev[i] * decay;
}

int whitecap_foam_loop(const float *lambda_min, int frames, size_t texels, float lambda_t,
                       float dt_s, float half_life_s, float *opacity, struct swell_err *err)
{
    if (frames < 1)
        return swell_fail(err, SWELL_E_ARG, "foam loop: %d frames, need at least 1", frames);
    if (!(dt_s > 0.0f) || !(half_life_s > 0.0f) || !isfinite(dt_s) || !isfinite(half_life_s))
        return swell_fail(err, SWELL_E_ARG,
                          "foam loop: frame step %g s and half-life %g s must be finite and > 0",
                          (double)dt_s, (double)half_life_s);
    float decay = (float)exp2(-(double)dt_s / (double)half_life_s);
    size_t F = (size_t)frames;
    float *last = opacity + (F - 1) * texels;

    /* Periodic steady state in two passes. Pass 1 starts from O = 0 (the paper's initial
     * state). A texel that breaks in some frame forgets its start there, so after pass 1 its
     * frame F-1 value is already periodic; a texel that never breaks decays to the periodic
     * value 0 and stays 0. Pass 2 restarts from that frame F-1 value, so frame 0 follows from
     * frame F-1 by eq. 7 and the loop closes exactly (same products, same rounding). */
    for (size_t i = 0; i < texels; i++)
        last[i] = 0.0f;
    for (int pass = 0; pass < 2; pass++) {
        foam_step(lambda_min, last, opacity, texels, lambda_t, decay);
        for (size_t f = 1; f < F; f++)
            foam_step(lambda_min + f * texels, opacity + (f - 1) * texels, opacity + f * texels,
                      texels, lambda_t, decay);
    }
    return 0;
}

double whitecap_measured_fraction(const float *opacity, size_t count)
{
    if (count == 0)
        return 0.0;
    double sum = 0.0;
    for (size_t i = 0; i < count; i++)
        sum += opacity[i];
    return sum / (double)count;   /* eq. 9 */
}

float whitecap_dupuy_k(float jxx, float jyy, float jxy, int patterns)
{
    double a = jxx, b = jyy, c = jxy;
    patterns = patterns < 1 ? 1 : patterns;
    return (float)(1.0 / patterns + a + b + a * b - c * c);   /* Dupuy eq. 7 */
}

double whitecap_dupuy_coverage(double epsilon, double mu, double var)
{
    if (!(var > 0.0))
        return epsilon > mu ? 1.0 : epsilon < mu ? 0.0 : 0.5;
    return 0.5 + 0.5 * erf((epsilon - mu) / sqrt(2.0 * var));   /* Dupuy eq. 6 */
}

double whitecap_dupuy_epsilon(double coverage, double mu, double var)
{
    if (!(var > 0.0))
        return mu;
    double w = coverage < 1e-9 ? 1e-9 : coverage > 1.0 - 1e-9 ? 1.0 - 1e-9 : coverage;
    /* erf has no inverse in C11: bisection on the monotonic eq. 6, 2^-100 of the bracket
     * (more than double precision), so the result does not depend on a starting guess. */
    double sd = sqrt(var), lo = mu - 10.0 * sd, hi = mu + 10.0 * sd;
    for (int it = 0; it < 100; it++) {
        double mid = 0.5 * (lo + hi);
        if (whitecap_dupuy_coverage(mid, mu, var) < w)
            lo = mid;
        else
            hi = mid;
    }
    return 0.5 * (lo + hi);
}
