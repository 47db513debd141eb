/* platform_kms.c - fullscreen back-end on a Linux KMS display with no window system:
 * libdrm (device, connector, CRTC, mode, page flips) + GBM (scan-out buffers) + EGL (GLES context
 * on a GBM surface).
 *
 * Ownership split (STYLE.md, after kmscube): pick_* choose device/connector/CRTC/mode; gbm_egl_*
 * set up rendering; two presentation strategies, atomic and legacy, behind
 * `struct kms_present_ops`.
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
 * read_rgba(): returns what the display scans out, not a copy of the GL back buffer. It asks the
 * kernel which framebuffer the CRTC shows now (drmModeGetCrtc -> drmModeGetFB2), maps that buffer
 * (DRM_IOCTL_MODE_MAP_DUMB; GBM's own mapping of the front buffer when the buffer is not a dumb
 * buffer) and converts XRGB8888 to RGBA8, top row first. Since present() returns only after the
 * flip completed, that is the frame just presented.
 */
#include "platform/platform.h"
#include "core/parse.h"

#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>

#include <drm_fourcc.h>
#include <gbm.h>
#include <xf86drm.h>
#include <xf86drmMode.h>

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GLES2/gl2.h>

#define MAX_DRM_DEVICES 16
#define FLIP_TIMEOUT_MS 2000   /* a flip event later than this means the display is stuck */
#define NO_HINT_MASTER "run it from a text console (VT) or as root, and stop the display manager " \
                       "(e.g. systemctl stop gdm) so that nothing else holds DRM master"

/* See the file comment: written only by the handler, read by should_quit(). */
static volatile sig_atomic_t quit_requested;

static void on_quit_signal(int sig)
{
    (void)sig;
    quit_requested = 1;
}

/* Atomic properties looked up by name once at start. */
enum conn_prop { CONN_CRTC_ID, CONN_PROP_COUNT };
enum crtc_prop { CRTC_MODE_ID, CRTC_ACTIVE, CRTC_PROP_COUNT };
enum plane_prop {
    PLANE_FB_ID, PLANE_CRTC_ID, PLANE_SRC_X, PLANE_SRC_Y, PLANE_SRC_W, PLANE_SRC_H,
    PLANE_CRTC_X, PLANE_CRTC_Y, PLANE_CRTC_W, PLANE_CRTC_H, PLANE_PROP_COUNT
};
static const char *const conn_prop_names[CONN_PROP_COUNT] = { "CRTC_ID" };
static const char *const crtc_prop_names[CRTC_PROP_COUNT] = { "MODE_ID", "ACTIVE" };
static const char *const plane_prop_names[PLANE_PROP_COUNT] = {
    "FB_ID", "CRTC_ID", "SRC_X", "SRC_Y", "SRC_W", "SRC_H", "CRTC_X", "CRTC_Y", "CRTC_W", "CRTC_H"
};

struct platform;

struct kms_present_ops {
    const char *name;
    /* first frame: light the CRTC with fb (blocking) */
    int (*modeset)(struct platform *p, uint32_t fb, struct swell_err *err);
    /* later frames: queue a flip to fb that raises a page-flip event */
    int (*flip)(struct platform *p, uint32_t fb, struct swell_err *err);
};

/* One per gbm_bo, owned by the bo (gbm_bo_set_user_data); freed by its destroy callback. */
struct kms_fb {
    int fd;
    uint32_t fb_id;
};

typedef EGLDisplay (*get_platform_display_fn)(EGLenum, void *, const EGLint *);

struct platform {
    int fd;                     /* -1 = none */
    int verbose;
    char device[256];
    uint32_t conn_id, crtc_id, plane_id;   /* 0 = none */
    int crtc_index;
    drmModeModeInfo mode;
    uint32_t mode_blob;         /* atomic MODE_ID blob, 0 = none */
    drmModeCrtc *saved_crtc;    /* state to restore; NULL = none saved */
    int lit;                    /* we changed the CRTC (so destroy restores it) */
    const struct kms_present_ops *ops;
    uint32_t conn_props[CONN_PROP_COUNT], crtc_props[CRTC_PROP_COUNT];
    uint32_t plane_props[PLANE_PROP_COUNT];

