/* programs.c - the renderer's GL programs (render/internal.h): the ocean.frag/ocean.vert
 * variants (k pattern slots' slopes, the first kw of their whitecaps), the sky and the sun;
 * their uniform and attribute names; the start-up probe that draws every variant once and
 * finds those the driver refuses (their rows then drawn with fewer fetches); the debug colours
 * that name a variant in a frame.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "render/internal.h"

/* a macro's value as a string literal (REFL_RIP_M into ocean.frag's defines) */
#define STRINGIFY_(x) #x
#define STRINGIFY(x) STRINGIFY_(x)

static const char *const ocean_uniform_names[OU_COUNT] = {
    "world_to_clip", "pattern_uv_offset", "pattern_inv_size", "fresnel_tex", "sky_tex",
    "sky_map_scale", "sky_map_size", "sun_dir_world", "sun_irr", "sea_radiance", "foam_radiance",
    "const_slope", "const_k", "unresolved_var", "whitecap_epsilon", "slope_scale", "slope_bias",
    "wc_scale", "wc_bias", "lin_s0", "total_var",
    "sky_map_inv_size", "slope_tex0", "slope_tex1", "slope_tex2", "slope_tex3", "wc_tex0",
    "wc_tex1", "wc_tex2", "wc_tex3", "sky_level_scale", "whitecap_epsilon_v",
    "sky_top_level", "sky_bias_max", "haze_tau", "haze_ray", "haze_mie", "haze_frame",
    "haze_tau_ratio", "detile_shift", "detile_atlas", "wc_mean", "fresnel_uv_scale",
    "slope_mean", "slot_lod", "wc_lod", "lod_frame", "slope_var", "lod_cmax", "var_knot_v",
    "var_knot_frame_v", "sky_run_lod", "sky_run_blk", "wc_trust", "foam_detail", "refl_tex", "refl_mat",
    "refl_screen", "refl_ray", "refl_down", "refl_blur", "refl_levels",
    "refl_axes", "wake_tex", "wake_mat", "wake_rot", "wake_k", "wake_foam", "foam_gain", "foam_gain_v",
    "wake_warp", "shadow_tex", "shadow_mat", "shadow_sea", "shadow_foam",
    "refr_tex", "refr_screen", "refr_shift", "refr_tau", "mask_box", "mask_mat", "mask_foam",
    "mask_foam_v", "fresnel_uv_max"
};
static const char *const sky_uniform_names[SU_COUNT] = {
    "clip_to_world_rel", "sky_view", "sky_view_scale", "sky_sun", "sun_ndc", "sun_display"
};
static const struct shader_attrib ocean_attribs[] = {
    { "a_pos", A_POS }, { "a_rest", A_REST }, { "a_geo", A_GEO }, { "a_lin", A_LIN },
    { "a_lin_dx", A_LIN_DX }, { "a_lin_dy", A_LIN_DY }, { "a_sun", A_SUN }, { "a_fog", A_FOG },
    { "a_grid", A_GRID }, { "a_geo_slope", A_GEO_SLOPE }, { "a_geo_k", A_GEO_K }
};
_Static_assert(VSHADE_POS == 4 * A_POS && VSHADE_REST == 4 * A_REST && VSHADE_GEO == 4 * A_GEO &&
               VSHADE_LIN == 4 * A_LIN && VSHADE_LIN_DX == 4 * A_LIN_DX &&
               VSHADE_LIN_DY == 4 * A_LIN_DY && VSHADE_SUN == 4 * A_SUN &&
               VSHADE_FOG == 4 * A_FOG && VSHADE_FLOATS == 4 * A_COUNT,
               "the attributes are vshade.h's vectors in order");
static const char *const vtf_uniform_names[VU_COUNT] = {
    "grid_fwd", "grid_right", "grid_up", "grid_frame", "grid_range", "grid_rows", "grid_rows_hz", "grid_margin",
    "grid_step", "disp_scale", "disp_bias", "disp_pattern", "disp_a0", "disp_b0", "disp_a1",
    "disp_b1", "disp_a2", "disp_b2", "disp_a3", "disp_b3", "detile_tex", "detile_atlas_v",
    "disp_cell"
};
static const struct shader_attrib sky_attribs[1] = { { "a_ndc", 0 } };

/* debug_variants' colours: variant v as red 10 (v + 1) (at most 250), green and blue 0, over
 * a white clear; drawn by blending (GL_ZERO, GL_CONSTANT_COLOR), so the programs are the ones
 * the frame runs and a pixel drawn twice comes out as the product of two colours. */
