/* test_kelvin.c - the Kelvin wake (geometry/kelvin.h) against what Kelvin's theory fixes
 * independently of the code's formulas: the wedge's half-angle asin(1/3) = 19.47 deg at every
 * speed, the transverse waves' wavelength 2 pi U^2 / g on the track, slopes that are the
 * height's gradient, symmetry about the track; and its map's moments against the field. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>
#include "geometry/kelvin.h"

static struct kelvin_desc boat(double speed)
{
    struct kelvin_desc d = { .speed_mps = speed, .hull_length_m = 9.0, .beam_m = 3.0,
                             .foam_half_life_s = 3.0 };
    return d;
}

/* The outermost angle from the track (deg, seen from the bow) at which the slope passes 2 %
 * of the largest at distance r behind the bow, scanned in 0.01 deg steps out to 30 deg. */
static double edge_angle(const struct kelvin_desc *d, double r)
{
    double smax = 0.0, edge = 0.0;
    for (int pass = 0; pass < 2; pass++)
        for (double a = 0.0; a <= 30.0; a += 0.01) {
            double t = a * M_PI / 180.0;
            struct kelvin_sample s;
            kelvin_eval(d, 0.5 * d->hull_length_m - r * cos(t), r * sin(t), &s);
            double m = hypot(s.slope[0], s.slope[1]);
            if (pass == 0)
                smax = fmax(smax, m);
            else if (m > 0.02 * smax)
                edge = a;
        }
    return edge;
}

static void test_half_angle(void **state)
{
    (void)state;
    const double speeds[2] = { 3.0, 8.0 };
    for (int i = 0; i < 2; i++) {
        struct kelvin_desc d = boat(speeds[i]);
        double lt = 2.0 * M_PI * speeds[i] * speeds[i] / 9.81;
        for (int n = 2; n <= 12; n += 5) {
            double a = edge_angle(&d, n * lt);
            print_message("U %.0f m/s: %2d transverse wavelengths behind the bow, the wake's "
                          "edge at %.2f deg\n", speeds[i], n, a);
            assert_true(a > 18.9 && a < 19.5);
        }
    }
}

/* On the track only the transverse wave: its crests 2 pi U^2 / g apart. */
static void test_transverse_wavelength(void **state)
{
    (void)state;
    const double speeds[2] = { 4.0, 7.0 };
    for (int i = 0; i < 2; i++) {
        struct kelvin_desc d = boat(speeds[i]);
        double lt = 2.0 * M_PI * speeds[i] * speeds[i] / 9.81, prev = 0.0, first = 0.0;
        int ups = 0;
        struct kelvin_sample s0, s1;
        kelvin_eval(&d, -2.0 * lt, 0.0, &s0);
        for (double x = -2.0 * lt; x > -12.0 * lt; x -= 0.001 * lt) {
            kelvin_eval(&d, x - 0.001 * lt, 0.0, &s1);
            if (s0.eta < 0.0 && s1.eta >= 0.0) {
                if (!ups)
                    first = x;
                prev = x;
                ups++;
            }
            s0 = s1;
        }
        double measured = (first - prev) / (ups - 1);
        print_message("U %.0f m/s: %d up-crossings, wavelength %.3f m, theory %.3f m\n",
                      speeds[i], ups, measured, lt);
        assert_true(ups >= 9);
        assert_true(fabs(measured / lt - 1.0) < 0.01);
    }
}

/* The slopes are the height's gradient (to stationary phase's order: its error grows towards
 * the cusp, where phi'' -> 0, so the points lie within 12 deg of the track), and the field is
 * symmetric about the track. */
static void test_gradient_and_symmetry(void **state)
{
    (void)state;
    struct kelvin_desc d = boat(5.0);
    double lt = 2.0 * M_PI * 25.0 / 9.81, worst = 0.0, smax = 0.0, e2 = 0.0, s2 = 0.0;
    for (int n = 0; n < 200; n++) {
        double r = (4.0 + 0.05 * n) * lt, a = (-12.0 + 0.12 * n) * M_PI / 180.0;
        double x = 4.5 - r * cos(a), y = r * sin(a), h = 0.002 * lt;
        struct kelvin_sample s, px, mx, py, my, mirror;
        kelvin_eval(&d, x, y, &s);
        kelvin_eval(&d, x + h, y, &px);
        kelvin_eval(&d, x - h, y, &mx);
        kelvin_eval(&d, x, y + h, &py);
        kelvin_eval(&d, x, y - h, &my);
        kelvin_eval(&d, x, -y, &mirror);
        double gx = (px.eta - mx.eta) / (2.0 * h), gy = (py.eta - my.eta) / (2.0 * h);
        worst = fmax(worst, hypot(gx - s.slope[0], gy - s.slope[1]));
        e2 += (gx - s.slope[0]) * (gx - s.slope[0]) + (gy - s.slope[1]) * (gy - s.slope[1]);
        s2 += s.slope[0] * s.slope[0] + s.slope[1] * s.slope[1];
        smax = fmax(smax, hypot(s.slope[0], s.slope[1]));
        assert_true(fabs(mirror.eta - s.eta) < 1e-9 && fabs(mirror.slope[0] - s.slope[0]) < 1e-9 &&
                    fabs(mirror.slope[1] + s.slope[1]) < 1e-9);
    }
    print_message("largest slope %.4f; the gradient of the height differs by %.4f at most, "
                  "%.1f %% rms\n", smax, worst, 100.0 * sqrt(e2 / s2));
    assert_true(smax > 0.02);
    assert_true(sqrt(e2 / s2) < 0.1 && worst < 0.3 * smax);
}

