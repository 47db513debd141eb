/* reflect.c - local reflections of the application's objects (issue 18; Hu et al. 2006 §2.2,
 * §5.2; Bruneton et al. 2010 §6): the reflection target the application draws its objects into,
 * mirrored in the mean sea plane, and what ocean.frag needs to read it.
 *
 * Hu renders the objects above the water mirrored into a screen-space texture and reads it by
 * projective texture mapping, the coordinates shifted by an ad-hoc scale of the bump. Bruneton
 * §6 filters the same map with the sky's fast environment lighting (eq. 27) through a mapping U
 * from microfacet slopes to map coordinates. This is that mapping: ocean.frag has the reflected
 * ray of its slope already, as the sky map's stereographic uv (common.glsl sky_map_uv); the ray
 * mirrored in the sea plane is a direction the camera sees, and the pass's projection takes it
 * to the map (refl_mat). On a flat sea that direction is the pixel's own view ray, so the
 * reflection lies exactly under its object; on waves it moves with the slope as a reflection
 * of something far away does, times the parallax factor of the objects' distance (ocean.frag).
 * The filter is eq. 27's: a footprint of 2 sigma du/dzeta. gles2-min has no explicit LOD, and
 * the implicit one follows the waves' detail from pixel to pixel (a reflected ray's map
 * position jumps with the slope): read by it, the map's coarse levels smeared an object's
 * colour over the whole sea. So the map's levels are copied into an atlas without mips
 * (reflect_atlas, as sky_run reads the sky on software rasterisers), and ocean.frag blends the
 * levels around the footprint there, each fetched bilinearly at its own level.
 *
 * Eq. 27's footprint is an ellipse: a slope turns the reflected ray by twice its angle in the
 * plane of incidence, across it by sin(depression) times that, so a reflection is a streak
 * along the view, the longer the lower the view (6:1 at 10 degrees). GLES 2 has no
 * anisotropic fetch; a mip level wide enough for the long axis blurred an object's reflection
 * across the view 5-6x wider than eq. 27 says (test_reflect test_blur_width). So the atlas
 * holds a ripmap's column for each level l of the chain: versions halved along the map's
 * vertical only, m = 0..REFL_RIP_M times (each a box of 2^m rows of level l), and ocean.frag
 * takes the level across from the ellipse's width and m from its length: four fetches.
 * Layout (w x 3h): level l's column at x = 0 for l = 0, w (1 - 2^(1 - l)) for l >= 1; at y = 0
 * for l = 0, 2h for l >= 1, plus 2 (h >> l) (1 - 2^-m) for version m.
 */
#include <math.h>
#include <string.h>
#include "render/internal.h"


/* The atlas of the map's levels (w x 3h RGBA8), the renderer's share. */
static uint64_t atlas_bytes(int w, int h)
{
    return (uint64_t)w * (uint64_t)h * 12u;
}

/* log2 of a power of two */
static int log2i(int n)
{
    int l = 0;
    while ((1 << (l + 1)) <= n)
        l++;
    return l;
}

static void release_target(struct renderer *r)
{
    if (r->refl.w)
        r->gpu_bytes -= atlas_bytes(r->refl.w, r->refl.h);
    if (r->refl_atlas_fbo)
        glDeleteFramebuffers(1, &r->refl_atlas_fbo);
    r->refl_atlas_fbo = 0;
    gpu_texture_destroy(r->gpu, &r->refl_atlas);
    pass_target_destroy(r, &r->refl);
}

void reflect_destroy(struct renderer *r)
{
    release_target(r);
    gpu_texture_destroy(r->gpu, &r->refl_none);
    shader_program_destroy(&r->refl_copy);
}

/* the probe's draw: the copy's largest version (its eight taps) over the transparent map, from
 * a client-side quad (the renderer's buffers come later) */