_Static_assert(10 * OCEAN_VARIANTS <= 250, "variant_colour's reds stay below the white clear");
void variant_colour(int v, float rgba[4])
{
    rgba[0] = (float)(10 * (v + 1)) / 255.0f;
    rgba[1] = rgba[2] = 0.0f;
    rgba[3] = 1.0f;
}

int renderer_pixel_variant(const uint8_t rgba[4])
{
    if (rgba[0] == 255 && rgba[1] == 255 && rgba[2] == 255)
        return RENDERER_PIXEL_SKY;
    if (rgba[1] || rgba[2] || rgba[0] % 10 || rgba[0] == 0 || rgba[0] / 10 > OCEAN_VARIANTS)
        return RENDERER_PIXEL_MIXED;
    return rgba[0] / 10 - 1;
}

/* How the programs were built where renderer_create built them again: " cpu-vertex" (the
 * terms of the vertex on the CPU), " no-detile" (no lattice), then " objects" for an ocean
 * that takes the application's objects (reflections, wakes, shadows or refractions: more
 * uniforms, units and work; tools/devices.py tells their programs apart by it). */
const char *program_tags(const struct renderer *r)
{
    static const char *const tags[8] = {
        "", " cpu-vertex", " no-detile", " cpu-vertex no-detile", " objects",
        " cpu-vertex objects", " no-detile objects", " cpu-vertex no-detile objects"
    };
    int cpu = r->cpu_vterms && !r->vtf, off = !renderer_detile(r);
    int obj = renderer_objects(r);
    return tags[cpu | off << 1 | obj << 2];
}

void renderer_program_name(const struct renderer *r, int v, char *buf, size_t size)
{
    snprintf(buf, size, "ocean k=%d kw=%d %s%s", VARIANT_K(v), VARIANT_KW(v),
             render_quality_name(r->d.quality), program_tags(r));
}

int build_programs(struct renderer *r, struct swell_err *err)
{
    char defines[256];
    struct shader_desc od = { 0 }, sd = { 0 };
    int rc;
    od.dir = sd.dir = r->d.shader_dir;
    od.caps = sd.caps = &r->gpu->caps;
    od.vs_file = "ocean.vert";
    od.fs_file = "ocean.frag";
    od.defines = defines;
    od.uniform_names = ocean_uniform_names;
    od.uniform_count = OU_COUNT;
    od.attribs = ocean_attribs;
    od.attrib_count = (int)(sizeof(ocean_attribs) / sizeof(ocean_attribs[0]));
    for (int k = 0; k <= r->nfs; k++) {
        for (int kw = 0; kw <= (k < r->nwc ? k : r->nwc); kw++) {
            int n = snprintf(defines, sizeof(defines), "FS_PATTERNS=%d FS_WHITECAPS=%d%s%s%s%s%s%s%s%s%s%s%s",
                             k, kw, r->d.quality == QUALITY_HIGH ? " QUALITY_HIGH" : "",
                             r->run_lod ? " SWELL_RUN_LOD" : "",
                             r->gpu->caps.order_fetches ? " SWELL_ORDER_FETCHES" : "",
                             renderer_detile(r) ? "" : " SWELL_NO_DETILE",
                             r->d.linear_output ? " SWELL_LINEAR_OUT" : "",
                             r->d.slope_output ? " SWELL_SLOPE_OUT" : "",
                             r->d.reflections ? " SWELL_REFLECT REFL_RIP_M=" STRINGIFY(REFL_RIP_M)
                                              : "",
                             r->d.wakes ? " SWELL_WAKE" : "",
                             r->d.shadows ? " SWELL_SHADOW" : "",
                             r->d.refractions ? " SWELL_REFRACT" : "",
                             r->d.wave_mask ? " SWELL_MASK" : "");
            int v = VARIANT(k, kw);
            if (r->vtf)
                snprintf(defines + n, sizeof(defines) - (size_t)n, " VTF_PATTERNS=%d",
                         r->t->patterns);
            else if (r->cpu_vterms)
                snprintf(defines + n, sizeof(defines) - (size_t)n, " CPU_VERTEX_TERMS");
            od.uniform_locations = r->ou[v];
            if ((rc = shader_program_build(&od, &r->ocean[v], err)))
                return rc;
            for (int i = 0; i < VU_COUNT; i++)
                r->vu[v][i] = r->vtf ? glGetUniformLocation(r->ocean[v].program,
                                                            vtf_uniform_names[i]) : -1;
            if (r->d.quality != QUALITY_HIGH)
                break;   /* low fetches no whitecaps: one variant per k */
        }
    }
    sd.vs_file = "sky.vert";
    sd.fs_file = "sky.frag";
    sd.uniform_names = sky_uniform_names;
    sd.uniform_count = SU_COUNT;
    sd.uniform_locations = r->su;
    sd.attribs = sky_attribs;
    sd.attrib_count = 1;
    sd.defines = r->d.linear_output ? "SWELL_LINEAR_OUT" : NULL;
    if ((rc = shader_program_build(&sd, &r->skyp, err)))
        return rc;
    sd.defines = "SUN_DISC";
    sd.uniform_locations = r->sunu;
    return shader_program_build(&sd, &r->sunp, err);
}


