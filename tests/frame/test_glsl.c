/* test_glsl.c - the shaders' math against its C reference, on the GPU (issue 14 item 2): a
 * function of shaders_gles/common.glsl is rendered over a grid of inputs (tests/glsl/fn_*.frag,
 * compiled by shader.c beside a copy of common.glsl, so the include is the real one), read back
 * as 16 bits per value and compared with the C function in src/ at every pixel, on gles2-min
 * (mediump) and on the best tier.
 *
 * fresnel_eff (Bruneton 2010 eq. 26) against fresnel.c fresnel_effective_tex; tone_map against
 * tonemap.h tone_map_rgb; whitecap_cover (Dupuy 2012 eq. 6 with Abramowitz-Stegun's erf)
 * against whitecap.c whitecap_dupuy_coverage (libm's erf). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <cmocka.h>
#include "optics/fresnel.h"
#include "core/fsutil.h"
#include "gl/gpu.h"
#include "platform/platform.h"
#include "optics/ross.h"
#include "gl/shader.h"
#include "optics/sky.h"
#include "optics/tonemap.h"
#include "geometry/vshade.h"
#include "bake/whitecap.h"
#include "core/camera.h"
#include "geometry/grid.h"
#include "frame/frame_util.h"

#define W 64
#define H 32

static struct platform_handle g_ph;
static char g_dir[512];

/* g_dir/name from src_dir/name (fsutil.h) */
static void copy_file(const char *src_dir, const char *name)
{
    char a[600], b[600];
    uint8_t *data = NULL;
    size_t n = 0;
    struct swell_err err = { 0 };
    if (fs_join(a, sizeof a, src_dir, name, &err) || fs_join(b, sizeof b, g_dir, name, &err) ||
        fs_read_file(a, 1u << 20, &data, &n, &err) || fs_write_atomic(b, data, n, &err))
        fail_msg("copy %s/%s -> %s: %s", src_dir, name, g_dir, err.msg);
    free(data);
}

/* A texture for a function that samples one: size x size RGBA8 (rows bottom-up), bound to
 * unit 0 as fn_tex, bilinear, no mips; scale is the uniform fn_scale. */
struct fn_tex {
    const uint8_t *rgba;
    int size;
    float scale[4];
};

/* A program of test_glsl's at tier, its uniforms' locations in loc. */
static void fn_program(int tier, const char *vs, const char *fs, const char *defines,
                       const char *const *names, int count, const struct shader_attrib *attribs,
                       int nattr, struct gpu *gpu, struct shader_program *prog, GLint *loc)
{
    struct swell_err err = { 0 };
    if (gpu_init(gpu, tier, 0, &err))
        fail_msg("gpu_init: %s", err.msg);
    struct shader_desc d = { .dir = g_dir, .vs_file = vs, .fs_file = fs, .caps = &gpu->caps,
                             .uniform_names = names, .uniform_count = count,
                             .uniform_locations = loc, .attribs = attribs, .attrib_count = nattr,
                             .defines = defines };
    if (shader_program_build(&d, prog, &err))
        fail_msg("%s at %s: %s", fs, gpu_tier_name(tier), err.msg);
}

static void fn_frame_begin(const struct shader_program *prog)
{
    struct swell_err err = { 0 };
    if (g_ph.be->begin_frame(g_ph.p, &err))
        fail_msg("begin_frame: %s", err.msg);
    glViewport(0, 0, W, H);
    glDisable(GL_BLEND);
    glDisable(GL_DEPTH_TEST);
    glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    glUseProgram(prog->program);
}

/* The frame's 16-bit values: out[y * W + x] at pixel (x, y), y counted from the bottom as
 * gl_FragCoord; covered[] (or NULL): whether the pixel was drawn (alpha 255). */
