/* Golden frames: the `swell` program renders five scenes at the forced gles2-min tier, with the
 * per-pixel texture LOD a gles2-min GPU takes (--lod pixel; test_render's test_run_lod checks
 * llvmpipe's own path, one level per run, against it), and each frame is compared with tests/golden/NAME.png within a tolerance (llvmpipe is deterministic on
 * one machine; the tolerance absorbs last-bit differences of FFTW/libm on another CPU).
 * Regenerate deliberately with `make golden` (SWELL_GOLDEN_UPDATE=1), then look at the PNGs. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <cmocka.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/image.h"

struct scene {
    const char *name;
    const char *args;
};

/* calm noon; rough sea with whitecaps; low sun glint; 1 km; 10 km */
static const struct scene scenes[] = {
    { "calm_noon", "--preset calm --sun 75,90 --camera 0,0,8 --pitch -12" },
    { "storm_whitecaps", "--preset storm --sun 40,200 --camera 0,0,15 --pitch -25" },
    { "low_sun_glint", "--preset moderate --sun 6,0 --camera 0,0,10 --heading 0 --pitch -4" },
    { "altitude_1km", "--preset moderate --path 1km" },
    { "altitude_10km", "--preset rough --path 10km" },
};

/* Per-pixel tolerance: RMSE over RGB and at most 0.5% of pixels off by > 24. The goldens are
 * made on x86-64, where a frame repeats them within RMSE 0.003: RMSE 2.0 there. swell built for
 * another architecture (SWELL_TARGET_ARCH, default this program's) draws from tables its FFTW
 * rounds differently, with llvmpipe's code for that CPU: measured on arm64 (tools/cross-test.sh,
 * the five scenes under qemu) RMSE 0.39, 0.60, 1.61, 2.26 and 3.57 and at most 0.20 % of
 * pixels off by > 24 (storm: whitecap thresholds met a little elsewhere), so RMSE 4.0 there. */
#if defined(__x86_64__)
#define HOST_ARCH "amd64"
#elif defined(__aarch64__)
#define HOST_ARCH "arm64"
#elif defined(__arm__)
#define HOST_ARCH "armhf"
#else
#define HOST_ARCH "other"
#endif
#define MAX_RMSE_AMD64 2.0
#define MAX_RMSE_OTHER 4.0
#define MAX_BAD_FRACTION 0.005
#define BAD_LEVEL 24

static double max_rmse(void)
{
    const char *a = getenv("SWELL_TARGET_ARCH");
    return strcmp(a && *a ? a : HOST_ARCH, "amd64") == 0 ? MAX_RMSE_AMD64 : MAX_RMSE_OTHER;
}

static void run_scene(const struct scene *s)
{
    const char *build = getenv("SWELL_BUILD") ? getenv("SWELL_BUILD") : "build/rel";
    const char *tmp = getenv("SWELL_TMP") ? getenv("SWELL_TMP") : "/tmp";
    /* a runner for another architecture's swell (qemu-user: tools/cross-test.sh) */
    const char *exec = getenv("SWELL_EXEC") ? getenv("SWELL_EXEC") : "";
    int update = getenv("SWELL_GOLDEN_UPDATE") && !strcmp(getenv("SWELL_GOLDEN_UPDATE"), "1");
    char out[512], golden[512], cmd[2048];
    snprintf(out, sizeof out, "%s/golden_%s.png", tmp, s->name);
    snprintf(golden, sizeof golden, "tests/golden/%s.png", s->name);
    snprintf(cmd, sizeof cmd,
             "%s %s/swell --platform surfaceless --tier gles2-min --lod pixel --size 256x144 --time 3 "
             "--debug uncovered "
             "--budget tiny %s --out %s > %s/golden_%s.log 2>&1",
             exec, build, s->args, update ? golden : out, tmp, s->name);
    int rc = system(cmd);
    if (rc != 0)
        fail_msg("%s: swell failed (%d); see %s/golden_%s.log", s->name, rc, tmp, s->name);
    if (update) {
        print_message("updated %s\n", golden);
        return;
    }
    uint8_t *a = NULL, *b = NULL;
    int aw, ah, bw, bh;
    struct swell_err err = { 0 };
    if (image_read_png(out, &a, &aw, &ah, &err))
        fail_msg("%s", err.msg);
    if (image_read_png(golden, &b, &bw, &bh, &err))
        fail_msg("%s (regenerate with `make golden`)", err.msg);
    assert_int_equal(aw, bw);
    assert_int_equal(ah, bh);
    struct image_diff d;
    image_compare(a, b, aw, ah, BAD_LEVEL, &d);
    double bad = (double)d.pixels_over / (double)d.pixels;
    print_message("%-16s rmse %.3f, max %d, %.4f%% pixels over %d\n", s->name, d.rmse,
                  d.max_abs, bad * 100.0, BAD_LEVEL);
    if (d.rmse > max_rmse() || bad > MAX_BAD_FRACTION)
        fail_msg("%s differs from %s: rmse %.3f (max %.1f), %.3f%% pixels off by > %d (max "
                 "%.1f%%), first at (%d, %d); frame in %s", s->name, golden, d.rmse, max_rmse(),
                 bad * 100.0, BAD_LEVEL, MAX_BAD_FRACTION * 100.0, d.first_x, d.first_y, out);
    free(a);
    free(b);
}

#define SCENE_TEST(i) static void test_scene_##i(void **st) { (void)st; run_scene(&scenes[i]); }
SCENE_TEST(0)
SCENE_TEST(1)
SCENE_TEST(2)
SCENE_TEST(3)
SCENE_TEST(4)

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_scene_0), cmocka_unit_test(test_scene_1),
        cmocka_unit_test(test_scene_2), cmocka_unit_test(test_scene_3),
        cmocka_unit_test(test_scene_4),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
