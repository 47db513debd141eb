/* platform_kms.c - fullscreen back-end on a Linux KMS display with no window system:
 * libdrm (device, connector, CRTC, mode, page flips) + GBM (scan-out buffers) + EGL (GLES context
 * on a GBM surface).
 *
 * Ownership split (STYLE.md, after kmscube), one file each (kms_internal.h lists them):
 * kms_device.c's kms_pick_* choose device/connector/CRTC/mode; setup_gbm_egl (here) sets up
 * rendering, with the EGL steps both back-ends share in egl.c; two presentation strategies,
 * atomic and legacy, behind `struct kms_present_ops` in kms_present.c.
 * Frames: present() swaps, locks the new front buffer, looks up (or creates once) its DRM
 * framebuffer through gbm_bo user data, commits it (the first frame with a modeset), then sleeps
 * in poll() on the DRM fd until the flip-complete event arrives (vblank pacing, no busy wait, no
 * fences: kms_swrast has no EGL_ANDROID_native_fence_sync). Only then is the previous buffer
 * released to GBM, so at most two buffers are in use and the frame loop allocates nothing once
 * every buffer of the surface has been seen.
 *
 * Lifecycle: the CRTC state found at start (fb, position, mode, connector) is saved and put back
 * by destroy(); master is dropped last, before the fd closes. Teardown runs in exact reverse
 * order: CRTC restore, EGL surface/context/display, GBM surface (its buffers' framebuffers are
 * removed by the user-data destroy callback while the fd is still open), GBM device, fd.
 *
 * Signals: create() installs SIGINT/SIGTERM handlers that only set `quit_requested`, which
 * should_quit() reads; destroy() puts the previous handlers back. That flag is the one
 * file-static mutable object in the back-end: a signal handler receives no user pointer, so
 * it cannot live in `struct platform`. A volatile sig_atomic_t is the only type the handler may
 * write portably.
 *
 * read_rgba() (kms_capture.c) returns what the display scans out, not a copy of the GL back
 * buffer.
 */
#include "platform/kms_internal.h"
#include "core/parse.h"

#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <gbm.h>
#include <xf86drm.h>
#include <xf86drmMode.h>

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GLES2/gl2.h>

/* See the file comment: written only by the handler, read by should_quit(). */
static volatile sig_atomic_t quit_requested;

static void on_quit_signal(int sig)
{
    (void)sig;
    quit_requested = 1;
}

/* ---- EGL on GBM ---------------------------------------------------------------------------- */

/* A window config whose native visual is XRGB8888 (the GBM surface format), depth 16 like the
 * surfaceless FBO so both platforms rasterise the same frame identically. */
static int choose_config(struct platform *p, struct swell_err *err)
{
    static const EGLint attrs[] = {
        EGL_SURFACE_TYPE, EGL_WINDOW_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_ES2_BIT,
        EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8, EGL_ALPHA_SIZE, 0,
        EGL_DEPTH_SIZE, 16, EGL_NONE
    };
    EGLint n = 0;
    if (!eglChooseConfig(p->egl.dpy, attrs, NULL, 0, &n) || n <= 0)
        return egl_fail(&p->egl, err, "eglChooseConfig (RGB888, depth >= 16, GLES2, window)",
                        NULL);
    EGLConfig *cfgs = malloc((size_t)n * sizeof *cfgs);
    if (!cfgs)
        return swell_fail(err, SWELL_E_NOMEM, "platform kms: EGL config list");
    eglChooseConfig(p->egl.dpy, attrs, cfgs, n, &n);
    int best_depth = 0;
    for (EGLint i = 0; i < n; i++) {
        EGLint vid = 0, depth = 0, r = 0, g = 0, b = 0;
        eglGetConfigAttrib(p->egl.dpy, cfgs[i], EGL_NATIVE_VISUAL_ID, &vid);
        eglGetConfigAttrib(p->egl.dpy, cfgs[i], EGL_DEPTH_SIZE, &depth);
        eglGetConfigAttrib(p->egl.dpy, cfgs[i], EGL_RED_SIZE, &r);
        eglGetConfigAttrib(p->egl.dpy, cfgs[i], EGL_GREEN_SIZE, &g);
        eglGetConfigAttrib(p->egl.dpy, cfgs[i], EGL_BLUE_SIZE, &b);
        if ((uint32_t)vid != GBM_FORMAT_XRGB8888 || r != 8 || g != 8 || b != 8)
            continue;
        if (!best_depth || (depth >= 16 && (best_depth < 16 || depth < best_depth))) {
            p->egl.config = cfgs[i];
            best_depth = depth;
        }
    }
    free(cfgs);
    if (!best_depth)
        return swell_fail(err, SWELL_E_EGL, "platform kms: none of %d EGL configs has native "
                          "visual XRGB8888 with 8-bit RGB", (int)n);
    return SWELL_OK;
}

