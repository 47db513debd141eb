/* ocean.c - Tessendorf 2001 FFT patterns, looping in time (Hu 2006 §2.1), n bands (Dupuy 2012).
 *
 * Conventions (all stated once, here):
 * - Synthesis h(x, t) = sum_k h~(k, t) e^{+i k.x} over k = (ix', iy') 2 pi / L, evaluated at
 *   x = (ix, iy) L / N (Hu 2006 eq. 1). That is FFTW's BACKWARD transform, which is
 *   unnormalised, so the amplitudes carry the physical scale and no 1/N^2 appears anywhere.
 * - A component travels towards +k: h~(k, t) = h0(k) e^{-i omega t} + conj(h0(-k)) e^{+i omega t}
 *   (Tessendorf writes e^{+i omega t}, which sends waves against the wind). The sum is
 *   Hermitian, h~(-k) = conj(h~(k)), so every field is real.
 * - E|h0(k)|^2 = Psi(k) dk^2 / 2 with dk = 2 pi / L, so the expected height variance is
 *   sum_k Psi dk^2, the Riemann sum of integral Psi d^2k (spectrum.h).
 * - Choppy displacement D = +i (k/|k|) h~. Tessendorf's -i k/|k| with e^{+i k.x} synthesis and
 *   lambda > 0 moves points away from crests (implementations then use lambda < 0); with +i,
 *   lambda = choppiness > 0 sharpens crests and the Jacobian of Dupuy eq. 4 drops below 1 at
 *   crests, where whitecaps belong. Hence jxx = lambda dDx/dx = -lambda kx^2/|k| h~ etc.
 * - Slopes i k h~ are of the height field h(x), not of the displaced surface.
 * - Time: omega is quantised to m 2 pi / T, m = max(1, round(omega T / 2 pi)), so every kept
 *   component repeats after T (Hu 2006 §2.1: samples played cyclically). Components with
 *   m > F/2 - 1 cannot be sampled by F frames (temporal Nyquist) and are left out; their slope
 *   variance becomes part of the BRDF's unresolved variance (Bruneton 2010 eq. 4).
 * - Phases are integer fractions of a turn: frame f uses (m f mod F) / F, time t uses
 *   (m j mod 2^24) / 2^24 with j = round(frac(t / T) 2^24) (t quantised to T / 2^24, about a
 *   microsecond), so t and t + T, and frames f and f + F, give bit-identical fields.
 */
#include "bake/ocean.h"

#include <fftw3.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bake/spectrum.h"

#define TWO_PI 6.283185307179586
#define TIME_STEPS (1u << 24)

/* The field pairs packed into one complex transform each: for real fields a and b with
 * Hermitian spectra A and B, ifft(A + i B) = a + i b. */
enum field_id { F_DX, F_DY, F_SX, F_SY, F_DZ, F_JXY, F_JXX, F_JYY, F_COUNT };
#define PAIRS (F_COUNT / 2)

struct comp {
    int32_t idx;        /* cell iy * N + ix */
    int32_t m;          /* omega = m 2 pi / T */
    float h0r, h0i;     /* h0(k) */
    float gr, gi;       /* conj(h0(-k)) */
    float kx, ky, kinv; /* rad/m, 1/|k| */
};

struct ocean {
    int n, frames, m_max;
    double period_s;
    float lambda;
    int count;
    struct comp *comp;
    float *cos_m, *sin_m;   /* phase of each m for the frame being evaluated */
    fftwf_complex *buf;     /* PAIRS transforms of N*N */
    fftwf_plan plan;
    float *field;           /* F_COUNT fields of N*N */
    struct ocean_stats stats;
};

/* splitmix64 (Steele, Lea, Flood 2014): a 64-bit counter through a fixed bijective mixer.
 * Integer-only, so the stream is identical on every machine. */
