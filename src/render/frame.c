/* frame.c - one frame (render/internal.h): the terms of the vertex stage (vertex_frame), the
 * ocean program's uniforms for a run of rows (lighting: Bruneton eq. 14-15, 26, 28; whitecaps:
 * Dupuy eq. 6-8), the runs of grid rows far to near with the variant each needs, and
 * renderer_frame, which draws the sky and then the sea into the bound framebuffer.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "render/internal.h"

/* The light the sea reflects and refracts, radiances times the exposure (tone_map in
 * common.glsl takes them so): the sun's irradiance, eq. 28's water body L_sea and the
 * Lambertian 0.4 foam (Dupuy §2), both lit by sun and sky: E, the irradiance on the level
 * sea, the sun's times sin(elevation) plus the sky's; and the sun's shares of the last two
 * (what a shadow takes away, shadow.c). */
static void sea_light(const struct renderer *r, float sun[3], float sea[3], float foam[3],
                      float sea_sun[3], float foam_sun[3])
{
    float e = r->exposure;
    for (int c = 0; c < 3; c++) {
        float direct = r->sky.sun_irr[c] * fmaxf(r->sky.sun_dir[2], 0.0f);
        float lit = direct + r->sky.sky_irr[c];
        sun[c] = r->d.no_sun ? 0.0f : e * r->sky.sun_irr[c];
        sea[c] = e * r->water_albedo[c] * lit / (float)M_PI;
        foam[c] = e * 0.4f * lit / (float)M_PI;
        sea_sun[c] = e * r->water_albedo[c] * direct / (float)M_PI;
        foam_sun[c] = e * 0.4f * direct / (float)M_PI;
    }
}

/* gl_FragCoord (fx, fy, 1) -> the flat sea's point (z = 0) under the pixel, relative to the
 * camera and homogeneous: (h d_x, h d_y, -d_z) with d the view ray in the world and h the
 * camera's height; its w > 0 below the horizon. For a perspective, off-axis or not (the
 * wake's and the shadow's lookups: wake.c, shadow.c). */
void screen_to_sea(const struct camera_frame *view, double q[3][3])
{
    double h = view->cam.pos[2] > 0.01 ? view->cam.pos[2] : 0.01;
    double p0 = view->proj[0][0], p1 = view->proj[1][1];
    double p8 = view->proj[2][0], p9 = view->proj[2][1];
    /* the eye-frame ray e = E (fx, fy, 1): x / -z = (ndc + P20) / P00 */
    double e[3][3] = {
        { 2.0 / (view->width * p0), 0.0, -(1.0 + 2.0 * view->x / view->width - p8) / p0 },
        { 0.0, 2.0 / (view->height * p1), -(1.0 + 2.0 * view->y / view->height - p9) / p1 },
        { 0.0, 0.0, -1.0 },
    };
    /* d = R^T e, R the view's rotation (view_rel, [col][row]) */
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            double d = 0.0;
            for (int k = 0; k < 3; k++)
                d += (double)view->view_rel[i][k] * e[k][j];
            q[i][j] = i < 2 ? h * d : -d;
        }
}

/* Uniform mat3 loc := aff (a map of the camera-relative sea plane, homogeneous) after
 * screen_to_sea: gl_FragCoord to aff's coordinates times w. on 0: a zero matrix. */
void sea_uniform_matrix(const struct camera_frame *view, const double aff[3][3], int on,
                        GLint loc)
{
    double q[3][3];
    screen_to_sea(view, q);
    float mat[9] = { 0 };   /* column-major */
    for (int i = 0; on && i < 3; i++)
        for (int j = 0; j < 3; j++) {
            double s = 0.0;
            for (int k = 0; k < 3; k++)
                s += aff[i][k] * q[k][j];
            mat[3 * j + i] = (float)s;
        }
    glUniformMatrix3fv(loc, 1, GL_FALSE, mat);
}

