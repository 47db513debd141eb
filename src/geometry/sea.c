/* sea.c - the sea on the CPU (sea.h). */
#include <math.h>
#include "geometry/detile.h"
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

void sea_displacement(const struct swell_tables *t, int detile, double x, double y, double t_s,
                      double out[3])
{
    out[0] = out[1] = out[2] = 0.0;
    for (int i = 0; i < t->patterns; i++) {
        const struct swell_table *tb = tables_find(t, TABLE_DISP, i);
        double l = t->pattern[i].size_m, a[3], b[3];
        struct stream_phase ph;
        if (!tb || tb->format != FORMAT_RGBA8 || !tb->data || !(l > 0.0))
            continue;
        stream_loop_phase(t_s, tables_pattern_period(t, i), tb->layers, &ph);
        /* uv = world / L (grid_uv_offset + rest / L), read at three random offsets blended
         * (detile.h); texel centres at (i + 0.5) / n */
        struct detile_taps tp;
        double wgt = (double)ph.w / STREAM_W_ONE;
        if (detile)
            detile_taps(i, x / l, y / l, &tp);
        else
            detile_taps_off(&tp);
        for (int j = 0; j < (detile ? 3 : 1); j++) {
            double u = (x / l + tp.du[j]) * tb->width - 0.5;
            double v = (y / l + tp.dv[j]) * tb->height - 0.5;
            sample3(tb, ph.f0, u, v, a);
            sample3(tb, ph.f1, u, v, b);
            for (int c = 0; c < 3; c++)
                out[c] += tp.w[j] * (a[c] + (b[c] - a[c]) * wgt);
        }
    }
}

double sea_surface_height(const struct swell_tables *t, int detile, double x, double y,
                          double t_s)
{
    double px = x, py = y, d[3] = { 0.0, 0.0, 0.0 };
    for (int k = 0; k < SEA_INVERT_STEPS; k++) {
        sea_displacement(t, detile, px, py, t_s, d);
        double nx = x - d[0], ny = y - d[1], step = fabs(nx - px) + fabs(ny - py);
        px = nx;
        py = ny;
        if (step < SEA_INVERT_TOL)
            break;
    }
    sea_displacement(t, detile, px, py, t_s, d);
    return d[2];
}
