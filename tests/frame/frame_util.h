/* frame_util.h - what the surfaceless frame tests share: opening the platform (skip, exit 77,
 * without an EGL device unless CI=true, where that is a failure) and drawing one frame of a
 * renderer into an RGBA8 buffer. Header-only: each test is one program. */
#ifndef SWELL_TESTS_FRAME_UTIL_H
#define SWELL_TESTS_FRAME_UTIL_H

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <GLES2/gl2.h>
#include "core/camera.h"
#include "platform/platform.h"
#include "render/renderer.h"

/* 0 when the surfaceless platform is open at w x h (GLES 3 context, tiers are forced lower),
 * else the exit status main() should return: 1 under CI=true, 77 (skip) elsewhere. */
static inline int frame_open(const char *test, int w, int h, struct platform_handle *ph)
{
    struct platform_desc pd = { 0 };
    struct swell_err err = { 0 };
    const char *ci = getenv("CI");
    pd.kind = PLATFORM_SURFACELESS;
    pd.width = w;
    pd.height = h;
    pd.gles_major = 3;
    if (!platform_open(&pd, ph, &err))
        return 0;
    if (ci && !strcmp(ci, "true")) {
        fprintf(stderr, "%s: no EGL device under CI=true: %s\n", test, err.msg);
        return 1;
    }
    fprintf(stderr, "%s: skipped, no EGL device: %s\n", test, err.msg);
    return 77;
}

/* One frame of r for camera c at time t_s, read back into rgba (w x h x 4); 0 or an error in
 * err (the caller fails the test with it). */
static inline int frame_draw(struct platform_handle *ph, struct renderer *r,
                             const struct camera *c, double t_s, int w, int h, uint8_t *rgba,
                             struct swell_err *err)
{
    int rc;
    if ((rc = ph->be->begin_frame(ph->p, err)) || (rc = renderer_frame(r, c, t_s, w, h, err)) ||
        (rc = ph->be->present(ph->p, err)) || (rc = ph->be->read_rgba(ph->p, rgba, err)))
        return rc;
    return 0;
}

/* An embedding application's framebuffer, as the API tests draw into: RGBA4 colour and 16-bit
 * depth renderbuffers, w x h, left bound; 0 when it is not complete. */
static inline GLuint frame_app_framebuffer(int w, int h)
{
    GLuint fbo, colour, depth;
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glGenRenderbuffers(1, &colour);
    glBindRenderbuffer(GL_RENDERBUFFER, colour);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA4, w, h);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour);
    glGenRenderbuffers(1, &depth);
    glBindRenderbuffer(GL_RENDERBUFFER, depth);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT16, w, h);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth);
    return glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE ? fbo : 0;
}

/* An application's object program: a_pos (attribute 0) by the uniform mvp, in one flat colour
 * (alpha 1); 0 when it does not link. */
static inline GLuint frame_flat_program(float r, float g, float b)
{
    char fs[160];
    snprintf(fs, sizeof fs, "precision mediump float;\nvoid main() { gl_FragColor = "
             "vec4(%.3f, %.3f, %.3f, 1.0); }\n", (double)r, (double)g, (double)b);
    const char *src[2] = { "attribute vec3 a_pos; uniform mat4 mvp;\n"
                           "void main() { gl_Position = mvp * vec4(a_pos, 1.0); }\n", fs };
    GLenum kind[2] = { GL_VERTEX_SHADER, GL_FRAGMENT_SHADER };
    GLuint p = glCreateProgram();
    for (int i = 0; i < 2; i++) {
        GLuint sh = glCreateShader(kind[i]);
        glShaderSource(sh, 1, &src[i], NULL);
        glCompileShader(sh);
        glAttachShader(p, sh);
    }
    glBindAttribLocation(p, 0, "a_pos");
    glLinkProgram(p);
    GLint ok = 0;
    glGetProgramiv(p, GL_LINK_STATUS, &ok);
    return ok ? p : 0;
}

#endif
