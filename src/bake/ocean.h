/* ocean.h - Tessendorf FFT wave patterns (Hu 2006 §2.1, Dupuy 2012 eq. 1), looping in time.
 *
 * A pattern is an N x N periodic patch of side L_i metres sampling one band [k_min, k_max) of
 * the sea state's directional spectrum (spectrum.h). Frequencies are quantised to multiples of
 * 2 pi / T so that frame F equals frame 0 exactly (Hu §2.1 "played cyclically"); components
 * faster than F frames can sample (|omega| T / (2 pi) > F/2 - 1) are left out of the fields and
 * their slope variance is reported as unresolved (Bruneton 2010 §3.2, eq. 4).
 * Units: metres, seconds, radians. Grid index (ix, iy) is at position (ix, iy) * L / N.
 */
#ifndef SWELL_OCEAN_H
#define SWELL_OCEAN_H

#include <stdint.h>
#include "core/err.h"
#include "core/seastate.h"
#include "tables/tables.h"

struct ocean_desc {
    const struct seastate *state; /* resolved, validated */
    int n;                        /* grid size N, power of two */
    float size_m;                 /* L */
    float k_min, k_max;           /* band, rad/m; |k| outside is zero */
    int frames;                   /* F */
    float period_s;               /* T */
    float lambda;                 /* choppiness lambda_i */
    uint32_t seed;                /* per-pattern seed (derived from state->seed and the index) */
};

/* One frame's fields, N*N floats each, row-major (index iy * N + ix). */
struct ocean_fields {
    int n;
    float *dx, *dy;     /* horizontal displacement lambda * D (Tessendorf 2001 choppy), m */
    float *dz;          /* height, m */
    float *sx, *sy;     /* slopes dh/dx, dh/dy of the height field (not of the displaced surface) */
    float *jxx, *jyy, *jxy; /* lambda dDx/dx, lambda dDy/dy, lambda dDx/dy (Dupuy a_i, b_i, c_i) */
};

struct ocean_stats {
    double var_h;       /* height variance in the fields, m^2 */
    double mss_x, mss_y;/* slope variance in the fields */
    double mss_fast_x, mss_fast_y; /* in-band slope variance dropped as too fast for F frames */
    int components;     /* nonzero spectral components kept */
    /* What the spectrum expects of the kept components, sum of Psi dk^2 (resp. kx^2, ky^2
     * times it) over them; var_h, mss_x, mss_y above are this realization's values. */
    double var_h_expected, mss_x_expected, mss_y_expected;
};

struct ocean;

int  ocean_create(const struct ocean_desc *desc, struct ocean **out, struct swell_err *err);
/* Evaluate frame f (time t = f T / F; any integer, taken mod F, so frame F is frame 0); fields
 * stay valid until the next call. */
int  ocean_eval(struct ocean *o, int frame, struct ocean_fields *out, struct swell_err *err);
/* Evaluate at any time t (s) - frame f is t = f T / F; t and t + T give identical fields. */
int  ocean_eval_time(struct ocean *o, double t_s, struct ocean_fields *out, struct swell_err *err);
void ocean_get_stats(const struct ocean *o, struct ocean_stats *out);
/* The height spectrum h~(k, t) of frame f that the fields are synthesised from, N*N complex
 * values interleaved (re, im) in FFTW order (index iy * N + ix, wavevector
 * (ix', iy') 2 pi / L with ix' = ix for ix < N/2, else ix - N); zero where not kept.
 * h(x) = sum_k h~(k) e^{+i k.x}, unnormalised. For tests and inspection. */
int  ocean_height_spectrum(struct ocean *o, int frame, float *coef, struct swell_err *err);
void ocean_destroy(struct ocean *o);

/* Choose n pattern sizes and bands for a sea state and grid size N (Dupuy §2): sizes
 * incommensurate (ratios not close to small rationals), bands disjoint and contiguous from the
 * spectral peak region to the grid's Nyquist of the smallest pattern. Fills size_m, k_min,
 * k_max, lambda of info[0..n-1] (largest first). *mss_beyond_x/y receive the slope variance of
 * the spectrum beyond the last band up to the capillary cut-off (the BRDF's part). */
int ocean_plan_patterns(const struct seastate *s, int n_patterns, int n,
                        struct swell_pattern_info info[], double *mss_beyond_x,
                        double *mss_beyond_y, struct swell_err *err);

#endif
