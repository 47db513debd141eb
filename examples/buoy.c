/* buoy.c - swell inside an application's own GLES 2 program: the application makes its EGL
 * context and framebuffer, draws its own background, asks swell to draw the sea with the
 * application's camera matrices, then floats a buoy on the sea where swell's CPU query says
 * the water is, depth-tested against the sea swell drew. The buoy is drawn once more into
 * swell's reflection pass, so the sea reflects it, and once more into its shadow pass, so it
 * shadows the sun on the sea; a boat passing by (not drawn) leaves its Kelvin wake, which the
 * buoy rides: its query names the wake.
 *
 *   cc buoy.c $(pkg-config --cflags --libs swell) -lm -o buoy && ./buoy [frame.ppm]
 *
 * Offscreen (EGL surfaceless, as a test or a batch renderer would run). It checks what it drew
 * and exits 1 if the sea, the buoy, its reflection, the wake or the application's own
 * background is missing, or if the draw left the GL state changed.
 */
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GLES2/gl2.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <swell.h>

#define W 320
#define H 180
#define PI 3.14159265358979323846

/* ---- the application's own GL: context, framebuffer, matrices, a buoy ---- */

static int make_context(EGLDisplay *dpy)
{
    PFNEGLGETPLATFORMDISPLAYEXTPROC get_display =
        (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
    if (!get_display)
        return 0;
    *dpy = get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
    if (*dpy == EGL_NO_DISPLAY || !eglInitialize(*dpy, NULL, NULL))
        return 0;
    static const EGLint cfg_attr[] = { EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE,
                                       EGL_OPENGL_ES2_BIT, EGL_NONE };
    static const EGLint ctx_attr[] = { EGL_CONTEXT_CLIENT_VERSION, 2, EGL_NONE };
    EGLConfig cfg;
    EGLint n = 0;
    eglBindAPI(EGL_OPENGL_ES_API);
    if (!eglChooseConfig(*dpy, cfg_attr, &cfg, 1, &n) || n < 1)
        return 0;
    EGLContext ctx = eglCreateContext(*dpy, cfg, EGL_NO_CONTEXT, ctx_attr);
    return ctx != EGL_NO_CONTEXT && eglMakeCurrent(*dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx);
}

static void make_framebuffer(void)
{
    GLuint fbo, colour, depth;
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glGenRenderbuffers(1, &colour);
    glBindRenderbuffer(GL_RENDERBUFFER, colour);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA4, W, H);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour);
    glGenRenderbuffers(1, &depth);
    glBindRenderbuffer(GL_RENDERBUFFER, depth);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT16, W, H);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth);
}

/* Column-major world-to-eye rotation looking from eye towards at (z up), and a perspective. */
static void look_at(const double eye[3], const double at[3], float m[16])
{
    double f[3] = { at[0] - eye[0], at[1] - eye[1], at[2] - eye[2] }, s[3], u[3];
    double fl = sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
    for (int i = 0; i < 3; i++)
        f[i] /= fl;
    s[0] = f[1]; s[1] = -f[0]; s[2] = 0.0;              /* f x z: level */
    double sl = sqrt(s[0] * s[0] + s[1] * s[1]);
    s[0] /= sl; s[1] /= sl;
    u[0] = s[1] * f[2] - s[2] * f[1]; u[1] = s[2] * f[0] - s[0] * f[2];
    u[2] = s[0] * f[1] - s[1] * f[0];
    float r[16] = { (float)s[0], (float)u[0], (float)-f[0], 0, (float)s[1], (float)u[1],
                    (float)-f[1], 0, (float)s[2], (float)u[2], (float)-f[2], 0, 0, 0, 0, 1 };
    memcpy(m, r, sizeof r);
}

static void perspective(double fov_y_deg, double aspect, double n, double f, float m[16])
{
    double t = 1.0 / tan(fov_y_deg * PI / 360.0);
    memset(m, 0, 16 * sizeof *m);
    m[0] = (float)(t / aspect);
    m[5] = (float)t;
    m[10] = (float)((f + n) / (n - f));
    m[11] = -1.0f;
    m[14] = (float)(2.0 * f * n / (n - f));
}

static GLuint buoy_program(void)
{
    static const char *vs = "attribute vec3 a_pos; uniform mat4 mvp;\n"
                            "void main() { gl_Position = mvp * vec4(a_pos, 1.0); }\n";
    static const char *fs = "precision mediump float;\n"
                            "void main() { gl_FragColor = vec4(1.0, 0.85, 0.0, 1.0); }\n";
    GLuint p = glCreateProgram();
    const char *src[2] = { vs, fs };
    GLenum kind[2] = { GL_VERTEX_SHADER, GL_FRAGMENT_SHADER };
    for (int i = 0; i < 2; i++) {
        GLuint s = glCreateShader(kind[i]);
        glShaderSource(s, 1, &src[i], NULL);
        glCompileShader(s);
        glAttachShader(p, s);
    }
    glBindAttribLocation(p, 0, "a_pos");
    glLinkProgram(p);
    return p;
}

