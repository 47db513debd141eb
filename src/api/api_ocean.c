/* api_ocean.c - the public ocean (include/swell.h): the renderer in the application's context,
 * drawn with the application's camera matrices into its framebuffer, the GL state it changes
 * restored (gl/glstate.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "api/api.h"
#include "geometry/mask.h"
#include "gl/glstate.h"

_Static_assert((int)SWELL_QUALITY_HIGH == QUALITY_HIGH && (int)SWELL_QUALITY_LOW == QUALITY_LOW,
               "swell.h's qualities are the renderer's");
_Static_assert((int)SWELL_GEOMETRY_GRID == GEOMETRY_GRID &&
               (int)SWELL_GEOMETRY_PATCHES == GEOMETRY_PATCHES,
               "swell.h's geometries are the grid's");
_Static_assert((int)SWELL_DETILE_AUTO == DETILE_MODE_AUTO &&
               (int)SWELL_DETILE_ON == DETILE_MODE_ON && (int)SWELL_DETILE_OFF == DETILE_MODE_OFF,
               "swell.h's detile modes are detile.h's");
_Static_assert(SWELL_TIER_GLES2_MIN - 1 == TIER_GLES2_MIN && SWELL_TIER_GLES3 - 1 == TIER_GLES3,
               "swell.h's tiers are gpu.h's plus one (0 = the best)");

/* The texture units swell may bind, whose bindings a call saves and restores: from the first
 * it was given, as many as it was given or (all it binds: 2 + 4 slots + 4 whitecap slots + 8
 * vertex-stage tables + the lattice hash = 19) GL_STATE_UNITS. */
static void save_state(const swell_ocean *o, struct gl_state *st)
{
    int n = o->units > 0 ? o->units : GL_STATE_UNITS;
    gl_state_save(st, o->unit0, n);
}

int swell_ocean_create(const swell_sea *sea, const swell_ocean_desc *desc, swell_ocean **out,
                       struct swell_err *err)
{
    swell_ocean_desc d0;
    memset(&d0, 0, sizeof d0);
    const swell_ocean_desc *d = desc ? desc : &d0;
    if (!sea || !out)
        return swell_fail(err, SWELL_E_ARG, "swell_ocean_create: sea and out must not be NULL");
    *out = NULL;
    if (d->quality < 0 || d->quality > SWELL_QUALITY_LOW || d->geometry < 0 ||
        d->geometry > SWELL_GEOMETRY_PATCHES || d->tier < 0 || d->tier > SWELL_TIER_GLES3 ||
        d->detile < 0 || d->detile > SWELL_DETILE_OFF)
        return swell_fail(err, SWELL_E_ARG, "swell_ocean_create: quality %d, geometry %d, tier "
                          "%d or detile %d is not one of swell.h's", d->quality, d->geometry,
                          d->tier, d->detile);
    if (d->sun_elev_deg < 0.0f || d->sun_elev_deg > 90.0f)
        return swell_fail(err, SWELL_E_ARG, "swell_ocean_create: sun elevation %g deg is out "
                          "of range: (0, 90], or 0 for 30", (double)d->sun_elev_deg);
    swell_ocean *o = calloc(1, sizeof *o);
    if (!o)
        return swell_fail(err, SWELL_E_NOMEM, "swell_ocean_create: no memory");
    o->sea = sea;
    if (d->shader_dir && !(o->shader_dir = strdup(d->shader_dir))) {
        free(o);
        return swell_fail(err, SWELL_E_NOMEM, "swell_ocean_create: no memory");
    }
    struct renderer_desc rd = {
        .tables = &sea->tables, .shader_dir = d->shader_dir, .quality = d->quality,
        .geometry = d->geometry, .sun_elev_deg = d->sun_elev_deg,
        .sun_azim_deg = d->sun_azim_deg, .detile = d->detile,
        .texture_unit_first = d->texture_unit_first, .texture_unit_count = d->texture_unit_count,
        .linear_output = d->linear_output, .reflections = d->reflections != 0,
        .wakes = d->wakes != 0, .shadows = d->shadows != 0,
        .refractions = d->refractions != 0, .pixel_lod = d->pixel_lod != 0,
        .wave_mask = d->wave_mask != 0,
        .debug_variants = d->debug_programs != 0,
    };
    struct gl_state st;
    o->unit0 = d->texture_unit_first;
    o->units = d->texture_unit_count;
    save_state(o, &st);
    int rc = renderer_open(&rd, &o->gpu, d->tier - 1, sea->tables.state.budget_bytes, d->note,
                           d->note_user, &o->renderer, err);
    o->quality = rd.quality;
    gl_state_restore(&st);
    if (rc) {
        free(o->shader_dir);
        free(o);
        return rc;
    }
    *out = o;
    return SWELL_OK;
}

