/* test_whitecap - Tessendorf, Reinhard, Gao 2023 (lambda_min, eq. 7-9, 11-13, algorithm 1) and
 * Dupuy & Bruneton 2012 eq. 6-7, each against an independent reference written here. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "seastate.h"
#include "whitecap.h"

/* A private generator so the samples do not depend on the C library's rand(). */
struct rng { uint64_t s; };

static double rng_uniform(struct rng *r)   /* (0, 1) */
{
    r->s ^= r->s << 13;
    r->s ^= r->s >> 7;
    r->s ^= r->s << 17;
    return ((double)(r->s >> 11) + 0.5) * (1.0 / 9007199254740992.0);
}

static double rng_gauss(struct rng *r)
{
    double u = rng_uniform(r), v = rng_uniform(r);
    return sqrt(-2.0 * log(u)) * cos(6.283185307179586 * v);
}

/* ---- lambda_min --------------------------------------------------------------------------- */

/* Smallest eigenvalue by power iteration on s I - J (its dominant eigenvalue is s - lambda_min),
 * refined by one Rayleigh quotient; no closed form involved. */
static double ref_lambda_min_power(double a, double b, double d)
{
    double s = fabs(a) + fabs(b) + fabs(d) + 1.0;
    double m00 = s - a, m01 = -b, m11 = s - d;
    double x = 0.6, y = 0.8;
    for (int it = 0; it < 3000; it++) {
        double nx = m00 * x + m01 * y, ny = m01 * x + m11 * y;
        double n = hypot(nx, ny);
        x = nx / n;
        y = ny / n;
    }
    double rq = x * (a * x + b * y) + y * (b * x + d * y);   /* Rayleigh quotient of J */
    return rq;
}

static void test_lambda_min_vs_references(void **state)
{
    (void)state;
    struct rng r = { 0x1234567u };
    for (int i = 0; i < 2000; i++) {
        float jxx = (float)(rng_gauss(&r) * 0.4), jyy = (float)(rng_gauss(&r) * 0.4);
        float jxy = (float)(rng_gauss(&r) * 0.3);
        long double a = 1.0L + jxx, d = 1.0L + jyy, b = jxy;
        /* characteristic polynomial t^2 - tr t + det = 0; the smaller root via the
         * cancellation-free form 2 det / (tr + sqrt(disc)) when tr > 0 */
        long double tr = a + d, det = a * d - b * b, disc = tr * tr - 4.0L * det;
        long double root = disc > 0 ? sqrtl(disc) : 0.0L;
        long double lo = tr > 0 ? 2.0L * det / (tr + root) : 0.5L * (tr - root);
        float got = whitecap_lambda_min(jxx, jyy, jxy);
        assert_true(fabsl((long double)got - lo) <= 2e-6L * (1.0L + fabsl(lo)));
        /* power iteration converges (3000 steps at ratio <= 1 - 0.1 / 10) when the eigenvalues
         * are separated */
        if (root > 0.1L) {
            double p = ref_lambda_min_power((double)a, (double)b, (double)d);
            assert_true(fabs((double)got - p) <= 2e-6 * (1.0 + fabs(p)));
        }
        /* lambda_min is an eigenvalue: det(J - lambda I) = 0, and the smaller one */
        long double res = (a - got) * (d - got) - b * b;
        assert_true(fabsl(res) <= 1e-5L * (1.0L + fabsl(tr) * fabsl(tr)));
        assert_true((long double)got <= 0.5L * tr + 1e-6L);
    }
    /* diagonal: the smaller diagonal entry exactly */
    assert_true(whitecap_lambda_min(0.25f, -0.5f, 0.0f) == 0.5f);
    assert_true(whitecap_lambda_min(0.0f, 0.0f, 0.0f) == 1.0f);
    /* pure shear [[1, c], [c, 1]]: 1 - |c| */
    assert_true(fabsf(whitecap_lambda_min(0.0f, 0.0f, -0.75f) - 0.25f) < 1e-7f);
}

/* ---- wind-speed models ------------------------------------------------------------------ */

static void test_model_fraction(void **state)
{
    (void)state;
    /* hand-evaluated from the published fits: 3.84e-6 * 10^3.41 = 3.84e-6 * 2570.40 and
     * 2.0e-6 * 10^3.75 = 2.0e-6 * 5623.41 */
    assert_true(fabs(whitecap_model_fraction(WHITECAP_MOM80, 10.0) - 0.0098703) < 2e-7);
    assert_true(fabs(whitecap_model_fraction(WHITECAP_DEFAULT, 10.0) - 0.0098703) < 2e-7);
    assert_true(fabs(whitecap_model_fraction(WHITECAP_WU88, 10.0) - 0.0112468) < 2e-7);
    /* U^b scaling: doubling U multiplies W by 2^b */
    double r = whitecap_model_fraction(WHITECAP_MOM80, 12.0) /
               whitecap_model_fraction(WHITECAP_MOM80, 6.0);
    assert_true(fabs(r - exp2(3.41)) < 1e-9 * r);
    for (int m = WHITECAP_MOM80; m < WHITECAP_COUNT; m++) {
        assert_true(whitecap_model_fraction(m, 0.0) == 0.0);
        assert_true(whitecap_model_fraction(m, -3.0) == 0.0);
        assert_true(whitecap_model_fraction(m, NAN) == 0.0);
        assert_true(whitecap_model_fraction(m, 60.0) == 1.0);   /* clamped */
        double prev = 0.0;
        for (double u = 0.5; u <= 60.0; u += 0.5) {
            double w = whitecap_model_fraction(m, u);
            assert_true(w >= prev && w <= 1.0);
            prev = w;
        }
    }
    assert_true(isnan(whitecap_model_fraction(WHITECAP_COUNT, 10.0)));
}

