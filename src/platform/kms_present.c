/* kms_present.c - putting a frame on the KMS display (kms_internal.h): two strategies behind
 * `struct kms_present_ops`, atomic (one commit names connector, CRTC, mode blob and primary
 * plane; DRM_MODE_ATOMIC_NONBLOCK flips) and legacy (drmModeSetCrtc, drmModePageFlip), chosen
 * once by kms_setup_api(); the DRM framebuffer of each gbm_bo, made the first time the bo is
 * seen and removed with it; and the wait for the page-flip event.
 *
 * Every flip raises an event and kms_wait_flip() sleeps in poll() until it arrives (no fences:
 * kms_swrast has no EGL_ANDROID_native_fence_sync). Only then may the buffer shown before be
 * given back to GBM (platform_kms.c, present).
 */
#include "platform/kms_internal.h"

#include <errno.h>
#include <poll.h>
#include <stdlib.h>
#include <string.h>

#include <drm_fourcc.h>
#include <gbm.h>
#include <xf86drm.h>
#include <xf86drmMode.h>

#define FLIP_TIMEOUT_MS 2000   /* a flip event later than this means the display is stuck */

/* The property names of kms_internal.h's enums, in their order. */
static const char *const conn_prop_names[CONN_PROP_COUNT] = { "CRTC_ID" };
static const char *const crtc_prop_names[CRTC_PROP_COUNT] = { "MODE_ID", "ACTIVE" };
static const char *const plane_prop_names[PLANE_PROP_COUNT] = {
    "FB_ID", "CRTC_ID", "SRC_X", "SRC_Y", "SRC_W", "SRC_H", "CRTC_X", "CRTC_Y", "CRTC_W", "CRTC_H"
};

/* One per gbm_bo, owned by the bo (gbm_bo_set_user_data); freed by its destroy callback. */
struct kms_fb {
    int fd;
    uint32_t fb_id;
};

/* ---- presentation: atomic ------------------------------------------------------------------ */

static int atomic_commit(struct platform *p, uint32_t fb, uint32_t flags, int full,
                         struct swell_err *err)
{
    drmModeAtomicReq *req = drmModeAtomicAlloc();
    if (!req)
        return swell_fail(err, SWELL_E_NOMEM, "platform kms: drmModeAtomicAlloc failed");
    int ok = 1;
    if (full) {
        ok &= drmModeAtomicAddProperty(req, p->conn_id, p->conn_props[CONN_CRTC_ID],
                                       p->crtc_id) >= 0;
        ok &= drmModeAtomicAddProperty(req, p->crtc_id, p->crtc_props[CRTC_MODE_ID],
                                       p->mode_blob) >= 0;
        ok &= drmModeAtomicAddProperty(req, p->crtc_id, p->crtc_props[CRTC_ACTIVE], 1) >= 0;
        const uint32_t *pp = p->plane_props;
        uint32_t pl = p->plane_id;
        ok &= drmModeAtomicAddProperty(req, pl, pp[PLANE_CRTC_ID], p->crtc_id) >= 0;
        ok &= drmModeAtomicAddProperty(req, pl, pp[PLANE_SRC_X], 0) >= 0;
        ok &= drmModeAtomicAddProperty(req, pl, pp[PLANE_SRC_Y], 0) >= 0;
        /* SRC_* are 16.16 fixed point */
        ok &= drmModeAtomicAddProperty(req, pl, pp[PLANE_SRC_W],
                                       (uint64_t)p->mode.hdisplay << 16) >= 0;
        ok &= drmModeAtomicAddProperty(req, pl, pp[PLANE_SRC_H],
                                       (uint64_t)p->mode.vdisplay << 16) >= 0;
        ok &= drmModeAtomicAddProperty(req, pl, pp[PLANE_CRTC_X], 0) >= 0;
        ok &= drmModeAtomicAddProperty(req, pl, pp[PLANE_CRTC_Y], 0) >= 0;
        ok &= drmModeAtomicAddProperty(req, pl, pp[PLANE_CRTC_W], p->mode.hdisplay) >= 0;
        ok &= drmModeAtomicAddProperty(req, pl, pp[PLANE_CRTC_H], p->mode.vdisplay) >= 0;
    }
    ok &= drmModeAtomicAddProperty(req, p->plane_id, p->plane_props[PLANE_FB_ID], fb) >= 0;
    if (!ok) {
        drmModeAtomicFree(req);
        return swell_fail(err, SWELL_E_NOMEM, "platform kms: building the atomic request failed");
    }
    int rc = drmModeAtomicCommit(p->fd, req, flags, p);
    int e = errno;
    drmModeAtomicFree(req);
    if (rc)
        return swell_fail(err, SWELL_E_DRM, "platform kms: atomic %s on %s (CRTC %u, plane %u, "
                          "fb %u) failed: %s%s%s", full ? "modeset" : "flip", p->device,
                          p->crtc_id, p->plane_id, fb, strerror(e),
                          (e == EACCES || e == EPERM) ? "; " : "; retry with --kms-api legacy, or "
                          "boot with drm.debug=0x1e to see why the kernel refused",
                          (e == EACCES || e == EPERM) ? NO_HINT_MASTER : "");
    return SWELL_OK;
}

