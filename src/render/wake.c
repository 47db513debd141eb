/* wake.c - the Kelvin wake of the application's hull on the sea (issue 18; Bruneton et al.
 * 2010 §6: local waves added with their slopes and slope variances, so the sun's and the
 * sky's reflections stay consistent at every distance).
 *
 * geometry/kelvin.h builds the wake's map in the hull's frame: mean slope, mean square slope
 * and foam, a mip chain of box means. ocean.frag (SWELL_WAKE) reads it at the flat sea's point
 * under the pixel: gl_FragCoord to the sea plane is a projective map (the view ray met with
 * z = 0), and on to the hull's frame an affine one, so one 3 x 3 matrix (wake_mat) takes the
 * pixel to the hull-frame coordinates P, Q times w, which ocean.frag warps into the map's u, v
 * (kelvin.h: finer near the hull). The fetch's implicit LOD is the right one here (the map's
 * coordinates are smooth over the screen, unlike the reflection map's), so distant wake
 * waves average out in the mean slope while their variance stays, as the patterns' do
 * (Bruneton §4.1). The slopes are rotated into the world's axes and added to the pixel's slope
 * deviation, the variance within the fetch to its slope variance (split evenly between the
 * axes), the foam to the whitecap coverage. The wake's heights (a few decimetres) displace
 * the geometry: the map's heights stay on the CPU and grid_update adds them per vertex at its
 * footprint (grid_set_wake), so an ocean with wakes keeps the CPU grid on every tier
 * (choose_vtf). swell_sea_sample adds them where its desc names the wake (api_sea.c).
 */
#include <math.h>
#include <string.h>
#include "render/internal.h"

#define WAKE_MAP_W 512   /* along the track */
#define WAKE_MAP_H 256   /* across it */
#define WAKE_REBUILD 0.02

void wake_destroy(struct renderer *r)
{
    kelvin_map_free(&r->wake_map);
    gpu_texture_destroy(r->gpu, &r->wake_tex);
    gpu_texture_destroy(r->gpu, &r->wake_none);
    r->wake_w = r->wake_h = 0;
}

static int map_levels(void)
{
    int levels = 1;
    while ((WAKE_MAP_W >> levels) || (WAKE_MAP_H >> levels))
        levels++;
    return levels;
}

/* The map's texture, allocated here so the budget counts it from the start, and the 1x1
 * still-water map a draw reads while no wake is set. */
int wake_create(struct renderer *r, struct swell_err *err)
{
    static const uint8_t still[4] = { 128, 128, 0, 0 };
    if (!r->d.wakes)
        return 0;
    glActiveTexture(GL_TEXTURE0 + (GLenum)(r->d.texture_unit_first + UNIT_WAKE_OF(r->d.reflections)));
    int rc = gpu_texture_create(r->gpu, WAKE_MAP_W, WAKE_MAP_H, map_levels(), FORMAT_RGBA8, 0,
                                "wake map", &r->wake_tex, err);
    if (!rc)
        rc = gpu_texture_create(r->gpu, 1, 1, 1, FORMAT_RGBA8, 0, "wake (none)", &r->wake_none,
                                err);
    if (rc)
        return rc;
    return upload_single(r->wake_none, 1, 1, still, "wake (none)", err);
}

static int differs(double a, double b)
{
    return fabs(a - b) > WAKE_REBUILD * fmax(fabs(a), fabs(b));
}

int renderer_set_wake(struct renderer *r, const struct renderer_wake *w, struct swell_err *err)
{
    if (r->objects_refused)
        return renderer_objects_refused(r, "wake map", err);
    if (!r->d.wakes)
        return swell_fail(err, SWELL_E_ARG, "renderer: no wake map: create the ocean with "
                          "wakes = 1");
    if (!w || w->speed_mps == 0.0f) {
        r->wake_on = 0;
        return 0;
    }
    if (!isfinite(w->pos[0]) || !isfinite(w->pos[1]) || !isfinite(w->heading_deg))
        return swell_fail(err, SWELL_E_ARG, "wake: position (%g, %g) m and heading %g deg must "
                          "be finite", w->pos[0], w->pos[1], (double)w->heading_deg);
    struct kelvin_desc kd = {
        .speed_mps = w->speed_mps,
        .hull_length_m = w->hull_length_m,
        .beam_m = w->beam_m,
        .foam_half_life_s = r->t->state.foam_half_life_s,
    };
    kelvin_desc_defaults(&kd);
    int rc = kelvin_check(&kd, err);
    if (rc)
        return rc;
    const struct kelvin_desc *b = &r->wake_built;
    if (!r->wake_w || differs(kd.speed_mps, b->speed_mps) ||
        differs(kd.hull_length_m, b->hull_length_m) || differs(kd.beam_m, b->beam_m)) {
        struct kelvin_map m;
        if ((rc = kelvin_map_build(&kd, WAKE_MAP_W, WAKE_MAP_H, &m, err)))
            return rc;
        glActiveTexture(GL_TEXTURE0 + (GLenum)(r->d.texture_unit_first +
                                               UNIT_WAKE_OF(r->d.reflections)));
        struct chain_tex c = { { r->wake_tex }, 0 };   /* one texture, its levels */
        rc = upload_chain(&c, m.w, m.h, m.levels, m.rgba, "renderer: wake map upload", err);
        r->wake_w = rc ? 0 : m.w;
        r->wake_h = rc ? 0 : m.h;
        r->wake_front = 0.5 * kd.hull_length_m + m.ahead_m;
        r->wake_span = m.span_m;
        double se = sqrt(m.u_offset), n = sqrt(1.0 + m.u_offset) - se;
        r->wake_warp[0] = (float)m.u_offset;
        r->wake_warp[1] = (float)(1.0 / n);
        r->wake_warp[2] = (float)(-se / n);
        r->wake_warp[3] = (float)m.spread_offset;
        r->wake_spread = m.spread;
        r->wake_slope_scale = m.slope_scale;
        /* the heights stay for the geometry (grid_set_wake), the texels are on the GPU */
        free(m.rgba);
        m.rgba = NULL;
        kelvin_map_free(&r->wake_map);
        r->wake_map = m;
        if (rc) {
            kelvin_map_free(&r->wake_map);
            return rc;
        }
        r->wake_built = kd;
    }
    r->wake = *w;
    r->wake_on = 1;
    return 0;
}