static void set_vtf_uniforms(struct renderer *r, int variant, const struct camera *cam)
{
    const GLint *u = r->vu[variant];
    const struct grid_projection *p = &r->proj;
    float sc[SWELL_MAX_PATTERNS][4] = { { 0 } }, bi[SWELL_MAX_PATTERNS][4] = { { 0 } };
    float pat[SWELL_MAX_PATTERNS][4] = { { 0 } }, v[3][3];
    float cell[SWELL_MAX_PATTERNS][2] = { { 0 } };
    int w = r->d.grid_w, h = r->d.grid_h;
    for (int c = 0; c < 3; c++) {
        v[0][c] = (float)p->fwd[c];
        v[1][c] = (float)p->right[c];
        v[2][c] = (float)p->up[c];
    }
    for (int i = 0; i < r->t->patterns; i++) {
        const struct swell_table *d = tables_find(r->t, TABLE_DISP, i);
        const struct swell_pattern_info *pi = &r->t->pattern[i];
        memcpy(sc[i], d->scale, 3 * sizeof(float));
        memcpy(bi[i], d->bias, 3 * sizeof(float));
        sc[i][3] = r->disp_w[i];
        grid_uv_offset(r->t, i, cam, pat[i]);
        pat[i][2] = 1.0f / pi->size_m;
        pat[i][3] = grid_band_wavelength(pi);
        for (int f = 0; f < 2; f++)
            bind_tex(r, unit_patterns(r) + r->nfs + r->nwc + 2 * i + f,
              r->disp_tex[i][r->disp_ab[i][f]], u[VU_A0 + 2 * i + f]);
        float sh[3];
        detile_camera_shift(i, cam->pos[0], cam->pos[1], 1.0 / pi->size_m, sh);
        cell[i][0] = sh[0];
        cell[i][1] = sh[1];
    }
    /* the atlas's hash on the unit after the displacement's (choose_vtf counts it) */
    if (renderer_detile(r))
        bind_tex(r, unit_patterns(r) + r->nfs + r->nwc + 2 * r->t->patterns,
          r->fresnel_tex, u[VU_DETILE_TEX]);
    float atlas[4];
    atlas_hash_frame(r, atlas);
    glUniform4fv(u[VU_DETILE_ATLAS], 1, atlas);
    glUniform2fv(u[VU_DISP_CELL], SWELL_MAX_PATTERNS, &cell[0][0]);
    glUniform3fv(u[VU_FWD], 1, v[0]);
    glUniform3fv(u[VU_RIGHT], 1, v[1]);
    glUniform3fv(u[VU_UP], 1, v[2]);
    glUniform4f(u[VU_FRAME], (float)p->col_split[0], (float)p->col_split[1], (float)p->alt,
                (float)p->alt_ray);
    glUniform4f(u[VU_RANGE], (float)p->col_ang[0], (float)p->col_ang[1], (float)p->col_ang[2],
                (float)p->col_ang[3]);
    glUniform4f(u[VU_ROWS], (float)p->row_cam[0], (float)p->row_cam[1], (float)p->row_split,
                (float)p->row_h);
    glUniform3f(u[VU_ROWS_HZ], (float)p->row_inv_delta, (float)p->row_ustar, (float)p->row_a);
    glUniform3f(u[VU_MARGIN], (float)p->row_margin[0], (float)p->row_margin[1], (float)-p->pitch);
    glUniform3f(u[VU_STEP], 1.0f / (float)(w - 1), 1.0f / (float)(h - 1), (float)p->dmax);
    glUniform4fv(u[VU_SCALE], SWELL_MAX_PATTERNS, &sc[0][0]);
    glUniform4fv(u[VU_BIAS], SWELL_MAX_PATTERNS, &bi[0][0]);
    glUniform4fv(u[VU_PATTERN], SWELL_MAX_PATTERNS, &pat[0][0]);
}

/* A slot whose whitecaps are not fetched enters Dupuy's sums as its patch's constants, unless
 * the grid resolves them per vertex (k_mask). */
static void add_k_constants(const struct renderer *r, const struct fs_slot *sl, float ck[2])
{
    if ((r->k_mask >> sl->pattern) & 1u)
        return;
    ck[0] += sl->top_k[0];
    ck[1] += sl->top_k[1];
}