static void fn_frame_read(double *out, int *covered)
{
    struct swell_err err = { 0 };
    static uint8_t rgba[W * H * 4];
    assert_int_equal(glGetError(), GL_NO_ERROR);
    if (g_ph.be->present(g_ph.p, &err) || g_ph.be->read_rgba(g_ph.p, rgba, &err))
        fail_msg("read back: %s", err.msg);
    for (int r = 0; r < H; r++)   /* read_rgba: top row first */
        for (int x = 0; x < W; x++) {
            const uint8_t *p = rgba + 4 * ((size_t)r * W + x);
            out[(H - 1 - r) * W + x] = (p[0] + p[1] / 255.0) / 255.0;
            if (covered)
                covered[(H - 1 - r) * W + x] = p[3] == 255;
        }
}

/* Render fs (with defines, or NULL) over W x H at tier with uniform fn_in = in and, unless tx is
 * NULL, its texture; out as fn_frame_read. */
static void render_fn(int tier, const char *fs, const char *defines, const float in[4],
                      const struct fn_tex *tx, double *out)
{
    struct gpu gpu;
    struct shader_program prog = { 0 };
    static const char *const names[] = { "fn_in", "fn_tex", "fn_scale" };
    static const struct shader_attrib attribs[] = { { "a_pos", 0 } };
    GLint loc[3];
    fn_program(tier, "fn.vert", fs, defines, names, 3, attribs, 1, &gpu, &prog, loc);
    fn_frame_begin(&prog);
    static const float tri[6] = { -1.0f, -1.0f, 3.0f, -1.0f, -1.0f, 3.0f };
    GLuint vbo;
    glGenBuffers(1, &vbo);
    glBindBuffer(GL_ARRAY_BUFFER, vbo);
    glBufferData(GL_ARRAY_BUFFER, sizeof tri, tri, GL_STATIC_DRAW);
    glUniform4fv(loc[0], 1, in);
    GLuint tex = 0;
    if (tx) {
        glActiveTexture(GL_TEXTURE0);
        glGenTextures(1, &tex);
        glBindTexture(GL_TEXTURE_2D, tex);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, tx->size, tx->size, 0, GL_RGBA,
                     GL_UNSIGNED_BYTE, tx->rgba);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        glUniform1i(loc[1], 0);
        glUniform4fv(loc[2], 1, tx->scale);
    }
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, (const void *)0);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDisableVertexAttribArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    glDeleteBuffers(1, &vbo);
    if (tex)
        glDeleteTextures(1, &tex);
    fn_frame_read(out, NULL);
    shader_program_destroy(&prog);
    gpu_shutdown(&gpu);
}

/* eq. 26 of the bumped view's Fresnel f in [0.03, 1] and a slope deviation in [0, 0.5] (the
 * range Bruneton fitted): within 3e-3 everywhere (mediump's exp2 / log2, the 16-bit read), where
 * the form the shader had before (exp(-2.69 sigma) as a factor of f - R0, not an exponent)
 * differs by up to 0.14. */
static void test_fresnel_eff(void **state)
{
    (void)state;
    const float in[4] = { 0.03f, 0.97f / W, 0.0f, 0.5f / H };
    static const int tiers[] = { TIER_GLES2_MIN, -1 };
    static double got[W * H];
    double old_max = 0.0;
    for (size_t t = 0; t < sizeof tiers / sizeof tiers[0]; t++) {
        render_fn(tiers[t], "fn_fresnel_eff.frag", NULL, in, NULL, got);
        double worst = 0.0;
        int wx = 0, wy = 0;
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++) {
                double f = in[0] + in[1] * (x + 0.5), s = in[2] + in[3] * (y + 0.5);
                double want = fresnel_effective_tex(f, s), e = fabs(got[y * W + x] - want);
                double r0 = fresnel_exact(1.0, SWELL_WATER_IOR);
                double old = r0 + (f - r0) * exp(-2.69 * s) / (1.0 + 22.7 * pow(s, 1.5));
                old_max = fmax(old_max, fabs(old - want));
                if (e > worst) {
                    worst = e;
                    wx = x;
                    wy = y;
                }
            }
        print_message("fresnel_eff at %s: worst |shader - fresnel_effective_tex| %.2e at f %.3f, "
                      "sigma %.3f (the old form was off by up to %.3f)\n",
                      tiers[t] < 0 ? "the best tier" : gpu_tier_name(tiers[t]), worst,
                      in[0] + in[1] * (wx + 0.5), in[2] + in[3] * (wy + 0.5), old_max);
        assert_true(worst < 3e-3);
    }
    assert_true(old_max > 0.1);   /* the grid of inputs tells the two forms apart */
}

