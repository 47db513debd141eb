/* kelvin.c - the Kelvin wake by stationary phase, and its map (kelvin.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "geometry/kelvin.h"

#define G 9.81
#define PI_D 3.14159265358979323846

void kelvin_desc_defaults(struct kelvin_desc *d)
{
    if (d->hull_length_m == 0.0)
        d->hull_length_m = 9.0;
    if (d->beam_m == 0.0)
        d->beam_m = d->hull_length_m / 3.0;
}

int kelvin_check(const struct kelvin_desc *d, struct swell_err *err)
{
    static const struct { size_t off; const char *name; double lo, hi; const char *unit; } f[] = {
        { offsetof(struct kelvin_desc, speed_mps), "speed", KELVIN_MIN_SPEED_MPS,
          KELVIN_MAX_SPEED_MPS, "m/s" },
        { offsetof(struct kelvin_desc, hull_length_m), "hull length", 1.0, 400.0, "m" },
        { offsetof(struct kelvin_desc, beam_m), "beam", 0.2, 100.0, "m" },
        { offsetof(struct kelvin_desc, foam_half_life_s), "foam half-life", 0.05, 60.0, "s" },
    };
    for (size_t i = 0; i < sizeof(f) / sizeof(f[0]); i++) {
        double v = *(const double *)(const void *)((const char *)d + f[i].off);
        if (!(v >= f[i].lo && v <= f[i].hi))
            return swell_fail(err, SWELL_E_ARG, "wake: %s %g %s is outside %g..%g %s",
                              f[i].name, v, f[i].unit, f[i].lo, f[i].hi, f[i].unit);
    }
    return 0;
}

/* The map's extent behind the hull's middle: 24 transverse wavelengths, >= 6 hull lengths. */
static double wake_behind(const struct kelvin_desc *d)
{
    double lt = 2.0 * PI_D * d->speed_mps * d->speed_mps / G;
    return fmax(24.0 * lt, 6.0 * d->hull_length_m);
}

/* phi'' / kappa at theta (tan theta = t, sec theta = s), for the angle alpha (c = cos, n =
 * sin): f = s (c + n t), f'' = c s (t^2 + s^2) + n s t (5 s^2 + t^2) */
static double f2_at(double th, double c, double n)
{
    double t = tan(th), s = 1.0 / cos(th);
    return c * s * (t * t + s * s) + n * s * t * (5.0 * s * s + t * t);
}

static double smooth01(double x)
{
    x = x < 0.0 ? 0.0 : x > 1.0 ? 1.0 : x;
    return x * x * (3.0 - 2.0 * x);
}

