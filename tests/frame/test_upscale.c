/* test_upscale.c - render scale (upscale.h, swell --scale): the output is the smaller frame
 * stretched over it, nothing else.
 *
 * The renderer draws into the target at the scaled size (the test reads that frame back from
 * the target itself), and every output pixel must be the bilinear sample of it at the pixel's
 * centre (GL's rule: texel coordinate uv w - 1/2, clamped to the edge texels), within the
 * rounding of an 8-bit filter. Both the frame and the output are drawn over a magenta clear
 * (renderer_desc.debug_uncovered): a pixel the stretch leaves or the sea and sky miss at the
 * smaller size shows. Scales 0.5 (every output pixel between two texels at 1/4, 3/4) and 0.37
 * (odd sizes, no common period), forced gles2-min, both qualities.
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
#include "core/camera.h"
#include "gl/gpu.h"
#include "platform/platform.h"
#include "core/preset.h"
#include "render/renderer.h"
#include "tables/tables.h"
#include "render/upscale.h"
#include "frame/frame_util.h"

#define W 320
#define H 180

static struct platform_handle g_ph;
static struct swell_tables g_tables;
static uint8_t g_out[W * H * 4];
static uint8_t g_small[W * H * 4];

static int magenta(const uint8_t *p) { return p[0] == 255 && p[1] == 0 && p[2] == 255; }

/* GL's bilinear sample of img (w x h, rows bottom first as glReadPixels gives them) at the
 * centre of output pixel (x, y) of W x H, channel c. */
static double bilinear(const uint8_t *img, int w, int h, int x, int y, int c)
{
    double u = (x + 0.5) / W * w - 0.5, v = (y + 0.5) / H * h - 0.5;
    int x0 = (int)floor(u), y0 = (int)floor(v);
    double fx = u - x0, fy = v - y0;
    int xa = x0 < 0 ? 0 : x0 > w - 1 ? w - 1 : x0, xb = x0 + 1 > w - 1 ? w - 1 : x0 + 1;
    int ya = y0 < 0 ? 0 : y0 > h - 1 ? h - 1 : y0, yb = y0 + 1 > h - 1 ? h - 1 : y0 + 1;
    if (x0 + 1 < 0)
        xb = 0;
    if (y0 + 1 < 0)
        yb = 0;
#define T(xx, yy) ((double)img[4 * ((size_t)(yy) * (size_t)w + (size_t)(xx)) + (size_t)c])
    return (1 - fy) * ((1 - fx) * T(xa, ya) + fx * T(xb, ya)) +
           fy * ((1 - fx) * T(xa, yb) + fx * T(xb, yb));
#undef T
}

static void check_scale(int quality, double scale)
{
    struct swell_err err = { 0 };
    struct gpu gpu;
    struct renderer *r = NULL;
    struct upscale up;
    if (gpu_init(&gpu, TIER_GLES2_MIN, 0, &err))
        fail_msg("gpu_init: %s", err.msg);
    struct renderer_desc d = { .tables = &g_tables, .gpu = &gpu, .quality = quality,
                               .sun_elev_deg = 20.0f, .debug_uncovered = 1 };
    if (renderer_create(&d, &r, &err))
        fail_msg("renderer_create: %s", err.msg);
    GLint depth_bits = 0;
    glGetIntegerv(GL_DEPTH_BITS, &depth_bits);
    if (upscale_create(&up, &gpu, 0, W, H, scale, depth_bits, NULL, &err))
        fail_msg("upscale_create: %s", err.msg);
    assert_int_equal(up.w, (int)lround(W * scale));
    assert_int_equal(up.h, (int)lround(H * scale));
    struct camera cam;
    camera_defaults(&cam);
    cam.pos[2] = 6.0;
    cam.pitch_deg = -8.0f;
    int rc = g_ph.be->begin_frame(g_ph.p, &err);
    if (!rc) {
        upscale_begin(&up);
        rc = renderer_frame(r, &cam, 1.5, up.w, up.h, &err);
    }
    if (!rc) {
        /* the frame as the renderer left it in the target */
        glPixelStorei(GL_PACK_ALIGNMENT, 1);
        glReadPixels(0, 0, up.w, up.h, GL_RGBA, GL_UNSIGNED_BYTE, g_small);
        rc = upscale_end(&up, &err);
    }
    if (!rc)
        rc = g_ph.be->present(g_ph.p, &err);
    if (!rc)
        rc = g_ph.be->read_rgba(g_ph.p, g_out, &err);   /* top row first */
    if (rc)
        fail_msg("frame: %s", err.msg);
    int holes_small = 0, holes_out = 0;
    double worst = 0.0, sum = 0.0;
    for (int i = 0; i < up.w * up.h; i++)
        holes_small += magenta(g_small + 4 * i);
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            const uint8_t *p = g_out + 4 * ((size_t)(H - 1 - y) * W + (size_t)x);
            holes_out += magenta(p);
            for (int c = 0; c < 3; c++) {
                double e = fabs(p[c] - bilinear(g_small, up.w, up.h, x, y, c));
                worst = e > worst ? e : worst;
                sum += e;
            }
        }
    print_message("test_upscale: %s scale %.2f (%dx%d): worst %.2f, mean %.3f of 255 from the "
                  "bilinear stretch; magenta %d in the frame, %d in the output\n",
                  render_quality_name(quality), scale, up.w, up.h, worst, sum / (3.0 * W * H),
                  holes_small, holes_out);
    assert_int_equal(holes_small, 0);
    assert_int_equal(holes_out, 0);
    assert_true(worst <= 2.0);   /* the filter's 8-bit weights */
    upscale_destroy(&up);
    renderer_destroy(r);
    gpu_shutdown(&gpu);
}

static void test_half(void **state)
{
    (void)state;
    check_scale(QUALITY_HIGH, 0.5);
    check_scale(QUALITY_LOW, 0.5);
}

static void test_odd(void **state)
{
    (void)state;
    check_scale(QUALITY_HIGH, 0.37);
    check_scale(QUALITY_LOW, 0.37);
}

/* Out of range: refused with the range said, nothing left allocated. */
static void test_refused_scale(void **state)
{
    (void)state;
    struct swell_err err = { 0 };
    struct gpu gpu;
    struct upscale up;
    if (gpu_init(&gpu, TIER_GLES2_MIN, 0, &err))
        fail_msg("gpu_init: %s", err.msg);
    const double bad[] = { 0.0, 0.2, 1.5, NAN };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        err.msg[0] = '\0';
        assert_int_equal(upscale_create(&up, &gpu, 0, W, H, bad[i], 0, NULL, &err), SWELL_E_ARG);
        assert_non_null(strstr(err.msg, "0.25..1"));
        assert_true(gpu.bytes == 0);
    }
    gpu_shutdown(&gpu);
}

int main(void)
{
    int open_rc = frame_open("test_upscale", W, H, &g_ph);
    if (open_rc)
        return open_rc;
    struct seastate ss = { 0 };
    struct swell_err err = { 0 };
    if (preset_load("moderate", &ss, &err) || swell_bake(&ss, NULL, &g_tables, &err)) {
        fprintf(stderr, "test_upscale: bake: %s\n", err.msg);
        return 1;
    }
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_half),
        cmocka_unit_test(test_odd),
        cmocka_unit_test(test_refused_scale),
    };
    int rc = cmocka_run_group_tests(tests, NULL, NULL);
    tables_destroy(&g_tables);
    platform_close(&g_ph);
    return rc;
}
