/* lp_width_repro.c - Mesa's alone: llvmpipe with LP_NATIVE_VECTOR_WIDTH=128 on an AVX CPU
 * corrupts its heap at an ordinary draw, without any of swell's code (issue 17).
 *
 * A GLES 2 context on EGL surfaceless, a 96 x 64 grid drawn with 16-bit indices by a program
 * passing N vec4 varyings (argument 1, default 8; swell's grid has that shape). Exit 0 when
 * the draws and the read-back complete. Measured with Debian 12's Mesa 22.3.6 on an AVX-512
 * CPU: with LP_NATIVE_VECTOR_WIDTH=128 and 8 varyings, "malloc(): invalid size (unsorted)",
 * abort, 3 runs of 3 (1-7 and 9-15 varyings draw; unset or 256 draws). Under Electric Fence
 * swell's own draw faults in the JIT's code, a vextractf128 of a 256-bit register stored past
 * the end of a buffer Mesa allocated. gl/gpu.c refuses that configuration before a draw.
 * Build: make build/rel/tools/lp-width-repro. Not part of the tests: its outcome is Mesa's.
 */
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GLES2/gl2.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { W = 96, H = 64 };

static GLuint compile(GLenum stage, const char *src)
{
    GLuint s = glCreateShader(stage);
    glShaderSource(s, 1, &src, NULL);
    glCompileShader(s);
    return s;
}

int main(int argc, char **argv)
{
    int nv = argc > 1 ? atoi(argv[1]) : 8;
    if (nv < 1 || nv > 15) {
        fprintf(stderr, "usage: lp-width-repro [VARYINGS 1..15]\n");
        return 2;
    }
    PFNEGLGETPLATFORMDISPLAYEXTPROC get_display =
        (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
    EGLDisplay d = get_display ? get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY,
                                             NULL) : EGL_NO_DISPLAY;
    EGLint context_attrs[] = { EGL_CONTEXT_CLIENT_VERSION, 2, EGL_NONE };
    EGLContext c = EGL_NO_CONTEXT;
    if (d != EGL_NO_DISPLAY && eglInitialize(d, NULL, NULL) && eglBindAPI(EGL_OPENGL_ES_API))
        c = eglCreateContext(d, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, context_attrs);
    if (c == EGL_NO_CONTEXT || !eglMakeCurrent(d, EGL_NO_SURFACE, EGL_NO_SURFACE, c)) {
        fprintf(stderr, "lp-width-repro: no EGL surfaceless GLES 2 context\n");
        return 1;
    }
    GLuint fbo, rb;
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glGenRenderbuffers(1, &rb);
    glBindRenderbuffer(GL_RENDERBUFFER, rb);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA4, 64, 64);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb);

    char vs[2048] = "attribute vec4 p;\n", fs[2048] = "precision mediump float;\n", line[64];
    for (int i = 0; i < nv; i++) {
        snprintf(line, sizeof line, "varying vec4 v%d;\n", i);
        strcat(vs, line);
        strcat(fs, line);
    }
    strcat(vs, "void main() {\n  gl_Position = vec4(p.xy, 0.0, 1.0);\n");
    strcat(fs, "void main() {\n  vec4 s = vec4(0.0);\n");
    for (int i = 0; i < nv; i++) {
        snprintf(line, sizeof line, "  v%d = p * %d.0;\n", i, i + 1);
        strcat(vs, line);
        snprintf(line, sizeof line, "  s += v%d;\n", i);
        strcat(fs, line);
    }
    strcat(vs, "}\n");
    strcat(fs, "  gl_FragColor = fract(s);\n}\n");
    GLuint prog = glCreateProgram();
    glAttachShader(prog, compile(GL_VERTEX_SHADER, vs));
    glAttachShader(prog, compile(GL_FRAGMENT_SHADER, fs));
    glBindAttribLocation(prog, 0, "p");
    glLinkProgram(prog);
    GLint linked = 0;
    glGetProgramiv(prog, GL_LINK_STATUS, &linked);
    if (!linked) {
        fprintf(stderr, "lp-width-repro: the program did not link\n");
        return 1;
    }
    glUseProgram(prog);

    static float v[W * H * 4];
    static unsigned short idx[(W - 1) * (H - 1) * 6];
    int k = 0;
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++) {
            float *q = v + 4 * (j * W + i);
            q[0] = 2.0f * (float)i / (W - 1) - 1.0f;
            q[1] = 2.0f * (float)j / (H - 1) - 1.0f;
            q[2] = 0.3f;
            q[3] = 1.0f;
        }
    for (int j = 0; j < H - 1; j++)
        for (int i = 0; i < W - 1; i++) {
            unsigned short o = (unsigned short)(j * W + i);
            unsigned short quad[6] = { o, (unsigned short)(o + 1), (unsigned short)(o + W),
                                       (unsigned short)(o + 1), (unsigned short)(o + W + 1),
                                       (unsigned short)(o + W) };
            memcpy(idx + k, quad, sizeof quad);
            k += 6;
        }
    GLuint buf[2];
    glGenBuffers(2, buf);
    glBindBuffer(GL_ARRAY_BUFFER, buf[0]);
    glBufferData(GL_ARRAY_BUFFER, sizeof v, v, GL_STATIC_DRAW);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, buf[1]);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, sizeof idx, idx, GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 4, GL_FLOAT, GL_FALSE, 0, NULL);
    glViewport(0, 0, 64, 64);
    for (int r = 0; r < 4; r++)     /* shorter and shorter runs of rows, as swell draws */
        glDrawElements(GL_TRIANGLES, k - 6 * r * (W - 1), GL_UNSIGNED_SHORT, NULL);
    unsigned char px[4];
    glReadPixels(0, 0, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, px);
    GLenum e = glGetError();
    printf("lp-width-repro: %s, %d varyings: %d indices drawn, GL error 0x%x\n",
           (const char *)glGetString(GL_VERSION), nv, k, e);
    return e == GL_NO_ERROR ? 0 : 1;
}