static void test_eq11_eq13(void **state)
{
    (void)state;
    /* algorithm 1's alpha */
    assert_true(fabs(SWELL_WHITECAP_ALPHA - 0.861) < 5e-4);
    assert_true(fabs(SWELL_WHITECAP_ALPHA - exp(-0.15)) < 1e-15);
    for (double w = 0.0; w <= 1.0; w += 0.01) {
        double th = whitecap_breaking_fraction(w, SWELL_WHITECAP_ALPHA);
        assert_true(th >= 0.0 && th <= w + 1e-15);   /* breaking is rarer than foam */
        /* eq. 13 solves eq. 11 */
        double back = th / (1.0 - SWELL_WHITECAP_ALPHA * (1.0 - th));
        assert_true(fabs(back - w) < 1e-12);
        assert_true(fabs(whitecap_ensemble_fraction(th, SWELL_WHITECAP_ALPHA) - w) < 1e-12);
    }
    /* small W: <Theta> ~ W (1 - alpha) */
    double th = whitecap_breaking_fraction(1e-4, 0.861);
    assert_true(fabs(th - 1e-4 * 0.139) < 1e-8);
}

/* ---- threshold from the CDF ------------------------------------------------------------- */

/* Standard normal quantile by Newton on 0.5 erfc(-z / sqrt 2) (independent of the code's
 * bisection in whitecap_dupuy_epsilon). */
static double ref_norm_quantile(double p)
{
    double z = 0.0;
    for (int it = 0; it < 100; it++) {
        double cdf = 0.5 * erfc(-z / sqrt(2.0));
        double pdf = exp(-0.5 * z * z) / sqrt(2.0 * M_PI);
        double step = (cdf - p) / pdf;
        if (step > 1.0) step = 1.0;
        if (step < -1.0) step = -1.0;
        z -= step;
        if (fabs(step) < 1e-14)
            break;
    }
    return z;
}

static int cmp_float_ref(const void *pa, const void *pb)
{
    float a = *(const float *)pa, b = *(const float *)pb;
    return a < b ? -1 : a > b ? 1 : 0;
}

static void test_threshold_gaussian(void **state)
{
    (void)state;
    const size_t n = 200000;
    const double mu = 0.8, sd = 0.1;
    float *x = malloc(n * sizeof *x);
    assert_non_null(x);
    struct rng r = { 42 };
    for (size_t i = 0; i < n; i++)
        x[i] = (float)(mu + sd * rng_gauss(&r));   /* P(x < 0) = Phi(-8): none drawn */
    float *sorted = malloc(n * sizeof *sorted);
    assert_non_null(sorted);
    memcpy(sorted, x, n * sizeof *x);
    qsort(sorted, n, sizeof *sorted, cmp_float_ref);
    int ties = 0;
    for (size_t i = 1; i < n; i++)
        ties += sorted[i] == sorted[i - 1];
    assert_true(ties > 0);   /* the tie rule below is exercised */
    const double fr[] = { 0.0005, 0.002, 0.01, 0.05, 0.2, 0.5, 0.9 };
    for (size_t j = 0; j < sizeof fr / sizeof fr[0]; j++) {
        struct swell_err err = { 0 };
        float lt = 0.0f;
        assert_int_equal(whitecap_threshold(x, n, fr[j], &lt, &err), 0);
        /* empirical: round(f n) samples below, by brute-force count; a tie of float samples
         * across the boundary cannot be split and goes above (the header's rule) */
        size_t k = (size_t)llround(fr[j] * (double)n), below = 0, below_k = 0;
        float sk = sorted[k];
        for (size_t i = 0; i < n; i++) {
            below += x[i] < lt;
            below_k += x[i] < sk;
        }
        assert_true(lt <= sk);
        assert_int_equal(below, below_k);
        assert_true(below_k <= k && below_k + 2 >= k);
        if (sorted[k - 1] < sk)
            assert_int_equal(below, k);
        assert_true(fabs(whitecap_cdf(x, n, lt) - fr[j]) <= 2.5 / (double)n);
        /* analytic quantile, within 5 standard errors of the sample quantile:
         * sqrt(f (1 - f) / n) / pdf(q) */
        double z = ref_norm_quantile(fr[j]);
        double q = mu + sd * z;
        double se = sqrt(fr[j] * (1.0 - fr[j]) / (double)n) /
                    (exp(-0.5 * z * z) / (sd * sqrt(2.0 * M_PI)));
        assert_true(fabs((double)lt - q) < 5.0 * se);
    }
    free(x);
    free(sorted);
}

