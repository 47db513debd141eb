/* sky.c - analytic single-scattering sky and its stereographic map (sky.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "tables/quantize.h"
#include "optics/fresnel.h"
#include "optics/sky.h"

static const float tau_r[3] = { 0.0464f, 0.108f, 0.265f };
#define TAU_M 0.0252f
#define MIE_EXT 1.1f
#define MIE_G 0.76f
/* Ozone (sky.h): 300 DU (8.06e18 molecules / cm^2) times Chappuis-band cross-sections of about
 * (1.22, 3.5, 0.16) e-21 cm^2 at 680/550/440 nm, in a thin shell 25 km up. */
static const float tau_o3[3] = { 0.0098f, 0.0282f, 0.0013f };
#define OZONE_ALT_M 25000.0f

/* Kasten & Young 1989 relative air mass for an elevation (degrees above the horizon). */
static float air_mass(float elev_deg)
{
    float e = elev_deg < 0.0f ? 0.0f : elev_deg;
    return 1.0f / (sinf(e * (float)M_PI / 180.0f) + 0.50572f * powf(e + 6.07995f, -1.6364f));
}

void sky_ozone_transmittance(float elev_rad, float out[3])
{
    /* air mass of a thin shell at height h: 1 / sqrt(1 - (R cos e / (R + h))^2) */
    float e = elev_rad > 0.0f ? elev_rad : 0.0f;
    float c = cosf(e) * 6.371e6f / (6.371e6f + OZONE_ALT_M);
    float m = 1.0f / sqrtf(1.0f - c * c);
    for (int k = 0; k < 3; k++)
        out[k] = expf(-tau_o3[k] * m);
}

static float sun_elev_deg(const struct sky *s)
{
    return asinf(s->sun_dir[2]) * 180.0f / (float)M_PI;
}

/* The single-scattering closed form (sky.h) for a view path of air mass m_v, per channel:
 * the gains that multiply the Rayleigh and the Mie phase functions. Below the horizon the sun
 * still lights the upper sky a little (twilight): fade over 6 deg. */
static void scatter_gains(const struct sky *s, float m_v, float ray[3], float mie[3])
{
    float elev = sun_elev_deg(s), m_s = air_mass(elev);
    float twilight = elev >= 0.0f ? 1.0f : fmaxf(0.0f, 1.0f + elev / 6.0f), o3[3];
    sky_ozone_transmittance(elev * (float)M_PI / 180.0f, o3);
    for (int c = 0; c < 3; c++) {
        float tau = tau_r[c] + MIE_EXT * TAU_M;
        float a = tau * m_s, b = tau * m_v;
        float f = fabsf(b - a) > 1e-4f ? (expf(-a) - expf(-b)) / (b - a) : expf(-a);
        float gain = twilight * o3[c] * m_v * f;
        ray[c] = tau_r[c] * gain;
        mie[c] = TAU_M * gain;
    }
}

void sky_radiance(const struct sky *s, const float dir[3], float rgb[3])
{
    if (dir[2] < 0.0f) {   /* multiple reflections (sky.h) */
        memcpy(rgb, s->below, sizeof(s->below));
        return;
    }
    float z = dir[2];
    float h = sqrtf(dir[0] * dir[0] + dir[1] * dir[1] + z * z);
    float v[3] = { dir[0] / h, dir[1] / h, z / h };
    float cg = v[0] * s->sun_dir[0] + v[1] * s->sun_dir[1] + v[2] * s->sun_dir[2];
    float p_r = 3.0f / (16.0f * (float)M_PI) * (1.0f + cg * cg);
    float hg = 1.0f + MIE_G * MIE_G - 2.0f * MIE_G * cg;
    float p_m = (1.0f - MIE_G * MIE_G) / (4.0f * (float)M_PI * hg * sqrtf(hg));
    float ray[3], mie[3];
    scatter_gains(s, air_mass(asinf(v[2]) * 180.0f / (float)M_PI), ray, mie);
    for (int c = 0; c < 3; c++)
        rgb[c] = ray[c] * p_r + mie[c] * p_m;
}

#define SCALE_HEIGHT_M 8000.0
#define EARTH_R_M 6.371e6      /* camera.h EARTH_RADIUS_M */

/* Column along the ray from altitude h at elevation e through rho = exp(-z / H) on the sphere,
 * over H (units of the vertical column from the sea); 0 where the ray hits the Earth before it
 * leaves the air (the caller uses the limb's then). Midpoint rule in the distance, steps of a
 * fraction of the local scale length. */
