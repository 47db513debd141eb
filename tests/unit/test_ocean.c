/* FFT wave patterns: FFT fields vs a direct DFT of the same coefficients, Hermitian symmetry,
 * Parseval (exact for the realization, statistical vs the spectrum), loop closure bit for bit,
 * too-fast components dropped and accounted, the pattern plan (bands, sizes), determinism and
 * the choppy sign (crests sharpen). */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <cmocka.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bake/ocean.h"
#include "bake/spectrum.h"

#define TWO_PI 6.283185307179586

static struct seastate sea(double u)
{
    struct seastate s = { 0 };
    s.wind_speed_mps = (float)u;
    s.wind_dir_deg = 20.0f;
    seastate_resolve(&s);
    return s;
}

static struct ocean *make(const struct ocean_desc *d)
{
    struct ocean *o = NULL;
    struct swell_err err = { 0 };
    if (ocean_create(d, &o, &err))
        fail_msg("ocean_create: %s", err.msg);
    return o;
}

static void eval_frame(struct ocean *o, int f, struct ocean_fields *fl)
{
    struct swell_err err = { 0 };
    if (ocean_eval(o, f, fl, &err))
        fail_msg("ocean_eval: %s", err.msg);
}

static void eval_time(struct ocean *o, double t, struct ocean_fields *fl)
{
    struct swell_err err = { 0 };
    if (ocean_eval_time(o, t, fl, &err))
        fail_msg("ocean_eval_time: %s", err.msg);
}

static int signed_index(int i, int n) { return i < n / 2 ? i : i - n; }

/* the 8 fields in a fixed order, with their spectral multipliers (ocean.c's conventions):
 * h, Dx = i lambda kx/k h, Dy, sx = i kx h, sy, jxx = -lambda kx^2/k h, jyy, jxy */
enum { NF = 8 };
static const char *const field_names[NF] = { "dz", "dx", "dy", "sx", "sy", "jxx", "jyy", "jxy" };

static const float *field_ptr(const struct ocean_fields *fl, int i)
{
    const float *p[NF] = { fl->dz, fl->dx, fl->dy, fl->sx, fl->sy, fl->jxx, fl->jyy, fl->jxy };
    return p[i];
}

static void multiplier(int field, double kx, double ky, double lam, double *re, double *im)
{
    double k = sqrt(kx * kx + ky * ky);
    *re = 0.0;
    *im = 0.0;
    switch (field) {
    case 0: *re = 1.0; break;
    case 1: *im = lam * kx / k; break;
    case 2: *im = lam * ky / k; break;
    case 3: *im = kx; break;
    case 4: *im = ky; break;
    case 5: *re = -lam * kx * kx / k; break;
    case 6: *re = -lam * ky * ky / k; break;
    default: *re = -lam * kx * ky / k; break;
    }
}

