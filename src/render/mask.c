/* mask.c - locally varying wave parameters by a coarse mask (issue 18; Bruneton et al. 2010
 * §6; geometry/mask.h says what the amplitude a scales and how).
 *
 * The application's bytes go into a 256 x 256 RGBA8 texture at texels 1..w, 1..h, with 255
 * (the open sea) all around, and a mip chain of box means (the sea far away reads the area's
 * mean amplitude, as its slope variance is an area's). ocean.frag (SWELL_MASK) reads it at the
 * flat sea's point under the pixel (one 3 x 3 matrix from gl_FragCoord, as the wake's, wake.c)
 * and scales the pixel's fetched slopes and variances; the grid on the CPU scales each vertex
 * (grid_set_mask), whose amplitude ocean.vert takes to scale the variances it adds. So an
 * ocean with a mask keeps the CPU grid on every tier (choose_vtf). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "bake/whitecap.h"
#include "render/internal.h"

#define MASK_TEX 256

static int mask_levels(void)
{
    int l = 1;
    while (MASK_TEX >> l)
        l++;
    return l;
}

void mask_destroy(struct renderer *r)
{
    gpu_texture_destroy(r->gpu, &r->mask_tex);
}

/* The texture's chain for mask m (NULL: 255 everywhere) into *out (malloc'd). */
static uint8_t *mask_chain(const struct wave_mask *m)
{
    size_t total = 0;
    for (int l = 0; l < mask_levels(); l++)
        total += 4 * (size_t)(MASK_TEX >> l) * (size_t)(MASK_TEX >> l);
    uint8_t *c = malloc(total);
    if (!c)
        return NULL;
    memset(c, 255, 4 * (size_t)MASK_TEX * MASK_TEX);
    if (m)
        for (int j = 0; j < m->h; j++)
            for (int i = 0; i < m->w; i++)
                memset(c + 4 * ((size_t)(j + 1) * MASK_TEX + (size_t)(i + 1)),
                       m->amp[(size_t)j * (size_t)m->w + (size_t)i], 4);
    uint8_t *prev = c;
    for (int l = 1, s = MASK_TEX / 2; l < mask_levels(); l++, s /= 2) {
        uint8_t *cur = prev + 4 * (size_t)(2 * s) * (size_t)(2 * s);
        for (int y = 0; y < s; y++)
            for (int x = 0; x < s; x++) {
                const uint8_t *p = prev + 4 * ((size_t)(2 * y) * (size_t)(2 * s) + 2 * (size_t)x);
                int sum = p[0] + p[4] + p[8 * s] + p[8 * s + 4];
                memset(cur + 4 * ((size_t)y * (size_t)s + (size_t)x), (sum + 2) / 4, 4);
            }
        prev = cur;
    }
    return c;
}

static int mask_upload(struct renderer *r, const struct wave_mask *m, struct swell_err *err)
{
    uint8_t *c = mask_chain(m);
    if (!c)
        return swell_fail(err, SWELL_E_NOMEM, "renderer: no memory for the wave mask");
    glActiveTexture(GL_TEXTURE0 + (GLenum)(r->d.texture_unit_first +
                                           UNIT_MASK_OF(r->d.reflections, r->d.wakes,
                                                        r->d.shadows, r->d.refractions)));
    struct chain_tex ct = { { r->mask_tex }, 0 };   /* one texture, its levels */
    int rc = upload_chain(&ct, MASK_TEX, MASK_TEX, mask_levels(), c,
                          "renderer: wave mask upload", err);
    free(c);
    return rc;
}

/* The texture, allocated and filled with the open sea here, so the budget counts it. */
int mask_create(struct renderer *r, struct swell_err *err)
{
    if (!r->d.wave_mask)
        return 0;
    glActiveTexture(GL_TEXTURE0 + (GLenum)(r->d.texture_unit_first +
                                           UNIT_MASK_OF(r->d.reflections, r->d.wakes,
                                                        r->d.shadows, r->d.refractions)));
    int rc = gpu_texture_create(r->gpu, MASK_TEX, MASK_TEX, mask_levels(), FORMAT_RGBA8, 0,
                                "wave mask", &r->mask_tex, err);
    return rc ? rc : mask_upload(r, NULL, err);
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
    if (m) {
        if (m->w < 1 || m->h < 1 || m->w > WAVE_MASK_MAX || m->h > WAVE_MASK_MAX || !m->amp)
            return swell_fail(err, SWELL_E_ARG, "renderer: the wave mask is %d x %d texels; "
                              "each side must be 1..%d", m->w, m->h, WAVE_MASK_MAX);
        size_t n = (size_t)m->w * (size_t)m->h;
        if (!(copy = malloc(n)))
            return swell_fail(err, SWELL_E_NOMEM, "renderer: no memory for the wave mask");
        memcpy(copy, m->amp, n);
        mc = *m;
        mc.amp = copy;
    }
    int rc = mask_upload(r, m ? &mc : NULL, err);
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
    bind_tex(r, UNIT_MASK_OF(r->d.reflections, r->d.wakes, r->d.shadows, r->d.refractions),
             r->mask_tex, u[OU_MASK_TEX]);
    /* the whitecap coverage's exponent b / 2 (geometry/mask.h) */
    float e = (float)(0.5 * whitecap_model_exponent(r->t->state.whitecap_model));
    glUniform1f(u[OU_MASK_FOAM], e);
    glUniform1f(u[OU_MASK_FOAM_V], e);
    /* gl_FragCoord -> the flat sea's camera-relative point (frame.c) -> the texture's uv: the
     * application's texel i at texel i + 1 (the border) */
    const struct wave_mask *m = &r->mask;
    double dx = m->amp ? m->dx : 1.0, dy = m->amp ? m->dy : 1.0;
    double x0 = m->amp ? m->x0 : 0.0, y0 = m->amp ? m->y0 : 0.0;
    double aff[3][3] = {
        { 1.0 / (dx * MASK_TEX), 0.0, ((view->cam.pos[0] - x0) / dx + 1.0) / MASK_TEX },
        { 0.0, 1.0 / (dy * MASK_TEX), ((view->cam.pos[1] - y0) / dy + 1.0) / MASK_TEX },
        { 0.0, 0.0, 1.0 },
    };
    sea_uniform_matrix(view, aff, 1, u[OU_MASK_MAT]);
}