static void test_threshold_edges_and_errors(void **state)
{
    (void)state;
    struct swell_err err = { 0 };
    float lt = 0.0f;
    /* negative samples are outside eq. 12 and do not move the threshold */
    const float with_neg[] = { -0.3f, 0.1f, -2.0f, 0.2f, 0.3f, 0.4f, -0.01f, 0.5f };
    const float pos[] = { 0.1f, 0.2f, 0.3f, 0.4f, 0.5f };
    float a = 0.0f, b = 0.0f;
    assert_int_equal(whitecap_threshold(with_neg, 8, 0.4, &a, &err), 0);
    assert_int_equal(whitecap_threshold(pos, 5, 0.4, &b, &err), 0);
    assert_true(a == b);
    assert_true(a > 0.2f && a < 0.3f);   /* two of five below */
    assert_true(whitecap_cdf(with_neg, 8, a) == 0.4);
    /* 0 and 1 */
    assert_int_equal(whitecap_threshold(pos, 5, 0.0, &lt, &err), 0);
    assert_true(whitecap_cdf(pos, 5, lt) == 0.0);
    assert_int_equal(whitecap_threshold(pos, 5, 1.0, &lt, &err), 0);
    assert_true(whitecap_cdf(pos, 5, lt) == 1.0);
    /* errors */
    assert_int_equal(whitecap_threshold(pos, 5, 1.5, &lt, &err), SWELL_E_ARG);
    assert_int_equal(whitecap_threshold(pos, 5, NAN, &lt, &err), SWELL_E_ARG);
    const float neg[] = { -1.0f, -0.5f };
    assert_int_equal(whitecap_threshold(neg, 2, 0.1, &lt, &err), SWELL_E_ARG);
    assert_true(strlen(err.msg) > 0);
    const float bad[] = { 0.5f, NAN };
    assert_int_equal(whitecap_threshold(bad, 2, 0.1, &lt, &err), SWELL_E_ARG);
    assert_int_equal(whitecap_threshold(pos, 0, 0.1, &lt, &err), SWELL_E_ARG);
}

/* ---- foam loop (eq. 7-8) ---------------------------------------------------------------- */

/* A point-sampled cover (sub = 1: eq. 7's binary Theta at each texel) of texels unrelated to
 * their neighbours, laid out as one row. */
static struct whitecap_cover point_cover(const float *lm, int F, size_t texels)
{
    struct whitecap_cover c;
    struct whitecap_cover_desc d = { .lambda_min = lm, .width = (int)texels, .height = 1,
                                     .frames = F, .sub = 1 };
    struct swell_err err = { 0 };
    assert_int_equal(whitecap_cover_create(&d, &c, &err), 0);
    return c;
}

static int foam_loop_points(const float *lm, int F, size_t texels, float lt, float dt, float half,
                            float *op, struct swell_err *err)
{
    struct whitecap_cover c = point_cover(lm, F, texels);
    int r = whitecap_foam_loop(&c, lt, dt, half, op, err);
    whitecap_cover_destroy(&c);
    return r;
}

/* Eq. 8 written out with Theta -> b (b = 0/1 is eq. 8 itself), run from O = 0 round the loop
 * until it stops changing. */
static void ref_foam_brute_b(const double *b, int F, size_t texels, double a, double *o)
{
    double *cur = calloc(texels, sizeof *cur);
    assert_non_null(cur);
    for (int loop = 0; loop < 400; loop++)
        for (int f = 0; f < F; f++)
            for (size_t i = 0; i < texels; i++) {
                double th = b[(size_t)f * texels + i];
                cur[i] = cur[i] * a + th * (1.0 - cur[i] * a);
                o[(size_t)f * texels + i] = cur[i];
            }
    free(cur);
}

static void ref_foam_brute(const float *lm, int F, size_t texels, float lt, double a, double *o)
{
    double *b = malloc((size_t)F * texels * sizeof *b);
    assert_non_null(b);
    for (size_t i = 0; i < (size_t)F * texels; i++)
        b[i] = lm[i] < lt ? 1.0 : 0.0;
    ref_foam_brute_b(b, F, texels, a, o);
    free(b);
}