static void check_dft(int n)
{
    struct seastate s = sea(10.0);
    double L = 40.0, lam = 0.8;
    struct ocean_desc d = {
        .state = &s, .n = n, .size_m = (float)L, .k_min = 0.0f,
        .k_max = (float)(M_PI * n / L), .frames = 64, .period_s = 8.0f, .lambda = (float)lam,
        .seed = 7,
    };
    struct ocean *o = make(&d);
    int frame = 5;
    float *coef = malloc(sizeof(float) * 2 * n * n);
    struct swell_err err = { 0 };
    assert_int_equal(ocean_height_spectrum(o, frame, coef, &err), 0);
    int nonzero = 0;
    for (int iy = 0; iy < n; iy++) {
        for (int ix = 0; ix < n; ix++) {
            int c = iy * n + ix, p = ((n - iy) % n) * n + (n - ix) % n;
            /* Hermitian, exactly: h~(-k) = conj h~(k) */
            if (coef[2 * c] != coef[2 * p] || coef[2 * c + 1] != -coef[2 * p + 1])
                fail_msg("N=%d: h~ not Hermitian at (%d, %d)", n, ix, iy);
            nonzero += coef[2 * c] != 0.0f || coef[2 * c + 1] != 0.0f;
        }
    }
    struct ocean_stats st;
    ocean_get_stats(o, &st);
    assert_int_equal(nonzero, st.components);
    assert_true(nonzero > n * n / 4);

    struct ocean_fields fl;
    eval_frame(o, frame, &fl);
    double dk = TWO_PI / L;
    for (int f = 0; f < NF; f++) {
        const float *fld = field_ptr(&fl, f);
        double max_err = 0.0, max_im = 0.0, rms = 0.0;
        for (int y = 0; y < n; y++) {
            for (int x = 0; x < n; x++) {
                double re = 0.0, im = 0.0;
                for (int iy = 0; iy < n; iy++) {
                    for (int ix = 0; ix < n; ix++) {
                        int c = iy * n + ix, sx = signed_index(ix, n), sy = signed_index(iy, n);
                        if (coef[2 * c] == 0.0f && coef[2 * c + 1] == 0.0f)
                            continue;
                        double mr, mi, hr = coef[2 * c], hi = coef[2 * c + 1];
                        multiplier(f, sx * dk, sy * dk, lam, &mr, &mi);
                        double vr = mr * hr - mi * hi, vi = mr * hi + mi * hr;
                        /* e^{+i k.x}, x = (x, y) L / N */
                        double ph = TWO_PI * (double)(sx * x + sy * y) / n;
                        re += vr * cos(ph) - vi * sin(ph);
                        im += vr * sin(ph) + vi * cos(ph);
                    }
                }
                double e = fabs(re - fld[y * n + x]);
                if (e > max_err) max_err = e;
                if (fabs(im) > max_im) max_im = fabs(im);
                rms += re * re;
            }
        }
        rms = sqrt(rms / (n * n));
        assert_true(rms > 0.0);
        if (max_err > 2e-5 * rms * n || max_im > 1e-9 * rms * n * n)
            fail_msg("N=%d field %s: FFT vs DFT max error %g, max imaginary %g (rms %g)", n,
                     field_names[f], max_err, max_im, rms);
    }
    free(coef);
    ocean_destroy(o);
}

static void test_fft_vs_dft(void **st)
{
    (void)st;
    check_dft(8);
    check_dft(16);
}

/* Parseval, exact: averaged over the F frames, the spatial variance of h equals the
 * realization's sum of |h0(k)|^2 + |h0(-k)|^2 (cross terms turn at 2 omega and cancel). */
static void test_parseval_exact(void **st)
{
    (void)st;
    struct seastate s = sea(8.0);
    int n = 32, F = 16;
    struct ocean_desc d = {
        .state = &s, .n = n, .size_m = 60.0f, .k_min = 0.0f, .k_max = (float)(M_PI * n / 60.0),
        .frames = F, .period_s = 30.0f, .lambda = 1.0f, .seed = 3,
    };
    struct ocean *o = make(&d);
    struct ocean_stats stt;
    ocean_get_stats(o, &stt);
    double vh = 0.0, vx = 0.0, vy = 0.0;
    for (int f = 0; f < F; f++) {
        struct ocean_fields fl;
        eval_frame(o, f, &fl);
        double m = 0.0;
        for (int i = 0; i < n * n; i++)
            m += fl.dz[i];
        m /= n * n;
        assert_true(fabs(m) < 1e-5 * sqrt(stt.var_h));   /* no k = 0 component */
        for (int i = 0; i < n * n; i++) {
            vh += (fl.dz[i] - m) * (fl.dz[i] - m);
            vx += fl.sx[i] * fl.sx[i];
            vy += fl.sy[i] * fl.sy[i];
        }
    }
    vh /= (double)F * n * n;
    vx /= (double)F * n * n;
    vy /= (double)F * n * n;
    assert_true(stt.components > 0);
    if (fabs(vh / stt.var_h - 1.0) > 1e-4 || fabs(vx / stt.mss_x - 1.0) > 1e-4 ||
        fabs(vy / stt.mss_y - 1.0) > 1e-4)
        fail_msg("Parseval: fields %g %g %g vs coefficients %g %g %g", vh, vx, vy, stt.var_h,
                 stt.mss_x, stt.mss_y);
    ocean_destroy(o);
}