/* The display transform: radiances u (c, 1 - c, 1/2), u in [0, 20] (the exposure folded in:
 * the sea and sky sit near 0.1-2, the sun's glitter far above), c in [0, 1], every channel
 * within 3e-3 of tonemap.h's (mediump's division and sqrt, the 16-bit read); and the hue
 * kept: where every channel is resolved (> 0.1), each channel's share of the largest is
 * sqrt of the radiance's within 1e-2, where a per-channel curve is off by up to 0.2. */
static void test_tone_map(void **state)
{
    (void)state;
    const float in[4] = { 0.0f, 20.0f / W, 0.0f, 1.0f / H };
    static const int tiers[] = { TIER_GLES2_MIN, -1 };
    static double got[3][W * H];
    double per_channel_off = 0.0;
    for (size_t t = 0; t < sizeof tiers / sizeof tiers[0]; t++) {
        for (int ch = 0; ch < 3; ch++)
            render_fn(tiers[t], "fn_tone_map.frag",
                      ch == 0 ? "TM_CHANNEL=0" : ch == 1 ? "TM_CHANNEL=1" : "TM_CHANNEL=2", in,
                      NULL, got[ch]);
        double worst = 0.0, hue = 0.0;
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++) {
                float u = in[0] + in[1] * (x + 0.5f), c = in[2] + in[3] * (y + 0.5f);
                float rad[3] = { u * c, u * (1.0f - c), 0.5f * u }, want[3];
                tone_map_rgb(rad, want);
                double m = 0.0, rm = fmax(fmax(rad[0], rad[1]), rad[2]), g[3];
                for (int ch = 0; ch < 3; ch++) {
                    g[ch] = got[ch][y * W + x];
                    worst = fmax(worst, fabs(g[ch] - want[ch]));
                    m = fmax(m, g[ch]);
                }
                for (int ch = 0; ch < 3 && rm > 0.0; ch++) {
                    double share = sqrt(rad[ch] / rm);
                    double pc = sqrt(rad[ch] / (1.0 + rad[ch])) /
                                sqrt(rm / (1.0 + rm));
                    if (g[ch] > 0.1 && m > 0.1)
                        hue = fmax(hue, fabs(g[ch] / m - share));
                    if (want[ch] > 0.1)
                        per_channel_off = fmax(per_channel_off, fabs(pc - share));
                }
            }
        print_message("tone_map at %s: worst |shader - tone_map_rgb| %.2e; hue: shares off by "
                      "%.2e (a per-channel curve: %.3f)\n",
                      tiers[t] < 0 ? "the best tier" : gpu_tier_name(tiers[t]), worst, hue,
                      per_channel_off);
        assert_true(worst < 3e-3);
        assert_true(hue < 1e-2);
    }
    assert_true(per_channel_off > 0.1);   /* the grid tells a per-channel curve apart */
}

/* Eq. 6's coverage for foam-memory means mu in [-1, 1] about the threshold and variances in
 * [0.002, 0.5]: within 3e-3 of the C with libm's erf everywhere (Abramowitz-Stegun 7.1.25 is
 * within 2.5e-5; the rest is mediump and the 16-bit read); the grid spans coverages from
 * near 0 to near 1. */
