/* platform.h - where frames go: one small interface, chosen at run time (STYLE.md 3).
 *
 * Renderer code never includes DRM/GBM/EGL-platform headers and never knows whether it draws on
 * a KMS display or offscreen. A back-end provides a `struct platform_backend` (see
 * platform_surfaceless.c, platform_kms.c); platform.c picks one (`auto`: KMS when a connected
 * display exists, else surfaceless) and forwards to it. Read-back (capture) happens only here.
 */
#ifndef SWELL_PLATFORM_H
#define SWELL_PLATFORM_H

#include <stdint.h>
#include "core/err.h"

enum platform_kind {
    PLATFORM_AUTO = 0,
    PLATFORM_SURFACELESS,   /* EGL_MESA_platform_surfaceless + FBO, read back to memory/PNG */
    PLATFORM_KMS,           /* libdrm + GBM + EGL, fullscreen page flips */
    PLATFORM_COUNT
};

enum kms_api { KMS_API_AUTO = 0, KMS_API_ATOMIC, KMS_API_LEGACY, KMS_API_COUNT };

struct platform_desc {
    int kind;               /* enum platform_kind. default AUTO */
    int width, height;      /* surfaceless: FBO size, default 1280x720. KMS: ignored (mode) */
    int gles_major;         /* context version to ask for: 2 or 3. default 2; 3 falls back to 2 */
    const char *device;     /* KMS: /dev/dri/cardN. default: first with a connected connector */
    const char *connector;  /* KMS: connector name such as "Virtual-1". default: first connected */
    int mode_w, mode_h;     /* KMS: wanted mode; 0 = preferred. nearest if not exact */
    int mode_hz;            /* KMS: wanted refresh, 0 = any */
    int kms_api;            /* enum kms_api. default AUTO (atomic, else legacy) */
    int verbose;            /* print the chosen device, mode, EGL config */
};

struct platform;

struct platform_backend {
    const char *name;
    /* Return SWELL_E_UNSUPPORTED (not an error to show) when unavailable here, for AUTO. */
    int  (*create)(const struct platform_desc *d, struct platform **out, struct swell_err *err);
    void (*size)(struct platform *p, int *w, int *h);
    int  (*begin_frame)(struct platform *p, struct swell_err *err);  /* bind the target */
    int  (*present)(struct platform *p, struct swell_err *err);      /* flip / finish */
    int  (*read_rgba)(struct platform *p, uint8_t *rgba, struct swell_err *err); /* last frame,
                                       w*h*4 bytes, top row first */
    int  (*should_quit)(struct platform *p);
    void (*destroy)(struct platform *p);
};

extern const struct platform_backend platform_surfaceless_backend;
extern const struct platform_backend platform_kms_backend;

struct platform_handle {
    const struct platform_backend *be;
    struct platform *p;
};

int  platform_open(const struct platform_desc *d, struct platform_handle *h, struct swell_err *err);
void platform_close(struct platform_handle *h);
const char *platform_kind_name(int kind);

#endif
