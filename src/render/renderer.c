/* renderer.c - draws the ocean (renderer.h).
 *
 * gles2-min path (DESIGN.md): the CPU builds the geometry (grid.c: projected grid or near/far
 * patches, displaced by the looping tables with Bruneton eq. 2 weights) and streams it into one
 * VBO per frame; loop frames of the slope and whitecap tables are blended on the CPU (stream.c)
 * into one texture per pattern and kind; patterns without a free texture unit are resolved per
 * vertex. Sky: analytic, baked once into a stereographic map (sky.c). Shading: ocean.frag.
 *
 * Fetches are the cost on fill-rate-bound GPUs (and llvmpipe): the sea is drawn as runs of grid
 * rows, far to near, each with the ocean.frag variant that fetches only the patterns not yet
 * fully filtered there. Where a pixel covers a whole patch of pattern i (footprint >= L_i) its
 * mip chain is at the top level, the patch's mean slope and slope variance (Bruneton §4.1; the
 * same for Dupuy's k moments), so the variant takes those as constants. Whitecap tables are
 * fetched only for patterns that carry whitecaps (the others' tables are constant).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "optics/fresnel.h"
#include "geometry/grid.h"
#include "tables/quantize.h"
#include "render/renderer.h"
#include "geometry/sea.h"
#include "gl/shader.h"
#include "optics/sky.h"
#include "tables/stream.h"
#include "optics/tonemap.h"
#include "optics/water.h"
#include "gl/capture.h"
#include "geometry/detile.h"
#include "geometry/vshade.h"

#define SKY_MAP_SIZE 256
#define FRESNEL_FALLBACK 64

enum ocean_uniform {
    OU_WORLD_TO_CLIP, OU_UV_OFFSET, OU_INV_SIZE, OU_FRESNEL_TEX, OU_SKY_TEX, OU_SKY_SCALE,
    OU_SKY_SIZE, OU_SUN_DIR, OU_SUN_IRR, OU_SEA_RADIANCE, OU_FOAM_RADIANCE, OU_CONST_SLOPE,
    OU_CONST_K, OU_UNRESOLVED, OU_EPSILON, OU_SLOPE_SCALE, OU_SLOPE_BIAS, OU_WC_SCALE, OU_WC_BIAS,
    OU_LIN_S0, OU_TOTAL_VAR, OU_SKY_INV_SIZE,
    OU_SLOPE_TEX0, OU_SLOPE_TEX1, OU_SLOPE_TEX2, OU_SLOPE_TEX3,
    OU_WC_TEX0, OU_WC_TEX1, OU_WC_TEX2, OU_WC_TEX3, OU_SKY_LEVEL_SCALE, OU_EPSILON_V, OU_SKY_TOP,
    OU_SKY_BIAS_MAX, OU_HAZE_TAU, OU_HAZE_RAY, OU_HAZE_MIE, OU_HAZE_FRAME,
    OU_HAZE_TAU_RATIO, OU_DETILE_SHIFT, OU_DETILE_ATLAS, OU_WC_MEAN, OU_FRESNEL_V, OU_SLOPE_MEAN,
    OU_SLOT_LOD, OU_WC_LOD, OU_LOD_FRAME, OU_SLOPE_VAR, OU_LOD_CMAX, OU_VAR_KNOT_V,
    OU_VAR_KNOT_FRAME_V, OU_SKY_RUN_LOD, OU_SKY_RUN_BLK, OU_WC_TRUST, OU_FOAM_DETAIL, OU_COUNT
};
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
    "var_knot_frame_v", "sky_run_lod", "sky_run_blk", "wc_trust", "foam_detail"
};

enum sky_uniform {
    SU_CLIP_TO_WORLD, SU_SKY_VIEW, SU_SKY_VIEW_SCALE, SU_SKY_SUN, SU_SUN_NDC, SU_SUN_DISPLAY,
    SU_COUNT
};
static const char *const sky_uniform_names[SU_COUNT] = {
    "clip_to_world_rel", "sky_view", "sky_view_scale", "sky_sun", "sun_ndc", "sun_display"
};

/* The background sky seen from the camera's altitude (sky.h sky_view_gains): a 512 x 2 table
 * of the Rayleigh and Mie gains by elevation, rebuilt when the altitude has moved by more than
 * SKY_VIEW_DALT_M + SKY_VIEW_DALT_REL of it (its column changes by well under 1 % between). */
#define SKY_VIEW_N 512
#define SKY_VIEW_DALT_M 50.0
#define SKY_VIEW_DALT_REL 0.02

/* The background sky mesh: view rays and map coordinates per vertex (sky.vert). */
#define SKY_MESH_W 33
#define SKY_MESH_H 19
#define SUN_RADIUS_RAD 0.00466f   /* 0.267 deg */

/* A pattern is dropped from a run of rows once its smallest pixel footprint there exceeds the
 * patch by this factor (LOD >= log2 N + 0.3: trilinear reads the 1x1 level alone), a margin for
 * the footprint estimate from the rows' vertices. */
#define DROP_FOOTPRINT 1.25f
/* ...or earlier, at the LOD from which the mip means of its slope table hold less than this
 * fraction of the patch's slope variance (slot_tables_stats): a pattern's band spans a few
 * octaves of wavenumber above its patch's fundamental, so well before the 1x1 level the means
 * are nearly flat and the variance is all within the texels (Bruneton §4.1), which the patch's
 * constants carry as well. */
#define DROP_RESOLVED 0.02f
/* A pattern's whitecaps are dropped earlier, once its patch covers fewer than 1 / this many
 * pixels along the view: there a pixel averages (N / 8)^2 or more of the table's texels, whose
 * k moments (Dupuy eq. 7-8) are then close to the patch's, so the coverage of eq. 6 from the
 * patch's constants differs little, while each whitecap fetch costs as much as a slope fetch. */
#define WC_DROP_FOOTPRINT 0.125f
/* ...unless renderer_desc keep_resolved: then at their 1x1 level, with the slopes. */
#define WC_DROP(r) ((r)->d.keep_resolved ? DROP_FOOTPRINT : WC_DROP_FOOTPRINT)
/* No pattern stops at a row (ocean.frag slot_weight): its fetched deviation fades out over this
 * many octaves of footprint (mip levels) before the rows that no longer fetch it, ending this
 * much before them (the shader's footprint is its vertex's, the renderer's a row's nearest). */
#define FADE_LEVELS 1.0f
#define FADE_MARGIN 0.1f
/* The contrast gain of a run's level where it is half an octave coarser than the footprint
 * (weight_terms). */
#define RUN_BLUR_GAIN 1.41421356f
/* 1: a run's level scaled to the contrast of the footprint's fractional level (weight_terms);
 * the seam metric at rough 1 km 45 deg down 1.65 -> 1.18, over test_seams' views high 2.81 ->
 * 1.38. The variance takes min(g, 1) of the gain (ocean.frag add_slope): with (1 - g^2) it
 * went negative on tables of a few waves (test_render), the sun a needle. */
#define RUN_CONTRAST 1
#define RUN_CONTRAST_MAX 2.0f

/* Ocean program variants: k slots' slopes and the first kw <= k of their whitecaps fetched. */
#define OCEAN_VARIANTS RENDERER_OCEAN_VARIANTS
#define VARIANT(k, kw) ((k) * (SWELL_MAX_PATTERNS + 1) + (kw))
#define VARIANT_K(v) ((v) / (SWELL_MAX_PATTERNS + 1))
#define VARIANT_KW(v) ((v) % (SWELL_MAX_PATTERNS + 1))

/* gles2-min's attributes with the terms of the vertex on the CPU (cpu_vterms) are vshade.h's
 * vectors, in order; without, grid.c's four (a_geo_slope, a_geo_k at 2 and 3); a
 * vertex-texture-fetch program has a_grid alone (at 0, with a_pos: GLES 2 promises 8
 * locations, and names sharing one are never in the same program). */
enum { A_POS = 0, A_REST, A_GEO, A_LIN, A_LIN_DX, A_LIN_DY, A_SUN, A_FOG, A_COUNT, A_GRID = 0,
       A_GEO_SLOPE = 2, A_GEO_K = 3, A_GRID_COUNT = 4 };
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

/* Vertex-texture-fetch grid (ocean.vert VTF_PATTERNS): its uniforms, per pattern. */
enum vtf_uniform {
    VU_FWD, VU_RIGHT, VU_UP, VU_FRAME, VU_RANGE, VU_ROWS, VU_ROWS_HZ, VU_MARGIN, VU_STEP, VU_SCALE, VU_BIAS,
    VU_PATTERN, VU_A0, VU_B0, VU_A1, VU_B1, VU_A2, VU_B2, VU_A3, VU_B3, VU_DETILE_TEX,
    VU_DETILE_ATLAS, VU_DISP_CELL, VU_COUNT
};
static const char *const vtf_uniform_names[VU_COUNT] = {
    "grid_fwd", "grid_right", "grid_up", "grid_frame", "grid_range", "grid_rows", "grid_rows_hz", "grid_margin",
    "grid_step", "disp_scale", "disp_bias", "disp_pattern", "disp_a0", "disp_b0", "disp_a1",
    "disp_b1", "disp_a2", "disp_b2", "disp_a3", "disp_b3", "detile_tex", "detile_atlas_v",
    "disp_cell"
};
static const struct shader_attrib sky_attribs[1] = { { "a_ndc", 0 } };

/* Texture units: 0 Fresnel, 1 sky, then slope/whitecap per fragment pattern slot. */
enum { UNIT_FRESNEL = 0, UNIT_SKY = 1, UNIT_PATTERNS = 2 };

#define SLOT_LEVELS 16                /* mip levels a run key holds (4 bits per table) */
#define VAR_KNOTS 4                   /* low quality's pixel variance per run (pixel_var_at) */

/* A table with mips on the GPU: one texture holding the chain or, with run_lod, one texture
 * per level, each without mips. Binding level l's texture is how a GLES 2 fragment shader
 * without texture LOD fetches at an explicit whole level (GLES 2 has no TEXTURE_BASE_LEVEL),
 * and llvmpipe filters a texture without mips on its fast path, with no LOD at all: measured
 * (A/B, gles3, 1280x720) against texture2DLodEXT at the run's level on the chain, high at 1 km
 * 6.1 -> 5.2x the quad, calm surface 5.0 -> 4.2x; low 2.9 -> 2.45x at the rough surface, 2.8
 * -> 2.5x at 10 km, but 3.0 -> 3.4x at rough 1 km (left so: one mechanism on every tier). */
struct chain_tex {
    GLuint tex[SLOT_LEVELS];          /* [0] the chain, or [l] level l */
    int levels;                       /* levels held as textures of their own; 0: one chain */
};

struct fs_slot {
    int pattern;                      /* table pattern index */
    const struct swell_table *slope, *wc;
    struct chain_tex slope_tex, wc_tex;
    uint8_t *slope_b, *wc_b;          /* blended chains streamed each frame */
    float top_slope[4], top_k[2];     /* dequantised top mip level: mean, variance */
    float level_var[SLOT_LEVELS][2];  /* per mip level: mean within-texel slope variance x, y
                                       * of the first loop frame (set_run_lods, drop_lod) */
    float level_kvar[SLOT_LEVELS];    /* ...and of the whitecap table's foam memory */
    int top_level[2];                 /* the slope and whitecap tables' last levels */
    float log2_density[2];            /* log2 texels per metre of the slope, whitecap table */
    int drop_lod;                     /* from this level up the slope table resolves too
                                       * little to fetch (DROP_RESOLVED) */
    struct stream_phase phase;        /* of the pattern's own loop period (bake.c) */
    int phase_valid;
    float level_within[SLOT_LEVELS];  /* ...level_var's x + y (weight_terms)... */
    float level_wfrac[SLOT_LEVELS];   /* ...and its share of the top level's (ocean.vert
                                       * fetched_var; 1 from the top level on) */
    float level_rho[SLOT_LEVELS];     /* per mip level: the correlation of the slope detail of
                                       * consecutive loop frames (loop_gain) */
};

