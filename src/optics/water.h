/* water.h - the colour of the water body, eq. 28's L_sea (Bruneton 2010), from its inherent
 * optical properties, at the three wavelengths of sky.h (680, 550, 440 nm).
 *
 * Deep open ocean (Case 1 water, Morel & Prieur 1977) with chlorophyll C mg / m^3:
 *   absorption   a = a_w + a_ph + a_g: pure sea water (Pope & Fry 1997: 0.465, 0.0565,
 *                0.00635 / m), phytoplankton (Bricaud et al. 1995: A(lambda) C^E(lambda)) and
 *                dissolved organic matter (a_g(440) = 0.2 (a_w + a_ph)(440), slope 0.014 / nm);
 *   backscatter  b_b = b_bw + b_bp: sea water (Morel 1974: b_w(500) = 0.00288 / m, lambda^-4.32,
 *                half of it backwards) and particles (Loisel & Morel 1998: b_p(550) =
 *                0.3 C^0.62 / m, lambda^-1 below, a backscattering ratio of 1 %);
 *   irradiance reflectance just below the surface R = 0.33 b_b / (a + b_b) (Gordon et al.
 *   1975; Morel & Prieur 1977's f = 0.33).
 * The water-leaving radiance under downwelling irradiance E is L = R E t / (n^2 Q): Q = pi for
 * an isotropic upwelling field, t = 0.98 the transmission into the water of the diffuse and
 * direct light, n^2 = 1.78 the radiance's spreading through the surface; the renderer applies
 * the transmission out of it, (1 - F), per pixel (ocean.frag, eq. 28). So
 *   L_sea = albedo E / pi,  albedo = 0.55 R.
 * At C = 0.1 (the open ocean's median) R = (0.0007, 0.0092, 0.044): deep blue, remote-sensing
 * reflectances (0.00012, 0.0016, 0.0077) / sr, from which NASA's OC4 band ratio reads C = 0.114
 * (test_water); the fixed albedo (0.004, 0.016, 0.024) it replaces was 3x that in green and 12x
 * in red, a teal. */
#ifndef SWELL_WATER_H
#define SWELL_WATER_H

#define WATER_CHLOROPHYLL_OPEN 0.1   /* mg / m^3 */

/* R (above) per channel (680, 550, 440 nm) for chlorophyll c_mg_m3 > 0. */
void water_reflectance(double c_mg_m3, double r[3]);
/* The beam attenuation c = a + b per channel, 1 / m (b the total scattering: sea water's
 * b_w(500) = 0.00288, the particles' 0.3 C^0.62 at 550 nm, lambda^-1): how fast an object's
 * contrast fades along a path through the water (Hu 2006 eq. 4's fog; refract.c). */
void water_attenuation(double c_mg_m3, double out[3]);
/* eq. 28's albedo: L_sea = albedo E / pi (above). */
void water_albedo(double c_mg_m3, float albedo[3]);

#endif
