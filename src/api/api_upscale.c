/* api_upscale.c - the public render scale (include/swell.h swell_upscale): render/upscale.h's
 * target and stretch, charged to an ocean's budget, on the ocean's first texture unit, the GL
 * state the stretch changes restored as a draw restores it. */
#include <stdlib.h>
#include "api/api.h"
#include "gl/glstate.h"
#include "render/upscale.h"

struct swell_upscale {
    swell_ocean *ocean;
    struct upscale up;
};

int swell_upscale_create(swell_ocean *o, int out_w, int out_h, double scale, int depth_bits,
                         swell_upscale **out, struct swell_err *err)
{
    if (!o || !out)
        return swell_fail(err, SWELL_E_ARG, "swell_upscale_create: ocean and out must not be "
                          "NULL");
    *out = NULL;
    if (out_w <= 0 || out_h <= 0 || out_w > 16384 || out_h > 16384)
        return swell_fail(err, SWELL_E_ARG, "swell_upscale_create: output %d x %d is not 1 to "
                          "16384 pixels a side", out_w, out_h);
    swell_upscale *u = calloc(1, sizeof *u);
    if (!u)
        return swell_fail(err, SWELL_E_NOMEM, "swell_upscale_create: no memory");
    u->ocean = o;
    struct gl_state st;
    gl_state_save(&st, o->unit0, 1);
    glActiveTexture(GL_TEXTURE0 + (GLenum)o->unit0);
    int rc = upscale_create(&u->up, &o->gpu, o->unit0, out_w, out_h, scale, depth_bits,
                            o->shader_dir, err);
    gl_state_restore(&st);
    if (rc) {
        swell_err_context(err, "swell_upscale_create");
        free(u);
        return rc;
    }
    *out = u;
    return SWELL_OK;
}

void swell_upscale_size(const swell_upscale *u, int *w, int *h)
{
    *w = u ? u->up.w : 0;
    *h = u ? u->up.h : 0;
}

void swell_upscale_begin(swell_upscale *u)
{
    if (u)
        upscale_begin(&u->up);
}

int swell_upscale_end(swell_upscale *u, struct swell_err *err)
{
    if (!u)
        return swell_fail(err, SWELL_E_ARG, "swell_upscale_end: up is NULL");
    struct gl_state st;
    gl_state_save(&st, u->ocean->unit0, 1);
    int rc = upscale_end(&u->up, err);
    /* the output stays bound, its viewport whole */
    glGetIntegerv(GL_FRAMEBUFFER_BINDING, &st.framebuffer);
    glGetIntegerv(GL_VIEWPORT, st.viewport);
    gl_state_restore(&st);
    return rc;
}

void swell_upscale_destroy(swell_upscale *u)
{
    if (!u)
        return;
    upscale_destroy(&u->up);
    free(u);
}