static void test_foam_steady_state(void **state)
{
    (void)state;
    const int F = 16;
    const size_t texels = 600;
    const float dt = 0.25f, half = 2.0f, lt = 0.35f;
    float *lm = malloc((size_t)F * texels * sizeof *lm);
    float *op = malloc((size_t)F * texels * sizeof *op);
    double *ref = malloc((size_t)F * texels * sizeof *ref);
    assert_true(lm && op && ref);
    struct rng r = { 7 };
    for (size_t i = 0; i < (size_t)F * texels; i++)
        lm[i] = (float)(0.7 + 0.15 * rng_gauss(&r));   /* ~1% breaking, many texels never */
    struct swell_err err = { 0 };
    assert_int_equal(foam_loop_points(lm, F, texels, lt, dt, half, op, &err), 0);
    double a = pow(0.5, dt / half);
    ref_foam_brute(lm, F, texels, lt, a, ref);
    size_t never = 0;
    for (size_t i = 0; i < texels; i++) {
        /* seamless: one more eq. 7 step from frame F-1 reproduces frame 0 bit for bit */
        float next = lm[i] < lt ? 1.0f : op[(size_t)(F - 1) * texels + i] * (float)a;
        assert_true(next == op[i]);
        int broke = 0;
        for (int f = 0; f < F; f++) {
            size_t k = (size_t)f * texels + i;
            assert_true(op[k] >= 0.0f && op[k] <= 1.0f);
            assert_true(fabs(op[k] - ref[k]) < 1e-5);
            broke |= lm[k] < lt;
        }
        never += !broke;
    }
    assert_true(never > 0 && never < texels);   /* both kinds of texel were exercised */
    free(lm);
    free(op);
    free(ref);
}

static void test_foam_impulse_half_life(void **state)
{
    (void)state;
    /* one texel breaks at frame 0 only: O(t) = 2^(-t / half-life); halves after one half-life */
    const int F = 40;
    const float dt = 0.1f, half = 1.0f;
    float lm[40], op[40];
    for (int f = 0; f < F; f++)
        lm[f] = 0.9f;
    lm[0] = 0.1f;
    struct swell_err err = { 0 };
    assert_int_equal(foam_loop_points(lm, F, 1, 0.5f, dt, half, op, &err), 0);
    assert_true(op[0] == 1.0f);
    assert_true(fabsf(op[10] - 0.5f) < 1e-5f);    /* t = 1 s = one half-life */
    assert_true(fabsf(op[20] - 0.25f) < 1e-5f);
    for (int f = 0; f < F; f++)
        assert_true(fabs(op[f] - exp2(-f * 0.1)) < 1e-5);
    /* never breaking: zero; always breaking: one */
    for (int f = 0; f < F; f++)
        lm[f] = 0.9f;
    assert_int_equal(foam_loop_points(lm, F, 1, 0.5f, dt, half, op, &err), 0);
    for (int f = 0; f < F; f++)
        assert_true(op[f] == 0.0f);
    assert_int_equal(foam_loop_points(lm, F, 1, 1.0f, dt, half, op, &err), 0);
    for (int f = 0; f < F; f++)
        assert_true(op[f] == 1.0f);
    /* a one-frame loop */
    assert_int_equal(foam_loop_points(lm, 1, 1, 1.0f, dt, half, op, &err), 0);
    assert_true(op[0] == 1.0f);
    /* bad arguments */
    struct whitecap_cover c = point_cover(lm, F, 1);
    assert_int_equal(whitecap_foam_loop(&c, 0.5f, 0.0f, half, op, &err), SWELL_E_ARG);
    assert_int_equal(whitecap_foam_loop(&c, 0.5f, dt, -1.0f, op, &err), SWELL_E_ARG);
    assert_int_equal(whitecap_foam_loop(&c, 0.5f, dt, NAN, op, &err), SWELL_E_ARG);
    whitecap_cover_destroy(&c);
    struct whitecap_cover_desc d = { .lambda_min = lm, .width = 1, .height = 1, .frames = 0 };
    assert_int_equal(whitecap_cover_create(&d, &c, &err), SWELL_E_ARG);
    d.frames = F;
    d.sub = WHITECAP_SUB_MAX + 1;
    assert_int_equal(whitecap_cover_create(&d, &c, &err), SWELL_E_ARG);
    d.sub = -1;
    assert_int_equal(whitecap_cover_create(&d, &c, &err), SWELL_E_ARG);
    d.sub = 0;
    lm[7] = NAN;
    assert_int_equal(whitecap_cover_create(&d, &c, &err), SWELL_E_ARG);
    assert_non_null(strstr(err.msg, "frame 7"));
    assert_null(c.range);
    whitecap_cover_destroy(&c);   /* a failed cover */
}

/* With independent breaking events of probability p per frame, O(t) is independent of the next
 * Theta, so eq. 10's factorisation is exact and eq. 11 gives the mean opacity with the
 * per-frame alpha. The loop's measured fraction (eq. 9) must match it. */
static void test_foam_fraction_matches_eq11(void **state)
{
    (void)state;
    const int F = 64;
    const size_t texels = 8000;
    const float dt = 0.1f, half = 0.5f;
    const double p = 0.05;
    float *lm = malloc((size_t)F * texels * sizeof *lm);
    float *op = malloc((size_t)F * texels * sizeof *op);
    assert_true(lm && op);
    struct rng r = { 99 };
    for (size_t i = 0; i < (size_t)F * texels; i++)
        lm[i] = (float)rng_uniform(&r);
    struct swell_err err = { 0 };
    assert_int_equal(foam_loop_points(lm, F, texels, (float)p, dt, half, op, &err), 0);
    double a = exp2(-dt / half);
    double expect = p / (1.0 - a * (1.0 - p));
    double got = whitecap_measured_fraction(op, (size_t)F * texels);
    assert_true(fabs(got - expect) < 0.01 * expect + 2e-3);
    free(lm);
    free(op);
}

