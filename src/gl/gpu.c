/* gpu.c - capability probe, tier choice and the one accounting point (gpu.h, DESIGN.md
 * "Device tiers", "Budgets"). Extensions are matched by exact token, never by substring, so
 * "GL_OES_texture_half_float_linear" does not imply "GL_OES_texture_half_float".
 */
#include "gl/gpu.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/parse.h"
#include "gl/capture.h"
#include "gl/shader.h"
#include "tables/tables.h"

/* GLES 3.0's GL_MAX_TEXTURE_LOD_BIAS, the same enum as EXT_texture_lod_bias's (GLES2/gl2.h has
 * neither) */
#define MAX_TEXTURE_LOD_BIAS 0x84FD

/* GLES 3.0 / OES_texture_half_float enums, not in gl2.h. */
#define SWELL_GL_HALF_FLOAT_OES 0x8D61
#define SWELL_GL_HALF_FLOAT     0x140B
#define SWELL_GL_RGBA16F        0x881A
#define SWELL_GL_TEXTURE_MAX_LEVEL 0x813D

/* DESIGN.md: gles2-min may assume 8 fragment texture units and no more. */
#define GLES2_MIN_TEXTURE_UNITS 8

static const char *const tier_names[TIER_COUNT] = { "gles2-min", "gles2-ext", "gles3" };

const char *gpu_tier_name(int tier)
{
    return name_of(tier_names, TIER_COUNT, tier);
}

int gpu_default_tier(const char *renderer, int available, const char **why)
{
    /* VideoCore IV (vc4): its gles2-ext is vertex texture fetch and EXT_shader_texture_lod
     * without derivatives or half floats, and there vc4 builds the detiled high-quality
     * fragment shaders fetching 3-4 patterns on one thread: by docs/devices.md's cost model
     * (make test-devices) the default view at 1280x720 takes 108 ms of fragment shading on
     * gles2-ext against 37 ms on gles2-min (9.2 against 27 fps; low 25 against 23 ms). */
    if (available == TIER_GLES2_EXT && strstr(renderer, "VC4")) {
        *why = "VideoCore IV: tier gles2-min, faster here than gles2-ext (src/gl/gpu.c)";
        return TIER_GLES2_MIN;
    }
    return available;
}

int gpu_orders_fetches(const char *renderer)
{
    /* Broadcom's V3D 4.x (Raspberry Pi 4; Mesa's v3d) allocates registers for two threads at
     * least and spills past them: its compiler hoisted every pattern slot's fetches and
     * lattice terms to the start of the high-quality programs, all live at once, and spilled
     * in every one with three or four slots or the objects' fetches. With each slot's fetches
     * made to wait for the slot before (ocean.frag SWELL_ORDER_FETCHES) none spills and the
     * 4-slot program is 26 % shorter (make test-devices, docs/devices.md). Elsewhere the same
     * order cost 3-10 % more instructions (Adreno, Mali, Vivante) or made vc4 (VC4 V3D 2.1,
     * the Raspberry Pi 0-3, whose register allocator cannot spill) refuse more programs. */
    return strstr(renderer, "V3D") && !strstr(renderer, "VC4");
}

int gpu_tier_from_name(const char *name)
{
    return parse_name(tier_names, 0, TIER_COUNT, name);
}

/* "OpenGL ES 3.2 Mesa ..." or "OpenGL ES-CM 1.1" -> major; 0 when unparsable. */
static int parse_es_major(const char *version)
{
    const char *prefix = "OpenGL ES";
    if (strncmp(version, prefix, strlen(prefix)) != 0)
        return 0;
    const char *p = version + strlen(prefix);
    while (*p && *p != ' ')
        p++;
    while (*p == ' ')
        p++;
    if (*p < '0' || *p > '9')
        return 0;
    return atoi(p);
}

static void copy_gl_string(char *dst, size_t size, GLenum what)
{
    const char *s = (const char *)glGetString(what);
    snprintf(dst, size, "%s", s ? s : "");
}