/* Parseval vs the spectrum: the mean over seeds of the height variance approaches the band's
 * integral of Psi. Two separate errors, each bounded on its own:
 * - discretisation: the grid's Riemann sum sum Psi dk^2 vs the integral (smooth band, < 3%);
 * - sampling: var_h = sum over the kept k of |h0(k)|^2 + |h0(-k)|^2 with |h0|^2 exponential of
 *   mean Psi dk^2 / 2, so its standard deviation is sigma = sqrt(sum (Psi dk^2)^2) per seed; the
 *   mean of S seeds is accepted within 4 sigma / sqrt(S) (false alarm ~ 6e-5). */
static void test_parseval_spectrum(void **st)
{
    (void)st;
    struct seastate s = sea(10.0);
    int n = 64, seeds = 24;
    double L = 400.0, kp = spectrum_peak_k(&s);
    double k0 = 1.5 * kp, k1 = M_PI * n / L;
    double riemann = 0.0, sq = 0.0, dk = TWO_PI / L;
    for (int iy = -n / 2 + 1; iy < n / 2; iy++) {
        for (int ix = -n / 2 + 1; ix < n / 2; ix++) {
            double k = dk * sqrt((double)ix * ix + (double)iy * iy);
            if (k < k0 || k >= k1)
                continue;
            double p = spectrum_psi(&s, ix * dk, iy * dk) * dk * dk;
            riemann += p;
            sq += p * p;
        }
    }
    double integral;
    spectrum_band_moments(&s, k0, k1, &integral, NULL, NULL);
    if (fabs(riemann / integral - 1.0) > 0.03)
        fail_msg("Riemann sum %g vs integral %g: band too coarse for this test", riemann,
                 integral);
    double mean = 0.0;
    for (int i = 0; i < seeds; i++) {
        struct ocean_desc d = {
            .state = &s, .n = n, .size_m = (float)L, .k_min = (float)k0, .k_max = (float)k1,
            .frames = 256, .period_s = 64.0f, .lambda = 1.0f, .seed = 100u + (uint32_t)i,
        };
        struct ocean *o = make(&d);
        struct ocean_stats stt;
        ocean_get_stats(o, &stt);
        assert_true(fabs(stt.var_h_expected / riemann - 1.0) < 1e-6);
        assert_true(stt.mss_fast_x == 0.0 && stt.mss_fast_y == 0.0);
        mean += stt.var_h / seeds;
        ocean_destroy(o);
    }
    double tol = 4.0 * sqrt(sq) / sqrt((double)seeds);
    if (fabs(mean - riemann) > tol)
        fail_msg("mean height variance %g vs spectrum %g: off by %g > 4 sigma = %g", mean,
                 riemann, fabs(mean - riemann), tol);
}

static void assert_fields_identical(const struct ocean_fields *a, const float *copy, int n,
                                    const char *what)
{
    for (int f = 0; f < NF; f++)
        if (memcmp(field_ptr(a, f), copy + (size_t)f * n * n, sizeof(float) * n * n))
            fail_msg("%s: field %s differs", what, field_names[f]);
}

static void copy_fields(const struct ocean_fields *a, float *copy, int n)
{
    for (int f = 0; f < NF; f++)
        memcpy(copy + (size_t)f * n * n, field_ptr(a, f), sizeof(float) * n * n);
}

