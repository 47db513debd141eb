/* internal.h - the renderer's one struct and what its modules share (the .c files of render/; not
 * public: callers use render/renderer.h). The tuning constants of the runs of rows are here, each
 * with its measurement, so they read in one place.
 */
#ifndef SWELL_RENDER_INTERNAL_H
#define SWELL_RENDER_INTERNAL_H

#include "optics/fresnel.h"
#include "geometry/grid.h"
#include "geometry/mask.h"
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
#include "geometry/kelvin.h"

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
    OU_VAR_KNOT_FRAME_V, OU_SKY_RUN_LOD, OU_SKY_RUN_BLK, OU_WC_TRUST, OU_FOAM_DETAIL, OU_REFL_TEX, OU_REFL_MAT,
    OU_REFL_SCREEN, OU_REFL_RAY, OU_REFL_DOWN, OU_REFL_BLUR,
    OU_REFL_LEVELS, OU_REFL_AXES, OU_WAKE_TEX, OU_WAKE_MAT, OU_WAKE_ROT, OU_WAKE_K, OU_WAKE_FOAM, OU_FOAM_GAIN, OU_FOAM_GAIN_V,
    OU_WAKE_WARP, OU_SHADOW_TEX, OU_SHADOW_MAT, OU_SHADOW_SEA, OU_SHADOW_FOAM,
    OU_REFR_TEX, OU_REFR_SCREEN, OU_REFR_SHIFT, OU_REFR_TAU, OU_MASK_BOX, OU_MASK_MAT,
    OU_MASK_FOAM, OU_MASK_FOAM_V, OU_FRESNEL_MAX,
    OU_COUNT
};

