/* shadow.c - the sun's shadows of the application's objects on the sea (issue 18; Bruneton et
 * al. 2010 §6: "shadows are easily handled with a shadow map"; Hu et al. 2006 §2.2).
 *
 * The application draws its shadow casters into a target with the sun's view: an orthographic
 * projection along the sun's rays over a square of sea around the camera (begin gives its
 * matrices). Only coverage is kept (the map's alpha, mipmapped): objects on the sea stand
 * above it, so whatever covers a sea point's ray towards the sun shadows it, and no depth
 * needs to be stored (gles2-min has no depth textures, and packing depth into RGBA8 would buy
 * nothing here). ocean.frag (SWELL_SHADOW) reads the map at the flat sea's point under the
 * pixel (one 3 x 3 matrix from gl_FragCoord, through the sea plane, into the map); the
 * coverage takes away the sun's glitter and the sun's share of the light the water body and
 * the foam send back, leaving the sky's. The mipmapped fetch's implicit LOD blurs the edge by
 * a pixel's footprint, as a penumbra; the sun's own half-degree penumbra is not modelled.
 */
#include <math.h>
#include <string.h>
#include "render/internal.h"

#define SHADOW_SIZE 512             /* the map's side, texels */
#define SHADOW_DISTANCE_M 150.0     /* default half-side of the sea covered */
#define SHADOW_HEIGHT_M 30.0        /* default tallest caster */

void shadow_destroy(struct renderer *r)
{
    pass_target_destroy(r, &r->shadow);
    gpu_texture_destroy(r->gpu, &r->shadow_none);
}

int shadow_create(struct renderer *r, struct swell_err *err)
{
    if (!r->d.shadows)
        return 0;
    int rc = pass_target_create(r, &r->shadow, SHADOW_SIZE, SHADOW_SIZE, 1,
                                UNIT_SHADOW_OF(r->d.reflections, r->d.wakes), "shadow map", err);
    if (!rc)
        rc = pass_none_create(r, &r->shadow_none, "shadow (none)", err);
    return rc;
}

int renderer_shadow_begin(struct renderer *r, const struct renderer_view *v,
                          const struct renderer_shadow *d, struct renderer_pass *out,
                          struct swell_err *err)
{
    if (r->objects_refused)
        return renderer_objects_refused(r, "shadow map", err);
    if (!r->d.shadows)
        return swell_fail(err, SWELL_E_ARG, "renderer: no shadow map: create the ocean with "
                          "shadows = 1");
    if (pass_open(r))
        return swell_fail(err, SWELL_E_ARG, "renderer: a pass is open already: end it first");
    double rad = d && d->distance_m > 0.0f ? d->distance_m : SHADOW_DISTANCE_M;
    double ht = d && d->height_m > 0.0f ? d->height_m : SHADOW_HEIGHT_M;
    if (d && (!(d->distance_m >= 0.0f && d->distance_m <= 1e5f) ||
              !(d->height_m >= 0.0f && d->height_m <= 1e4f)))
        return swell_fail(err, SWELL_E_ARG, "renderer: shadow distance %g m and caster height "
                          "%g m must be in 0..1e5 and 0..1e4 (0: defaults)",
                          (double)d->distance_m, (double)d->height_m);
    /* the sun's frame: z towards the sun, x horizontal */
    double l[3] = { r->sky.sun_dir[0], r->sky.sun_dir[1], r->sky.sun_dir[2] };
    double xl[3] = { -l[1], l[0], 0.0 }, xn = hypot(xl[0], xl[1]);
    if (xn < 1e-6) {
        xl[0] = 1.0;
        xl[1] = 0.0;
        xn = 1.0;
    }
    xl[0] /= xn;
    xl[1] /= xn;
    double yl[3] = { l[1] * xl[2] - l[2] * xl[1], l[2] * xl[0] - l[0] * xl[2],
                     l[0] * xl[1] - l[1] * xl[0] };
    /* the square's centre: half the distance ahead of the point under the camera */
    struct camera_frame view;
    renderer_view_frame(v, &v->cam, &view);
    double fh = hypot(view.fwd[0], view.fwd[1]);
    double c[3] = { v->cam.pos[0], v->cam.pos[1], 0.0 };
    if (fh > 1e-6) {
        c[0] += 0.5 * rad * view.fwd[0] / fh;
        c[1] += 0.5 * rad * view.fwd[1] / fh;
    }
    double sin_e = fmax(l[2], 0.02), cos_e = sqrt(fmax(1.0 - sin_e * sin_e, 0.0));
    double dist = rad + ht + 10.0;
    double yh = rad * sin_e + ht * cos_e, zn = dist - ht * sin_e - rad * cos_e - 1.0;
    double zf = dist + rad * cos_e + 1.0;
    zn = zn > 0.1 ? zn : 0.1;
    memset(out, 0, sizeof *out);
    for (int k = 0; k < 3; k++) {
        out->camera_pos[k] = c[k] + dist * l[k];
        out->view[4 * k + 0] = (float)xl[k];
        out->view[4 * k + 1] = (float)yl[k];
        out->view[4 * k + 2] = (float)l[k];
    }
    out->view[15] = 1.0f;
    out->proj[0] = (float)(1.0 / rad);
    out->proj[5] = (float)(1.0 / yh);
    out->proj[10] = (float)(-2.0 / (zf - zn));
    out->proj[14] = (float)(-(zf + zn) / (zf - zn));
    out->proj[15] = 1.0f;
    out->viewport[2] = SHADOW_SIZE;
    out->viewport[3] = SHADOW_SIZE;