    struct gbm_device *gbm;
    struct gbm_surface *gs;
    struct gbm_bo *front;       /* shown now (flip completed), owned until the next flip */
    int flip_pending;

    EGLDisplay dpy;
    EGLConfig config;
    EGLContext ctx;
    EGLSurface surf;

    struct sigaction old_int, old_term;
    int signals_installed;
};

static const char *conn_status(drmModeConnection c)
{
    return c == DRM_MODE_CONNECTED ? "connected"
         : c == DRM_MODE_DISCONNECTED ? "disconnected" : "unknown";
}

static void connector_name(const drmModeConnector *c, char *buf, size_t n)
{
    const char *t = drmModeGetConnectorTypeName(c->connector_type);
    snprintf(buf, n, "%s-%u", t ? t : "Unknown", c->connector_type_id);
}

/* ---- device and connector ------------------------------------------------------------------ */

/* The connector to drive on fd: desc->connector by name, else the first connected one.
 * Returns it (caller frees) or NULL with `why` filled. */
static drmModeConnector *find_connector(int fd, const char *want, char *why, size_t why_n)
{
    drmModeRes *res = drmModeGetResources(fd);
    if (!res) {
        snprintf(why, why_n, "not a KMS device (drmModeGetResources: %s)", strerror(errno));
        return NULL;
    }
    drmModeConnector *found = NULL;
    size_t used = 0;
    why[0] = '\0';
    used += (size_t)snprintf(why, why_n, "connectors:");
    for (int i = 0; i < res->count_connectors && !found; i++) {
        drmModeConnector *c = drmModeGetConnector(fd, res->connectors[i]);
        if (!c)
            continue;
        char name[64];
        connector_name(c, name, sizeof name);
        if (used < why_n)
            used += (size_t)snprintf(why + used, why_n - used, " %s (%s)", name,
                                     conn_status(c->connection));
        int name_ok = !want || strcmp(want, name) == 0;
        if (name_ok && c->connection == DRM_MODE_CONNECTED && c->count_modes > 0)
            found = c;
        else
            drmModeFreeConnector(c);
    }
    if (!found && res->count_connectors == 0)
        snprintf(why, why_n, "no connectors");
    drmModeFreeResources(res);
    return found;
}

static int open_device(struct platform *p, const char *path, struct swell_err *err)
{
    p->fd = open(path, O_RDWR | O_CLOEXEC);
    if (p->fd < 0) {
        int e = errno;
        return swell_fail(err, SWELL_E_DRM, "platform kms: cannot open %s: %s%s%s", path,
                          strerror(e), (e == EACCES || e == EPERM) ? "; " : "",
                          (e == EACCES || e == EPERM) ? "add yourself to the 'video' group or "
                          NO_HINT_MASTER : "");
    }
    snprintf(p->device, sizeof p->device, "%s", path);
    return SWELL_OK;
}

