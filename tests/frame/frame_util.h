/* frame_util.h - what the surfaceless frame tests share: opening the platform (skip, exit 77,
 * without an EGL device unless CI=true, where that is a failure) and drawing one frame of a
 * renderer into an RGBA8 buffer. Header-only: each test is one program. */
#ifndef SWELL_TESTS_FRAME_UTIL_H
#define SWELL_TESTS_FRAME_UTIL_H

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <GLES2/gl2.h>
#include "core/camera.h"
#include "platform/platform.h"
#include "render/renderer.h"
#include "swell.h"

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

/* An RGBA8 target (a GL_RGBA texture: renders on every GPU swell targets, GLES 2 core) with
 * 16-bit depth, bound; 0 when incomplete. Where exact colours or faint tails matter, not the
 * RGBA4 application framebuffer above. Its texture and depth buffer live as long as the test's
 * context. */
static inline GLuint frame_rgba8_framebuffer(int w, int h)
{
    GLuint fbo, tex, depth;
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_2D, tex);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex, 0);
    glGenRenderbuffers(1, &depth);
    glBindRenderbuffer(GL_RENDERBUFFER, depth);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT16, w, h);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth);
    return glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE ? fbo : 0;
}

/* An application's program from its two sources, a_pos at attribute 0; 0 when it does not
 * link. */
static inline GLuint frame_program(const char *vs, const char *fs)
{
    const char *src[2] = { vs, fs };
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

/* An application's object program: a_pos (attribute 0) by the uniform mvp, in one flat colour
 * (alpha 1); 0 when it does not link. */
static inline GLuint frame_flat_program(float r, float g, float b)
{
    char fs[160];
    snprintf(fs, sizeof fs, "precision mediump float;\nvoid main() { gl_FragColor = "
             "vec4(%.3f, %.3f, %.3f, 1.0); }\n", (double)r, (double)g, (double)b);
    return frame_program("attribute vec3 a_pos; uniform mat4 mvp;\n"
                         "void main() { gl_Position = mvp * vec4(a_pos, 1.0); }\n", fs);
}

/* out = a b, 4 x 4 column-major. */
static inline void frame_mat_mul(const float a[16], const float b[16], float out[16])
{
    for (int c = 0; c < 4; c++)
        for (int r = 0; r < 4; r++) {
            float acc = 0.0f;
            for (int k = 0; k < 4; k++)
                acc += a[4 * k + r] * b[4 * c + k];
            out[4 * c + r] = acc;
        }
}

/* An application's object: the quad of corners c (world, m; a triangle strip's order) drawn
 * with program prog (frame_flat_program) by view and proj relative to eye, as an application
 * draws (positions less the eye in double), depth-tested. */
static inline void frame_draw_quad(GLuint prog, const float view[16], const float proj[16],
                                   const double eye[3], const double c[4][3])
{
    float mvp[16], v[12];
    frame_mat_mul(proj, view, mvp);
    for (int i = 0; i < 4; i++)
        for (int k = 0; k < 3; k++)
            v[3 * i + k] = (float)(c[i][k] - eye[k]);
    glUseProgram(prog);
    glUniformMatrix4fv(glGetUniformLocation(prog, "mvp"), 1, GL_FALSE, mvp);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, v);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    glDisableVertexAttribArray(0);
    glDisable(GL_DEPTH_TEST);
}

/* An application's camera as a swell_view: the eye at eye (m), looking along heading_deg (CCW
 * from +x) pitch_deg up (negative: down), no roll; a 45 deg vertical field of view, near 0.5 m,
 * far 5 km; the viewport w x h at the origin; clear and sky. */
static inline void frame_app_view(swell_view *v, const double eye[3], double heading_deg,
                                  double pitch_deg, int w, int h)
{
    memset(v, 0, sizeof *v);
    memcpy(v->camera_pos, eye, sizeof v->camera_pos);
    double hd = heading_deg * M_PI / 180.0, p = pitch_deg * M_PI / 180.0;
    double f[3] = { cos(p) * cos(hd), cos(p) * sin(hd), sin(p) }, s[3] = { sin(hd), -cos(hd), 0.0 };
    double u[3] = { s[1] * f[2] - s[2] * f[1], s[2] * f[0] - s[0] * f[2],
                    s[0] * f[1] - s[1] * f[0] };
    float r[16] = { (float)s[0], (float)u[0], (float)-f[0], 0, (float)s[1], (float)u[1],
                    (float)-f[1], 0, (float)s[2], (float)u[2], (float)-f[2], 0, 0, 0, 0, 1 };
    memcpy(v->view, r, sizeof r);
    double t = 1.0 / tan(45.0 * M_PI / 360.0), n = 0.5, fa = 5000.0;
    v->proj[0] = (float)(t * h / w);
    v->proj[5] = (float)t;
    v->proj[10] = (float)((fa + n) / (n - fa));
    v->proj[11] = -1.0f;
    v->proj[14] = (float)(2.0 * fa * n / (n - fa));
    v->viewport[2] = w;
    v->viewport[3] = h;
    v->flags = SWELL_DRAW_CLEAR | SWELL_DRAW_SKY;
}

/* The flat sea's point (z = 0) under pixel (x, y) (GL's rows, from the bottom) of view v, its
 * viewport at the origin, its projection perspective (off-axis too: ndc = P00 e_x / -e_z -
 * P20, so the eye ray is ((ndc_x + P20) / P00, (ndc_y + P21) / P11, -1)): 0 and xy, or -1
 * above the horizon. */
static inline int frame_sea_point(const swell_view *v, double x, double y, double xy[2])
{
    double e[3] = { ((2.0 * (x + 0.5) / v->viewport[2]) - 1.0 + v->proj[8]) / v->proj[0],
                    ((2.0 * (y + 0.5) / v->viewport[3]) - 1.0 + v->proj[9]) / v->proj[5], -1.0 };
    double d[3];
    for (int i = 0; i < 3; i++)   /* world = R^T eye: row i of R^T is column i of the view */
        d[i] = v->view[4 * i + 0] * e[0] + v->view[4 * i + 1] * e[1] + v->view[4 * i + 2] * e[2];
    if (d[2] >= -1e-9)
        return -1;
    double t = v->camera_pos[2] / -d[2];
    xy[0] = v->camera_pos[0] + t * d[0];
    xy[1] = v->camera_pos[1] + t * d[1];
    return 0;
}

#endif