/* Driver configurations known to corrupt memory whatever a program draws, refused before the
 * first draw (a crash is never the answer to bad input). Mesa 22 (Debian 12: 22.3.6): llvmpipe
 * with LP_NATIVE_VECTOR_WIDTH below 256 on an AVX CPU writes past its own buffers at a draw
 * (tools/lp_width_repro.c aborts the same way without any of swell's code). */
static int known_driver_fault(const struct gpu_caps *c, struct swell_err *err)
{
#if defined(__x86_64__) || defined(__i386__)
    const char *w = getenv("LP_NATIVE_VECTOR_WIDTH");
    const char *mesa = strstr(c->version, "Mesa ");
    if (w && atoi(w) > 0 && atoi(w) < 256 && strstr(c->renderer, "llvmpipe") && mesa &&
        atoi(mesa + 5) <= 22 && __builtin_cpu_supports("avx"))
        return swell_fail(err, SWELL_E_UNSUPPORTED,
                          "gpu: LP_NATIVE_VECTOR_WIDTH=%s with %s (%s) on this AVX CPU: this "
                          "Mesa's llvmpipe writes past its own buffers at a draw and aborts "
                          "(tools/lp_width_repro.c shows it without swell); unset "
                          "LP_NATIVE_VECTOR_WIDTH or set it to 256", w, c->renderer, c->version);
#else
    (void)c;
    (void)err;
#endif
    return SWELL_OK;
}