static void test_loop_closure(void **st)
{
    (void)st;
    struct seastate s = sea(10.0);
    int n = 32, F = 16;
    double T = 16.0, L = 40.0;
    struct ocean_desc d = {
        .state = &s, .n = n, .size_m = (float)L, .k_min = 0.0f, .k_max = (float)(M_PI * n / L),
        .frames = F, .period_s = (float)T, .lambda = 1.0f, .seed = 11,
    };
    struct ocean *o = make(&d);
    float *a = malloc(sizeof(float) * NF * n * n);
    struct ocean_fields fl;

    eval_frame(o, 0, &fl);
    copy_fields(&fl, a, n);
    eval_frame(o, F, &fl);
    assert_fields_identical(&fl, a, n, "frame F vs frame 0");
    eval_time(o, T, &fl);
    assert_fields_identical(&fl, a, n, "time T vs frame 0");
    eval_frame(o, 1, &fl);
    if (!memcmp(fl.dz, a, sizeof(float) * n * n))
        fail_msg("frame 1 equals frame 0: nothing moves");

    eval_frame(o, 3, &fl);
    copy_fields(&fl, a, n);
    eval_frame(o, 3 + F, &fl);
    assert_fields_identical(&fl, a, n, "frame 3 + F vs frame 3");
    eval_frame(o, 3 - 2 * F, &fl);
    assert_fields_identical(&fl, a, n, "frame 3 - 2F vs frame 3");
    eval_time(o, 3.0 * T / F, &fl);
    assert_fields_identical(&fl, a, n, "time 3 T / F vs frame 3");

    const double times[] = { 0.37, 5.5, 15.99, -3.2, 1234.56 };
    for (int i = 0; i < 5; i++) {
        eval_time(o, times[i], &fl);
        copy_fields(&fl, a, n);
        eval_time(o, times[i] + T, &fl);
        assert_fields_identical(&fl, a, n, "time t + T vs t");
        eval_time(o, times[i] - 3.0 * T, &fl);
        assert_fields_identical(&fl, a, n, "time t - 3T vs t");
    }
    free(a);
    ocean_destroy(o);
}

/* F = 4 frames sample only m <= F/2 - 1 = 1: everything faster is absent from the spectrum of
 * the fields, and its slope variance is reported; kept + dropped = the band's Riemann sum. */
static void test_fast_dropped(void **st)
{
    (void)st;
    struct seastate s = sea(10.0);
    int n = 32, F = 4;
    double L = 300.0, T = 16.0, dk = TWO_PI / L;
    struct ocean_desc d = {
        .state = &s, .n = n, .size_m = (float)L, .k_min = 0.0f,
        .k_max = (float)(M_PI * n / (2.0 * L)), .frames = F, .period_s = (float)T,
        .lambda = 1.0f, .seed = 5,
    };
    struct ocean *o = make(&d);
    struct ocean_stats stt;
    ocean_get_stats(o, &stt);
    float *coef = malloc(sizeof(float) * 2 * n * n);
    struct swell_err err = { 0 };
    assert_int_equal(ocean_height_spectrum(o, 1, coef, &err), 0);
    double band_x = 0.0, band_y = 0.0;
    int kept = 0, slow = 0;
    for (int iy = 0; iy < n; iy++) {
        for (int ix = 0; ix < n; ix++) {
            int sx = signed_index(ix, n), sy = signed_index(iy, n), c = iy * n + ix;
            double k = dk * sqrt((double)sx * sx + (double)sy * sy);
            int nz = coef[2 * c] != 0.0f || coef[2 * c + 1] != 0.0f;
            kept += nz;
            if (k == 0.0 || k >= d.k_max || sx == -n / 2 || sy == -n / 2) {
                assert_false(nz);
                continue;
            }
            double m = spectrum_omega(k, 0.0) * T / TWO_PI;
            if (m < 1.5) {
                slow++;
            } else if (nz) {
                fail_msg("component (%d, %d) with omega T / 2 pi = %g > F/2 - 1 kept", sx, sy, m);
            }
            double p = spectrum_psi(&s, sx * dk, sy * dk) * dk * dk;
            band_x += sx * dk * sx * dk * p;
            band_y += sy * dk * sy * dk * p;
        }
    }
    assert_int_equal(kept, stt.components);
    assert_true(kept <= slow);
    assert_true(stt.mss_fast_x > 0.1 * band_x);
    if (fabs(stt.mss_x_expected + stt.mss_fast_x - band_x) > 1e-9 * band_x ||
        fabs(stt.mss_y_expected + stt.mss_fast_y - band_y) > 1e-9 * band_y)
        fail_msg("kept + dropped (%g, %g) != band (%g, %g)",
                 stt.mss_x_expected + stt.mss_fast_x, stt.mss_y_expected + stt.mss_fast_y,
                 band_x, band_y);
    free(coef);
    ocean_destroy(o);
}