/* Both passes are linearised about the slots' mean slope (ocean.vert) with a step of the slope
 * deviation of every slot, fetched or not: the same secant in every run, so no seam where a run
 * drops a pattern (with the fetched slots' deviation alone, fetching every pattern everywhere
 * and the runs differed by RMSE 0.85 at 1 km in low quality; with this, 0.19:
 * test_fetch_runs). lin: the mean slope xy and the step; tot: every pattern's slope variance
 * and the unresolved. */
static void lin_frame(const struct renderer *r, float lin[3], float tot[2])
{
    float var = 0.0f;
    lin[0] = lin[1] = 0.0f;
    tot[0] = r->t->mss_unresolved_x;
    tot[1] = r->t->mss_unresolved_y;
    for (int s = 0; s < r->nfs; s++) {
        const float *m = r->slot[s].top_slope;
        lin[0] += m[0];
        lin[1] += m[1];
        tot[0] += m[2];
        tot[1] += m[3];
        var += fmaxf(m[2], m[3]);
    }
    lin[2] = fmaxf(sqrtf(var), 0.01f);
}

/* The aerial perspective's air mass per metre of path from the camera's height h through the
 * exponential atmosphere, (1 - e^{-h/H}) / h -> 1 / H at the sea (ocean.vert haze_frame). */
static float haze_air_mass(const struct sky_haze *hz, const struct camera *cam)
{
    double h = fmax(cam->pos[2], 0.0), hs = hz->scale_height_m;
    return (float)(h > 1e-3 * hs ? -expm1(-h / hs) / h : (1.0 - 0.5 * h / hs) / hs);
}

/* The camera's altitude for the pixel footprint and one pixel's angle, rad (camera.h). */
static void view_scale(const struct camera_frame *view, float *alt, float *pix)
{
    *alt = (float)view->footprint_alt_m;
    *pix = view->pixel_rad;
}

/* This frame's values for the terms of the vertex alone: vshade.c takes them on gles2-min, the
 * programs (ocean.vert's vterms.glsl, and ocean.frag some of them) as uniforms. */
static void vertex_frame(struct renderer *r, const struct camera_frame *view)
{
    const struct camera *cam = &view->cam;
    struct vshade_frame *f = &r->vf;
    float alt, pix;
    memset(f, 0, sizeof(*f));
    lin_frame(r, f->lin_s0, f->total_var);
    memcpy(f->sun_dir, r->sky.sun_dir, sizeof(f->sun_dir));
    f->fresnel_uv_scale[0] = (float)r->fresnel->width / (float)r->atlas_w;
    f->fresnel_uv_scale[1] = (float)r->fresnel->height / (float)r->atlas_h;
    f->sky_map_size = (float)r->sky.size;
    view_scale(view, &alt, &pix);
    f->lod_frame[0] = alt * alt;
    f->lod_frame[1] = log2f(pix / alt);
    memcpy(f->haze_tau, r->haze.tau_ext, sizeof(f->haze_tau));
    f->haze_frame[0] = haze_air_mass(&r->haze, cam);
    f->haze_frame[1] = r->haze.mie_g;
    memcpy(f->haze_ray, r->haze.ray, sizeof(f->haze_ray));
    memcpy(f->haze_mie, r->haze.mie, sizeof(f->haze_mie));
    f->fog = r->d.quality != QUALITY_HIGH;
}

/* Uniforms of the variant fetching the first k slots' slopes and the first kw's whitecaps;
 * the rest enter as their patches' constants. */
