/* test_shader.c - the loader's assembly without a GL context: header order and content per
 * tier, includes (nested, once, cycle, depth, missing, malformed), and the #line table checked
 * by simulating the preprocessor's line counter against the original files. */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "gl/shader.h"

static char dir[512];

static void put(const char *name, const char *text)
{
    char path[700];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs(text, f);
    assert_int_equal(fclose(f), 0);
}

static struct gpu_caps caps_for(int tier)
{
    struct gpu_caps c = { .tier = tier, .tier_available = TIER_GLES3, .texture_units = 8 };
    if (tier >= TIER_GLES2_EXT) {
        c.derivatives = c.texture_lod = c.fragment_highp = 1;
        c.glsl100_derivatives = c.glsl100_texture_lod = 1;
        c.vertex_texture_units = 16;
    }
    return c;
}

static const char *find_line(const char *src, const char *line)
{
    size_t n = strlen(line);
    for (const char *p = src; p; p = strchr(p, '\n')) {
        if (*p == '\n')
            p++;
        if (strncmp(p, line, n) == 0 && (p[n] == '\n' || p[n] == '\0'))
            return p;
    }
    return NULL;
}

/* The tier drawn on unasked: the best available, but VideoCore IV's gles2-ext (vc4: 2.7x the
 * fragment time of its gles2-min by docs/devices.md's cost model) gives way to gles2-min, with
 * a reason to print; other GPUs and vc4 on other tiers keep theirs. */
static void test_default_tier(void **state)
{
    (void)state;
    const char *why = NULL;
    assert_int_equal(gpu_default_tier("VC4 V3D 2.1", TIER_GLES2_EXT, &why), TIER_GLES2_MIN);
    assert_non_null(why);
    assert_non_null(strstr(why, "VideoCore IV"));
    why = NULL;
    assert_int_equal(gpu_default_tier("VC4 V3D 2.1", TIER_GLES2_MIN, &why), TIER_GLES2_MIN);
    assert_int_equal(gpu_default_tier("V3D 4.2", TIER_GLES3, &why), TIER_GLES3);
    assert_int_equal(gpu_default_tier("Mali450", TIER_GLES2_EXT, &why), TIER_GLES2_EXT);
    assert_int_equal(gpu_default_tier("Vivante GC2000 rev 5108", TIER_GLES2_EXT, &why),
                     TIER_GLES2_EXT);
    assert_int_equal(gpu_default_tier("llvmpipe (LLVM 15.0.6, 256 bits)", TIER_GLES3, &why),
                     TIER_GLES3);
    assert_null(why);
}

/* The fetch order of ocean.frag (SWELL_ORDER_FETCHES) on V3D 4.x alone: not on vc4, whose
 * renderer string also names V3D, nor on the other GPUs or llvmpipe. */
static void test_order_fetches(void **state)
{
    (void)state;
    assert_true(gpu_orders_fetches("V3D 4.2"));
    assert_true(gpu_orders_fetches("V3D 7.1"));
    assert_false(gpu_orders_fetches("VC4 V3D 2.1"));
    assert_false(gpu_orders_fetches("Mali450"));
    assert_false(gpu_orders_fetches("FD630"));
    assert_false(gpu_orders_fetches("llvmpipe (LLVM 15.0.6, 256 bits)"));
}