enum sky_uniform {
    SU_CLIP_TO_WORLD, SU_SKY_VIEW, SU_SKY_VIEW_SCALE, SU_SKY_SUN, SU_SUN_NDC, SU_SUN_DISPLAY,
    SU_COUNT
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

/* Vertex-texture-fetch grid (ocean.vert VTF_PATTERNS): its uniforms, per pattern. */
enum vtf_uniform {
    VU_FWD, VU_RIGHT, VU_UP, VU_FRAME, VU_RANGE, VU_ROWS, VU_ROWS_HZ, VU_MARGIN, VU_STEP, VU_SCALE, VU_BIAS,
    VU_PATTERN, VU_A0, VU_B0, VU_A1, VU_B1, VU_A2, VU_B2, VU_A3, VU_B3, VU_DETILE_TEX,
    VU_DETILE_ATLAS, VU_DISP_CELL, VU_COUNT
};

/* A target the application draws a pass into (pass.c): RGBA8 colour with its mip chain and
 * 16-bit depth; and the application's GL state a pass changes, saved at its begin. */
struct pass_target {
    GLuint fbo, tex, depth;
    int w, h, levels;
};
struct pass_saved {
    GLint fbo, viewport[4], front, active;
    GLfloat clear[4];
    GLboolean depth_mask, scissor;
};

/* Texture units: 0 Fresnel (an atlas with the lattice's hash and the wave mask, textures.c),
 * 1 sky, 2 the reflection map where renderer_desc reflections asks for one (reflect.c), then
 * the wake's map where wakes asks (wake.c), the shadow map where shadows asks (shadow.c), the
 * refraction map where refractions asks (refract.c), then slope/whitecap per fragment pattern
 * slot (unit_patterns). */
enum { UNIT_FRESNEL = 0, UNIT_SKY = 1, UNIT_REFLECT = 2 };
#define UNIT_WAKE_OF(reflections) (2 + ((reflections) != 0))
#define UNIT_SHADOW_OF(reflections, wakes) (UNIT_WAKE_OF(reflections) + ((wakes) != 0))
#define UNIT_REFRACT_OF(reflections, wakes, shadows) \
    (UNIT_SHADOW_OF(reflections, wakes) + ((shadows) != 0))
#define UNIT_PATTERNS_OF(reflections, wakes, shadows, refractions) \
    (UNIT_REFRACT_OF(reflections, wakes, shadows) + ((refractions) != 0))

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
    GLuint frame_tex[2][2];           /* stream_gpu.c: [slope, whitecap][pair] a loop frame's
                                       * chain as baked, the blend's sources */
    int frame_of[2][2];               /* the table frame each holds, -1 none */
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
    int mask_x;                       /* the wave mask's block in it, its first column */
    int nfs;                          /* patterns shaded from textures, largest first */
    int nwc;                          /* leading slots whose whitecaps are fetched (high) */
    unsigned cpu_mask;                /* patterns resolved per vertex */
    struct foam_bias foam_bias;       /* eq. 6's gains (the set's, or found at create) */
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
    int gpu_blend;                    /* 1: the loop blend drawn on the GPU (stream_gpu.c) */
    const char *gpu_blend_why;        /* why not, where it is not */
    long blend_texels;                /* the GPU blend's texels drawn a loop step */
    struct shader_program blendp;     /* stream_blend.frag */
    GLint blend_u[3];
    GLuint blend_fbo;
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
    int objects_refused;              /* the objects' passes were asked for, and the driver
                                       * refused every program with them (renderer_open) */
    int detile_refused;               /* > 0: --detile auto turned the lattice off, with which
                                       * the probe found this many refused (renderer_create) */
    /* Local reflections (reflect.c, renderer_desc reflections) */
    struct pass_target refl;          /* the target the application draws into */
    GLuint refl_none;                 /* 1x1 transparent: a draw with no pass before it */
    GLuint refl_atlas, refl_atlas_fbo;  /* the map's levels side by side, no mips (w x 2h) */
    struct shader_program refl_copy;  /* upscale.vert/.frag: the atlas's copy */
    GLint refl_copy_u[3];             /* the atlas copy's frame_tex, copy_step, copy_bias */
    int refl_active;                  /* between renderer_reflection_begin and _end */
    int refl_ready;                   /* a pass ended since the last draw */
    float refl_mat[9];                /* reflected ray -> map uv times w (ocean.frag) */
    float refl_screen[4];             /* gl_FragCoord -> the flat sea's map uv */
    float refl_ray[4];                /* gl_FragCoord -> the eye-frame view ray */
    float refl_down[4];               /* world -z in the eye frame; camera height / distance */
    float refl_blur[2];               /* twice the map's level-0 texels per 2 rad across
                                       * (2 P00 w of the pass) and along (2 P11 h) */
    float refl_axes[2];               /* (c_x^2, c_y^2): c the world vertical's unit direction
                                       * on the map at its centre (0, 1 without roll) */
    struct pass_saved refl_saved;     /* the application's state at begin */
    /* The Kelvin wake (wake.c, renderer_desc wakes) */
    GLuint wake_tex;                  /* kelvin.h's map, mipmapped, clamped */
    GLuint wake_none;                 /* 1x1 still water: no wake set */
    int wake_on;                      /* renderer_set_wake gave one */
    int wake_w, wake_h;               /* the map's texels (0: none built) */
    struct kelvin_desc wake_built;    /* the hull and speed the map was built for */
    struct renderer_wake wake;        /* where it is now */
    double wake_front, wake_span;     /* kelvin.h's map: its front before the hull's middle */
    double wake_spread;               /* kelvin.h's */
    float wake_warp[4];               /* ocean.frag's: e, the u scale and offset, spread_offset */
    double wake_slope_scale;
    struct kelvin_map wake_map;       /* its heights (the rgba on the GPU): the geometry's */
    /* Sun shadows (shadow.c, renderer_desc shadows) */
    struct pass_target shadow;        /* the sun's view the application draws casters into */
    GLuint shadow_none;               /* 1x1 transparent: a draw with no pass before it */
    int shadow_active, shadow_ready;  /* as refl_active, refl_ready */
    double shadow_aff[3][3];          /* the camera-relative sea point -> the map's uv */
    struct pass_saved shadow_saved;
    /* Refractions (refract.c, renderer_desc refractions) */
    struct pass_target refr;          /* the scaled underwater scene the application draws */
    GLuint refr_none;                 /* 1x1 transparent: a draw with no pass before it */
    int refr_active, refr_ready;
    float refr_screen[4];             /* gl_FragCoord -> the map's uv */
    float refr_shift[4];              /* mat2: the slope deviation -> the map's uv shift */
    float refr_tau[3];                /* each channel's beam attenuation over green's */
    struct pass_saved refr_saved;
    /* The wave mask (mask.c, renderer_desc wave_mask): its texels in the Fresnel atlas */
    uint8_t *mask_bytes;              /* the application's bytes, copied */
    struct wave_mask mask;            /* over mask_bytes; mask.amp NULL: none set */
};