/* ---- sub-texel coverage ------------------------------------------------------------------ */

/* Bilinear reconstruction between texel centres of a periodic w x h table at texel coordinates
 * (u, v) (texel (x, y)'s centre at (x, y)): written out directly, no shared code. */
static double ref_bilinear(const float *lm, int w, int h, double u, double v)
{
    double fu = floor(u), fv = floor(v);
    double tu = u - fu, tv = v - fv;
    int x0 = (((int)fu % w) + w) % w, y0 = (((int)fv % h) + h) % h;
    int x1 = (x0 + 1) % w, y1 = (y0 + 1) % h;
    return (1 - tv) * ((1 - tu) * lm[y0 * w + x0] + tu * lm[y0 * w + x1]) +
           tv * ((1 - tu) * lm[y1 * w + x0] + tu * lm[y1 * w + x1]);
}

/* Share of texel (x, y)'s unit square below lt on an m x m midpoint grid. */
static double ref_coverage(const float *lm, int w, int h, int x, int y, double lt, int m)
{
    int below = 0;
    for (int j = 0; j < m; j++)
        for (int i = 0; i < m; i++)
            below += ref_bilinear(lm, w, h, x - 0.5 + (i + 0.5) / m, y - 0.5 + (j + 0.5) / m) < lt;
    return (double)below / (double)(m * m);
}

static struct whitecap_cover make_cover(const float *lm, int w, int h, int F, int sub)
{
    struct whitecap_cover c;
    struct whitecap_cover_desc d = { .lambda_min = lm, .width = w, .height = h, .frames = F,
                                     .sub = sub };
    struct swell_err err = { 0 };
    assert_int_equal(whitecap_cover_create(&d, &c, &err), 0);
    return c;
}

/* One breaking texel in a flat field: the bilinear reconstruction is a pyramid, breaking where
 * (1 - |x|)(1 - |y|) > c = (0.9 - lt) / 0.4. Its area, 4 ((1 - c) + c ln c), is shared out
 * over the texel and its neighbours, falling off with distance; eq. 7's binary test puts it
 * all on one texel. The dip sits at the corner so its neighbours wrap round the table. */
static void test_cover_single_texel(void **state)
{
    (void)state;
    enum { N = 8 };
    float lm[N * N];
    for (int i = 0; i < N * N; i++)
        lm[i] = 0.9f;
    lm[0] = 0.5f;
    struct whitecap_cover c4 = make_cover(lm, N, N, 1, 0), c1 = make_cover(lm, N, N, 1, 1);
    assert_int_equal(c4.desc.sub, WHITECAP_SUB_DEFAULT);
    float b[N * N], b1[N * N];
    /* lt = 0.85 (c = 1/8): 4 x 4 midpoints give centre 1, edge neighbours 4/16, corners 1/16 */
    whitecap_cover_frame(&c4, 0, 0.85f, b);
    whitecap_cover_frame(&c1, 0, 0.85f, b1);
    assert_true(b[0] == 1.0f);
    int edge[4] = { 1, N - 1, N, (N - 1) * N }, corner[4] = { N + 1, N + N - 1,
                    (N - 1) * N + 1, N * N - 1 };
    for (int k = 0; k < 4; k++) {
        assert_true(b[edge[k]] == 0.25f);
        assert_true(b[corner[k]] == 1.0f / 16.0f);
        assert_true(b1[edge[k]] == 0.0f && b1[corner[k]] == 0.0f);
    }
    double sum = 0.0, sum1 = 0.0;
    for (int i = 0; i < N * N; i++) {
        sum += b[i];
        sum1 += b1[i];
        int x = i % N, y = i / N;
        int dx = x < N - x ? x : N - x, dy = y < N - y ? y : N - y;
        if (dx > 1 || dy > 1)
            assert_true(b[i] == 0.0f);
        /* against a 64 x 64 midpoint reference of the same bilinear field */
        assert_true(fabs(b[i] - ref_coverage(lm, N, N, x, y, 0.85, 64)) <= 0.125);
    }
    assert_true(sum1 == 1.0);
    /* the total is the pyramid's breaking area, for thresholds across its range */
    for (float lt = 0.55f; lt < 0.9f; lt += 0.05f) {
        double cc = (0.9 - lt) / 0.4, area = 4.0 * ((1.0 - cc) + cc * log(cc));
        whitecap_cover_frame(&c4, 0, lt, b);
        sum = 0.0;
        for (int i = 0; i < N * N; i++) {
            sum += b[i];
            assert_true(b[i] >= 0.0f && b[i] <= b[0]);   /* highest at the dip */
        }
        /* the 4 x 4 midpoint rule's own error on this pyramid is up to 0.14 + 0.09 area */
        if (fabs(sum - area) > 0.15 + 0.1 * area)
            fail_msg("lt %.2f: coverage sums to %.4f, the pyramid's area is %.4f", lt, sum, area);
        assert_true(fabs(whitecap_cover_mean(&c4, lt) - sum / (N * N)) < 1e-12);
    }
    float lo, hi;
    whitecap_cover_extent(&c4, &lo, &hi);
    assert_true(fabsf(lo - (0.9f - 0.4f * 49.0f / 64.0f)) < 1e-6f && hi == 0.9f);   /* (1/8, 1/8) */
    whitecap_cover_destroy(&c4);
    whitecap_cover_destroy(&c1);
}