    /* ocean.frag: a sea point p relative to the camera, in the map: u = 1/2 + xl.(p + cam -
     * e) / (2 rad), v = 1/2 + yl.(p + cam - e) / (2 yh); after the pixel's sea point (frame.c
     * screen_to_sea, homogeneous) */
    double ce[3] = { v->cam.pos[0] - out->camera_pos[0], v->cam.pos[1] - out->camera_pos[1],
                     -out->camera_pos[2] };
    double aff[3][3] = {
        { xl[0] / (2.0 * rad), xl[1] / (2.0 * rad),
          0.5 + (xl[0] * ce[0] + xl[1] * ce[1] + xl[2] * ce[2]) / (2.0 * rad) },
        { yl[0] / (2.0 * yh), yl[1] / (2.0 * yh),
          0.5 + (yl[0] * ce[0] + yl[1] * ce[1] + yl[2] * ce[2]) / (2.0 * yh) },
        { 0.0, 0.0, 1.0 },
    };
    memcpy(r->shadow_aff, aff, sizeof aff);

    pass_save(&r->shadow_saved);
    pass_target_bind(&r->shadow);
    r->shadow_active = 1;
    r->shadow_ready = 0;
    return gpu_check("renderer: shadow pass", err);
}

int renderer_shadow_end(struct renderer *r, struct swell_err *err)
{
    if (!r->shadow_active)
        return swell_fail(err, SWELL_E_ARG, "renderer: no shadow pass is open: begin one first");
    r->shadow_active = 0;
    glActiveTexture(GL_TEXTURE0 + (GLenum)(r->d.texture_unit_first +
                                           UNIT_SHADOW_OF(r->d.reflections, r->d.wakes)));
    glBindTexture(GL_TEXTURE_2D, r->shadow.tex);
    glGenerateMipmap(GL_TEXTURE_2D);
    pass_restore(&r->shadow_saved);
    r->shadow_ready = 1;
    return gpu_check("renderer: shadow pass end", err);
}

/* ocean.frag's shadow uniforms for a draw of view: the map of the pass ended since the last
 * draw, else none; the sun's shares of the water body's and the foam's light (sea_light). */
void shadow_uniforms(const struct renderer *r, const struct camera_frame *view, const GLint *u,
                     const float sea_sun[3], const float foam_sun[3])
{
    if (!r->d.shadows)
        return;
    int on = r->shadow_ready;
    bind_tex(r, UNIT_SHADOW_OF(r->d.reflections, r->d.wakes), on ? r->shadow.tex : r->shadow_none,
             u[OU_SHADOW_TEX]);
    glUniform3fv(u[OU_SHADOW_SEA], 1, sea_sun);
    glUniform3fv(u[OU_SHADOW_FOAM], 1, foam_sun);
    sea_uniform_matrix(view, r->shadow_aff, on, u[OU_SHADOW_MAT]);
}