int gpu_init(struct gpu *g, int forced_tier, uint64_t budget_bytes, struct swell_err *err)
{
    memset(g, 0, sizeof *g);
    g->budget_bytes = budget_bytes;
    struct gpu_caps *c = &g->caps;

    copy_gl_string(c->vendor, sizeof c->vendor, GL_VENDOR);
    copy_gl_string(c->renderer, sizeof c->renderer, GL_RENDERER);
    copy_gl_string(c->version, sizeof c->version, GL_VERSION);
    const char *exts = (const char *)glGetString(GL_EXTENSIONS);
    if (!c->version[0] || !exts)
        return swell_fail(err, SWELL_E_GL, "gpu: glGetString returned NULL (GL_VERSION or "
                          "GL_EXTENSIONS): no current GLES context; create the platform first");
    int rc = known_driver_fault(c, err);
    if (rc)
        return rc;
    c->context_major = parse_es_major(c->version);
    if (c->context_major < 2)
        return swell_fail(err, SWELL_E_TIER, "gpu: context version '%s' is not OpenGL ES 2.0 or "
                          "later; swell needs a GLES 2 context", c->version);

    GLint units = 0, vunits = 0, max_size = 0;
    glGetIntegerv(GL_MAX_TEXTURE_IMAGE_UNITS, &units);
    glGetIntegerv(GL_MAX_VERTEX_TEXTURE_IMAGE_UNITS, &vunits);
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
    GLint range[2] = { 0, 0 }, precision = 0;
    glGetShaderPrecisionFormat(GL_FRAGMENT_SHADER, GL_HIGH_FLOAT, range, &precision);
    rc = gpu_check("gpu: probing limits", err);
    if (rc)
        return rc;

    int es3 = c->context_major >= 3;
    int ext_half = parse_has_token(exts, "GL_OES_texture_half_float") &&
                   parse_has_token(exts, "GL_OES_texture_half_float_linear");
    int ext_deriv = parse_has_token(exts, "GL_OES_standard_derivatives");
    int ext_lod = parse_has_token(exts, "GL_EXT_shader_texture_lod");

    if (es3)
        c->tier_available = TIER_GLES3;
    else if (ext_half || ext_deriv || ext_lod || vunits > 0)
        c->tier_available = TIER_GLES2_EXT;
    else
        c->tier_available = TIER_GLES2_MIN;

    if (forced_tier >= TIER_COUNT)
        return swell_fail(err, SWELL_E_ARG, "gpu: forced tier %d is not a tier (0..%d)",
                          forced_tier, TIER_COUNT - 1);
    if (forced_tier > c->tier_available)
        return swell_fail(err, SWELL_E_TIER, "gpu: tier %s was asked for but this context "
                          "(%s, %s) only offers %s; pick --tier %s or lower",
                          gpu_tier_name(forced_tier), c->renderer, c->version,
                          gpu_tier_name(c->tier_available), gpu_tier_name(c->tier_available));
    c->tier_reason = NULL;
    c->tier = forced_tier >= 0 ? forced_tier
                               : gpu_default_tier(c->renderer, c->tier_available, &c->tier_reason);
    c->max_texture_size = max_size;
    c->fbo_render_mipmap = es3 || parse_has_token(exts, "GL_OES_fbo_render_mipmap");

    switch (c->tier) {
    case TIER_GLES2_MIN:
        c->texture_units = units < GLES2_MIN_TEXTURE_UNITS ? units : GLES2_MIN_TEXTURE_UNITS;
        break;
    case TIER_GLES2_EXT:
        c->texture_units = units;
        c->vertex_texture_units = vunits;
        c->half_float = ext_half;
        c->derivatives = ext_deriv;
        c->texture_lod = ext_lod;
        c->fragment_highp = precision > 0;
        c->glsl100_derivatives = ext_deriv;
        c->glsl100_texture_lod = ext_lod;
        break;
    default:
        /* GLES 3.0 core: half-float textures with linear filtering, dFdx, textureGrad. */
        c->texture_units = units;
        c->vertex_texture_units = vunits;
        c->half_float = 1;
        c->derivatives = 1;
        c->texture_lod = 1;
        c->glsl300 = 1;
        c->fragment_highp = precision > 0;
        c->glsl100_derivatives = ext_deriv;
        c->glsl100_texture_lod = ext_lod;
        break;
    }
    /* Software rasterisers (Mesa llvmpipe, softpipe) lower mediump to fp16 and emulate it on
     * fp32 SIMD: measured here, the gles2-min ocean shader took 2.4x as long in mediump as in
     * highp (10 km, low: 142 vs 59 ms at 1280x720). Where highp exists (never on gles2-min)
     * they get it; GPUs keep mediump, which is as fast or faster on real fp16 hardware. */
    int software = strstr(c->renderer, "llvmpipe") || strstr(c->renderer, "softpipe");
    c->prefer_highp = c->fragment_highp && software;
    /* llvmpipe computes the implicit LOD per 2x2 quad, and where the quads of one SIMD vector
     * differ it fetches each from its own mip level: measured here, a slope fetch at one
     * uniform LOD per draw made the whole 1 km frame 20-30 % faster (low 26.7 -> 21.8 ms,
     * high 46 -> 34 ms at 1280x720, gles3). So on software rasterisers the renderer picks
     * the level per run of rows from the rows' footprint (renderer.c draw_runs) and binds it
     * as that level's own texture without mips (renderer.c chain_tex), on every tier; GPUs
     * keep the per-pixel LOD, free there. */
    c->prefer_run_lod = software;
    c->order_fetches = gpu_orders_fetches(c->renderer);
    /* A shader's LOD bias is clamped to [-MAX_TEXTURE_LOD_BIAS, MAX_TEXTURE_LOD_BIAS] (GLES 3.0
     * §3.8.10: at least 2; EXT_texture_lod_bias for GLES 2); ocean.frag's gles2-min sky filter
     * keeps its biases within it. GLES 2 without the extension cannot say: assumed 16, what
     * Mesa's drivers report. */
    GLfloat bias_max = 0.0f;
    if (es3 || parse_has_token(exts, "GL_EXT_texture_lod_bias")) {
        glGetFloatv(MAX_TEXTURE_LOD_BIAS, &bias_max);
        if ((rc = gpu_check("gpu: probing the LOD bias limit", err)))
            return rc;
    }
    c->max_lod_bias = bias_max > 0.0f ? bias_max : 16.0f;
    return SWELL_OK;
}

