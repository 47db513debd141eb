/* gpu.h - the GL device: capability probe, tier choice, and the one accounting point for every
 * texture and buffer allocation (DESIGN.md "Budgets").
 *
 * Tiers (DESIGN.md): GLES2_MIN assumes nothing beyond GLES 2.0 with no vertex texture fetch, no
 * float textures, mediump fragment shaders, no derivatives, no texture LOD in the fragment
 * shader, POT textures, 8 texture units. A forced tier may be lower than the context offers,
 * never higher; code must consult caps (never the context) so a forced tier is honoured.
 */
#ifndef SWELL_GPU_H
#define SWELL_GPU_H

#include <stddef.h>
#include <stdint.h>
#include <GLES2/gl2.h>
#include "core/err.h"

enum gpu_tier { TIER_GLES2_MIN = 0, TIER_GLES2_EXT, TIER_GLES3, TIER_COUNT };

struct gpu_caps {
    int tier;                   /* enum gpu_tier in force */
    int tier_available;         /* highest the context could do */
    const char *tier_reason;    /* why tier is below tier_available unasked (gpu.c), or NULL */
    int texture_units;          /* fragment units usable (min(real, 8) on GLES2_MIN) */
    int vertex_texture_units;   /* 0 on GLES2_MIN */
    int half_float;             /* half-float textures usable (filtering too) */
    int derivatives;            /* OES_standard_derivatives or GLES3 */
    int texture_lod;            /* EXT_shader_texture_lod or GLES3 textureGrad/Lod */
    int glsl300;                /* may compile #version 300 es */
    int max_texture_size;
    int context_major;          /* GL_VERSION major of the context (not the tier) */
    int fragment_highp;         /* highp float in fragment shaders (never on GLES2_MIN) */
    int prefer_highp;           /* fragment shaders use highp: software rasteriser (gpu.c) */
    int prefer_run_lod;         /* pattern fetches at one whole level per draw: software
                                 * rasteriser (gpu.c) */
    int order_fetches;          /* ocean.frag SWELL_ORDER_FETCHES: V3D 4.x (gpu_orders_fetches) */
    int glsl100_derivatives;    /* #version 100 shaders may enable GL_OES_standard_derivatives */
    int glsl100_texture_lod;    /* #version 100 shaders may enable GL_EXT_shader_texture_lod */
    int fbo_render_mipmap;      /* a framebuffer may draw into any mip level of a texture
                                 * (GLES 3, or GLES 2's OES_fbo_render_mipmap; every Mesa
                                 * driver has it): on any tier, not a shader feature */
    float max_lod_bias;         /* largest texture-lookup bias the device applies (gpu.c) */
    char vendor[64], renderer[128], version[128];
};

/* One accounted GL object: the size charged when it was created, released on delete. */
struct gpu_alloc {
    GLenum kind;                /* GL_TEXTURE, or GL_ARRAY_BUFFER for any buffer (names are per kind) */
    GLuint name;
    uint64_t bytes;
};

struct gpu {
    struct gpu_caps caps;
    uint64_t budget_bytes;      /* refuse allocations past this; 0 = no limit */
    uint64_t bytes;             /* accounted now */
    uint64_t peak_bytes;
    struct gpu_alloc *allocs;   /* owned; live objects made by gpu_texture/buffer_create */
    int alloc_count, alloc_cap;
};

const char *gpu_tier_name(int tier);       /* "gles2-min" */
int gpu_tier_from_name(const char *name);  /* TIER_* or -1 */
/* The tier drawn on when none is forced, for a context offering `available` whose
 * GL_RENDERER is `renderer`: `available` but where a lower one is faster on that GPU (*why
 * then says which and why; else untouched). */
int gpu_default_tier(const char *renderer, int available, const char **why);
/* Whether ocean.frag orders its fetches on this device (GL_RENDERER), gpu_caps.order_fetches. */
int gpu_orders_fetches(const char *renderer);
/* Fragment shaders of this tier can give an explicit LOD: GLSL ES 3.00 (the gles3 tier) or
 * GL_EXT_shader_texture_lod in #version 100 shaders (shader.c's SWELL_HAS_TEXTURE_LOD). */
int gpu_fragment_texture_lod(const struct gpu_caps *c);

/* Probe the current context; forced_tier -1 = best available. Fails if forced > available. */
int gpu_init(struct gpu *g, int forced_tier, uint64_t budget_bytes, struct swell_err *err);

/* Free the accounting record (not GL objects: their owners delete them first). Accepts a zeroed
 * or half-initialised struct; safe to call twice. */
void gpu_shutdown(struct gpu *g);

/* Accounting: check first (before allocating), then record; release on delete. */
int  gpu_account(struct gpu *g, uint64_t bytes, const char *what, struct swell_err *err);
void gpu_release(struct gpu *g, uint64_t bytes);

/* Texture helpers going through the accounting point. format: enum table_format.
 * levels 1 = no mips. Allocates storage (NULL data), wrap REPEAT or CLAMP by `repeat`. */
/* The pixel type FORMAT_RGBA16F texels are uploaded with (GLES 3 core or OES_texture_half_float). */
GLenum gpu_half_type(const struct gpu *g);
int  gpu_texture_create(struct gpu *g, int width, int height, int levels, int format, int repeat,
                        const char *what, GLuint *tex, struct swell_err *err);
void gpu_texture_destroy(struct gpu *g, GLuint *tex);
int  gpu_buffer_create(struct gpu *g, GLenum target, size_t bytes, GLenum usage, const char *what,
                       GLuint *buf, struct swell_err *err);
void gpu_buffer_destroy(struct gpu *g, GLuint *buf);

/* glGetError() drained into err with the call site named; 0 if none. */
int gpu_check(const char *where, struct swell_err *err);

/* A start-up probe's small target (renderer.c probe_programs, upscale.c): a size x size RGBA8
 * texture bound as the framebuffer (the one bound before kept in prev), cleared to magenta.
 * complete: the framebuffer is; executes: the clear read back, i.e. this device runs draws
 * (Mesa's noop drm-shims run none, so a probe there can only read the driver's words). */
struct gpu_probe_target {
    GLuint fbo, tex;
    GLint prev;
    int size, complete, executes;
};
void gpu_probe_target_begin(struct gpu_probe_target *t, int size);
/* The framebuffer bound before begin bound again; the target deleted. */
void gpu_probe_target_end(struct gpu_probe_target *t);
/* One probe draw of a program outside the ocean's (upscale.c's stretch, reflect.c's copy):
 * draw(ctx) into a size x size probe target with stderr captured (capture.h); the driver runs
 * it unless it said it cannot, or, where draws execute, check(ctx) (may be NULL) finds the
 * target's pixels wrong. With SWELL_SHADER_LABELS=1 labelled "swell-program: probe NAME" ...
 * "swell-program: end ok|refused" (tools/devices.py). GL errors it left are cleared; the
 * framebuffer bound before is bound again. 1 when the driver runs it. */
int gpu_probe_draw(const char *name, int size, void (*draw)(void *ctx),
                   int (*check)(void *ctx), void *ctx);

#endif