/* A smooth random periodic field (a few Fourier modes): every texel's B equals the share of its
 * own 4 x 4 midpoints below lt (independent bilinear reference; 1/16 allowed for a sample on the
 * threshold rounding the other way) and stays within 0.1 of a 32 x 32 reference on average
 * better than the binary test does. */
static void fill_smooth(float *lm, int w, int h, int F, struct rng *r, double amp)
{
    enum { MODES = 6 };
    double kx[MODES], ky[MODES], ph[MODES], om[MODES], am[MODES];
    for (int m = 0; m < MODES; m++) {
        kx[m] = 2 * M_PI * (1 + (int)(rng_uniform(r) * 4)) / w;
        ky[m] = 2 * M_PI * ((int)(rng_uniform(r) * 7) - 3) / h;
        ph[m] = 2 * M_PI * rng_uniform(r);
        om[m] = 2 * M_PI * (1 + (int)(rng_uniform(r) * 2)) / F;
        am[m] = amp * (0.5 + rng_uniform(r)) / MODES;
    }
    for (int f = 0; f < F; f++)
        for (int y = 0; y < h; y++)
            for (int x = 0; x < w; x++) {
                double v = 0.8;
                for (int m = 0; m < MODES; m++)
                    v += am[m] * cos(kx[m] * x + ky[m] * y - om[m] * f + ph[m]);
                lm[((size_t)f * h + y) * w + x] = (float)v;
            }
}

static void test_cover_vs_reference(void **state)
{
    (void)state;
    enum { W = 32, H = 16 };
    float lm[W * H];
    struct rng r = { 31 };
    fill_smooth(lm, W, H, 1, &r, 0.6);
    struct whitecap_cover c4 = make_cover(lm, W, H, 1, 4), c1 = make_cover(lm, W, H, 1, 1);
    float b[W * H], b1[W * H];
    const float lt = 0.6f;
    whitecap_cover_frame(&c4, 0, lt, b);
    whitecap_cover_frame(&c1, 0, lt, b1);
    double err4 = 0.0, err1 = 0.0;
    size_t partial = 0, edge = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            float v = b[y * W + x];
            assert_true(fabs(v - ref_coverage(lm, W, H, x, y, lt, 4)) <= 1.0 / 16.0 + 1e-9);
            double fine = ref_coverage(lm, W, H, x, y, lt, 32);
            if (fine > 0.0 && fine < 1.0) {
                edge++;
                err4 += fabs(v - fine);
                err1 += fabs(b1[y * W + x] - fine);
                partial += v > 0.0f && v < 1.0f;
            }
        }
    print_message("%zu edge texels: %zu partial; mean |B - area|: 4x4 %.4f, binary %.4f\n",
                  edge, partial, err4 / edge, err1 / edge);
    assert_true(edge > 20);
    assert_true(partial > edge / 2);
    assert_true(err4 / edge < 0.1 && err4 < 0.3 * err1);
    whitecap_cover_destroy(&c4);
    whitecap_cover_destroy(&c1);
}

/* Eq. 8 with fractional B: the loop against eq. 8 brute-forced to its steady state with the
 * same B, seamless, in [0, 1]. A long half-life keeps a^F near 1, so texels that only ever see
 * partial coverage remember their start: a fixed-count restart from O = 0 would not close. */
static void test_foam_fractional_steady_state(void **state)
{
    (void)state;
    enum { W = 32, H = 32, F = 8 };
    const size_t texels = W * H;
    const float dt = 0.1f, half = 2.0f, lt = 0.55f;
    float *lm = malloc(F * texels * sizeof *lm), *bf = malloc(F * texels * sizeof *bf);
    float *op = malloc(F * texels * sizeof *op);
    double *b = malloc(F * texels * sizeof *b), *ref = malloc(F * texels * sizeof *ref);
    assert_true(lm && bf && op && b && ref);
    struct rng r = { 5 };
    fill_smooth(lm, W, H, F, &r, 0.6);
    struct whitecap_cover c = make_cover(lm, W, H, F, 0);
    for (int f = 0; f < F; f++)
        whitecap_cover_frame(&c, f, lt, bf + (size_t)f * texels);
    for (size_t i = 0; i < F * texels; i++)
        b[i] = bf[i];
    struct swell_err err = { 0 };
    assert_int_equal(whitecap_foam_loop(&c, lt, dt, half, op, &err), 0);
    double a = exp2(-dt / half);
    ref_foam_brute_b(b, F, texels, a, ref);
    size_t only_partial = 0;
    for (size_t i = 0; i < texels; i++) {
        double next = b[i] + (1.0 - b[i]) * a * op[(F - 1) * texels + i];
        assert_true(fabs(next - op[i]) < 1e-6);
        int full = 0, part = 0;
        for (int f = 0; f < F; f++) {
            size_t k = (size_t)f * texels + i;
            assert_true(op[k] >= 0.0f && op[k] <= 1.0f);
            if (fabs(op[k] - ref[k]) > 1e-5)
                fail_msg("texel %zu frame %d: %.7f, eq. 8 gives %.7f", i, f, op[k], ref[k]);
            full |= b[k] == 1.0;
            part |= b[k] > 0.0 && b[k] < 1.0;
        }
        only_partial += part && !full;
    }
    assert_true(only_partial > 20);
    free(lm);
    free(bf);
    free(op);
    free(b);
    free(ref);
    whitecap_cover_destroy(&c);
}