void kelvin_eval(const struct kelvin_desc *d, double x, double y, struct kelvin_sample *out)
{
    memset(out, 0, sizeof *out);
    double u = d->speed_mps, len = d->hull_length_m, beam = d->beam_m;
    double k0 = G / (u * u);
    /* the source at the bow: X behind it, Y to port */
    double bx = 0.5 * len - x, by = y, r = hypot(bx, by);
    double span = wake_behind(d) + 0.5 * len;
    if (bx > 0.0 && r > 1e-9) {
        double ca = bx / r, sa = by / r, a = sa / ca, disc = 1.0 - 8.0 * a * a;
        double kappa = k0 * r;
        /* source strength (kelvin.h): KELVIN_HEIGHT_COEF U^2 / g at r = L on the track */
        double a0 = KELVIN_HEIGHT_COEF * u * sqrt(len) / sqrt(2.0 * PI_D * G);
        /* the near field (stationary phase holds for g r / U^2 >> 1) faded in over a hull
         * length, the far end of the map faded out */
        double fade = (1.0 - exp(-(r / len) * (r / len))) *
                      (1.0 - smooth01((bx / span - 0.8) / 0.17));
        if (disc >= 0.0 && fade > 0.0) {
            double sq = sqrt(disc);
            int roots = fabs(a) < 1e-9 ? 1 : 2;
            for (int i = 0; i < roots; i++) {
                double t = roots == 1 ? 0.0 : (-1.0 + (i ? -sq : sq)) / (4.0 * a);
                double th = atan(t), s = 1.0 / cos(th);
                double f = s * (ca + sa * t);
                double f2 = f2_at(th, ca, sa);
                double f3 = (f2_at(th + 1e-4, ca, sa) - f2_at(th - 1e-4, ca, sa)) / 2e-4;
                /* sqrt(2 pi / |phi''|), held at Airy's scale where phi'' -> 0 (the cusp) */
                double p2 = fmax(kappa * fabs(f2), cbrt(kappa * fabs(f3) * kappa * fabs(f3)));
                double k = k0 * s * s;
                /* a thin hull's source (Michell, Havelock): waves at theta weighted by
                 * sec^2 theta, filtered at the beam's scale */
                double hull = s * s * exp(-(k * beam / 4.0) * (k * beam / 4.0));
                double amp = a0 * hull * sqrt(2.0 * PI_D / p2) * fade;
                double ph = kappa * f + (f2 >= 0.0 ? 0.25 : -0.25) * PI_D;
                out->eta += amp * cos(ph);
                /* grad phi = k (cos theta, sin theta) in (X, Y); x = -X */
                double g = -amp * sin(ph) * k;
                out->slope[0] -= g * cos(th);
                out->slope[1] += g * sin(th);
            }
        }
    }
    double hl = d->foam_half_life_s;
    /* foam where the wake breaks: slopes past a breaking slope, from when the bow passed */
    double sm = hypot(out->slope[0], out->slope[1]);
    double f_break = bx > 0.0 ? smooth01((sm - 0.25) / 0.25) * exp2(-bx / u / hl) : 0.0;
    /* the stern's turbulent strip, the beam wide and widening, from when the stern passed */
    double sx = -0.5 * len - x, f_stern = 0.0;
    if (sx > -0.25 * len) {
        double w = 0.5 * beam * sqrt(1.0 + fmax(sx, 0.0) / len);
        f_stern = 0.6 * exp(-(y / w) * (y / w)) * exp2(-fmax(sx, 0.0) / u / hl) *
                  smooth01((sx + 0.25 * len) / (0.25 * len));
    }
    out->foam = 1.0 - (1.0 - f_break) * (1.0 - f_stern);
}

