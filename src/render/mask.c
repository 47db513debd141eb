/* mask.c - locally varying wave parameters by a coarse mask (issue 18; Bruneton et al. 2010
 * §6; geometry/mask.h says what the amplitude a scales and how).
 *
 * The application's bytes go into a MASK_TEX-square block of the Fresnel atlas (textures.c) at
 * texels 1..w, 1..h of it, with 255 (the open sea) all around: no texture unit of its own (on
 * gles2-min one more unit moved a wave pattern's shading to the CPU). The atlas has no mips, so
 * far away, where a pixel spans several of the mask's texels, the pixel reads a bilinear sample
 * of the mask, not its mean (a coarse, smooth mask does not alias). ocean.frag (SWELL_MASK)
 * reads it at the flat sea's point under the pixel (one 3 x 3 matrix from gl_FragCoord, as the
 * wake's, wake.c), the coordinates clamped to the block's border texels, and scales the
 * pixel's fetched slopes and variances; the grid on the CPU scales each vertex (grid_set_mask),
 * whose amplitude ocean.vert takes to scale the variances it adds. So an ocean with a mask
 * keeps the CPU grid on every tier (choose_vtf). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "bake/whitecap.h"
#include "render/internal.h"

/* The block for mask m (no bytes: 255 everywhere) into out, rows row_bytes apart. */
void mask_block(const struct wave_mask *m, uint8_t *out, size_t row_bytes)
{
    for (int y = 0; y < MASK_TEX; y++) {
        uint8_t *o = out + (size_t)y * row_bytes;
        memset(o, 255, 4 * (size_t)MASK_TEX);
        if (!m->amp || y < 1 || y > m->h)
            continue;
        for (int i = 0; i < m->w; i++)
            memset(o + 4 * (size_t)(i + 1), m->amp[(size_t)(y - 1) * (size_t)m->w + (size_t)i], 4);
    }
}

int renderer_set_mask(struct renderer *r, const struct wave_mask *m, struct swell_err *err)
{
    if (r->objects_refused)
        return renderer_objects_refused(r, "wave mask", err);
    if (!r->d.wave_mask)
        return swell_fail(err, SWELL_E_ARG, "renderer: no wave mask: create the ocean with "
                          "wave_mask = 1");
    uint8_t *copy = NULL;
    struct wave_mask mc = { 0 };
    if (m) {   /* (its fields checked by wave_mask_init, swell_ocean_set_mask) */
        size_t n = (size_t)m->w * (size_t)m->h;
        if (!(copy = malloc(n)))
            return swell_fail(err, SWELL_E_NOMEM, "renderer: no memory for the wave mask");
        memcpy(copy, m->amp, n);
        mc = *m;
        mc.amp = copy;
    }
    /* the block into the atlas (on the Fresnel unit, the renderer's own) */
    uint8_t *block = malloc(4 * (size_t)MASK_TEX * MASK_TEX);
    if (!block) {
        free(copy);
        return swell_fail(err, SWELL_E_NOMEM, "renderer: no memory for the wave mask");
    }
    mask_block(&mc, block, 4 * (size_t)MASK_TEX);
    glActiveTexture(GL_TEXTURE0 + (GLenum)(r->d.texture_unit_first + UNIT_FRESNEL));
    glBindTexture(GL_TEXTURE_2D, r->fresnel_tex);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexSubImage2D(GL_TEXTURE_2D, 0, r->mask_x, 0, MASK_TEX, MASK_TEX, GL_RGBA,
                    GL_UNSIGNED_BYTE, block);
    free(block);
    int rc = gpu_check("renderer: wave mask upload", err);
    if (rc) {
        free(copy);
        return rc;
    }
    free(r->mask_bytes);
    r->mask_bytes = copy;
    r->mask = mc;
    return 0;
}

/* The grid's mask for a frame (grid_set_mask): the amplitude attribute whenever the ocean
 * has a mask, 1 while none is set. */
void mask_grid(const struct renderer *r, struct grid *g)
{
    if (r->d.wave_mask)
        grid_set_mask(g, 1, r->mask.amp ? &r->mask : NULL);
}

/* The amplitude at world (x, y): 1 without a mask (the camera's clearance, frame.c). */
float mask_amp_at(const struct renderer *r, double x, double y)
{
    return r->d.wave_mask && r->mask.amp ? wave_mask_at(&r->mask, x, y) : 1.0f;
}

/* ocean.frag's and ocean.vert's mask uniforms for a draw of view. */
void mask_uniforms(const struct renderer *r, const struct camera_frame *view, const GLint *u)
{
    if (!r->d.wave_mask)
        return;
    /* the whitecap coverage's exponent b / 2 (geometry/mask.h) */
    float e = (float)(0.5 * whitecap_model_exponent(r->t->state.whitecap_model));
    glUniform1f(u[OU_MASK_FOAM], e);
    glUniform1f(u[OU_MASK_FOAM_V], e);
    /* gl_FragCoord -> the flat sea's camera-relative point (frame.c) -> the atlas's uv: the
     * application's texel i at the block's texel i + 1 (the border), the block from column
     * mask_x; read within the centres of its border texels */
    const struct wave_mask *m = &r->mask;
    double dx = m->amp ? m->dx : 1.0, dy = m->amp ? m->dy : 1.0;
    double x0 = m->amp ? m->x0 : 0.0, y0 = m->amp ? m->y0 : 0.0;
    double aw = r->atlas_w, ah = r->atlas_h;
    double aff[3][3] = {
        { 1.0 / (dx * aw), 0.0, ((view->cam.pos[0] - x0) / dx + 1.0 + r->mask_x) / aw },
        { 0.0, 1.0 / (dy * ah), ((view->cam.pos[1] - y0) / dy + 1.0) / ah },
        { 0.0, 0.0, 1.0 },
    };
    sea_uniform_matrix(view, aff, 1, u[OU_MASK_MAT]);
    glUniform4f(u[OU_MASK_BOX], (float)((r->mask_x + 0.5) / aw), (float)(0.5 / ah),
                (float)((r->mask_x + MASK_TEX - 0.5) / aw), (float)((MASK_TEX - 0.5) / ah));
}