static double incommensurability(double ratio)
{
    double worst = 1.0;
    for (int q = 1; q <= 8; q++) {
        double x = q * ratio, dd = fabs(x - floor(x + 0.5));
        if (dd < worst)
            worst = dd;
    }
    return worst;
}

static void test_plan(void **st)
{
    (void)st;
    const double speeds[] = { 3.0, 10.0, 20.0 };
    for (int u = 0; u < 3; u++) {
        struct seastate s = sea(speeds[u]);
        s.choppiness = 1.3f;
        double lp = TWO_PI / spectrum_peak_k(&s), kc = spectrum_k_cutoff(&s);
        for (int n = 16; n <= 256; n *= 2) {
            for (int np = 1; np <= 4; np++) {
                struct swell_pattern_info in[SWELL_MAX_PATTERNS];
                double bx, by;
                struct swell_err err = { 0 };
                if (ocean_plan_patterns(&s, np, n, in, &bx, &by, &err))
                    fail_msg("plan: %s", err.msg);
                if (!(in[0].size_m > 3.0 * lp && in[0].size_m < 8.0 * lp))
                    fail_msg("largest pattern %g m for peak wavelength %g m", in[0].size_m, lp);
                assert_true(in[0].k_min <= TWO_PI / in[0].size_m);
                for (int i = 0; i < np; i++) {
                    double L = in[i].size_m;
                    assert_true(in[i].k_min < in[i].k_max);
                    assert_true(in[i].k_max <= M_PI * n / L);       /* inside the circle */
                    assert_true(in[i].k_max <= kc * (1.0 + 1e-6));
                    assert_true(in[i].lambda == s.choppiness);
                    if (i > 0) {
                        assert_true(in[i].size_m < in[i - 1].size_m);   /* largest first */
                        assert_true(in[i].k_min == in[i - 1].k_max);    /* contiguous */
                        assert_true(in[i].k_min >= TWO_PI / L);         /* resolvable */
                    }
                    for (int j = 0; j < i; j++) {
                        double g = incommensurability((double)in[j].size_m / in[i].size_m);
                        if (g < 0.05)
                            fail_msg("U %g N %d: L%d / L%d = %g is within %g of a rational "
                                     "p/q, q <= 8", speeds[u], n, j, i,
                                     (double)in[j].size_m / in[i].size_m, g);
                    }
                }
                /* beyond: integral k^2 S d omega from the last band's end to the cut-off */
                double w0 = log(spectrum_omega(in[np - 1].k_max, 0.0));
                double w1 = log(spectrum_omega(kc, 0.0)), mss = 0.0;
                int steps = 20000;
                for (int k = 0; k < steps && w1 > w0; k++) {
                    double w = exp(w0 + (k + 0.5) * (w1 - w0) / steps), kk = w * w / 9.81;
                    mss += kk * kk * spectrum_S_omega(&s, w) * w * (w1 - w0) / steps;
                }
                if (fabs(bx + by - mss) > 2e-3 * mss + 1e-12)
                    fail_msg("mss beyond %g vs %g", bx + by, mss);
                /* wind at 20 degrees: more slope along x than along y */
                assert_true(bx >= by);
            }
        }
    }
    struct seastate s = sea(10.0);
    struct swell_pattern_info in[SWELL_MAX_PATTERNS];
    double bx, by;
    struct swell_err err = { 0 };
    assert_int_equal(ocean_plan_patterns(&s, 5, 128, in, &bx, &by, &err), SWELL_E_ARG);
    assert_int_equal(ocean_plan_patterns(&s, 4, 100, in, &bx, &by, &err), SWELL_E_ARG);
}

/* The whole slope budget of the default bake plan: in the tables + too fast + beyond the last
 * band = integral of k^2 Psi up to the cut-off (within the Riemann sums' discretisation). */
