/* sea.c - the sea on the CPU (sea.h). */
#include <math.h>
#include "geometry/detile.h"
#include "geometry/grid.h"
#include "geometry/sea.h"
#include "tables/stream.h"

#define SEA_INVERT_STEPS 24  /* at most this many fixed-point steps of the choppy inversion;
                                each multiplies the error by about |lambda dD/dx| (< 1 where
                                the surface does not fold) */
#define SEA_INVERT_TOL 1e-5  /* m: stop once a step moves the rest point less */

/* Bilinear RGBA8 sample of channels 0-2 of layer `layer` at texel coordinates (u, v) (texel
 * centres at integers), wrapping; dequantised. */
static void sample3(const struct swell_table *tb, int layer, double u, double v, double out[3])
{
    int w = tb->width, h = tb->height;
    double fu = floor(u), fv = floor(v), a = u - fu, b = v - fv;
    long iu = (long)fmod(fu, (double)w), iv = (long)fmod(fv, (double)h);
    iu = iu < 0 ? iu + w : iu;
    iv = iv < 0 ? iv + h : iv;
    const uint8_t *d = tb->data + table_offset(tb, 0, layer);
    long x1 = (iu + 1) % w, y1 = (iv + 1) % h;
    const uint8_t *t00 = d + 4 * (iv * w + iu), *t10 = d + 4 * (iv * w + x1);
    const uint8_t *t01 = d + 4 * (y1 * w + iu), *t11 = d + 4 * (y1 * w + x1);
    for (int c = 0; c < 3; c++) {
        double q = (1 - a) * (1 - b) * t00[c] + a * (1 - b) * t10[c] + (1 - a) * b * t01[c] +
                   a * b * t11[c];
        out[c] = tb->bias[c] + tb->scale[c] * (q / 255.0);
    }
}

/* Every pattern's displacement summed at (x, y), pattern i scaled by weight[i] (NULL: 1, the
 * renderer's sum, bit for bit), and its time derivative into vel (may be NULL). */
static void displace(const struct swell_tables *t, int detile, const float *weight, double x,
                     double y, double t_s, double out[3], double vel[3])
{
    out[0] = out[1] = out[2] = 0.0;
    if (vel)
        vel[0] = vel[1] = vel[2] = 0.0;
    for (int i = 0; i < t->patterns; i++) {
        const struct swell_table *tb = tables_find(t, TABLE_DISP, i);
        double l = t->pattern[i].size_m, a[3], b[3];
        struct stream_phase ph;
        if (!tb || tb->format != FORMAT_RGBA8 || !tb->data || !(l > 0.0))
            continue;
        if (weight && weight[i] <= 0.0f)
            continue;
        stream_pattern_phase(t, i, t_s, tb->layers, &ph);
        /* uv = world / L (grid_uv_offset + rest / L), read at three random offsets blended
         * (detile.h); texel centres at (i + 0.5) / n */
        struct detile_taps tp;
        double wgt = (double)ph.w / STREAM_W_ONE;
        /* the blend weight runs through one loop frame in period / frames seconds */
        double rate = tb->layers / tables_pattern_period(t, i);
        if (detile)
            detile_taps(i, x / l, y / l, &tp);
        else
            detile_taps_off(&tp);
        for (int j = 0; j < (detile ? 3 : 1); j++) {
            double u = (x / l + tp.du[j]) * tb->width - 0.5;
            double v = (y / l + tp.dv[j]) * tb->height - 0.5;
            double w = weight ? tp.w[j] * weight[i] : tp.w[j];
            sample3(tb, ph.f0, u, v, a);
            sample3(tb, ph.f1, u, v, b);
            for (int c = 0; c < 3; c++) {
                out[c] += w * (a[c] + (b[c] - a[c]) * wgt);
                if (vel)
                    vel[c] += w * (b[c] - a[c]) * rate;
            }
        }
    }
}