static int variant_exists(const struct renderer *r, int k, int kw)
{
    return k >= 0 && k <= r->nfs && kw >= 0 && kw <= (k < r->nwc ? k : r->nwc) &&
           r->ocean[VARIANT(k, kw)].program != 0;
}

#define PROBE_SIZE 16

/* One probe frame of cam into the bound 16x16 target, its stderr captured into text (and
 * passed on), labelled "swell-program: probe NAME" first unless name is NULL; GL errors it
 * left are cleared. Returns renderer_frame's code. */
static int probe_draw(struct renderer *r, const struct camera *cam, const char *name,
                      char *text, size_t size)
{
    struct capture cap;
    struct swell_err ferr = { 0 };
    if (name)
        fprintf(stderr, "swell-program: probe %s\n", name);
    capture_begin(&cap);
    int rc = renderer_frame(r, cam, 0.0, PROBE_SIZE, PROBE_SIZE, &ferr);
    glFlush();   /* the drivers compile at the draw; glFinish hangs on lima's shim */
    capture_end(&cap, text, size);
    while (glGetError() != GL_NO_ERROR)
        ;
    return rc;
}

/* Start-up probe (issue 15): every ocean variant draws a nadir view into a small target
 * once, so the driver compiles it now (most compile on first draw), while its stderr is
 * captured: a variant is refused where the driver says so (refusal_text) or, on a device
 * that executes draws (the target's clear reads back; Mesa's noop drm-shims execute none),
 * where it leaves the target empty. A refused variant's rows are drawn with the nearest one
 * that runs and fetches fewer patterns or whitecaps, else more (variant_use); if none runs,
 * the renderer cannot draw the sea here (SWELL_E_SHADER: the caller tries low quality). With
 * SWELL_SHADER_LABELS=1 each probe draw is labelled on stderr, so a driver's statistics
 * (tools/devices.py) are told apart by program. The sky's two programs are drawn once too
 * (towards the sun, so its disc is in view). */
/* The first variant the driver runs, k2 from ka to kb and kw2 from wa to wb (each by its step;
 * variant_exists skips the counts a k2 has no program for), or -1. */
static int running_variant(const struct renderer *r, int ka, int kb, int kstep, int wa, int wb,
                           int wstep)
{
    for (int k2 = ka; kstep > 0 ? k2 <= kb : k2 >= kb; k2 += kstep)
        for (int kw2 = wa; wstep > 0 ? kw2 <= wb : kw2 >= wb; kw2 += wstep)
            if (variant_exists(r, k2, kw2) && r->variant_ok[VARIANT(k2, kw2)])
                return VARIANT(k2, kw2);
    return -1;
}