/* The renderer's camera from the application's matrices: heading and pitch from the view's
 * forward axis, the field of view and clip planes from the projection. */
static int view_camera(const swell_view *v, struct camera *c, struct swell_err *err)
{
    const float *m = v->view, *p = v->proj;
    /* rows of the rotation (column-major: element (row r, column k) at m[4 k + r]) */
    double right[3] = { m[0], m[4], m[8] }, up[3] = { m[1], m[5], m[9] };
    double fwd[3] = { -m[2], -m[6], -m[10] };
    double rl = sqrt(right[0] * right[0] + right[1] * right[1] + right[2] * right[2]);
    double fl = sqrt(fwd[0] * fwd[0] + fwd[1] * fwd[1] + fwd[2] * fwd[2]);
    if (!(rl > 0.0) || !(fl > 0.0) || !isfinite(rl) || !isfinite(fl))
        return swell_fail(err, SWELL_E_ARG, "swell_ocean_draw: the view matrix has no rotation");
    if (fabs(fwd[2] / fl) > 0.99985)
        return swell_fail(err, SWELL_E_ARG, "swell_ocean_draw: the view looks straight up or "
                          "down (within 1 deg): keep its pitch within -89..89 deg");
    if (p[3] != 0.0f || p[7] != 0.0f || p[11] != -1.0f || p[15] != 0.0f || p[1] != 0.0f ||
        p[4] != 0.0f || !(p[0] > 0.0f) || !(p[5] > 0.0f) || !isfinite(p[8]) || !isfinite(p[9]))
        return swell_fail(err, SWELL_E_ARG, "swell_ocean_draw: the projection is not a "
                          "perspective (as gluPerspective or glFrustum builds)");
    /* the frustum's edges as tangents from the axis (renderer_view_frame), its corners within
     * 85 deg of it: the projected grid's rays stay within 81 deg of its own */
    double tx = fmax(fabs((-1.0 + p[8]) / p[0]), fabs((1.0 + p[8]) / p[0]));
    double ty = fmax(fabs((-1.0 + p[9]) / p[5]), fabs((1.0 + p[9]) / p[5]));
    if (!(atan(sqrt(tx * tx + ty * ty)) < 85.0 * M_PI / 180.0))
        return swell_fail(err, SWELL_E_ARG, "swell_ocean_draw: the projection's frustum reaches "
                          "%.1f deg from its axis at a corner (at most 85: narrow the field of "
                          "view or its offset)", atan(sqrt(tx * tx + ty * ty)) * 180.0 / M_PI);
    double n = p[14] / (p[10] - 1.0), f = p[14] / (p[10] + 1.0);
    if (!(n > 0.0) || !(f > n) || !isfinite(f))
        return swell_fail(err, SWELL_E_ARG, "swell_ocean_draw: the projection's clip planes "
                          "(%g, %g m) are not 0 < near < far", n, f);
    if (!isfinite(v->camera_pos[0]) || !isfinite(v->camera_pos[1]) ||
        !isfinite(v->camera_pos[2]) || fabs(v->camera_pos[2]) > 5e5)
        return swell_fail(err, SWELL_E_ARG, "swell_ocean_draw: camera_pos (%g, %g, %g) must be "
                          "finite, its altitude within 500 km", v->camera_pos[0],
                          v->camera_pos[1], v->camera_pos[2]);
    memset(c, 0, sizeof *c);
    for (int k = 0; k < 3; k++)
        c->pos[k] = v->camera_pos[k];
    c->heading_deg = (float)(atan2(fwd[1], fwd[0]) * 180.0 / M_PI);
    c->pitch_deg = (float)(asin(fmax(-1.0, fmin(1.0, fwd[2] / fl))) * 180.0 / M_PI);
    /* the bank: the eye's x axis is cos r level-right + sin r level-up (camera.h roll_deg) */
    c->roll_deg = (float)(atan2(right[2], up[2]) * 180.0 / M_PI);
    c->fov_y_deg = (float)(2.0 * atan(1.0 / p[5]) * 180.0 / M_PI);
    c->near_m = (float)n;
    c->far_m = (float)f;
    return SWELL_OK;
}