struct renderer {
    struct renderer_desc d;
    struct gpu *gpu;
    const struct swell_tables *t;
    struct grid *grid;
    struct sky sky;
    struct sky_haze haze;       /* the sky's haze, its horizon terms x exposure */
    struct shader_program ocean[OCEAN_VARIANTS], skyp;   /* ocean[VARIANT(k, kw)] */
    struct shader_program sunp;
    GLint ou[OCEAN_VARIANTS][OU_COUNT], su[SU_COUNT], sunu[SU_COUNT];
    GLuint sky_vbo, sky_ibo;
    GLint vu[OCEAN_VARIANTS][VU_COUNT];
    /* Tiers with vertex texture fetch, projected grid: the grid is built and displaced in
     * ocean.vert from a static VBO of grid parameters and, per pattern, the two loop frames
     * the animation is between (uploaded as they are when the frame changes, blended in
     * float in the vertex shader: no CPU work per vertex or texel). */
    int vtf;
    GLuint disp_tex[SWELL_MAX_PATTERNS][2];   /* two loop frames per pattern, blended in VS */
    int disp_frame[SWELL_MAX_PATTERNS][2];    /* table frame each holds, -1 none */
    int disp_ab[SWELL_MAX_PATTERNS][2];       /* this frame's a and b: indices into the pair */
    float disp_w[SWELL_MAX_PATTERNS];
    struct grid_projection proj;
    double camera_raise_m;      /* how far the last frame raised the camera (renderer_frame) */
    GLuint fresnel_tex, vbo, ibo, quad_vbo;
    struct chain_tex sky_tex;
    GLuint sky_view_tex;              /* background: gains by elevation from the camera */
    float sky_view_scale[2][3];       /* texel / 255 x scale = gain x exposure, ray and mie */
    float sky_view_sun[3];            /* the sun's transmittance from the camera */
    double sky_view_alt;              /* altitude the table is for; NAN: to be built */
    int sky_half;                     /* sky_tex holds half-float radiances (scale 1) */
    const struct swell_table *fresnel;
    uint8_t *scratch;                 /* derived textures are built here */
    struct swell_table fresnel_own;   /* built here only when the tables lack one */
    int atlas_w, atlas_h;             /* the Fresnel textures' atlas (atlas_size) */
    int nfs;                          /* patterns shaded from textures, largest first */
    int nwc;                          /* leading slots whose whitecaps are fetched (high) */
    unsigned cpu_mask;                /* patterns resolved per vertex */
    unsigned k_mask;                  /* low quality, CPU grid: fragment patterns whose
                                       * whitecap moments the grid resolves per vertex
                                       * (grid.h k_patterns; not the patch's constants) */
    struct fs_slot slot[SWELL_MAX_PATTERNS];
    float *verts;                     /* VTF: the grid parameters; else grid.c's vertices */
    float *shaded;                    /* cpu_vterms: vshade.c's, uploaded each frame */
    int cpu_vterms;                   /* gles2-min: the terms of each vertex on the CPU
                                       * (vshade.h), the driver refusing ocean.vert's
                                       * (renderer_create) */
    struct vshade_frame vf;           /* this frame's terms of the vertex stage (vertex_frame):
                                       * vshade.c's input, the VTF programs' uniforms */
    float exposure;
    float water_albedo[3];            /* eq. 28's water body, L_sea = albedo E / pi (water.h) */
    uint64_t stream_bytes;
    uint64_t gpu_bytes;               /* accounted by gpu.h for this renderer's objects */
    int run_lod;                      /* pattern fetches at one LOD per run (gpu.c) */
    int draws;                        /* sea draws in the last frame */
    int draws_wc_const;               /* ...with whitecaps of a fetched slot as constants */
    int draws_resolved_drop;          /* ...dropping a slope slot by DROP_RESOLVED */
    /* The start-up probe (probe_programs): which ocean variants the driver runs, and the one
     * each variant's rows are drawn with (itself, or one fetching fewer patterns) */
    int variant_ok[OCEAN_VARIANTS];
    int variant_use[OCEAN_VARIANTS];
    int force_variant;                /* >= 0: every row with this variant (the probe) */
    int probing;                      /* 1: no sky, cleared to 0 (the probe) */
    int probe_executes;               /* the device drew the probe's clear (not a noop shim) */
    int refused;                      /* variants the probe found refused */
    int detile_refused;               /* > 0: --detile auto turned the lattice off, with which
                                       * the probe found this many refused (renderer_create) */
};

static const char *const quality_names[QUALITY_COUNT] = { "high", "low" };
static const char *const geometry_names[GEOMETRY_COUNT] = { "grid", "patches" };
static const char *const detile_names[DETILE_MODE_COUNT] = { "auto", "on", "off" };

/* An enum's name and its value from a name (-1 if none) through its table of n names. */
static const char *enum_name(const char *const *names, int n, int v)
{
    return v >= 0 && v < n ? names[v] : "?";
}

static int enum_from_name(const char *const *names, int n, const char *name)
{
    for (int i = 0; name && i < n; i++)
        if (strcmp(name, names[i]) == 0)
            return i;
    return -1;
}

const char *render_quality_name(int q) { return enum_name(quality_names, QUALITY_COUNT, q); }
int render_quality_from_name(const char *name)
{
    return enum_from_name(quality_names, QUALITY_COUNT, name);
}
const char *geometry_kind_name(int g) { return enum_name(geometry_names, GEOMETRY_COUNT, g); }
int geometry_kind_from_name(const char *name)
{
    return enum_from_name(geometry_names, GEOMETRY_COUNT, name);
}
const char *detile_mode_name(int m) { return enum_name(detile_names, DETILE_MODE_COUNT, m); }
int detile_mode_from_name(const char *name)
{
    return enum_from_name(detile_names, DETILE_MODE_COUNT, name);
}

/* debug_variants' colours: variant v as red 10 (v + 1) (at most 250), green and blue 0, over
 * a white clear; drawn by blending (GL_ZERO, GL_CONSTANT_COLOR), so the programs are the ones
 * the frame runs and a pixel drawn twice comes out as the product of two colours. */
_Static_assert(10 * OCEAN_VARIANTS <= 250, "variant_colour's reds stay below the white clear");
static void variant_colour(int v, float rgba[4])
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

/* How the programs were built where renderer_create built them again: "", " cpu-vertex"
 * (the terms of the vertex on the CPU), " no-detile" (no lattice), or both. */
static const char *program_tags(const struct renderer *r)
{
    int cpu = r->cpu_vterms && !r->vtf, off = !renderer_detile(r);
    return cpu && off ? " cpu-vertex no-detile" : cpu ? " cpu-vertex" : off ? " no-detile" : "";
}

void renderer_program_name(const struct renderer *r, int v, char *buf, size_t size)
{
    snprintf(buf, size, "ocean k=%d kw=%d %s%s", VARIANT_K(v), VARIANT_KW(v),
             render_quality_name(r->d.quality), program_tags(r));
}

int renderer_detile(const struct renderer *r)
{
    return r->d.detile == DETILE_MODE_ON;
}

static void resolve(struct renderer_desc *d)
{
    if (!d->shader_dir)
        d->shader_dir = "shaders_gles";
    if (d->grid_w <= 0)
        d->grid_w = 80;
    if (d->grid_h <= 0)
        d->grid_h = 56;
    if (d->sun_elev_deg == 0.0f)
        d->sun_elev_deg = 30.0f;
    if (d->detile == DETILE_MODE_AUTO)
        d->detile = d->quality == QUALITY_HIGH ? DETILE_MODE_ON : DETILE_MODE_OFF;
}

/* A table of levels mips (levels 1: none) as one texture, or with run_lod one per level. */
static int chain_create(struct renderer *r, int w, int h, int levels, int format, int repeat,
                        const char *what, struct chain_tex *c, struct swell_err *err)
{
    int rc;
    memset(c, 0, sizeof(*c));
    if (!r->run_lod || levels <= 1)
        return gpu_texture_create(r->gpu, w, h, levels, format, repeat, what, &c->tex[0], err);
    if (levels > SLOT_LEVELS)
        return swell_fail(err, SWELL_E_ARG, "%s: %d mip levels, at most %d", what, levels,
                          SLOT_LEVELS);
    for (int l = 0; l < levels; l++) {
        int lw = w >> l > 0 ? w >> l : 1, lh = h >> l > 0 ? h >> l : 1;
        if ((rc = gpu_texture_create(r->gpu, lw, lh, 1, format, repeat, what, &c->tex[l], err)))
            return rc;
        c->levels = l + 1;
    }
    return 0;
}

static void chain_destroy(struct renderer *r, struct chain_tex *c)
{
    for (int l = SLOT_LEVELS - 1; l >= 0; l--)
        gpu_texture_destroy(r->gpu, &c->tex[l]);
    c->levels = 0;
}

/* The texture to bind for fetches at level l (the chain itself, which the shader or the
 * hardware takes its level from, or level l's own). */
static GLuint chain_at(const struct chain_tex *c, int l)
{
    if (c->levels == 0)
        return c->tex[0];
    return c->tex[l < 0 ? 0 : l < c->levels ? l : c->levels - 1];
}

void renderer_destroy(struct renderer *r)
{
    if (!r)
        return;
    for (int s = SWELL_MAX_PATTERNS - 1; s >= 0; s--) {
        gpu_texture_destroy(r->gpu, &r->disp_tex[s][1]);
        gpu_texture_destroy(r->gpu, &r->disp_tex[s][0]);
        chain_destroy(r, &r->slot[s].wc_tex);
        chain_destroy(r, &r->slot[s].slope_tex);
        free(r->slot[s].wc_b);
        free(r->slot[s].slope_b);
    }
    gpu_buffer_destroy(r->gpu, &r->sky_ibo);
    gpu_buffer_destroy(r->gpu, &r->sky_vbo);
    gpu_buffer_destroy(r->gpu, &r->quad_vbo);
    gpu_buffer_destroy(r->gpu, &r->ibo);
    gpu_buffer_destroy(r->gpu, &r->vbo);
    gpu_texture_destroy(r->gpu, &r->sky_view_tex);
    chain_destroy(r, &r->sky_tex);
    gpu_texture_destroy(r->gpu, &r->fresnel_tex);
    free(r->scratch);
    shader_program_destroy(&r->sunp);
    shader_program_destroy(&r->skyp);
    for (int v = OCEAN_VARIANTS - 1; v >= 0; v--)
        shader_program_destroy(&r->ocean[v]);
    free(r->fresnel_own.data);
    free(r->verts);
    free(r->shaded);
    sky_destroy(&r->sky);
    grid_destroy(r->grid);
    free(r);
}

/* Channels 0..2 (m, m^2, 0: what ocean.frag reads; channel 3 is the bake's k_i) the same in
 * every texel of every level and layer: the whitecaps of a pattern that carries none (bake.c)
 * are a constant, never a texture. */
static int whitecaps_constant(const struct swell_table *t)
{
    size_t n = table_bytes(t);
    for (size_t i = 4; i < n; i++)
        if ((i & 3) != 3 && t->data[i] != t->data[i & 3])
            return 0;
    return 1;
}

/* Fragment-shader slots go to the smallest patterns, largest first; when the units run short
 * the largest patterns go to the vertices (the grid resolves their waves best). High quality
 * also fetches whitecaps for the leading slots that carry them. */
static void slot_tables_stats(struct renderer *r, struct fs_slot *sl);

static void assign_patterns(struct renderer *r)
{
    int order[SWELL_MAX_PATTERNS], n = r->t->patterns, breaks[SWELL_MAX_PATTERNS];
    int units = r->gpu->caps.texture_units > 0 ? r->gpu->caps.texture_units : 8;
    int high = r->d.quality == QUALITY_HIGH, fs, nwc = 0;
    for (int i = 0; i < n; i++)
        order[i] = i;
    for (int i = 1; i < n; i++)
        for (int j = i; j > 0 && r->t->pattern[order[j]].size_m > r->t->pattern[order[j - 1]].size_m; j--) {
            int tmp = order[j];
            order[j] = order[j - 1];
            order[j - 1] = tmp;
        }
    for (int i = 0; i < n; i++) {
        const struct swell_table *wc = tables_find(r->t, TABLE_WHITECAP, order[i]);
        breaks[i] = wc && wc->format == FORMAT_RGBA8 && !whitecaps_constant(wc);
    }
    for (fs = n < SWELL_MAX_PATTERNS ? n : SWELL_MAX_PATTERNS; fs > 0; fs--) {
        nwc = 0;
        for (int s = 0; high && s < fs; s++)
            if (breaks[n - fs + s])
                nwc = s + 1;
        if (UNIT_PATTERNS + fs + nwc <= units)
            break;
    }
    if (fs == 0)
        nwc = 0;
    r->nfs = fs;
    r->nwc = nwc;
    r->cpu_mask = 0;
    for (int i = 0; i < n - fs; i++)
        r->cpu_mask |= 1u << order[i];
    for (int s = 0; s < fs; s++) {
        struct fs_slot *sl = &r->slot[s];
        sl->pattern = order[n - fs + s];
        sl->slope = tables_find(r->t, TABLE_SLOPE, sl->pattern);
        sl->wc = tables_find(r->t, TABLE_WHITECAP, sl->pattern);
        sl->drop_lod = SLOT_LEVELS;
        if (sl->slope && sl->wc)
            slot_tables_stats(r, sl);
    }
}