int kelvin_map_build(const struct kelvin_desc *d, int w, int h, struct kelvin_map *out,
                     struct swell_err *err)
{
    memset(out, 0, sizeof *out);
    int rc = kelvin_check(d, err);
    if (rc)
        return rc;
    if (w < 16 || h < 16 || w > 4096 || h > 4096 || (w & (w - 1)) || (h & (h - 1)))
        return swell_fail(err, SWELL_E_ARG, "wake: map %dx%d: sides must be powers of two in "
                          "16..4096", w, h);
    out->w = w;
    out->h = h;
    out->ahead_m = 0.25 * d->hull_length_m;
    out->span_m = out->ahead_m + 0.5 * d->hull_length_m + wake_behind(d);
    out->u_offset = (out->ahead_m + d->hull_length_m) / out->span_m;
    out->spread = 2.2 * tan(KELVIN_HALF_ANGLE_DEG * PI_D / 180.0);
    /* 1.5 beams either side at the bow */
    out->spread_offset = fmax(3.0 * d->beam_m / out->spread - out->ahead_m, 0.0) / out->span_m;
    size_t total = 0;
    int levels = 0;
    for (int lw = w, lh = h;; lw = lw > 1 ? lw / 2 : 1, lh = lh > 1 ? lh / 2 : 1) {
        out->offset[levels++] = total * 4u;
        total += (size_t)lw * (size_t)lh;
        if (lw == 1 && lh == 1)
            break;
    }
    out->levels = levels;
    out->hull_length_m = d->hull_length_m;
    float *m = malloc(total * 4u * sizeof(float));
    out->rgba = malloc(total * 4u);
    out->height = malloc(total * sizeof(float));
    if (!m || !out->rgba || !out->height) {
        free(m);
        kelvin_map_free(out);
        return swell_fail(err, SWELL_E_NOMEM, "wake: no memory for a %dx%d map", w, h);
    }
    /* level 0: moments over 2 x 2 samples per texel (the waves span 8 texels or more: the
     * hull's filter); the outermost texels still water */
    double msq_max = 0.0;
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) {
            float *p = m + 4u * ((size_t)j * (size_t)w + (size_t)i);
            double acc[4] = { 0, 0, 0, 0 }, eta = 0.0;
            if (i > 0 && j > 0 && i < w - 1 && j < h - 1)
                for (int b = 0; b < 2; b++)
                    for (int a = 0; a < 2; a++) {
                        struct kelvin_sample s;
                        double x, y;
                        kelvin_map_point(out, d->hull_length_m, (i + 0.25 + 0.5 * a) / w,
                                         (j + 0.25 + 0.5 * b) / h, &x, &y);
                        kelvin_eval(d, x, y, &s);
                        acc[0] += s.slope[0];
                        acc[1] += s.slope[1];
                        acc[2] += s.slope[0] * s.slope[0] + s.slope[1] * s.slope[1];
                        acc[3] += s.foam;
                        eta += s.eta;
                    }
            for (int c = 0; c < 4; c++)
                p[c] = (float)(acc[c] / 4.0);
            out->height[(size_t)j * (size_t)w + (size_t)i] = (float)(eta / 4.0);
            out->height_max_m = fmax(out->height_max_m, fabs(eta / 4.0));
            msq_max = fmax(msq_max, p[2]);
        }
    /* the chain: box means of the moments */
    for (int l = 1, pw = w, ph = h; l < levels; l++) {
        int lw = pw > 1 ? pw / 2 : 1, lh = ph > 1 ? ph / 2 : 1;
        const float *src = m + out->offset[l - 1];
        float *dst = m + out->offset[l];
        const float *hs = out->height + out->offset[l - 1] / 4u;
        float *hd = out->height + out->offset[l] / 4u;
        for (int j = 0; j < lh; j++)
            for (int i = 0; i < lw; i++) {
                int i1 = pw > 1 ? 2 * i + 1 : i, j1 = ph > 1 ? 2 * j + 1 : j;
                for (int c = 0; c < 4; c++)
                    dst[4 * (j * lw + i) + c] = 0.25f * (src[4 * (2 * j * pw + 2 * i) + c] +
                                                         src[4 * (2 * j * pw + i1) + c] +
                                                         src[4 * (j1 * pw + 2 * i) + c] +
                                                         src[4 * (j1 * pw + i1) + c]);
                hd[j * lw + i] = 0.25f * (hs[2 * j * pw + 2 * i] + hs[2 * j * pw + i1] +
                                          hs[j1 * pw + 2 * i] + hs[j1 * pw + i1]);
            }
        pw = lw;
        ph = lh;
    }
    out->slope_scale = fmax(sqrt(msq_max), 1e-4);
    double sc = out->slope_scale;
    for (size_t n = 0; n < total; n++) {
        const float *p = m + 4u * n;
        uint8_t *q = out->rgba + 4u * n;
        for (int c = 0; c < 2; c++)
            q[c] = (uint8_t)lrint(fmin(fmax(128.0 + 127.0 * p[c] / sc, 1.0), 255.0));
        q[2] = (uint8_t)lrint(fmin(fmax(255.0 * p[2] / (sc * sc), 0.0), 255.0));
        q[3] = (uint8_t)lrint(fmin(fmax(255.0 * p[3], 0.0), 255.0));
    }
    free(m);
    return 0;
}

