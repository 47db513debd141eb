/* sky.h - an analytic, sun-dependent clear sky, baked into the stereographic sky map of
 * Bruneton 2010 §5.2 (u = 1/2 + h/2 [r_x r_y] / (1 + r_z): zenith at the centre, horizon on the
 * circle of radius h = SKY_MAP_HORIZON of the half-width) with a full mip chain for the filtered
 * lookup of eq. 27. The ring outside the horizon holds the radiance below it (Bruneton 2010 §6,
 * multiple reflections: a view ray reflected below the horizon meets another wave and is
 * reflected towards the sky or refracted into the water; its radiance is approximated as an
 * average Fresnel reflectance times the sky irradiance, F_avg E_sky / pi, F_avg the flat
 * water's reflectance averaged over a uniform sky, 0.066 at n = 1.333). Lookups below the
 * horizon read the ring's middle, and filtering blends it with the horizon where a lobe of
 * reflected rays straddles it.
 *
 * Model (why: cheap, no tables, physically motivated): single scattering in a flat homogeneous
 * atmosphere of Rayleigh optical depth tau_R = (0.046, 0.108, 0.265) (680/550/440 nm, 8 km scale
 * height) and Mie optical depth 0.025 (extinction 1.1x, Henyey-Greenstein g = 0.76), air masses
 * from Kasten & Young 1989. Looking at air mass m_v with the sun at air mass m_s, the radiance is
 *     L = E0 (tau_R p_R(gamma) + tau_M p_M(gamma)) m_v (e^{-tau m_s} - e^{-tau m_v}) / (tau (m_v - m_s))
 * (the closed form of the single-scattering integral through the slab), E0 = 1 extraterrestrial
 * sun irradiance, so every radiance is relative to it. Multiple scattering is ignored.
 * The sunlight reaches the air through the ozone layer (sky_ozone_transmittance: 300 DU, its
 * Chappuis band absorbing green and red, optical depth (0.0098, 0.0282, 0.0013), in a thin
 * shell 25 km up): what keeps the zenith blue at low sun, where the long path's Rayleigh
 * extinction alone leaves the light that reaches it yellow and the zenith grey (at 3 degrees
 * its green falls by 0.76, blue by 0.99). The view paths from below the layer skip it.
 */
#ifndef SWELL_SKY_H
#define SWELL_SKY_H

#include <stdint.h>
#include "core/err.h"

/* The horizon circle's radius in units of the map's half-width; the ring outside it, 8 texels
 * wide at level 0 of a 256^2 map, holds the radiance below the horizon. common.glsl
 * SKY_HORIZON is the same number (test_glsl test_sky_lookup reads the map through it). */
#define SKY_MAP_HORIZON 0.9375f
/* The lowest z of a reflected ray the lookups take (common.glsl sky_map_uv): normalised, its
 * map radius h tan(theta / 2) is the ring's middle (1 + h) / 2. */
#define SKY_MAP_BELOW_Z (-0.0328f)

/* A of level l of the RGBA8 sky map (up to 9 levels, 256^2) */
#define SKY_LEVEL_ALPHA 28

struct sky {
    float sun_dir[3];       /* unit vector towards the sun, world */
    float sun_irr[3];       /* sun irradiance at the sea (normal incidence), relative to E0 */
    float sky_irr[3];       /* sky irradiance on a horizontal surface, relative to E0 */
    float below[3];         /* radiance below the horizon, F_avg sky_irr / pi (multiple
                             * reflections, above) */
    float map_scale[3];     /* per channel, the largest radiance of level 0: a texel value v
                             * of data is radiance (v / 255)^2 map_scale[c] (sky_texel_radiance;
                             * ocean.frag sky_decode) */
    int size, levels;       /* sky map: size x size, full mip chain */
    uint8_t *data;          /* RGBA8, level-major, rows bottom-up, tightly packed: RGB the
                             * square root of the radiance over map_scale, so the dim horizon
                             * opposite a low sun keeps 60-100 steps a channel (linear over
                             * the map's largest value it had 2-3 in blue: bands of colour in
                             * the sea's reflection on gles2-min); A holds
                             * the level l as SKY_LEVEL_ALPHA * l: a fetch's A / 255 x
                             * (255 / SKY_LEVEL_ALPHA) is the LOD it sampled (ocean.frag) */
    uint16_t *half;         /* the same levels as IEEE halves of the radiance's square root
                             * (no scale: map_scale 1), RGBA16F;
                             * A as data's, A = SKY_LEVEL_ALPHA l / 255 */
};