static void set_ocean_uniforms(struct renderer *r, int k, int kw, const struct camera_frame *view)
{
    const struct camera *cam = &view->cam;
    const GLint *u = r->ou[VARIANT(k, kw)];
    if (r->vtf)
        set_vtf_uniforms(r, VARIANT(k, kw), cam);
    float off[SWELL_MAX_PATTERNS][2] = { { 0 } }, inv[SWELL_MAX_PATTERNS] = { 0 };
    float ss[SWELL_MAX_PATTERNS][4] = { { 0 } }, sb[SWELL_MAX_PATTERNS][4] = { { 0 } };
    float ws[SWELL_MAX_PATTERNS][4] = { { 0 } }, wb[SWELL_MAX_PATTERNS][4] = { { 0 } };
    float cs[4] = { 0.0f, 0.0f, 0.0f, 0.0f }, ck[2] = { 0.0f, 0.0f };
    float dsh[SWELL_MAX_PATTERNS][3] = { { 0 } };
    float sun[3], sea[3], foam[3], sea_sun[3], foam_sun[3], e = r->exposure;
    float unres[2] = { r->t->mss_unresolved_x, r->t->mss_unresolved_y };
    for (int s = 0; s < r->nfs; s++) {
        struct fs_slot *sl = &r->slot[s];
        if (s >= k) {
            /* const_slope.xy stays 0: the means are in lin_s0 (ocean.vert) */
            cs[2] += sl->top_slope[2];
            cs[3] += sl->top_slope[3];
            add_k_constants(r, sl, ck);
            continue;
        }
        grid_uv_offset(r->t, sl->pattern, cam, off[s]);
        inv[s] = 1.0f / r->t->pattern[sl->pattern].size_m;
        detile_camera_shift(sl->pattern, cam->pos[0], cam->pos[1],
                            1.0 / r->t->pattern[sl->pattern].size_m, dsh[s]);
        memcpy(ss[s], sl->slope->scale, sizeof(ss[s]));
        memcpy(sb[s], sl->slope->bias, sizeof(sb[s]));
        memcpy(ws[s], sl->wc->scale, sizeof(ws[s]));
        memcpy(wb[s], sl->wc->bias, sizeof(wb[s]));
        /* channel 2: the loop blend's own variance (stream_blend_whitecap) over level 0's mean
         * within-texel variance c0 (lod.c wc_trust_terms): ocean.frag add_whitecap's c0 */
        ws[s][2] = STREAM_WC_MIX_SCALE(sl->wc->scale[0]);
        wb[s][2] = sl->level_kvar[0];
        bind_tex(r, unit_patterns(r) + s, chain_at(&sl->slope_tex, 0), u[OU_SLOPE_TEX0 + s]);
        if (r->d.quality == QUALITY_HIGH) {
            /* the fetched patch's variance T (and below its foam memory's mean and variance)
             * in the constants: ocean.frag's slot adds only what depends on its taps */
            cs[2] += sl->top_slope[2];
            cs[3] += sl->top_slope[3];
        }
        if (s < kw) {   /* kw <= nwc: whitecap textures exist for these (create_textures) */
            bind_tex(r, unit_patterns(r) + r->nfs + s, chain_at(&sl->wc_tex, 0), u[OU_WC_TEX0 + s]);
            if (r->d.quality == QUALITY_HIGH) {
                ck[0] += sl->top_k[0];
                ck[1] += sl->top_k[1];
            }
        } else {
            add_k_constants(r, sl, ck);
        }
    }
    sea_light(r, sun, sea, foam, sea_sun, foam_sun);
    glUniformMatrix4fv(u[OU_WORLD_TO_CLIP], 1, GL_FALSE, (const GLfloat *)view->world_to_clip);
    glUniform2fv(u[OU_UV_OFFSET], SWELL_MAX_PATTERNS, &off[0][0]);
    glUniform1fv(u[OU_INV_SIZE], SWELL_MAX_PATTERNS, inv);
    glUniform4fv(u[OU_SLOPE_SCALE], SWELL_MAX_PATTERNS, &ss[0][0]);
    glUniform4fv(u[OU_SLOPE_BIAS], SWELL_MAX_PATTERNS, &sb[0][0]);
    glUniform4fv(u[OU_WC_SCALE], SWELL_MAX_PATTERNS, &ws[0][0]);
    glUniform4fv(u[OU_WC_BIAS], SWELL_MAX_PATTERNS, &wb[0][0]);
    glUniform4fv(u[OU_CONST_SLOPE], 1, cs);
    glUniform2fv(u[OU_CONST_K], 1, ck);
    glUniform3fv(u[OU_DETILE_SHIFT], SWELL_MAX_PATTERNS, &dsh[0][0]);
    float atlas[4];
    atlas_hash_frame(r, atlas);
    glUniform4fv(u[OU_DETILE_ATLAS], 1, atlas);
    glUniform2fv(u[OU_FRESNEL_V], 1, r->vf.fresnel_uv_scale);
    /* the same corner as ocean.frag's clamp: a uniform of its own, since one name in both
     * stages would need one precision */
    glUniform2fv(u[OU_FRESNEL_MAX], 1, r->vf.fresnel_uv_scale);
    bind_tex(r, UNIT_FRESNEL, r->fresnel_tex, u[OU_FRESNEL_TEX]);
    bind_tex(r, UNIT_SKY, chain_at(&r->sky_tex, 0), u[OU_SKY_TEX]);
    float sky_scale[3];   /* per channel; the half-float map's is 1 (sky.h) */
    for (int c = 0; c < 3; c++)
        sky_scale[c] = e * (r->sky_half ? 1.0f : r->sky.map_scale[c]);
    glUniform3fv(u[OU_SKY_SCALE], 1, sky_scale);
    glUniform1f(u[OU_SKY_SIZE], r->vf.sky_map_size);
    glUniform1f(u[OU_SKY_INV_SIZE], 1.0f / (float)r->sky.size);
    glUniform1f(u[OU_SKY_LEVEL_SCALE], 255.0f / (float)SKY_LEVEL_ALPHA);
    glUniform1f(u[OU_SKY_TOP], (float)(r->sky.levels - 1));
    glUniform1f(u[OU_SKY_BIAS_MAX], r->gpu->caps.max_lod_bias);
    glUniform3fv(u[OU_SUN_DIR], 1, r->vf.sun_dir);
    {
        /* aerial perspective (vertex_frame's haze terms; the horizon's come from the sky,
         * update_sky_constants). Low quality takes them in ocean.vert, high in ocean.frag:
         * one name serves both, no program has both. */
        const struct sky_haze *hz = &r->haze;
        glUniform3fv(u[OU_HAZE_TAU], 1, r->vf.haze_tau);
        glUniform3fv(u[OU_HAZE_RAY], 1, r->vf.haze_ray);
        glUniform3fv(u[OU_HAZE_MIE], 1, r->vf.haze_mie);
        glUniform2fv(u[OU_HAZE_FRAME], 1, r->vf.haze_frame);
        glUniform3f(u[OU_HAZE_TAU_RATIO], hz->tau_ext[0] / hz->tau_ext[1], 1.0f,
                    hz->tau_ext[2] / hz->tau_ext[1]);
    }
    glUniform3fv(u[OU_SUN_IRR], 1, sun);
    glUniform3fv(u[OU_SEA_RADIANCE], 1, sea);
    glUniform3fv(u[OU_FOAM_RADIANCE], 1, foam);
    glUniform2fv(u[OU_UNRESOLVED], 1, unres);
    glUniform1f(u[OU_EPSILON], r->t->whitecap_epsilon);
    glUniform1f(u[OU_EPSILON_V], r->t->whitecap_epsilon);
    /* the linearisation (lin_frame); the pixel's ds = its fetched slopes' deviations from
     * their patches' means (ocean.frag) */
    glUniform3fv(u[OU_LIN_S0], 1, r->vf.lin_s0);
    glUniform2fv(u[OU_TOTAL_VAR], 1, r->vf.total_var);
    reflect_uniforms(r, u);
    wake_uniforms(r, view, u, foam);
    shadow_uniforms(r, view, u, sea_sun, foam_sun);
    refract_uniforms(r, u);
    mask_uniforms(r, view, u);
}