void kelvin_map_point(const struct kelvin_map *m, double hull_length_m, double u, double v,
                      double *x, double *y)
{
    double e = m->u_offset, r = u * (sqrt(1.0 + e) - sqrt(e)) + sqrt(e), p = r * r - e;
    *x = 0.5 * hull_length_m + m->ahead_m - p * m->span_m;
    *y = (v - 0.5) * m->spread * (p + m->spread_offset) * m->span_m;
}

void kelvin_map_free(struct kelvin_map *m)
{
    free(m->rgba);
    free(m->height);
    m->rgba = NULL;
    m->height = NULL;
}

/* Level l's bilinear height at (u, v) in [0, 1]^2, texel centres at (i + 1/2) / w, clamped to
 * the edge (the still outermost texels). */
static float height_bilinear(const struct kelvin_map *m, int l, double u, double v)
{
    int lw = m->w >> l, lh = m->h >> l;
    lw = lw > 0 ? lw : 1;
    lh = lh > 0 ? lh : 1;
    const float *t = m->height + m->offset[l] / 4u;
    double x = u * lw - 0.5, y = v * lh - 0.5;
    double fx = floor(x), fy = floor(y);
    int i0 = (int)fx, j0 = (int)fy;
    float ax = (float)(x - fx), ay = (float)(y - fy);
    int i1 = i0 + 1 < lw ? i0 + 1 : lw - 1, j1 = j0 + 1 < lh ? j0 + 1 : lh - 1;
    i0 = i0 < 0 ? 0 : i0;
    j0 = j0 < 0 ? 0 : j0;
    i1 = i1 < 0 ? 0 : i1;
    j1 = j1 < 0 ? 0 : j1;
    float a = t[j0 * lw + i0] + (t[j0 * lw + i1] - t[j0 * lw + i0]) * ax;
    float b = t[j1 * lw + i0] + (t[j1 * lw + i1] - t[j1 * lw + i0]) * ax;
    return a + (b - a) * ay;
}

float kelvin_map_height(const struct kelvin_map *m, double x, double y, float foot_m)
{
    if (!m->height || !(m->span_m > 0.0))
        return 0.0f;
    /* kelvin.h: P along from the map's front, Q across; u, v by the warp */
    double p = (0.5 * m->hull_length_m + m->ahead_m - x) / m->span_m, q = y / m->span_m;
    if (!(p >= 0.0 && p <= 1.0))
        return 0.0f;
    double e = m->u_offset, se = sqrt(e), n = sqrt(1.0 + e) - se, sp = sqrt(p + e);
    double across = m->spread * (p + m->spread_offset);
    double u = (sp - se) / n, v = 0.5 + q / across;
    if (!(v >= 0.0 && v <= 1.0))
        return 0.0f;
    /* the level-0 texel's sides there, m: du/dP = 1 / (2 n sqrt(P + e)), dv/dQ = 1 / across;
     * the level whose texel's longer side is half the footprint, so the waves a grid of that
     * spacing holds (eq. 2 keeps those over 4 footprints whole) stay nearly whole through the
     * box and the bilinear blur: on the grid next to the camera a gain of 0.94 (test_grid
     * test_grid_wake; 0.81 with the longer side at the footprint, 0.25 with GL's rule, the
     * shorter side). The hull's filter keeps the waves 8 level-0 texels long or more. */
    double t_along = m->span_m * 2.0 * n * sp / m->w, t_across = m->span_m * across / m->h;
    double r = fmin((double)foot_m / t_along, (double)foot_m / t_across);
    double lod = r > 2.0 ? log2(r) - 1.0 : 0.0;
    int top = m->levels - 1;
    if (lod >= top)
        return height_bilinear(m, top, u, v);
    int l0 = (int)lod;
    float f = (float)(lod - l0), h0 = height_bilinear(m, l0, u, v);
    return f > 0.0f ? h0 + (height_bilinear(m, l0 + 1, u, v) - h0) * f : h0;
}