/* The grid's wake for a frame from camera position cam_xy (grid_set_wake): none while no wake
 * is set. */
void wake_grid(const struct renderer *r, const double cam_xy[2], struct grid *g)
{
    if (!r->d.wakes)
        return;
    if (!r->wake_on || !r->wake_w || !r->wake_map.height) {
        grid_set_wake(g, NULL);
        return;
    }
    double hd = r->wake.heading_deg * M_PI / 180.0;
    struct grid_wake w = {
        .map = &r->wake_map,
        .hull_xy = { r->wake.pos[0] - cam_xy[0], r->wake.pos[1] - cam_xy[1] },
        .fwd = { cos(hd), sin(hd) },
    };
    grid_set_wake(g, &w);
}

/* The wake's height at world (x, y) at footprint foot_m, m: 0 without one (the camera's
 * clearance, frame.c). */
double wake_height_at(const struct renderer *r, double x, double y, float foot_m)
{
    if (!r->d.wakes || !r->wake_on || !r->wake_w || !r->wake_map.height)
        return 0.0;
    double hd = r->wake.heading_deg * M_PI / 180.0, f0 = cos(hd), f1 = sin(hd);
    double dx = x - r->wake.pos[0], dy = y - r->wake.pos[1];
    return kelvin_map_height(&r->wake_map, dx * f0 + dy * f1, dy * f0 - dx * f1, foot_m);
}

/* ocean.frag's wake uniforms for a draw of view. */
void wake_uniforms(const struct renderer *r, const struct camera_frame *view, const GLint *u,
                   const float foam[3])
{
    if (!r->d.wakes)
        return;
    int on = r->wake_on && r->wake_w;
    bind_tex(r, UNIT_WAKE_OF(r->d.reflections), on ? r->wake_tex : r->wake_none, u[OU_WAKE_TEX]);
    glUniform3fv(u[OU_WAKE_FOAM], 1, foam);
    double hd = r->wake.heading_deg * M_PI / 180.0;
    double f[2] = { cos(hd), sin(hd) }, l[2] = { -f[1], f[0] };
    double sc = on ? r->wake_slope_scale : 0.0;
    /* the map's bytes to world slopes: s = (255 t - 128) / 127 scale along (f, l) */
    double a = 255.0 / 127.0 * sc, c = 128.0 / 127.0 * sc;
    float rot[4] = { (float)(a * f[0]), (float)(a * f[1]), (float)(a * l[0]), (float)(a * l[1]) };
    float k[3] = { (float)(-c * (f[0] + l[0])), (float)(-c * (f[1] + l[1])), (float)(sc * sc) };
    glUniform4fv(u[OU_WAKE_ROT], 1, rot);
    glUniform3fv(u[OU_WAKE_K], 1, k);
    /* gl_FragCoord -> the flat sea's point (frame.c) -> the hull's frame, x, y the point less the hull's position along f and l, and the
     * map's P = (front - x) / span, Q = y / span (kelvin.h), Q over the spread: ocean.frag
     * takes u, v from them */
    double cb[2] = { view->cam.pos[0] - r->wake.pos[0], view->cam.pos[1] - r->wake.pos[1] };
    double sp = r->wake_span > 0.0 ? r->wake_span : 1.0;
    double spr = r->wake_spread > 0.0 ? r->wake_spread : 1.0;
    double aff[3][3] = {
        { -f[0] / sp, -f[1] / sp, (r->wake_front - (cb[0] * f[0] + cb[1] * f[1])) / sp },
        { l[0] / (sp * spr), l[1] / (sp * spr), (cb[0] * l[0] + cb[1] * l[1]) / (sp * spr) },
        { 0.0, 0.0, 1.0 },
    };
    sea_uniform_matrix(view, aff, 1, u[OU_WAKE_MAT]);
    glUniform4fv(u[OU_WAKE_WARP], 1, r->wake_warp);
}