static float log2_density(const struct swell_table *t, float size_m)
{
    int texels = t->width > t->height ? t->width : t->height;
    return log2f((float)texels / size_m);
}

/* What the run LOD (draw_runs) needs of a slot's tables, once: their texels per metre, and per
 * mip level of the slope table's first loop frame (Bruneton §4.1) the mean over its texels of
 * the within-texel variance <s^2> - <s>^2 (table_level_within_var), x and y: what a pixel
 * fetching that level resolves below itself. */
/* The correlation of level l's slope detail (the differences of neighbouring texels' mean
 * slopes, channels 0, 1: the high-pass a viewer sees) between consecutive loop frames f and
 * f + 1 (mod F), over every frame pair; 1 where the level does not vary. */
static float level_frame_rho(const struct swell_table *t, int l)
{
    if (l >= t->levels || t->format != FORMAT_RGBA8 || t->layers < 2)
        return 1.0f;
    size_t n = (size_t)table_level_width(t, l) * (size_t)table_level_height(t, l);
    double cov = 0.0, var = 0.0;
    for (int f = 0; f < t->layers; f++) {
        const uint8_t *a = t->data + table_offset(t, l, f);
        const uint8_t *b = t->data + table_offset(t, l, (f + 1) % t->layers);
        for (size_t i = 0; i + 1 < n; i++)
            for (int c = 0; c < 2; c++) {
                double da = (double)a[4 * i + 4 + c] - a[4 * i + c];
                double db = (double)b[4 * i + 4 + c] - b[4 * i + c];
                cov += da * db;
                var += da * da;
            }
    }
    return var > 0.0 ? (float)fmax(cov / var, -1.0) : 1.0f;
}

/* Loop playback without detail loss (issue 14 item 5): the blend (1 - w) a + w b of two loop
 * frames whose deviations from the mean correlate by rho has their variance times
 * (1 - w)^2 + w^2 + 2 w (1 - w) rho (0.5 (1 + rho) at w = 1/2: the fastest waves of a band move
 * 90-160 deg of phase per frame, rho well below 1), so the fetched deviation is scaled back by
 * the inverse square root: the texture's contrast stays over the loop. */
static float loop_gain(float rho, int w_fixed)
{
    float w = (float)w_fixed / (float)STREAM_W_ONE;
    float v = (1.0f - w) * (1.0f - w) + w * w + 2.0f * w * (1.0f - w) * rho;
    return v > 1e-3f ? 1.0f / sqrtf(v) : 1.0f;
}

static int top_level(const struct swell_table *t)
{
    return (t->levels < SLOT_LEVELS ? t->levels : SLOT_LEVELS) - 1;
}

static void slot_tables_stats(struct renderer *r, struct fs_slot *sl)
{
    const struct swell_table *t = sl->slope;
    float size_m = r->t->pattern[sl->pattern].size_m;
    sl->log2_density[0] = log2_density(t, size_m);
    sl->log2_density[1] = log2_density(sl->wc, size_m);
    for (int l = 0; l < SLOT_LEVELS; l++) {
        sl->level_var[l][0] = table_level_within_var(t, l, 0, 2);
        sl->level_var[l][1] = table_level_within_var(t, l, 1, 3);
        sl->level_kvar[l] = table_level_within_var(sl->wc, l, 0, 1);
        sl->level_rho[l] = level_frame_rho(t, l);
        sl->level_within[l] = sl->level_var[l][0] + sl->level_var[l][1];
    }
    sl->top_level[0] = top_level(t);
    sl->top_level[1] = top_level(sl->wc);
    int top = sl->top_level[0];
    float total = sl->level_within[top];
    for (int l = 0; l < SLOT_LEVELS; l++)
        sl->level_wfrac[l] = l >= top || total <= 0.0f ? 1.0f : sl->level_within[l] / total;
    /* The fraction resolved by the mip means at level l: 1 - within(l) / within(top). */
    sl->drop_lod = SLOT_LEVELS;
    for (int l = top; l >= 0 && total > 0.0f; l--) {
        if (total - sl->level_within[l] >= DROP_RESOLVED * total)
            break;
        sl->drop_lod = l;
    }
}

static void bind_tex(int unit, GLuint tex, GLint loc)
{
    glActiveTexture(GL_TEXTURE0 + (GLenum)unit);
    glBindTexture(GL_TEXTURE_2D, tex);
    if (loc >= 0)
        glUniform1i(loc, unit);
}

/* Low quality fetches no whitecaps: the fragment patterns whose whitecaps vary, which the CPU
 * grid's vertices carry at their footprint's mip level (grid.c k_moment_pass), so eq. 6 per
 * vertex sees the foam's patches as high quality's pixels do; with the patch's constants alone
 * every vertex had the same coverage (15 m/s from 10 m: low's rows up to 24 % darker than
 * high's near the camera, now 7 %: test_render test_quality_match). 0 in high quality. */
static unsigned low_foam_mask(const struct renderer *r)
{
    unsigned m = 0;
    for (int s = 0; r->d.quality != QUALITY_HIGH && s < r->nfs; s++)
        if (r->slot[s].wc && r->slot[s].wc->format == FORMAT_RGBA8 &&
            !whitecaps_constant(r->slot[s].wc))
            m |= 1u << r->slot[s].pattern;
    return m;
}

/* Vertex texture fetch pays where the tier has a unit per loop frame for every pattern beside
 * the fragment shader's, and the geometry is the projected grid (patches stay on the CPU).
 * Not for low quality on a sea with foam (low_foam_mask): its vertices' foam comes from the
 * CPU grid, so low quality draws one sea on every tier (a vertex-shader grid took the
 * patches' constants: 15 m/s from the surface, rows 44 % apart from gles2-min's,
 * test_render test_tiers_low). */
static int choose_vtf(const struct renderer *r)
{
    GLint combined = 0;
    int n = r->t->patterns;
    int hash = renderer_detile(r);
    if (r->d.cpu_geometry || r->d.geometry != GEOMETRY_GRID || r->cpu_mask || low_foam_mask(r) ||
        r->gpu->caps.vertex_texture_units < 2 * n + hash)
        return 0;
    glGetIntegerv(GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS, &combined);
    /* a unit per loop frame of every pattern and one for the lattice hash (detile.h) */
    if (combined < UNIT_PATTERNS + r->nfs + r->nwc + 2 * n + hash)
        return 0;
    for (int i = 0; i < n; i++) {
        const struct swell_table *d = tables_find(r->t, TABLE_DISP, i);
        if (!d || d->format != FORMAT_RGBA8)
            return 0;
    }
    return 1;
}

/* A texture's mip chain, level-major and tightly packed: RGBA8, or with type the GL half-float
 * type, RGBA16F (upload_chain_typed); into the chain's texture, or each level's own. */
static int upload_chain_typed(const struct chain_tex *c, int w, int h, int levels,
                              const void *data, GLenum type, const char *what,
                              struct swell_err *err)
{
    size_t off = 0, texel = type == GL_UNSIGNED_BYTE ? 4 : 8;
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    for (int l = 0; l < levels; l++) {
        int lw = w >> l > 0 ? w >> l : 1, lh = h >> l > 0 ? h >> l : 1;
        if (l == 0 || c->levels)
            glBindTexture(GL_TEXTURE_2D, chain_at(c, l));
        glTexSubImage2D(GL_TEXTURE_2D, c->levels ? 0 : l, 0, 0, lw, lh, GL_RGBA, type,
                        (const uint8_t *)data + off);
        off += texel * (size_t)lw * lh;
    }
    return gpu_check(what, err);
}

static int upload_chain(const struct chain_tex *c, int w, int h, int levels,
                        const uint8_t *data, const char *what, struct swell_err *err)
{
    return upload_chain_typed(c, w, h, levels, data, GL_UNSIGNED_BYTE, what, err);
}

/* A texture without mips (levels 1 of upload_chain). */
static int upload_single(GLuint tex, int w, int h, const uint8_t *data, const char *what,
                         struct swell_err *err)
{
    struct chain_tex c = { { tex }, 0 };
    return upload_chain(&c, w, h, 1, data, what, err);
}

/* With run_lod the sky map's levels sit in one texture without mips, twice as wide as high
 * (SWELL_RUN_LOD in ocean.frag reads two neighbouring levels of it per pixel and blends them,
 * set_run_lods): level 0 at the left, level l >= 1 at x = size, y = size - size / 2^(l-1).
 * Returns the level's side, texels. */
static int sky_atlas_at(int size, int l, int *x, int *y)
{
    *x = l == 0 ? 0 : size;
    *y = l == 0 ? 0 : size - (size >> (l - 1));
    return size >> l > 0 ? size >> l : 1;
}

/* The HDR sky map of high quality: half-float radiances where the tier has half-float
 * textures (no 8-bit steps in the dark zenith), else RGBA8 times sky.map_scale. */
static int upload_sky(struct renderer *r, const struct sky *sk, struct swell_err *err)
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

static void update_sky_constants(struct renderer *r);

static uint8_t unorm8(float x)
{
    return (uint8_t)lrintf(255.0f * fminf(fmaxf(x, 0.0f), 1.0f));
}

/* The light the sea reflects and refracts, radiances times the exposure (tone_map in
 * common.glsl takes them so): the sun's irradiance, eq. 28's water body L_sea and the
 * Lambertian 0.4 foam (Dupuy §2), both lit by sun and sky: E, the irradiance on the level
 * sea, the sun's times sin(elevation) plus the sky's. */
static void sea_light(const struct renderer *r, float sun[3], float sea[3], float foam[3])
{
    float e = r->exposure;
    for (int c = 0; c < 3; c++) {
        float lit = r->sky.sun_irr[c] * fmaxf(r->sky.sun_dir[2], 0.0f) + r->sky.sky_irr[c];
        sun[c] = r->d.no_sun ? 0.0f : e * r->sky.sun_irr[c];
        sea[c] = e * r->water_albedo[c] * lit / (float)M_PI;
        foam[c] = e * 0.4f * lit / (float)M_PI;
    }
}

/* The Fresnel textures are an atlas (detile.h): the F x F Fresnel texels in rows [0, F), row F a
 * copy of row F - 1 (a bilinear lookup at the disc's edge, fresnel_uv_scale, reads no hash), the
 * lattice hash's cells (detile_cell_table) in rows [F + 1, F + 1 + DETILE_N), columns
 * [0, DETILE_N); POT. ocean.frag reads both through one unit: gles2-min's 8 are all in use. */
static void atlas_size(const struct swell_table *fr, int *w, int *h)
{
    int need = fr->height + 1 + DETILE_N;
    *w = fr->width > DETILE_N ? fr->width : DETILE_N;
    for (*h = 1; *h < need; *h *= 2)
        ;
}

/* out (atlas_w x atlas_h RGBA8) holds the Fresnel rows; add the guard row and the hash. */
static void atlas_finish(const struct renderer *r, uint8_t *out)
{
    const struct swell_table *fr = r->fresnel;
    size_t row = 4 * (size_t)r->atlas_w;
    memset(out + row * (size_t)fr->height, 0, row * (size_t)(r->atlas_h - fr->height));
    for (int y = 0; r->atlas_w > fr->width && y < fr->height; y++)   /* a guard column too */
        memcpy(out + row * (size_t)y + 4 * (size_t)fr->width,
               out + row * (size_t)y + 4 * (size_t)(fr->width - 1), 4);
    memcpy(out + row * (size_t)fr->height, out + row * (size_t)(fr->height - 1), row);
    detile_cell_table(out + row * (size_t)(fr->height + 1), row);
}

/* Where the atlas's hash is, for ocean.frag's detile_atlas and ocean.vert's detile_atlas_v:
 * 1 / its size and the hash rows' origin v. */
static void atlas_hash_frame(const struct renderer *r, float out[4])
{
    out[0] = 1.0f / (float)r->atlas_w;
    out[1] = 1.0f / (float)r->atlas_h;
    out[2] = (float)(r->fresnel->height + 1) / (float)r->atlas_h;
    out[3] = 0.0f;
}

static int upload_atlas(const struct renderer *r, GLuint tex, uint8_t *atlas,
                        struct swell_err *err)
{
    atlas_finish(r, atlas);
    return upload_single(tex, r->atlas_w, r->atlas_h, atlas, "renderer: Fresnel upload", err);
}