static void test_header_per_tier(void **state)
{
    (void)state;
    put("h.vert", "void main() { gl_Position = vec4(0.0); }\n");
    put("h.frag", "void main() { gl_FragColor = vec4(1.0); }\n");
    struct gpu_caps c = caps_for(TIER_GLES2_MIN);
    struct shader_desc d = { .dir = dir, .vs_file = "h.vert", .fs_file = "h.frag", .caps = &c,
                             .defines = "QUALITY_HIGH  SWELL_HIGHP\tPATTERNS=4" };
    struct swell_err err = { 0 };
    char *fs = NULL, *vs = NULL;
    assert_int_equal(shader_assemble(&d, GL_FRAGMENT_SHADER, &fs, &err), 0);
    assert_int_equal(strncmp(fs, "#version 100\n", 13), 0);
    assert_non_null(find_line(fs, "#define SWELL_TIER_GLES2_MIN 1"));
    assert_non_null(find_line(fs, "#define QUALITY_HIGH 1"));
    assert_non_null(find_line(fs, "#define PATTERNS 4"));
    assert_non_null(find_line(fs, "precision mediump float;"));
    assert_null(strstr(fs, "highp float"));      /* gles2-min: never highp */
    assert_null(strstr(fs, "#extension"));
    assert_null(strstr(fs, "SWELL_HAS_"));
    free(fs);

    c = caps_for(TIER_GLES3);
    assert_int_equal(shader_assemble(&d, GL_FRAGMENT_SHADER, &fs, &err), 0);
    const char *ext = find_line(fs, "#extension GL_OES_standard_derivatives : enable");
    const char *prec = find_line(fs, "precision highp float;");
    assert_non_null(ext);
    assert_non_null(prec);
    assert_true(ext < prec);                      /* #extension before any non-preprocessor token */
    assert_non_null(find_line(fs, "#extension GL_EXT_shader_texture_lod : enable"));
    assert_non_null(find_line(fs, "#define SWELL_TIER_GLES3 1"));
    assert_non_null(find_line(fs, "#define SWELL_HAS_DERIVATIVES 1"));
    assert_null(strstr(fs, "mediump"));
    free(fs);

    d.defines = "QUALITY_LOW";
    assert_int_equal(shader_assemble(&d, GL_FRAGMENT_SHADER, &fs, &err), 0);
    assert_non_null(find_line(fs, "precision mediump float;"));   /* highp only when asked */
    free(fs);
    assert_int_equal(shader_assemble(&d, GL_VERTEX_SHADER, &vs, &err), 0);
    assert_null(strstr(vs, "precision"));
    assert_null(strstr(vs, "#extension"));
    assert_non_null(find_line(vs, "#define SWELL_VERTEX_SHADER 1"));
    assert_non_null(find_line(vs, "#define SWELL_HAS_VTF 1"));
    free(vs);

    d.defines = "1BAD";
    assert_int_equal(shader_assemble(&d, GL_VERTEX_SHADER, &vs, &err), SWELL_E_ARG);
    assert_null(vs);
    assert_non_null(strstr(err.msg, "1BAD"));
}

/* Replays the assembled source the way the GLSL preprocessor numbers lines (`#line L` makes the
 * next line L; see shader.c) and checks each non-directive line against line L % 100000 of file
 * number L / 100000, read from disk independently. */
static void check_line_table(const char *src, const char *const *files, int nfiles)
{
    char *texts[8] = { 0 };
    for (int i = 1; i < nfiles; i++) {
        char path[700];
        snprintf(path, sizeof path, "%s/%s", dir, files[i]);
        FILE *f = fopen(path, "r");
        assert_non_null(f);
        texts[i] = calloc(1, 65536);
        size_t n = fread(texts[i], 1, 65535, f);
        texts[i][n] = '\0';
        fclose(f);
    }
    long cur = -1;   /* -1: still in the generated header */
    int checked = 0;
    for (const char *p = src; *p;) {
        const char *nl = strchr(p, '\n');
        size_t n = nl ? (size_t)(nl - p) : strlen(p);
        long L, S;
        if (sscanf(p, "#line %ld %ld", &L, &S) == 2) {
            cur = L;
            assert_int_equal(S, L / 100000);
        } else if (cur >= 0) {
            int file = (int)(cur / 100000), line = (int)(cur % 100000);
            assert_true(file >= 1 && file < nfiles);
            const char *q = texts[file];
            for (int k = 1; k < line && q; k++) {
                q = strchr(q, '\n');
                if (q)
                    q++;
            }
            assert_non_null(q);
            if (n > 0) {
                if (strncmp(q, p, n) != 0 || (q[n] != '\n' && q[n] != '\0'))
                    fail_msg("output line '%.*s' is not %s:%d", (int)n, p, files[file], line);
                checked++;
            }
            cur++;
        }
        p += n + (nl ? 1 : 0);
    }
    assert_true(checked > 0);
    for (int i = 1; i < nfiles; i++)
        free(texts[i]);
}