/* The sea, far rows first, one draw per run of rows fetching the same slots (and, with
 * run_lod, at the same levels). */
static void draw_runs(struct renderer *r, const struct camera_frame *view)
{
    float alt, pix;
    view_scale(view, &alt, &pix);
    int rows = grid_row_count(r->grid), run_first = 0, run_count = 0, run_k = -1, run_kw = -1;
    int run_early = 0;
    uint32_t run_key = 0;
    float run_d2_far = 0.0f, run_d2 = 0.0f;   /* the run's first (farthest) and last rows' */
    int high = r->d.quality == QUALITY_HIGH;
    r->draws = r->draws_wc_const = r->draws_resolved_drop = 0;
    for (int row = 0; row <= rows; row++) {
        int first = 0, count = 0, k = -2, kw = -2, early = 0;
        uint32_t key = 0;
        float d2 = 0.0f;
        if (row < rows) {
            grid_row_span(r->grid, row, &first, &count, &d2);
            if (r->force_variant >= 0) {
                k = VARIANT_K(r->force_variant);
                kw = VARIANT_KW(r->force_variant);
            } else if (r->d.fetch_all) {
                k = r->nfs;
                kw = high ? r->nwc : 0;
            } else {
                k = slots_needed(r, d2, alt, pix, DROP_FOOTPRINT, 1);
                early = k < slots_needed(r, d2, alt, pix, DROP_FOOTPRINT, 0);
                kw = high ? slots_needed(r, d2, alt, pix, WC_DROP(r), 0) : 0;
                kw = kw < r->nwc ? kw : r->nwc;
                kw = kw < k ? kw : k;
            }
            key = run_lod_key(r, row_footprint(d2, alt, pix), k, kw);
        }
        if (k == run_k && kw == run_kw && key == run_key && first == run_first + run_count) {
            run_count += count;
            run_d2 = d2;
            run_early |= early;
            continue;
        }
        if (run_count > 0) {
            if (r->force_variant < 0) {
                /* a variant the driver refused: its rows with the one the probe chose */
                int use = r->variant_use[VARIANT(run_k, run_kw)];
                run_k = VARIANT_K(use);
                run_kw = VARIANT_KW(use);
            }
            glUseProgram(r->ocean[VARIANT(run_k, run_kw)].program);
            set_ocean_uniforms(r, run_k, run_kw, view);
            set_run_lods(r, run_k, run_kw, run_key, run_d2_far, run_d2, alt, pix);
            set_slot_lods(r, run_k, run_kw, run_key, alt, pix,
                   log2f(row_footprint(run_d2_far, alt, pix) * RUN_LOD_ROW_MEAN),
                          log2f(row_footprint(run_d2, alt, pix) * RUN_LOD_ROW_MEAN));
            if (r->d.debug_variants) {
                float c[4];
                variant_colour(VARIANT(run_k, run_kw), c);
                glBlendColor(c[0], c[1], c[2], c[3]);
            }
            glDrawElements(GL_TRIANGLES, run_count, GL_UNSIGNED_SHORT,
                           (const void *)((size_t)run_first * sizeof(uint16_t)));
            r->draws++;
            r->draws_wc_const += run_kw < (run_k < r->nwc ? run_k : r->nwc);
            r->draws_resolved_drop += run_early;
        }
        run_first = first;
        run_count = count;
        run_k = k;
        run_kw = kw;
        run_early = early;
        run_key = key;
        run_d2_far = run_d2 = d2;
    }
}