/* A pass (reflection, shadow, refraction) is open: no other may begin. */
static inline int pass_open(const struct renderer *r)
{
    return r->refl_active || r->shadow_active || r->refr_active;
}

/* The first unit of the pattern slots' tables. */
static inline int unit_patterns(const struct renderer *r)
{
    return UNIT_PATTERNS_OF(r->d.reflections, r->d.wakes, r->d.shadows, r->d.refractions);
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

/* ---- shared between the modules (the .c files of render/) ---- */

/* programs.c */
void variant_colour(int v, float rgba[4]);
int build_programs(struct renderer *r, struct swell_err *err);
int probe_programs(struct renderer *r, struct swell_err *err);
const char *program_tags(const struct renderer *r);

/* slots.c */
float loop_gain(float rho, int w_fixed);
void assign_patterns(struct renderer *r);
int choose_vtf(const struct renderer *r);
unsigned low_foam_mask(const struct renderer *r);

/* textures.c */
void atlas_hash_frame(const struct renderer *r, float out[4]);
void bind_tex(const struct renderer *r, int unit, GLuint tex, GLint loc);
GLuint chain_at(const struct chain_tex *c, int l);
void stream_disp(struct renderer *r, double t_s);
void stream_textures(struct renderer *r, double t_s);
/* stream_gpu.c: the loop blend on the GPU where the device can (render/stream_gpu.c), else the
 * CPU's (tables/stream.h); never an error: gpu_blend and gpu_blend_why say which and why */
void stream_gpu_create(struct renderer *r);
void stream_gpu_destroy(struct renderer *r);
void stream_gpu_slot(struct renderer *r, struct fs_slot *sl, const struct stream_phase *ph);
void chain_destroy(struct renderer *r, struct chain_tex *c);
int create_textures(struct renderer *r, struct swell_err *err);
int upload_chain_typed(const struct chain_tex *c, int w, int h, int levels,
                       const void *data, GLenum type, const char *what,
                       struct swell_err *err);
int upload_chain(const struct chain_tex *c, int w, int h, int levels,
                 const uint8_t *data, const char *what, struct swell_err *err);
int upload_single(GLuint tex, int w, int h, const uint8_t *data, const char *what,
                  struct swell_err *err);

/* sky_draw.c */
int draw_sky(struct renderer *r, const struct camera_frame *view, struct swell_err *err);
int sky_atlas_at(int size, int l, int *x, int *y);
int create_sky_mesh(struct renderer *r, struct swell_err *err);
void update_sky_constants(struct renderer *r);
int upload_sky(struct renderer *r, const struct sky *sk, struct swell_err *err);

/* reflect.c */
int reflect_create(struct renderer *r, struct swell_err *err);
void reflect_destroy(struct renderer *r);
void reflect_uniforms(const struct renderer *r, const GLint *u);

/* pass.c */
/* mips 1: with its mip chain (the pass's end builds it), 0: level 0 alone */
int  pass_target_create(struct renderer *r, struct pass_target *t, int w, int h, int mips,
                        int unit, const char *what, struct swell_err *err);
void pass_target_destroy(struct renderer *r, struct pass_target *t);
void pass_target_bind(const struct pass_target *t);
void pass_save(struct pass_saved *s);
/* A pass of quads drawn by the renderer into fbo (the loop blend, the reflection atlas's
 * copy): no blending, depth test, culling or scissor, program in use, the renderer's quad as
 * attribute 0 (the caller disables it after). */
void pass_quad_begin(const struct renderer *r, GLuint fbo, GLuint program);
void pass_restore(const struct pass_saved *s);
int  pass_none_create(struct renderer *r, GLuint *tex, const char *what, struct swell_err *err);
/* The size of a view pass's map for a viewport (half of it, POT, 32..512). */
void pass_target_size(int vw, int vh, int *w, int *h);
/* Lengyel's oblique near plane: proj (column-major) made to clip at the eye-space plane c
 * (points with c . (x, y, z, 1) < 0 cut), the camera on that side (c[3] < 0). */
void pass_oblique_near(float p[16], const double c[4]);
/* gl_FragCoord to a view pass's map uv: scale xy, offset zw (ocean.frag refl_/refr_screen). */
void pass_screen_uv(const struct renderer_view *v, float out[4]);
/* The reflection atlas (reflect.c): each level of the map's mip chain, and below it up to
 * REFL_RIP_M versions halved again and again along the map's vertical only (a ripmap's
 * column): eq. 27's ellipse is up to 2^REFL_RIP_M times longer along the view than across. */
#define REFL_RIP_M 4
/* A view pass's field of view is the view's widened by this factor (tan of the half angles),
 * so a ray the waves tilt past the screen's edge still finds its object. */
#define PASS_MARGIN 1.25f
/* The view's projection (column-major) widened by PASS_MARGIN about its frustum's centre
 * (off-axis or not: P00, P11 and the offsets P20, P21 over m), so the pass's ndc is the
 * view's over m at every pixel (pass_screen_uv). */
void pass_widen(float p[16]);

/* refract.c */
int  refract_create(struct renderer *r, struct swell_err *err);
void refract_destroy(struct renderer *r);
void refract_uniforms(const struct renderer *r, const GLint *u);

/* shadow.c */
int  shadow_create(struct renderer *r, struct swell_err *err);
void shadow_destroy(struct renderer *r);
void shadow_uniforms(const struct renderer *r, const struct camera_frame *view, const GLint *u,
                     const float sea_sun[3], const float foam_sun[3]);

/* mask.c */
#define MASK_TEX 256                  /* the mask's block in the atlas: WAVE_MASK_MAX + a border */
void mask_block(const struct wave_mask *m, uint8_t *out, size_t row_bytes);
void mask_grid(const struct renderer *r, struct grid *g);
float mask_amp_at(const struct renderer *r, double x, double y);
void mask_uniforms(const struct renderer *r, const struct camera_frame *view, const GLint *u);

/* wake.c */
int wake_create(struct renderer *r, struct swell_err *err);
void wake_destroy(struct renderer *r);
void wake_grid(const struct renderer *r, const double cam_xy[2], struct grid *g);
double wake_height_at(const struct renderer *r, double x, double y, float foot_m);
void wake_uniforms(const struct renderer *r, const struct camera_frame *view, const GLint *u,
                   const float foam[3]);

/* frame.c */
void screen_to_sea(const struct camera_frame *view, double q[3][3]);
void sea_uniform_matrix(const struct camera_frame *view, const double aff[3][3], int on,
                        GLint loc);
void renderer_view_frame(const struct renderer_view *v, const struct camera *cam,
                         struct camera_frame *view);

/* lod.c */
float row_footprint(float d2, float alt, float pix_angle);
uint32_t run_lod_key(const struct renderer *r, float foot, int k, int kw);
void set_run_lods(struct renderer *r, int k, int kw, uint32_t key, float d2_far,
                  float d2_near, float alt, float pix);
void set_slot_lods(struct renderer *r, int k, int kw, uint32_t key, float alt, float pix,
                   float lf_far, float lf_near);
int slots_needed(const struct renderer *r, float d2, float alt, float pix_angle,
                 float drop, int resolved);

/* The error of an objects' pass (what: "reflection target", ...) on a renderer whose driver
 * refused them (objects_refused). */
int renderer_objects_refused(const struct renderer *r, const char *what, struct swell_err *err);

#endif