/* The renderer's view of the application's: its viewport, matrices and flags. */
static int renderer_view_of(const swell_view *v, double t_s, struct renderer_view *out,
                            struct swell_err *err)
{
    if (v->viewport[2] <= 0 || v->viewport[3] <= 0 || !isfinite(t_s))
        return swell_fail(err, SWELL_E_ARG, "swell_ocean_draw: viewport %d x %d must not be "
                          "empty and t_s %g finite", v->viewport[2], v->viewport[3], t_s);
    struct renderer_view rv = {
        .x = v->viewport[0], .y = v->viewport[1], .width = v->viewport[2],
        .height = v->viewport[3], .proj = v->proj, .view = v->view,
        .flags = ((v->flags & SWELL_DRAW_CLEAR) ? RENDERER_CLEAR : 0) |
                 ((v->flags & SWELL_DRAW_SKY) ? RENDERER_SKY : 0),
    };
    *out = rv;
    return view_camera(v, &out->cam, err);
}

int swell_ocean_draw(swell_ocean *o, const swell_view *v, double t_s, struct swell_err *err)
{
    if (!o || !v)
        return swell_fail(err, SWELL_E_ARG, "swell_ocean_draw: ocean and view must not be NULL");
    struct renderer_view rv;
    int rc = renderer_view_of(v, t_s, &rv, err);
    if (rc)
        return rc;
    struct gl_state st;
    save_state(o, &st);
    rc = renderer_draw(o->renderer, &rv, t_s, err);
    gl_state_restore(&st);
    return rc;
}

static void pass_out(const struct renderer_pass *p, swell_pass *out)
{
    memcpy(out->camera_pos, p->camera_pos, sizeof out->camera_pos);
    memcpy(out->view, p->view, sizeof out->view);
    memcpy(out->proj, p->proj, sizeof out->proj);
    memcpy(out->viewport, p->viewport, sizeof out->viewport);
    out->attenuation_per_m = p->attenuation_per_m;
}

/* A pass's begin: the arguments checked, the view converted; then begin (one of the three
 * renderer begins, its descriptor in d) and the pass copied out. */
enum pass_kind { PASS_REFLECTION, PASS_REFRACTION, PASS_SHADOW };
static int begin_pass(swell_ocean *o, const swell_view *v, enum pass_kind kind, const void *d,
                      swell_pass *out, const char *what, struct swell_err *err)
{
    if (!o || !v || !out)
        return swell_fail(err, SWELL_E_ARG, "%s: ocean, view and out must not be NULL", what);
    struct renderer_view rv;
    int rc = renderer_view_of(v, 0.0, &rv, err);
    if (rc)
        return rc;
    struct renderer_pass p;
    rc = kind == PASS_REFLECTION ? renderer_reflection_begin(o->renderer, &rv, d, &p, err)
       : kind == PASS_REFRACTION ? renderer_refraction_begin(o->renderer, &rv, d, &p, err)
                                 : renderer_shadow_begin(o->renderer, &rv, d, &p, err);
    if (!rc)
        pass_out(&p, out);
    return rc;
}

