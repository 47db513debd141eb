/* platform_surfaceless.c - offscreen back-end: EGL_MESA_platform_surfaceless display, a GLES
 * context made current with no surface (EGL_KHR_surfaceless_context), and an FBO as the frame.
 * Needs no display, no window system and no DRM master: tests and batch PNG output use it.
 * The EGL calls themselves are egl.c's, shared with the KMS back-end.
 */
#include "platform/platform.h"

#include <stdlib.h>
#include <string.h>

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GLES2/gl2.h>
#include <GLES2/gl2ext.h>

#include "core/parse.h"
#include "platform/egl.h"

#define DEFAULT_WIDTH 1280
#define DEFAULT_HEIGHT 720

struct platform {
    int width, height;
    struct egl egl;             /* display and context; no surface */
    GLuint fbo, color_rb, color_tex, depth_rb;
    uint8_t *row;               /* one row, for the vertical flip in read_rgba */
};

static void sl_destroy(struct platform *p)
{
    if (!p)
        return;
    if (p->egl.dpy != EGL_NO_DISPLAY && p->egl.ctx != EGL_NO_CONTEXT &&
        eglGetCurrentContext() == p->egl.ctx) {
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        if (p->fbo)
            glDeleteFramebuffers(1, &p->fbo);
        if (p->color_rb)
            glDeleteRenderbuffers(1, &p->color_rb);
        if (p->color_tex)
            glDeleteTextures(1, &p->color_tex);
        if (p->depth_rb)
            glDeleteRenderbuffers(1, &p->depth_rb);
    }
    egl_destroy(&p->egl);
    free(p->row);
    free(p);
}

static int open_display(struct platform *p, struct swell_err *err)
{
    const char *client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!client)
        return swell_fail(err, SWELL_E_UNSUPPORTED, "platform surfaceless: this EGL has no client "
                          "extensions (EGL_EXT_client_extensions); install Mesa's libEGL");
    if (!parse_has_token(client, "EGL_EXT_platform_base") ||
        !parse_has_token(client, "EGL_MESA_platform_surfaceless"))
        return swell_fail(err, SWELL_E_UNSUPPORTED, "platform surfaceless: EGL lacks "
                          "EGL_EXT_platform_base or EGL_MESA_platform_surfaceless (client "
                          "extensions: %.600s); install Mesa's libEGL", client);
    const struct egl_display_desc dd = {
        .platform = EGL_PLATFORM_SURFACELESS_MESA,
        .platform_name = "EGL_PLATFORM_SURFACELESS_MESA",
        .native = EGL_DEFAULT_DISPLAY,
        .no_entry_code = SWELL_E_UNSUPPORTED,
        .no_entry_msg = "eglGetPlatformDisplayEXT is advertised but not loadable",
        .init_what = "eglInitialize",
        .init_hint = "is there a render node (/dev/dri/renderD*) or Mesa's software rasteriser "
                     "(llvmpipe)?",
    };
    int rc = egl_open_display(&p->egl, &dd, err);
    if (rc)
        return rc;
    const char *exts = eglQueryString(p->egl.dpy, EGL_EXTENSIONS);
    if (!parse_has_token(exts, "EGL_KHR_surfaceless_context"))
        return swell_fail(err, SWELL_E_UNSUPPORTED, "platform surfaceless: the display lacks "
                          "EGL_KHR_surfaceless_context");
    return SWELL_OK;
}

static int create_context(struct platform *p, int gles_major, struct swell_err *err)
{
    int rc = egl_bind_gles(&p->egl, err);
    if (rc)
        return rc;
    /* GLES 3 first when asked, then GLES 2 (platform.h: 3 falls back to 2). */
    for (int major = gles_major; major >= 2; major--) {
        const EGLint config_attrs[] = {
            EGL_SURFACE_TYPE, EGL_PBUFFER_BIT,
            EGL_RENDERABLE_TYPE, major >= 3 ? EGL_OPENGL_ES3_BIT_KHR : EGL_OPENGL_ES2_BIT,
            EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8, EGL_ALPHA_SIZE, 8,
            EGL_NONE
        };
        EGLConfig config;
        EGLint n = 0;
        if (!eglChooseConfig(p->egl.dpy, config_attrs, &config, 1, &n) || n < 1)
            continue;
        p->egl.config = config;
        if (egl_try_context(&p->egl, major))
            break;
    }
    if (p->egl.ctx == EGL_NO_CONTEXT)
        return egl_fail(&p->egl, err, "eglCreateContext (GLES 2 and 3)",
                        "no GLES config on this display");
    return egl_make_current(&p->egl, err);
}