/* Eq. 10-11 with B for Theta: B at frame t is independent of the opacity before it, so the
 * measured fraction (eq. 9) is <B> / (1 - a (1 - <B>)) with <B> the sub-sample CDF
 * (whitecap_cover_mean) - not the texel-centre CDF, which the bilinear reconstruction narrows:
 * here the two predictions differ by more than half, so the threshold must come from the
 * sub-samples. */
static void test_cover_eq11(void **state)
{
    (void)state;
    enum { W = 64, H = 64, F = 48 };
    const size_t texels = W * H, count = F * texels;
    const float dt = 0.1f, half = 0.5f, lt = 0.08f;
    float *lm = malloc(count * sizeof *lm), *op = malloc(count * sizeof *op);
    assert_true(lm && op);
    struct rng r = { 77 };
    for (size_t i = 0; i < count; i++)
        lm[i] = (float)rng_uniform(&r);   /* independent texels and frames */
    struct whitecap_cover c = make_cover(lm, W, H, F, 0);
    struct swell_err err = { 0 };
    assert_int_equal(whitecap_foam_loop(&c, lt, dt, half, op, &err), 0);
    double a = exp2(-dt / half);
    double theta_sub = whitecap_cover_mean(&c, lt), theta_pt = whitecap_cdf(lm, count, lt);
    double w_sub = whitecap_ensemble_fraction(theta_sub, a);
    double w_pt = whitecap_ensemble_fraction(theta_pt, a);
    double got = whitecap_measured_fraction(op, count);
    print_message("eq. 9 %.5f; eq. 11 from sub-samples %.5f, from texel centres %.5f\n", got,
                  w_sub, w_pt);
    assert_true(fabs(got - w_sub) < 0.03 * w_sub);
    assert_true(fabs(got - w_pt) > 0.5 * got);
    free(lm);
    free(op);
    whitecap_cover_destroy(&c);
}

/* A breaking front crossing the table: the foam's edge texels (some but not all of their area
 * breaking now) hold partial opacity instead of eq. 7's exact 1 / exact decayed values, and
 * the binary test's share of opacities that are exactly 0 or 1 there drops. */
static void test_foam_edges_soften(void **state)
{
    (void)state;
    enum { W = 32, H = 32, F = 16 };
    const size_t texels = W * H;
    float *lm = malloc(F * texels * sizeof *lm), *op4 = malloc(F * texels * sizeof *op4);
    float *op1 = malloc(F * texels * sizeof *op1);
    assert_true(lm && op4 && op1);
    struct rng r = { 11 };
    fill_smooth(lm, W, H, F, &r, 0.6);
    struct whitecap_cover c4 = make_cover(lm, W, H, F, 0), c1 = make_cover(lm, W, H, F, 1);
    struct swell_err err = { 0 };
    const float lt = 0.5f;
    assert_int_equal(whitecap_foam_loop(&c4, lt, 0.1f, 0.4f, op4, &err), 0);
    assert_int_equal(whitecap_foam_loop(&c1, lt, 0.1f, 0.4f, op1, &err), 0);
    size_t edge = 0, hard4 = 0, hard1 = 0;
    for (int f = 0; f < F; f++)
        for (size_t i = 0; i < texels; i++) {
            double fine = ref_coverage(lm + (size_t)f * texels, W, H, (int)(i % W),
                                       (int)(i / W), lt, 16);
            if (fine <= 0.0 || fine >= 1.0)
                continue;
            float v4 = op4[(size_t)f * texels + i], v1 = op1[(size_t)f * texels + i];
            edge++;
            hard4 += v4 == 0.0f || v4 == 1.0f;
            hard1 += v1 == 0.0f || v1 == 1.0f;
        }
    print_message("%zu breaking-edge texels: exactly 0 or 1 %.3f (binary) -> %.3f (4x4)\n",
                  edge, (double)hard1 / edge, (double)hard4 / edge);
    assert_true(edge > 100);
    assert_true(hard1 > edge / 3);
    assert_true(hard4 * 4 < hard1);
    /* eq. 9 on the same threshold barely moves: the coverage redistributes the foam */
    double w4 = whitecap_measured_fraction(op4, F * texels);
    double w1 = whitecap_measured_fraction(op1, F * texels);
    assert_true(fabs(w4 - w1) < 0.25 * w1);
    free(lm);
    free(op4);
    free(op1);
    whitecap_cover_destroy(&c4);
    whitecap_cover_destroy(&c1);
}