static void test_whitecap_cover(void **state)
{
    (void)state;
    const float in[4] = { -1.0f, 2.0f / W, 0.002f, 0.5f / H };
    static const int tiers[] = { TIER_GLES2_MIN, -1 };
    static double got[W * H];
    for (size_t t = 0; t < sizeof tiers / sizeof tiers[0]; t++) {
        render_fn(tiers[t], "fn_whitecap_cover.frag", NULL, in, NULL, got);
        double worst = 0.0, lo = 1.0, hi = 0.0;
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++) {
                double mu = in[0] + in[1] * (x + 0.5), var = in[2] + in[3] * (y + 0.5);
                double want = whitecap_dupuy_coverage(0.0, mu, var);
                worst = fmax(worst, fabs(got[y * W + x] - want));
                lo = fmin(lo, want);
                hi = fmax(hi, want);
            }
        print_message("whitecap_cover at %s: worst |shader - whitecap_dupuy_coverage| %.2e "
                      "(coverages %.3f-%.3f)\n",
                      tiers[t] < 0 ? "the best tier" : gpu_tier_name(tiers[t]), worst, lo, hi);
        assert_true(worst < 3e-3);
        assert_true(lo < 0.01 && hi > 0.99);
    }
}

/* Smith's shadowing 1 / (1 + Lambda) of eq. 16 for view cosines in [0.01, 1] and slope
 * variances in [0.0005, 0.1] (calm to beyond storm): within 5e-3 of ross.h's erfc form
 * (Walter's fit is within 0.35 %; the rest is mediump and the 16-bit read), and the grid spans
 * grazing shadowing below 0.3 to none. */
static void test_ross_lambda(void **state)
{
    (void)state;
    const float in[4] = { 0.01f, 0.99f / W, 0.0005f, 0.0995f / H };
    static const int tiers[] = { TIER_GLES2_MIN, -1 };
    static double got[W * H];
    for (size_t t = 0; t < sizeof tiers / sizeof tiers[0]; t++) {
        render_fn(tiers[t], "fn_ross_lambda.frag", NULL, in, NULL, got);
        double worst = 0.0, lo = 1.0, hi = 0.0;
        int wx = 0, wy = 0;
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++) {
                double c = in[0] + in[1] * (x + 0.5), var = in[2] + in[3] * (y + 0.5);
                double want = 1.0 / (1.0 + ross_lambda_exact(fmin(c, 0.9999), var));
                double e = fabs(got[y * W + x] - want);
                if (e > worst) {
                    worst = e;
                    wx = x;
                    wy = y;
                }
                lo = fmin(lo, want);
                hi = fmax(hi, want);
            }
        print_message("ross_lambda at %s: worst |shader - ross_lambda_exact| of 1 / (1 + Lambda) "
                      "%.2e at cos %.3f, var %.4f (shadowing %.3f-%.3f)\n",
                      tiers[t] < 0 ? "the best tier" : gpu_tier_name(tiers[t]), worst,
                      in[0] + in[1] * (wx + 0.5), in[2] + in[3] * (wy + 0.5), lo, hi);
        assert_true(worst < 5e-3);
        assert_true(lo < 0.3 && hi > 0.999);
    }
}

/* The sky map's lookup (Bruneton 2010 §5.2's stereographic map, sky_map_uv, one bilinear
 * fetch of the baked RGBA8 level 0, decoded by sky_decode) against sky.c's sky_radiance for
 * the same direction, at elevations -30 to 89 degrees over all azimuths, the sun at 30
 * degrees: within 2 % of the map's largest channel scale (8-bit steps and bilinear
 * interpolation; measured below), where the same map read mirrored (v flipped, the rows'
 * order) is off by far more. Below the horizon the map's ring (Bruneton §6's multiple
 * reflections, sky.h), except within 1.5 degrees of the horizon, where the bilinear fetch
 * straddles the circle's edge. */