static int atomic_modeset(struct platform *p, uint32_t fb, struct swell_err *err)
{
    return atomic_commit(p, fb, DRM_MODE_ATOMIC_ALLOW_MODESET, 1, err);
}

static int atomic_flip(struct platform *p, uint32_t fb, struct swell_err *err)
{
    return atomic_commit(p, fb, DRM_MODE_ATOMIC_NONBLOCK | DRM_MODE_PAGE_FLIP_EVENT, 0, err);
}

static const struct kms_present_ops atomic_ops = { "atomic", atomic_modeset, atomic_flip };

/* ---- presentation: legacy ------------------------------------------------------------------ */

static int legacy_modeset(struct platform *p, uint32_t fb, struct swell_err *err)
{
    if (drmModeSetCrtc(p->fd, p->crtc_id, fb, 0, 0, &p->conn_id, 1, &p->mode)) {
        int e = errno;
        return swell_fail(err, SWELL_E_DRM, "platform kms: drmModeSetCrtc(%s, CRTC %u, %ux%u) "
                          "failed: %s%s%s", p->device, p->crtc_id, p->mode.hdisplay,
                          p->mode.vdisplay, strerror(e), (e == EACCES || e == EPERM) ? "; " : "",
                          (e == EACCES || e == EPERM) ? NO_HINT_MASTER : "");
    }
    return SWELL_OK;
}

static int legacy_flip(struct platform *p, uint32_t fb, struct swell_err *err)
{
    if (drmModePageFlip(p->fd, p->crtc_id, fb, DRM_MODE_PAGE_FLIP_EVENT, p))
        return swell_fail(err, SWELL_E_DRM, "platform kms: drmModePageFlip(%s, CRTC %u, fb %u) "
                          "failed: %s", p->device, p->crtc_id, fb, strerror(errno));
    return SWELL_OK;
}

static const struct kms_present_ops legacy_ops = { "legacy", legacy_modeset, legacy_flip };

/* ---- choosing one -------------------------------------------------------------------------- */

int kms_setup_api(struct platform *p, int api, struct swell_err *err)
{
    int atomic_ok = api != KMS_API_LEGACY &&
                    drmSetClientCap(p->fd, DRM_CLIENT_CAP_UNIVERSAL_PLANES, 1) == 0 &&
                    drmSetClientCap(p->fd, DRM_CLIENT_CAP_ATOMIC, 1) == 0;
    if (!atomic_ok) {
        if (api == KMS_API_ATOMIC)
            return swell_fail(err, SWELL_E_DRM, "platform kms: %s does not support atomic "
                              "modesetting (DRM_CLIENT_CAP_ATOMIC refused); use --kms-api legacy",
                              p->device);
        p->ops = &legacy_ops;
        return SWELL_OK;
    }
    int rc = kms_pick_plane(p, err);
    if (!rc)
        rc = kms_find_props(p->fd, p->conn_id, DRM_MODE_OBJECT_CONNECTOR, conn_prop_names,
                            CONN_PROP_COUNT, p->conn_props, "connector", err);
    if (!rc)
        rc = kms_find_props(p->fd, p->crtc_id, DRM_MODE_OBJECT_CRTC, crtc_prop_names,
                            CRTC_PROP_COUNT, p->crtc_props, "CRTC", err);
    if (!rc)
        rc = kms_find_props(p->fd, p->plane_id, DRM_MODE_OBJECT_PLANE, plane_prop_names,
                            PLANE_PROP_COUNT, p->plane_props, "plane", err);
    if (!rc && drmModeCreatePropertyBlob(p->fd, &p->mode, sizeof p->mode, &p->mode_blob))
        rc = swell_fail(err, SWELL_E_DRM, "platform kms: mode blob: %s", strerror(errno));
    if (rc && api == KMS_API_AUTO) {
        /* Atomic is incomplete here: the legacy path needs none of it. */
        swell_err_clear(err);
        drmSetClientCap(p->fd, DRM_CLIENT_CAP_ATOMIC, 0);
        p->ops = &legacy_ops;
        return SWELL_OK;
    }
    if (rc)
        return rc;
    p->ops = &atomic_ops;
    return SWELL_OK;
}