static uint64_t splitmix64(uint64_t *state)
{
    uint64_t z = (*state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

/* Uniform in (-1, 1) from the top 53 bits. */
static double uniform_pm1(uint64_t *state)
{
    return ((double)(splitmix64(state) >> 11) + 0.5) * (2.0 / 9007199254740992.0) - 1.0;
}

/* Two independent standard normals by Marsaglia's polar method (Box-Muller without sin/cos:
 * only sqrt, which IEEE rounds exactly, and log). */
static void gaussian_pair(uint64_t *state, double *a, double *b)
{
    double u, v, s;
    do {
        u = uniform_pm1(state);
        v = uniform_pm1(state);
        s = u * u + v * v;
    } while (s >= 1.0 || s == 0.0);
    double f = sqrt(-2.0 * log(s) / s);
    *a = u * f;
    *b = v * f;
}

static int is_pow2(int v) { return v > 0 && (v & (v - 1)) == 0; }

static int validate_desc(const struct ocean_desc *d, struct swell_err *err)
{
    if (!d || !d->state)
        return swell_fail(err, SWELL_E_ARG, "ocean_create: no descriptor or no sea state");
    if (!is_pow2(d->n) || d->n < 4 || d->n > 4096)
        return swell_fail(err, SWELL_E_ARG,
                          "ocean grid n = %d: must be a power of two in [4, 4096]", d->n);
    if (!(d->size_m > 0.0f) || !isfinite(d->size_m))
        return swell_fail(err, SWELL_E_ARG, "ocean size_m = %g m: must be positive",
                          (double)d->size_m);
    if (d->frames < 2 || d->frames > 4096)
        return swell_fail(err, SWELL_E_ARG, "ocean frames = %d: must be in [2, 4096]",
                          d->frames);
    if (!(d->period_s > 0.0f) || !isfinite(d->period_s))
        return swell_fail(err, SWELL_E_ARG, "ocean period_s = %g s: must be positive",
                          (double)d->period_s);
    if (!(d->k_min >= 0.0f) || !(d->k_max >= d->k_min) || !isfinite(d->k_max))
        return swell_fail(err, SWELL_E_ARG,
                          "ocean band [%g, %g) rad/m: need 0 <= k_min <= k_max < inf",
                          (double)d->k_min, (double)d->k_max);
    double nyq = M_PI * d->n / d->size_m;
    if (d->k_max > nyq * (1.0 + 1e-6))
        return swell_fail(err, SWELL_E_ARG,
                          "ocean k_max = %g rad/m exceeds the grid's Nyquist pi N / L = %g rad/m "
                          "(N = %d, L = %g m): the square grid's corners alias; lower k_max or "
                          "raise N", (double)d->k_max, nyq, d->n, (double)d->size_m);
    if (!isfinite(d->lambda))
        return swell_fail(err, SWELL_E_ARG, "ocean lambda = %g: must be finite",
                          (double)d->lambda);
    return 0;
}

static int signed_index(int i, int n) { return i < n / 2 ? i : i - n; }

/* Draw h0 for every cell in a fixed order (so a mode's amplitude does not depend on the band
 * or the frame count) and keep the in-band ones the frames can sample. */
static int build_components(struct ocean *o, const struct ocean_desc *d, struct swell_err *err)
{
    int n = o->n;
    size_t cells = (size_t)n * (size_t)n;
    double dk = TWO_PI / d->size_m, w_step = TWO_PI / d->period_s;
    double *h0 = malloc(cells * 2 * sizeof *h0);
    o->comp = malloc(cells * sizeof *o->comp);
    if (!h0 || !o->comp) {
        free(h0);
        return swell_fail(err, SWELL_E_NOMEM, "ocean: cannot allocate %zu spectral cells", cells);
    }
    uint64_t rng = (uint64_t)d->seed;
    for (int iy = 0; iy < n; iy++) {
        for (int ix = 0; ix < n; ix++) {
            size_t c = (size_t)iy * n + ix;
            double a, b;
            gaussian_pair(&rng, &a, &b);
            int sx = signed_index(ix, n), sy = signed_index(iy, n);
            double kx = sx * dk, ky = sy * dk;
            double k = dk * sqrt((double)sx * sx + (double)sy * sy);   /* as below, bit for bit */
            double psi = k >= d->k_min && k < d->k_max ? spectrum_psi(d->state, kx, ky) : 0.0;
            double amp = sqrt(psi) * dk * 0.5;   /* E|h0|^2 = Psi dk^2 / 2 */
            h0[2 * c] = a * amp;
            h0[2 * c + 1] = b * amp;
        }
    }
    struct ocean_stats *st = &o->stats;
    for (int iy = 0; iy < n; iy++) {
        for (int ix = 0; ix < n; ix++) {
            int sx = signed_index(ix, n), sy = signed_index(iy, n);
            /* the Nyquist row and column are their own mirror image: never used */
            if (sx == -n / 2 || sy == -n / 2 || (sx == 0 && sy == 0))
                continue;
            double kx = sx * dk, ky = sy * dk;
            double k = dk * sqrt((double)sx * sx + (double)sy * sy);
            if (!(k >= d->k_min && k < d->k_max))
                continue;
            double psi_dk2 = spectrum_psi(d->state, kx, ky) * dk * dk;
            double w = spectrum_omega(k, d->state->depth_m);
            long m = lround(w / w_step);
            if (m < 1)
                m = 1;
            if (m > o->m_max) {
                st->mss_fast_x += kx * kx * psi_dk2;
                st->mss_fast_y += ky * ky * psi_dk2;
                continue;
            }
            size_t c = (size_t)iy * n + ix;
            size_t p = (size_t)((n - iy) % n) * n + (size_t)((n - ix) % n);
            struct comp *q = &o->comp[o->count++];
            q->idx = (int32_t)c;
            q->m = (int32_t)m;
            q->h0r = (float)h0[2 * c];
            q->h0i = (float)h0[2 * c + 1];
            q->gr = (float)h0[2 * p];
            q->gi = (float)-h0[2 * p + 1];
            q->kx = (float)kx;
            q->ky = (float)ky;
            q->kinv = (float)(1.0 / k);
            /* time average over the loop of |h~|^2 = |h0|^2 + |g|^2: the cross term turns at
             * 2 omega = 2m 2 pi / T with 0 < 2m < F, so it averages to 0 over the F frames */
            double p2 = (double)q->h0r * q->h0r + (double)q->h0i * q->h0i +
                        (double)q->gr * q->gr + (double)q->gi * q->gi;
            st->var_h += p2;
            st->mss_x += kx * kx * p2;
            st->mss_y += ky * ky * p2;
            st->var_h_expected += psi_dk2;
            st->mss_x_expected += kx * kx * psi_dk2;
            st->mss_y_expected += ky * ky * psi_dk2;
        }
    }
    st->components = o->count;
    free(h0);
    return 0;
}

int ocean_create(const struct ocean_desc *desc, struct ocean **out, struct swell_err *err)
{
    int r;
    *out = NULL;
    if ((r = validate_desc(desc, err)))
        return r;
    struct ocean *o = calloc(1, sizeof *o);
    if (!o)
        return swell_fail(err, SWELL_E_NOMEM, "ocean: cannot allocate the pattern state");
    o->n = desc->n;
    o->frames = desc->frames;
    o->m_max = desc->frames / 2 - 1;
    o->period_s = desc->period_s;
    o->lambda = desc->lambda;
    size_t cells = (size_t)o->n * (size_t)o->n;

    if ((r = build_components(o, desc, err)))
        goto fail;
    o->cos_m = calloc((size_t)o->m_max + 1, sizeof *o->cos_m);
    o->sin_m = calloc((size_t)o->m_max + 1, sizeof *o->sin_m);
    o->field = malloc(cells * F_COUNT * sizeof *o->field);
    o->buf = fftwf_alloc_complex(cells * PAIRS);
    if (!o->cos_m || !o->sin_m || !o->field || !o->buf) {
        r = swell_fail(err, SWELL_E_NOMEM, "ocean: cannot allocate fields for N = %d", o->n);
        goto fail;
    }
    /* One plan for the PAIRS in-place transforms; FFTW_ESTIMATE does not touch the data and
     * picks the same plan on every run. */
    int dims[2] = { o->n, o->n };
    o->plan = fftwf_plan_many_dft(2, dims, PAIRS, o->buf, NULL, 1, (int)cells, o->buf, NULL, 1,
                                  (int)cells, FFTW_BACKWARD, FFTW_ESTIMATE);
    if (!o->plan) {
        r = swell_fail(err, SWELL_E_FFT,
                       "ocean: FFTW could not plan %d complex %dx%d transforms; check the "
                       "fftw3f installation", PAIRS, o->n, o->n);
        goto fail;
    }
    *out = o;
    return 0;

fail:
    ocean_destroy(o);
    return r;
}

void ocean_destroy(struct ocean *o)
{
    if (!o)
        return;
    if (o->plan)
        fftwf_destroy_plan(o->plan);
    fftwf_free(o->buf);
    free(o->field);
    free(o->sin_m);
    free(o->cos_m);
    free(o->comp);
    free(o);
}

/* Phase of every m at the turn fraction j / den: 2 pi (m j mod den) / den. */
static void set_phases(struct ocean *o, uint64_t j, uint64_t den)
{
    for (int m = 1; m <= o->m_max; m++) {
        double a = TWO_PI * (double)(((uint64_t)m * j) % den) / (double)den;
        o->cos_m[m] = (float)cos(a);
        o->sin_m[m] = (float)sin(a);
    }
}

/* h~(k, t) = h0 e^{-i phi} + g e^{+i phi}, grouped so that the mirror component -k computes
 * exactly the conjugate (same two products, summed in either order). */
static void comp_height(const struct ocean *o, const struct comp *q, float *hr, float *hi)
{
    float c = o->cos_m[q->m], s = o->sin_m[q->m];
    float a = q->h0r * c + q->h0i * s, b = q->gr * c - q->gi * s;
    float e = q->h0i * c - q->h0r * s, f = q->gi * c + q->gr * s;
    *hr = a + b;
    *hi = e + f;
}

/* A = i p h, B = i q h (p, q real): A + i B = (-p hi - q hr) + i (p hr - q hi). */
static void put_imag_pair(fftwf_complex *dst, float p, float q, float hr, float hi)
{
    dst[0][0] = -p * hi - q * hr;
    dst[0][1] = p * hr - q * hi;
}

/* A = p h, B = q h (p, q real): A + i B = (p hr - q hi) + i (p hi + q hr). */
static void put_real_pair(fftwf_complex *dst, float p, float q, float hr, float hi)
{
    dst[0][0] = p * hr - q * hi;
    dst[0][1] = p * hi + q * hr;
}

static void synthesise(struct ocean *o, struct ocean_fields *out)
{
    size_t cells = (size_t)o->n * (size_t)o->n;
    fftwf_complex *b0 = o->buf, *b1 = b0 + cells, *b2 = b1 + cells, *b3 = b2 + cells;
    memset(o->buf, 0, cells * PAIRS * sizeof *o->buf);
    float lam = o->lambda;
    for (int i = 0; i < o->count; i++) {
        const struct comp *q = &o->comp[i];
        float hr, hi;
        comp_height(o, q, &hr, &hi);
        float ux = q->kx * q->kinv, uy = q->ky * q->kinv;   /* k / |k| */
        size_t c = (size_t)q->idx;
        put_imag_pair(&b0[c], lam * ux, lam * uy, hr, hi);              /* Dx, Dy */
        put_imag_pair(&b1[c], q->kx, q->ky, hr, hi);                    /* sx, sy */
        put_real_pair(&b2[c], 1.0f, -lam * q->kx * uy, hr, hi);         /* h, jxy */
        put_real_pair(&b3[c], -lam * q->kx * ux, -lam * q->ky * uy, hr, hi); /* jxx, jyy */
    }
    fftwf_execute(o->plan);
    static const int pair_fields[PAIRS][2] = {
        { F_DX, F_DY }, { F_SX, F_SY }, { F_DZ, F_JXY }, { F_JXX, F_JYY },
    };
    for (int p = 0; p < PAIRS; p++) {
        const fftwf_complex *src = o->buf + cells * p;
        float *fa = o->field + cells * pair_fields[p][0];
        float *fb = o->field + cells * pair_fields[p][1];
        for (size_t i = 0; i < cells; i++) {
            fa[i] = src[i][0];
            fb[i] = src[i][1];
        }
    }
    out->n = o->n;
    out->dx = o->field + cells * F_DX;
    out->dy = o->field + cells * F_DY;
    out->dz = o->field + cells * F_DZ;
    out->sx = o->field + cells * F_SX;
    out->sy = o->field + cells * F_SY;
    out->jxx = o->field + cells * F_JXX;
    out->jyy = o->field + cells * F_JYY;
    out->jxy = o->field + cells * F_JXY;
}

static uint64_t frame_turn(const struct ocean *o, int frame)
{
    int f = frame % o->frames;
    return (uint64_t)(f < 0 ? f + o->frames : f);
}

int ocean_eval(struct ocean *o, int frame, struct ocean_fields *out, struct swell_err *err)
{
    if (!o || !out)
        return swell_fail(err, SWELL_E_ARG, "ocean_eval: NULL pattern or output");
    set_phases(o, frame_turn(o, frame), (uint64_t)o->frames);
    synthesise(o, out);
    return 0;
}

int ocean_eval_time(struct ocean *o, double t_s, struct ocean_fields *out, struct swell_err *err)
{
    if (!o || !out)
        return swell_fail(err, SWELL_E_ARG, "ocean_eval_time: NULL pattern or output");
    if (!isfinite(t_s))
        return swell_fail(err, SWELL_E_ARG, "ocean_eval_time: t = %g s is not finite", t_s);
    double tau = fmod(t_s, o->period_s);       /* exact */
    if (tau < 0.0)
        tau += o->period_s;
    uint64_t j = (uint64_t)llround(tau / o->period_s * (double)TIME_STEPS) % TIME_STEPS;
    set_phases(o, j, TIME_STEPS);
    synthesise(o, out);
    return 0;
}

void ocean_get_stats(const struct ocean *o, struct ocean_stats *out)
{
    *out = o->stats;
}

int ocean_height_spectrum(struct ocean *o, int frame, float *coef, struct swell_err *err)
{
    if (!o || !coef)
        return swell_fail(err, SWELL_E_ARG, "ocean_height_spectrum: NULL pattern or output");
    set_phases(o, frame_turn(o, frame), (uint64_t)o->frames);
    memset(coef, 0, (size_t)o->n * (size_t)o->n * 2 * sizeof *coef);
    for (int i = 0; i < o->count; i++) {
        const struct comp *q = &o->comp[i];
        comp_height(o, q, &coef[2 * (size_t)q->idx], &coef[2 * (size_t)q->idx + 1]);
    }
    return 0;
}

/* ---- pattern planning (Dupuy 2012 §2) ------------------------------------------------------ */

/* The largest pattern holds this many peak wavelengths: the peak then sits 5 grid steps from
 * k = 0, and everything below half the fundamental (k_p / 10, where the spectrum's
 * exp(-1.25 (omega_p / omega)^4) < e^-120) is negligible. */
#define PEAK_WAVELENGTHS 5.0
/* A band ends at half the grid's Nyquist, 4 texels per wavelength: bilinear magnification stays
 * smooth, and the displacement table (a 2x box-filtered level of the same grid, bake.c) still
 * resolves every kept wave. */
#define BAND_END_OF_NYQUIST 0.5
/* The next pattern's band must start at least this many of its grid steps from k = 0, so its
 * band has a ring of directions to sample, which caps the size ratio at N / 16. */
#define HANDOFF_STEPS 4.0
#define RATIO_MIN 1.5
/* Incommensurability: for q = 1..Q tiles of the larger pattern, how far q L_a / L_b is from a
 * whole number of the smaller; the sizes maximise the worst case over all pairs. */
#define INCOMMENSURATE_Q 8
#define RATIO_SEARCH_SPAN 0.15
#define RATIO_SEARCH_STEPS 600

static double commensurability_gap(double ratio)
{
    double worst = 1.0;
    for (int q = 1; q <= INCOMMENSURATE_Q; q++) {
        double x = q * ratio, d = fabs(x - nearbyint(x));
        if (d < worst)
            worst = d;
    }
    return worst;
}

int ocean_plan_patterns(const struct seastate *s, int n_patterns, int n,
                        struct swell_pattern_info info[], double *mss_beyond_x,
                        double *mss_beyond_y, struct swell_err *err)
{
    if (!s || !info || !mss_beyond_x || !mss_beyond_y)
        return swell_fail(err, SWELL_E_ARG, "ocean_plan_patterns: NULL argument");
    if (n_patterns < 1 || n_patterns > SWELL_MAX_PATTERNS)
        return swell_fail(err, SWELL_E_ARG, "patterns = %d: must be in [1, %d]", n_patterns,
                          SWELL_MAX_PATTERNS);
    if (!is_pow2(n) || n < 8)
        return swell_fail(err, SWELL_E_ARG, "pattern grid N = %d: must be a power of two >= 8",
                          n);
    double kp = spectrum_peak_k(s), kc = spectrum_k_cutoff(s);
    if (!(kp > 0.0) || !isfinite(kp))
        return swell_fail(err, SWELL_E_ARG,
                          "sea state has no spectral peak (k_p = %g rad/m); check wind speed "
                          "and fetch", kp);
    double L[SWELL_MAX_PATTERNS];
    L[0] = PEAK_WAVELENGTHS * TWO_PI / kp;
    double end0 = BAND_END_OF_NYQUIST * M_PI * n / L[0];

    /* Geometric sizes spanning the first band's end to the cut-off, each step at most N / 16
     * (HANDOFF_STEPS) and at least RATIO_MIN; then each ratio is nudged down (never up, which
     * would break the handoff) to the most incommensurate value in a 15% window. */
    double r_max = BAND_END_OF_NYQUIST * n / (2.0 * HANDOFF_STEPS);
    double r_target = n_patterns > 1 ? pow(kc / end0, 1.0 / (n_patterns - 1)) : 1.0;
    if (r_target > r_max)
        r_target = r_max;
    if (r_target < RATIO_MIN)
        r_target = RATIO_MIN;
    for (int i = 1; i < n_patterns; i++) {
        double best_r = r_target, best_gap = -1.0;
        for (int c = 0; c <= RATIO_SEARCH_STEPS; c++) {
            double r = r_target * (1.0 - RATIO_SEARCH_SPAN * c / RATIO_SEARCH_STEPS);
            double li = L[i - 1] / r, gap = 1.0;
            for (int a = 0; a < i; a++) {
                double g = commensurability_gap(L[a] / li);
                if (g < gap)
                    gap = g;
            }
            if (gap > best_gap) {
                best_gap = gap;
                best_r = r;
            }
        }
        L[i] = L[i - 1] / best_r;
    }

    /* Bands: the first starts at half its fundamental (so its lowest modes are in), each ends at
     * its band end or the cut-off, and the next starts exactly where it ends (same float). */
    float k_lo = (float)(M_PI / L[0]);
    for (int i = 0; i < n_patterns; i++) {
        double end = BAND_END_OF_NYQUIST * M_PI * n / L[i];
        float k_hi = (float)(end < kc ? end : kc);
        if (k_hi < k_lo)
            k_hi = k_lo;
        info[i].size_m = (float)L[i];
        info[i].k_min = k_lo;
        info[i].k_max = k_hi;
        info[i].lambda = s->choppiness;
        info[i].var_h = 0.0f;
        info[i].mss_x = 0.0f;
        info[i].mss_y = 0.0f;
        k_lo = k_hi;
    }
    spectrum_band_moments(s, (double)k_lo, kc, NULL, mss_beyond_x, mss_beyond_y);
    return 0;
}
