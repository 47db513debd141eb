/* sky_draw.c - the sky on the GPU (render/internal.h): the stereographic sky map baked by
 * optics/sky.c uploaded as a mip atlas (the approximately filtered sky, Bruneton §4.2), the
 * exposure and haze constants, the table of background gains by elevation from the camera's
 * altitude, and the background sky mesh with the sun's disc drawn before the sea.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "render/internal.h"

/* With run_lod the sky map's levels sit in one texture without mips, twice as wide as high
 * (SWELL_RUN_LOD in ocean.frag reads two neighbouring levels of it per pixel and blends them,
 * set_run_lods): level 0 at the right, level l >= 1 of side n at x = 0, y = n - 1, so the
 * coarse levels lie near the origin. A coarse texel spans many pixels at the horizon, and
 * gles2-min's mediump coordinates are finest near 0: with the coarse levels at u >= 1/2 and v
 * near 1 a fetch moved in quarter texels there, and the sea below the horizon drew wedges of
 * constant colour (calm, 3 m up, gles2-min on llvmpipe; test_render test_low_sun_horizon).
 * Returns the level's side, texels. */
int sky_atlas_at(int size, int l, int *x, int *y)
{
    int n = size >> l > 0 ? size >> l : 1;
    *x = l == 0 ? size : 0;
    *y = l == 0 ? 0 : n - 1;
    return n;
}

/* The HDR sky map of high quality: half-float radiances where the tier has half-float
 * textures (no 8-bit steps in the dark zenith), else RGBA8 times sky.map_scale. */
int upload_sky(struct renderer *r, const struct sky *sk, struct swell_err *err)
{
    if (r->run_lod) {
        GLenum type = r->sky_half ? gpu_half_type(r->gpu) : GL_UNSIGNED_BYTE;
        glBindTexture(GL_TEXTURE_2D, r->sky_tex.tex[0]);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
        for (int l = 0; l < sk->levels; l++) {
            int x, y, n = sky_atlas_at(sk->size, l, &x, &y);
            size_t off = sky_level_offset(sk, l);
            const void *px = r->sky_half ? (const void *)(sk->half + off)
                                         : (const void *)(sk->data + off);
            glTexSubImage2D(GL_TEXTURE_2D, 0, x, y, n, n, GL_RGBA, type, px);
        }
        return gpu_check("renderer: sky atlas upload", err);
    }
    if (r->sky_half)
        return upload_chain_typed(&r->sky_tex, sk->size, sk->size, sk->levels, sk->half,
                           gpu_half_type(r->gpu), "renderer: sky upload (half)", err);
    return upload_chain(&r->sky_tex, sk->size, sk->size, sk->levels, sk->data,
                 "renderer: sky upload", err);
}

static uint8_t unorm8(float x)
{
    return (uint8_t)lrintf(255.0f * fminf(fmaxf(x, 0.0f), 1.0f));
}

int create_sky_mesh(struct renderer *r, struct swell_err *err)
{
    float v[SKY_MESH_W * SKY_MESH_H * 2];
    uint16_t idx[(SKY_MESH_W - 1) * (SKY_MESH_H - 1) * 6];
    int n = 0, rc;
    for (int j = 0; j < SKY_MESH_H; j++)
        for (int i = 0; i < SKY_MESH_W; i++) {
            v[2 * (j * SKY_MESH_W + i)] = -1.0f + 2.0f * (float)i / (SKY_MESH_W - 1);
            v[2 * (j * SKY_MESH_W + i) + 1] = -1.0f + 2.0f * (float)j / (SKY_MESH_H - 1);
        }
    for (int j = 0; j + 1 < SKY_MESH_H; j++)
        for (int i = 0; i + 1 < SKY_MESH_W; i++) {
            uint16_t a = (uint16_t)(j * SKY_MESH_W + i), b = (uint16_t)(a + 1);
            uint16_t c = (uint16_t)(a + SKY_MESH_W), d = (uint16_t)(c + 1);
            idx[n++] = a; idx[n++] = b; idx[n++] = c;
            idx[n++] = b; idx[n++] = d; idx[n++] = c;
        }
    if ((rc = gpu_buffer_create(r->gpu, GL_ARRAY_BUFFER, sizeof(v), GL_STATIC_DRAW,
                                "renderer: sky mesh", &r->sky_vbo, err)) ||
        (rc = gpu_buffer_create(r->gpu, GL_ELEMENT_ARRAY_BUFFER, sizeof(idx), GL_STATIC_DRAW,
                                "renderer: sky mesh indices", &r->sky_ibo, err)))
        return rc;
    glBindBuffer(GL_ARRAY_BUFFER, r->sky_vbo);
    glBufferSubData(GL_ARRAY_BUFFER, 0, sizeof(v), v);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, r->sky_ibo);
    glBufferSubData(GL_ELEMENT_ARRAY_BUFFER, 0, sizeof(idx), idx);
    return 0;
}