static double column(double h, double e)
{
    const double top = EARTH_R_M + 25.0 * SCALE_HEIGHT_M;   /* above 200 km: e^-25, nothing */
    double r0 = EARTH_R_M + h, se = sin(e), sum = 0.0, s = 0.0;
    if (r0 > top) {
        /* from above the air: straight to where the ray enters it, if it does */
        double b = r0 * se, c = r0 * r0 - top * top, disc = b * b - c;
        if (se >= 0.0 || disc <= 0.0)
            return 0.0;
        s = -b - sqrt(disc);
    }
    for (int it = 0; it < 100000; it++) {
        double r = sqrt(r0 * r0 + s * s + 2.0 * r0 * s * se), z = r - EARTH_R_M;
        double climb = (s + r0 * se) / r;   /* dr / ds */
        if (z < 0.0)
            return -1.0;   /* below the sea */
        if (r > top && climb >= 0.0)
            break;         /* out of the air for good */
        /* a step of a quarter of the distance over which the density changes e-fold along the
         * ray (its height changes by H; the midpoint rule is then within 0.3 %), at least 10 m,
         * at most 20 km */
        double ds = fmin(fmax(0.25 * SCALE_HEIGHT_M / (fabs(climb) + 1e-3), 10.0), 20000.0);
        double sm = s + 0.5 * ds;
        double rm = sqrt(r0 * r0 + sm * sm + 2.0 * r0 * sm * se);
        sum += exp(-(rm - EARTH_R_M) / SCALE_HEIGHT_M) * ds;
        s += ds;
    }
    return sum / SCALE_HEIGHT_M;
}

float sky_view_air_mass(double alt_m, float elev_rad)
{
    double h = alt_m > 0.0 ? alt_m : 0.0;
    /* the lowest elevation that misses the Earth: the limb, -acos(R / (R + h)) */
    double limb = -acos(EARTH_R_M / (EARTH_R_M + h)) + 1e-6;
    double e = elev_rad > limb ? elev_rad : limb;
    double ky = air_mass(fmaxf((float)(e * 180.0 / M_PI), 0.0f));
    double c0 = column(0.0, e > 0.0 ? e : 0.0), c = column(h, e);
    return c > 0.0 && c0 > 0.0 ? (float)(c * ky / c0) : 0.0f;
}

void sky_transmittance(float m, float out[3])
{
    for (int c = 0; c < 3; c++)
        out[c] = expf(-(tau_r[c] + MIE_EXT * TAU_M) * m);
}

void sky_view_gains(const struct sky *s, double alt_m, int n, float *ray, float *mie)
{
    for (int k = 0; k < n; k++)
        scatter_gains(s, sky_view_air_mass(alt_m, (float)asin(2.0 * (k + 0.5) / n - 1.0)),
                      ray + 3 * k, mie + 3 * k);
}

void sky_haze(const struct sky *s, struct sky_haze *out)
{
    scatter_gains(s, air_mass(0.0f), out->ray, out->mie);   /* sky_radiance at elevation 0 */
    for (int c = 0; c < 3; c++)
        out->tau_ext[c] = tau_r[c] + MIE_EXT * TAU_M;
    out->mie_g = MIE_G;
    out->scale_height_m = (float)SCALE_HEIGHT_M;
}

