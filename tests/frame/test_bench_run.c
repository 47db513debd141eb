/* test_bench_run.c - `swell --bench` end to end on EGL surfaceless: bench_run over a real renderer
 * fills consistent statistics, leaves the renderer's GPU accounting untouched (the baseline's
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

#include "bake/bake.h"
#include "app/bench.h"
#include "gl/gpu.h"
#include "platform/platform.h"
#include "render/renderer.h"
#include "tables/tables.h"

#define W 160
#define H 90
#define FRAMES 5

static struct platform_handle ph;

static void test_bench_run(void **state)
{
    (void)state;
    struct swell_err err = { 0 };
    struct seastate ss;
    memset(&ss, 0, sizeof ss);
    ss.budget_bytes = 4u << 20;     /* the tiny preset: quickest bake */
    struct swell_tables t;
    assert_int_equal(swell_bake(&ss, NULL, &t, &err), 0);
    struct gpu g;
    memset(&g, 0, sizeof g);
    assert_int_equal(gpu_init(&g, TIER_GLES2_MIN, t.state.budget_bytes, &err), 0);
    struct renderer_desc rd = { .tables = &t, .gpu = &g, .quality = QUALITY_LOW,
                                .debug_uncovered = 1 };
    struct renderer *r = NULL;
    if (renderer_create(&rd, &r, &err))
        fail_msg("renderer_create: %s", err.msg);
    uint64_t bytes_before = g.bytes;

    struct bench_desc bd = {
        .ph = &ph, .renderer = r, .gpu = &g, .path = CAMERA_PATH_1KM, .frames = FRAMES,
        .warmup = 1, .scene = "test", .quality = "low", .geometry = "grid",
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
    /* the baseline is accounted on its own record and gone afterwards */
    assert_true(g.bytes == bytes_before);
    assert_true(res.bytes_gpu == bytes_before);

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
    renderer_destroy(r);
    gpu_shutdown(&g);
    tables_destroy(&t);
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
