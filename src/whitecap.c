#include "whitecap.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

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

/* ---- sub-texel breaking coverage ------------------------------------------------------- */

/* The sub x sub points of texel (x, y): offsets (2s + 1 - sub) / (2 sub) from its centre, each
 * a bilinear blend of the centre and the neighbour on that side (weight |offset|), separable:
 * along x on the three rows, then along y. Offset 0 (sub = 1, odd sub's middle) gives the
 * centre's own value exactly. */
static void sub_samples(const float *lm, int w, int h, int x, int y, int sub, float *out)
{
    int xm = x > 0 ? x - 1 : w - 1, xp = x + 1 < w ? x + 1 : 0;
    int ym = y > 0 ? y - 1 : h - 1, yp = y + 1 < h ? y + 1 : 0;
    const float *row[3] = { lm + (size_t)ym * (size_t)w, lm + (size_t)y * (size_t)w,
                            lm + (size_t)yp * (size_t)w };
    float hz[3][WHITECAP_SUB_MAX];
    for (int s = 0; s < sub; s++) {
        float o = (float)(2 * s + 1 - sub) / (float)(2 * sub);
        float wt = fabsf(o);
        int xn = o < 0.0f ? xm : xp;
        for (int r = 0; r < 3; r++)
            hz[r][s] = row[r][x] + wt * (row[r][xn] - row[r][x]);
    }
    for (int t = 0; t < sub; t++) {
        float o = (float)(2 * t + 1 - sub) / (float)(2 * sub);
        float wt = fabsf(o);
        int rn = o < 0.0f ? 0 : 2;
        for (int s = 0; s < sub; s++)
            out[t * sub + s] = hz[1][s] + wt * (hz[rn][s] - hz[1][s]);
    }
}

int whitecap_cover_create(const struct whitecap_cover_desc *desc, struct whitecap_cover *out,
                          struct swell_err *err)
{
    memset(out, 0, sizeof *out);
    struct whitecap_cover_desc d = *desc;
    if (d.sub == 0)
        d.sub = WHITECAP_SUB_DEFAULT;
    if (!d.lambda_min || d.width < 1 || d.height < 1 || d.frames < 1)
        return swell_fail(err, SWELL_E_ARG,
                          "whitecap cover: %d x %d texels x %d frames%s; need a lambda_min "
                          "table of at least 1 x 1 x 1", d.width, d.height, d.frames,
                          d.lambda_min ? "" : " and no samples");
    if (d.sub < 1 || d.sub > WHITECAP_SUB_MAX)
        return swell_fail(err, SWELL_E_ARG,
                          "whitecap cover: %d sub-samples per texel side, need 1..%d (0 = %d)",
                          d.sub, WHITECAP_SUB_MAX, WHITECAP_SUB_DEFAULT);
    size_t texels = (size_t)d.width * (size_t)d.height, count = texels * (size_t)d.frames;
    for (size_t i = 0; i < count; i++)
        if (isnan(d.lambda_min[i]))
            return swell_fail(err, SWELL_E_ARG,
                              "whitecap cover: lambda_min of texel %zu, frame %zu is NaN; the "
                              "Jacobian fields hold NaN (check the spectrum and choppiness)",
                              i % texels, i / texels);
    out->range = malloc(2 * count * sizeof *out->range);
    if (!out->range)
        return swell_fail(err, SWELL_E_NOMEM,
                          "whitecap cover: cannot allocate %zu floats of sub-sample ranges",
                          2 * count);
    out->desc = d;
    float smp[WHITECAP_SUB_MAX * WHITECAP_SUB_MAX];
    int n = d.sub * d.sub;
    for (int f = 0; f < d.frames; f++) {
        const float *lm = d.lambda_min + (size_t)f * texels;
        float *rg = out->range + 2 * (size_t)f * texels;
        for (int y = 0; y < d.height; y++)
            for (int x = 0; x < d.width; x++) {
                sub_samples(lm, d.width, d.height, x, y, d.sub, smp);
                float lo = smp[0], hi = smp[0];
                for (int k = 1; k < n; k++) {
                    lo = fminf(lo, smp[k]);
                    hi = fmaxf(hi, smp[k]);
                }
                size_t i = (size_t)y * (size_t)d.width + (size_t)x;
                rg[2 * i] = lo;
                rg[2 * i + 1] = hi;
            }
    }
    return 0;
}

void whitecap_cover_destroy(struct whitecap_cover *c)
{
    if (!c)
        return;
    free(c->range);
    memset(c, 0, sizeof *c);
}