int gpu_fragment_texture_lod(const struct gpu_caps *c)
{
    return (c->tier == TIER_GLES3 && c->glsl300) || (c->glsl100_texture_lod && c->texture_lod);
}

void gpu_shutdown(struct gpu *g)
{
    if (!g)
        return;
    free(g->allocs);
    g->allocs = NULL;
    g->alloc_count = g->alloc_cap = 0;
}

int gpu_account(struct gpu *g, uint64_t bytes, const char *what, struct swell_err *err)
{
    if (g->budget_bytes && (bytes > g->budget_bytes || g->bytes > g->budget_bytes - bytes))
        return swell_fail(err, SWELL_E_BUDGET, "gpu: %s needs %llu bytes but %llu of the %llu-byte "
                          "budget are in use (%llu over); use a larger --budget or a smaller "
                          "configuration", what ? what : "allocation",
                          (unsigned long long)bytes, (unsigned long long)g->bytes,
                          (unsigned long long)g->budget_bytes,
                          (unsigned long long)(g->bytes + bytes - g->budget_bytes));
    g->bytes += bytes;
    if (g->bytes > g->peak_bytes)
        g->peak_bytes = g->bytes;
    return SWELL_OK;
}

void gpu_release(struct gpu *g, uint64_t bytes)
{
    g->bytes = bytes > g->bytes ? 0 : g->bytes - bytes;
}

/* Room for one more record, made before the GL object so a failure leaves nothing behind. */
static int reserve_record(struct gpu *g, struct swell_err *err)
{
    if (g->alloc_count < g->alloc_cap)
        return SWELL_OK;
    int cap = g->alloc_cap ? 2 * g->alloc_cap : 32;
    struct gpu_alloc *a = realloc(g->allocs, (size_t)cap * sizeof *a);
    if (!a)
        return swell_fail(err, SWELL_E_NOMEM, "gpu: cannot grow the allocation record to %d "
                          "entries", cap);
    g->allocs = a;
    g->alloc_cap = cap;
    return SWELL_OK;
}

static void add_record(struct gpu *g, GLenum kind, GLuint name, uint64_t bytes)
{
    g->allocs[g->alloc_count++] = (struct gpu_alloc){ kind, name, bytes };
}

/* Remove the record of (kind, name); returns its bytes, 0 if unknown. */
static uint64_t take_record(struct gpu *g, GLenum kind, GLuint name)
{
    for (int i = 0; i < g->alloc_count; i++) {
        if (g->allocs[i].kind == kind && g->allocs[i].name == name) {
            uint64_t bytes = g->allocs[i].bytes;
            g->allocs[i] = g->allocs[--g->alloc_count];
            return bytes;
        }
    }
    return 0;
}

static uint64_t texture_bytes(int w, int h, int levels, int texel)
{
    uint64_t total = 0;
    for (int l = 0; l < levels; l++) {
        uint64_t lw = (uint64_t)(w >> l ? w >> l : 1), lh = (uint64_t)(h >> l ? h >> l : 1);
        total += lw * lh * (uint64_t)texel;
    }
    return total;
}

static int is_pot(int v) { return v > 0 && (v & (v - 1)) == 0; }

GLenum gpu_half_type(const struct gpu *g)
{
    return g->caps.context_major >= 3 ? SWELL_GL_HALF_FLOAT : SWELL_GL_HALF_FLOAT_OES;
}