/* Aerial perspective in the same model (ocean.vert): between the camera and a sea point the
 * path's transmittance per channel is exp(-tau_ext m) with m its air mass, and it scatters in
 * (1 - T) times the sky's radiance at the horizon in that azimuth, tau_r p_R(gamma) gain_r +
 * tau_m p_M(gamma) gain_m (what sky_radiance gives at elevation 0: the path through the whole
 * atmosphere towards the horizon). */
struct sky_haze {
    float tau_ext[3];       /* vertical optical depth, per channel */
    float ray[3];           /* tau_R x the horizon gain: multiplies p_R(gamma) */
    float mie[3];           /* tau_M x the horizon gain: multiplies p_M(gamma) */
    float mie_g;            /* Henyey-Greenstein g */
    float scale_height_m;   /* of the homogeneous slab's density, m */
};
void sky_haze(const struct sky *s, struct sky_haze *out);

/* The sky seen from a camera alt_m above the sea (Bruneton 2010 §6: from the ground to
 * space), for the background: the same single scattering with the view path's air mass
 * replaced by the column of an exponential atmosphere on the sphere (scale height 8 km) along
 * the ray from the camera, in units of the vertical column from the sea (numerically
 * integrated; scaled so that at the sea it is Kasten & Young's air mass, so alt 0 gives
 * sky_radiance exactly). Above the atmosphere the column vanishes: black space, and a glowing
 * limb where the ray grazes the air. Directions below the horizon that miss the Earth (from
 * high up) are included; those that hit it take the limb's.
 *
 * For n elevations with sin e_k = 2 (k + 1/2) / n - 1 (even in the direction's z, so the
 * shader indexes by z without an asin; the steps in elevation are finest at the horizon and
 * about as fine at orbit's limb): L(e, gamma) = ray[e] p_R(gamma) + mie[e] p_M(gamma) per
 * channel (rgb triples), p_R and p_M the phase functions of sky_radiance (common.glsl
 * horizon_sky evaluates them). */
void sky_view_gains(const struct sky *s, double alt_m, int n, float *ray, float *mie);
/* Air mass of the column from a camera alt_m up along elevation elev_rad (as sky_view_gains);
 * the sun disc's transmittance is exp(-tau m). */
float sky_view_air_mass(double alt_m, float elev_rad);
/* The ozone layer's transmittance per channel for the sun at elevation elev_rad (clamped to
 * 0): sky_radiance, the sea's sun irradiance and the sun disc take it. */
void sky_ozone_transmittance(float elev_rad, float out[3]);
/* exp(-tau_c m) per channel: the transmittance of air mass m (sky_view_air_mass). */
void sky_transmittance(float m, float out[3]);

/* common.glsl sky_map_uv: the map coordinates of unit direction r; below SKY_MAP_BELOW_Z its z
 * is raised to it (the ring's middle). */
void sky_map_uv(const float r[3], float uv[2]);

/* The radiance of RGBA8 texel p of s->data (its encoding, above). */
void sky_texel_radiance(const struct sky *s, const uint8_t *p, float out[3]);

/* Sky radiance towards unit direction dir (z up); below the horizon s->below (set by sky_bake;
 * multiple reflections, above). */
void sky_radiance(const struct sky *s, const float dir[3], float rgb[3]);

/* Bake for a sun at elev_deg (may be negative: no sun term then) / azim_deg (CCW from +x). */
int  sky_bake(float elev_deg, float azim_deg, int size, struct sky *out, struct swell_err *err);
void sky_destroy(struct sky *s);

/* The unpolarised Fresnel reflectance of flat water averaged over a uniform sky:
 * 2 int_0^1 F(mu) mu dmu (hemispherical-directional, cosine-weighted). */
double sky_fresnel_avg(void);

/* Byte offset of a mip level in data. */
size_t sky_level_offset(const struct sky *s, int level);

#endif
