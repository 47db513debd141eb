/* test_water.c - the water body's colour (water.h) against published ocean optics: the
 * remote-sensing reflectance of the open ocean, and the chlorophyll that NASA's OC4 band-ratio
 * algorithm (O'Reilly et al. 2000, fitted to in-situ data, independent of the model here)
 * reads from the model's blue/green ratio. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <cmocka.h>
#include "optics/water.h"

/* R_rs above the surface, 1 / sr: R t / (n^2 Q) with water.h's t / n^2 and Q = pi */
static double rrs(double r) { return 0.98 / 1.78 * r / M_PI; }

/* OC4 with the 443 nm band (the maximum of its band ratio in clear water): log10 C =
 * sum a_i x^i, x = log10(R_rs(443) / R_rs(555)). */
static double oc4(double blue, double green)
{
    static const double a[5] = { 0.366, -3.067, 1.930, 0.649, -1.532 };
    double x = log10(blue / green), y = 0.0;
    for (int i = 4; i >= 0; i--)
        y = y * x + a[i];
    return pow(10.0, y);
}

static void test_open_ocean(void **state)
{
    (void)state;
    double r[3];
    water_reflectance(WATER_CHLOROPHYLL_OPEN, r);
    print_message("C %.2f mg/m^3: R %.4f %.4f %.4f, R_rs %.5f %.5f %.5f / sr\n",
                  WATER_CHLOROPHYLL_OPEN, r[0], r[1], r[2], rrs(r[0]), rrs(r[1]), rrs(r[2]));
    /* blue water: R_rs(440) 0.006-0.010, R_rs(550) 0.0012-0.0025, red below 0.0005 */
    assert_true(rrs(r[2]) > 0.006 && rrs(r[2]) < 0.010);
    assert_true(rrs(r[1]) > 0.0012 && rrs(r[1]) < 0.0025);
    assert_true(rrs(r[0]) < 0.0005);
    /* the albedo is that reflectance through the surface (water.h) */
    float al[3];
    water_albedo(WATER_CHLOROPHYLL_OPEN, al);
    for (int k = 0; k < 3; k++)
        assert_true(fabs(al[k] - 0.98 / 1.78 * r[k]) < 1e-6);
}

static void test_band_ratio(void **state)
{
    (void)state;
    static const double cs[] = { 0.1, 0.2, 0.3, 0.5 };
    for (size_t i = 0; i < sizeof cs / sizeof cs[0]; i++) {
        double r[3];
        water_reflectance(cs[i], r);
        double c = oc4(rrs(r[2]), rrs(r[1]));
        print_message("C %.2f: OC4 reads %.3f from the model's 440/550 ratio %.2f\n", cs[i], c,
                      r[2] / r[1]);
        assert_true(fabs(log(c / cs[i])) < log(1.4));
    }
    /* greener with more chlorophyll */
    double lo[3], hi[3];
    water_reflectance(0.05, lo);
    water_reflectance(1.0, hi);
    assert_true(lo[2] / lo[1] > 3.0 * hi[2] / hi[1]);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_open_ocean),
        cmocka_unit_test(test_band_ratio),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