static void test_includes_and_lines(void **state)
{
    (void)state;
    put("a.glsl", "// a\n#include \"b.glsl\"\nfloat fa() { return fb(); }\n");
    put("b.glsl", "float fb() {\n  return 2.0;\n}\n");
    put("m.frag", "// main\n#include \"a.glsl\"\n  #  include   \"b.glsl\"  \n"
                  "void main() {\n  gl_FragColor = vec4(fa());\n}\n");
    put("m.vert", "void main() { gl_Position = vec4(0.0); }\n");
    struct gpu_caps c = caps_for(TIER_GLES2_EXT);
    struct shader_desc d = { .dir = dir, .vs_file = "m.vert", .fs_file = "m.frag", .caps = &c };
    struct swell_err err = { 0 };
    char *fs = NULL;
    assert_int_equal(shader_assemble(&d, GL_FRAGMENT_SHADER, &fs, &err), 0);
    /* b.glsl once, though included twice */
    const char *first = strstr(fs, "float fb()");
    assert_non_null(first);
    assert_null(strstr(first + 1, "float fb()"));
    /* b before a's body before main */
    assert_true(first < strstr(fs, "float fa()"));
    assert_true(strstr(fs, "float fa()") < strstr(fs, "void main()"));
    assert_null(strstr(fs, "#include"));
    static const char *const files[] = { "", "m.frag", "a.glsl", "b.glsl" };
    check_line_table(fs, files, 4);
    free(fs);
}

static void expect(const char *fs_file, int code, const char *needle)
{
    struct gpu_caps c = caps_for(TIER_GLES2_MIN);
    struct shader_desc d = { .dir = dir, .vs_file = "m.vert", .fs_file = fs_file, .caps = &c };
    struct swell_err err = { 0 };
    char *src = (char *)1;
    assert_int_equal(shader_assemble(&d, GL_FRAGMENT_SHADER, &src, &err), code);
    assert_null(src);
    if (!strstr(err.msg, needle))
        fail_msg("'%s' not in: %s", needle, err.msg);
}

static void test_include_errors(void **state)
{
    (void)state;
    char want[1200];
    put("m.vert", "void main() { gl_Position = vec4(0.0); }\n");
    put("c1.glsl", "\n#include \"c2.glsl\"\n");
    put("c2.glsl", "#include \"c1.glsl\"\n");
    put("cyc.frag", "#include \"c1.glsl\"\nvoid main() {}\n");
    snprintf(want, sizeof want, "%s/c2.glsl:1: #include cycle: c1.glsl -> c2.glsl -> c1.glsl", dir);
    expect("cyc.frag", SWELL_E_SHADER, want);

    put("self.frag", "\n\n#include \"self.frag\"\n");
    snprintf(want, sizeof want, "%s/self.frag:3: #include cycle: self.frag -> self.frag", dir);
    expect("self.frag", SWELL_E_SHADER, want);

    /* d0 -> d1 -> ... -> d9: deeper than SHADER_MAX_INCLUDE_DEPTH (8) */
    for (int i = 0; i < 10; i++) {
        char name[32], text[64];
        snprintf(name, sizeof name, "d%d.glsl", i);
        snprintf(text, sizeof text, "#include \"d%d.glsl\"\n", i + 1);
        put(name, i < 9 ? text : "float deep;\n");
    }
    put("deep.frag", "#include \"d0.glsl\"\n");
    expect("deep.frag", SWELL_E_SHADER, "nested deeper than 8");

    put("miss.frag", "\n#include \"nope.glsl\"\n");
    snprintf(want, sizeof want, "%s/miss.frag:2: #include: shader: cannot open %s/nope.glsl", dir,
             dir);
    expect("miss.frag", SWELL_E_IO, want);

    put("mal.frag", "void f();\n#include <x.glsl>\n");
    snprintf(want, sizeof want, "%s/mal.frag:2: malformed #include", dir);
    expect("mal.frag", SWELL_E_SHADER, want);
    put("up.frag", "#include \"../etc/passwd\"\n");
    expect("up.frag", SWELL_E_SHADER, "malformed #include");

    put("ver.frag", "#version 100\nvoid main() {}\n");
    snprintf(want, sizeof want, "%s/ver.frag:1: remove #version", dir);
    expect("ver.frag", SWELL_E_SHADER, want);
}

int main(void)
{
    const char *base = getenv("SWELL_TMP");
    snprintf(dir, sizeof dir, "%s/test_shader.XXXXXX", base && base[0] ? base : "/tmp");
    if (!mkdtemp(dir)) {
        perror(dir);
        return 1;
    }
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_default_tier),
        cmocka_unit_test(test_order_fetches),
        cmocka_unit_test(test_header_per_tier),
        cmocka_unit_test(test_includes_and_lines),
        cmocka_unit_test(test_include_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