static void test_sky_lookup(void **state)
{
    (void)state;
    struct sky sky;
    struct swell_err err = { 0 };
    if (sky_bake(30.0f, 20.0f, 256, &sky, &err))
        fail_msg("sky_bake: %s", err.msg);
    const float deg = (float)(M_PI / 180.0);
    const float in[4] = { 0.0f, 2.0f * (float)M_PI / W, -30.0f * deg, 119.0f * deg / H };
    static const int tiers[] = { TIER_GLES2_MIN, -1 };
    static double got[3][W * H];
    float peak = 0.0f;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            float az = in[0] + in[1] * (x + 0.5f), el = in[2] + in[3] * (y + 0.5f), rgb[3];
            float d[3] = { cosf(el) * cosf(az), cosf(el) * sinf(az), sinf(el) };
            sky_radiance(&sky, d, rgb);
            peak = fmaxf(peak, fmaxf(rgb[0], fmaxf(rgb[1], rgb[2])));
        }
    struct fn_tex tx = { sky.data, sky.size, { 0.0f, 1.25f * peak, 0.0f, 0.0f } };
    const float top = fmaxf(sky.map_scale[0], fmaxf(sky.map_scale[1], sky.map_scale[2]));
    for (size_t t = 0; t < sizeof tiers / sizeof tiers[0]; t++) {
        for (int ch = 0; ch < 3; ch++) {
            tx.scale[0] = sky.map_scale[ch];
            render_fn(tiers[t], "fn_sky_lookup.frag",
                      ch == 0 ? "SKY_CHANNEL=0" : ch == 1 ? "SKY_CHANNEL=1" : "SKY_CHANNEL=2",
                      in, &tx, got[ch]);
        }
        double worst = 0.0, flipped = 0.0, below = 0.0;
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++) {
                float az = in[0] + in[1] * (x + 0.5f), el = in[2] + in[3] * (y + 0.5f);
                if (fabsf(el) < 1.5f * deg)
                    continue;
                float d[3] = { cosf(el) * cosf(az), cosf(el) * sinf(az), sinf(el) };
                float m[3] = { d[0], -d[1], d[2] }, want[3], mirror[3];
                sky_radiance(&sky, d, want);
                sky_radiance(&sky, m, mirror);
                for (int ch = 0; ch < 3; ch++) {
                    double e = fabs(got[ch][y * W + x] * tx.scale[1] - want[ch]);
                    worst = fmax(worst, e);
                    if (el < 0.0f)
                        below = fmax(below, e);
                    flipped = fmax(flipped, fabs(mirror[ch] - want[ch]));
                }
            }
        print_message("sky lookup at %s: worst |shader - sky_radiance| %.2e = %.2f %% of the "
                      "map's scale %.3f (below the horizon %.2f %%; read mirrored: %.2f %%)\n",
                      tiers[t] < 0 ? "the best tier" : gpu_tier_name(tiers[t]), worst,
                      100.0 * worst / top, top, 100.0 * below / top, 100.0 * flipped / top);
        assert_true(worst < 0.02 * top);
        /* below the horizon the ring's constant, within an 8-bit step */
        assert_true(below < 1.0 / 255.0 * top);
        assert_true(flipped > 0.1 * top);
    }
    sky_destroy(&sky);
}

/* vshade.c's terms of a vertex (the CPU's, where a driver refuses ocean.vert's) against
 * vterms.glsl's vertex_terms (ocean.vert's), the GPU's in highp, at 2048 vertices from 2 m to
 * 30 km around a camera 10 m up (positions displaced up to 1.5 m, on the curved sea: the
 * farthest have normals facing away, reflected; half with slopes and slope variances of
 * patterns resolved on the CPU), both qualities: every term within
 * 2e-3 of its range over the vertices (the Ross factor compared in log2; measured: 3e-4 for
 * the Fresnel uv's derivatives, llvmpipe's asin against libm's, 1e-5 for the rest, the 16-bit
 * read), and every term varies over them. Dropping the sphere's slope from vshade.c's s0
 * fails it (0.24). */