/* The frame of view v from camera cam (v's, or the one the renderer draws from): the
 * application's matrices, exactly, where it gave them, so it can depth-test against the sea. */
void renderer_view_frame(const struct renderer_view *v, const struct camera *cam,
                         struct camera_frame *view)
{
    camera_frame_make(cam, v->width, v->height, view);
    view->x = v->x;
    view->y = v->y;
    if (v->view) {
        memcpy(view->view_rel, v->view, sizeof view->view_rel);
        view->view_rel[3][0] = view->view_rel[3][1] = view->view_rel[3][2] = 0.0f;
    }
    if (v->proj) {
        memcpy(view->proj, v->proj, sizeof view->proj);
        view->aspect = view->proj[1][1] / view->proj[0][0];
        /* the edges ndc = +-1 of a perspective, off-axis or not: ndc = P00 x / -z - P20, so
         * x / -z = (ndc + P20) / P00 */
        double p0 = view->proj[0][0], p1 = view->proj[1][1];
        double p8 = view->proj[2][0], p9 = view->proj[2][1];
        view->tan_lrbt[0] = (-1.0 + p8) / p0;
        view->tan_lrbt[1] = (1.0 + p8) / p0;
        view->tan_lrbt[2] = (-1.0 + p9) / p1;
        view->tan_lrbt[3] = (1.0 + p9) / p1;
    }
    if (v->view || v->proj)
        glm_mat4_mul(view->proj, view->view_rel, view->world_to_clip);
}