int gpu_texture_create(struct gpu *g, int width, int height, int levels, int format, int repeat,
                       const char *what, GLuint *tex, struct swell_err *err)
{
    *tex = 0;
    const char *name = what ? what : "texture";
    if (width <= 0 || height <= 0 || width > g->caps.max_texture_size ||
        height > g->caps.max_texture_size)
        return swell_fail(err, SWELL_E_ARG, "gpu: %s: size %dx%d outside 1..%d (GL_MAX_TEXTURE_SIZE)",
                          name, width, height, g->caps.max_texture_size);
    if ((levels > 1 || repeat) && (!is_pot(width) || !is_pot(height)))
        return swell_fail(err, SWELL_E_ARG, "gpu: %s: %dx%d is not a power of two, which "
                          "GLES 2 needs for mipmaps and REPEAT", name, width, height);
    int max_levels = 1;
    while ((width >> max_levels) || (height >> max_levels))
        max_levels++;
    if (levels < 1 || levels > max_levels)
        return swell_fail(err, SWELL_E_ARG, "gpu: %s: %d mip levels, a %dx%d texture has 1..%d",
                          name, levels, width, height, max_levels);
    if (levels > 1 && levels < max_levels && g->caps.context_major < 3)
        return swell_fail(err, SWELL_E_ARG, "gpu: %s: %d of %d mip levels: a partial chain is "
                          "incomplete on GLES 2 (no GL_TEXTURE_MAX_LEVEL); give all levels",
                          name, levels, max_levels);
    GLenum internal = GL_RGBA, type = GL_UNSIGNED_BYTE;
    int texel = 4;
    if (format == FORMAT_RGBA16F) {
        if (!g->caps.half_float)
            return swell_fail(err, SWELL_E_TIER, "gpu: %s: half-float textures are not usable on "
                              "tier %s; bake RGBA8 tables for this tier", name,
                              gpu_tier_name(g->caps.tier));
        texel = 8;
        if (g->caps.context_major >= 3) {
            internal = SWELL_GL_RGBA16F;
            type = SWELL_GL_HALF_FLOAT;
        } else {
            type = SWELL_GL_HALF_FLOAT_OES;
        }
    } else if (format != FORMAT_RGBA8) {
        return swell_fail(err, SWELL_E_ARG, "gpu: %s: format %d is not an enum table_format",
                          name, format);
    }
    uint64_t bytes = texture_bytes(width, height, levels, texel);
    int rc = gpu_account(g, bytes, name, err);
    if (rc)
        return rc;
    rc = reserve_record(g, err);
    if (rc)
        goto fail_account;

    gpu_check("gpu: before texture create", NULL);
    glGenTextures(1, tex);
    glBindTexture(GL_TEXTURE_2D, *tex);
    for (int l = 0; l < levels; l++) {
        int lw = width >> l ? width >> l : 1, lh = height >> l ? height >> l : 1;
        glTexImage2D(GL_TEXTURE_2D, l, (GLint)internal, lw, lh, 0, GL_RGBA, type, NULL);
    }
    GLint wrap = repeat ? GL_REPEAT : GL_CLAMP_TO_EDGE;
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, wrap);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, wrap);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER,
                    levels > 1 ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR);
    /* A partial chain is complete only with MAX_LEVEL set (GLES 3; refused above on GLES 2). */
    if (levels > 1 && levels < max_levels)
        glTexParameteri(GL_TEXTURE_2D, SWELL_GL_TEXTURE_MAX_LEVEL, levels - 1);
    rc = gpu_check(name, err);
    if (rc)
        goto fail_tex;
    add_record(g, GL_TEXTURE, *tex, bytes);
    return SWELL_OK;

fail_tex:
    glDeleteTextures(1, tex);
    *tex = 0;
fail_account:
    gpu_release(g, bytes);
    return rc;
}

void gpu_texture_destroy(struct gpu *g, GLuint *tex)
{
    if (!tex || !*tex)
        return;
    gpu_release(g, take_record(g, GL_TEXTURE, *tex));
    glDeleteTextures(1, tex);
    *tex = 0;
}

