/* egl.c - the EGL both back-ends share (egl.h). */
#include "platform/egl.h"

#include <stddef.h>
#include <stdio.h>

void egl_init(struct egl *e, const char *who)
{
    e->who = who;
    e->dpy = EGL_NO_DISPLAY;
    e->config = NULL;
    e->ctx = EGL_NO_CONTEXT;
    e->surf = EGL_NO_SURFACE;
    e->major = 0;
    e->minor = 0;
}

int egl_fail(const struct egl *e, struct swell_err *err, const char *what, const char *hint)
{
    return swell_fail(err, SWELL_E_EGL, "%s: %s failed (EGL error 0x%04x)%s%s", e->who, what,
                      (unsigned)eglGetError(), hint ? "; " : "", hint ? hint : "");
}

int egl_open_display(struct egl *e, const struct egl_display_desc *d, struct swell_err *err)
{
    PFNEGLGETPLATFORMDISPLAYEXTPROC get_display =
        (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
    if (!get_display)
        return swell_fail(err, d->no_entry_code, "%s: %s", e->who, d->no_entry_msg);
    e->dpy = get_display(d->platform, d->native, NULL);
    if (e->dpy == EGL_NO_DISPLAY) {
        char what[96];
        snprintf(what, sizeof what, "eglGetPlatformDisplayEXT(%s)", d->platform_name);
        return egl_fail(e, err, what, NULL);
    }
    if (!eglInitialize(e->dpy, &e->major, &e->minor)) {
        int rc = egl_fail(e, err, d->init_what, d->init_hint);
        /* not initialised: nothing for egl_destroy to terminate */
        e->dpy = EGL_NO_DISPLAY;
        return rc;
    }
    return SWELL_OK;
}

int egl_bind_gles(struct egl *e, struct swell_err *err)
{
    if (!eglBindAPI(EGL_OPENGL_ES_API))
        return egl_fail(e, err, "eglBindAPI(EGL_OPENGL_ES_API)", NULL);
    return SWELL_OK;
}

int egl_try_context(struct egl *e, int major)
{
    const EGLint ctx_attrs[] = { EGL_CONTEXT_CLIENT_VERSION, major, EGL_NONE };
    e->ctx = eglCreateContext(e->dpy, e->config, EGL_NO_CONTEXT, ctx_attrs);
    return e->ctx != EGL_NO_CONTEXT;
}

int egl_make_current(struct egl *e, struct swell_err *err)
{
    if (!eglMakeCurrent(e->dpy, e->surf, e->surf, e->ctx))
        return egl_fail(e, err, e->surf == EGL_NO_SURFACE ? "eglMakeCurrent(EGL_NO_SURFACE)"
                                                          : "eglMakeCurrent", NULL);
    return SWELL_OK;
}

void egl_destroy(struct egl *e)
{
    if (e->dpy != EGL_NO_DISPLAY) {
        eglMakeCurrent(e->dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (e->surf != EGL_NO_SURFACE)
            eglDestroySurface(e->dpy, e->surf);
        if (e->ctx != EGL_NO_CONTEXT)
            eglDestroyContext(e->dpy, e->ctx);
        eglTerminate(e->dpy);
    }
    egl_init(e, e->who);
}