static void test_slope_budget(void **st)
{
    (void)st;
    struct seastate s = sea(10.0);
    int n = 64, F = 16;
    struct swell_pattern_info in[SWELL_MAX_PATTERNS];
    double bx, by;
    struct swell_err err = { 0 };
    assert_int_equal(ocean_plan_patterns(&s, 4, n, in, &bx, &by, &err), 0);
    double sum_x = bx, sum_y = by;
    for (int i = 0; i < 4; i++) {
        struct ocean_desc d = {
            .state = &s, .n = n, .size_m = in[i].size_m, .k_min = in[i].k_min,
            .k_max = in[i].k_max, .frames = F, .period_s = s.loop_period_s,
            .lambda = in[i].lambda, .seed = 1u + (uint32_t)i,
        };
        struct ocean *o = make(&d);
        struct ocean_stats stt;
        ocean_get_stats(o, &stt);
        sum_x += stt.mss_x_expected + stt.mss_fast_x;
        sum_y += stt.mss_y_expected + stt.mss_fast_y;
        ocean_destroy(o);
    }
    double tx, ty;
    spectrum_band_moments(&s, 0.0, spectrum_k_cutoff(&s), NULL, &tx, &ty);
    if (fabs(sum_x / tx - 1.0) > 0.03 || fabs(sum_y / ty - 1.0) > 0.05)
        fail_msg("slope budget: kept + fast + beyond = (%g, %g), total (%g, %g)", sum_x, sum_y,
                 tx, ty);
}

static void test_determinism(void **st)
{
    (void)st;
    struct seastate s = sea(12.0);
    int n = 64;
    struct ocean_desc d = {
        .state = &s, .n = n, .size_m = 200.0f, .k_min = 0.01f, .k_max = 0.9f, .frames = 32,
        .period_s = 20.0f, .lambda = 1.2f, .seed = 42,
    };
    struct ocean *a = make(&d), *b = make(&d);
    d.seed = 43;
    struct ocean *c = make(&d);
    float *copy = malloc(sizeof(float) * NF * n * n);
    struct ocean_fields fl;
    eval_frame(a, 7, &fl);
    copy_fields(&fl, copy, n);
    eval_frame(b, 7, &fl);
    assert_fields_identical(&fl, copy, n, "second creation");
    eval_frame(c, 7, &fl);
    if (!memcmp(fl.dz, copy, sizeof(float) * n * n))
        fail_msg("different seeds give identical heights");
    free(copy);
    ocean_destroy(a);
    ocean_destroy(b);
    ocean_destroy(c);
}

/* Choppy sign: with lambda > 0 the horizontal displacement converges on crests, so the
 * divergence jxx + jyy = -lambda sum |k| h~ e^{ikx} anti-correlates with h:
 * sum_x h (jxx + jyy) = -lambda N^2 sum_k |k| |h~(k)|^2 < 0 (Parseval). */
static void test_choppy_sign(void **st)
{
    (void)st;
    struct seastate s = sea(10.0);
    int n = 32;
    double L = 80.0, lam = 1.5, dk = TWO_PI / L;
    struct ocean_desc d = {
        .state = &s, .n = n, .size_m = (float)L, .k_min = 0.0f, .k_max = (float)(M_PI * n / L),
        .frames = 64, .period_s = 32.0f, .lambda = (float)lam, .seed = 9,
    };
    struct ocean *o = make(&d);
    struct ocean_fields fl;
    eval_frame(o, 2, &fl);
    double corr = 0.0, want = 0.0;
    for (int i = 0; i < n * n; i++)
        corr += (double)fl.dz[i] * (fl.jxx[i] + fl.jyy[i]);
    float *coef = malloc(sizeof(float) * 2 * n * n);
    struct swell_err err = { 0 };
    assert_int_equal(ocean_height_spectrum(o, 2, coef, &err), 0);
    for (int iy = 0; iy < n; iy++)
        for (int ix = 0; ix < n; ix++) {
            int sx = signed_index(ix, n), sy = signed_index(iy, n), c = iy * n + ix;
            double k = dk * sqrt((double)sx * sx + (double)sy * sy);
            want -= lam * n * n * k *
                    ((double)coef[2 * c] * coef[2 * c] + (double)coef[2 * c + 1] * coef[2 * c + 1]);
        }
    assert_true(want < 0.0);
    if (fabs(corr / want - 1.0) > 1e-4)
        fail_msg("sum h div(lambda D) = %g, expected %g", corr, want);
    free(coef);
    ocean_destroy(o);
}