static int setup_gbm_egl(struct platform *p, int gles_major, struct swell_err *err)
{
    p->gbm = gbm_create_device(p->fd);
    if (!p->gbm)
        return swell_fail(err, SWELL_E_DRM, "platform kms: gbm_create_device(%s) failed: %s "
                          "(is the Mesa GBM driver installed? libgbm1 libgl1-mesa-dri)",
                          p->device, strerror(errno));
    p->gs = gbm_surface_create(p->gbm, p->mode.hdisplay, p->mode.vdisplay, GBM_FORMAT_XRGB8888,
                               GBM_BO_USE_SCANOUT | GBM_BO_USE_RENDERING);
    if (!p->gs)
        return swell_fail(err, SWELL_E_DRM, "platform kms: gbm_surface_create(%ux%u XRGB8888, "
                          "scanout|rendering) failed: %s", p->mode.hdisplay, p->mode.vdisplay,
                          strerror(errno));

    const char *cext = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!parse_has_token(cext, "EGL_EXT_platform_base") ||
        !(parse_has_token(cext, "EGL_KHR_platform_gbm") || parse_has_token(cext, "EGL_MESA_platform_gbm")))
        return swell_fail(err, SWELL_E_EGL, "platform kms: EGL lacks EGL_EXT_platform_base + "
                          "EGL_KHR_platform_gbm (client extensions: %s)", cext ? cext : "none");
    const struct egl_display_desc dd = {
        .platform = EGL_PLATFORM_GBM_KHR,
        .platform_name = "EGL_PLATFORM_GBM_KHR",
        .native = p->gbm,
        .no_entry_code = SWELL_E_EGL,
        .no_entry_msg = "eglGetPlatformDisplayEXT not found",
        .init_what = "eglInitialize on the GBM display",
    };
    struct egl *e = &p->egl;
    int rc = egl_open_display(e, &dd, err);
    if (!rc)
        rc = egl_bind_gles(e, err);
    if (!rc)
        rc = choose_config(p, err);
    if (rc)
        return rc;
    /* GLES 3 when asked for, else (or when refused) GLES 2. */
    int v = gles_major >= 3 ? 3 : 2;
    while (v >= 2 && !egl_try_context(e, v))
        v--;
    if (e->ctx == EGL_NO_CONTEXT)
        return egl_fail(e, err, "eglCreateContext (GLES 2)", NULL);
    /* egl_destroy() destroys it with the context */
    e->surf = eglCreateWindowSurface(e->dpy, e->config, (EGLNativeWindowType)p->gs, NULL);
    if (e->surf == EGL_NO_SURFACE)
        return egl_fail(e, err, "eglCreateWindowSurface on the GBM surface", NULL);
    rc = egl_make_current(e, err);
    if (rc)
        return rc;
    if (p->verbose) {
        EGLint depth = 0;
        eglGetConfigAttrib(e->dpy, e->config, EGL_DEPTH_SIZE, &depth);
        fprintf(stderr, "platform kms: EGL %d.%d, XRGB8888 + depth %d, %s / %s\n", e->major,
                e->minor, depth, (const char *)glGetString(GL_VERSION),
                (const char *)glGetString(GL_RENDERER));
    }
    return SWELL_OK;
}

/* ---- create / destroy ---------------------------------------------------------------------- */

static void kms_destroy(struct platform *p)
{
    if (!p)
        return;
    if (p->fd >= 0 && p->flip_pending) {
        struct swell_err ignored;
        kms_wait_flip(p, &ignored);
    }
    /* Put the display back as found, before the framebuffers we showed disappear. */
    if (p->fd >= 0 && p->lit && p->saved_crtc) {
        drmModeCrtc *s = p->saved_crtc;
        if (s->buffer_id && s->mode_valid)
            drmModeSetCrtc(p->fd, s->crtc_id, s->buffer_id, s->x, s->y, &p->conn_id, 1, &s->mode);
        else
            drmModeSetCrtc(p->fd, s->crtc_id, 0, 0, 0, NULL, 0, NULL);
    }
    if (p->gs && p->front)
        gbm_surface_release_buffer(p->gs, p->front);
    p->front = NULL;
    egl_destroy(&p->egl);
    if (p->gs)
        gbm_surface_destroy(p->gs);
    if (p->gbm)
        gbm_device_destroy(p->gbm);
    if (p->fd >= 0 && p->mode_blob)
        drmModeDestroyPropertyBlob(p->fd, p->mode_blob);
    if (p->saved_crtc)
        drmModeFreeCrtc(p->saved_crtc);
    if (p->fd >= 0) {
        drmDropMaster(p->fd);
        close(p->fd);
    }
    if (p->signals_installed) {
        sigaction(SIGINT, &p->old_int, NULL);
        sigaction(SIGTERM, &p->old_term, NULL);
    }
    free(p);
}