static void test_measured_fraction(void **state)
{
    (void)state;
    /* 64 x 64: 16 rows full foam, 16 rows half opacity, the rest clear: 1/4 + 1/8 */
    float *o = calloc(64 * 64, sizeof *o);
    assert_non_null(o);
    for (int y = 0; y < 32; y++)
        for (int x = 0; x < 64; x++)
            o[y * 64 + x] = y < 16 ? 1.0f : 0.5f;
    assert_true(whitecap_measured_fraction(o, 64 * 64) == 0.375);
    /* a disc of radius 20 texels: coverage counted independently from its equation */
    size_t inside = 0;
    for (int y = 0; y < 64; y++)
        for (int x = 0; x < 64; x++) {
            int in = (x - 31.5) * (x - 31.5) + (y - 31.5) * (y - 31.5) < 400.0;
            o[y * 64 + x] = in ? 1.0f : 0.0f;
            inside += (size_t)in;
        }
    double w = whitecap_measured_fraction(o, 64 * 64);
    assert_true(w == (double)inside / 4096.0);
    assert_true(fabs(w - M_PI * 400.0 / 4096.0) < 0.01);
    assert_true(whitecap_measured_fraction(o, 0) == 0.0);
    free(o);
}

/* ---- Dupuy & Bruneton 2012 -------------------------------------------------------------- */

static void test_dupuy(void **state)
{
    (void)state;
    struct rng r = { 5 };
    for (int i = 0; i < 200; i++) {
        double a1 = 0.3 * rng_gauss(&r), b1 = 0.3 * rng_gauss(&r), c1 = 0.3 * rng_gauss(&r);
        double a2 = 0.3 * rng_gauss(&r), b2 = 0.3 * rng_gauss(&r), c2 = 0.3 * rng_gauss(&r);
        /* one pattern: k is the determinant of eq. 4 */
        double det1 = (1.0 + a1) * (1.0 + b1) - c1 * c1;
        assert_true(fabs(whitecap_dupuy_k((float)a1, (float)b1, (float)c1, 1) - det1) < 1e-5);
        /* two patterns: det of the summed Jacobian = k_1 + k_2 + the cross terms of §3 */
        double det2 = (1.0 + a1 + a2) * (1.0 + b1 + b2) - (c1 + c2) * (c1 + c2);
        double cross = a1 * b2 + a2 * b1 - 2.0 * c1 * c2;
        double ks = (double)whitecap_dupuy_k((float)a1, (float)b1, (float)c1, 2) +
                    (double)whitecap_dupuy_k((float)a2, (float)b2, (float)c2, 2);
        assert_true(fabs(ks + cross - det2) < 1e-5);
    }
    /* eq. 6: Phi values */
    assert_true(fabs(whitecap_dupuy_coverage(0.7, 0.7, 0.04) - 0.5) < 1e-15);
    assert_true(fabs(whitecap_dupuy_coverage(0.9, 0.7, 0.04) - 0.8413447460685429) < 1e-12);
    assert_true(fabs(whitecap_dupuy_coverage(0.3, 0.7, 0.04) - 0.0227501319481792) < 1e-12);
    assert_true(whitecap_dupuy_coverage(0.8, 0.7, 0.0) == 1.0);
    assert_true(whitecap_dupuy_coverage(0.6, 0.7, 0.0) == 0.0);
    for (double w = 0.001; w < 1.0; w += 0.0371) {
        double e = whitecap_dupuy_epsilon(w, 0.9, 0.01);
        assert_true(fabs(whitecap_dupuy_coverage(e, 0.9, 0.01) - w) < 1e-12);
        assert_true(fabs(e - (0.9 + 0.1 * ref_norm_quantile(w))) < 1e-9);
    }
    assert_true(isfinite(whitecap_dupuy_epsilon(0.0, 0.9, 0.01)));
    assert_true(isfinite(whitecap_dupuy_epsilon(1.0, 0.9, 0.01)));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_lambda_min_vs_references),
        cmocka_unit_test(test_model_fraction),
        cmocka_unit_test(test_eq11_eq13),
        cmocka_unit_test(test_threshold_gaussian),
        cmocka_unit_test(test_threshold_edges_and_errors),
        cmocka_unit_test(test_foam_steady_state),
        cmocka_unit_test(test_foam_impulse_half_life),
        cmocka_unit_test(test_foam_fraction_matches_eq11),
        cmocka_unit_test(test_cover_single_texel),
        cmocka_unit_test(test_cover_vs_reference),
        cmocka_unit_test(test_foam_fractional_steady_state),
        cmocka_unit_test(test_cover_eq11),
        cmocka_unit_test(test_foam_edges_soften),
        cmocka_unit_test(test_measured_fraction),
        cmocka_unit_test(test_dupuy),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