/* Heights of a 9 m hull: the transverse wave one hull behind the bow is KELVIN_HEIGHT_COEF
 * U^2 / g before the hull's filter; ahead of the bow and beyond the wedge the sea is still. */
static void test_heights(void **state)
{
    (void)state;
    struct kelvin_desc d = boat(4.0);
    double hmax = 0.0;
    for (double x = -4.5 - 12.0; x > -4.5 - 40.0; x -= 0.05) {
        struct kelvin_sample s;
        kelvin_eval(&d, x, 0.0, &s);
        hmax = fmax(hmax, fabs(s.eta));
    }
    double k = 9.81 / 16.0, filt = exp(-(k * 3.0 / 4.0) * (k * 3.0 / 4.0));
    double want = KELVIN_HEIGHT_COEF * 16.0 / 9.81 * filt * sqrt(9.0 / 21.0);
    print_message("transverse crest 12..40 m behind the bow: %.3f m (theory %.3f)\n", hmax, want);
    assert_true(hmax > 0.9 * want && hmax < 2.0 * want);
    struct kelvin_sample s;
    kelvin_eval(&d, 20.0, 0.0, &s);
    assert_true(s.eta == 0.0 && s.foam == 0.0);
    kelvin_eval(&d, -100.0, 100.0 * tan(21.0 * M_PI / 180.0), &s);
    assert_true(s.eta == 0.0 && s.slope[0] == 0.0);
    /* foam: the stern's strip, halving per half-life of sailing */
    struct kelvin_sample f1, f2;
    kelvin_eval(&d, -4.5 - 12.0, 0.0, &f1);
    kelvin_eval(&d, -4.5 - 24.0, 0.0, &f2);
    print_message("stern foam 12 m and 24 m behind: %.3f %.3f\n", f1.foam, f2.foam);
    assert_true(f1.foam > 0.2 && f2.foam < 0.6 * f1.foam);
}

static void test_map(void **state)
{
    (void)state;
    struct kelvin_desc d = boat(5.0);
    struct kelvin_map m;
    struct swell_err err = { 0 };
    assert_int_equal(kelvin_map_build(&d, 256, 128, &m, &err), 0);
    assert_int_equal(m.levels, 9);
    /* the edges are still water */
    for (int i = 0; i < m.w; i++) {
        const uint8_t *a = m.rgba + 4 * i, *b = m.rgba + 4 * ((m.h - 1) * m.w + i);
        assert_true(a[0] == 128 && a[1] == 128 && a[2] == 0 && b[0] == 128 && b[2] == 0);
    }
    /* level 0's mean slope against the field at texel centres (a 2 x 2 box: smoother) */
    double err2 = 0.0, sig2 = 0.0, var_min = 1.0;
    for (int j = 1; j < m.h - 1; j++)
        for (int i = 1; i < m.w - 1; i++) {
            const uint8_t *p = m.rgba + 4 * (j * m.w + i);
            double sx = (p[0] - 128.0) / 127.0 * m.slope_scale;
            double sy = (p[1] - 128.0) / 127.0 * m.slope_scale;
            double msq = p[2] / 255.0 * m.slope_scale * m.slope_scale;
            var_min = fmin(var_min, msq - sx * sx - sy * sy + 3.0 * m.slope_scale *
                                                              m.slope_scale / 255.0);
            struct kelvin_sample s;
            double x, y;
            kelvin_map_point(&m, d.hull_length_m, (i + 0.5) / m.w, (j + 0.5) / m.h, &x, &y);
            kelvin_eval(&d, x, y, &s);
            err2 += (sx - s.slope[0]) * (sx - s.slope[0]) + (sy - s.slope[1]) * (sy - s.slope[1]);
            sig2 += s.slope[0] * s.slope[0] + s.slope[1] * s.slope[1];
        }
    print_message("map %dx%d, %.1f m before the bow, %.0f m long, spread %.3f + %.3f; slope "
                  "scale %.3f; level 0 vs the field: relative rms %.3f\n", m.w, m.h, m.ahead_m,
                  m.span_m, m.spread, m.spread_offset, m.slope_scale, sqrt(err2 / sig2));
    assert_true(sqrt(err2 / sig2) < 0.35);
    assert_true(var_min >= 0.0);
    /* the last level: a mean near 0 (waves average out), the variance kept */
    const uint8_t *top = m.rgba + m.offset[m.levels - 1];
    print_message("1x1 level: %d %d %d %d\n", top[0], top[1], top[2], top[3]);
    assert_true(abs(top[0] - 128) <= 2 && abs(top[1] - 128) <= 1 && top[2] > 0);
    kelvin_map_free(&m);
    d.speed_mps = 0.1;
    assert_int_equal(kelvin_map_build(&d, 256, 128, &m, &err), SWELL_E_ARG);
    print_message("%s\n", err.msg);
    assert_non_null(strstr(err.msg, "speed 0.1 m/s"));
    d = boat(5.0);
    d.beam_m = NAN;
    assert_int_equal(kelvin_check(&d, &err), SWELL_E_ARG);
    assert_non_null(strstr(err.msg, "beam"));
    d = boat(5.0);
    assert_int_equal(kelvin_map_build(&d, 300, 128, &m, &err), SWELL_E_ARG);
}

