/* test_sky.c - the RGBA8 sky map's A channel: each level's index, so a fetch on gles2-min
 * reads the LOD it sampled (ocean.frag's own LOD, sky.h SKY_LEVEL_ALPHA). */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <math.h>
#include <cmocka.h>

#include "sky.h"

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

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_level_alpha),
        cmocka_unit_test(test_haze_horizon),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