static void probe_copy(void *ctx)
{
    static const float quad[8] = { -1.0f, -1.0f, 1.0f, -1.0f, -1.0f, 1.0f, 1.0f, 1.0f };
    struct renderer *r = ctx;
    glActiveTexture(GL_TEXTURE0 + (GLenum)(r->d.texture_unit_first + UNIT_REFLECT));
    glBindTexture(GL_TEXTURE_2D, r->refl_none);
    glDisable(GL_BLEND);
    glDisable(GL_DEPTH_TEST);
    glUseProgram(r->refl_copy.program);
    glUniform1i(r->refl_copy_u[0], r->d.texture_unit_first + UNIT_REFLECT);
    glUniform2f(r->refl_copy_u[1], 1.0f / 16.0f, (float)(1 << (REFL_RIP_M - 1)));
    glUniform1f(r->refl_copy_u[2], -(float)REFL_RIP_M);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, quad);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    glDisableVertexAttribArray(0);
}

/* The atlas's copy drawn once into a probe target, so a driver that refuses it says so at
 * creation (SWELL_E_SHADER: renderer_open then makes the sea without the objects' passes);
 * labelled for tools/devices.py as the ocean's probe is. */
static int reflect_probe(struct renderer *r, struct swell_err *err)
{
    if (!gpu_probe_draw("reflection copy objects", 16, probe_copy, NULL, r))
        return swell_fail(err, SWELL_E_SHADER, "renderer: the driver does not run the reflection "
                          "atlas's copy (shaders_gles/refl_copy.frag; its messages are above)");
    return 0;
}

/* The atlas's copy (probed) and the 1x1 transparent map a draw reads when no pass was drawn
 * for it. */
int reflect_create(struct renderer *r, struct swell_err *err)
{
    static const char *const names[3] = { "frame_tex", "copy_step", "copy_bias" };
    static const struct shader_attrib attribs[1] = { { "a_ndc", 0 } };
    if (!r->d.reflections)
        return 0;
    /* the atlas's copy: upscale.vert, refl_copy.frag (a box of rows of one level) */
    struct shader_desc sd = {
        .dir = r->d.shader_dir, .vs_file = "upscale.vert", .fs_file = "refl_copy.frag",
        .caps = &r->gpu->caps, .uniform_names = names, .uniform_count = 3,
        .uniform_locations = r->refl_copy_u, .attribs = attribs, .attrib_count = 1,
    };
    int rc = shader_program_build(&sd, &r->refl_copy, err);
    if (rc || (rc = pass_none_create(r, &r->refl_none, "reflection (none)", err)))
        return rc;
    return reflect_probe(r, err);
}

static int ensure_target(struct renderer *r, int vw, int vh, struct swell_err *err)
{
    int w, h;
    pass_target_size(vw, vh, &w, &h);
    if (r->refl.fbo && w == r->refl.w && h == r->refl.h)
        return 0;
    release_target(r);
    int rc = pass_target_create(r, &r->refl, w, h, 1, UNIT_REFLECT, "reflection map", err);
    if (rc)
        return rc;
    rc = gpu_texture_create(r->gpu, w, 3 * h, 1, FORMAT_RGBA8, 0, "reflection atlas",
                            &r->refl_atlas, err);
    if (rc) {
        pass_target_destroy(r, &r->refl);
        return rc;
    }
    r->gpu_bytes += atlas_bytes(w, h);
    glGenFramebuffers(1, &r->refl_atlas_fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, r->refl_atlas_fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, r->refl_atlas,
                           0);
    GLenum st = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    if (st != GL_FRAMEBUFFER_COMPLETE) {
        release_target(r);
        return swell_fail(err, SWELL_E_GL, "renderer: the reflection atlas %dx%d (RGBA8) is not "
                          "complete on this device (status 0x%x)", w, 3 * h, st);
    }
    return gpu_check("renderer: reflection target", err);
}

int renderer_reflection_begin(struct renderer *r, const struct renderer_view *v,
                              const struct renderer_reflection *d, struct renderer_pass *out,
                              struct swell_err *err)
{
    if (r->objects_refused)
        return renderer_objects_refused(r, "reflection target", err);
    if (!r->d.reflections)
        return swell_fail(err, SWELL_E_ARG, "renderer: no reflection target: create the ocean "
                          "with reflections = 1");
    if (pass_open(r))
        return swell_fail(err, SWELL_E_ARG, "renderer: a pass is open already: end it first");
    if (d && (!(d->distance_m >= 0.0f) || !isfinite(d->distance_m)))
        return swell_fail(err, SWELL_E_ARG, "renderer: the reflected objects' distance %g m "
                          "must be finite and >= 0 (0: far away)", (double)d->distance_m);
    struct camera_frame view;
    renderer_view_frame(v, &v->cam, &view);
    pass_save(&r->refl_saved);
    int rc = ensure_target(r, v->width, v->height, err);
    if (rc) {   /* the application's state as it was */
        pass_restore(&r->refl_saved);
        return rc;
    }

