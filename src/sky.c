/* sky.c - analytic single-scattering sky and its stereographic map (sky.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "quantize.h"
#include "sky.h"

static const float tau_r[3] = { 0.0464f, 0.108f, 0.265f };
#define TAU_M 0.0252f
#define MIE_EXT 1.1f
#define MIE_G 0.76f

/* Kasten & Young 1989 relative air mass for an elevation (degrees above the horizon). */
static float air_mass(float elev_deg)
{
    float e = elev_deg < 0.0f ? 0.0f : elev_deg;
    return 1.0f / (sinf(e * (float)M_PI / 180.0f) + 0.50572f * powf(e + 6.07995f, -1.6364f));
}

static float sun_elev_deg(const struct sky *s)
{
    return asinf(s->sun_dir[2]) * 180.0f / (float)M_PI;
}

void sky_radiance(const struct sky *s, const float dir[3], float rgb[3])
{
    float z = dir[2] > 0.0f ? dir[2] : 0.0f;
    float h = sqrtf(dir[0] * dir[0] + dir[1] * dir[1] + z * z);
    float v[3] = { dir[0] / h, dir[1] / h, z / h };
    float cg = v[0] * s->sun_dir[0] + v[1] * s->sun_dir[1] + v[2] * s->sun_dir[2];
    float p_r = 3.0f / (16.0f * (float)M_PI) * (1.0f + cg * cg);
    float hg = 1.0f + MIE_G * MIE_G - 2.0f * MIE_G * cg;
    float p_m = (1.0f - MIE_G * MIE_G) / (4.0f * (float)M_PI * hg * sqrtf(hg));
    float m_v = air_mass(asinf(v[2]) * 180.0f / (float)M_PI);
    float elev = sun_elev_deg(s);
    /* Below the horizon the sun still lights the upper sky a little (twilight): fade over 6 deg. */
    float m_s = air_mass(elev);
    float twilight = elev >= 0.0f ? 1.0f : fmaxf(0.0f, 1.0f + elev / 6.0f);
    for (int c = 0; c < 3; c++) {
        float tau = tau_r[c] + MIE_EXT * TAU_M;
        float a = tau * m_s, b = tau * m_v;
        float f = fabsf(b - a) > 1e-4f ? (expf(-a) - expf(-b)) / (b - a) : expf(-a);
        rgb[c] = twilight * (tau_r[c] * p_r + TAU_M * p_m) * m_v * f;
    }
}

void sky_haze(const struct sky *s, struct sky_haze *out)
{
    float m_v = air_mass(0.0f), elev = sun_elev_deg(s), m_s = air_mass(elev);
    float twilight = elev >= 0.0f ? 1.0f : fmaxf(0.0f, 1.0f + elev / 6.0f);
    for (int c = 0; c < 3; c++) {
        float tau = tau_r[c] + MIE_EXT * TAU_M;
        float a = tau * m_s, b = tau * m_v;
        float f = fabsf(b - a) > 1e-4f ? (expf(-a) - expf(-b)) / (b - a) : expf(-a);
        float gain = twilight * m_v * f;   /* sky_radiance at elevation 0 */
        out->tau_ext[c] = tau;
        out->ray[c] = tau_r[c] * gain;
        out->mie[c] = TAU_M * gain;
    }
    out->mie_g = MIE_G;
    out->scale_height_m = 8000.0f;
}

size_t sky_level_offset(const struct sky *s, int level)
{
    size_t off = 0;
    for (int l = 0; l < level; l++) {
        size_t n = (size_t)(s->size >> l);
        off += 4 * n * n;
    }
    return off;
}

void sky_destroy(struct sky *s)
{
    if (!s)
        return;
    free(s->data);
    free(s->half);
    s->data = NULL;
    s->half = NULL;
}

