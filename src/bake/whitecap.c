#include "bake/whitecap.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/seastate.h"

/* W = a U^b of a model; 0 for an unknown one */
static int model_fit(int model, double *a, double *b)
{
    switch (model) {
    case WHITECAP_DEFAULT:
    case WHITECAP_MOM80:   /* Tessendorf 2023 eq. 14 (Monahan & O'Muircheartaigh 1980) */
        *a = 3.84e-6;
        *b = 3.41;
        return 1;
    case WHITECAP_WU88:    /* Wu 1988 */
        *a = 2.0e-6;
        *b = 3.75;
        return 1;
    default:
        return 0;
    }
}

double whitecap_model_exponent(int model)
{
    double a, b;
    return model_fit(model, &a, &b) ? b : NAN;
}

double whitecap_model_fraction(int model, double wind_speed_mps)
{
    double a, b;
    if (!model_fit(model, &a, &b))
        return NAN;
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

/* ---- foam memory and sums of independent patterns ---------------------------------------- */

int whitecap_memory_loop(const float *k, size_t texels, int frames, float step, float *m,
                         struct swell_err *err)
{
    float *run = malloc(texels * sizeof *run);
    if (!run)
        return swell_fail(err, SWELL_E_NOMEM, "foam memory: cannot allocate %zu floats", texels);
    for (size_t i = 0; i < texels; i++)
        run[i] = INFINITY;
    /* Pass 1 from m = +inf before frame 0 reaches frame F-1 with every n < F; pass 2 then sees
     * every k(f - n) + n step with n < F around the loop (larger n only add whole loops of
     * step >= 0, never lower). So pass 2 writes the steady state exactly. */
    for (int pass = 0; pass < 2; pass++)
        for (int f = 0; f < frames; f++) {
            const float *kf = k + (size_t)f * texels;
            float *mf = m + (size_t)f * texels;
            for (size_t i = 0; i < texels; i++) {
                float v = run[i] + step;
                run[i] = kf[i] < v ? kf[i] : v;
                if (pass)
                    mf[i] = run[i];
            }
        }
    free(run);
    return 0;
}

void whitecap_sum_destroy(struct whitecap_sum *s)
{
    if (!s)
        return;
    free(s->cum);
    memset(s, 0, sizeof *s);
}

int whitecap_sum_create(const float *const *samples, const size_t *counts, int n, double offset,
                        struct whitecap_sum *out, struct swell_err *err)
{
    memset(out, 0, sizeof *out);
    if (n < 1 || n > SWELL_WHITECAP_SUM_MAX)
        return swell_fail(err, SWELL_E_ARG, "whitecap sum: %d variables, need 1..%d", n,
                          SWELL_WHITECAP_SUM_MAX);
    double lo[SWELL_WHITECAP_SUM_MAX], hi[SWELL_WHITECAP_SUM_MAX], span = 0.0;
    for (int v = 0; v < n; v++) {
        if (counts[v] == 0)
            return swell_fail(err, SWELL_E_ARG, "whitecap sum: variable %d has no sample", v);
        lo[v] = hi[v] = samples[v][0];
        for (size_t i = 0; i < counts[v]; i++) {
            double x = samples[v][i];
            if (!isfinite(x))
                return swell_fail(err, SWELL_E_ARG,
                                  "whitecap sum: sample %zu of variable %d is %g; the Jacobian "
                                  "fields are not finite (check the spectrum and choppiness)",
                                  i, v, x);
            lo[v] = x < lo[v] ? x : lo[v];
            hi[v] = x > hi[v] ? x : hi[v];
        }
        span = hi[v] - lo[v] > span ? hi[v] - lo[v] : span;
    }
    double h = span > 0.0 ? span / WHITECAP_SUM_BINS : 1.0;
    int points = 1;
    for (int v = 0; v < n; v++)
        points += (int)ceil((hi[v] - lo[v]) / h) + 1;
    double *acc = calloc((size_t)points, sizeof *acc);
    double *nxt = calloc((size_t)points, sizeof *nxt);
    double *one = calloc(WHITECAP_SUM_BINS + 3, sizeof *one);
    if (!acc || !nxt || !one) {
        free(acc);
        free(nxt);
        free(one);
        return swell_fail(err, SWELL_E_NOMEM, "whitecap sum: cannot allocate %d grid points",
                          points);
    }
    /* the sum so far sits on the grid offset + sum of the lo's + j h; mass split linearly
     * between the two grid points around each sample, then convolved in */
    acc[0] = 1.0;
    int used = 1;
    double base = offset;
    for (int v = 0; v < n; v++) {
        int pts = (int)ceil((hi[v] - lo[v]) / h) + 2;
        memset(one, 0, (size_t)pts * sizeof *one);
        double w = 1.0 / (double)counts[v];
        for (size_t i = 0; i < counts[v]; i++) {
            double t = (samples[v][i] - lo[v]) / h;
            int j = (int)t;
            j = j < 0 ? 0 : j > pts - 2 ? pts - 2 : j;
            double f = t - j;
            one[j] += w * (1.0 - f);
            one[j + 1] += w * f;
        }
        memset(nxt, 0, (size_t)(used + pts - 1) * sizeof *nxt);
        for (int a = 0; a < used; a++) {
            if (acc[a] == 0.0)
                continue;
            for (int b = 0; b < pts; b++)
                nxt[a + b] += acc[a] * one[b];
        }
        double *t = acc;
        acc = nxt;
        nxt = t;
        used += pts - 1;
        base += lo[v];
    }
    for (int j = 1; j < used; j++)
        acc[j] += acc[j - 1];
    double total = acc[used - 1];
    for (int j = 0; j < used; j++)
        acc[j] /= total;
    free(nxt);
    free(one);
    out->lo = base;
    out->h = h;
    out->points = used;
    out->cum = acc;
    return 0;
}

double whitecap_sum_cdf(const struct whitecap_sum *s, double x)
{
    double t = (x - s->lo) / s->h + 0.5;
    if (!(t > 0.0))
        return 0.0;
    if (t >= s->points)
        return 1.0;
    int j = (int)t;
    double below = j ? s->cum[j - 1] : 0.0;
    return below + (s->cum[j] - below) * (t - j);
}

double whitecap_sum_quantile(const struct whitecap_sum *s, double p)
{
    p = p < 0.0 ? 0.0 : p > 1.0 ? 1.0 : p;
    int a = 0, b = s->points - 1;   /* the smallest j with cum[j] >= p */
    while (a < b) {
        int mid = (a + b) / 2;
        if (s->cum[mid] >= p)
            b = mid;
        else
            a = mid + 1;
    }
    double below = a ? s->cum[a - 1] : 0.0, mass = s->cum[a] - below;
    double f = mass > 0.0 ? (p - below) / mass : 0.0;
    return s->lo + (a - 0.5 + f) * s->h;
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