/* ---- framebuffers per gbm_bo --------------------------------------------------------------- */

static void fb_destroy_cb(struct gbm_bo *bo, void *data)
{
    (void)bo;
    struct kms_fb *f = data;
    if (f->fb_id)
        drmModeRmFB(f->fd, f->fb_id);
    free(f);
}

int kms_fb_for_bo(struct platform *p, struct gbm_bo *bo, uint32_t *fb_id, struct swell_err *err)
{
    struct kms_fb *f = gbm_bo_get_user_data(bo);
    if (f) {
        *fb_id = f->fb_id;
        return SWELL_OK;
    }
    uint32_t handles[4] = { 0 }, strides[4] = { 0 }, offsets[4] = { 0 };
    uint64_t mods[4] = { 0 };
    uint64_t mod = gbm_bo_get_modifier(bo);
    int planes = gbm_bo_get_plane_count(bo);
    for (int i = 0; i < planes && i < 4; i++) {
        handles[i] = gbm_bo_get_handle_for_plane(bo, i).u32;
        strides[i] = gbm_bo_get_stride_for_plane(bo, i);
        offsets[i] = gbm_bo_get_offset(bo, i);
        mods[i] = mod;
    }
    uint32_t w = gbm_bo_get_width(bo), h = gbm_bo_get_height(bo);
    uint32_t fmt = gbm_bo_get_format(bo);
    uint64_t cap = 0;
    int rc;
    /* kms_swrast reports DRM_FORMAT_MOD_INVALID: passing it with DRM_MODE_FB_MODIFIERS makes the
     * modeset fail with EINVAL (notes/kms-vm.md), so the plain call is used then. */
    if (mod != DRM_FORMAT_MOD_INVALID && drmGetCap(p->fd, DRM_CAP_ADDFB2_MODIFIERS, &cap) == 0 &&
        cap)
        rc = drmModeAddFB2WithModifiers(p->fd, w, h, fmt, handles, strides, offsets, mods, fb_id,
                                        DRM_MODE_FB_MODIFIERS);
    else
        rc = drmModeAddFB2(p->fd, w, h, fmt, handles, strides, offsets, fb_id, 0);
    if (rc)
        return swell_fail(err, SWELL_E_DRM, "platform kms: drmModeAddFB2 (%ux%u, format 0x%08x, "
                          "modifier 0x%llx) on %s failed: %s", w, h, fmt,
                          (unsigned long long)mod, p->device, strerror(errno));
    f = malloc(sizeof *f);
    if (!f) {
        drmModeRmFB(p->fd, *fb_id);
        return swell_fail(err, SWELL_E_NOMEM, "platform kms: framebuffer record");
    }
    f->fd = p->fd;
    f->fb_id = *fb_id;
    gbm_bo_set_user_data(bo, f, fb_destroy_cb);
    return SWELL_OK;
}

/* ---- events -------------------------------------------------------------------------------- */

static void on_flip(int fd, unsigned seq, unsigned sec, unsigned usec, void *data)
{
    (void)fd; (void)seq; (void)sec; (void)usec;
    struct platform *p = data;
    p->flip_pending = 0;
}

static void on_flip2(int fd, unsigned seq, unsigned sec, unsigned usec, unsigned crtc, void *data)
{
    (void)crtc;
    on_flip(fd, seq, sec, usec, data);
}

/* Sleep in poll() until the pending flip completes. A signal interrupts the sleep but not the
 * wait: the flip is still queued in the kernel and must finish before its buffers are reused. */
int kms_wait_flip(struct platform *p, struct swell_err *err)
{
    drmEventContext ev = { 0 };
    ev.version = 3;
    ev.page_flip_handler = on_flip;
    ev.page_flip_handler2 = on_flip2;
    while (p->flip_pending) {
        struct pollfd pfd = { .fd = p->fd, .events = POLLIN };
        int n = poll(&pfd, 1, FLIP_TIMEOUT_MS);
        if (n < 0 && errno == EINTR)
            continue;
        if (n < 0)
            return swell_fail(err, SWELL_E_DRM, "platform kms: poll on %s: %s", p->device,
                              strerror(errno));
        if (n == 0)
            return swell_fail(err, SWELL_E_DRM, "platform kms: no page-flip event from %s within "
                              "%d ms: the display is not scanning out (CRTC off? VT switched "
                              "away?)", p->device, FLIP_TIMEOUT_MS);
        if (drmHandleEvent(p->fd, &ev))
            return swell_fail(err, SWELL_E_DRM, "platform kms: drmHandleEvent on %s: %s",
                              p->device, strerror(errno));
    }
    return SWELL_OK;
}
