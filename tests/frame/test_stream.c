/* test_stream.c - the loop blend drawn on the GPU (render/stream_gpu.c) against the CPU's
 * (tables/stream.h, byte-exact and unit-tested in tests/unit): every level of every streamed
 * slope and whitecap table read back from the texture the ocean samples, after frames at
 * phases between loop frames, forced gles2-min, high quality (its whitecap tables stream too),
 * on both texture layouts (one texture per level, the software rasteriser's run LOD; and one
 * mipmapped texture, drawn into level by level through OES_fbo_render_mipmap). Channels within
 * 1 of 255 of the CPU's bytes (the GPU rounds a + (b - a) w once, the CPU its 16-bit sum), the
 * whitecap blend's own variance (channel 2 of levels 0 and 1) within 2 (the CPU rounds its
 * square and its factor apart). Then the frames themselves, GPU against CPU blend, and the
 * fallback: asked for the CPU, the renderer says so and draws the same sea.
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
#include "core/preset.h"
#include "gl/gpu.h"
#include "platform/platform.h"
#include "render/internal.h"
#include "tables/stream.h"
#include "tables/tables.h"
#include "frame/frame_util.h"

#define W 320
#define H 180

static struct platform_handle g_ph;
static struct swell_tables g_tables;
static uint8_t g_a[W * H * 4], g_b[W * H * 4];
static const double g_times[3] = { 0.37, 1.91, 7.3 };

static struct renderer *open_renderer(struct gpu *gpu, int pixel_lod, int cpu_blend)
{
    struct swell_err err = { 0 };
    struct renderer *r = NULL;
    if (gpu_init(gpu, TIER_GLES2_MIN, 0, &err))
        fail_msg("gpu_init: %s", err.msg);
    struct renderer_desc d = { .tables = &g_tables, .gpu = gpu, .quality = QUALITY_HIGH,
                               .sun_elev_deg = 25.0f, .pixel_lod = pixel_lod,
                               .cpu_loop_blend = cpu_blend };
    if (renderer_create(&d, &r, &err))
        fail_msg("renderer_create: %s", err.msg);
    return r;
}

static void surface_view(struct camera *c)
{
    camera_defaults(c);
    c->pos[2] = 4.0;
    c->pitch_deg = -6.0f;
}

/* Level l of chain c read back (w x h RGBA8) through a framebuffer of the test's own. */
static void read_level(const struct chain_tex *c, int l, int w, int h, uint8_t *out)
{
    GLint prev = 0;
    GLuint fbo;
    glGetIntegerv(GL_FRAMEBUFFER_BINDING, &prev);
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, chain_at(c, l),
                           c->levels ? 0 : l);
    assert_int_equal(glCheckFramebufferStatus(GL_FRAMEBUFFER), GL_FRAMEBUFFER_COMPLETE);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, out);
    glBindFramebuffer(GL_FRAMEBUFFER, (GLuint)prev);
    glDeleteFramebuffers(1, &fbo);
    assert_int_equal(glGetError(), GL_NO_ERROR);
}

/* Every level of table t as the GPU blended it into c against the CPU's blend at phase ph:
 * the largest difference of channel 2 of levels 0 and 1 of a whitecap table in *mix, of the
 * rest in *rest, and the share of bytes that differ at all in *off. */
static void compare_table(const struct swell_table *t, const struct chain_tex *c,
                          const struct stream_phase *ph, int whitecap, int *rest, int *mix,
                          double *off)
{
    uint8_t *cpu = malloc(stream_blended_bytes(t)), *gpu = malloc(4 * (size_t)t->width * t->height);
    assert_non_null(cpu);
    assert_non_null(gpu);
    if (whitecap)
        stream_blend_whitecap(t, ph, cpu);
    else
        stream_blend(t, ph, cpu);
    long n = 0, differ = 0;
    for (int l = 0; l < t->levels; l++) {
        int w = t->width >> l > 0 ? t->width >> l : 1, h = t->height >> l > 0 ? t->height >> l : 1;
        const uint8_t *ref = cpu + stream_level_offset(t, l);
        read_level(c, l, w, h, gpu);
        for (size_t i = 0; i < 4 * (size_t)w * h; i++) {
            int d = abs((int)gpu[i] - (int)ref[i]);
            int *worst = whitecap && l < 2 && i % 4 == 2 ? mix : rest;
            *worst = d > *worst ? d : *worst;
            differ += d != 0;
            n++;
        }
    }
    *off = (double)differ / (double)n;
    free(gpu);
    free(cpu);
}