void sky_map_uv(const float rin[3], float uv[2])
{
    float r[3] = { rin[0], rin[1], rin[2] > SKY_MAP_BELOW_Z ? rin[2] : SKY_MAP_BELOW_Z };
    if (rin[2] < SKY_MAP_BELOW_Z) {   /* else r is a unit vector already */
        float k = 1.0f / sqrtf(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
        r[0] *= k;
        r[1] *= k;
        r[2] *= k;
    }
    uv[0] = 0.5f + 0.5f * SKY_MAP_HORIZON * r[0] / (1.0f + r[2]);
    uv[1] = 0.5f + 0.5f * SKY_MAP_HORIZON * r[1] / (1.0f + r[2]);
}

double sky_fresnel_avg(void)
{
    /* midpoint rule in mu^2 (the integrand F(mu) d(mu^2)): 4096 steps, within 2e-6 of the
     * converged value (the grazing end, F -> 1, converges slowest) */
    const int n = 4096;
    double sum = 0.0;
    for (int k = 0; k < n; k++)
        sum += fresnel_exact(sqrt((k + 0.5) / n), SWELL_WATER_IOR);
    return sum / n;
}

void sky_texel_radiance(const struct sky *s, const uint8_t *p, float out[3])
{
    for (int c = 0; c < 3; c++) {
        float v = p[c] / 255.0f;
        out[c] = v * v * s->map_scale[c];
    }
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
    float *lin = NULL, maxv[3] = { 1e-6f, 1e-6f, 1e-6f };
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
        float m_s = air_mass(elev_deg), o3[3];
        sky_ozone_transmittance(e, o3);
        for (int c = 0; c < 3; c++)
            out->sun_irr[c] =
                elev_deg > -0.5f ? o3[c] * expf(-(tau_r[c] + MIE_EXT * TAU_M) * m_s) : 0.0f;
    }
    lin = malloc(sizeof(float) * 3 * (size_t)size * size);
    out->data = malloc(sky_level_offset(out, levels));
    out->half = malloc(sky_level_offset(out, levels) * sizeof(uint16_t));
    if (!lin || !out->data || !out->half) {
        free(lin);
        sky_destroy(out);
        return swell_fail(err, SWELL_E_NOMEM, "sky: no memory for a %d^2 sky map", size);
    }
    /* Inverse stereographic projection of each texel centre inside the horizon circle (map
     * coordinates x, y over SKY_MAP_HORIZON), and the sky irradiance on a horizontal plane: L
     * cos(theta) over the hemisphere in the map's own measure, d omega = 4 / (1 + r^2)^2 dx dy
     * for the stereographic projection (dx dy the texel's area in those coordinates). Then the
     * ring outside the circle (marked -1 meanwhile): the radiance below the horizon (sky.h). */
    const float hs = SKY_MAP_HORIZON;
    for (int j = 0; j < size; j++)
        for (int i = 0; i < size; i++) {
            float x = (2.0f * (i + 0.5f) / size - 1.0f) / hs;
            float y = (2.0f * (j + 0.5f) / size - 1.0f) / hs;
            float r2 = x * x + y * y, dir[3], *px = lin + 3 * ((size_t)j * size + i);
            if (r2 >= 1.0f) {
                px[0] = -1.0f;
                continue;
            }
            dir[0] = 2.0f * x / (1.0f + r2);
            dir[1] = 2.0f * y / (1.0f + r2);
            dir[2] = (1.0f - r2) / (1.0f + r2);
            sky_radiance(out, dir, px);
            float dA = 4.0f / ((float)size * size * hs * hs);
            float dw = 4.0f / ((1.0f + r2) * (1.0f + r2)) * dA;
            for (int c = 0; c < 3; c++)
                out->sky_irr[c] += px[c] * dir[2] * dw;
        }
    {
        float f_avg = (float)sky_fresnel_avg();
        for (int c = 0; c < 3; c++)
            out->below[c] = f_avg * out->sky_irr[c] / (float)M_PI;
    }
    for (size_t k = 0; k < (size_t)size * size; k++)
        if (lin[3 * k] < 0.0f)
            memcpy(lin + 3 * k, out->below, sizeof(out->below));
    for (size_t k = 0; k < 3 * (size_t)size * size; k++)
        maxv[k % 3] = fmaxf(maxv[k % 3], lin[k]);
    memcpy(out->map_scale, maxv, sizeof(maxv));
    /* Level 0 quantised, then 2x2 box mips of the linear radiance (the filter eq. 27 needs). */
    for (int l = 0; l < levels; l++) {
        int m = size >> l;
        uint8_t *dst = out->data + sky_level_offset(out, l);
        uint16_t *hdst = out->half + sky_level_offset(out, l);
        int alpha = SKY_LEVEL_ALPHA * (l < 9 ? l : 9);   /* the level's index (sky.h) */
        for (int j = 0; j < m; j++)
            for (int i = 0; i < m; i++) {
                for (int c = 0; c < 3; c++) {
                    float rad = lin[3 * ((size_t)j * m + i) + c];
                    float v = sqrtf(fminf(fmaxf(rad / maxv[c], 0.0f), 1.0f));   /* (sky.h) */
                    dst[4 * ((size_t)j * m + i) + c] = (uint8_t)(v * 255.0f + 0.5f);
                    hdst[4 * ((size_t)j * m + i) + c] = quantize_half_from_float(sqrtf(fmaxf(rad, 0.0f)));
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