/* desc->device, else the first primary node (/dev/dri/cardN) with a usable connector. */
static int pick_device(struct platform *p, const struct platform_desc *d,
                       drmModeConnector **conn, struct swell_err *err)
{
    char why[768];
    if (d->device) {
        int rc = open_device(p, d->device, err);
        if (rc)
            return rc;
        *conn = find_connector(p->fd, d->connector, why, sizeof why);
        if (!*conn)
            return swell_fail(err, SWELL_E_DRM, "platform kms: no connected connector%s%s%s "
                              "with modes on %s (%s); plug a display in or pick another "
                              "--connector", d->connector ? " named '" : "",
                              d->connector ? d->connector : "", d->connector ? "'" : "",
                              d->device, why);
        return SWELL_OK;
    }
    drmDevicePtr devs[MAX_DRM_DEVICES];
    int n = drmGetDevices2(0, devs, MAX_DRM_DEVICES);
    int primaries = 0;
    char tried[1024];
    size_t used = 0;
    tried[0] = '\0';
    for (int i = 0; i < (n > 0 ? n : 0) && p->fd < 0; i++) {
        if (!(devs[i]->available_nodes & (1 << DRM_NODE_PRIMARY)))
            continue;
        const char *path = devs[i]->nodes[DRM_NODE_PRIMARY];
        primaries++;
        int fd = open(path, O_RDWR | O_CLOEXEC);
        if (fd < 0) {
            if (used < sizeof tried)
                used += (size_t)snprintf(tried + used, sizeof tried - used, "%s%s: %s",
                                         used ? "; " : "", path, strerror(errno));
            continue;
        }
        drmModeConnector *c = find_connector(fd, d->connector, why, sizeof why);
        if (c) {
            p->fd = fd;
            snprintf(p->device, sizeof p->device, "%s", path);
            *conn = c;
        } else {
            close(fd);
            if (used < sizeof tried)
                used += (size_t)snprintf(tried + used, sizeof tried - used, "%s%s: %s",
                                         used ? "; " : "", path, why);
        }
    }
    if (n > 0)
        drmFreeDevices(devs, n);
    if (primaries == 0)
        return swell_fail(err, SWELL_E_UNSUPPORTED, "platform kms: no /dev/dri/card*: no KMS "
                          "display here; use --platform surfaceless");
    if (p->fd < 0)
        return swell_fail(err, SWELL_E_UNSUPPORTED, "platform kms: no connected connector%s%s%s "
                          "with modes on any DRM device (%s); connect a display, name one with "
                          "--connector, or use --platform surfaceless",
                          d->connector ? " named '" : "", d->connector ? d->connector : "",
                          d->connector ? "'" : "", tried);
    return SWELL_OK;
}

/* ---- CRTC, mode, plane --------------------------------------------------------------------- */

static int pick_crtc(struct platform *p, const drmModeConnector *c, struct swell_err *err)
{
    drmModeRes *res = drmModeGetResources(p->fd);
    if (!res)
        return swell_fail(err, SWELL_E_DRM, "platform kms: drmModeGetResources on %s: %s",
                          p->device, strerror(errno));
    uint32_t crtc = 0;
    /* Keep the CRTC the connector is already driven by: no other output loses its CRTC. */
    if (c->encoder_id) {
        drmModeEncoder *e = drmModeGetEncoder(p->fd, c->encoder_id);
        if (e) {
            crtc = e->crtc_id;
            drmModeFreeEncoder(e);
        }
    }
    for (int i = 0; i < c->count_encoders && !crtc; i++) {
        drmModeEncoder *e = drmModeGetEncoder(p->fd, c->encoders[i]);
        if (!e)
            continue;
        for (int j = 0; j < res->count_crtcs && !crtc; j++)
            if (e->possible_crtcs & (1u << j))
                crtc = res->crtcs[j];
        drmModeFreeEncoder(e);
    }
    p->crtc_index = -1;
    for (int j = 0; j < res->count_crtcs; j++)
        if (res->crtcs[j] == crtc)
            p->crtc_index = j;
    drmModeFreeResources(res);
    if (!crtc || p->crtc_index < 0)
        return swell_fail(err, SWELL_E_DRM, "platform kms: no CRTC can drive connector %u on %s "
                          "(all in use?)", c->connector_id, p->device);
    p->crtc_id = crtc;
    return SWELL_OK;
}

static int mode_hz(const drmModeModeInfo *m)
{
    if (m->vrefresh)
        return (int)m->vrefresh;
    if (!m->htotal || !m->vtotal)
        return 0;
    return (int)((m->clock * 1000.0) / ((double)m->htotal * m->vtotal) + 0.5);
}

/* Preferred mode by default; else exact WxH (@Hz when given, else the highest refresh), else the
 * mode nearest in size (sum of |dw| + |dh|, ties to the preferred/earlier one). */
