/* test_coverage.c - every pixel covered wherever the camera is (issue 13): a seeded fuzz of
 * camera poses over every preset's baked sea, each frame cleared to magenta first
 * (renderer_desc.debug_uncovered, `swell --debug uncovered`) and required to hold none.
 *
 * Poses: altitude log-uniform from 0.3 m to 400 km (a third of them below 10 m, where crests
 * reach the camera), pitch uniform in [-89, 89], any heading, a position within 100 km and a
 * time within 1000 s. The renderer keeps the camera CAMERA_CLEARANCE_M above the surface under
 * it (renderer.h); the projected grid's range holds what displacement can reach (grid.c).
 * At the forced gles2-min tier (CPU geometry) for every preset; a share again on gles3, whose
 * grid is built in the vertex shader from the same frame, and with --geometry patches; and a
 * share rolled, any angle (upside down included), from a stream of its own; and a share as
 * panoramic strips of 16:1 and 32:1 (viewports of the bottom rows).
 * A failure prints the pose as a `swell` command line.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>
#include "bake/bake.h"
#include "gl/gpu.h"
#include "platform/platform.h"
#include "core/preset.h"
#include "render/renderer.h"
#include "tables/tables.h"
#include "frame/frame_util.h"

#define W 128
#define H 72
#define SW 512                 /* the surface: wide enough for the strips' viewports */
#define POSES_MIN 80           /* gles2-min poses per preset (5 presets: 400 in all) */
#define POSES_OTHER 20        /* per preset on gles3 and with patches */
#define POSES_ROLL 16         /* per preset with the camera rolled (gles2-min and gles3) */
#define POSES_WIDE 12         /* per preset as a panoramic strip, 16:1 or 32:1 */

static struct platform_handle g_ph;
static uint8_t g_img[SW * H * 4];

static uint64_t g_rng = 0x5eed2026u;
static uint64_t g_roll_rng = 0x5eed2612u;   /* its own stream: the unrolled poses as before */
static uint64_t g_wide_rng = 0x5eed1217u;   /* the panoramic strips' pitch, likewise */

/* xorshift64*: a fixed seed, the same poses on every machine */
static double next_uniform(uint64_t *s)
{
    *s ^= *s >> 12;
    *s ^= *s << 25;
    *s ^= *s >> 27;
    return (double)((*s * 2685821657736338717ull) >> 11) * (1.0 / 9007199254740992.0);
}

static double uniform(void) { return next_uniform(&g_rng); }

static void random_pose(struct camera *c, double *t)
{
    camera_defaults(c);
    double u = uniform();
    /* a third below 10 m, the rest log-uniform up to 400 km (low Earth orbit) */
    c->pos[2] = u < 1.0 / 3.0 ? 0.3 * pow(10.0 / 0.3, 3.0 * u)
                              : 10.0 * pow(40000.0, (u - 1.0 / 3.0) * 1.5);
    c->pos[0] = (uniform() - 0.5) * 2e5;
    c->pos[1] = (uniform() - 0.5) * 2e5;
    c->pitch_deg = (float)(-89.0 + 178.0 * uniform());
    c->heading_deg = (float)(360.0 * uniform());
    *t = 1000.0 * uniform();
}

/* Magenta pixels in the viewport vw x vh at the surface's bottom left: the image's (top row
 * first) last vh rows, first vw columns. */
static int uncovered(const uint8_t *img, int vw, int vh)
{
    int n = 0;
    for (int y = H - vh; y < H; y++)
        for (int x = 0; x < vw; x++) {
            const uint8_t *q = img + 4 * ((size_t)y * SW + x);
            n += q[0] == 255 && q[1] == 0 && q[2] == 255;
        }
    return n;
}

struct run {
    const char *preset;
    int tier, geometry, quality, poses;
    int roll;                   /* 1: each pose also rolled, -180..180 deg */
    int vh;                     /* 0: a W x H viewport; else a panoramic strip SW x vh, drawn
                                   with its field of view narrowed to what the grid covers
                                   (camera_fov_covered) */
};

