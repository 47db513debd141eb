/* test_platform.c - the GL foundation on a real context (Mesa surfaceless): FBO clear and
 * read-back orientation, one triangle through the shader loader at forced gles2-min, tier probe
 * and forcing, budget refusal before allocation, compile errors mapped to file:line.
 *
 * Exit 77 (skip) only when no EGL device exists and CI is not "true" (STYLE.md 12).
 */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "gl/gpu.h"
#include "platform/platform.h"
#include "gl/shader.h"
#include "tables/tables.h"

#define W 96
#define H 64

struct fixture {
    struct platform_handle ph;
    uint8_t *rgba;
    char dir[512];      /* scratch directory for shader files */
};

static struct fixture fx;

static void write_text(const char *name, const char *text)
{
    char path[700];
    snprintf(path, sizeof path, "%s/%s", fx.dir, name);
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    assert_int_equal(fputs(text, f) >= 0, 1);
    assert_int_equal(fclose(f), 0);
}

static void read_frame(void)
{
    struct swell_err err = { 0 };
    int rc = fx.ph.be->read_rgba(fx.ph.p, fx.rgba, &err);
    if (rc)
        fail_msg("read_rgba: %s", err.msg);
}

static void test_clear_every_pixel(void **state)
{
    (void)state;
    struct swell_err err = { 0 };
    int w = 0, h = 0;
    fx.ph.be->size(fx.ph.p, &w, &h);
    assert_int_equal(w, W);
    assert_int_equal(h, H);
    assert_int_equal(fx.ph.be->begin_frame(fx.ph.p, &err), 0);
    /* 0.2, 0.4, 0.6, 1.0 -> 51, 102, 153, 255 exactly (x * 255 is integral) */
    glClearColor(0.2f, 0.4f, 0.6f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    assert_int_equal(fx.ph.be->present(fx.ph.p, &err), 0);
    read_frame();
    const uint8_t want[4] = { 51, 102, 153, 255 };
    for (int i = 0; i < W * H; i++)
        for (int c = 0; c < 4; c++)
            if (abs((int)fx.rgba[i * 4 + c] - want[c]) > 1)
                fail_msg("pixel (%d,%d) channel %d is %d, want %d", i % W, i / W, c,
                         fx.rgba[i * 4 + c], want[c]);
}

/* Signed area test: > 0 when (px,py) is left of the edge a->b (counter-clockwise triangle). */
static double edge(const float *a, const float *b, double px, double py)
{
    return (b[0] - a[0]) * (py - a[1]) - (b[1] - a[1]) * (px - a[0]);
}

static void test_triangle_gles2_min(void **state)
{
    (void)state;
    struct swell_err err = { 0 };
    struct gpu g;
    if (gpu_init(&g, TIER_GLES2_MIN, 0, &err))
        fail_msg("gpu_init gles2-min: %s", err.msg);
    write_text("tri.vert", "attribute vec2 a_pos_ndc;\n"
                           "void main() {\n"
                           "    gl_Position = vec4(a_pos_ndc, 0.0, 1.0);\n"
                           "}\n");
    write_text("colour.glsl", "uniform vec4 u_color;\n"
                              "uniform float u_unused;\n"
                              "vec4 colour() { return u_color; }\n");
    write_text("tri.frag", "#include \"colour.glsl\"\n"
                           "void main() {\n"
                           "#ifdef SWELL_TIER_GLES2_MIN\n"
                           "    gl_FragColor = colour();\n"
                           "#else\n"
                           "    gl_FragColor = vec4(1.0, 0.0, 1.0, 1.0);\n"
                           "#endif\n"
                           "}\n");
    enum { U_COLOR, U_UNUSED, U_COUNT };
    static const char *const names[U_COUNT] = { "u_color", "u_unused" };
    GLint loc[U_COUNT] = { -2, -2 };
    const struct shader_attrib attribs[] = { { "a_pos_ndc", 3 } };
    struct shader_desc d = {
        .dir = fx.dir, .vs_file = "tri.vert", .fs_file = "tri.frag", .defines = "TEST_DEFINE=2",
        .caps = &g.caps, .uniform_names = names, .uniform_count = U_COUNT,
        .uniform_locations = loc, .attribs = attribs, .attrib_count = 1,
    };
    char *src = NULL;
    assert_int_equal(shader_assemble(&d, GL_FRAGMENT_SHADER, &src, &err), 0);
    assert_non_null(strstr(src, "precision mediump float;"));
    assert_null(strstr(src, "#extension"));
    assert_null(strstr(src, "highp"));
    free(src);

    struct shader_program prog = { 0 };
    if (shader_program_build(&d, &prog, &err))
        fail_msg("build: %s", err.msg);
    assert_true(loc[U_COLOR] >= 0);
    assert_int_equal(loc[U_UNUSED], -1);
    assert_int_equal(glGetAttribLocation(prog.program, "a_pos_ndc"), 3);

    /* A right triangle in the lower-left/upper-left: asymmetric in x and y so a flipped or
     * mirrored read-back fails. Counter-clockwise. */
    static const float tri[3][2] = { { -0.8f, -0.6f }, { 0.6f, -0.6f }, { -0.8f, 0.7f } };
    assert_int_equal(fx.ph.be->begin_frame(fx.ph.p, &err), 0);
    glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glUseProgram(prog.program);
    glUniform4f(loc[U_COLOR], 1.0f, 0.6f, 0.2f, 1.0f);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    glVertexAttribPointer(3, 2, GL_FLOAT, GL_FALSE, 0, tri);
    glEnableVertexAttribArray(3);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDisableVertexAttribArray(3);
    assert_int_equal(gpu_check("draw", &err), 0);
    assert_int_equal(fx.ph.be->present(fx.ph.p, &err), 0);
    read_frame();

    int inside = 0, outside = 0, coloured = 0;
    for (int y = 0; y < H; y++) {
        for (int x = 0; x < W; x++) {
            /* Pixel centre in NDC; row 0 of the read-back is the top (NDC y = +1). */
            double px = (x + 0.5) / W * 2.0 - 1.0, py = 1.0 - (y + 0.5) / H * 2.0;
            double e0 = edge(tri[0], tri[1], px, py), e1 = edge(tri[1], tri[2], px, py),
                   e2 = edge(tri[2], tri[0], px, py);
            double margin = 0.08;   /* about two pixels of edge area, in NDC^2 units */
            const uint8_t *p = fx.rgba + ((size_t)y * W + (size_t)x) * 4;
            coloured += p[0] > 128;
            if (e0 > margin && e1 > margin && e2 > margin) {
                inside++;
                if (abs(p[0] - 255) > 1 || abs(p[1] - 153) > 1 || abs(p[2] - 51) > 1)
                    fail_msg("inside pixel (%d,%d) = %d,%d,%d, want 255,153,51", x, y, p[0],
                             p[1], p[2]);
            } else if (e0 < -margin || e1 < -margin || e2 < -margin) {
                outside++;
                if (p[0] > 1 || p[1] > 1 || p[2] > 1)
                    fail_msg("outside pixel (%d,%d) = %d,%d,%d, want black", x, y, p[0], p[1],
                             p[2]);
            }
        }
    }
    /* Area: the triangle covers 1.4 * 1.3 / 2 / 4 = 22.75 % of the screen; pixel-centre
     * sampling miscounts at most about half the pixels its edges cross (~4 % of the area). */
    double area_px = 1.4 * 1.3 / 8.0 * W * H;
    if (fabs(coloured - area_px) > 0.04 * area_px)
        fail_msg("triangle covers %d pixels, want %.1f", coloured, area_px);
    assert_true(inside > 0.7 * area_px);
    assert_true(outside > 0.7 * (W * H - area_px));
    shader_program_destroy(&prog);
    assert_int_equal(prog.program, 0);
    gpu_shutdown(&g);
}

static void test_tier_probe_and_force(void **state)
{
    (void)state;
    struct swell_err err = { 0 };
    struct gpu g;
    if (gpu_init(&g, -1, 0, &err))
        fail_msg("gpu_init: %s", err.msg);
    /* The fixture asked for GLES 3; Mesa llvmpipe provides it (the test's premise). */
    const char *v = (const char *)glGetString(GL_VERSION);
    assert_non_null(v);
    if (strncmp(v, "OpenGL ES 3", 11) == 0) {
        assert_int_equal(g.caps.tier_available, TIER_GLES3);
        assert_int_equal(g.caps.tier, TIER_GLES3);
        assert_true(g.caps.half_float && g.caps.derivatives && g.caps.texture_lod &&
                    g.caps.glsl300);
    }
    assert_true(g.caps.renderer[0] != '\0');
    gpu_shutdown(&g);

    if (gpu_init(&g, TIER_GLES2_MIN, 0, &err))
        fail_msg("gpu_init forced gles2-min: %s", err.msg);
    assert_int_equal(g.caps.tier, TIER_GLES2_MIN);
    assert_int_equal(g.caps.vertex_texture_units, 0);
    assert_int_equal(g.caps.half_float, 0);
    assert_int_equal(g.caps.derivatives, 0);
    assert_int_equal(g.caps.texture_lod, 0);
    assert_int_equal(g.caps.glsl300, 0);
    assert_int_equal(g.caps.fragment_highp, 0);
    GLint units = 0;
    glGetIntegerv(GL_MAX_TEXTURE_IMAGE_UNITS, &units);
    assert_int_equal(g.caps.texture_units, units < 8 ? units : 8);
    GLuint tex = 7;
    assert_int_equal(gpu_texture_create(&g, 16, 16, 1, FORMAT_RGBA16F, 0, "half", &tex, &err),
                     SWELL_E_TIER);
    assert_int_equal(tex, 0);
    gpu_shutdown(&g);

    assert_int_equal(gpu_init(&g, TIER_COUNT, 0, &err), SWELL_E_ARG);
    for (int t = 0; t < TIER_COUNT; t++)
        assert_int_equal(gpu_tier_from_name(gpu_tier_name(t)), t);
    assert_int_equal(gpu_tier_from_name("gles2"), -1);
}

/* Independent of gpu.c: bytes of a mip chain by the definition (each level halves, min 1). */
static uint64_t chain_bytes(int w, int h, int levels, int texel)
{
    uint64_t sum = 0;
    for (int l = 0; l < levels; l++) {
        int lw = w, lh = h;
        for (int k = 0; k < l; k++) {
            lw = lw > 1 ? lw / 2 : 1;
            lh = lh > 1 ? lh / 2 : 1;
        }
        sum += (uint64_t)lw * (uint64_t)lh * (uint64_t)texel;
    }
    return sum;
}

static void test_budget_refused_before_allocation(void **state)
{
    (void)state;
    struct swell_err err = { 0 };
    struct gpu g;
    const uint64_t budget = 1024 * 1024;
    if (gpu_init(&g, -1, budget, &err))
        fail_msg("gpu_init: %s", err.msg);
    GLuint a = 0, big = 99, buf = 0;
    if (gpu_texture_create(&g, 256, 64, 9, FORMAT_RGBA8, 1, "slope", &a, &err))
        fail_msg("create: %s", err.msg);
    uint64_t a_bytes = chain_bytes(256, 64, 9, 4);
    assert_int_equal(g.bytes, a_bytes);
    assert_true(glIsTexture(a));
    if (gpu_buffer_create(&g, GL_ARRAY_BUFFER, 1000, GL_STATIC_DRAW, "vbo", &buf, &err))
        fail_msg("buffer: %s", err.msg);
    assert_int_equal(g.bytes, a_bytes + 1000);
    int records = g.alloc_count;

    /* 512 x 512 RGBA8 = exactly the budget: with anything else held it cannot fit. */
    assert_int_equal(gpu_texture_create(&g, 512, 512, 1, FORMAT_RGBA8, 0, "too big", &big, &err),
                     SWELL_E_BUDGET);
    assert_int_equal(big, 0);
    assert_int_equal(g.bytes, a_bytes + 1000);
    assert_int_equal(g.alloc_count, records);
    assert_int_equal(glGetError(), GL_NO_ERROR);
    char want[64];
    snprintf(want, sizeof want, "%llu", (unsigned long long)(512 * 512 * 4));
    assert_non_null(strstr(err.msg, want));
    snprintf(want, sizeof want, "%llu", (unsigned long long)(a_bytes + 1000));
    assert_non_null(strstr(err.msg, want));
    snprintf(want, sizeof want, "%llu", (unsigned long long)budget);
    assert_non_null(strstr(err.msg, want));
    assert_non_null(strstr(err.msg, "too big"));

    gpu_texture_destroy(&g, &a);
    assert_int_equal(a, 0);
    assert_int_equal(g.bytes, 1000);
    /* Freed room: the same request now fits, up to the last byte. */
    gpu_buffer_destroy(&g, &buf);
    assert_int_equal(g.bytes, 0);
    if (gpu_texture_create(&g, 512, 512, 1, FORMAT_RGBA8, 0, "exact fit", &big, &err))
        fail_msg("exact fit: %s", err.msg);
    assert_int_equal(g.bytes, budget);
    assert_int_equal(g.peak_bytes, budget);
    gpu_texture_destroy(&g, &big);
    assert_int_equal(g.bytes, 0);
    gpu_shutdown(&g);
    gpu_shutdown(&g);
}

static void expect_error(struct shader_desc *d, const char *needle)
{
    struct swell_err err = { 0 };
    struct shader_program prog = { 0 };
    int rc = shader_program_build(d, &prog, &err);
    assert_int_equal(rc, SWELL_E_SHADER);
    assert_int_equal(prog.program, 0);
    if (!strstr(err.msg, needle))
        fail_msg("message lacks '%s':\n%s", needle, err.msg);
}

static void test_compile_error_file_line(void **state)
{
    (void)state;
    struct swell_err err = { 0 };
    struct gpu g;
    if (gpu_init(&g, TIER_GLES2_MIN, 0, &err))
        fail_msg("gpu_init: %s", err.msg);
    write_text("ok.vert", "attribute vec2 a_pos;\nvoid main() { gl_Position = vec4(a_pos, 0.0, "
                          "1.0); }\n");
    /* The undeclared name is on line 4 of helper.glsl, included from line 2 of bad.frag. */
    write_text("helper.glsl", "// helper\n"
                              "vec4 helper() {\n"
                              "    vec4 c = vec4(0.5);\n"
                              "    return c * not_declared_anywhere;\n"
                              "}\n");
    write_text("bad.frag", "// broken on purpose\n"
                           "#include \"helper.glsl\"\n"
                           "void main() {\n"
                           "    gl_FragColor = helper();\n"
                           "    gl_FragColor += missing_too;\n"
                           "}\n");
    struct shader_desc d = { .dir = fx.dir, .vs_file = "ok.vert", .fs_file = "bad.frag",
                             .caps = &g.caps };
    char want[700];
    snprintf(want, sizeof want, "%s/helper.glsl:4:", fx.dir);
    expect_error(&d, want);
    snprintf(want, sizeof want, "%s/bad.frag:5:", fx.dir);
    expect_error(&d, want);

    write_text("bad.vert", "attribute vec2 a_pos;\n\nvoid main() {\n    gl_Position = a_pos;\n}\n");
    d.vs_file = "bad.vert";
    d.fs_file = "helper.glsl";
    snprintf(want, sizeof want, "%s/bad.vert:4:", fx.dir);
    expect_error(&d, want);
    gpu_shutdown(&g);
}

static int no_egl_skip(const struct swell_err *err)
{
    const char *ci = getenv("CI");
    if (ci && strcmp(ci, "true") == 0) {
        fprintf(stderr, "test_platform: CI=true and the surfaceless platform failed: %s\n",
                err->msg);
        return 1;
    }
    fprintf(stderr, "test_platform: SKIP, no EGL device: %s\n", err->msg);
    return 77;
}

int main(void)
{
    struct swell_err err = { 0 };
    struct platform_desc pd = { .kind = PLATFORM_SURFACELESS, .width = W, .height = H,
                                .gles_major = 3 };
    int rc = platform_open(&pd, &fx.ph, &err);
    if (rc == SWELL_E_UNSUPPORTED || rc == SWELL_E_EGL)
        return no_egl_skip(&err);
    if (rc) {
        fprintf(stderr, "test_platform: platform_open: %s\n", err.msg);
        return 1;
    }
    const char *base = getenv("SWELL_TMP");
    snprintf(fx.dir, sizeof fx.dir, "%s/test_platform.XXXXXX", base && base[0] ? base : "/tmp");
    fx.rgba = malloc((size_t)W * H * 4);
    if (!mkdtemp(fx.dir) || !fx.rgba) {
        fprintf(stderr, "test_platform: scratch %s: %s\n", fx.dir, strerror(errno));
        platform_close(&fx.ph);
        return 1;
    }
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_clear_every_pixel),
        cmocka_unit_test(test_triangle_gles2_min),
        cmocka_unit_test(test_tier_probe_and_force),
        cmocka_unit_test(test_budget_refused_before_allocation),
        cmocka_unit_test(test_compile_error_file_line),
    };
    int failed = cmocka_run_group_tests(tests, NULL, NULL);
    free(fx.rgba);
    platform_close(&fx.ph);
    return failed ? 1 : 0;
}