    /* the view mirrored: eye = V S (p - S c) = V (S p - c), S = diag(1, 1, -1) */
    memset(out, 0, sizeof *out);
    const float *vr = &view.view_rel[0][0], *pr = &view.proj[0][0];
    memcpy(out->view, vr, sizeof out->view);
    for (int k = 0; k < 3; k++)
        out->view[8 + k] = -vr[8 + k];
    out->view[12] = out->view[13] = out->view[14] = 0.0f;
    out->camera_pos[0] = v->cam.pos[0];
    out->camera_pos[1] = v->cam.pos[1];
    out->camera_pos[2] = -v->cam.pos[2];
    memcpy(out->proj, pr, sizeof out->proj);
    pass_widen(out->proj);
    double cz = v->cam.pos[2] > 0.01 ? v->cam.pos[2] : 0.01;
    /* what lies below the sea plane is not reflected: in the mirrored scene, what is above it,
     * z' > 0, i.e. with q the mirrored point less the camera, -(q_z + c_z) >= 0 kept. In the
     * eye frame the plane's normal is V (0, 0, -1). */
    double plane[4] = { -vr[8], -vr[9], -vr[10], -cz };
    pass_oblique_near(out->proj, plane);
    out->viewport[2] = r->refl.w;
    out->viewport[3] = r->refl.h;

    /* ocean.frag: the reflected ray r, mirrored (S r), in the eye frame (V), to the map's uv
     * times w: u w = (P00 e_x + P20 e_z - e_z) / 2, v w = (P11 e_y + P21 e_z - e_z) / 2,
     * w = -e_z, P the pass's (pass_widen) */
    for (int k = 0; k < 3; k++) {
        float s = k == 2 ? -1.0f : 1.0f;
        float ex = vr[4 * k + 0] * s, ey = vr[4 * k + 1] * s, ez = vr[4 * k + 2] * s;
        r->refl_mat[3 * k + 0] = 0.5f * (out->proj[0] * ex + out->proj[8] * ez - ez);
        r->refl_mat[3 * k + 1] = 0.5f * (out->proj[5] * ey + out->proj[9] * ez - ez);
        r->refl_mat[3 * k + 2] = -ez;
    }
    /* eq. 27's footprint: a slope deviation sigma turns the reflected ray by 2 sigma, an
     * angle the map sees as 2 sigma P h / 2 = sigma P h texels at its centre (P00 w across,
     * P11 h along: the pass's projection, the map's size); ocean.frag takes twice that (the
     * level whose kernel has that deviation, log2 of twice it) */
    r->refl_blur[0] = 2.0f * out->proj[0] * (float)r->refl.w;
    r->refl_blur[1] = 2.0f * out->proj[5] * (float)r->refl.h;
    /* gl_FragCoord to the flat sea's map uv, 0.5 + ndc / (2 m) */
    pass_screen_uv(v, r->refl_screen);
    /* gl_FragCoord to the eye-frame view ray ((ndc_x + P20) / P00, (ndc_y + P21) / P11, -1),
     * and world -z in
     * the eye frame (the third row of the rotation, negated): its dot with the ray over the
     * ray's length is the sine of the depression, c / D */
    r->refl_ray[0] = 2.0f / ((float)v->width * pr[0]);
    r->refl_ray[1] = 2.0f / ((float)v->height * pr[5]);
    r->refl_ray[2] = -(1.0f + 2.0f * (float)v->x / (float)v->width - pr[8]) / pr[0];
    r->refl_ray[3] = -(1.0f + 2.0f * (float)v->y / (float)v->height - pr[9]) / pr[5];
    for (int i = 0; i < 3; i++)
        r->refl_down[i] = -vr[8 + i];   /* -V (0, 0, 1)^T's row: world z of an eye vector */
    /* c / D_o, 0 for objects at infinity (ocean.frag's parallax factor) */
    r->refl_down[3] = d && d->distance_m > 0.0f ? (float)(cz / d->distance_m) : 0.0f;
    /* the map's vertical: world z in the eye frame, its direction on the screen at the
     * centre (rolled views turn it); ocean.frag takes its components' squares */
    float tx = vr[8], ty = vr[9], tl = tx * tx + ty * ty;
    if (!(tl > 0.0f)) {
        tx = 0.0f;
        ty = tl = 1.0f;
    }
    r->refl_axes[0] = tx * tx / tl;
    r->refl_axes[1] = ty * ty / tl;

