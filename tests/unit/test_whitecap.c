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

#include "core/seastate.h"
#include "bake/whitecap.h"

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

/* Standard normal quantile by Newton on 0.5 erfc(-z / sqrt 2). */
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

/* ---- foam memory (the (min, +) form of eq. 8) ----------------------------------------------- */

/* Steady state by its definition: min over n in [0, F) of k(f - n) + n step, around the loop. */
static void test_memory_loop_vs_definition(void **state)
{
    (void)state;
    enum { T = 37, F = 11 };
    struct rng r = { 21 };
    float k[F * T], m[F * T];
    for (int i = 0; i < F * T; i++)
        k[i] = (float)(0.8 + 0.2 * rng_gauss(&r));
    const float steps[] = { 0.0f, 0.013f, 0.2f, 5.0f };
    for (int s = 0; s < 4; s++) {
        struct swell_err err = { 0 };
        assert_int_equal(whitecap_memory_loop(k, T, F, steps[s], m, &err), 0);
        for (int f = 0; f < F; f++)
            for (int i = 0; i < T; i++) {
                double ref = INFINITY;
                for (int n = 0; n < F; n++)
                    ref = fmin(ref, k[((f - n + F) % F) * T + i] + n * (double)steps[s]);
                if (fabs(m[f * T + i] - ref) > 1e-5)
                    fail_msg("step %g frame %d texel %d: %g, definition %g", (double)steps[s],
                             f, i, (double)m[f * T + i], ref);
                /* it loops: one more update from frame F-1 gives frame 0 */
                float next = fminf(k[i], m[(F - 1) * T + i] + steps[s]);
                assert_true(fabsf(next - m[i]) < 1e-5f);
                assert_true(m[f * T + i] <= k[f * T + i]);
            }
    }
}

/* A single break to k = 0.4 at frame 3 stays below 0.725 for (0.725 - 0.4) / 0.05 frames. */
static void test_memory_single_break(void **state)
{
    (void)state;
    enum { F = 64 };
    float k[F], m[F];
    struct swell_err err = { 0 };
    for (int f = 0; f < F; f++)
        k[f] = 1.0f;
    k[3] = 0.4f;
    assert_int_equal(whitecap_memory_loop(k, 1, F, 0.05f, m, &err), 0);
    int below = 0;
    for (int f = 0; f < F; f++)
        below += m[f] < 0.725f;
    assert_int_equal(below, 7);   /* 0.4, 0.45, ..., 0.7: frames 3..9 */
    assert_true(fabsf(m[10] - 0.75f) < 1e-6f);
    assert_true(m[20] == 1.0f);
    assert_true(m[2] == 1.0f);
}

/* ---- distribution of a sum of independent patterns -------------------------------------- */

static double ref_norm_cdf(double x)
{
    return 0.5 * erfc(-x / sqrt(2.0));
}

static void test_sum_of_uniforms_and_gaussians(void **state)
{
    (void)state;
    enum { N = 40000 };
    float *a = malloc(N * sizeof *a), *b = malloc(N * sizeof *b);
    assert_true(a && b);
    struct swell_err err = { 0 };
    struct whitecap_sum s;
    /* U(0, 1) + U(0, 2) + 0.5, samples at the cell centres: the trapezoid distribution */
    for (int i = 0; i < N; i++) {
        a[i] = (float)((i + 0.5) / N);
        b[i] = (float)(2.0 * ((i * 7919 % N) + 0.5) / N);
    }
    const float *smp[2] = { a, b };
    size_t cnt[2] = { N, N };
    assert_int_equal(whitecap_sum_create(smp, cnt, 2, 0.5, &s, &err), 0);
    for (double x = 0.3; x < 3.8; x += 0.137) {
        double y = x - 0.5, ref;   /* P(U1 + U2 < y), U1 ~ U(0,1), U2 ~ U(0,2) */
        if (y <= 0.0)
            ref = 0.0;
        else if (y <= 1.0)
            ref = y * y / 4.0;
        else if (y <= 2.0)
            ref = (y - 0.5) / 2.0;
        else if (y <= 3.0)
            ref = 1.0 - (3.0 - y) * (3.0 - y) / 4.0;
        else
            ref = 1.0;
        double got = whitecap_sum_cdf(&s, x);
        if (fabs(got - ref) > 2e-3)
            fail_msg("uniform sum: P(S < %g) = %g, exact %g", x, got, ref);
        if (ref > 0.01 && ref < 0.99)
            assert_true(fabs(whitecap_sum_quantile(&s, ref) - x) < 4e-3);
    }
    assert_true(whitecap_sum_cdf(&s, 0.4) == 0.0);
    assert_true(whitecap_sum_cdf(&s, 3.6) == 1.0);
    whitecap_sum_destroy(&s);

    /* N(0, 1) + N(1, 4): N(1, 5), tails included (the whitecap fractions are tails) */
    struct rng r = { 99 };
    for (int i = 0; i < N; i++) {
        a[i] = (float)rng_gauss(&r);
        b[i] = (float)(1.0 + 2.0 * rng_gauss(&r));
    }
    assert_int_equal(whitecap_sum_create(smp, cnt, 2, 0.0, &s, &err), 0);
    for (double z = -3.0; z <= 3.0; z += 0.25) {
        double x = 1.0 + sqrt(5.0) * z, ref = ref_norm_cdf(z), got = whitecap_sum_cdf(&s, x);
        /* sampling error of N draws: about sqrt(p (1 - p) / N) <= 0.0025 */
        if (fabs(got - ref) > 0.008 + 0.2 * ref)
            fail_msg("gaussian sum: P(S < %g) = %g, exact %g", x, got, ref);
    }
    double q = whitecap_sum_quantile(&s, 0.01);
    assert_true(fabs(whitecap_sum_cdf(&s, q) - 0.01) < 1e-9);
    whitecap_sum_destroy(&s);

    /* errors: no variable, an empty one, a NaN */
    assert_int_equal(whitecap_sum_create(smp, cnt, 0, 0.0, &s, &err), SWELL_E_ARG);
    size_t none[2] = { N, 0 };
    assert_int_equal(whitecap_sum_create(smp, none, 2, 0.0, &s, &err), SWELL_E_ARG);
    assert_non_null(strstr(err.msg, "variable 1"));
    b[17] = NAN;
    assert_int_equal(whitecap_sum_create(smp, cnt, 2, 0.0, &s, &err), SWELL_E_ARG);
    assert_non_null(strstr(err.msg, "sample 17"));
    assert_null(s.cum);
    whitecap_sum_destroy(&s);
    free(a);
    free(b);
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
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_lambda_min_vs_references),
        cmocka_unit_test(test_model_fraction),
        cmocka_unit_test(test_eq11_eq13),
        cmocka_unit_test(test_threshold_gaussian),
        cmocka_unit_test(test_threshold_edges_and_errors),
        cmocka_unit_test(test_memory_loop_vs_definition),
        cmocka_unit_test(test_memory_single_break),
        cmocka_unit_test(test_sum_of_uniforms_and_gaussians),
        cmocka_unit_test(test_dupuy),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