static int pick_mode(struct platform *p, const drmModeConnector *c, const struct platform_desc *d,
                     struct swell_err *err)
{
    if (c->count_modes <= 0)
        return swell_fail(err, SWELL_E_DRM, "platform kms: connector %u reports no modes",
                          c->connector_id);
    int best = -1;
    if (d->mode_w <= 0 || d->mode_h <= 0) {
        for (int i = 0; i < c->count_modes && best < 0; i++)
            if (c->modes[i].type & DRM_MODE_TYPE_PREFERRED)
                best = i;
        if (best < 0)
            best = 0;
    } else {
        for (int i = 0; i < c->count_modes; i++) {
            const drmModeModeInfo *m = &c->modes[i];
            if (m->hdisplay != d->mode_w || m->vdisplay != d->mode_h)
                continue;
            if (d->mode_hz > 0 && mode_hz(m) != d->mode_hz)
                continue;
            if (best < 0 || mode_hz(m) > mode_hz(&c->modes[best]))
                best = i;
        }
        if (best < 0 && d->mode_hz > 0) {
            char list[700];
            size_t used = 0;
            list[0] = '\0';
            for (int i = 0; i < c->count_modes && used < sizeof list; i++)
                used += (size_t)snprintf(list + used, sizeof list - used, "%s%dx%d@%d",
                                         i ? " " : "", c->modes[i].hdisplay,
                                         c->modes[i].vdisplay, mode_hz(&c->modes[i]));
            return swell_fail(err, SWELL_E_DRM, "platform kms: mode %dx%d@%d is not available "
                              "on %s; available: %s", d->mode_w, d->mode_h, d->mode_hz,
                              p->device, list);
        }
        long best_d = -1;
        for (int i = 0; i < c->count_modes && best < 0; i++) {
            const drmModeModeInfo *m = &c->modes[i];
            long dist = labs((long)m->hdisplay - d->mode_w) + labs((long)m->vdisplay - d->mode_h);
            if (best_d < 0 || dist < best_d)
                best_d = dist;
        }
        for (int i = 0; i < c->count_modes && best < 0 && best_d >= 0; i++) {
            const drmModeModeInfo *m = &c->modes[i];
            if (labs((long)m->hdisplay - d->mode_w) + labs((long)m->vdisplay - d->mode_h) == best_d)
                best = i;
        }
    }
    p->mode = c->modes[best];
    return SWELL_OK;
}

static int find_props(int fd, uint32_t obj, uint32_t type, const char *const *names, int count,
                      uint32_t *ids, const char *what, struct swell_err *err)
{
    drmModeObjectProperties *props = drmModeObjectGetProperties(fd, obj, type);
    if (!props)
        return swell_fail(err, SWELL_E_DRM, "platform kms: properties of %s %u: %s", what, obj,
                          strerror(errno));
    for (int k = 0; k < count; k++)
        ids[k] = 0;
    for (uint32_t i = 0; i < props->count_props; i++) {
        drmModePropertyRes *pr = drmModeGetProperty(fd, props->props[i]);
        if (!pr)
            continue;
        for (int k = 0; k < count; k++)
            if (strcmp(pr->name, names[k]) == 0)
                ids[k] = pr->prop_id;
        drmModeFreeProperty(pr);
    }
    drmModeFreeObjectProperties(props);
    for (int k = 0; k < count; k++)
        if (!ids[k])
            return swell_fail(err, SWELL_E_DRM, "platform kms: %s %u has no '%s' property "
                              "(atomic modesetting incomplete); try --kms-api legacy", what, obj,
                              names[k]);
    return SWELL_OK;
}

static uint64_t prop_value(int fd, uint32_t obj, uint32_t type, const char *name, uint64_t none)
{
    drmModeObjectProperties *props = drmModeObjectGetProperties(fd, obj, type);
    uint64_t v = none;
    if (!props)
        return v;
    for (uint32_t i = 0; i < props->count_props; i++) {
        drmModePropertyRes *pr = drmModeGetProperty(fd, props->props[i]);
        if (!pr)
            continue;
        if (strcmp(pr->name, name) == 0)
            v = props->prop_values[i];
        drmModeFreeProperty(pr);
    }
    drmModeFreeObjectProperties(props);
    return v;
}

/* The primary plane that can sit on our CRTC (atomic needs it named explicitly). */
static int pick_plane(struct platform *p, struct swell_err *err)
{
    drmModePlaneRes *pres = drmModeGetPlaneResources(p->fd);
    if (!pres)
        return swell_fail(err, SWELL_E_DRM, "platform kms: drmModeGetPlaneResources: %s",
                          strerror(errno));
    for (uint32_t i = 0; i < pres->count_planes && !p->plane_id; i++) {
        drmModePlane *pl = drmModeGetPlane(p->fd, pres->planes[i]);
        if (!pl)
            continue;
        if ((pl->possible_crtcs & (1u << p->crtc_index)) &&
            prop_value(p->fd, pl->plane_id, DRM_MODE_OBJECT_PLANE, "type", ~0ull) ==
                DRM_PLANE_TYPE_PRIMARY)
            p->plane_id = pl->plane_id;
        drmModeFreePlane(pl);
    }
    drmModeFreePlaneResources(pres);
    if (!p->plane_id)
        return swell_fail(err, SWELL_E_DRM, "platform kms: no primary plane for CRTC %u on %s; "
                          "try --kms-api legacy", p->crtc_id, p->device);
    return SWELL_OK;
}

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