#define VT_TERMS 22
static const char *const vt_names[VT_TERMS] = {
    "fresnel u", "fresnel v", "sky u", "sky v", "d fresnel u/dsx", "d fresnel v/dsx",
    "d sky u/dsx", "d sky v/dsx", "d fresnel u/dsy", "d fresnel v/dsy", "d sky u/dsy",
    "d sky v/dsy", "zeta x", "zeta y", "log2 ross", "eq. 25 wx", "lod_foot", "sky lod",
    "haze T green", "fog r (high: Rayleigh phase)", "fog g (high: Mie phase)", "fog b"
};
/* term t's offset in vshade.h's layout */
static int vt_offset(int t)
{
    return t < 16 ? VSHADE_LIN + t
         : t < 17 ? VSHADE_POS + 3
         : t < 19 ? VSHADE_GEO + 2 + (t - 17)
         : VSHADE_FOG + (t - 19);
}

static double vt_value(const float *o, int t)
{
    double x = o[vt_offset(t)];
    return t == 14 ? log2(fmax(x, 1e-12)) : x;
}

static void test_vshade(void **state)
{
    (void)state;
    enum { N = W * H };
    const float alt = 10.0f, deg = (float)(M_PI / 180.0);
    struct vshade_frame f = {
        .lin_s0 = { 0.01f, -0.005f, 0.12f }, .total_var = { 0.012f, 0.008f },
        .sun_dir = { cosf(30 * deg) * cosf(20 * deg), cosf(30 * deg) * sinf(20 * deg),
                     sinf(30 * deg) },
        .fresnel_uv_scale = { 1.0f, 0.5f }, .sky_map_size = 256.0f,
        .lod_frame = { alt * alt, log2f(1e-3f / alt) },
        .haze_tau = { 0.12f, 0.25f, 0.5f }, .haze_frame = { 1.0f / 8000.0f, 0.76f },
        .haze_ray = { 0.3f, 0.5f, 0.9f }, .haze_mie = { 0.2f, 0.18f, 0.15f },
    };
    enum { VF = 11 };   /* per vertex: p, rest, svar, slope, pixel */
    static float grid[N * GRID_FLOATS], cpu[N * VSHADE_FLOATS], vbuf[N * VF];
    uint32_t seed = 12345u;
#define VT_RAND() ((seed = seed * 1664525u + 1013904223u) / 4294967296.0f)
    memset(grid, 0, sizeof grid);
    for (int i = 0; i < N; i++) {
        float d = 2.0f * powf(15000.0f, VT_RAND()), az = 2.0f * (float)M_PI * VT_RAND();
        float *g = grid + (size_t)i * GRID_FLOATS, *v = vbuf + (size_t)i * VF;
        double r2 = (double)d * d;
        g[GRID_A_REST] = d * cosf(az);
        g[GRID_A_REST + 1] = d * sinf(az);
        g[GRID_A_POS] = g[GRID_A_REST] + 3.0f * (VT_RAND() - 0.5f);
        g[GRID_A_POS + 1] = g[GRID_A_REST + 1] + 3.0f * (VT_RAND() - 0.5f);
        g[GRID_A_POS + 2] = 3.0f * (VT_RAND() - 0.5f) - alt -
            (float)(r2 / (EARTH_RADIUS_M + sqrt(EARTH_RADIUS_M * EARTH_RADIUS_M - r2)));
        /* half the vertices with patterns resolved on the CPU: their slope and variance */
        if (i % 2) {
            g[GRID_A_SLOPE] = 0.3f * (VT_RAND() - 0.5f);
            g[GRID_A_SLOPE + 1] = 0.3f * (VT_RAND() - 0.5f);
            g[GRID_A_SVAR] = 0.01f * VT_RAND();
            g[GRID_A_SVAR + 1] = 0.01f * VT_RAND();
        }
        memcpy(v, g + GRID_A_POS, 3 * sizeof(float));
        memcpy(v + 3, g + GRID_A_REST, 2 * sizeof(float));
        memcpy(v + 5, g + GRID_A_SVAR, 2 * sizeof(float));
        memcpy(v + 7, g + GRID_A_SLOPE, 2 * sizeof(float));
        v[9] = (float)(i % W);
        v[10] = (float)(i / W);
    }
#undef VT_RAND
    static const char *const names[] = {
        "fn_mask", "fn_range", "fn_size", "fn_log", "fresnel_uv_scale", "lin_s0", "lod_frame",
        "sun_dir_world", "haze_tau", "haze_frame", "total_var", "sky_map_size", "haze_ray",
        "haze_mie"
    };
    enum { NU = sizeof names / sizeof names[0] };
    static const struct shader_attrib attribs[] = { { "a_p", 0 }, { "a_rest", 1 },
                                                    { "a_slope", 2 }, { "a_px", 3 } };
    static const int tiers[] = { TIER_GLES2_MIN, -1 };
    static double got[W * H];
    static int covered[W * H];
    for (int q = 0; q < 2; q++) {
        f.fog = q == 0;
        vshade_fill(&f, grid, N, cpu);
        int nterms = q == 0 ? VT_TERMS : VT_TERMS - 1;   /* high: fog r, g are the phases */
        for (size_t ti = 0; ti < sizeof tiers / sizeof tiers[0]; ti++) {
            struct gpu gpu;
            struct shader_program prog = { 0 };
            GLint loc[NU];
            fn_program(tiers[ti], "fn_vterms.vert", "fn_vterms.frag",
                       q == 0 ? NULL : "QUALITY_HIGH", names, NU, attribs, 4, &gpu, &prog, loc);
            GLuint vbo;
            glGenBuffers(1, &vbo);
            glBindBuffer(GL_ARRAY_BUFFER, vbo);
            glBufferData(GL_ARRAY_BUFFER, sizeof vbuf, vbuf, GL_STATIC_DRAW);
            double worst_all = 0.0;
            int worst_t = 0;
            for (int t = 0; t < nterms; t++) {
                double lo = 1e30, hi = -1e30;
                for (int i = 0; i < N; i++) {
                    double x = vt_value(cpu + (size_t)i * VSHADE_FLOATS, t);
                    lo = fmin(lo, x);
                    hi = fmax(hi, x);
                }
                double pad = 0.01 * (hi - lo) + 1e-6;
                lo -= pad;
                hi += pad;
                float mask[24] = { 0 };
                mask[t < 19 ? t : t + 1] = 1.0f;   /* fn_vterms.vert's order */
                const float range[2] = { (float)lo, (float)(1.0 / (hi - lo)) };
                const float size[2] = { (float)W, (float)H };
                fn_frame_begin(&prog);
                glUniform4fv(loc[0], 6, mask);
                glUniform2fv(loc[1], 1, range);
                glUniform2fv(loc[2], 1, size);
                glUniform1f(loc[3], t == 14 ? 1.0f : 0.0f);
                glUniform2fv(loc[4], 1, f.fresnel_uv_scale);
                glUniform3fv(loc[5], 1, f.lin_s0);
                glUniform2fv(loc[6], 1, f.lod_frame);
                glUniform3fv(loc[7], 1, f.sun_dir);
                glUniform3fv(loc[8], 1, f.haze_tau);
                glUniform2fv(loc[9], 1, f.haze_frame);
                glUniform2fv(loc[10], 1, f.total_var);
                glUniform1f(loc[11], f.sky_map_size);
                if (q == 0) {
                    glUniform3fv(loc[12], 1, f.haze_ray);
                    glUniform3fv(loc[13], 1, f.haze_mie);
                }
                static const int asize[4] = { 3, 4, 2, 2 }, aoff[4] = { 0, 3, 7, 9 };
                for (GLuint a = 0; a < 4; a++) {
                    glEnableVertexAttribArray(a);
                    glVertexAttribPointer(a, asize[a], GL_FLOAT, GL_FALSE, VF * sizeof(float),
                                          (void *)(aoff[a] * sizeof(float)));
                }
                glDrawArrays(GL_POINTS, 0, N);
                for (GLuint a = 0; a < 4; a++)
                    glDisableVertexAttribArray(a);
                fn_frame_read(got, covered);
                double worst = 0.0;
                int wi = 0;
                for (int i = 0; i < N; i++) {
                    assert_true(covered[i]);
                    double want = vt_value(cpu + (size_t)i * VSHADE_FLOATS, t);
                    double e = fabs(lo + got[i] * (hi - lo) - want) / (hi - lo);
                    if (e > worst) {
                        worst = e;
                        wi = i;
                    }
                }
                const float *gw = grid + (size_t)wi * GRID_FLOATS;
                if (worst >= 2e-3)
                    print_message("vshade %s at %s, %s: worst %.2e of the range %.3g..%.3g "
                                  "at %.0f m\n", q == 0 ? "low" : "high",
                                  tiers[ti] < 0 ? "the best tier" : gpu_tier_name(tiers[ti]),
                                  vt_names[t], worst, lo + pad, hi - pad,
                                  hypot(gw[GRID_A_REST], gw[GRID_A_REST + 1]));
                if (worst > worst_all) {
                    worst_all = worst;
                    worst_t = t;
                }
                assert_true(hi - lo > 1e-3 * (fabs(hi) + fabs(lo)));   /* the term varies */
            }
            print_message("vshade %s at %s: worst term %s, %.2e of its range\n",
                          q == 0 ? "low" : "high",
                          tiers[ti] < 0 ? "the best tier" : gpu_tier_name(tiers[ti]),
                          vt_names[worst_t], worst_all);
            assert_true(worst_all < 2e-3);
            glBindBuffer(GL_ARRAY_BUFFER, 0);
            glDeleteBuffers(1, &vbo);
            shader_program_destroy(&prog);
            gpu_shutdown(&gpu);
        }
    }
}

