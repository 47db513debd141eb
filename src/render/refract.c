/* refract.c - the application's objects under the water, seen through it (issue 18; Hu et al.
 * 2006 §2.2, §5.2, eq. 4; Bruneton et al. 2010 §6: "local refractions can be handled in the
 * same way" as local reflections).
 *
 * Hu renders the objects under the water plane into a refraction map, the underwater scene
 * scaled along the vertical (an approximation of Snell's refraction at a flat surface: a point
 * d deep is seen about d / n deep from above), with a fog from depth,
 *     C_refract = alpha_fog(d) C_deep_water + (1 - alpha_fog(d)) C_obj,            (eq. 4)
 * and reads it by projective texture mapping with coordinates shifted by the bump. Here the
 * pass gives the application the view of that scaled scene (the view times diag(1, 1, 1/n),
 * the eye at n times its height, Lengyel's oblique near plane at the sea plane so only what
 * lies under it is drawn) and asks it to write, as alpha, the water's transmittance down to
 * each point, exp(attenuation z) (z < 0 the point's height, the attenuation the water model's
 * beam attenuation in green, optics/water.h). ocean.frag (SWELL_REFRACT) takes eq. 4 per
 * channel: 1 - alpha_fog = that transmittance raised to each channel's attenuation over green's,
 * C_deep_water the water body's own radiance (eq. 28's L_sea, sunlit or shadowed), all of it
 * through the surface's (1 - F). The lookup is the pixel's own position in the map shifted by
 * the slope deviation times (1 - 1/n) the objects' depth, projected at their distance.
 */
#include <math.h>
#include <string.h>
#include "render/internal.h"

#define WATER_N 1.333               /* sea water's index of refraction */
#define REFRACT_DEPTH_M 2.0         /* default depth of the objects */
#define REFRACT_DISTANCE_M 30.0     /* default distance of the objects */

void refract_destroy(struct renderer *r)
{
    pass_target_destroy(r, &r->refr);
    gpu_texture_destroy(r->gpu, &r->refr_none);
}

int refract_create(struct renderer *r, struct swell_err *err)
{
    if (!r->d.refractions)
        return 0;
    return pass_none_create(r, &r->refr_none, "refraction (none)", err);
}

int renderer_refraction_begin(struct renderer *r, const struct renderer_view *v,
                              const struct renderer_refraction *d, struct renderer_pass *out,
                              struct swell_err *err)
{
    if (r->objects_refused)
        return renderer_objects_refused(r, "refraction map", err);
    if (!r->d.refractions)
        return swell_fail(err, SWELL_E_ARG, "renderer: no refraction map: create the ocean with "
                          "refractions = 1");
    if (pass_open(r))
        return swell_fail(err, SWELL_E_ARG, "renderer: a pass is open already: end it first");
    if (d && (!(d->depth_m >= 0.0f && d->depth_m <= 1e4f) ||
              !(d->distance_m >= 0.0f && d->distance_m <= 1e6f)))
        return swell_fail(err, SWELL_E_ARG, "renderer: the refracted objects' depth %g m and "
                          "distance %g m must be in 0..1e4 and 0..1e6 (0: defaults)",
                          (double)d->depth_m, (double)d->distance_m);
    double depth = d && d->depth_m > 0.0f ? d->depth_m : REFRACT_DEPTH_M;
    double dist = d && d->distance_m > 0.0f ? d->distance_m : REFRACT_DISTANCE_M;
    struct camera_frame view;
    renderer_view_frame(v, &v->cam, &view);
    pass_save(&r->refr_saved);
    int w, h;
    pass_target_size(v->width, v->height, &w, &h);
    if (!r->refr.fbo || w != r->refr.w || h != r->refr.h) {
        int rc = pass_target_create(r, &r->refr, w, h, 0,
                                    UNIT_REFRACT_OF(r->d.reflections, r->d.wakes, r->d.shadows),
                                    "refraction map", err);
        if (rc) {
            pass_restore(&r->refr_saved);
            return rc;
        }
    }
    /* the scene scaled by s = 1/n along z: eye = V (S p - c) = (V S) (p - S^-1 c) */
    double s = 1.0 / WATER_N, cz = v->cam.pos[2] > 0.01 ? v->cam.pos[2] : 0.01;
    memset(out, 0, sizeof *out);
    const float *vr = &view.view_rel[0][0], *pr = &view.proj[0][0];
    memcpy(out->view, vr, sizeof out->view);
    for (int k = 0; k < 3; k++)
        out->view[8 + k] = (float)(s * vr[8 + k]);
    out->view[12] = out->view[13] = out->view[14] = 0.0f;
    out->camera_pos[0] = v->cam.pos[0];
    out->camera_pos[1] = v->cam.pos[1];
    out->camera_pos[2] = cz / s;
    memcpy(out->proj, pr, sizeof out->proj);
    pass_widen(out->proj);
    /* keep what lies under the sea plane: with e the eye-space point, p = c' + S^-1 V^T e, so
     * s p_z = cz + V's third column . e, < 0 */
    double plane[4] = { -vr[8], -vr[9], -vr[10], -cz };
    pass_oblique_near(out->proj, plane);
    out->viewport[2] = r->refr.w;
    out->viewport[3] = r->refr.h;
    double att[3];
    water_attenuation(WATER_CHLOROPHYLL_OPEN, att);
    out->attenuation_per_m = (float)att[1];
    for (int k = 0; k < 3; k++)
        r->refr_tau[k] = (float)(att[k] / att[1]);

    /* ocean.frag: gl_FragCoord to the map's uv, 0.5 + ndc / (2 m); the slope deviation ds
     * moves the refracted ray's point at the objects' depth by (1 - 1/n) depth ds (world,
     * horizontal), seen at their distance: uv moves by P (R that) / (2 m dist), R the view's
     * rotation's first two rows */
    pass_screen_uv(v, r->refr_screen);
    double g = (1.0 - s) * depth / (2.0 * PASS_MARGIN * dist);
    /* mat2, column-major: column j is world axis j's uv */
    r->refr_shift[0] = (float)(g * pr[0] * vr[0]);
    r->refr_shift[1] = (float)(g * pr[5] * vr[1]);
    r->refr_shift[2] = (float)(g * pr[0] * vr[4]);
    r->refr_shift[3] = (float)(g * pr[5] * vr[5]);

    pass_target_bind(&r->refr);
    r->refr_active = 1;
    r->refr_ready = 0;
    return gpu_check("renderer: refraction pass", err);
}

int renderer_refraction_end(struct renderer *r, struct swell_err *err)
{
    if (!r->refr_active)
        return swell_fail(err, SWELL_E_ARG, "renderer: no refraction pass is open: begin one "
                          "first");
    r->refr_active = 0;
    pass_restore(&r->refr_saved);
    r->refr_ready = 1;
    return gpu_check("renderer: refraction pass end", err);
}

/* ocean.frag's refraction uniforms for a draw: the map of the pass ended since the last draw,
 * else the transparent one (the water body alone). */
void refract_uniforms(const struct renderer *r, const GLint *u)
{
    if (!r->d.refractions)
        return;
    bind_tex(r, UNIT_REFRACT_OF(r->d.reflections, r->d.wakes, r->d.shadows),
             r->refr_ready ? r->refr.tex : r->refr_none, u[OU_REFR_TEX]);
    glUniform4fv(u[OU_REFR_SCREEN], 1, r->refr_screen);
    glUniformMatrix2fv(u[OU_REFR_SHIFT], 1, GL_FALSE, r->refr_shift);
    glUniform3fv(u[OU_REFR_TAU], 1, r->refr_tau);
}
