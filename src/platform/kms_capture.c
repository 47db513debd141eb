/* kms_capture.c - the KMS back-end's read_rgba() (kms_internal.h): returns what the display
 * scans out, not a copy of the GL back buffer. It asks the kernel which framebuffer the CRTC
 * shows now (drmModeGetCrtc -> drmModeGetFB2), maps that buffer (DRM_IOCTL_MODE_MAP_DUMB; GBM's
 * own mapping of the front buffer when the buffer is not a dumb buffer) and converts XRGB8888 to
 * RGBA8, top row first. Since present() returns only after the flip completed, that is the frame
 * just presented.
 */
#include "platform/kms_internal.h"

#include <errno.h>
#include <string.h>
#include <sys/mman.h>

#include <drm_fourcc.h>
#include <gbm.h>
#include <xf86drm.h>
#include <xf86drmMode.h>

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

int kms_read_rgba(struct platform *p, uint8_t *rgba, struct swell_err *err)
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