/* What follows from a new sky. Automatic exposure: the sky's mean radiance E_sky / pi maps to
 * x = 0.5, Reinhard 0.33 before gamma (0.58 after), which leaves headroom for the brighter
 * horizon and the glint. The haze (sky_haze), its radiances scaled by that exposure. */
void update_sky_constants(struct renderer *r)
{
    if (r->d.exposure > 0.0f) {
        r->exposure = r->d.exposure;
    } else {
        float e = 0.2f * r->sky.sky_irr[0] + 0.7f * r->sky.sky_irr[1] + 0.1f * r->sky.sky_irr[2];
        r->exposure = 0.5f * (float)M_PI / (e > 1e-4f ? e : 1e-4f);
    }
    sky_haze(&r->sky, &r->haze);
    for (int c = 0; c < 3; c++) {
        r->haze.ray[c] *= r->exposure;
        r->haze.mie[c] *= r->exposure;
    }
    r->sky_view_alt = NAN;   /* the background's table follows the sky */
}

/* The background's table for a camera alt_m up (see SKY_VIEW_N), and the sun's transmittance
 * from there (the disc is the unattenuated sun above the air). */
static int update_sky_view(struct renderer *r, double alt_m, struct swell_err *err)
{
    float g[2][3 * SKY_VIEW_N];
    sky_view_gains(&r->sky, alt_m, SKY_VIEW_N, g[0], g[1]);
    for (int row = 0; row < 2; row++)
        for (int c = 0; c < 3; c++) {
            float m = 1e-30f;
            for (int k = 0; k < SKY_VIEW_N; k++)
                m = fmaxf(m, g[row][3 * k + c]);
            r->sky_view_scale[row][c] = m * r->exposure;
            for (int k = 0; k < SKY_VIEW_N; k++)
                r->scratch[4 * (row * SKY_VIEW_N + k) + c] = unorm8(g[row][3 * k + c] / m);
        }
    for (int k = 0; k < 2 * SKY_VIEW_N; k++)
        r->scratch[4 * k + 3] = 255;
    float e_sun = asinf(fminf(fmaxf(r->sky.sun_dir[2], -1.0f), 1.0f));
    float o3[3];
    sky_transmittance(sky_view_air_mass(alt_m, e_sun), r->sky_view_sun);
    sky_ozone_transmittance(e_sun, o3);
    for (int c = 0; c < 3; c++)
        r->sky_view_sun[c] *= o3[c];
    for (int c = 0; c < 3; c++)
        if (!(r->sky.sun_irr[c] > 0.0f))
            r->sky_view_sun[c] = 0.0f;   /* below the horizon (sky_bake) */
    r->sky_view_alt = alt_m;
    return upload_single(r->sky_view_tex, SKY_VIEW_N, 2, r->scratch,
                  "renderer: background sky upload", err);
}


/* The sphere's horizon at azimuth a (dip below the level) in NDC: 1 and its y when it is in
 * front and within the screen's width. */
static int horizon_ndc(mat4 world_to_clip, double dip, float a, float *y)
{
    vec4 dir = { (float)cos(dip) * cosf(a), (float)cos(dip) * sinf(a), (float)-sin(dip), 0.0f },
         clip;
    glm_mat4_mulv(world_to_clip, dir, clip);
    if (!(clip[3] > 0.0f && fabsf(clip[0]) <= clip[3]))
        return 0;
    *y = clip[1] / clip[3];
    return 1;
}

/* The sky is drawn only above the horizon (a scissor from just below the horizon's row up):
 * below it the sea covers every pixel, and a full-screen sky pass there was pure overdraw. */