static int create_disp_textures(struct renderer *r, struct swell_err *err)
{
    for (int i = 0; i < r->t->patterns; i++) {
        const struct swell_table *d = tables_find(r->t, TABLE_DISP, i);
        for (int k = 0; k < 2; k++) {
            int rc = gpu_texture_create(r->gpu, d->width, d->height, 1, FORMAT_RGBA8, 1,
                                        "renderer: displacement (vertex shader)",
                                        &r->disp_tex[i][k], err);
            if (rc)
                return rc;
            r->disp_frame[i][k] = -1;
        }
    }
    return 0;
}

/* Make the pair of pattern i hold loop frames f0 and f1, uploading only a frame it lacks. */
static void stream_disp(struct renderer *r, double t_s)
{
    for (int i = 0; i < r->t->patterns; i++) {
        const struct swell_table *d = tables_find(r->t, TABLE_DISP, i);
        struct stream_phase ph;
        int want[2], *have = r->disp_frame[i];
        stream_loop_phase(t_s, tables_pattern_period(r->t, i), r->t->frames, &ph);
        want[0] = ph.f0 < d->layers ? ph.f0 : 0;
        want[1] = ph.f1 < d->layers ? ph.f1 : 0;
        for (int k = 0; k < 2; k++) {
            int slot = have[0] == want[k] ? 0 : have[1] == want[k] ? 1 : -1;
            if (slot < 0) {
                /* replace the one the other wanted frame is not in */
                slot = (have[0] == want[1 - k]) ? 1 : 0;
                have[slot] = want[k];
                upload_single(r->disp_tex[i][slot], d->width, d->height,
                              d->data + table_offset(d, 0, want[k]), "renderer: displacement",
                              NULL);
            }
            r->disp_ab[i][k] = slot;
        }
        r->disp_w[i] = (float)ph.w / STREAM_W_ONE;
    }
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
            bind_tex(UNIT_PATTERNS + r->nfs + r->nwc + 2 * i + f,
                     r->disp_tex[i][r->disp_ab[i][f]], u[VU_A0 + 2 * i + f]);
        float sh[3];
        detile_camera_shift(i, cam->pos[0], cam->pos[1], 1.0 / pi->size_m, sh);
        cell[i][0] = sh[0];
        cell[i][1] = sh[1];
    }
    /* the atlas's hash on the unit after the displacement's (choose_vtf counts it) */
    if (renderer_detile(r))
        bind_tex(UNIT_PATTERNS + r->nfs + r->nwc + 2 * r->t->patterns,
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

static int create_textures(struct renderer *r, struct swell_err *err)
{
    const struct swell_table *fr = tables_find(r->t, TABLE_FRESNEL, -1);
    int rc;
    if (!fr) {
        if ((rc = fresnel_hu_table(FRESNEL_FALLBACK, &r->fresnel_own, err)))
            return rc;
        fr = &r->fresnel_own;
    }
    r->fresnel = fr;
    atlas_size(fr, &r->atlas_w, &r->atlas_h);
    if ((rc = sky_bake(r->d.sun_elev_deg, r->d.sun_azim_deg, SKY_MAP_SIZE, &r->sky, err)))
        return rc;
    size_t scratch = sky_level_offset(&r->sky, r->sky.levels);
    if (scratch < 4 * (size_t)r->atlas_w * r->atlas_h)
        scratch = 4 * (size_t)r->atlas_w * r->atlas_h;
    if (!(r->scratch = malloc(scratch)))
        return swell_fail(err, SWELL_E_NOMEM, "renderer: no memory for derived textures");
    for (int y = 0; y < fr->height; y++)
        memcpy(r->scratch + 4 * (size_t)r->atlas_w * y, fr->data + 4 * (size_t)fr->width * y,
               4 * (size_t)fr->width);
    if ((rc = gpu_texture_create(r->gpu, r->atlas_w, r->atlas_h, 1, FORMAT_RGBA8, 0,
                                 "renderer: Fresnel texture", &r->fresnel_tex, err)) ||
        (rc = upload_atlas(r, r->fresnel_tex, r->scratch, err)))
        return rc;
    update_sky_constants(r);
    if ((rc = gpu_texture_create(r->gpu, SKY_VIEW_N, 2, 1, FORMAT_RGBA8, 0,
                                 "renderer: background sky table", &r->sky_view_tex, err)))
        return rc;
    r->sky_half = r->gpu->caps.half_float;
    int sky_format = r->sky_half ? FORMAT_RGBA16F : FORMAT_RGBA8;
    if ((rc = r->run_lod ? gpu_texture_create(r->gpu, 2 * SKY_MAP_SIZE, SKY_MAP_SIZE, 1,
                                              sky_format, 0, "renderer: sky map atlas",
                                              &r->sky_tex.tex[0], err)
                         : chain_create(r, SKY_MAP_SIZE, SKY_MAP_SIZE, r->sky.levels, sky_format,
                                        0, "renderer: sky map", &r->sky_tex, err)) ||
        (rc = upload_sky(r, &r->sky, err)))
        return rc;
    if (r->vtf && (rc = create_disp_textures(r, err)))
        return rc;
    for (int s = 0; s < r->nfs; s++) {
        struct fs_slot *sl = &r->slot[s];
        if (!sl->slope || !sl->wc || sl->slope->format != FORMAT_RGBA8 ||
            sl->wc->format != FORMAT_RGBA8)
            return swell_fail(err, SWELL_E_FORMAT, "renderer: pattern %d lacks rgba8 slope or "
                              "whitecap tables; re-bake for the gles2-min format", sl->pattern);
        if ((rc = chain_create(r, sl->slope->width, sl->slope->height, sl->slope->levels,
                               FORMAT_RGBA8, 1, "renderer: slope", &sl->slope_tex, err)))
            return rc;
        if (!(sl->slope_b = malloc(stream_blended_bytes(sl->slope))))
            return swell_fail(err, SWELL_E_NOMEM, "renderer: no memory to blend slopes");
        r->stream_bytes += stream_blended_bytes(sl->slope);
        if (s >= r->nwc)
            continue;
        if ((rc = chain_create(r, sl->wc->width, sl->wc->height, sl->wc->levels, FORMAT_RGBA8,
                               1, "renderer: whitecap", &sl->wc_tex, err)))
            return rc;
        if (!(sl->wc_b = malloc(stream_blended_bytes(sl->wc))))
            return swell_fail(err, SWELL_E_NOMEM, "renderer: no memory to blend whitecaps");
        r->stream_bytes += stream_blended_bytes(sl->wc);
    }
    return 0;
}

static int build_programs(struct renderer *r, struct swell_err *err)
{
    char defines[128];
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
            int n = snprintf(defines, sizeof(defines), "FS_PATTERNS=%d FS_WHITECAPS=%d%s%s%s",
                             k, kw, r->d.quality == QUALITY_HIGH ? " QUALITY_HIGH" : "",
                             r->run_lod ? " SWELL_RUN_LOD" : "",
                             renderer_detile(r) ? "" : " SWELL_NO_DETILE");
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
    if ((rc = shader_program_build(&sd, &r->skyp, err)))
        return rc;
    sd.defines = "SUN_DISC";
    sd.uniform_locations = r->sunu;
    return shader_program_build(&sd, &r->sunp, err);
}

static int create_sky_mesh(struct renderer *r, struct swell_err *err)
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

static int create_buffers(struct renderer *r, struct swell_err *err)
{
    static const float quad[8] = { -1.0f, -1.0f, 1.0f, -1.0f, -1.0f, 1.0f, 1.0f, 1.0f };
    /* VTF: a static (i, j) / (w - 1, h - 1) per vertex; else the streamed CPU vertices, grid.c's
     * and vshade.c's from them */
    size_t nv = (size_t)grid_vertex_count(r->grid);
    size_t vbytes = sizeof(float) * (r->vtf ? 2 : r->cpu_vterms ? VSHADE_FLOATS : GRID_FLOATS) * nv;
    size_t gbytes = sizeof(float) * (r->vtf ? 2 : GRID_FLOATS) * nv;
    size_t ibytes = sizeof(uint16_t) * (size_t)grid_index_count(r->grid);
    int rc;
    if (!(r->verts = calloc(1, gbytes)) || (r->cpu_vterms && !(r->shaded = calloc(1, vbytes))))
        return swell_fail(err, SWELL_E_NOMEM, "renderer: no memory for %zu vertex bytes",
                          vbytes + gbytes);
    if ((rc = gpu_buffer_create(r->gpu, GL_ARRAY_BUFFER, vbytes,
                                r->vtf ? GL_STATIC_DRAW : GL_STREAM_DRAW,
                                r->vtf ? "renderer: sea grid parameters" : "renderer: sea vertices",
                                &r->vbo, err)) ||
        (rc = gpu_buffer_create(r->gpu, GL_ELEMENT_ARRAY_BUFFER, ibytes, GL_STATIC_DRAW,
                                "renderer: sea indices", &r->ibo, err)) ||
        (rc = gpu_buffer_create(r->gpu, GL_ARRAY_BUFFER, sizeof(quad), GL_STATIC_DRAW,
                                "renderer: sun quad", &r->quad_vbo, err)) ||
        (rc = create_sky_mesh(r, err)))
        return rc;
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, r->ibo);
    glBufferSubData(GL_ELEMENT_ARRAY_BUFFER, 0, (GLsizeiptr)ibytes, grid_indices(r->grid));
    glBindBuffer(GL_ARRAY_BUFFER, r->quad_vbo);
    glBufferSubData(GL_ARRAY_BUFFER, 0, sizeof(quad), quad);
    if (r->vtf) {
        int w = r->d.grid_w, h = r->d.grid_h;
        for (int j = 0; j < h; j++)
            for (int i = 0; i < w; i++) {
                r->verts[2 * (j * w + i)] = (float)i / (float)(w - 1);
                r->verts[2 * (j * w + i) + 1] = (float)j / (float)(h - 1);
            }
        glBindBuffer(GL_ARRAY_BUFFER, r->vbo);
        glBufferSubData(GL_ARRAY_BUFFER, 0, (GLsizeiptr)vbytes, r->verts);
    }
    return gpu_check("renderer: buffer upload", err);
}

/* What follows from a new sky. Automatic exposure: the sky's mean radiance E_sky / pi maps to
 * x = 0.5, Reinhard 0.33 before gamma (0.58 after), which leaves headroom for the brighter
 * horizon and the glint. The haze (sky_haze), its radiances scaled by that exposure. */
static void update_sky_constants(struct renderer *r)
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

static int probe_programs(struct renderer *r, struct swell_err *err)
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
            unsigned refuse = r->d.probe_refuse |
                              (renderer_detile(r) ? r->d.probe_refuse_detile : 0u) |
                              (r->cpu_vterms ? 0u : r->d.probe_refuse_gpu_vertex);
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

static int create_once(const struct renderer_desc *desc, struct renderer **out,
                       struct swell_err *err)
{
    struct renderer *r;
    struct grid_desc gd = { 0 };
    int rc;
    *out = NULL;
    if (!desc || !desc->tables || !desc->gpu)
        return swell_fail(err, SWELL_E_ARG, "renderer: descriptor needs tables and a gpu");
    if (desc->quality < 0 || desc->quality >= QUALITY_COUNT || desc->geometry < 0 ||
        desc->geometry >= GEOMETRY_COUNT || desc->detile < 0 || desc->detile >= DETILE_MODE_COUNT)
        return swell_fail(err, SWELL_E_ARG, "renderer: quality %d / geometry %d / detile %d out "
                          "of range", desc->quality, desc->geometry, desc->detile);
    if (!(r = calloc(1, sizeof(*r))))
        return swell_fail(err, SWELL_E_NOMEM, "renderer: no memory");
    r->d = *desc;
    water_albedo(WATER_CHLOROPHYLL_OPEN, r->water_albedo);
    resolve(&r->d);
    uint64_t before = desc->gpu->bytes;
    r->gpu = desc->gpu;
    r->t = desc->tables;
    assign_patterns(r);
    r->vtf = choose_vtf(r);
    r->cpu_vterms = !r->vtf && r->d.cpu_vertex_terms;
    r->run_lod = r->gpu->caps.prefer_run_lod && !r->d.pixel_lod;
    gd.tables = r->t;
    gd.kind = r->d.geometry;
    gd.w = r->d.grid_w;
    gd.h = r->d.grid_h;
    gd.cpu_patterns = r->cpu_mask;
    r->k_mask = low_foam_mask(r);   /* never with vtf (choose_vtf) */
    gd.k_patterns = r->k_mask;
    gd.no_detile = !renderer_detile(r);
    if ((rc = grid_create(&gd, &r->grid, err)) || (rc = create_textures(r, err)) ||
        (rc = build_programs(r, err)) || (rc = create_buffers(r, err)) ||
        (rc = probe_programs(r, err)))
        goto fail;
    r->gpu_bytes = r->gpu->bytes - before;
    *out = r;
    return 0;
fail:
    swell_err_context(err, "renderer_create");
    renderer_destroy(r);
    return rc;
}