/* Waves travel towards the wind: for k along the wind (where Psi(-k) is negligible) the phase
 * of h~(k) advances by -omega dt per frame (e^{i (k.x - omega t)}), i.e. the crests move
 * downwind. Checked as the amplitude-weighted sign of Im(h~(t1) conj h~(t0)). */
static void test_travel_direction(void **st)
{
    (void)st;
    struct seastate s = sea(10.0);
    s.wind_dir_deg = 0.0f;
    int n = 32, F = 64;
    double L = 300.0;
    struct ocean_desc d = {
        .state = &s, .n = n, .size_m = (float)L, .k_min = 0.0f,
        .k_max = (float)(M_PI * n / (2.0 * L)), .frames = F, .period_s = 64.0f, .lambda = 1.0f,
        .seed = 21,
    };
    struct ocean *o = make(&d);
    float *c0 = malloc(sizeof(float) * 2 * n * n), *c1 = malloc(sizeof(float) * 2 * n * n);
    struct swell_err err = { 0 };
    assert_int_equal(ocean_height_spectrum(o, 0, c0, &err), 0);
    assert_int_equal(ocean_height_spectrum(o, 1, c1, &err), 0);
    double down = 0.0, up = 0.0;
    for (int iy = 0; iy < n; iy++)
        for (int ix = 1; ix < n / 2; ix++) {      /* kx > 0: downwind half */
            int sy = signed_index(iy, n), c = iy * n + ix;
            if (abs(sy) > ix)
                continue;                         /* within 45 degrees of the wind */
            double im = (double)c1[2 * c + 1] * c0[2 * c] - (double)c1[2 * c] * c0[2 * c + 1];
            if (im < 0.0)
                down -= im;
            else
                up += im;
        }
    if (!(down > 20.0 * up))
        fail_msg("phase advance: downwind %g vs upwind %g", down, up);
    free(c0);
    free(c1);
    ocean_destroy(o);
}

static void test_bad_args(void **st)
{
    (void)st;
    struct seastate s = sea(10.0);
    struct ocean_desc good = {
        .state = &s, .n = 32, .size_m = 50.0f, .k_min = 0.0f, .k_max = 1.0f, .frames = 16,
        .period_s = 16.0f, .lambda = 1.0f, .seed = 1,
    };
    struct ocean *o = NULL;
    struct swell_err err = { 0 };
    struct ocean_desc d = good;
    d.n = 48;
    assert_int_equal(ocean_create(&d, &o, &err), SWELL_E_ARG);
    assert_non_null(strstr(err.msg, "n = 48"));
    assert_null(o);
    d = good;
    d.k_max = 3.0f;   /* > pi 32 / 50 = 2.01 */
    assert_int_equal(ocean_create(&d, &o, &err), SWELL_E_ARG);
    assert_non_null(strstr(err.msg, "Nyquist"));
    d = good;
    d.size_m = NAN;
    assert_int_equal(ocean_create(&d, &o, &err), SWELL_E_ARG);
    d = good;
    d.frames = 1;
    assert_int_equal(ocean_create(&d, &o, &err), SWELL_E_ARG);
    ocean_destroy(NULL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fft_vs_dft),
        cmocka_unit_test(test_parseval_exact),
        cmocka_unit_test(test_parseval_spectrum),
        cmocka_unit_test(test_loop_closure),
        cmocka_unit_test(test_fast_dropped),
        cmocka_unit_test(test_plan),
        cmocka_unit_test(test_slope_budget),
        cmocka_unit_test(test_determinism),
        cmocka_unit_test(test_choppy_sign),
        cmocka_unit_test(test_travel_direction),
        cmocka_unit_test(test_bad_args),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
