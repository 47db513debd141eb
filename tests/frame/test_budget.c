/* test_budget.c - the memory budget (issue 17 item 4; DESIGN.md "Budgets") against what the
 * renderer really allocates. For table sets baked at several budgets, on every tier, geometry
 * kind, quality and LOD path:
 *   - the GPU bytes the renderer holds (its accounting's peak over creation and a few frames)
 *     stay within tables/budget.h's budget_gpu_bytes for the set, which the bake checks against
 *     the budget, so a set the bake says fits always opens;
 *   - the model is tight: the largest combination takes at least 80 % of it (93-99 % at the
 *     preset budgets, 87 % with 256^2 tables);
 *   - the renderer opens with exactly the model as its budget; with 64 KiB less, on the
 *     combination that needs most, it blends the loop frames on the CPU (render/stream_gpu.c's
 *     sources left out) within budget_gpu_need_bytes, and with 64 KiB less than that it is
 *     refused (SWELL_E_BUDGET, nothing left accounted).
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
#include "core/camera.h"
#include "geometry/grid.h"
#include "gl/gpu.h"
#include "platform/platform.h"
#include "render/renderer.h"
#include "tables/budget.h"
#include "tables/tables.h"
#include "frame/frame_util.h"

#define W 96
#define H 64

static struct platform_handle ph;

struct combo { int tier, geometry, quality, pixel_lod; };

/* Open a renderer for t on this combination with budget (0: none), draw three frames; the
 * accounting's peak, or 0 with *code set when it was refused. */
static uint64_t peak_of(const struct swell_tables *t, struct combo c, uint64_t budget, int *code)
{
    struct swell_err err = { 0 };
    struct gpu g;
    memset(&g, 0, sizeof g);
    *code = 0;
    if (gpu_init(&g, c.tier, budget, &err))
        fail_msg("gpu_init: %s", err.msg);
    struct renderer_desc rd = { .tables = t, .gpu = &g, .quality = c.quality,
                                .geometry = c.geometry, .pixel_lod = c.pixel_lod };
    struct renderer *r = NULL;
    if (renderer_create(&rd, &r, &err)) {
        *code = err.code;
        assert_int_equal(g.bytes, 0);       /* a refusal leaves nothing accounted */
        gpu_shutdown(&g);
        return 0;
    }
    struct camera cam;
    camera_defaults(&cam);
    for (int f = 0; f < 3; f++) {
        if (renderer_frame(r, &cam, 0.4 * f, W, H, &err))
            fail_msg("renderer_frame: %s", err.msg);
        cam.pitch_deg -= 20.0f;             /* near the sea too: every pattern fetched */
    }
    uint64_t peak = g.peak_bytes;
    renderer_destroy(r);
    gpu_shutdown(&g);
    return peak;
}

static void check_set(uint64_t budget, int size_fs, int frames)
{
    struct swell_err err = { 0 };
    struct seastate ss;
    memset(&ss, 0, sizeof ss);
    ss.budget_bytes = budget;
    ss.size_fs = size_fs;
    ss.frames = frames;
    struct swell_tables t;
    if (swell_bake(&ss, NULL, &t, &err))
        fail_msg("bake at %llu bytes: %s", (unsigned long long)budget, err.msg);
    uint64_t model = budget_gpu_bytes(&t.state);
    static const int tiers[] = { TIER_GLES2_MIN, TIER_GLES2_EXT, TIER_GLES3 };
    uint64_t most = 0;
    struct combo worst = { 0 };
    for (int ti = 0; ti < 3; ti++)
        for (int gk = 0; gk < 2; gk++)
            for (int q = 0; q < 2; q++)
                for (int pl = 0; pl < 2; pl++) {
                    struct combo c = { tiers[ti], gk ? GEOMETRY_PATCHES : GEOMETRY_GRID,
                                       q ? QUALITY_HIGH : QUALITY_LOW, pl };
                    int code;
                    uint64_t peak = peak_of(&t, c, 0, &code);
                    printf("test_budget: set %dx%d x %d frames, tier %s, %s, %s, lod %s: "
                           "%llu of the model's %llu bytes\n", t.state.size_fs, t.state.size_fs,
                           t.state.frames, gpu_tier_name(c.tier), gk ? "patches" : "grid",
                           q ? "high" : "low", pl ? "pixel" : "auto",
                           (unsigned long long)peak, (unsigned long long)model);
                    assert_true(peak > 0 && peak <= model);
                    if (peak > most) {
                        most = peak;
                        worst = c;
                    }
                }
    assert_true(model <= t.state.budget_bytes);     /* what the bake promises */
    assert_true(most >= model / 5 * 4);
    int code;
    assert_true(peak_of(&t, worst, model, &code) == most && code == 0);
    /* short of the GPU blend's sources: the CPU blends, in the least the model says it needs;
     * short of that, refused */
    uint64_t need = budget_gpu_need_bytes(&t.state);
    uint64_t cpu = peak_of(&t, worst, most - 65536, &code);
    printf("test_budget: %llu bytes with the CPU's loop blend (budget %llu), the model's "
           "least %llu\n", (unsigned long long)cpu, (unsigned long long)(most - 65536),
           (unsigned long long)need);
    assert_int_equal(code, 0);
    assert_true(cpu > 0 && cpu < most && cpu <= need);
    assert_true(peak_of(&t, worst, cpu - 65536, &code) == 0);
    assert_int_equal(code, SWELL_E_BUDGET);
    tables_destroy(&t);
}

static void test_tiny(void **state) { (void)state; check_set(SWELL_BUDGET_TINY, 0, 0); }
static void test_default(void **state) { (void)state; check_set(SWELL_BUDGET_DEFAULT, 0, 0); }
/* a large slope table and a large budget: the streamed part dominates */
static void test_large(void **state) { (void)state; check_set(48u << 20, 256, 8); }

int main(void)
{
    int rc = frame_open("test_budget", W, H, &ph);
    if (rc)
        return rc;
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_tiny),
        cmocka_unit_test(test_default),
        cmocka_unit_test(test_large),
    };
    int failed = cmocka_run_group_tests(tests, NULL, NULL);
    platform_close(&ph);
    return failed ? 1 : 0;
}