/* One build for renderer_create: 0 and the number of programs refused in *refused, or its
 * error; a driver that runs none of them (SWELL_E_SHADER) counts as refusing all, with no
 * renderer. */
static int create_try(const struct renderer_desc *d, struct renderer **out, int *refused,
                      struct swell_err *err)
{
    int rc = create_once(d, out, err);
    *refused = rc == 0 ? (*out)->refused : OCEAN_VARIANTS + 1;
    return rc == SWELL_E_SHADER ? 0 : rc;
}

/* Where the driver refuses ocean programs (issue 15), built again in the ways that may fit,
 * in order: on gles2-min the terms of each vertex on the CPU (vshade.h: Vivante GC2000 refuses
 * ocean.vert's past its 256 instructions; costs CPU time, not the picture); with --detile auto,
 * without the lattice of random offsets (VideoCore IV runs 7 of high quality's 12 programs
 * with it, 12 without: each pattern then repeats on its tile, the lesser loss than the
 * patterns a refused program's rows go without); both (GC2000: 1, 3 with the CPU's terms, 12
 * with both). The first build the driver refuses nothing of is kept, else the one it refuses
 * least of (the earliest of those): one renderer at a time, so the GPU budget holds. */
int renderer_create(const struct renderer_desc *desc, struct renderer **out, struct swell_err *err)
{
    struct swell_err first_err = { 0 };
    int first, rc = create_try(desc, out, &first, &first_err);
    if (rc || first == 0) {
        if (err)
            *err = first_err;
        return rc;
    }
    /* what the first build resolved (create_once): vertex texture fetch leaves no vertex
     * terms to move; auto's lattice is on in high quality */
    struct renderer_desc probe_d = *desc;
    resolve(&probe_d);
    int vtf = *out ? (*out)->vtf : 0, cpu = *out ? (*out)->cpu_vterms : desc->cpu_vertex_terms;
    struct renderer_desc tries[3];
    int n = 0, can_cpu = !vtf && !cpu;
    int can_off = desc->detile == DETILE_MODE_AUTO && probe_d.detile == DETILE_MODE_ON;
    if (can_cpu) {
        tries[n] = *desc;
        tries[n++].cpu_vertex_terms = 1;
    }
    if (can_off) {
        tries[n] = *desc;
        tries[n++].detile = DETILE_MODE_OFF;
    }
    if (can_cpu && can_off) {
        tries[n] = tries[n - 1];
        tries[n++].cpu_vertex_terms = 1;
    }
    int best = -1, best_refused = first, cur = -1;   /* -1: desc itself */
    for (int i = 0; i < n && best_refused > 0; i++) {
        int refused;
        if (*out)
            renderer_destroy(*out);
        *out = NULL;
        cur = i;
        if ((rc = create_try(&tries[i], out, &refused, err)))
            return rc;
        if (refused < best_refused) {
            best = i;
            best_refused = refused;
        }
    }
    if (best_refused > OCEAN_VARIANTS) {   /* none runs any: the first build's message */
        if (*out)
            renderer_destroy(*out);
        *out = NULL;
        if (err)
            *err = first_err;
        return SWELL_E_SHADER;
    }
    if (cur != best || !*out) {
        if (*out)
            renderer_destroy(*out);
        *out = NULL;
        if ((rc = create_once(best < 0 ? desc : &tries[best], out, err)))
            return rc;
    }
    if (best >= 0) {
        (*out)->detile_refused = renderer_detile(*out) ? 0 : first;
        if (first > OCEAN_VARIANTS)
            fprintf(stderr, "swell: built again as%s: the driver refuses %d ocean program(s), "
                    "not all\n", program_tags(*out), (*out)->refused);
        else
            fprintf(stderr, "swell: built again as%s: the driver refuses %d ocean program(s), "
                    "not %d\n", program_tags(*out), (*out)->refused, first);
    }
    if (err)
        memset(err, 0, sizeof(*err));   /* a try that failed on the way is no error */
    return 0;
}

int renderer_set_sun(struct renderer *r, float elev_deg, float azim_deg, struct swell_err *err)
{
    struct sky fresh;
    if (!(elev_deg > 0.0f && elev_deg <= 90.0f) || !isfinite(azim_deg))
        return swell_fail(err, SWELL_E_ARG, "renderer_set_sun: elevation %g deg must be in (0, "
                          "90] and azimuth %g deg finite", (double)elev_deg, (double)azim_deg);
    /* bake first: a failure leaves the current sky in place */
    int rc = sky_bake(elev_deg, azim_deg, SKY_MAP_SIZE, &fresh, err);
    if (rc)
        return rc;
    if (r->sky_tex.tex[0] && (rc = upload_sky(r, &fresh, err))) {
        sky_destroy(&fresh);
        return rc;
    }
    sky_destroy(&r->sky);
    r->sky = fresh;
    r->d.sun_elev_deg = elev_deg;
    r->d.sun_azim_deg = azim_deg;
    update_sky_constants(r);
    return 0;
}

/* Dequantised first texel of the top (1x1) level of a blended chain or, for a table that is
 * not streamed, of the table itself (constant tables only reach here unstreamed). */
static void top_texel(const struct swell_table *t, const uint8_t *chain, float out[4])
{
    const uint8_t *px = chain ? chain + stream_level_offset(t, t->levels - 1)
                              : t->data + table_offset(t, t->levels - 1, 0);
    for (int c = 0; c < 4; c++)
        out[c] = t->bias[c] + t->scale[c] * (float)px[c] * (1.0f / 255.0f);
}

/* A slot's moments where its pattern is not fetched: mean and variance over the whole patch. */
static void slot_constants(struct fs_slot *sl)
{
    float m[4];
    top_texel(sl->slope, sl->slope_b, m);
    sl->top_slope[0] = m[0];
    sl->top_slope[1] = m[1];
    sl->top_slope[2] = fmaxf(m[2] - m[0] * m[0], 0.0f);
    sl->top_slope[3] = fmaxf(m[3] - m[1] * m[1], 0.0f);
    top_texel(sl->wc, sl->wc_tex.tex[0] ? sl->wc_b : NULL, m);
    sl->top_k[0] = m[0];
    sl->top_k[1] = fmaxf(m[1] - m[0] * m[0], 0.0f);
}

static void stream_textures(struct renderer *r, double t_s)
{
    for (int s = 0; s < r->nfs; s++) {
        struct fs_slot *sl = &r->slot[s];
        struct stream_phase ph;
        stream_loop_phase(t_s, tables_pattern_period(r->t, sl->pattern), r->t->frames, &ph);
        if (sl->phase_valid && ph.f0 == sl->phase.f0 && ph.w == sl->phase.w)
            continue;
        sl->phase = ph;
        sl->phase_valid = 1;
        stream_blend(sl->slope, &ph, sl->slope_b);
        upload_chain(&sl->slope_tex, sl->slope->width, sl->slope->height, sl->slope->levels,
                     sl->slope_b, "renderer: slope stream", NULL);
        if (sl->wc_tex.tex[0]) {
            stream_blend(sl->wc, &ph, sl->wc_b);
            upload_chain(&sl->wc_tex, sl->wc->width, sl->wc->height, sl->wc->levels, sl->wc_b,
                         "renderer: whitecap stream", NULL);
        }
        slot_constants(sl);
    }
}


/* The sky is drawn only above the horizon (a scissor from just below the horizon's row up):
 * below it the sea covers every pixel, and a full-screen sky pass there was pure overdraw. */
