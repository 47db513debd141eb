/* mask.c - the coarse mask of local wave amplitude (mask.h). */
#include "geometry/mask.h"

#include <math.h>
#include <stddef.h>

int wave_mask_init(struct wave_mask *m, const char *who, const uint8_t *amp, int w, int h,
                   const double origin_m[2], const double size_m[2], struct swell_err *err)
{
    if (!amp)
        return swell_fail(err, SWELL_E_ARG, "%s: the mask's amplitude bytes are NULL", who);
    if (w < 1 || h < 1 || w > WAVE_MASK_MAX || h > WAVE_MASK_MAX)
        return swell_fail(err, SWELL_E_ARG, "%s: the mask is %d x %d texels; each side must be "
                          "1..%d", who, w, h, WAVE_MASK_MAX);
    if (!isfinite(origin_m[0]) || !isfinite(origin_m[1]) || fabs(origin_m[0]) > 1e9 ||
        fabs(origin_m[1]) > 1e9)
        return swell_fail(err, SWELL_E_ARG, "%s: the mask's origin (%g, %g) m must be finite, "
                          "within 1e9 m", who, origin_m[0], origin_m[1]);
    for (int c = 0; c < 2; c++)
        if (!(size_m[c] > 0.0) || !(size_m[c] <= WAVE_MASK_MAX_SIZE_M))
            return swell_fail(err, SWELL_E_ARG, "%s: the mask's size_m[%d] is %g m; it must be "
                              "above 0 and at most %g m", who, c, size_m[c],
                              WAVE_MASK_MAX_SIZE_M);
    m->amp = amp;
    m->w = w;
    m->h = h;
    m->x0 = origin_m[0];
    m->y0 = origin_m[1];
    m->dx = size_m[0] / w;
    m->dy = size_m[1] / h;
    return SWELL_OK;
}

/* texel (i, j), 255 outside: the border the GPU's texture holds */
static float texel(const struct wave_mask *m, long i, long j)
{
    if (i < 0 || j < 0 || i >= m->w || j >= m->h)
        return 255.0f;
    return (float)m->amp[(size_t)j * (size_t)m->w + (size_t)i];
}

float wave_mask_texel_at(const struct wave_mask *m, float u, float v)
{
    /* the four texels read all lie outside (255) unless floor(u) is in [-1, w - 1] */
    if (!(u >= -1.0f && v >= -1.0f && u < (float)m->w && v < (float)m->h))
        return 1.0f;
    /* floor by truncation of u + 1 >= 0 (no libm call), and the four texels read directly
     * inside the mask: this function 0.43 -> 0.30 M instructions a frame in the grid's pass
     * (grid_set_mask; callgrind, README.md's mask view) */
    long i = (long)(u + 1.0f) - 1, j = (long)(v + 1.0f) - 1;
    float fu = u - (float)i, fv = v - (float)j;
    float t00, t10, t01, t11;
    if (i >= 0 && j >= 0 && i + 1 < m->w && j + 1 < m->h) {
        const uint8_t *p = m->amp + (size_t)j * (size_t)m->w + (size_t)i;
        t00 = p[0];
        t10 = p[1];
        t01 = p[m->w];
        t11 = p[m->w + 1];
    } else {
        t00 = texel(m, i, j);
        t10 = texel(m, i + 1, j);
        t01 = texel(m, i, j + 1);
        t11 = texel(m, i + 1, j + 1);
    }
    float a = t00 + fu * (t10 - t00), b = t01 + fu * (t11 - t01);
    return (a + fv * (b - a)) * (1.0f / 255.0f);
}

float wave_mask_at(const struct wave_mask *m, double x, double y)
{
    /* texel coordinates with centres at whole numbers, as GL_LINEAR; far outside: the open
     * sea (no float conversion of a huge coordinate) */
    double u = (x - m->x0) / m->dx - 0.5, v = (y - m->y0) / m->dy - 0.5;
    if (!(u > -2.0 && v > -2.0 && u < m->w + 1.0 && v < m->h + 1.0))
        return 1.0f;
    return wave_mask_texel_at(m, (float)u, (float)v);
}