/* B of texel i of frame f: 0 or 1 from its sub-sample range unless lambda_t falls inside it. */
static float cover_texel(const struct whitecap_cover *c, int f, size_t i, float lambda_t)
{
    const struct whitecap_cover_desc *d = &c->desc;
    size_t texels = (size_t)d->width * (size_t)d->height;
    const float *rg = c->range + 2 * ((size_t)f * texels + i);
    if (!(lambda_t > rg[0]))
        return 0.0f;
    if (lambda_t > rg[1])
        return 1.0f;
    float smp[WHITECAP_SUB_MAX * WHITECAP_SUB_MAX];
    int n = d->sub * d->sub, below = 0;
    sub_samples(d->lambda_min + (size_t)f * texels, d->width, d->height,
                (int)(i % (size_t)d->width), (int)(i / (size_t)d->width), d->sub, smp);
    for (int k = 0; k < n; k++)
        below += smp[k] < lambda_t;
    return (float)below / (float)n;
}

void whitecap_cover_frame(const struct whitecap_cover *c, int frame, float lambda_t, float *b)
{
    size_t texels = (size_t)c->desc.width * (size_t)c->desc.height;
    for (size_t i = 0; i < texels; i++)
        b[i] = cover_texel(c, frame, i, lambda_t);
}

double whitecap_cover_mean(const struct whitecap_cover *c, float lambda_t)
{
    size_t texels = (size_t)c->desc.width * (size_t)c->desc.height;
    double sum = 0.0;
    for (int f = 0; f < c->desc.frames; f++)
        for (size_t i = 0; i < texels; i++)
            sum += cover_texel(c, f, i, lambda_t);
    return sum / ((double)texels * (double)c->desc.frames);
}

void whitecap_cover_extent(const struct whitecap_cover *c, float *lo, float *hi)
{
    size_t count = (size_t)c->desc.width * (size_t)c->desc.height * (size_t)c->desc.frames;
    *lo = c->range[0];
    *hi = c->range[1];
    for (size_t i = 1; i < count; i++) {
        *lo = fminf(*lo, c->range[2 * i]);
        *hi = fmaxf(*hi, c->range[2 * i + 1]);
    }
}

/* One update of eq. 8 with Theta -> B for every texel of frame f: O' = B + (1 - B) a O. B = 1
 * gives 1 + 0 = 1 and B = 0 gives a O, both exactly (eq. 7's cases), so a binary cover
 * reproduces eq. 7 bit for bit. q, unless NULL, accumulates the product of the (1 - B) a
 * factors. */
static void foam_step(const struct whitecap_cover *c, int f, const float *prev, float *next,
                      float *q, float lambda_t, float decay)
{
    size_t texels = (size_t)c->desc.width * (size_t)c->desc.height;
    for (size_t i = 0; i < texels; i++) {
        float b = cover_texel(c, f, i, lambda_t);
        float keep = (1.0f - b) * decay;
        next[i] = b + keep * prev[i];
        if (q)
            q[i] *= keep;
    }
}

int whitecap_foam_loop(const struct whitecap_cover *c, float lambda_t, float dt_s,
                       float half_life_s, float *opacity, struct swell_err *err)
{
    if (!(dt_s > 0.0f) || !(half_life_s > 0.0f) || !isfinite(dt_s) || !isfinite(half_life_s))
        return swell_fail(err, SWELL_E_ARG,
                          "foam loop: frame step %g s and half-life %g s must be finite and > 0",
                          (double)dt_s, (double)half_life_s);
    float decay = (float)exp2(-(double)dt_s / (double)half_life_s);
    int F = c->desc.frames;
    size_t texels = (size_t)c->desc.width * (size_t)c->desc.height;
    float *last = opacity + (size_t)(F - 1) * texels;
    float *q = malloc(texels * sizeof *q);
    if (!q)
        return swell_fail(err, SWELL_E_NOMEM, "foam loop: cannot allocate %zu floats", texels);

    /* Periodic steady state. Round the loop eq. 8 is affine per texel: from O = x before frame
     * 0, frame F-1 is P + Q x with Q = prod_f (1 - B_f) a <= a^F < 1. Pass 1 runs from x = 0
     * (the paper's initial state), giving P and Q; the fixed point x* = P / (1 - Q) is the
     * frame F-1 value of the periodic state, and pass 2 restarts from it. Where some frame has
     * B = 1, Q = 0 and x* = P exactly; where B = 0 throughout, P = 0 = x*: those texels close
     * the loop bit for bit, as eq. 7's two-pass loop did. */
    for (size_t i = 0; i < texels; i++) {
        last[i] = 0.0f;
        q[i] = 1.0f;
    }
    for (int pass = 0; pass < 2; pass++) {
        for (int f = 0; f < F; f++)
            foam_step(c, f, f ? opacity + (size_t)(f - 1) * texels : last,
                      opacity + (size_t)f * texels, pass ? NULL : q, lambda_t, decay);
        if (pass == 0)
            for (size_t i = 0; i < texels; i++) {
                double x = q[i] > 0.0f ? (double)last[i] / (1.0 - (double)q[i]) : last[i];
                last[i] = x < 1.0 ? (float)x : 1.0f;
            }
    }
    free(q);
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