/* ---- framebuffers per gbm_bo --------------------------------------------------------------- */

static void fb_destroy_cb(struct gbm_bo *bo, void *data)
{
    (void)bo;
    struct kms_fb *f = data;
    if (f->fb_id)
        drmModeRmFB(f->fd, f->fb_id);
    free(f);
}

static int fb_for_bo(struct platform *p, struct gbm_bo *bo, uint32_t *fb_id, struct swell_err *err)
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
static int wait_flip(struct platform *p, struct swell_err *err)
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

/* ---- EGL on GBM ---------------------------------------------------------------------------- */

static int egl_fail(struct swell_err *err, const char *what)
{
    return swell_fail(err, SWELL_E_EGL, "platform kms: %s failed (EGL error 0x%04x)", what,
                      (unsigned)eglGetError());
}

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
    if (!eglChooseConfig(p->dpy, attrs, NULL, 0, &n) || n <= 0)
        return egl_fail(err, "eglChooseConfig (RGB888, depth >= 16, GLES2, window)");
    EGLConfig *cfgs = malloc((size_t)n * sizeof *cfgs);
    if (!cfgs)
        return swell_fail(err, SWELL_E_NOMEM, "platform kms: EGL config list");
    eglChooseConfig(p->dpy, attrs, cfgs, n, &n);
    int best_depth = 0;
    for (EGLint i = 0; i < n; i++) {
        EGLint vid = 0, depth = 0, r = 0, g = 0, b = 0;
        eglGetConfigAttrib(p->dpy, cfgs[i], EGL_NATIVE_VISUAL_ID, &vid);
        eglGetConfigAttrib(p->dpy, cfgs[i], EGL_DEPTH_SIZE, &depth);
        eglGetConfigAttrib(p->dpy, cfgs[i], EGL_RED_SIZE, &r);
        eglGetConfigAttrib(p->dpy, cfgs[i], EGL_GREEN_SIZE, &g);
        eglGetConfigAttrib(p->dpy, cfgs[i], EGL_BLUE_SIZE, &b);
        if ((uint32_t)vid != GBM_FORMAT_XRGB8888 || r != 8 || g != 8 || b != 8)
            continue;
        if (!best_depth || (depth >= 16 && (best_depth < 16 || depth < best_depth))) {
            p->config = cfgs[i];
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
    get_platform_display_fn get_display =
        (get_platform_display_fn)eglGetProcAddress("eglGetPlatformDisplayEXT");
    if (!get_display)
        return swell_fail(err, SWELL_E_EGL, "platform kms: eglGetPlatformDisplayEXT not found");
    p->dpy = get_display(EGL_PLATFORM_GBM_KHR, p->gbm, NULL);
    if (p->dpy == EGL_NO_DISPLAY)
        return egl_fail(err, "eglGetPlatformDisplayEXT(EGL_PLATFORM_GBM_KHR)");
    EGLint maj = 0, min = 0;
    if (!eglInitialize(p->dpy, &maj, &min)) {
        p->dpy = EGL_NO_DISPLAY;
        return egl_fail(err, "eglInitialize on the GBM display");
    }
    if (!eglBindAPI(EGL_OPENGL_ES_API))
        return egl_fail(err, "eglBindAPI(EGL_OPENGL_ES_API)");
    int rc = choose_config(p, err);
    if (rc)
        return rc;
    /* GLES 3 when asked for, else (or when refused) GLES 2. */
    for (int v = gles_major >= 3 ? 3 : 2; v >= 2 && p->ctx == EGL_NO_CONTEXT; v--) {
        const EGLint cattrs[] = { EGL_CONTEXT_CLIENT_VERSION, v, EGL_NONE };
        p->ctx = eglCreateContext(p->dpy, p->config, EGL_NO_CONTEXT, cattrs);
    }
    if (p->ctx == EGL_NO_CONTEXT)
        return egl_fail(err, "eglCreateContext (GLES 2)");
    p->surf = eglCreateWindowSurface(p->dpy, p->config, (EGLNativeWindowType)p->gs, NULL);
    if (p->surf == EGL_NO_SURFACE)
        return egl_fail(err, "eglCreateWindowSurface on the GBM surface");
    if (!eglMakeCurrent(p->dpy, p->surf, p->surf, p->ctx))
        return egl_fail(err, "eglMakeCurrent");
    if (p->verbose) {
        EGLint depth = 0;
        eglGetConfigAttrib(p->dpy, p->config, EGL_DEPTH_SIZE, &depth);
        fprintf(stderr, "platform kms: EGL %d.%d, XRGB8888 + depth %d, %s / %s\n", maj, min,
                depth, (const char *)glGetString(GL_VERSION),
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
        wait_flip(p, &ignored);
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
    if (p->dpy != EGL_NO_DISPLAY) {
        eglMakeCurrent(p->dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (p->surf != EGL_NO_SURFACE)
            eglDestroySurface(p->dpy, p->surf);
        if (p->ctx != EGL_NO_CONTEXT)
            eglDestroyContext(p->dpy, p->ctx);
        eglTerminate(p->dpy);
    }
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

static int setup_api(struct platform *p, int api, struct swell_err *err)
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
    int rc = pick_plane(p, err);
    if (!rc)
        rc = find_props(p->fd, p->conn_id, DRM_MODE_OBJECT_CONNECTOR, conn_prop_names,
                        CONN_PROP_COUNT, p->conn_props, "connector", err);
    if (!rc)
        rc = find_props(p->fd, p->crtc_id, DRM_MODE_OBJECT_CRTC, crtc_prop_names,
                        CRTC_PROP_COUNT, p->crtc_props, "CRTC", err);
    if (!rc)
        rc = find_props(p->fd, p->plane_id, DRM_MODE_OBJECT_PLANE, plane_prop_names,
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
    p->dpy = EGL_NO_DISPLAY;
    p->ctx = EGL_NO_CONTEXT;
    p->surf = EGL_NO_SURFACE;
    p->verbose = d->verbose;
    drmModeConnector *conn = NULL;
    int rc = pick_device(p, d, &conn, err);
    if (rc)
        goto fail;
    p->conn_id = conn->connector_id;
    rc = pick_crtc(p, conn, err);
    if (!rc)
        rc = pick_mode(p, conn, d, err);
    char cname[64];
    connector_name(conn, cname, sizeof cname);
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
    rc = setup_api(p, d->kms_api, err);
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
                mode_hz(&p->mode), p->ops->name);
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
    if (eglGetCurrentContext() != p->ctx && !eglMakeCurrent(p->dpy, p->surf, p->surf, p->ctx))
        return egl_fail(err, "eglMakeCurrent");
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, p->mode.hdisplay, p->mode.vdisplay);
    return SWELL_OK;
}

static int kms_present(struct platform *p, struct swell_err *err)
{
    if (!eglSwapBuffers(p->dpy, p->surf))
        return egl_fail(err, "eglSwapBuffers");
    struct gbm_bo *bo = gbm_surface_lock_front_buffer(p->gs);
    if (!bo)
        return swell_fail(err, SWELL_E_DRM, "platform kms: gbm_surface_lock_front_buffer failed");
    uint32_t fb = 0;
    int rc = fb_for_bo(p, bo, &fb, err);
    if (!rc && !p->lit) {
        rc = p->ops->modeset(p, fb, err);
        if (!rc)
            p->lit = 1;
    } else if (!rc) {
        rc = p->ops->flip(p, fb, err);
        if (!rc) {
            p->flip_pending = 1;
            rc = wait_flip(p, err);
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

static void xrgb_to_rgba(const uint8_t *src, uint32_t pitch, int w, int h, uint8_t *rgba)
{
    for (int y = 0; y < h; y++) {
        const uint32_t *row = (const uint32_t *)(src + (size_t)y * pitch);
        uint8_t *o = rgba + (size_t)y * w * 4;
        for (int x = 0; x < w; x++) {
            uint32_t v = row[x];
            o[4 * x + 0] = (uint8_t)(v >> 16);
            o[4 * x + 1] = (uint8_t)(v >> 8);
            o[4 * x + 2] = (uint8_t)v;
            o[4 * x + 3] = 255;
        }
    }
}

/* GBM's mapping of our front buffer: for drivers whose buffers are not dumb buffers. */
static int read_front_gbm(struct platform *p, uint8_t *rgba, struct swell_err *err)
{
    uint32_t w = p->mode.hdisplay, h = p->mode.vdisplay, stride = 0;
    void *map_data = NULL;
    void *ptr = gbm_bo_map(p->front, 0, 0, w, h, GBM_BO_TRANSFER_READ, &stride, &map_data);
    if (!ptr)
        return swell_fail(err, SWELL_E_DRM, "platform kms: cannot map the scanned-out buffer "
                          "(MAP_DUMB and gbm_bo_map both failed: %s)", strerror(errno));
    xrgb_to_rgba(ptr, stride, (int)w, (int)h, rgba);
    gbm_bo_unmap(p->front, map_data);
    return SWELL_OK;
}

static int kms_read_rgba(struct platform *p, uint8_t *rgba, struct swell_err *err)
{
    if (!p->lit || !p->front)
        return swell_fail(err, SWELL_E_ARG, "platform kms: read_rgba before the first present");
    drmModeCrtc *c = drmModeGetCrtc(p->fd, p->crtc_id);
    if (!c)
        return swell_fail(err, SWELL_E_DRM, "platform kms: drmModeGetCrtc(%u): %s", p->crtc_id,
                          strerror(errno));
    uint32_t fb_id = c->buffer_id;
    drmModeFreeCrtc(c);
    drmModeFB2 *fb = fb_id ? drmModeGetFB2(p->fd, fb_id) : NULL;
    if (!fb)
        return swell_fail(err, SWELL_E_DRM, "platform kms: CRTC %u shows no readable framebuffer "
                          "(fb %u): %s", p->crtc_id, fb_id, strerror(errno));
    int rc = SWELL_OK;
    if (fb->pixel_format != DRM_FORMAT_XRGB8888 && fb->pixel_format != DRM_FORMAT_ARGB8888) {
        rc = swell_fail(err, SWELL_E_DRM, "platform kms: scanned-out fb %u has format 0x%08x, "
                        "not XRGB8888", fb_id, fb->pixel_format);
    } else if ((int)fb->width != p->mode.hdisplay || (int)fb->height != p->mode.vdisplay) {
        rc = swell_fail(err, SWELL_E_DRM, "platform kms: scanned-out fb %u is %ux%u, not the "
                        "mode's %ux%u", fb_id, fb->width, fb->height, p->mode.hdisplay,
                        p->mode.vdisplay);
    } else {
        struct drm_mode_map_dumb map = { .handle = fb->handles[0] };
        size_t len = (size_t)fb->pitches[0] * fb->height + fb->offsets[0];
        void *ptr = MAP_FAILED;
        if (fb->handles[0] && drmIoctl(p->fd, DRM_IOCTL_MODE_MAP_DUMB, &map) == 0)
            ptr = mmap(NULL, len, PROT_READ, MAP_SHARED, p->fd, (off_t)map.offset);
        if (ptr != MAP_FAILED) {
            xrgb_to_rgba((const uint8_t *)ptr + fb->offsets[0], fb->pitches[0], (int)fb->width,
                         (int)fb->height, rgba);
            munmap(ptr, len);
        } else {
            rc = read_front_gbm(p, rgba, err);
        }
    }
    /* drmModeGetFB2 opened new GEM handles for us; planes may share one. */
    for (int i = 0; i < 4; i++) {
        int dup = 0;
        for (int j = 0; j < i; j++)
            dup |= fb->handles[j] == fb->handles[i];
        if (fb->handles[i] && !dup)
            drmCloseBufferHandle(p->fd, fb->handles[i]);
    }
    drmModeFreeFB2(fb);
    return rc;
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
