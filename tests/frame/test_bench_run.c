/* test_bench_run.c - `swell --bench` end to end on EGL surfaceless: bench_run over a real ocean
 * (swell.h, as swell.c draws it) fills consistent statistics, leaves the ocean's GPU accounting
 * untouched (the baseline's
 * objects are its own and freed), and the baseline quad really samples its noise texture (the
 * read-back of its last frame: no clear colour, varied texels, mean near the texture's 127.5).
 * Exit 77 (skip) only when no EGL device exists and CI is not "true" (STYLE.md 12).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "swell.h"
#include "app/bench.h"
#include "core/camera.h"
#include "platform/platform.h"

#define W 160
#define H 90
#define FRAMES 5

static struct platform_handle ph;

/* A frame as swell.c's, without the view's refinements: the camera's matrices, the sea. */
static int frame(void *ctx, const struct camera *cam, double t, struct swell_err *err)
{
    struct camera_frame cf;
    camera_frame_make(cam, W, H, &cf);
    swell_view v = { .viewport = { 0, 0, W, H }, .flags = SWELL_DRAW_CLEAR | SWELL_DRAW_SKY };
    memcpy(v.camera_pos, cam->pos, sizeof v.camera_pos);
    memcpy(v.view, cf.view_rel, sizeof v.view);
    memcpy(v.proj, cf.proj, sizeof v.proj);
    return swell_ocean_draw(ctx, &v, t, err);
}

static void test_bench_run(void **state)
{
    (void)state;
    struct swell_err err = { 0 };
    swell_sea_desc sd = { .budget_bytes = 4u << 20 };     /* the tiny preset: quickest bake */
    swell_sea *sea = NULL;
    assert_int_equal(swell_sea_bake(&sd, &sea, &err), 0);
    swell_ocean_desc od = { .quality = SWELL_QUALITY_LOW, .tier = SWELL_TIER_GLES2_MIN };
    swell_ocean *ocean = NULL;
    if (swell_ocean_create(sea, &od, &ocean, &err))
        fail_msg("swell_ocean_create: %s", err.msg);
    swell_ocean_stats before, after;
    swell_ocean_get_stats(ocean, &before);

    struct bench_desc bd = {
        .ph = &ph, .frame = frame, .ctx = ocean, .path = CAMERA_PATH_1KM, .frames = FRAMES,
        .warmup = 1, .scene = "test", .quality = "low", .geometry = "grid",
        .swell_tier = before.tier,
    };
    camera_defaults(&bd.camera);
    struct bench_result res;
    if (bench_run(&bd, &res, &err))
        fail_msg("bench_run: %s", err.msg);

    assert_int_equal(res.frames, FRAMES);
    assert_int_equal(res.warmup, 1);
    assert_int_equal(res.frame.n, FRAMES);
    assert_int_equal(res.quad.n, FRAMES);
    assert_int_equal(res.width, W);
    assert_int_equal(res.height, H);
    assert_true(res.frame.min_ms > 0.0 && res.quad.min_ms > 0.0);
    assert_true(res.frame.min_ms <= res.frame.median_ms);
    assert_true(res.frame.median_ms <= res.frame.p95_ms && res.frame.p95_ms <= res.frame.max_ms);
    assert_true(res.ratio == res.frame.median_ms / res.quad.median_ms);
    assert_string_equal(res.tier, "gles2-min");
    assert_string_equal(res.path, "1km");
    assert_string_equal(res.platform, "surfaceless");
    assert_true(strlen(res.gl_renderer) > 0);
    assert_true(res.cpu_valid || strstr(res.notes, "perf_event_open") != NULL);
    /* the baseline is the benchmark's own: nothing charged to the ocean's budget */
    swell_ocean_get_stats(ocean, &after);
    assert_true(after.gpu_bytes_charged == before.gpu_bytes_charged && before.gpu_bytes > 0);

    /* The last frame drawn is the baseline quad: the hash-noise texture, trilinear-filtered. */
    uint8_t *rgba = malloc((size_t)W * H * 4);
    assert_non_null(rgba);
    assert_int_equal(ph.be->read_rgba(ph.p, rgba, &err), 0);
    double sum = 0;
    int magenta = 0, changes = 0;
    for (int i = 0; i < W * H; i++) {
        const uint8_t *p = rgba + 4 * i;
        magenta += p[0] == 255 && p[1] == 0 && p[2] == 255;
        sum += p[0] + p[1] + p[2];
        if (i > 0 && memcmp(p, p - 4, 3) != 0)
            changes++;
    }
    double mean = sum / (3.0 * W * H);
    assert_int_equal(magenta, 0);
    assert_true(changes > W * H / 2);
    /* uniform bytes have mean 127.5; filtering averages texels, which keeps the mean */
    assert_true(mean > 112.0 && mean < 143.0);

    char json[8192];
    int n = bench_format_json(&res, json, sizeof json);
    assert_true(n > 0 && (size_t)n < sizeof json);
    assert_non_null(strstr(json, "\"frames\": 5,"));
    free(rgba);
    swell_ocean_destroy(ocean);
    swell_sea_destroy(sea);
}

int main(void)
{
    struct swell_err err = { 0 };
    struct platform_desc pd = { .kind = PLATFORM_SURFACELESS, .width = W, .height = H,
                                .gles_major = 2 };
    int rc = platform_open(&pd, &ph, &err);
    if (rc == SWELL_E_UNSUPPORTED || rc == SWELL_E_EGL) {
        const char *ci = getenv("CI");
        if (ci && strcmp(ci, "true") == 0) {
            fprintf(stderr, "test_bench_run: CI=true and the surfaceless platform failed: %s\n",
                    err.msg);
            return 1;
        }
        fprintf(stderr, "test_bench_run: SKIP, no EGL device: %s\n", err.msg);
        return 77;
    }
    if (rc) {
        fprintf(stderr, "test_bench_run: platform_open: %s\n", err.msg);
        return 1;
    }
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bench_run),
    };
    int failed = cmocka_run_group_tests(tests, NULL, NULL);
    platform_close(&ph);
    return failed ? 1 : 0;
}