int gpu_buffer_create(struct gpu *g, GLenum target, size_t bytes, GLenum usage, const char *what,
                      GLuint *buf, struct swell_err *err)
{
    *buf = 0;
    const char *name = what ? what : "buffer";
    if (bytes == 0)
        return swell_fail(err, SWELL_E_ARG, "gpu: %s: zero-byte buffer", name);
    int rc = gpu_account(g, bytes, name, err);
    if (rc)
        return rc;
    rc = reserve_record(g, err);
    if (rc)
        goto fail_account;
    gpu_check("gpu: before buffer create", NULL);
    glGenBuffers(1, buf);
    glBindBuffer(target, *buf);
    glBufferData(target, (GLsizeiptr)bytes, NULL, usage);
    rc = gpu_check(name, err);
    if (rc)
        goto fail_buf;
    add_record(g, GL_ARRAY_BUFFER, *buf, bytes);
    return SWELL_OK;

fail_buf:
    glDeleteBuffers(1, buf);
    *buf = 0;
fail_account:
    gpu_release(g, bytes);
    return rc;
}

void gpu_buffer_destroy(struct gpu *g, GLuint *buf)
{
    if (!buf || !*buf)
        return;
    gpu_release(g, take_record(g, GL_ARRAY_BUFFER, *buf));
    glDeleteBuffers(1, buf);
    *buf = 0;
}

static const char *gl_error_name(GLenum e)
{
    switch (e) {
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
    default: return "unknown GL error";
    }
}

int gpu_check(const char *where, struct swell_err *err)
{
    GLenum first = glGetError();
    if (first == GL_NO_ERROR)
        return SWELL_OK;
    /* Drain: GL keeps one flag per kind, and a stale one would be blamed on the next call. */
    for (int i = 0; i < 16 && glGetError() != GL_NO_ERROR; i++)
        ;
    return swell_fail(err, SWELL_E_GL, "%s: %s (0x%04x)%s", where ? where : "GL",
                      gl_error_name(first), (unsigned)first,
                      first == GL_OUT_OF_MEMORY ? "; lower --budget or the table sizes" : "");
}

void gpu_probe_target_begin(struct gpu_probe_target *t, int size)
{
    uint8_t px[4] = { 0, 0, 0, 0 };
    memset(t, 0, sizeof *t);
    t->size = size;
    glGetIntegerv(GL_FRAMEBUFFER_BINDING, &t->prev);
    glGenTextures(1, &t->tex);
    glBindTexture(GL_TEXTURE_2D, t->tex);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, size, size, 0, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glGenFramebuffers(1, &t->fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, t->fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, t->tex, 0);
    t->complete = glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
    if (!t->complete)
        return;
    glViewport(0, 0, size, size);
    glClearColor(1.0f, 0.0f, 1.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    glReadPixels(0, 0, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, px);
    t->executes = px[0] == 255 && px[1] == 0 && px[2] == 255 && px[3] == 255;
}

void gpu_probe_target_end(struct gpu_probe_target *t)
{
    glBindFramebuffer(GL_FRAMEBUFFER, (GLuint)t->prev);
    glDeleteFramebuffers(1, &t->fbo);
    glDeleteTextures(1, &t->tex);
    t->fbo = t->tex = 0;
}

int gpu_probe_draw(const char *name, int size, void (*draw)(void *ctx),
                   int (*check)(void *ctx), void *ctx)
{
    int label = shader_labels(), ok = 1;
    struct gpu_probe_target pt;
    gpu_probe_target_begin(&pt, size);
    if (pt.complete) {
        char text[2048];
        struct capture cap;
        if (label)
            fprintf(stderr, "swell-program: probe %s\n", name);
        capture_begin(&cap);
        draw(ctx);
        glFlush();   /* the drivers compile at the draw; glFinish hangs on lima's shim */
        capture_end(&cap, text, sizeof text);
        ok = !capture_refused(text) && !(pt.executes && check && !check(ctx));
        if (label)
            fprintf(stderr, "swell-program: end %s\n", ok ? "ok" : "refused");
    }
    while (glGetError() != GL_NO_ERROR)
        ;
    gpu_probe_target_end(&pt);
    return ok;
}