int main(void)
{
    int open_rc = frame_open("test_glsl", W, H, &g_ph);
    if (open_rc)
        return open_rc;
    const char *tmp = getenv("SWELL_TMP") ? getenv("SWELL_TMP") : "/tmp";
    snprintf(g_dir, sizeof g_dir, "%s/test_glsl.XXXXXX", tmp);
    if (!mkdtemp(g_dir)) {
        fprintf(stderr, "test_glsl: mkdtemp %s failed\n", g_dir);
        return 1;
    }
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fresnel_eff),
        cmocka_unit_test(test_tone_map),
        cmocka_unit_test(test_whitecap_cover),
        cmocka_unit_test(test_ross_lambda),
        cmocka_unit_test(test_sky_lookup),
        cmocka_unit_test(test_vshade),
    };
    copy_file("shaders_gles", "common.glsl");
    copy_file("tests/glsl", "fn.vert");
    copy_file("tests/glsl", "fn_fresnel_eff.frag");
    copy_file("tests/glsl", "fn_tone_map.frag");
    copy_file("tests/glsl", "fn_whitecap_cover.frag");
    copy_file("tests/glsl", "fn_ross_lambda.frag");
    copy_file("tests/glsl", "fn_sky_lookup.frag");
    copy_file("shaders_gles", "vterms.glsl");
    copy_file("tests/glsl", "fn_vterms.vert");
    copy_file("tests/glsl", "fn_vterms.frag");
    int rc = cmocka_run_group_tests(tests, NULL, NULL);
    static const char *const copies[] = { "common.glsl", "fn.vert", "fn_fresnel_eff.frag",
                                          "fn_tone_map.frag", "fn_whitecap_cover.frag",
                                          "fn_ross_lambda.frag", "fn_sky_lookup.frag",
                                          "vterms.glsl", "fn_vterms.vert", "fn_vterms.frag" };
    for (size_t k = 0; k < sizeof copies / sizeof copies[0]; k++) {
        char path[600];
        if (snprintf(path, sizeof path, "%s/%s", g_dir, copies[k]) < (int)sizeof path)
            unlink(path);
    }
    if (rmdir(g_dir) != 0)
        fprintf(stderr, "test_glsl: could not remove %s\n", g_dir);
    platform_close(&g_ph);
    return rc;
}