static int kms_create(const struct platform_desc *d, struct platform **out, struct swell_err *err)
{
    *out = NULL;
    if (d->kms_api < 0 || d->kms_api >= KMS_API_COUNT)
        return swell_fail(err, SWELL_E_ARG, "platform kms: kms_api %d is not auto/atomic/legacy",
                          d->kms_api);
    struct platform *p = calloc(1, sizeof *p);
    if (!p)
        return swell_fail(err, SWELL_E_NOMEM, "platform kms: state");
    p->fd = -1;
    egl_init(&p->egl, "platform kms");
    p->verbose = d->verbose;
    drmModeConnector *conn = NULL;
    int rc = kms_pick_device(p, d, &conn, err);
    if (rc)
        goto fail;
    p->conn_id = conn->connector_id;
    rc = kms_pick_crtc(p, conn, err);
    if (!rc)
        rc = kms_pick_mode(p, conn, d, err);
    char cname[64];
    kms_connector_name(conn, cname, sizeof cname);
    drmModeFreeConnector(conn);
    if (rc)
        goto fail;
    if (!drmIsMaster(p->fd) && drmSetMaster(p->fd)) {
        rc = swell_fail(err, SWELL_E_DRM, "platform kms: cannot become DRM master on %s (%s): "
                        "another program drives the display; %s", p->device, strerror(errno),
                        NO_HINT_MASTER);
        goto fail;
    }
    p->saved_crtc = drmModeGetCrtc(p->fd, p->crtc_id);
    if (!p->saved_crtc) {
        rc = swell_fail(err, SWELL_E_DRM, "platform kms: reading CRTC %u of %s: %s", p->crtc_id,
                        p->device, strerror(errno));
        goto fail;
    }
    rc = kms_setup_api(p, d->kms_api, err);
    if (rc)
        goto fail;
    rc = setup_gbm_egl(p, d->gles_major, err);
    if (rc)
        goto fail;
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_quit_signal;
    sigemptyset(&sa.sa_mask);
    quit_requested = 0;
    sigaction(SIGINT, &sa, &p->old_int);
    sigaction(SIGTERM, &sa, &p->old_term);
    p->signals_installed = 1;
    if (p->verbose)
        fprintf(stderr, "platform kms: %s, connector %s, CRTC %u, mode %ux%u@%d, %s page flips\n",
                p->device, cname, p->crtc_id, p->mode.hdisplay, p->mode.vdisplay,
                kms_mode_hz(&p->mode), p->ops->name);
    *out = p;
    return SWELL_OK;
fail:
    kms_destroy(p);
    return rc;
}

/* ---- frame --------------------------------------------------------------------------------- */

static void kms_size(struct platform *p, int *w, int *h)
{
    *w = p->mode.hdisplay;
    *h = p->mode.vdisplay;
}

static int kms_begin_frame(struct platform *p, struct swell_err *err)
{
    if (eglGetCurrentContext() != p->egl.ctx) {
        int rc = egl_make_current(&p->egl, err);
        if (rc)
            return rc;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, p->mode.hdisplay, p->mode.vdisplay);
    return SWELL_OK;
}

static int kms_present(struct platform *p, struct swell_err *err)
{
    if (!eglSwapBuffers(p->egl.dpy, p->egl.surf))
        return egl_fail(&p->egl, err, "eglSwapBuffers", NULL);
    struct gbm_bo *bo = gbm_surface_lock_front_buffer(p->gs);
    if (!bo)
        return swell_fail(err, SWELL_E_DRM, "platform kms: gbm_surface_lock_front_buffer failed");
    uint32_t fb = 0;
    int rc = kms_fb_for_bo(p, bo, &fb, err);
    if (!rc && !p->lit) {
        rc = p->ops->modeset(p, fb, err);
        if (!rc)
            p->lit = 1;
    } else if (!rc) {
        rc = p->ops->flip(p, fb, err);
        if (!rc) {
            p->flip_pending = 1;
            rc = kms_wait_flip(p, err);
        }
    }
    if (rc) {
        if (!p->flip_pending)
            gbm_surface_release_buffer(p->gs, bo);
        return rc;
    }
    if (p->front)
        gbm_surface_release_buffer(p->gs, p->front);
    p->front = bo;
    return SWELL_OK;
}

static int kms_should_quit(struct platform *p)
{
    (void)p;
    return quit_requested != 0;
}

const struct platform_backend platform_kms_backend = {
    .name = "kms",
    .create = kms_create,
    .size = kms_size,
    .begin_frame = kms_begin_frame,
    .present = kms_present,
    .read_rgba = kms_read_rgba,
    .should_quit = kms_should_quit,
    .destroy = kms_destroy,
};