    pass_target_bind(&r->refl);
    glFrontFace(GL_CW);   /* the mirror turns every triangle's winding */
    r->refl_active = 1;
    r->refl_ready = 0;
    return gpu_check("renderer: reflection pass", err);
}

int renderer_reflection_end(struct renderer *r, struct swell_err *err)
{
    if (!r->refl_active)
        return swell_fail(err, SWELL_E_ARG, "renderer: no reflection pass is open: begin one "
                          "first");
    r->refl_active = 0;
    /* the mip chain, then its levels into the atlas (the layout above). Each version (l, m) is
     * drawn at its own size, w >> l by h >> (l + m), over fetches of the chain whose implicit
     * LOD is then l + m, biased by -m to l, each the mean of two of its rows (at their
     * boundary), 2^(m - 1) of them (one at m = 0: the row itself). State the copy changes and the
     * application's may hold (program, buffer, attribute 0, blend, depth, cull, the unit's
     * binding) is the caller's to restore (api_ocean.c). */
    glActiveTexture(GL_TEXTURE0 + (GLenum)(r->d.texture_unit_first + UNIT_REFLECT));
    glBindTexture(GL_TEXTURE_2D, r->refl.tex);
    glGenerateMipmap(GL_TEXTURE_2D);
    pass_quad_begin(r, r->refl_atlas_fbo, r->refl_copy.program);
    glUniform1i(r->refl_copy_u[0], r->d.texture_unit_first + UNIT_REFLECT);
    int top = log2i(r->refl.h);   /* versions stop where a row is the whole level */
    for (int l = 0; l < r->refl.levels && l <= top; l++)
        for (int m = 0; m <= REFL_RIP_M && l + m <= top; m++) {
            int lw = r->refl.w >> l > 0 ? r->refl.w >> l : 1, lh = r->refl.h >> (l + m);
            int col = 2 * (r->refl.h >> l);
            int x = l == 0 ? 0 : r->refl.w - (r->refl.w >> (l - 1));
            int y = (l == 0 ? 0 : 2 * r->refl.h) + col - (col >> m);
            int n = m > 0 ? 1 << (m - 1) : 1;
            /* a row of level l in uv; the taps' count */
            glUniform2f(r->refl_copy_u[1], (float)(1 << l) / (float)r->refl.h, (float)n);
            glUniform1f(r->refl_copy_u[2], -(float)m);
            glViewport(x, y, lw, lh);
            glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
        }
    glDisableVertexAttribArray(0);
    pass_restore(&r->refl_saved);
    r->refl_ready = 1;
    return gpu_check("renderer: reflection pass end", err);
}

/* ocean.frag's reflection uniforms for a draw: the map of the pass ended since the last draw,
 * else the transparent one (the sky alone). */
void reflect_uniforms(const struct renderer *r, const GLint *u)
{
    if (!r->d.reflections)
        return;
    bind_tex(r, UNIT_REFLECT, r->refl_ready ? r->refl_atlas : r->refl_none, u[OU_REFL_TEX]);
    glUniformMatrix3fv(u[OU_REFL_MAT], 1, GL_FALSE, r->refl_mat);
    glUniform4fv(u[OU_REFL_SCREEN], 1, r->refl_screen);
    glUniform4fv(u[OU_REFL_RAY], 1, r->refl_ray);
    glUniform4fv(u[OU_REFL_DOWN], 1, r->refl_down);
    glUniform2fv(u[OU_REFL_BLUR], 1, r->refl_blur);
    glUniform2fv(u[OU_REFL_AXES], 1, r->refl_axes);
    int top = log2i(r->refl.h);
    glUniform4f(u[OU_REFL_LEVELS], (float)(r->refl.levels - 1 < top ? r->refl.levels - 1 : top),
                1.0f / (float)r->refl.w, 1.0f / (float)r->refl.h, (float)top);
}