int sky_bake(float elev_deg, float azim_deg, int size, struct sky *out, struct swell_err *err)
{
    float e = elev_deg * (float)M_PI / 180.0f, a = azim_deg * (float)M_PI / 180.0f;
    float *lin = NULL, maxv = 1e-6f;
    int n = size, levels = 0;
    memset(out, 0, sizeof(*out));
    if (size < 4 || (size & (size - 1)))
        return swell_fail(err, SWELL_E_ARG, "sky: map size %d must be a power of two >= 4", size);
    while ((n >> levels) > 0)
        levels++;
    out->size = size;
    out->levels = levels;
    out->sun_dir[0] = cosf(e) * cosf(a);
    out->sun_dir[1] = cosf(e) * sinf(a);
    out->sun_dir[2] = sinf(e);
    {
        float m_s = air_mass(elev_deg);
        for (int c = 0; c < 3; c++)
            out->sun_irr[c] = elev_deg > -0.5f ? expf(-(tau_r[c] + MIE_EXT * TAU_M) * m_s) : 0.0f;
    }
    lin = malloc(sizeof(float) * 3 * (size_t)size * size);
    out->data = malloc(sky_level_offset(out, levels));
    out->half = malloc(sky_level_offset(out, levels) * sizeof(uint16_t));
    if (!lin || !out->data || !out->half) {
        free(lin);
        sky_destroy(out);
        return swell_fail(err, SWELL_E_NOMEM, "sky: no memory for a %d^2 sky map", size);
    }
    /* Inverse stereographic projection of each texel centre; outside the horizon circle the
     * horizon radiance of the same azimuth (only reached by filtering and grazing lookups). */
    for (int j = 0; j < size; j++)
        for (int i = 0; i < size; i++) {
            float x = 2.0f * (i + 0.5f) / size - 1.0f, y = 2.0f * (j + 0.5f) / size - 1.0f;
            float r2 = x * x + y * y, dir[3];
            if (r2 > 1.0f) {
                float r = sqrtf(r2);
                x /= r;
                y /= r;
                r2 = 1.0f;
            }
            dir[0] = 2.0f * x / (1.0f + r2);
            dir[1] = 2.0f * y / (1.0f + r2);
            dir[2] = (1.0f - r2) / (1.0f + r2);
            sky_radiance(out, dir, lin + 3 * ((size_t)j * size + i));
        }
    /* Sky irradiance on a horizontal plane: integrate L cos(theta) over the hemisphere in the
     * map's own measure, d omega = 4 / (1 + r^2)^2 dx dy for the stereographic projection. */
    for (int j = 0; j < size; j++)
        for (int i = 0; i < size; i++) {
            float x = 2.0f * (i + 0.5f) / size - 1.0f, y = 2.0f * (j + 0.5f) / size - 1.0f;
            float r2 = x * x + y * y, dA = 4.0f / ((float)size * size);
            if (r2 >= 1.0f)
                continue;
            float cos_t = (1.0f - r2) / (1.0f + r2), dw = 4.0f / ((1.0f + r2) * (1.0f + r2)) * dA;
            for (int c = 0; c < 3; c++)
                out->sky_irr[c] += lin[3 * ((size_t)j * size + i) + c] * cos_t * dw;
        }
    for (size_t k = 0; k < 3 * (size_t)size * size; k++)
        maxv = fmaxf(maxv, lin[k]);
    out->map_scale = maxv;
    /* Level 0 quantised, then 2x2 box mips of the linear radiance (the filter eq. 27 needs). */
    for (int l = 0; l < levels; l++) {
        int m = size >> l;
        uint8_t *dst = out->data + sky_level_offset(out, l);
        uint16_t *hdst = out->half + sky_level_offset(out, l);
        int alpha = SKY_LEVEL_ALPHA * (l < 9 ? l : 9);   /* the level's index (sky.h) */
        for (int j = 0; j < m; j++)
            for (int i = 0; i < m; i++) {
                for (int c = 0; c < 3; c++) {
                    float rad = lin[3 * ((size_t)j * m + i) + c], v = rad / maxv;
                    dst[4 * ((size_t)j * m + i) + c] = (uint8_t)(fminf(fmaxf(v, 0.0f), 1.0f) * 255.0f + 0.5f);
                    hdst[4 * ((size_t)j * m + i) + c] = quantize_half_from_float(rad);
                }
                dst[4 * ((size_t)j * m + i) + 3] = (uint8_t)alpha;
                hdst[4 * ((size_t)j * m + i) + 3] = quantize_half_from_float((float)alpha / 255.0f);
            }
        if (m > 1)
            for (int j = 0; j < m / 2; j++)
                for (int i = 0; i < m / 2; i++)
                    for (int c = 0; c < 3; c++) {
                        const float *p = lin + 3 * ((size_t)(2 * j) * m + 2 * i) + c;
                        lin[3 * ((size_t)j * (m / 2) + i) + c] =
                            0.25f * (p[0] + p[3] + p[3 * m] + p[3 * m + 3]);
                    }
    }
    free(lin);
    return 0;
}
