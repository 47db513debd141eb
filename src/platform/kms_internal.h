/* kms_internal.h - what the KMS back-end's files share, for them alone (callers see platform.h):
 * its state, `struct platform`, and the functions one of its files calls in another.
 *
 *   platform_kms.c  the back-end itself: create/destroy, GBM + EGL (egl.h), frames, signals
 *   kms_device.c    picks device, connector, CRTC, mode and (atomic) primary plane
 *   kms_present.c   atomic or legacy presentation behind `struct kms_present_ops`, DRM
 *                   framebuffers per gbm_bo, waiting for the flip event
 *   kms_capture.c   read_rgba: reads back the framebuffer the CRTC scans out
 *
 * Handles' "none" values are those of STYLE.md 6: fd -1, DRM ids 0, NULL pointers, EGL_NO_*.
 */
#ifndef SWELL_KMS_INTERNAL_H
#define SWELL_KMS_INTERNAL_H

#include <signal.h>
#include <stddef.h>
#include <stdint.h>

#include <gbm.h>
#include <xf86drmMode.h>

#include "core/err.h"
#include "platform/egl.h"
#include "platform/platform.h"

#define NO_HINT_MASTER "run it from a text console (VT) or as root, and stop the display manager " \
                       "(e.g. systemctl stop gdm) so that nothing else holds DRM master"

/* Atomic properties looked up by name once at start. */
enum conn_prop { CONN_CRTC_ID, CONN_PROP_COUNT };
enum crtc_prop { CRTC_MODE_ID, CRTC_ACTIVE, CRTC_PROP_COUNT };
enum plane_prop {
    PLANE_FB_ID, PLANE_CRTC_ID, PLANE_SRC_X, PLANE_SRC_Y, PLANE_SRC_W, PLANE_SRC_H,
    PLANE_CRTC_X, PLANE_CRTC_Y, PLANE_CRTC_W, PLANE_CRTC_H, PLANE_PROP_COUNT
};

struct platform;

struct kms_present_ops {
    const char *name;
    /* first frame: light the CRTC with fb (blocking) */
    int (*modeset)(struct platform *p, uint32_t fb, struct swell_err *err);
    /* later frames: queue a flip to fb that raises a page-flip event */
    int (*flip)(struct platform *p, uint32_t fb, struct swell_err *err);
};

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

    struct egl egl;             /* display, config, context, window surface on `gs` */

    struct sigaction old_int, old_term;
    int signals_installed;
};

/* ---- kms_device.c ---------------------------------------------------------------------------- */

/* "Virtual-1": the name --connector takes. */
void kms_connector_name(const drmModeConnector *c, char *buf, size_t n);
/* Refresh rate in Hz, rounded; 0 when the mode does not say. */
int kms_mode_hz(const drmModeModeInfo *m);
/* Opens desc->device, else the first primary node with a usable connector: sets p->fd and
 * p->device and returns the connector (caller frees). SWELL_E_UNSUPPORTED when the machine has
 * no KMS display at all (platform.c then falls back to surfaceless). */
int kms_pick_device(struct platform *p, const struct platform_desc *d, drmModeConnector **conn,
                    struct swell_err *err);
int kms_pick_crtc(struct platform *p, const drmModeConnector *c, struct swell_err *err);
int kms_pick_mode(struct platform *p, const drmModeConnector *c, const struct platform_desc *d,
                  struct swell_err *err);
/* The property ids of `names` on object `obj`, all or an error naming the first missing one. */
int kms_find_props(int fd, uint32_t obj, uint32_t type, const char *const *names, int count,
                   uint32_t *ids, const char *what, struct swell_err *err);
int kms_pick_plane(struct platform *p, struct swell_err *err);

/* ---- kms_present.c --------------------------------------------------------------------------- */

/* Sets p->ops: atomic when api allows and the device has all it needs, else legacy. */
int kms_setup_api(struct platform *p, int api, struct swell_err *err);
/* The DRM framebuffer of bo, created on first sight and owned by the bo from then on. */
int kms_fb_for_bo(struct platform *p, struct gbm_bo *bo, uint32_t *fb_id, struct swell_err *err);
/* Sleeps until the pending flip's event clears p->flip_pending. */
int kms_wait_flip(struct platform *p, struct swell_err *err);

/* ---- kms_capture.c --------------------------------------------------------------------------- */

/* platform_backend.read_rgba: the scanned-out frame as RGBA8, top row first. */
int kms_read_rgba(struct platform *p, uint8_t *rgba, struct swell_err *err);

#endif