void renderer_frame_view(const struct renderer *r, const struct camera *cam, int width,
                         int height, struct renderer_view *out)
{
    memset(out, 0, sizeof *out);
    out->cam = *cam;
    out->width = width;
    out->height = height;
    out->flags = RENDERER_CLEAR | (r->d.no_sky ? 0 : RENDERER_SKY);
    /* the program's own projection: no wider than the grid covers (an embedding application
     * brings its own, renderer_draw) */
    out->cam.fov_y_deg = camera_fov_covered(cam->fov_y_deg,
                                            height > 0 ? (float)width / (float)height : 1.0f);
}

int renderer_frame(struct renderer *r, const struct camera *user_cam, double t_s, int width,
                   int height, struct swell_err *err)
{
    struct renderer_view v;
    renderer_frame_view(r, user_cam, width, height, &v);
    return renderer_draw(r, &v, t_s, err);
}

int renderer_draw(struct renderer *r, const struct renderer_view *v, double t_s,
                  struct swell_err *err)
{
    const struct camera *user_cam = &v->cam;
    int width = v->width, height = v->height;
    /* uploads bind on the active unit: one of the renderer's, never the application's */
    glActiveTexture(GL_TEXTURE0 + (GLenum)r->d.texture_unit_first);
    /* The camera floats CAMERA_CLEARANCE_M above the surface the renderer draws under it (the
     * same displacement, sea.h), so no view is from under the water; the projected grid's
     * coverage argument (grid.c) rests on it. */
    struct camera cam_local = *user_cam;
    const struct camera *cam = &cam_local;
    cam_local.surface_z_m = sea_surface_height(r->t, renderer_detile(r), user_cam->pos[0],
                                             user_cam->pos[1], t_s) *
                            mask_amp_at(r, user_cam->pos[0], user_cam->pos[1]) +
                            wake_height_at(r, user_cam->pos[0], user_cam->pos[1], 0.0f);
    r->camera_raise_m = 0.0;
    if (cam_local.pos[2] < cam_local.surface_z_m + CAMERA_CLEARANCE_M) {
        r->camera_raise_m = cam_local.surface_z_m + CAMERA_CLEARANCE_M - cam_local.pos[2];
        cam_local.pos[2] = cam_local.surface_z_m + CAMERA_CLEARANCE_M;
    }
    GLint depth_bits = 0;
    int nidx;
    size_t vbytes = sizeof(float) * (r->cpu_vterms ? VSHADE_FLOATS : GRID_FLOATS) *
                    (size_t)grid_vertex_count(r->grid);
    struct camera_frame view;
    renderer_view_frame(v, cam, &view);
    stream_textures(r, t_s);
    vertex_frame(r, &view);   /* after the slots' constants of this loop phase */
    if (r->vtf) {
        nidx = grid_projection(r->grid, &view, &r->proj);
        stream_disp(r, t_s);
    } else {
        wake_grid(r, view.cam.pos, r->grid);
        mask_grid(r, r->grid);
        nidx = grid_update(r->grid, &view, t_s, r->verts);
        if (nidx > 0 && r->cpu_vterms)   /* the terms of each vertex, on the CPU (vshade.h) */
            vshade_fill(&r->vf, r->verts, grid_vertex_count(r->grid), r->shaded);
    }