int swell_ocean_begin_reflection(swell_ocean *o, const swell_view *v,
                                 const swell_reflection_desc *desc, swell_pass *out,
                                 struct swell_err *err)
{
    struct renderer_reflection rd = { 0 };
    if (desc)
        rd.distance_m = desc->object_distance_m;
    return begin_pass(o, v, PASS_REFLECTION, &rd, out, "swell_ocean_begin_reflection", err);
}

int swell_ocean_begin_refraction(swell_ocean *o, const swell_view *v,
                                 const swell_refraction_desc *desc, swell_pass *out,
                                 struct swell_err *err)
{
    struct renderer_refraction rd = { 0 };
    if (desc) {
        rd.depth_m = desc->object_depth_m;
        rd.distance_m = desc->object_distance_m;
    }
    return begin_pass(o, v, PASS_REFRACTION, &rd, out, "swell_ocean_begin_refraction", err);
}

int swell_ocean_begin_shadow(swell_ocean *o, const swell_view *v, const swell_shadow_desc *desc,
                             swell_pass *out, struct swell_err *err)
{
    struct renderer_shadow sd = { 0 };
    if (desc) {
        sd.distance_m = desc->distance_m;
        sd.height_m = desc->caster_height_m;
    }
    return begin_pass(o, v, PASS_SHADOW, &sd, out, "swell_ocean_begin_shadow", err);
}

/* A pass's end: what it changes besides the framebuffer, viewport, clear colour, depth mask
 * and scissor (restored by the renderer's end, to begin's) restored as a draw restores it. */
static int end_pass(swell_ocean *o, int (*end)(struct renderer *, struct swell_err *),
                    const char *what, struct swell_err *err)
{
    if (!o)
        return swell_fail(err, SWELL_E_ARG, "%s: ocean is NULL", what);
    struct gl_state st;
    save_state(o, &st);
    int rc = end(o->renderer, err);
    glGetIntegerv(GL_FRAMEBUFFER_BINDING, &st.framebuffer);
    glGetIntegerv(GL_VIEWPORT, st.viewport);
    glGetFloatv(GL_COLOR_CLEAR_VALUE, st.clear_color);
    glGetBooleanv(GL_DEPTH_WRITEMASK, &st.depth_mask);
    st.scissor_test = glIsEnabled(GL_SCISSOR_TEST);
    gl_state_restore(&st);
    return rc;
}

int swell_ocean_end_reflection(swell_ocean *o, struct swell_err *err)
{
    return end_pass(o, renderer_reflection_end, "swell_ocean_end_reflection", err);
}

int swell_ocean_end_refraction(swell_ocean *o, struct swell_err *err)
{
    return end_pass(o, renderer_refraction_end, "swell_ocean_end_refraction", err);
}

int swell_ocean_end_shadow(swell_ocean *o, struct swell_err *err)
{
    return end_pass(o, renderer_shadow_end, "swell_ocean_end_shadow", err);
}

int swell_ocean_set_wake(swell_ocean *o, const swell_wake *w, struct swell_err *err)
{
    if (!o)
        return swell_fail(err, SWELL_E_ARG, "swell_ocean_set_wake: ocean is NULL");
    struct renderer_wake rw = { 0 };
    if (w) {
        rw.pos[0] = w->position_m[0];
        rw.pos[1] = w->position_m[1];
        rw.heading_deg = w->heading_deg;
        rw.speed_mps = w->speed_mps;
        rw.hull_length_m = w->hull_length_m;
        rw.beam_m = w->beam_m;
    }
    /* a new map is uploaded on the wake's unit: restored as a draw restores it */
    struct gl_state st;
    save_state(o, &st);
    int rc = renderer_set_wake(o->renderer, w ? &rw : NULL, err);
    gl_state_restore(&st);
    if (rc)
        swell_err_context(err, "swell_ocean_set_wake");
    return rc;
}