int draw_sky(struct renderer *r, const struct camera_frame *view, struct swell_err *err)
{
    const struct camera *cam = &view->cam;
    int width = view->width, height = view->height;
    mat4 world_to_clip;
    glm_mat4_copy((vec4 *)view->world_to_clip, world_to_clip);
    mat4 inv;
    float h = cam->heading_deg * (float)(M_PI / 180.0);
    /* the sphere's horizon, a circle acos(R / (R + alt)) below the level (camera.h): its lowest
     * row on screen, over the azimuths of the front half (from high up it bends down towards
     * the sides, and a row through its middle left the corners to neither sky nor sea) */
    double alt = fmax(cam->pos[2], 0.0);
    double dip = acos(EARTH_RADIUS_M / (EARTH_RADIUS_M + alt));
    float hz = 2.0f;   /* NDC y of the lowest horizon point in view */
    float prev_a = 0.0f;
    int prev_in = 0;
    for (int k = 0; k <= 64; k++) {
        float a = h + (float)M_PI * ((float)k / 64.0f - 0.5f), y;
        int in = horizon_ndc(world_to_clip, dip, a, &y);
        if (in)
            hz = fminf(hz, y);
        /* where the curve leaves the screen between two samples it may still be falling (a
         * panoramic view from high up): its row at the screen's edge, found by bisection */
        if (k > 0 && in != prev_in) {
            float lo = in ? prev_a : a, hi = in ? a : prev_a;   /* lo out, hi in */
            for (int it = 0; it < 24; it++) {
                float mid = 0.5f * (lo + hi);
                if (horizon_ndc(world_to_clip, dip, mid, &y))
                    hi = mid;
                else
                    lo = mid;
            }
            if (horizon_ndc(world_to_clip, dip, hi, &y))
                hz = fminf(hz, y);
        }
        prev_a = a;
        prev_in = in;
    }
    if (hz > 1.5f || view->up[2] <= 0.0)
        hz = -1.0f;   /* no horizon in view, or the view rolled upside down (the sky below the
                       * horizon on screen): the sky pass everywhere */
    int y0 = (int)floorf((0.5f * (hz - 0.1f) + 0.5f) * (float)height);
    if (y0 >= height)
        return 0;
    if (isnan(r->sky_view_alt) ||
        fabs(alt - r->sky_view_alt) > SKY_VIEW_DALT_M + SKY_VIEW_DALT_REL * alt) {
        int rc = update_sky_view(r, alt, err);
        if (rc)
            return rc;
    }
    if (y0 < 0)
        y0 = 0;
    glEnable(GL_SCISSOR_TEST);
    glScissor(view->x, view->y + y0, width, height - y0);
    glm_mat4_inv(world_to_clip, inv);
    glUseProgram(r->skyp.program);
    glUniformMatrix4fv(r->su[SU_CLIP_TO_WORLD], 1, GL_FALSE, (const GLfloat *)inv);
    glUniform3fv(r->su[SU_SKY_VIEW_SCALE], 2, &r->sky_view_scale[0][0]);
    glUniform4f(r->su[SU_SKY_SUN], r->sky.sun_dir[0], r->sky.sun_dir[1], r->sky.sun_dir[2],
                r->haze.mie_g);
    bind_tex(r, UNIT_SKY, r->sky_view_tex, r->su[SU_SKY_VIEW]);
    glBindBuffer(GL_ARRAY_BUFFER, r->sky_vbo);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, r->sky_ibo);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, (const void *)0);
    glDrawElements(GL_TRIANGLES, (SKY_MESH_W - 1) * (SKY_MESH_H - 1) * 6, GL_UNSIGNED_SHORT,
                   (const void *)0);
    /* The sun disc, where it is above the horizon and in front: a quad around the direction's
     * projection (the sea, drawn next, hides whatever of it is below the horizon). Its colour:
     * E_sun over the disc's solid angle (6.8e-5 sr), tone-mapped. */
    const float *sd = r->sky.sun_dir;
    vec4 dir = { sd[0], sd[1], sd[2], 0.0f }, clip;
    glm_mat4_mulv(world_to_clip, dir, clip);
    if (sd[2] > 0.0f && clip[3] > 0.0f) {
        float sun_disp[3];
        const vec4 *proj = view->proj;
        /* radius: the disc's angle times the projection's scale (small-angle, near the axis) */
        float ndc[4] = { clip[0] / clip[3], clip[1] / clip[3], SUN_RADIUS_RAD * proj[0][0],
                         SUN_RADIUS_RAD * proj[1][1] };
        float sun_rad[3];
        for (int c = 0; c < 3; c++)
            sun_rad[c] = r->exposure * r->sky_view_sun[c] / 6.8e-5f;
        if (r->d.linear_output)
            for (int c = 0; c < 3; c++)
                sun_disp[c] = fminf(sun_rad[c], 1.0e4f);  /* as tone_map's linear output */
        else
            tone_map_rgb(sun_rad, sun_disp);
        glUseProgram(r->sunp.program);
        glUniform4fv(r->sunu[SU_SUN_NDC], 1, ndc);
        glUniform3fv(r->sunu[SU_SUN_DISPLAY], 1, sun_disp);
        glBindBuffer(GL_ARRAY_BUFFER, r->quad_vbo);
        glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, (const void *)0);
        glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    }
    glDisableVertexAttribArray(0);
    glDisable(GL_SCISSOR_TEST);
    return 0;
}