/* A buoy: an octahedron 2 m across around (x, y, z) relative to the eye. */
static void draw_buoy(GLuint prog, const float view[16], const float proj[16], const float c[3])
{
    const float r = 1.0f;
    float v[6][3] = { { r, 0, 0 }, { -r, 0, 0 }, { 0, r, 0 }, { 0, -r, 0 }, { 0, 0, r },
                      { 0, 0, -r } };
    static const unsigned short idx[24] = { 0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4,
                                            2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5 };
    for (int i = 0; i < 6; i++)
        for (int k = 0; k < 3; k++)
            v[i][k] += c[k];
    float mvp[16];
    for (int col = 0; col < 4; col++)
        for (int row = 0; row < 4; row++) {
            float s = 0.0f;
            for (int k = 0; k < 4; k++)
                s += proj[4 * k + row] * view[4 * col + k];
            mvp[4 * col + row] = s;
        }
    glUseProgram(prog);
    glUniformMatrix4fv(glGetUniformLocation(prog, "mvp"), 1, GL_FALSE, mvp);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, v);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    glDrawElements(GL_TRIANGLES, 24, GL_UNSIGNED_SHORT, idx);
}

static int fail(const char *what, const struct swell_err *err)
{
    fprintf(stderr, "buoy: %s%s%s\n", what, err ? ": " : "", err ? err->msg : "");
    return 1;
}

