/* pass.c - what the application's passes share (reflect.c, shadow.c): a target it draws into
 * (RGBA8 colour with its mip chain and 16-bit depth), and the GL state a pass changes, saved
 * at its begin and restored at its end. */
#include "render/internal.h"

/* A view pass's map: the viewport's size halved, as a power of two (GLES 2 mipmaps), within
 * these. */
#define PASS_MIN 32
#define PASS_MAX 512

static uint64_t depth_bytes(int w, int h)
{
    return (uint64_t)w * (uint64_t)h * 2u;
}

/* The renderer's share (renderer_stats): colour (with its mips, 4/3) and depth. */
static uint64_t target_bytes(int w, int h, int levels)
{
    uint64_t n = (uint64_t)w * (uint64_t)h;
    return (levels > 1 ? n * 16u / 3u : n * 4u) + depth_bytes(w, h);
}

void pass_target_destroy(struct renderer *r, struct pass_target *t)
{
    if (t->w)
        r->gpu_bytes -= target_bytes(t->w, t->h, t->levels);
    if (t->fbo)
        glDeleteFramebuffers(1, &t->fbo);
    if (t->depth) {
        glDeleteRenderbuffers(1, &t->depth);
        gpu_release(r->gpu, depth_bytes(t->w, t->h));
    }
    gpu_texture_destroy(r->gpu, &t->tex);
    t->fbo = t->depth = 0;
    t->w = t->h = t->levels = 0;
}

int pass_target_create(struct renderer *r, struct pass_target *t, int w, int h, int mips,
                       int unit, const char *what, struct swell_err *err)
{
    pass_target_destroy(r, t);
    glActiveTexture(GL_TEXTURE0 + (GLenum)(r->d.texture_unit_first + unit));
    int levels = 1;
    while (mips && ((w >> levels) || (h >> levels)))
        levels++;
    int rc = gpu_texture_create(r->gpu, w, h, levels, FORMAT_RGBA8, 0, what, &t->tex, err);
    if (rc)
        return rc;
    if ((rc = gpu_account(r->gpu, depth_bytes(w, h), what, err))) {
        gpu_texture_destroy(r->gpu, &t->tex);
        return rc;
    }
    t->w = w;
    t->h = h;
    t->levels = levels;
    r->gpu_bytes += target_bytes(w, h, levels);
    glGenRenderbuffers(1, &t->depth);
    glBindRenderbuffer(GL_RENDERBUFFER, t->depth);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT16, w, h);
    glGenFramebuffers(1, &t->fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, t->fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, t->tex, 0);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, t->depth);
    GLenum st = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    if (st != GL_FRAMEBUFFER_COMPLETE) {
        pass_target_destroy(r, t);
        return swell_fail(err, SWELL_E_GL, "renderer: the %s %dx%d (RGBA8, 16-bit depth) is not "
                          "complete on this device (status 0x%x)", what, w, h, st);
    }
    return gpu_check(what, err);
}

/* The target bound for the application's draws: its viewport, no scissor, depth writes on,
 * colour cleared to transparent black and depth to 1. */
void pass_target_bind(const struct pass_target *t)
{
    glBindFramebuffer(GL_FRAMEBUFFER, t->fbo);
    glViewport(0, 0, t->w, t->h);
    glDisable(GL_SCISSOR_TEST);
    glDepthMask(GL_TRUE);
    glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
}

void pass_save(struct pass_saved *s)
{
    glGetIntegerv(GL_FRAMEBUFFER_BINDING, &s->fbo);
    glGetIntegerv(GL_VIEWPORT, s->viewport);
    glGetIntegerv(GL_FRONT_FACE, &s->front);
    glGetFloatv(GL_COLOR_CLEAR_VALUE, s->clear);
    glGetBooleanv(GL_DEPTH_WRITEMASK, &s->depth_mask);
    glGetIntegerv(GL_ACTIVE_TEXTURE, &s->active);
    s->scissor = glIsEnabled(GL_SCISSOR_TEST);
}

void pass_quad_begin(const struct renderer *r, GLuint fbo, GLuint program)
{
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glDisable(GL_BLEND);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glDisable(GL_SCISSOR_TEST);
    glUseProgram(program);
    glBindBuffer(GL_ARRAY_BUFFER, r->quad_vbo);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, (const void *)0);
}

void pass_restore(const struct pass_saved *s)
{
    glBindFramebuffer(GL_FRAMEBUFFER, (GLuint)s->fbo);
    glViewport(s->viewport[0], s->viewport[1], s->viewport[2], s->viewport[3]);
    glFrontFace((GLenum)s->front);
    glActiveTexture((GLenum)s->active);
    glClearColor(s->clear[0], s->clear[1], s->clear[2], s->clear[3]);
    glDepthMask(s->depth_mask);
    if (s->scissor)
        glEnable(GL_SCISSOR_TEST);
    else
        glDisable(GL_SCISSOR_TEST);
}

/* The 1x1 transparent map a draw reads when no pass was drawn for it. */
int pass_none_create(struct renderer *r, GLuint *tex, const char *what, struct swell_err *err)
{
    static const uint8_t clear[4] = { 0, 0, 0, 0 };
    int rc = gpu_texture_create(r->gpu, 1, 1, 1, FORMAT_RGBA8, 0, what, tex, err);
    if (rc)
        return rc;
    return upload_single(*tex, 1, 1, clear, what, err);
}

static int pot_floor(int n)
{
    int p = 1;
    while (2 * p <= n)
        p *= 2;
    return p;
}

void pass_target_size(int vw, int vh, int *w, int *h)
{
    *w = pot_floor(vw / 2);
    *h = pot_floor(vh / 2);
    *w = *w < PASS_MIN ? PASS_MIN : *w > PASS_MAX ? PASS_MAX : *w;
    *h = *h < PASS_MIN ? PASS_MIN : *h > PASS_MAX ? PASS_MAX : *h;
}

/* Lengyel's oblique near plane: proj (column-major) made to clip at the eye-space plane c
 * (points with c . (x, y, z, 1) < 0 cut), the camera on that side (c[3] < 0). */
void pass_oblique_near(float p[16], const double c[4])
{
    double q[4] = { ((c[0] > 0.0) - (c[0] < 0.0) + p[8]) / p[0],
                    ((c[1] > 0.0) - (c[1] < 0.0) + p[9]) / p[5], -1.0,
                    (1.0 + p[10]) / p[14] };
    double dq = c[0] * q[0] + c[1] * q[1] + c[2] * q[2] + c[3] * q[3];
    double s = 2.0 / dq;
    p[2] = (float)(c[0] * s);
    p[6] = (float)(c[1] * s);
    p[10] = (float)(c[2] * s + 1.0);
    p[14] = (float)(c[3] * s);
}


void pass_widen(float p[16])
{
    p[0] /= PASS_MARGIN;
    p[5] /= PASS_MARGIN;
    p[8] /= PASS_MARGIN;
    p[9] /= PASS_MARGIN;
}

/* gl_FragCoord to a view pass's map uv (the view's viewport, the pass's projection widened by
 * PASS_MARGIN): 0.5 + ndc / (2 m), as scale xy and offset zw. */
void pass_screen_uv(const struct renderer_view *v, float out[4])
{
    out[0] = 1.0f / ((float)v->width * PASS_MARGIN);
    out[1] = 1.0f / ((float)v->height * PASS_MARGIN);
    out[2] = 0.5f - (0.5f + (float)v->x / (float)v->width) / PASS_MARGIN;
    out[3] = 0.5f - (0.5f + (float)v->y / (float)v->height) / PASS_MARGIN;
}