/* Render `poses` random poses of one preset; returns how many left pixels uncovered. */
static int fuzz(const struct swell_tables *t, const struct run *ru, int *raised)
{
    struct gpu gpu;
    struct renderer *r = NULL;
    struct swell_err err = { 0 };
    struct renderer_desc d = { 0 };
    int bad = 0;
    if (gpu_init(&gpu, ru->tier, 0, &err))
        fail_msg("gpu_init: %s", err.msg);
    d.tables = t;
    d.gpu = &gpu;
    d.quality = ru->quality;
    d.geometry = ru->geometry;
    d.sun_elev_deg = 35.0f;
    d.sun_azim_deg = 20.0f;
    d.debug_uncovered = 1;
    if (renderer_create(&d, &r, &err))
        fail_msg("renderer_create: %s", err.msg);
    for (int k = 0; k < ru->poses; k++) {
        struct camera c;
        struct renderer_stats st;
        double t_s;
        random_pose(&c, &t_s);
        if (ru->roll)
            c.roll_deg = (float)(360.0 * next_uniform(&g_roll_rng) - 180.0);
        if (ru->vh)   /* strips look at the horizon, where their sides had been bare */
            c.pitch_deg = (float)(30.0 * next_uniform(&g_wide_rng) - 15.0);
        int vw = ru->vh ? SW : W, vh = ru->vh ? ru->vh : H;
        if (frame_draw(&g_ph, r, &c, t_s, vw, vh, g_img, &err))
            fail_msg("frame: %s", err.msg);
        renderer_get_stats(r, &st);
        *raised += st.camera_raise_m > 0.0;
        int n = uncovered(g_img, vw, vh);
        if (n > 0) {
            bad++;
            print_error("%d of %d pixels uncovered: swell --preset %s --tier %s --geometry %s "
                        "--quality %s --size %dx%d --sun 35,20 --camera %.3f,%.3f,%.4f "
                        "--heading %.3f --pitch %.3f --roll %.3f --time %.4f --debug uncovered\n", n,
                        vw * vh, ru->preset, gpu_tier_name(ru->tier),
                        geometry_kind_name(ru->geometry), render_quality_name(ru->quality), vw,
                        vh, c.pos[0], c.pos[1], c.pos[2], (double)c.heading_deg,
                        (double)c.pitch_deg, (double)c.roll_deg, t_s);
        }
    }
    renderer_destroy(r);
    gpu_shutdown(&gpu);
    return bad;
}

static void test_camera_fuzz(void **state)
{
    static const char *const presets[] = { "calm", "moderate", "default", "rough", "storm" };
    int bad = 0, poses = 0, raised = 0;
    (void)state;
    for (size_t p = 0; p < sizeof presets / sizeof presets[0]; p++) {
        struct seastate ss = { 0 };
        struct swell_tables t;
        struct swell_err err = { 0 };
        if (preset_load(presets[p], &ss, &err))
            fail_msg("preset %s: %s", presets[p], err.msg);
        ss.budget_bytes = SWELL_BUDGET_TINY;
        if (swell_bake(&ss, NULL, &t, &err))
            fail_msg("swell_bake %s: %s", presets[p], err.msg);
        const struct run runs[] = {
            { presets[p], TIER_GLES2_MIN, GEOMETRY_GRID, QUALITY_HIGH, POSES_MIN, 0, 0 },
            { presets[p], TIER_GLES3, GEOMETRY_GRID, p % 2 ? QUALITY_LOW : QUALITY_HIGH,
              POSES_OTHER, 0, 0 },
            { presets[p], TIER_GLES2_MIN, GEOMETRY_PATCHES, QUALITY_LOW, POSES_OTHER, 0, 0 },
            { presets[p], p % 2 ? TIER_GLES3 : TIER_GLES2_MIN, GEOMETRY_GRID,
              p % 2 ? QUALITY_HIGH : QUALITY_LOW, POSES_ROLL, 1, 0 },
            /* panoramic strips, 16:1 and 32:1 (their sides had been left bare), unrolled and
             * rolled */
            { presets[p], TIER_GLES2_MIN, GEOMETRY_GRID, QUALITY_HIGH, POSES_WIDE, p % 2,
              p % 2 ? 16 : 32 },
        };
        for (size_t k = 0; k < sizeof runs / sizeof runs[0]; k++) {
            bad += fuzz(&t, &runs[k], &raised);
            poses += runs[k].poses;
        }
        tables_destroy(&t);
    }
    print_message("camera fuzz: %d poses, %d with uncovered pixels, %d drawn raised to %.1f m "
                  "above the surface under them\n", poses, bad, raised,
                  (double)CAMERA_CLEARANCE_M);
    assert_true(poses >= 300);
    assert_int_equal(bad, 0);
}

int main(void)
{
    int open_rc = frame_open("test_coverage", SW, H, &g_ph);
    if (open_rc)
        return open_rc;
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_camera_fuzz),
    };
    int rc = cmocka_run_group_tests(tests, NULL, NULL);
    platform_close(&g_ph);
    return rc;
}