static int create_fbo(struct platform *p, struct swell_err *err)
{
    const char *exts = (const char *)glGetString(GL_EXTENSIONS);
    const char *version = (const char *)glGetString(GL_VERSION);
    int es3 = version && strncmp(version, "OpenGL ES 3", 11) == 0;
    glGenFramebuffers(1, &p->fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, p->fbo);
    if (es3 || parse_has_token(exts, "GL_OES_rgb8_rgba8")) {
        glGenRenderbuffers(1, &p->color_rb);
        glBindRenderbuffer(GL_RENDERBUFFER, p->color_rb);
        glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8_OES, p->width, p->height);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                                  p->color_rb);
    } else {
        /* GLES 2 core has no 8-bit-per-channel renderbuffer; an RGBA texture is renderable. */
        glGenTextures(1, &p->color_tex);
        glBindTexture(GL_TEXTURE_2D, p->color_tex);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, p->width, p->height, 0, GL_RGBA,
                     GL_UNSIGNED_BYTE, NULL);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D,
                               p->color_tex, 0);
    }
    glGenRenderbuffers(1, &p->depth_rb);
    glBindRenderbuffer(GL_RENDERBUFFER, p->depth_rb);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT16, p->width, p->height);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, p->depth_rb);
    GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    GLenum gl_err = glGetError();
    if (status != GL_FRAMEBUFFER_COMPLETE || gl_err != GL_NO_ERROR)
        return swell_fail(err, SWELL_E_GL, "platform surfaceless: %dx%d RGBA8 + DEPTH16 "
                          "framebuffer incomplete (status 0x%04x, GL error 0x%04x); try a "
                          "smaller --size", p->width, p->height, (unsigned)status,
                          (unsigned)gl_err);
    glViewport(0, 0, p->width, p->height);
    return SWELL_OK;
}

static int sl_create(const struct platform_desc *d, struct platform **out, struct swell_err *err)
{
    *out = NULL;
    int w = d->width ? d->width : DEFAULT_WIDTH;
    int h = d->height ? d->height : DEFAULT_HEIGHT;
    if (w < 1 || h < 1 || w > 16384 || h > 16384)
        return swell_fail(err, SWELL_E_ARG, "platform surfaceless: size %dx%d outside "
                          "1x1..16384x16384", w, h);
    int gles_major = d->gles_major ? d->gles_major : 2;
    if (gles_major != 2 && gles_major != 3)
        return swell_fail(err, SWELL_E_ARG, "platform surfaceless: gles_major %d is not 2 or 3",
                          gles_major);
    struct platform *p = calloc(1, sizeof *p);
    if (!p)
        return swell_fail(err, SWELL_E_NOMEM, "platform surfaceless: no memory for the state");
    p->width = w;
    p->height = h;
    egl_init(&p->egl, "platform surfaceless");
    int rc = SWELL_OK;
    p->row = malloc((size_t)w * 4);
    if (!p->row) {
        rc = swell_fail(err, SWELL_E_NOMEM, "platform surfaceless: no memory for a %d-pixel row", w);
        goto fail;
    }
    rc = open_display(p, err);
    if (rc)
        goto fail;
    rc = create_context(p, gles_major, err);
    if (rc)
        goto fail;
    rc = create_fbo(p, err);
    if (rc)
        goto fail;
    *out = p;
    return SWELL_OK;

fail:
    sl_destroy(p);
    return rc;
}

static void sl_size(struct platform *p, int *w, int *h)
{
    *w = p->width;
    *h = p->height;
}

static int sl_begin_frame(struct platform *p, struct swell_err *err)
{
    glBindFramebuffer(GL_FRAMEBUFFER, p->fbo);
    glViewport(0, 0, p->width, p->height);
    GLenum e = glGetError();
    if (e != GL_NO_ERROR)
        return swell_fail(err, SWELL_E_GL, "platform surfaceless: binding the frame FBO: GL "
                          "error 0x%04x", (unsigned)e);
    return SWELL_OK;
}

static int sl_present(struct platform *p, struct swell_err *err)
{
    (void)p;
    glFlush();
    GLenum e = glGetError();
    if (e != GL_NO_ERROR)
        return swell_fail(err, SWELL_E_GL, "platform surfaceless: present: GL error 0x%04x",
                          (unsigned)e);
    return SWELL_OK;
}

static int sl_read_rgba(struct platform *p, uint8_t *rgba, struct swell_err *err)
{
    glBindFramebuffer(GL_FRAMEBUFFER, p->fbo);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, p->width, p->height, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
    GLenum e = glGetError();
    if (e != GL_NO_ERROR)
        return swell_fail(err, SWELL_E_GL, "platform surfaceless: glReadPixels %dx%d: GL error "
                          "0x%04x", p->width, p->height, (unsigned)e);
    /* GL rows are bottom-up; platform.h promises the top row first. */
    size_t stride = (size_t)p->width * 4;
    for (int y = 0; y < p->height / 2; y++) {
        uint8_t *a = rgba + (size_t)y * stride, *b = rgba + (size_t)(p->height - 1 - y) * stride;
        memcpy(p->row, a, stride);
        memcpy(a, b, stride);
        memcpy(b, p->row, stride);
    }
    return SWELL_OK;
}

static int sl_should_quit(struct platform *p)
{
    (void)p;
    return 0;
}

const struct platform_backend platform_surfaceless_backend = {
    .name = "surfaceless",
    .create = sl_create,
    .size = sl_size,
    .begin_frame = sl_begin_frame,
    .present = sl_present,
    .read_rgba = sl_read_rgba,
    .should_quit = sl_should_quit,
    .destroy = sl_destroy,
};