int probe_programs(struct renderer *r, struct swell_err *err)
{
    static uint8_t px[4 * PROBE_SIZE * PROBE_SIZE];
    int label = shader_labels();
    for (int v = 0; v < OCEAN_VARIANTS; v++) {
        r->variant_ok[v] = r->ocean[v].program != 0;
        r->variant_use[v] = v;
    }
    r->force_variant = -1;
    struct gpu_probe_target pt;
    gpu_probe_target_begin(&pt, PROBE_SIZE);
    int complete = pt.complete;
    r->probe_executes = pt.executes;
    struct camera cam;
    camera_defaults(&cam);
    cam.pos[2] = 20.0;
    cam.pitch_deg = -89.0f;
    r->probing = 1;
    for (int k = 0; complete && k <= r->nfs; k++)
        for (int kw = 0; kw <= (k < r->nwc ? k : r->nwc); kw++) {
            int v = VARIANT(k, kw);
            if (!r->ocean[v].program)
                continue;
            char text[2048], name[64];
            renderer_program_name(r, v, name, sizeof name);
            r->force_variant = v;
            int rc = probe_draw(r, &cam, label ? name : NULL, text, sizeof text);
            int covered = 1;
            if (r->probe_executes && !rc) {
                int n = 0;
                glReadPixels(0, 0, PROBE_SIZE, PROBE_SIZE, GL_RGBA, GL_UNSIGNED_BYTE, px);
                for (int i = 0; i < PROBE_SIZE * PROBE_SIZE; i++)
                    n += px[4 * i + 3] > 0;
                covered = n > PROBE_SIZE * PROBE_SIZE / 2;
            }
            int objects = renderer_objects(r);
            unsigned refuse = r->d.probe_refuse |
                              (renderer_detile(r) ? r->d.probe_refuse_detile : 0u) |
                              (r->cpu_vterms ? 0u : r->d.probe_refuse_gpu_vertex) |
                              (objects && r->d.probe_refuse_objects ? ~0u : 0u);
            r->variant_ok[v] = !rc && !capture_refused(text) && covered &&
                               !((refuse >> (v & 31)) & 1u);
            if (label)
                fprintf(stderr, "swell-program: end %s\n", r->variant_ok[v] ? "ok" : "refused");
        }
    /* the sky's programs too, towards the sun (their refusal leaves the sea drawn: said only) */
    if (complete) {
        char text[2048];
        struct camera up;
        camera_defaults(&up);
        up.pos[2] = 20.0;
        up.heading_deg = r->d.sun_azim_deg;
        up.pitch_deg = r->d.sun_elev_deg;
        r->probing = 2;
        int refused = probe_draw(r, &up, label ? "sky" : NULL, text, sizeof text) ||
                      capture_refused(text);
        if (refused)
            fprintf(stderr, "swell: the driver refused the sky's programs: no sky will be "
                    "drawn behind the sea\n");
        if (label)
            fprintf(stderr, "swell-program: end %s\n", refused ? "refused" : "ok");
    }
    r->probing = 0;
    r->force_variant = -1;
    r->sky_view_alt = NAN;   /* the first frame builds the background for its own camera */
    gpu_probe_target_end(&pt);
    /* each variant's stand-in: the most patterns, then whitecaps, among those that run */
    char list[256] = "";
    size_t ln = 0;
    r->refused = 0;
    for (int k = 0; k <= r->nfs; k++)
        for (int kw = 0; kw <= (k < r->nwc ? k : r->nwc); kw++) {
            int v = VARIANT(k, kw), use = -1;
            if (!r->ocean[v].program)
                continue;
            r->refused += !r->variant_ok[v];
            use = running_variant(r, k, 0, -1, kw, 0, -1);
            /* none smaller (GC2000: the vertex shaders that evaluate eq. 6 per vertex are
             * the ones past its 256 instructions): the most patterns up to k with more
             * whitecap tables, else the one fetching the fewest more patterns. Extra slots
             * and tables fade out where this variant's rows stop fetching them (their
             * weights, set_slot_lods), so the rows draw the same sea at more cost. */
            if (use < 0)
                use = running_variant(r, k, 0, -1, kw + 1, SWELL_MAX_PATTERNS, 1);
            if (use < 0)
                use = running_variant(r, k + 1, r->nfs, 1, kw, SWELL_MAX_PATTERNS, 1);
            r->variant_use[v] = use;
            if (use < 0)
                return swell_fail(err, SWELL_E_SHADER, "renderer: the driver (%s) runs no %s "
                                  "quality ocean program, not even one fetching no pattern "
                                  "(its messages are above)", (const char *)glGetString(GL_RENDERER),
                                  render_quality_name(r->d.quality));
            if (use != v && ln < sizeof list)
                ln += (size_t)snprintf(list + ln, sizeof list - ln, " %d/%d->%d/%d", k, kw,
                                       VARIANT_K(use), VARIANT_KW(use));
        }
    if (r->refused)
        fprintf(stderr, "swell: the driver (%s) refused %d ocean program(s)%s%s%s; their rows "
                "are drawn fetching fewer (or more) patterns/whitecap tables:%s\n",
                (const char *)glGetString(GL_RENDERER), r->refused,
                program_tags(r)[0] ? " [" : "", program_tags(r)[0] ? program_tags(r) + 1 : "",
                program_tags(r)[0] ? "]" : "", list);
    return gpu_check("renderer: start-up probe", err);
}