    glViewport(v->x, v->y, width, height);
    glGetIntegerv(GL_DEPTH_BITS, &depth_bits);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_TRUE);
    if (v->flags & RENDERER_CLEAR) {
        if (r->probing)
            glClearColor(0.0f, 0.0f, 0.0f, 0.0f);   /* the probe counts what the sea writes */
        else if (r->d.debug_variants)
            glClearColor(1.0f, 1.0f, 1.0f, 1.0f);   /* variant_colour's white */
        else if (r->d.debug_uncovered)
            glClearColor(1.0f, 0.0f, 1.0f, 1.0f);   /* magenta: any pixel left is a bug */
        else
            glClearColor(0.02f, 0.05f, 0.07f, 1.0f);
        glEnable(GL_SCISSOR_TEST);   /* the viewport alone: an application's frame keeps the rest */
        glScissor(v->x, v->y, width, height);
        glClear(GL_COLOR_BUFFER_BIT | (depth_bits > 0 ? GL_DEPTH_BUFFER_BIT : 0));
        glDisable(GL_SCISSOR_TEST);
    }
    int rc;
    if ((v->flags & RENDERER_SKY) && !r->d.debug_variants && r->probing != 1 &&
        (rc = draw_sky(r, &view, err)))
        return rc;
    if (nidx > 0 && r->probing != 2) {
        /* Rows are ordered far to near, so without a depth buffer the painter's order holds. */
        if (depth_bits > 0) {
            glEnable(GL_DEPTH_TEST);
            glDepthFunc(GL_LEQUAL);
        }
        glBindBuffer(GL_ARRAY_BUFFER, r->vbo);
        if (r->vtf) {
            glEnableVertexAttribArray(A_GRID);
            glVertexAttribPointer(A_GRID, 2, GL_FLOAT, GL_FALSE, 0, (const void *)0);
        } else if (r->cpu_vterms) {
            glBufferSubData(GL_ARRAY_BUFFER, 0, (GLsizeiptr)vbytes, r->shaded);
            /* vshade.h: eight vec4 in order */
            for (int a = 0; a < A_COUNT; a++) {
                glEnableVertexAttribArray((GLuint)a);
                glVertexAttribPointer((GLuint)a, 4, GL_FLOAT, GL_FALSE,
                                      VSHADE_FLOATS * sizeof(float),
                                      (const void *)(4 * (size_t)a * sizeof(float)));
            }
        } else {
            glBufferSubData(GL_ARRAY_BUFFER, 0, (GLsizeiptr)vbytes, r->verts);
            static const struct { int loc, size, off; } grid_attr[A_GRID_COUNT] = {
                { A_POS, 3, GRID_A_POS }, { A_REST, 2, GRID_A_REST },
                { A_GEO_SLOPE, 4, GRID_A_SLOPE }, { A_GEO_K, 3, GRID_A_K }  /* k; the mask */
            };
            for (int a = 0; a < A_GRID_COUNT; a++) {
                glEnableVertexAttribArray((GLuint)grid_attr[a].loc);
                glVertexAttribPointer((GLuint)grid_attr[a].loc, grid_attr[a].size, GL_FLOAT,
                                      GL_FALSE, GRID_FLOATS * sizeof(float),
                                      (const void *)(grid_attr[a].off * sizeof(float)));
            }
        }
        glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, r->ibo);
        if (r->d.debug_variants && !r->probing) {
            glEnable(GL_BLEND);
            glBlendFunc(GL_ZERO, GL_CONSTANT_COLOR);
        }
        draw_runs(r, &view);
        r->refl_ready = r->shadow_ready = r->refr_ready = 0;   /* a pass serves the draw
                                                                * after it */
        glDisable(GL_BLEND);
        for (int a = 0; a < A_COUNT; a++)
            glDisableVertexAttribArray((GLuint)a);
        glDisable(GL_DEPTH_TEST);
    }
    glActiveTexture(GL_TEXTURE0 + (GLenum)r->d.texture_unit_first);
    return gpu_check("renderer_frame", err);
}
