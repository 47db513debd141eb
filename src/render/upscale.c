/* upscale.c - render scale (upscale.h). */
#include "render/upscale.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tables/tables.h"   /* FORMAT_RGBA8 */

#define PROBE_SIZE 16

static const char *const uniform_names[1] = { "frame_tex" };
static const struct shader_attrib attribs[1] = { { "a_ndc", 0 } };

int upscale_side(int out, double scale)
{
    long s = lround((double)out * scale);
    return s < 1 ? 1 : (int)s;
}

static void draw_stretch(struct upscale *u, int w, int h)
{
    glViewport(0, 0, w, h);
    glDisable(GL_BLEND);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glUseProgram(u->prog.program);
    glActiveTexture(GL_TEXTURE0 + (GLenum)u->unit);
    glBindTexture(GL_TEXTURE_2D, u->tex);
    glUniform1i(u->u_frame, u->unit);
    glBindBuffer(GL_ARRAY_BUFFER, u->vbo);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, (const void *)0);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    glDisableVertexAttribArray(0);
}

/* The stretch drawn once into a 16x16 target from the scaled target cleared to a known colour:
 * refused where the driver says so on stderr (capture.h), or, where draws execute (a clear
 * reads back), where the colour does not arrive. Labelled for tools/devices.py with
 * SWELL_SHADER_LABELS=1, as the renderer's probe is. */
static void probe_stretch(void *ctx)
{
    draw_stretch(ctx, PROBE_SIZE, PROBE_SIZE);
}

static int probe_green(void *ctx)
{
    uint8_t px[4] = { 0, 0, 0, 0 };
    (void)ctx;
    glReadPixels(PROBE_SIZE / 2, PROBE_SIZE / 2, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, px);
    return px[0] < 8 && px[1] > 247 && px[2] < 8;
}

static int probe(struct upscale *u, struct swell_err *err)
{
    GLint prev = 0;
    glGetIntegerv(GL_FRAMEBUFFER_BINDING, &prev);
    glBindFramebuffer(GL_FRAMEBUFFER, u->fbo);
    glViewport(0, 0, u->w, u->h);
    glClearColor(0.0f, 1.0f, 0.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    glBindFramebuffer(GL_FRAMEBUFFER, (GLuint)prev);
    if (!gpu_probe_draw("upscale", PROBE_SIZE, probe_stretch, probe_green, u))
        return swell_fail(err, SWELL_E_SHADER, "upscale: the driver does not run the stretch of "
                          "--scale (shaders_gles/upscale.*); use --scale 1");
    return SWELL_OK;
}

int upscale_create(struct upscale *u, struct gpu *g, int unit, int out_w, int out_h, double scale,
                   int depth_bits, const char *shader_dir, struct swell_err *err)
{
    static const float ndc[8] = { -1, -1, 1, -1, -1, 1, 1, 1 };
    memset(u, 0, sizeof *u);
    u->gpu = g;
    u->unit = unit;
    u->out_w = out_w;
    u->out_h = out_h;
    u->w = upscale_side(out_w, scale);
    u->h = upscale_side(out_h, scale);
    if (!(scale >= UPSCALE_MIN && scale <= UPSCALE_MAX))
        return swell_fail(err, SWELL_E_ARG, "upscale: scale %g outside %g..%g", scale,
                          UPSCALE_MIN, UPSCALE_MAX);
    struct shader_desc sd = {
        .dir = shader_dir, .vs_file = "upscale.vert", .fs_file = "upscale.frag",
        .caps = &g->caps, .uniform_names = uniform_names, .uniform_count = 1,
        .uniform_locations = &u->u_frame, .attribs = attribs, .attrib_count = 1,
    };
    int rc = shader_program_build(&sd, &u->prog, err);
    if (!rc)
        rc = gpu_texture_create(g, u->w, u->h, 1, FORMAT_RGBA8, 0, "upscale: the scaled frame",
                                &u->tex, err);
    if (!rc && depth_bits > 0) {
        rc = gpu_account(g, (uint64_t)u->w * (uint64_t)u->h * 2u, "upscale: its depth buffer",
                         err);
        if (!rc) {
            glGenRenderbuffers(1, &u->depth);
            glBindRenderbuffer(GL_RENDERBUFFER, u->depth);
            glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT16, u->w, u->h);
            rc = gpu_check("upscale: its depth buffer", err);
        }
    }
    if (!rc)
        rc = gpu_buffer_create(g, GL_ARRAY_BUFFER, sizeof ndc, GL_STATIC_DRAW,
                               "upscale: the strip", &u->vbo, err);
    if (!rc) {
        glBindBuffer(GL_ARRAY_BUFFER, u->vbo);
        glBufferSubData(GL_ARRAY_BUFFER, 0, sizeof ndc, ndc);
        GLint prev = 0;
        glGetIntegerv(GL_FRAMEBUFFER_BINDING, &prev);
        glGenFramebuffers(1, &u->fbo);
        glBindFramebuffer(GL_FRAMEBUFFER, u->fbo);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, u->tex, 0);
        if (u->depth)
            glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER,
                                      u->depth);
        GLenum st = glCheckFramebufferStatus(GL_FRAMEBUFFER);
        glBindFramebuffer(GL_FRAMEBUFFER, (GLuint)prev);
        if (st != GL_FRAMEBUFFER_COMPLETE)
            rc = swell_fail(err, SWELL_E_GL, "upscale: this GPU cannot draw into a %dx%d RGBA8 "
                            "texture%s (framebuffer status 0x%x); use --scale 1", u->w, u->h,
                            u->depth ? " with a 16-bit depth buffer" : "", (unsigned)st);
        else
            rc = gpu_check("upscale: the target", err);
    }
    if (!rc)
        rc = probe(u, err);
    if (rc)
        upscale_destroy(u);
    return rc;
}

void upscale_begin(struct upscale *u)
{
    glGetIntegerv(GL_FRAMEBUFFER_BINDING, &u->target);
    glBindFramebuffer(GL_FRAMEBUFFER, u->fbo);
}

int upscale_end(struct upscale *u, struct swell_err *err)
{
    glBindFramebuffer(GL_FRAMEBUFFER, (GLuint)u->target);
    draw_stretch(u, u->out_w, u->out_h);
    return gpu_check("upscale: the stretch", err);
}

void upscale_destroy(struct upscale *u)
{
    if (!u->gpu)
        return;
    if (u->fbo)
        glDeleteFramebuffers(1, &u->fbo);
    if (u->depth) {
        glDeleteRenderbuffers(1, &u->depth);
        gpu_release(u->gpu, (uint64_t)u->w * (uint64_t)u->h * 2u);
    }
    gpu_buffer_destroy(u->gpu, &u->vbo);
    gpu_texture_destroy(u->gpu, &u->tex);
    shader_program_destroy(&u->prog);
    memset(u, 0, sizeof *u);
}