static void check_layout(int pixel_lod)
{
    struct gpu gpu;
    struct swell_err err = { 0 };
    struct renderer *r = open_renderer(&gpu, pixel_lod, 0);
    print_message("%s: %s\n", pixel_lod ? "one mipmapped texture" : "a texture per level",
                  r->gpu_blend ? "blended on the GPU" : r->gpu_blend_why);
    assert_int_equal(r->gpu_blend, 1);
    assert_int_equal(r->run_lod, gpu.caps.prefer_run_lod && !pixel_lod);
    assert_true(r->nwc > 0);   /* whitecap tables streamed too */
    struct camera cam;
    surface_view(&cam);
    int rest = 0, mix = 0, tables = 0, mid = 0;
    double off_worst = 0.0;
    for (int k = 0; k < 3; k++) {
        if (frame_draw(&g_ph, r, &cam, g_times[k], W, H, g_a, &err))
            fail_msg("frame: %s", err.msg);
        for (int s = 0; s < r->nfs; s++) {
            struct fs_slot *sl = &r->slot[s];
            double off;
            mid += sl->phase.w > 0;
            compare_table(sl->slope, &sl->slope_tex, &sl->phase, 0, &rest, &mix, &off);
            off_worst = off > off_worst ? off : off_worst;
            tables++;
            if (sl->wc_tex.tex[0]) {
                compare_table(sl->wc, &sl->wc_tex, &sl->phase, 1, &rest, &mix, &off);
                off_worst = off > off_worst ? off : off_worst;
                tables++;
            }
        }
    }
    print_message("  %d tables at 3 phases (%d between two loop frames): largest difference %d "
                  "of 255 (the whitecap blend's variance: %d); at most %.2f %% of a table's "
                  "bytes differ\n", tables, mid, rest, mix, 100.0 * off_worst);
    assert_true(mid >= tables / 2);   /* the blend itself, not frames alone, was compared */
    assert_true(rest <= 1);
    assert_true(mix <= 2);
    renderer_destroy(r);
    gpu_shutdown(&gpu);
}

static void test_per_level(void **state)
{
    (void)state;
    check_layout(0);
}

static void test_mipmapped(void **state)
{
    (void)state;
    check_layout(1);
}

/* The frames: GPU blend against the CPU's (cpu_loop_blend), which also says why it blends on
 * the CPU. RMSE under 1 of 255 (1-of-255 texel differences, magnified where the glitter reads
 * the slopes), measured below. */
static void test_frames(void **state)
{
    (void)state;
    struct gpu ga, gb;
    struct swell_err err = { 0 };
    struct camera cam;
    surface_view(&cam);
    for (int k = 0; k < 3; k++) {
        struct renderer *a = open_renderer(&ga, 0, 0);
        if (frame_draw(&g_ph, a, &cam, g_times[k], W, H, g_a, &err))
            fail_msg("frame: %s", err.msg);
        renderer_destroy(a);
        gpu_shutdown(&ga);
        struct renderer *b = open_renderer(&gb, 0, 1);
        assert_int_equal(b->gpu_blend, 0);
        assert_non_null(b->gpu_blend_why);
        assert_non_null(strstr(b->gpu_blend_why, "asked for"));
        if (frame_draw(&g_ph, b, &cam, g_times[k], W, H, g_b, &err))
            fail_msg("frame: %s", err.msg);
        renderer_destroy(b);
        gpu_shutdown(&gb);
        double se = 0.0;
        int worst = 0;
        for (size_t i = 0; i < sizeof g_a; i++) {
            if (i % 4 == 3)
                continue;
            int d = abs((int)g_a[i] - (int)g_b[i]);
            worst = d > worst ? d : worst;
            se += (double)d * d;
        }
        double rmse = sqrt(se / (3.0 * W * H));
        print_message("t = %.2f s: GPU vs CPU loop blend, RMSE %.3f of 255, largest %d\n",
                      g_times[k], rmse, worst);
        assert_true(rmse < 1.0);
    }
}

int main(void)
{
    int open_rc = frame_open("test_stream", W, H, &g_ph);
    if (open_rc)
        return open_rc;
    struct seastate ss = { 0 };
    struct swell_err err = { 0 };
    if (preset_load("rough", &ss, &err) || swell_bake(&ss, NULL, &g_tables, &err)) {
        fprintf(stderr, "test_stream: bake: %s\n", err.msg);
        return 1;
    }
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_per_level),
        cmocka_unit_test(test_mipmapped),
        cmocka_unit_test(test_frames),
    };
    int rc = cmocka_run_group_tests(tests, NULL, NULL);
    tables_destroy(&g_tables);
    platform_close(&g_ph);
    return rc;
}