/* The map's heights (the geometry's, kelvin_map_height): at a fine footprint the field itself
 * (the demo boat's 512 x 256 map; measured 0.6 % rms), at a 16 m one the waves averaged out
 * (0.026 m rms against the field's 0.115 m; the map's texels are boxes in the warped (u, v),
 * so the value is not a 16 m square's mean, which is 0.016 m), off the map nothing. Fails with
 * the warp's u and v swapped (tried: 126 % rms). The level's choice is tested on the grid
 * (test_grid test_grid_wake). */
static void test_map_heights(void **state)
{
    (void)state;
    struct kelvin_desc d = boat(4.0);
    struct kelvin_map m;
    struct swell_err err = { 0 };
    assert_int_equal(kelvin_map_build(&d, 512, 256, &m, &err), 0);
    double err2 = 0.0, sig2 = 0.0, coarse2 = 0.0, box2 = 0.0, peak = 0.0;
    int n = 0;
    uint32_t seed = 12345u;
    for (int k = 0; k < 4000; k++) {
        seed = seed * 1664525u + 1013904223u;
        double a = (seed >> 8) / 16777216.0;
        seed = seed * 1664525u + 1013904223u;
        double b = (seed >> 8) / 16777216.0;
        /* points within the wedge, 1 to 60 m behind the stern */
        double x = -4.5 - 1.0 - 59.0 * a, back = 4.5 - x;
        double y = (2.0 * b - 1.0) * 0.33 * back;
        struct kelvin_sample s;
        kelvin_eval(&d, x, y, &s);
        double h = kelvin_map_height(&m, x, y, 0.02f);
        err2 += (h - s.eta) * (h - s.eta);
        sig2 += s.eta * s.eta;
        peak = fmax(peak, fabs(s.eta));
        /* a 16 m footprint: against the field's mean over a 16 m box there */
        double mean = 0.0;
        for (int j = 0; j < 8; j++)
            for (int i = 0; i < 8; i++) {
                struct kelvin_sample t;
                kelvin_eval(&d, x + 2.0 * (i - 3.5), y + 2.0 * (j - 3.5), &t);
                mean += t.eta / 64.0;
            }
        double hc = kelvin_map_height(&m, x, y, 16.0f);
        coarse2 += (hc - mean) * (hc - mean);
        box2 += mean * mean;
        n++;
    }
    double rel = sqrt(err2 / sig2), coarse = sqrt(coarse2 / n), field = sqrt(sig2 / n);
    print_message("heights, 4 m/s: field rms %.3f m (peak %.3f m); map at a 2 cm footprint "
                  "relative rms error %.3f; at 16 m rms %.4f m against the box mean's %.4f m\n",
                  field, peak, rel, coarse, sqrt(box2 / n));
    assert_true(peak > 0.05);
    assert_true(rel < 0.15);
    assert_true(coarse < 0.3 * field);
    /* off the map, or ahead of it */
    assert_true(kelvin_map_height(&m, 100.0, 0.0, 0.1f) == 0.0f);
    assert_true(kelvin_map_height(&m, -20.0, 200.0, 0.1f) == 0.0f);
    assert_true(kelvin_map_height(&m, -1e5, 0.0, 0.1f) == 0.0f);
    kelvin_map_free(&m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_half_angle),
        cmocka_unit_test(test_transverse_wavelength),
        cmocka_unit_test(test_gradient_and_symmetry),
        cmocka_unit_test(test_heights),
        cmocka_unit_test(test_map),
        cmocka_unit_test(test_map_heights),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
