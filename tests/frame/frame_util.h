/* frame_util.h - what the surfaceless frame tests share: opening the platform (skip, exit 77,
 * without an EGL device unless CI=true, where that is a failure) and drawing one frame of a
 * renderer into an RGBA8 buffer. Header-only: each test is one program. */
#ifndef SWELL_TESTS_FRAME_UTIL_H
#define SWELL_TESTS_FRAME_UTIL_H

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "core/camera.h"
#include "platform/platform.h"
#include "render/renderer.h"

/* 0 when the surfaceless platform is open at w x h (GLES 3 context, tiers are forced lower),
 * else the exit status main() should return: 1 under CI=true, 77 (skip) elsewhere. */
static inline int frame_open(const char *test, int w, int h, struct platform_handle *ph)
{
    struct platform_desc pd = { 0 };
    struct swell_err err = { 0 };
    const char *ci = getenv("CI");
    pd.kind = PLATFORM_SURFACELESS;
    pd.width = w;
    pd.height = h;
    pd.gles_major = 3;
    if (!platform_open(&pd, ph, &err))
        return 0;
    if (ci && !strcmp(ci, "true")) {
        fprintf(stderr, "%s: no EGL device under CI=true: %s\n", test, err.msg);
        return 1;
    }
    fprintf(stderr, "%s: skipped, no EGL device: %s\n", test, err.msg);
    return 77;
}

/* One frame of r for camera c at time t_s, read back into rgba (w x h x 4); 0 or an error in
 * err (the caller fails the test with it). */
static inline int frame_draw(struct platform_handle *ph, struct renderer *r,
                             const struct camera *c, double t_s, int w, int h, uint8_t *rgba,
                             struct swell_err *err)
{
    int rc;
    if ((rc = ph->be->begin_frame(ph->p, err)) || (rc = renderer_frame(r, c, t_s, w, h, err)) ||
        (rc = ph->be->present(ph->p, err)) || (rc = ph->be->read_rgba(ph->p, rgba, err)))
        return rc;
    return 0;
}

#endif