int swell_ocean_set_mask(swell_ocean *o, const swell_mask *m, struct swell_err *err)
{
    if (!o)
        return swell_fail(err, SWELL_E_ARG, "swell_ocean_set_mask: ocean is NULL");
    struct wave_mask wm;
    int rc = 0;
    if (m)
        rc = wave_mask_init(&wm, "swell_ocean_set_mask", m->amplitude, m->width, m->height,
                            m->origin_m, m->size_m, err);
    if (rc)
        return rc;
    /* the mask is uploaded on its unit: restored as a draw restores it */
    struct gl_state st;
    save_state(o, &st);
    rc = renderer_set_mask(o->renderer, m ? &wm : NULL, err);
    gl_state_restore(&st);
    if (rc)
        swell_err_context(err, "swell_ocean_set_mask");
    return rc;
}

int swell_ocean_set_sun(swell_ocean *o, float elev_deg, float azim_deg, struct swell_err *err)
{
    if (!o)
        return swell_fail(err, SWELL_E_ARG, "swell_ocean_set_sun: ocean is NULL");
    if (!(elev_deg > 0.0f && elev_deg <= 90.0f) || !isfinite(azim_deg))
        return swell_fail(err, SWELL_E_ARG, "swell_ocean_set_sun: elevation %g deg must be in "
                          "(0, 90] and the azimuth finite", (double)elev_deg);
    struct gl_state st;
    save_state(o, &st);
    int rc = renderer_set_sun(o->renderer, elev_deg, azim_deg, err);
    gl_state_restore(&st);
    return rc;
}

void swell_ocean_get_stats(const swell_ocean *o, swell_ocean_stats *out)
{
    memset(out, 0, sizeof *out);
    if (!o)
        return;
    struct renderer_stats st;
    renderer_get_stats(o->renderer, &st);
    out->tier = o->gpu.caps.tier + 1;
    out->tier_available = o->gpu.caps.tier_available + 1;
    out->quality = o->quality;
    out->detile = renderer_detile(o->renderer);
    out->objects = renderer_objects(o->renderer);
    out->gpu_bytes = st.gpu_bytes;
    out->gpu_bytes_charged = o->gpu.bytes;
    out->budget_bytes = o->gpu.budget_bytes;
    out->vertices = st.vertices;
    out->triangles = st.triangles;
    out->cpu_bytes_per_frame = st.cpu_bytes_per_frame;
    out->camera_raise_m = st.camera_raise_m;
}

size_t swell_ocean_describe(const swell_ocean *o, char *buf, size_t cap)
{
    char text[4096];
    text[0] = '\0';
    if (o)
        renderer_describe(o->renderer, text, sizeof text);
    return api_text_out(text, strlen(text), buf, cap);
}

_Static_assert((int)SWELL_PIXEL_SKY == (int)RENDERER_PIXEL_SKY &&
               (int)SWELL_PIXEL_MIXED == (int)RENDERER_PIXEL_MIXED,
               "swell.h's pixel codes are the renderer's");

int swell_ocean_program_at(const swell_ocean *o, const uint8_t rgba[4], char *name, size_t cap)
{
    int v = renderer_pixel_variant(rgba);
    if (cap)
        name[0] = '\0';
    if (o && v >= 0 && cap)
        renderer_program_name(o->renderer, v, name, cap);
    return v;
}

void swell_ocean_destroy(swell_ocean *o)
{
    if (!o)
        return;
    renderer_destroy(o->renderer);
    gpu_shutdown(&o->gpu);
    free(o->shader_dir);
    free(o);
}
