/* test_sky.c - the RGBA8 sky map's A channel: each level's index, so a fetch on gles2-min
 * reads the LOD it sampled (ocean.frag's own LOD, sky.h SKY_LEVEL_ALPHA). */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <math.h>
#include <cmocka.h>

#include "optics/sky.h"

/* Every texel of level l holds A = SKY_LEVEL_ALPHA l, and A / 255 times the scale ocean.frag
 * gets (255 / SKY_LEVEL_ALPHA) gives l back; a trilinear blend of levels l and l + 1 with
 * weight f gives l + f (linear in A). The largest level index stays below 256. */
/* IEEE half to float, independent of quantize.c (normal numbers and zero suffice here). */
static float half_to_float(uint16_t h)
{
    int e = (h >> 10) & 31, m = h & 1023;
    if (e == 0 && m == 0)
        return 0.0f;
    return (h & 0x8000 ? -1.0f : 1.0f) * ldexpf(1.0f + m / 1024.0f, e - 15);
}

static void test_level_alpha(void **state)
{
    struct sky s;
    struct swell_err err;
    (void)state;
    assert_int_equal(sky_bake(30.0f, 10.0f, 256, &s, &err), 0);
    assert_int_equal(s.levels, 9);
    assert_true(SKY_LEVEL_ALPHA * (s.levels - 1) <= 255);
    const float scale = 255.0f / (float)SKY_LEVEL_ALPHA;
    for (int l = 0; l < s.levels; l++) {
        int m = s.size >> l;
        const uint8_t *q = s.data + sky_level_offset(&s, l);
        for (int i = 0; i < m * m; i++)
            assert_int_equal(q[4 * i + 3], SKY_LEVEL_ALPHA * l);
        /* the half-float map (tiers with half-float textures but no gradients use the same
         * path) holds the same A */
        const uint16_t *h = s.half + sky_level_offset(&s, l);
        for (int i = 0; i < m * m; i++)
            assert_true(fabsf(half_to_float(h[4 * i + 3]) * scale - (float)l) < 0.01f);
        float decoded = q[3] / 255.0f * scale;
        assert_true(fabsf(decoded - (float)l) < 1e-4f);
        if (l + 1 < s.levels) {
            const uint8_t *r = s.data + sky_level_offset(&s, l + 1);
            float blend = (0.25f * q[3] + 0.75f * r[3]) / 255.0f * scale;
            assert_true(fabsf(blend - ((float)l + 0.75f)) < 1e-4f);
        }
    }
    sky_destroy(&s);
}

/* sky_haze's horizon (what ocean.vert's haze() evaluates: tau_R p_R gain + tau_M p_M gain)
 * is sky_radiance at elevation 0 in every azimuth, for a high, a low and a set sun; and its
 * extinction is the model's. */
static void test_haze_horizon(void **state)
{
    static const float elevs[] = { 60.0f, 5.0f, -3.0f };
    (void)state;
    for (int e = 0; e < 3; e++) {
        struct sky s;
        struct sky_haze hz;
        struct swell_err err;
        assert_int_equal(sky_bake(elevs[e], 40.0f, 64, &s, &err), 0);
        sky_haze(&s, &hz);
        for (int a = 0; a < 36; a++) {
            float dir[3] = { cosf(a * 0.1745f), sinf(a * 0.1745f), 0.0f }, ref[3];
            sky_radiance(&s, dir, ref);
            float cg = dir[0] * s.sun_dir[0] + dir[1] * s.sun_dir[1] + dir[2] * s.sun_dir[2];
            float g = hz.mie_g, hg = 1.0f + g * g - 2.0f * g * cg;
            float pr = 3.0f / (16.0f * (float)M_PI) * (1.0f + cg * cg);
            float pm = (1.0f - g * g) / (4.0f * (float)M_PI * hg * sqrtf(hg));
            for (int c = 0; c < 3; c++) {
                float v = hz.ray[c] * pr + hz.mie[c] * pm;
                assert_true(fabsf(v - ref[c]) <= 1e-5f + 1e-4f * ref[c]);
            }
        }
        assert_true(fabsf(hz.tau_ext[2] - (0.265f + 1.1f * 0.0252f)) < 1e-6f);
        sky_destroy(&s);
    }
}

/* The background from altitude (sky.h sky_view_gains). Air masses against closed forms: at the
 * sea Kasten & Young's exactly; straight up from h, e^{-h/H} of the sea's; towards the limb
 * from 400 km twice the sea's horizontal column (the ray grazes the surface and leaves again);
 * nothing above the level from 400 km (the air is below). The gains at the sea reproduce
 * sky_radiance, and from orbit the space above the limb is black. */
static double ref_kasten_young(double e_deg)
{
    return 1.0 / (sin(e_deg * M_PI / 180.0) + 0.50572 * pow(e_deg + 6.07995, -1.6364));
}