static int draw_sky(struct renderer *r, const struct camera *cam, mat4 world_to_clip,
                    int width, int height, struct swell_err *err)
{
    mat4 inv;
    float h = cam->heading_deg * (float)(M_PI / 180.0);
    /* the sphere's horizon, a circle acos(R / (R + alt)) below the level (camera.h): its lowest
     * row on screen, over the azimuths of the front half (from high up it bends down towards
     * the sides, and a row through its middle left the corners to neither sky nor sea) */
    double alt = fmax(cam->pos[2], 0.0);
    double dip = acos(EARTH_RADIUS_M / (EARTH_RADIUS_M + alt));
    float hz = 2.0f;   /* NDC y of the lowest horizon point in view */
    for (int k = 0; k <= 64; k++) {
        float a = h + (float)M_PI * ((float)k / 64.0f - 0.5f);
        vec4 dir = { (float)cos(dip) * cosf(a), (float)cos(dip) * sinf(a), (float)-sin(dip),
                     0.0f }, clip;
        glm_mat4_mulv(world_to_clip, dir, clip);
        if (clip[3] > 0.0f && fabsf(clip[0]) <= 1.05f * clip[3])
            hz = fminf(hz, clip[1] / clip[3]);
    }
    if (hz > 1.5f)
        hz = -1.0f;   /* no horizon in view: the sky pass everywhere */
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
    glScissor(0, y0, width, height - y0);
    glm_mat4_inv(world_to_clip, inv);
    glUseProgram(r->skyp.program);
    glUniformMatrix4fv(r->su[SU_CLIP_TO_WORLD], 1, GL_FALSE, (const GLfloat *)inv);
    glUniform3fv(r->su[SU_SKY_VIEW_SCALE], 2, &r->sky_view_scale[0][0]);
    glUniform4f(r->su[SU_SKY_SUN], r->sky.sun_dir[0], r->sky.sun_dir[1], r->sky.sun_dir[2],
                r->haze.mie_g);
    bind_tex(UNIT_SKY, r->sky_view_tex, r->su[SU_SKY_VIEW]);
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
        mat4 proj;
        camera_projection(cam, height > 0 ? (float)width / (float)height : 1.0f, proj);
        /* radius: the disc's angle times the projection's scale (small-angle, near the axis) */
        float ndc[4] = { clip[0] / clip[3], clip[1] / clip[3], SUN_RADIUS_RAD * proj[0][0],
                         SUN_RADIUS_RAD * proj[1][1] };
        float sun_rad[3];
        for (int c = 0; c < 3; c++)
            sun_rad[c] = r->exposure * r->sky_view_sun[c] / 6.8e-5f;
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

/* The camera's altitude for the pixel footprint (at least 0.5 m) and one pixel's angle, rad. */
static void view_scale(const struct camera *cam, int height, float *alt, float *pix)
{
    float fov = (cam->fov_y_deg > 0.0f ? cam->fov_y_deg : 45.0f) * (float)(M_PI / 180.0);
    *alt = fmaxf((float)cam->pos[2], 0.5f);
    *pix = 2.0f * tanf(0.5f * fov) / (float)(height > 0 ? height : 1);
}

/* This frame's values for the terms of the vertex alone: vshade.c takes them on gles2-min, the
 * programs (ocean.vert's vterms.glsl, and ocean.frag some of them) as uniforms. */
static void vertex_frame(struct renderer *r, const struct camera *cam, int height)
{
    struct vshade_frame *f = &r->vf;
    float alt, pix;
    memset(f, 0, sizeof(*f));
    lin_frame(r, f->lin_s0, f->total_var);
    memcpy(f->sun_dir, r->sky.sun_dir, sizeof(f->sun_dir));
    f->fresnel_uv_scale[0] = (float)r->fresnel->width / (float)r->atlas_w;
    f->fresnel_uv_scale[1] = (float)r->fresnel->height / (float)r->atlas_h;
    f->sky_map_size = (float)r->sky.size;
    view_scale(cam, height, &alt, &pix);
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
static void set_ocean_uniforms(struct renderer *r, int k, int kw, const struct camera *cam,
                               mat4 world_to_clip)
{
    const GLint *u = r->ou[VARIANT(k, kw)];
    if (r->vtf)
        set_vtf_uniforms(r, VARIANT(k, kw), cam);
    float off[SWELL_MAX_PATTERNS][2] = { { 0 } }, inv[SWELL_MAX_PATTERNS] = { 0 };
    float ss[SWELL_MAX_PATTERNS][4] = { { 0 } }, sb[SWELL_MAX_PATTERNS][4] = { { 0 } };
    float ws[SWELL_MAX_PATTERNS][4] = { { 0 } }, wb[SWELL_MAX_PATTERNS][4] = { { 0 } };
    float cs[4] = { 0.0f, 0.0f, 0.0f, 0.0f }, ck[2] = { 0.0f, 0.0f };
    float dsh[SWELL_MAX_PATTERNS][3] = { { 0 } };
    float sun[3], sea[3], foam[3], e = r->exposure;
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
        bind_tex(UNIT_PATTERNS + s, chain_at(&sl->slope_tex, 0), u[OU_SLOPE_TEX0 + s]);
        if (r->d.quality == QUALITY_HIGH) {
            /* the fetched patch's variance T (and below its foam memory's mean and variance)
             * in the constants: ocean.frag's slot adds only what depends on its taps */
            cs[2] += sl->top_slope[2];
            cs[3] += sl->top_slope[3];
        }
        if (s < kw) {   /* kw <= nwc: whitecap textures exist for these (create_textures) */
            bind_tex(UNIT_PATTERNS + r->nfs + s, chain_at(&sl->wc_tex, 0), u[OU_WC_TEX0 + s]);
            if (r->d.quality == QUALITY_HIGH) {
                ck[0] += sl->top_k[0];
                ck[1] += sl->top_k[1];
            }
        } else {
            add_k_constants(r, sl, ck);
        }
    }
    sea_light(r, sun, sea, foam);
    glUniformMatrix4fv(u[OU_WORLD_TO_CLIP], 1, GL_FALSE, (const GLfloat *)world_to_clip);
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
    bind_tex(UNIT_FRESNEL, r->fresnel_tex, u[OU_FRESNEL_TEX]);
    bind_tex(UNIT_SKY, chain_at(&r->sky_tex, 0), u[OU_SKY_TEX]);
    glUniform1f(u[OU_SKY_SCALE], e * (r->sky_half ? 1.0f : r->sky.map_scale));
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
}

/* One LOD per run (SWELL_RUN_LOD): each fetched table at the mip level nearest the LOD the
 * hardware would take at the row, so a run is a span of rows where no table's level changes.
 * Whole levels, because llvmpipe fetches one level where the LOD has no fraction and two (the
 * trilinear blend) otherwise: measured at 1 km, gles3, whole levels made the frame 10 % faster
 * than fractional ones, which were no faster than per-pixel LOD (sampling at one level and
 * choosing it per run is GL_LINEAR_MIPMAP_NEAREST made coarser: up to half a level too sharp
 * or too blurred, and a visible step only where patterns are still resolved).
 * Along a row of the projected grid the footprint grows from the centre of the screen (where
 * grid_row_span's distance is taken) to its edges: at 16:9 and 45 degrees vertical field of
 * view the edge is 1.24x farther, 1.55x the footprint (0.63 levels). The LOD is taken at 1.25x
 * the centre's footprint, a third of a level up, between the two. */
#define RUN_LOD_ROW_MEAN 1.25f
#define RUN_LOD_MAX (SLOT_LEVELS - 1)

static int nearest_level(float log2_foot, float log2_density)
{
    float lod = floorf(log2_foot + log2_density + 0.5f);
    return lod <= 0.0f ? 0 : lod >= (float)RUN_LOD_MAX ? RUN_LOD_MAX : (int)lod;
}

/* Slots fetched for a row whose nearest vertex is at squared horizontal distance d2: those whose
 * patch is still larger than drop x the pixel footprint there. On a plane seen from altitude a
 * at distance d the footprint along the view (the larger axis, which sets the LOD) is
 * d^2 / a times the pixel's angle. With resolved, also only those whose mip means still vary
 * at the row's level (drop_lod; the level a run fetches, nearest_level). Slots are largest
 * first, so the answer is a count. */
static float row_footprint(float d2, float alt, float pix_angle)
{
    return (d2 + alt * alt) / alt * pix_angle;
}

static int slots_needed(const struct renderer *r, float d2, float alt, float pix_angle,
                        float drop, int resolved)
{
    float foot = row_footprint(d2, alt, pix_angle), lf = log2f(foot * RUN_LOD_ROW_MEAN);
    int k = 0;
    while (k < r->nfs && r->t->pattern[r->slot[k].pattern].size_m * drop > foot &&
           (!resolved || r->d.keep_resolved ||
            nearest_level(lf, r->slot[k].log2_density[0]) < r->slot[k].drop_lod))
        k++;
    return k;
}

/* The run key of a row at footprint foot (m per pixel) fetching k slopes and kw whitecaps: the
 * level of each fetched table, 4 bits each (slopes in the low 16 bits). 0 without run_lod. */
static uint32_t run_lod_key(const struct renderer *r, float foot, int k, int kw)
{
    uint32_t key = 0;
    if (!r->run_lod)
        return 0;
    float lf = log2f(foot * RUN_LOD_ROW_MEAN);
    for (int s = 0; s < k; s++) {
        /* never the last level fetched before the drop (drop_lod - 1): its means hold a sliver
         * of the variance and the next level's none, too little for weight_terms' contrast
         * line to scale up to what the pixel would resolve (its blocky 8x8 texels of a band
         * several octaves finer), so the texture stepped there. The run keeps the level
         * before, whose line takes the detail out on the way to the drop: at calm 1 km 45 deg
         * down, low quality, the seam metric 1.60 -> 1.21 (test_seams) */
        int lev = nearest_level(lf, r->slot[s].log2_density[0]);
        int last = r->d.keep_resolved ? RUN_LOD_MAX : r->slot[s].drop_lod - 2;
        key |= (uint32_t)(lev < last || last < 0 ? lev : last) << (4 * s);
        if (s < kw)
            key |= (uint32_t)nearest_level(lf, r->slot[s].log2_density[1]) << (16 + 4 * s);
    }
    return key;
}

/* Eq. 27's sky footprint (log2 texels) at footprint f (log2 m, ocean.frag V_FOOT) of a row at
 * squared distance d2 seen from altitude alt, fetching k slots: 2 sigma size du/dzeta with
 * du/dzeta = 1 / (1 + r_z), as ocean.vert and ocean.frag take it per pixel, here with sigma^2
 * the unresolved variance, the top variance of the slots not fetched and each fetched slot's
 * mean within-texel variance at the level f asks (between whole levels geometric: continuous
 * in f, so neighbouring runs agree where they meet; the larger of x and y, as the shader);
 * r_z the reflected view's on a flat sea. */
static float sky_run_foot(const struct renderer *r, int k, float f, float d2, float alt)
{
    float var[2] = { r->t->mss_unresolved_x, r->t->mss_unresolved_y };
    for (int s = 0; s < r->nfs && s < SWELL_MAX_PATTERNS; s++) {
        const struct fs_slot *sl = &r->slot[s];
        if (s >= k) {
            var[0] += sl->top_slope[2];
            var[1] += sl->top_slope[3];
            continue;
        }
        float x = fminf(fmaxf(f + sl->log2_density[0], 0.0f), (float)sl->top_level[0]);
        int l0 = (int)floorf(x), l1 = l0 < sl->top_level[0] ? l0 + 1 : l0;
        for (int c = 0; c < 2; c++) {
            float v0 = fmaxf(sl->level_var[l0][c], 1e-12f), v1 = fmaxf(sl->level_var[l1][c], 1e-12f);
            var[c] += v0 * powf(v1 / v0, x - (float)l0);
        }
    }
    float rz = alt / sqrtf(d2 + alt * alt);
    return 0.5f * log2f(fmaxf(fmaxf(var[0], var[1]), 1e-4f)) +
           log2f(2.0f * (float)r->sky.size / (1.0f + rz));
}

/* The levels of a run from its key, bound as textures, and the sky map's two levels
 * (ocean.frag SWELL_RUN_LOD): eq. 27's footprint (sky_run_foot) at the run's farthest and
 * nearest rows (squared distances d2_far, d2_near), as a line in the pixel's footprint V_FOOT
 * between them, blends level L = floor of the smaller and L + 1, read from the sky atlas
 * (sky_atlas_at), each clamped half a texel inside its block as clamp-to-edge would. Before,
 * a run read one whole level: where the next run read another, the brightness stepped (6-9 %
 * at a 1 km view, test_seams test_sky_levels_continuous). */
static void set_run_lods(struct renderer *r, int k, int kw, uint32_t key, float d2_far,
                         float d2_near, float alt, float pix)
{
    int sl[SWELL_MAX_PATTERNS] = { 0 }, wl[SWELL_MAX_PATTERNS] = { 0 };
    if (!r->run_lod)
        return;
    for (int s = 0; s < k && s < SWELL_MAX_PATTERNS; s++) {
        sl[s] = (int)((key >> (4 * s)) & 15u);
        wl[s] = s < kw ? (int)((key >> (16 + 4 * s)) & 15u) : 0;
    }
    float f_far = log2f(row_footprint(d2_far, alt, pix) * RUN_LOD_ROW_MEAN);
    float f_near = log2f(row_footprint(d2_near, alt, pix) * RUN_LOD_ROW_MEAN);
    float s_far = sky_run_foot(r, k, f_far, d2_far, alt);
    float s_near = sky_run_foot(r, k, f_near, d2_near, alt);
    int top = r->sky.levels - 1;
    int l0 = (int)fminf(fmaxf(floorf(fminf(s_far, s_near)), 0.0f), (float)top);
    int l1 = l0 < top ? l0 + 1 : l0;
    /* w = s(V_FOOT) - l0 = a V_FOOT + b */
    float a = f_far - f_near > 1e-3f ? (s_far - s_near) / (f_far - f_near) : 0.0f;
    float b = s_near - a * f_near - (float)l0;
    float blk[2][4], half[2];
    for (int i = 0; i < 2; i++) {
        int x, y, n = sky_atlas_at(r->sky.size, i ? l1 : l0, &x, &y);
        blk[i][0] = (float)n / (float)(2 * r->sky.size);
        blk[i][1] = (float)n / (float)r->sky.size;
        blk[i][2] = (float)x / (float)(2 * r->sky.size);
        blk[i][3] = (float)y / (float)r->sky.size;
        half[i] = 0.5f / (float)n;
    }
    const GLint *u = r->ou[VARIANT(k, kw)];
    glUniform4f(u[OU_SKY_RUN_LOD], a, b, half[0], half[1]);
    glUniform4fv(u[OU_SKY_RUN_BLK], 2, &blk[0][0]);
    /* no LOD in the shader: each table's level is the texture bound (chain_tex) */
    for (int s = 0; s < k && s < SWELL_MAX_PATTERNS; s++) {
        bind_tex(UNIT_PATTERNS + s, chain_at(&r->slot[s].slope_tex, sl[s]), -1);
        if (s < kw)
            bind_tex(UNIT_PATTERNS + r->nfs + s, chain_at(&r->slot[s].wc_tex, wl[s]), -1);
    }
}

/* log2 of the footprint (m, at a row's nearest vertex) from which slots_needed no longer
 * fetches slot s with these arguments (slots are largest first: the least over slots 0..s);
 * INFINITY where it always does. */
static float slot_drop_foot(const struct renderer *r, int s, float drop, int resolved)
{
    float lf = INFINITY;
    for (int j = 0; j <= s; j++) {
        const struct fs_slot *sl = &r->slot[j];
        float l = log2f(r->t->pattern[sl->pattern].size_m * drop);
        /* nearest_level(lf + log2 RUN_LOD_ROW_MEAN, density) < drop_lod */
        if (resolved && !r->d.keep_resolved && sl->drop_lod < SLOT_LEVELS)
            l = fminf(l, (float)sl->drop_lod - 0.5f - sl->log2_density[0] -
                             log2f(RUN_LOD_ROW_MEAN));
        lf = fminf(lf, l);
    }
    return lf;
}

/* The variance of a table's mip means at level l: what its texels resolve below the whole
 * patch, within(top) - within(l) (Bruneton §4.1). */
static float means_var(const float *within, int stride, int l, int top)
{
    l = l < 0 ? 0 : l > top ? top : l;
    return fmaxf(within[stride * top] - within[stride * l], 0.0f);
}

static float within_at(const float *within, int stride, int l, int top)
{
    return within[stride * (l < 0 ? 0 : l > top ? top : l)];
}

/* One table's weight terms (ocean.frag slot_weight) for a run: the fade to its drop footprint
 * drop_lf and, at whole level lev (lev < 0: per-pixel LOD), the contrast of the level the
 * footprint asks for. The ideal variance of the means at fractional level x is taken
 * log-linear between whole levels, so at x = lev +- 0.5 the contrast sqrt(V(x) / V(lev)) is
 * (V(lev +- 1) / V(lev))^(1/4), what the neighbouring run's level gives there: the runs meet
 * at equal contrast. Between, it is linear in x. At x = lev - 0.5 the level is half an octave
 * coarser than the pixel, so its bilinear texels change by 1 / sqrt(2) as much from pixel to
 * pixel as the finer neighbour's: RUN_BLUR_GAIN more contrast there keeps the texture the
 * viewer sees (|dI/dx|, test_seams) continuous across the runs, not only the variance
 * (measured at rough 1 km, 45 deg down: 4-row window step 1.65 -> 1.18). x is the level at
 * the shader's footprint (ocean.vert lod_foot) times RUN_LOD_ROW_MEAN, as the runs choose
 * their levels by (run_lod_key): so the lines meet where the runs do (anchored at the
 * footprint itself, test_seams' worst step was 1.41 in high, now 1.32). Also the level of the
 * means' variance the shader moves to within the pixel (the fade's middle at per-pixel LOD). */
static int weight_terms(const float *within, int stride, int top, float density, float drop_lf,
                        int lev, float out[4], float *cmax)
{
    *cmax = 1.0f;
    out[0] = 0.0f;
    out[1] = 1.0f;
    if (isfinite(drop_lf)) {
        out[0] = -1.0f / FADE_LEVELS;
        out[1] = (drop_lf - FADE_MARGIN) / FADE_LEVELS;
    }
    out[2] = 0.0f;
    out[3] = 1.0f;
    if (lev < 0 || !RUN_CONTRAST) {
        if (!isfinite(drop_lf))
            return top;   /* no fade: g = 1, the level unused */
        return (int)floorf(drop_lf - FADE_MARGIN - 0.5f * FADE_LEVELS + density + 0.5f);
    }
    float v = means_var(within, stride, lev, top);
    if (v > 0.0f) {
        float lo = lev > 0 ? RUN_BLUR_GAIN * powf(means_var(within, stride, lev - 1, top) / v,
                                                  0.25f)
                           : 1.0f;
        /* where a level has nearly no contrast left (a band ending within an octave, as in
         * synthetic tables of a few waves) its texels hold no detail worth amplifying */
        lo = fminf(lo, RUN_CONTRAST_MAX);
        float hi = lev < top ? powf(means_var(within, stride, lev + 1, top) / v, 0.25f) : 0.0f;
        out[2] = hi - lo;                                   /* per octave of footprint */
        out[3] = lo + out[2] * (density - (float)lev + 0.5f + log2f(RUN_LOD_ROW_MEAN));
        /* no more than at x = lev - 0.5: a row's vertices reach beyond it, and the line
         * extrapolated there overshoots */
        *cmax = fmaxf(lo, hi);
    }
    return lev;
}

/* The slots' weights for a run fetching k slopes and kw whitecaps at the levels of key (with
 * run_lod), the means (top level) and the variance of the means at the level the shader
 * treats, and the footprint's terms for ocean.vert lod_foot (camera altitude alt, pixel angle
 * pix, as draw_runs). */
/* The loop gain of slot sl at fractional level lam (rho linear between whole levels). */
static float loop_gain_at(const struct fs_slot *sl, float lam)
{
    int top = sl->top_level[0];
    lam = fminf(fmaxf(lam, 0.0f), (float)top);
    int l0 = (int)floorf(lam), l1 = l0 < top ? l0 + 1 : l0;
    float f = lam - (float)l0;
    float rho = sl->level_rho[l0] + (sl->level_rho[l1] - sl->level_rho[l0]) * f;
    return loop_gain(rho, sl->phase_valid ? sl->phase.w : 0);
}

/* Scales a slot's contrast line c(f) = l[3] + l[2] f (weight_terms) by the loop gain at both
 * ends fa, fb of the footprints it spans (log2 m; the run's rows, or its level +- 1/2 with
 * run_lod): the line through the products, so neighbouring runs meet at equal gain. */
static void apply_loop_gain(const struct fs_slot *sl, float fa, float fb, float l[4], float *cmax)
{
    float d = sl->log2_density[0];
    float ga = loop_gain_at(sl, fa + d), gb = loop_gain_at(sl, fb + d);
    float ca = (l[3] + l[2] * fa) * ga, cb = (l[3] + l[2] * fb) * gb;
    l[2] = fb - fa > 1e-3f ? (cb - ca) / (fb - fa) : 0.0f;
    l[3] = ca - l[2] * fa;
    *cmax *= fmaxf(ga, gb);
}

/* How far ocean.frag add_whitecap trusts a fetched within-texel variance of the foam memory,
 * <m^2> - <m>^2 from two RGBA8 channels, over the level's mean S: S^2 / (S^2 + N^2), N the
 * deviation of its rounding, each channel's (uniform, step^2 / 12) taken twice (the texel's and
 * an 8-bit filter's), the mean's through 2 <m> d<m>. */
static float wc_trust(const struct fs_slot *sl, float level_mean)
{
    const float *sc = sl->wc->scale;
    double km = sl->top_k[0], q = 1.0 / 255.0;
    double n2 = 2.0 / 12.0 * q * q * (sc[1] * sc[1] + 4.0 * km * km * sc[0] * sc[0]);
    double s2 = (double)level_mean * level_mean;
    return s2 + n2 > 0.0 ? (float)(s2 / (s2 + n2)) : 0.0f;
}

/* Low quality's pixel slope variance from the fetched slots at footprint f (log2 m), as high
 * quality's g v + (1 - g) W + (1 - g^2) (T - W) (ocean.frag add_slope) takes it with the
 * fetched within-texel variance v at its mean W over the level read there (log-linear
 * between levels): W + (1 - h^2) (T - W), h = min(g, 1). Per slot s: its weight's terms
 * sl_lod, largest contrast factor cmax[s][0], wt (T xy; its level at f: wt[2] f + wt[3]), W / T
 * per level wfrac[l][s]. */
static void pixel_var_at(const float sl_lod[][4], const float cmax[][2], const float wt[][4],
                         const float wfrac[][4], int k, float f, float out[2])
{
    out[0] = out[1] = 0.0f;
    for (int s = 0; s < k; s++) {
        const float *l = sl_lod[s];
        float g = fminf(fmaxf(l[0] * f + l[1], 0.0f), 1.0f) *
                  fminf(fmaxf(l[3] + l[2] * f, 0.0f), cmax[s][0]);
        float h = fminf(g, 1.0f);
        float lam = fminf(fmaxf(wt[s][2] * f + wt[s][3], 0.0f), (float)(SLOT_LEVELS - 1));
        int i0 = (int)floorf(lam), i1 = i0 + 1 < SLOT_LEVELS ? i0 + 1 : i0;
        float frac = wfrac[i0][s] + (wfrac[i1][s] - wfrac[i0][s]) * (lam - (float)i0);
        for (int c = 0; c < 2; c++) {
            float w = wt[s][c] * frac;
            out[c] += w + (1.0f - h * h) * (wt[s][c] - w);
        }
    }
}

/* The share of level 0's variance below a texel that ocean.frag add_whitecap keeps as eq. 6's
 * blur where a texel spans two pixels or more (the rest is drawn as detail from the finer
 * patterns' slopes, main): 0 drew hard, frayed edges (storm from 15 m), 0.35 soft ones with
 * the detail in them; a look, not a measurement. */
#define FOAM_BLUR_SHARE 0.35f

/* ocean.frag add_whitecap's B and s (the share of c0 left to eq. 6's blur) as lines in the
 * pixel's footprint f (log2 m), clamped to [0, 1] and [blur, 1] there, for slot sl: tr = (B, s
 * at f = 0; their slopes per unit of f). At the level lambda = f + log2 density the pixel
 * reads, B runs through wc_trust at levels 0 and 1 (0.2-0.25 at level 0 and 0.7-0.85 at level
 * 1 in 8-15 m/s bakes, 0.92-0.96 at level 2, where the line is already 1), 0 where level 0 is
 * magnified (lambda < -B0 / (B1 - B0)); s is 1 down to level 0 and blur where a texel spans
 * two pixels (lambda = -1; a linear field's variance over a footprint goes as its square, 1/4
 * there): the rest is drawn as detail. c0 = W0, level 0's mean. */
static void wc_trust_terms(const struct fs_slot *sl, float blur, float tr[4], float *c0)
{
    float w0 = sl->level_kvar[0], w1 = sl->level_kvar[sl->top_level[1] > 0 ? 1 : 0];
    float b0 = wc_trust(sl, w0), b1 = wc_trust(sl, w1), d = sl->log2_density[1];
    float db = b1 > b0 ? b1 - b0 : 0.0f;
    *c0 = w0;
    tr[0] = b0 + db * d;
    tr[1] = 1.0f + (1.0f - blur) * d;   /* blur + (1 - blur) (1 + lambda), clamped at blur */
    tr[2] = db;
    tr[3] = 1.0f - blur;
}

static void set_slot_lods(struct renderer *r, int k, int kw, uint32_t key, float alt, float pix,
                          float lf_far, float lf_near)
{
    const GLint *u = r->ou[VARIANT(k, kw)];
    float sl_lod[SWELL_MAX_PATTERNS][4] = { { 0 } }, wc_lod[SWELL_MAX_PATTERNS][4] = { { 0 } };
    float smu[SWELL_MAX_PATTERNS][4] = { { 0 } }, wmu[SWELL_MAX_PATTERNS][4] = { { 0 } };
    float svar[SWELL_MAX_PATTERNS][2] = { { 0 } }, cmax[SWELL_MAX_PATTERNS][2] = { { 0 } };
    float wt_v[SWELL_MAX_PATTERNS][4] = { { 0 } }, wfrac[SLOT_LEVELS][4] = { { 0 } };
    float wtr[SWELL_MAX_PATTERNS][4] = { { 0 } }, tvar = 0.0f;
    /* ocean.frag main: the detail's slots, their patches' variance T (T - W at the run's level,
     * nearer the detail's own variance where their means hold less than T, changed the
     * detail's amplitude from run to run: brightness steps of up to 8.7 % between runs) */
    for (int s = kw; s < k && s < r->nfs; s++)
        tvar += r->slot[s].top_slope[2] + r->slot[s].top_slope[3];
    /* without slots finer than the foam's, no detail: c0 stays eq. 6's blur */
    float blur = tvar > 0.0f ? FOAM_BLUR_SHARE : 1.0f;
    for (int s = 0; s < k && s < r->nfs; s++) {
        const struct fs_slot *sl = &r->slot[s];
        float drop = r->d.fetch_all ? INFINITY : slot_drop_foot(r, s, DROP_FOOTPRINT, 1);
        int key_lev = (int)((key >> (4 * s)) & 15u);
        /* on x + y: the contrast of both */
        int lev = weight_terms(sl->level_within, 1, sl->top_level[0], sl->log2_density[0], drop,
                               r->run_lod ? key_lev : -1, sl_lod[s], &cmax[s][0]);
        /* the loop blend's contrast back (loop_gain), over the footprints the run spans: its
         * rows', or with run_lod its level's (+- 1/2 level, where weight_terms' line ends) */
        if (r->run_lod)
            apply_loop_gain(sl, (float)lev - 0.5f - sl->log2_density[0] - log2f(RUN_LOD_ROW_MEAN),
                            (float)lev + 0.5f - sl->log2_density[0] - log2f(RUN_LOD_ROW_MEAN),
                            sl_lod[s], &cmax[s][0]);
        else
            apply_loop_gain(sl, lf_near, lf_far, sl_lod[s], &cmax[s][0]);
        smu[s][0] = sl->top_slope[0];
        smu[s][1] = sl->top_slope[1];
        smu[s][2] = within_at(&sl->level_var[0][0], 2, lev, sl->top_level[0]);
        smu[s][3] = within_at(&sl->level_var[0][1], 2, lev, sl->top_level[0]);
        svar[s][0] = sl->top_slope[2] - smu[s][2];   /* T - W (ocean.frag add_slope) */
        svar[s][1] = sl->top_slope[3] - smu[s][3];
        if (r->d.quality != QUALITY_HIGH) {   /* low: the bias less the mean (ocean.frag) */
            smu[s][2] = sl->slope->bias[0] - sl->top_slope[0];
            smu[s][3] = sl->slope->bias[1] - sl->top_slope[1];
        }
        /* low quality's pixel variance (pixel_var_at): T and the level read at footprint
         * f, a f + b (the run's level, or the per-pixel LOD f + log2 density) */
        wt_v[s][0] = sl->top_slope[2];
        wt_v[s][1] = sl->top_slope[3];
        wt_v[s][2] = r->run_lod ? 0.0f : 1.0f;
        wt_v[s][3] = r->run_lod ? (float)key_lev : sl->log2_density[0];
        for (int l = 0; l < SLOT_LEVELS; l++)
            wfrac[l][s] = sl->level_wfrac[l];
        if (s >= kw)
            continue;
        float wdrop = r->d.fetch_all ? INFINITY
                                     : fminf(drop, slot_drop_foot(r, s, WC_DROP(r), 0));
        int wl = r->run_lod ? (int)((key >> (16 + 4 * s)) & 15u) : -1;
        wl = weight_terms(sl->level_kvar, 1, sl->top_level[1], sl->log2_density[1], wdrop, wl,
                          wc_lod[s], &cmax[s][1]);
        /* ocean.frag add_whitecap: mean; c0, -W, T - W of W the level's within-texel
         * variance (the fade's), T the patch's; B and s per pixel (wc_trust_terms) */
        float w = within_at(sl->level_kvar, 1, wl, sl->top_level[1]);
        wmu[s][0] = sl->top_k[0];
        wc_trust_terms(sl, blur, wtr[s], &wmu[s][1]);
        wmu[s][2] = -w;
        wmu[s][3] = sl->top_k[1] - w;
    }
    glUniform4fv(u[OU_SLOT_LOD], SWELL_MAX_PATTERNS, &sl_lod[0][0]);
    glUniform4fv(u[OU_SLOPE_MEAN], SWELL_MAX_PATTERNS, &smu[0][0]);
    glUniform4fv(u[OU_WC_LOD], SWELL_MAX_PATTERNS, &wc_lod[0][0]);
    glUniform4fv(u[OU_WC_MEAN], SWELL_MAX_PATTERNS, &wmu[0][0]);
    glUniform4fv(u[OU_WC_TRUST], SWELL_MAX_PATTERNS, &wtr[0][0]);
    glUniform2f(u[OU_FOAM_DETAIL], tvar > 0.0f ? 1.0f / tvar : 0.0f, blur);
    glUniform2fv(u[OU_SLOPE_VAR], SWELL_MAX_PATTERNS, &svar[0][0]);
    glUniform2fv(u[OU_LOD_CMAX], SWELL_MAX_PATTERNS, &cmax[0][0]);
    glUniform2fv(u[OU_LOD_FRAME], 1, r->vf.lod_frame);
    if (r->d.quality == QUALITY_HIGH)
        return;
    /* low quality's vertex stage (ocean.vert fetched_var): the fetched slots' pixel variance
     * depends on the vertex's footprint f alone, so it is tabulated here at VAR_KNOTS knots
     * over the run's footprints (from half an octave nearer than its nearest row to one
     * farther than its farthest: a row's vertices off the screen's centre lie farther).
     * Linear between 4 knots it is within ~5 % of pixel_var_at, the most near a fade's
     * kink (1e-4 of slope variance in a 10 m moderate view); 8 knots took lima's vertex
     * shaders fetching 2-4 slots past 512 instructions */
    float f0 = lf_near - 0.5f, f1 = fmaxf(lf_far + 1.0f, f0 + 0.5f);
    float knot[2][VAR_KNOTS];         /* x at the knots, then y: ocean.vert's 2 vec4 */
    for (int j = 0; j < VAR_KNOTS; j++) {
        float f = f0 + (f1 - f0) * (float)j / (float)(VAR_KNOTS - 1), v[2];
        pixel_var_at(sl_lod, cmax, wt_v, wfrac, k < r->nfs ? k : r->nfs, f, v);
        knot[0][j] = v[0];
        knot[1][j] = v[1];
    }
    glUniform4fv(u[OU_VAR_KNOT_V], 2, &knot[0][0]);
    glUniform2f(u[OU_VAR_KNOT_FRAME_V], f0, (float)(VAR_KNOTS - 1) / (f1 - f0));
}

/* The sea, far rows first, one draw per run of rows fetching the same slots (and, with
 * run_lod, at the same levels). */
static void draw_runs(struct renderer *r, const struct camera *cam, mat4 world_to_clip,
                      int height)
{
    float alt, pix;
    view_scale(cam, height, &alt, &pix);
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
            set_ocean_uniforms(r, run_k, run_kw, cam, world_to_clip);
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

int renderer_frame(struct renderer *r, const struct camera *user_cam, double t_s, int width,
                   int height, struct swell_err *err)
{
    mat4 view, proj, world_to_clip;
    /* The camera floats CAMERA_CLEARANCE_M above the surface the renderer draws under it (the
     * same displacement, sea.h), so no view is from under the water; the projected grid's
     * coverage argument (grid.c) rests on it. */
    struct camera cam_local = *user_cam;
    const struct camera *cam = &cam_local;
    cam_local.surface_z_m = sea_surface_height(r->t, renderer_detile(r), user_cam->pos[0],
                                             user_cam->pos[1], t_s);
    r->camera_raise_m = 0.0;
    if (cam_local.pos[2] < cam_local.surface_z_m + CAMERA_CLEARANCE_M) {
        r->camera_raise_m = cam_local.surface_z_m + CAMERA_CLEARANCE_M - cam_local.pos[2];
        cam_local.pos[2] = cam_local.surface_z_m + CAMERA_CLEARANCE_M;
    }
    float aspect = height > 0 ? (float)width / (float)height : 1.0f;
    GLint depth_bits = 0;
    int nidx;
    size_t vbytes = sizeof(float) * (r->cpu_vterms ? VSHADE_FLOATS : GRID_FLOATS) *
                    (size_t)grid_vertex_count(r->grid);
    camera_view_rel(cam, view);
    camera_projection(cam, aspect, proj);
    glm_mat4_mul(proj, view, world_to_clip);
    stream_textures(r, t_s);
    vertex_frame(r, cam, height);   /* after the slots' constants of this loop phase */
    if (r->vtf) {
        nidx = grid_projection(r->grid, cam, aspect, &r->proj);
        stream_disp(r, t_s);
    } else {
        nidx = grid_update(r->grid, cam, aspect, t_s, r->verts);
        if (nidx > 0 && r->cpu_vterms)   /* the terms of each vertex, on the CPU (vshade.h) */
            vshade_fill(&r->vf, r->verts, grid_vertex_count(r->grid), r->shaded);
    }

    glViewport(0, 0, width, height);
    glGetIntegerv(GL_DEPTH_BITS, &depth_bits);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_TRUE);
    if (r->probing)
        glClearColor(0.0f, 0.0f, 0.0f, 0.0f);   /* the probe counts what the sea writes */
    else if (r->d.debug_variants)
        glClearColor(1.0f, 1.0f, 1.0f, 1.0f);   /* variant_colour's white */
    else if (r->d.debug_uncovered)
        glClearColor(1.0f, 0.0f, 1.0f, 1.0f);   /* magenta: any pixel left is a bug */
    else
        glClearColor(0.02f, 0.05f, 0.07f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | (depth_bits > 0 ? GL_DEPTH_BUFFER_BIT : 0));
    int rc;
    if (!r->d.no_sky && !r->d.debug_variants && r->probing != 1 &&
        (rc = draw_sky(r, cam, world_to_clip, width, height, err)))
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
                { A_GEO_SLOPE, 4, GRID_A_SLOPE }, { A_GEO_K, 2, GRID_A_K }
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
        draw_runs(r, cam, world_to_clip, height);
        glDisable(GL_BLEND);
        for (int a = 0; a < A_COUNT; a++)
            glDisableVertexAttribArray((GLuint)a);
        glDisable(GL_DEPTH_TEST);
    }
    glActiveTexture(GL_TEXTURE0);
    return gpu_check("renderer_frame", err);
}

