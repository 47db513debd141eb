/* egl.h - the EGL both back-ends share (platform_surfaceless.c, platform_kms.c): a platform
 * display opened through EGL_EXT_platform_base and initialised, the GLES API bound, a GLES
 * context of a given version, making it current, the teardown, and the one format of an EGL
 * failure message.
 *
 * What differs stays with each back-end: the client extensions it needs and the advice when
 * they are missing; the config (offscreen: the first RGBA8888 pbuffer config of each GLES
 * version tried; KMS: a window config whose native visual is the GBM format, the smallest depth
 * from 16 up, like the offscreen FBO's); and the KMS window surface, which `struct egl` then
 * owns. Every message starts with the back-end's `who`, like the back-end's own messages.
 */
#ifndef SWELL_PLATFORM_EGL_H
#define SWELL_PLATFORM_EGL_H

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include "core/err.h"

struct egl {
    const char *who;        /* prefix of every message: "platform kms", "platform surfaceless" */
    EGLDisplay dpy;         /* EGL_NO_DISPLAY = none */
    EGLConfig config;       /* chosen by the back-end, before egl_try_context */
    EGLContext ctx;         /* EGL_NO_CONTEXT = none */
    EGLSurface surf;        /* EGL_NO_SURFACE = none: the offscreen context draws without one */
    EGLint major, minor;    /* EGL version, from eglInitialize */
};

/* One EGL platform's display. The back-end has checked the client extensions first; the
 * strings are its words in the messages. */
struct egl_display_desc {
    EGLenum platform;           /* EGL_PLATFORM_GBM_KHR, EGL_PLATFORM_SURFACELESS_MESA */
    const char *platform_name;  /* the same as text, for eglGetPlatformDisplayEXT's message */
    void *native;               /* the native display: a gbm_device *, or EGL_DEFAULT_DISPLAY */
    int no_entry_code;          /* eglGetPlatformDisplayEXT not loadable: this code ... */
    const char *no_entry_msg;   /* ... and this message */
    const char *init_what;      /* eglInitialize's failure: what failed ... */
    const char *init_hint;      /* ... and what to do, NULL = nothing to add */
};

/* Every handle "none"; egl_destroy accepts the result at any later stage. */
void egl_init(struct egl *e, const char *who);

/* "<who>: <what> failed (EGL error 0x....)[; <hint>]" with eglGetError(); returns SWELL_E_EGL. */
int egl_fail(const struct egl *e, struct swell_err *err, const char *what, const char *hint);

/* eglGetPlatformDisplayEXT + eglInitialize: sets e->dpy, e->major, e->minor. */
int egl_open_display(struct egl *e, const struct egl_display_desc *d, struct swell_err *err);

/* eglBindAPI(EGL_OPENGL_ES_API). */
int egl_bind_gles(struct egl *e, struct swell_err *err);

/* A GLES `major` context on e->config: 1 when made (e->ctx set), else 0 with EGL's error left
 * for the caller's message (it tries the next version first). */
int egl_try_context(struct egl *e, int major);

/* e->ctx current on e->surf (draw and read), or on no surface. */
int egl_make_current(struct egl *e, struct swell_err *err);

/* Releases the context and destroys surface, context and display, in that order. */
void egl_destroy(struct egl *e);

#endif