void sea_displacement(const struct swell_tables *t, int detile, double x, double y, double t_s,
                      double out[3])
{
    displace(t, detile, NULL, x, y, t_s, out, NULL);
}

/* The rest point whose displaced position lies above (x, y): p + D_xy(p) = (x, y) by
 * fixed-point iteration (the choppy map contracts where the surface does not fold). */
static void invert(const struct swell_tables *t, int detile, const float *weight, double x,
                   double y, double t_s, double p[2])
{
    double px = x, py = y, d[3] = { 0.0, 0.0, 0.0 };
    for (int k = 0; k < SEA_INVERT_STEPS; k++) {
        displace(t, detile, weight, px, py, t_s, d, NULL);
        double nx = x - d[0], ny = y - d[1], step = fabs(nx - px) + fabs(ny - py);
        px = nx;
        py = ny;
        if (step < SEA_INVERT_TOL)
            break;
    }
    p[0] = px;
    p[1] = py;
}

double sea_surface_height(const struct swell_tables *t, int detile, double x, double y,
                          double t_s)
{
    double p[2], d[3];
    invert(t, detile, NULL, x, y, t_s, p);
    displace(t, detile, NULL, p[0], p[1], t_s, d, NULL);
    return d[2];
}

void sea_query_init(const struct swell_tables *t, int detile, double min_wavelength_m,
                    struct sea_query *q)
{
    q->detile = detile;
    q->height_only = 0;
    for (int i = 0; i < SWELL_MAX_PATTERNS; i++) {
        float lambda = i < t->patterns ? grid_band_wavelength(&t->pattern[i]) : 0.0f;
        q->weight[i] = min_wavelength_m > 0.0
                           ? grid_filter_weight(GRID_FILTER_NMIN, GRID_FILTER_NMAX,
                                                (float)(lambda * GRID_FILTER_NMIN /
                                                        min_wavelength_m))
                           : 1.0f;
    }
}

void sea_query_point(const struct swell_tables *t, const struct sea_query *q, double x, double y,
                     double t_s, struct sea_point *out)
{
    double p[2], dx0[3], dx1[3], dy0[3], dy1[3], h = INFINITY;
    invert(t, q->detile, q->weight, x, y, t_s, p);
    displace(t, q->detile, q->weight, p[0], p[1], t_s, out->disp,
             q->height_only ? NULL : out->velocity);
    out->height = out->disp[2];
    if (q->height_only) {
        for (int c = 0; c < 3; c++) {
            out->velocity[c] = 0.0;
            out->normal[c] = c == 2;
        }
        return;
    }
    for (int i = 0; i < t->patterns; i++) {
        const struct swell_table *tb = tables_find(t, TABLE_DISP, i);
        if (tb && tb->width > 0 && q->weight[i] > 0.0f)
            h = fmin(h, 0.25 * t->pattern[i].size_m / tb->width);
    }
    if (!isfinite(h) || !(h > 0.0))
        h = 0.01;
    /* tangents of the displaced surface P(p) = p + D(p) along the rest axes */
    displace(t, q->detile, q->weight, p[0] + h, p[1], t_s, dx1, NULL);
    displace(t, q->detile, q->weight, p[0] - h, p[1], t_s, dx0, NULL);
    displace(t, q->detile, q->weight, p[0], p[1] + h, t_s, dy1, NULL);
    displace(t, q->detile, q->weight, p[0], p[1] - h, t_s, dy0, NULL);
    double tu[3], tv[3];
    for (int c = 0; c < 3; c++) {
        tu[c] = (dx1[c] - dx0[c]) / (2.0 * h) + (c == 0);
        tv[c] = (dy1[c] - dy0[c]) / (2.0 * h) + (c == 1);
    }
    double n[3] = { tu[1] * tv[2] - tu[2] * tv[1], tu[2] * tv[0] - tu[0] * tv[2],
                    tu[0] * tv[1] - tu[1] * tv[0] };
    double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int c = 0; c < 3; c++)
        out->normal[c] = len > 0.0 ? n[c] / len : (c == 2);
}