int main(int argc, char **argv)
{
    EGLDisplay dpy;
    struct swell_err err = { 0 };
    if (!make_context(&dpy))
        return fail("no EGL surfaceless GLES 2 context", NULL);
    make_framebuffer();

    /* the sea: a moderate sea baked in memory, its GPU side in this context */
    swell_sea_desc sd = { .preset = "moderate", .budget_bytes = 8u << 20 };
    swell_sea *sea = NULL;
    swell_ocean *ocean = NULL;
    if (swell_sea_bake(&sd, &sea, &err))
        return fail("baking the sea", &err);
    swell_ocean_desc od = { .quality = SWELL_QUALITY_LOW, .sun_elev_deg = 25.0f,
                            .sun_azim_deg = 150.0f, .reflections = 1, .shadows = 1,
                            .wakes = 1 };
    if (swell_ocean_create(sea, &od, &ocean, &err))
        return fail("creating the ocean", &err);

    /* a 12 m hull at 5 m/s sailing north 25 m past the buoy: the buoy rides its wake, the
     * query naming the wake as the ocean draws it */
    swell_wake wake = { .position_m = { 16.0, 27.0 }, .heading_deg = 90.0f, .speed_mps = 5.0f,
                        .hull_length_m = 12.0f };
    /* the camera, the application's: 4 m up, looking at the buoy 16 m ahead */
    double t = 3.0, eye[3] = { 0.0, 0.0, 4.0 }, xy[2] = { 16.0, 2.0 };
    swell_sample at, open;
    swell_sample_desc qd = { .min_wavelength_m = 1.2, .no_detile = 1, .wake = &wake };
    if (swell_sea_sample(sea, &qd, xy, 1, t, &at, &err))
        return fail("asking the sea's height", &err);
    qd.wake = NULL;
    if (swell_sea_sample(sea, &qd, xy, 1, t, &open, &err))
        return fail("asking the open sea's height", &err);
    double buoy[3] = { xy[0], xy[1], at.height_m };
    swell_view view = { .camera_pos = { eye[0], eye[1], eye[2] }, .viewport = { 0, 0, W, H },
                        .flags = 0 };  /* no clear, no sky: the application's background stays */
    look_at(eye, buoy, view.view);
    perspective(50.0, (double)W / H, 0.5, 5000.0, view.proj);

    /* the application's frame: its background, the sea, its buoy */
    glViewport(0, 0, W, H);
    glClearColor(0.2f, 0.4f, 0.8f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    GLuint prog = buoy_program();
    glUseProgram(prog);
    GLint before_prog = 0, before_vp[4], after_prog = 0, after_vp[4];
    glGetIntegerv(GL_CURRENT_PROGRAM, &before_prog);
    glGetIntegerv(GL_VIEWPORT, before_vp);
    GLboolean before_depth = glIsEnabled(GL_DEPTH_TEST);
    float rel[3] = { (float)(buoy[0] - eye[0]), (float)(buoy[1] - eye[1]),
                     (float)(buoy[2] - eye[2]) };
    /* the sea alone first, to compare with: the same draw with no reflection pass before it */
    static unsigned char px[W * H * 4], alone[W * H * 4];
    if (swell_ocean_draw(ocean, &view, t, &err))
        return fail("drawing the sea", &err);
    glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, alone);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    /* the hull's wake on the sea */
    if (swell_ocean_set_wake(ocean, &wake, &err))
        return fail("setting the wake", &err);
    /* the buoy's reflection: drawn with the pass's mirrored camera, into swell's target */
    swell_pass pass;
    swell_reflection_desc rd = { .object_distance_m = 16.0f };
    if (swell_ocean_begin_reflection(ocean, &view, &rd, &pass, &err))
        return fail("beginning the reflection pass", &err);
    float mrel[3] = { (float)(buoy[0] - pass.camera_pos[0]),
                      (float)(buoy[1] - pass.camera_pos[1]),
                      (float)(buoy[2] - pass.camera_pos[2]) };
    draw_buoy(prog, pass.view, pass.proj, mrel);
    glDisable(GL_DEPTH_TEST);
    if (swell_ocean_end_reflection(ocean, &err))
        return fail("ending the reflection pass", &err);
    /* its shadow: drawn with the sun's view, into swell's shadow map */
    if (swell_ocean_begin_shadow(ocean, &view, NULL, &pass, &err))
        return fail("beginning the shadow pass", &err);
    float srel[3] = { (float)(buoy[0] - pass.camera_pos[0]),
                      (float)(buoy[1] - pass.camera_pos[1]),
                      (float)(buoy[2] - pass.camera_pos[2]) };
    draw_buoy(prog, pass.view, pass.proj, srel);
    glDisable(GL_DEPTH_TEST);
    if (swell_ocean_end_shadow(ocean, &err))
        return fail("ending the shadow pass", &err);
    glUseProgram(prog);
    if (swell_ocean_draw(ocean, &view, t, &err))
        return fail("drawing the sea", &err);
    glGetIntegerv(GL_CURRENT_PROGRAM, &after_prog);
    glGetIntegerv(GL_VIEWPORT, after_vp);
    int state_kept = before_prog == after_prog && !memcmp(before_vp, after_vp, sizeof after_vp) &&
                     before_depth == glIsEnabled(GL_DEPTH_TEST);
    /* the buoy's reflection, before the buoy covers any of it: pixels yellower than the sea
     * drawn alone */
    glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, px);
    int reflection_px = 0, changed_px = 0;
    for (int i = 0; i < W * H; i++) {
        const unsigned char *p = px + 4 * i, *q = alone + 4 * i;
        int yellow = (p[0] + p[1] - 2 * p[2]) - (q[0] + q[1] - 2 * q[2]) > 40;
        reflection_px += yellow;
        /* the wake and the shadow: the sea changed otherwise */
        changed_px += !yellow && abs(p[0] - q[0]) + abs(p[1] - q[1]) + abs(p[2] - q[2]) > 12;
    }
    draw_buoy(prog, view.view, view.proj, rel);

    glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, px);
    int background = 0, sea_px = 0, buoy_px = 0;
    for (int i = 0; i < W * H; i++) {
        const unsigned char *p = px + 4 * i;
        if (abs(p[0] - 51) < 12 && abs(p[1] - 102) < 12 && abs(p[2] - 204) < 12)
            background++;
        else if (p[0] > 200 && p[1] > 170 && p[2] < 60)
            buoy_px++;
        else
            sea_px++;
    }
    if (argc > 1) {
        FILE *f = fopen(argv[1], "wb");
        if (f) {
            fprintf(f, "P6 %d %d 255\n", W, H);
            for (int y = H - 1; y >= 0; y--)
                for (int x = 0; x < W; x++)
                    fwrite(px + 4 * (y * W + x), 1, 3, f);
            fclose(f);
        }
    }
    printf("buoy: water at (%.1f, %.1f) is %.2f m high (%+.2f m of it the wake); %d sea, %d buoy, "
           "%d reflection, %d wake and shadow, %d background pixels; GL state %s\n", xy[0], xy[1],
           at.height_m, at.height_m - open.height_m, sea_px, buoy_px, reflection_px, changed_px,
           background, state_kept ? "kept" : "CHANGED");
    swell_ocean_destroy(ocean);
    swell_sea_destroy(sea);
    eglTerminate(dpy);
    int ok = sea_px > W * H / 4 && buoy_px > 20 && reflection_px > 10 && changed_px > 200 &&
             background > W * H / 10 && state_kept;
    return ok ? 0 : 1;
}