void renderer_get_stats(const struct renderer *r, struct renderer_stats *out)
{
    memset(out, 0, sizeof(*out));
    out->gpu_bytes = r->gpu_bytes;
    out->cpu_bytes_per_frame = r->stream_bytes + (r->vtf ? 0 :
        sizeof(float) * (r->cpu_vterms ? VSHADE_FLOATS : GRID_FLOATS) *
        (uint64_t)grid_vertex_count(r->grid));
    out->cpu_vertex_terms = r->cpu_vterms;
    out->vertices = grid_vertex_count(r->grid);
    out->triangles = grid_index_count(r->grid) / 3;
    out->sea_draws = r->draws;
    out->sea_draws_wc_const = r->draws_wc_const;
    out->sea_draws_resolved_drop = r->draws_resolved_drop;
    out->run_lod = r->run_lod;
    out->vtf = r->vtf;
    out->detile = renderer_detile(r);
    out->camera_raise_m = r->camera_raise_m;
    out->refused = r->refused;
}

void renderer_describe(const struct renderer *r, char *buf, size_t size)
{
    int n = snprintf(buf, size,
        "tier: %s (%d texture units)\n"
        "geometry: %s, %s, %d vertices\n"
        "patterns: %d in the fragment shader, %d resolved per vertex (mask 0x%x), whitecaps "
        "per vertex of mask 0x%x\n"
        "loop frames: blended on the CPU, %llu bytes of textures streamed per loop step\n"
        "fetches: per run of rows only the patterns whose mip means still vary there; "
        "whitecaps of %d pattern(s); %s\n"
        "tiles: %s\n"
        "fragment precision: %s\n"
        "sky map: %s\n"
        "shading: %s\n",
        gpu_tier_name(r->gpu->caps.tier), r->gpu->caps.texture_units,
        geometry_kind_name(r->d.geometry),
        r->vtf ? "built and displaced in the vertex shader (vertex texture fetch, two loop frames "
                 "per pattern blended there)"
        : r->cpu_vterms ? "CPU-displaced (no vertex texture fetch) and the terms of each vertex "
                          "on the CPU (the driver refused the vertex shaders that evaluate "
                          "them), streamed per frame"
               : "CPU-displaced (no vertex texture fetch), streamed per frame",
        grid_vertex_count(r->grid), r->nfs,
        r->t->patterns - r->nfs, r->cpu_mask, r->cpu_mask | r->k_mask,
        (unsigned long long)r->stream_bytes, r->nwc,
        r->run_lod ? "one level per run, by binding that level's own texture (software "
                     "rasteriser: per-pixel LOD is its slow path)"
                   : "per-pixel LOD",
        r->detile_refused ? "each pattern read once: it repeats on its tile (--detile auto: "
                            "the driver refused more programs with the random offsets)"
        : !renderer_detile(r) ? "each pattern read once: it repeats on its tile (--detile off; "
                                "auto in low quality)"
                            : "each pattern read at three random offsets blended over a lattice of "
                         "half-tiles (Heitz & Neyret 2018, detile.h)",
        r->gpu->caps.tier == TIER_GLES2_MIN ? "mediump (gles2-min)"
        : r->gpu->caps.prefer_highp ? "highp (software rasteriser: its mediump is emulated fp16)"
                                    : "mediump",
        r->sky_half ? "half-float radiances (RGBA16F)" : "RGBA8 with a scale",
        r->d.quality == QUALITY_HIGH
            ? r->run_lod
              ? "high: Ross BRDF sun (eq. 15), sky map filtered at one level per run of rows "
                "(eq. 27 for the run's mean variance; software rasteriser), effective Fresnel "
                "(eq. 26) on Hu's Fresnel texture, refraction (eq. 28), whitecaps (Dupuy eq. 6)"
            : shader_has_gradients(&r->gpu->caps)
              ? "high: Ross BRDF sun (eq. 15), sky map filtered with explicit gradients (eq. 27, "
                "textureGrad), effective Fresnel (eq. 26) on Hu's Fresnel texture, "
                "refraction (eq. 28), whitecaps (Dupuy eq. 6)"
              : "high: Ross BRDF sun (eq. 15), sky map filtered by an LOD bias beyond the pixel's "
                "own LOD, read from the map's alpha (eq. 27), effective Fresnel "
              "(eq. 26) on Hu's Fresnel texture, refraction (eq. 28), whitecaps (Dupuy eq. 6)"
            : "low: one pass with the same slope moments, Ross BRDF sun (eq. 15), effective "
              "Fresnel (eq. 26) and refraction (eq. 28); the sky filtered as high quality's "
              "(eq. 27) at the vertex's variance, whitecaps (Dupuy eq. 6) and haze per vertex");
    if (n > 0 && (size_t)n < size && !r->run_lod && !shader_has_gradients(&r->gpu->caps))
        n += snprintf(buf + n, size - (size_t)n, "sky LOD bias: at most %g (the device's "
                      "limit)\n", (double)r->gpu->caps.max_lod_bias);
    if (n > 0 && (size_t)n < size)
        snprintf(buf + n, size - (size_t)n, "programs: ocean k=K kw=KW %s%s (the start-up "
                 "probe's names), %d refused\n", render_quality_name(r->d.quality),
                 program_tags(r), r->refused);
}