static void test_view_from_altitude(void **state)
{
    (void)state;
    for (double e = 0.0; e <= 90.0; e += 7.5)
        assert_true(fabs(sky_view_air_mass(0.0, (float)(e * M_PI / 180.0)) -
                         ref_kasten_young(e)) < 1e-4 * ref_kasten_young(e));
    for (double h = 1000.0; h <= 30000.0; h *= 2.0) {
        double m = sky_view_air_mass(h, (float)(M_PI / 2.0));
        if (fabs(m - exp(-h / 8000.0)) > 0.005 * exp(-h / 8000.0))
            fail_msg("zenith from %g m: air mass %g, e^-h/H %g", h, m, exp(-h / 8000.0));
    }
    double limb = acos(6.371e6 / (6.371e6 + 4e5));
    double ml = sky_view_air_mass(4e5, (float)(-limb + 1e-4));
    print_message("from 400 km: grazing air mass %.1f (sea's horizontal %.1f), level %.3g\n", ml,
                  ref_kasten_young(0.0), (double)sky_view_air_mass(4e5, 0.0f));
    assert_true(fabs(ml - 2.0 * ref_kasten_young(0.0)) < 0.03 * ml);
    assert_true(sky_view_air_mass(4e5, 0.0f) == 0.0f);
    /* rays that miss the limb climb through ever thinner air: the column falls with elevation */
    float prev = ml;
    for (double e = -limb + 0.002; e < 0.0; e += 0.002) {
        float m = sky_view_air_mass(4e5, (float)e);
        assert_true(m <= prev);
        prev = m;
    }

    struct sky sk;
    struct swell_err err;
    assert_int_equal(sky_bake(25.0f, 40.0f, 64, &sk, &err), 0);
    enum { N = 90 };
    float ray[3 * N], mie[3 * N];
    sky_view_gains(&sk, 0.0, N, ray, mie);
    const double g = 0.76;
    for (int k = N / 2; k < N; k++) {
        double e = asin(2.0 * (k + 0.5) / N - 1.0);
        for (double az = 0.0; az < 6.2; az += 1.1) {
            float dir[3] = { (float)(cos(e) * cos(az)), (float)(cos(e) * sin(az)), (float)sin(e) };
            float ref[3];
            sky_radiance(&sk, dir, ref);
            double cg = dir[0] * sk.sun_dir[0] + dir[1] * sk.sun_dir[1] + dir[2] * sk.sun_dir[2];
            double p_r = 3.0 / (16.0 * M_PI) * (1.0 + cg * cg), hg = 1.0 + g * g - 2.0 * g * cg;
            double p_m = (1.0 - g * g) / (4.0 * M_PI * hg * sqrt(hg));
            for (int c = 0; c < 3; c++) {
                double l = ray[3 * k + c] * p_r + mie[3 * k + c] * p_m;
                if (fabs(l - ref[c]) > 1e-4 * ref[c] + 1e-9)
                    fail_msg("elevation %g az %g channel %d: gains give %g, sky_radiance %g",
                             e, az, c, l, (double)ref[c]);
            }
        }
    }
    sky_view_gains(&sk, 4e5, N, ray, mie);
    for (int k = N / 2; k < N; k++)
        for (int c = 0; c < 3; c++)
            assert_true(ray[3 * k + c] == 0.0f && mie[3 * k + c] == 0.0f);
    sky_destroy(&sk);
}

/* Multiple reflections (Bruneton 2010 §6, sky.h): below the horizon the sky is the average
 * Fresnel reflectance times the sky irradiance over pi. The average is flat water's under a
 * uniform sky, 2 int F(mu) mu dmu: 0.066 at n = 1.333 (Fresnel's formulas integrated; the
 * diffuse reflectance quoted for a calm sea is 6.6 %); the map's ring outside the horizon
 * circle holds that radiance (8-bit steps), inside the circle's edge the horizon's; and the
 * lookup's constants keep a ray below the horizon in the ring's middle, within the map. */
static void test_below_horizon(void **state)
{
    struct sky s;
    struct swell_err err;
    (void)state;
    double f = sky_fresnel_avg();
    print_message("average Fresnel reflectance %.4f\n", f);
    assert_true(fabs(f - 0.066) < 0.001);
    assert_int_equal(sky_bake(20.0f, 40.0f, 256, &s, &err), 0);
    for (int c = 0; c < 3; c++) {
        float want = (float)f * s.sky_irr[c] / (float)M_PI, got[3];
        assert_true(s.sky_irr[c] > 0.0f);
        assert_true(fabsf(s.below[c] - want) < 1e-6f * want + 1e-9f);
        const float down[3] = { 0.3f, -0.2f, -0.5f }, grazing[3] = { 0.0f, 1.0f, -1e-4f };
        sky_radiance(&s, down, got);
        assert_true(got[c] == s.below[c]);
        sky_radiance(&s, grazing, got);
        assert_true(got[c] == s.below[c]);
    }
    /* level 0: a texel in the ring (a corner, and the middle of an edge) and one just inside
     * the circle on the same axis */
    const int n = s.size, edge = (int)(0.5f * n * (1.0f + SKY_MAP_HORIZON)) + 2;
    const int inside = (int)(0.5f * n * (1.0f + SKY_MAP_HORIZON)) - 2;
    const int at[3] = { 0, edge, inside };
    for (int k = 0; k < 3; k++) {
        const uint8_t *p = s.data + 4 * ((size_t)(k == 0 ? 0 : n / 2) * n + at[k]);
        for (int c = 0; c < 3; c++) {
            float v = p[c] / 255.0f * s.map_scale;
            if (k < 2)
                assert_true(fabsf(v - s.below[c]) <= 0.5f / 255.0f * s.map_scale + 1e-7f);
            else
                assert_true(v > 4.0f * s.below[c]);   /* the horizon sky, several times brighter */
        }
    }
    /* the lookup's lowest z lands in the ring's middle: radius h tan(theta / 2) */
    double th = acos(SKY_MAP_BELOW_Z), r = SKY_MAP_HORIZON * tan(0.5 * th);
    assert_true(fabs(r - 0.5 * (1.0 + SKY_MAP_HORIZON)) < 1e-3);
    sky_destroy(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_level_alpha),
        cmocka_unit_test(test_haze_horizon),
        cmocka_unit_test(test_view_from_altitude),
        cmocka_unit_test(test_below_horizon),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
