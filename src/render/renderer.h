/* renderer.h - draws the ocean from baked tables into the bound framebuffer.
 *
 * Knows nothing of KMS or surfaceless (platform.h). Uploads and accounts every GL object
 * through gpu.h; the frame loop allocates nothing. Paths chosen from gpu caps (tier), printed
 * through renderer_describe().
 */
#ifndef SWELL_RENDERER_H
#define SWELL_RENDERER_H

#include <stddef.h>
#include <stdint.h>
#include "core/camera.h"
#include "core/err.h"
#include "gl/gpu.h"
#include "geometry/detile.h"
#include "geometry/grid.h"
#include "tables/tables.h"

enum render_quality { QUALITY_HIGH = 0, QUALITY_LOW, QUALITY_COUNT };

struct renderer_desc {
    const struct swell_tables *tables;  /* not owned; must outlive the renderer */
    struct gpu *gpu;                    /* not owned; context current */
    const char *shader_dir;             /* default NULL: found (core/datadir.h) */
    int quality;                        /* enum render_quality. default HIGH */
    int geometry;                       /* enum geometry_kind (grid.h). default GRID */
    int grid_w, grid_h;                 /* projected-grid vertices; default 0 = 96 x 64 */
    float sun_elev_deg;                 /* sun elevation above the horizon; default 0 = 30 */
    float sun_azim_deg;                 /* sun azimuth, CCW from +x; default 0 */
    float exposure;                     /* tone-mapping exposure; default 0 = automatic */
    int cpu_geometry;                   /* 1: displace on the CPU even where the tier has
                                         * vertex texture fetch (tests compare the two) */
    int fetch_all;                      /* 1: every row fetches every pattern (tests compare
                                         * with the runs that drop fully filtered ones) */
    int pixel_lod;                      /* 1: per-pixel texture LOD even where the device
                                         * prefers one LOD per run (gpu.c prefer_run_lod;
                                         * tests compare the two) */
    int keep_resolved;                  /* 1: drop a pattern, its slopes and its whitecaps,
                                         * only at its 1x1 level, not where its mip means are
                                         * nearly flat or its whitecaps little more than its
                                         * patch's (tests compare) */
    int no_sky;                         /* 1: draw no sky, so the sea's silhouette meets the
                                         * clear colour (tests: the horizon row) */
    int no_sun;                         /* 1: the sea reflects no sun (eq. 15's term 0; the
                                         * foam and the water body stay sunlit), so the
                                         * difference from a frame with it is the glitter
                                         * (tests: its width against Cox & Munk) */
    unsigned probe_refuse;              /* tests: bit VARIANT(k, kw) = k * 5 + kw set: the
                                         * start-up probe takes that ocean variant as refused
                                         * by the driver (renderer.c probe_programs) */
    unsigned probe_refuse_detile;       /* tests: the same for the programs built with the
                                         * lattice of random offsets only (GC2000's case) */
    unsigned probe_refuse_gpu_vertex;   /* tests: the same for those whose vertex shader
                                         * evaluates the terms of the vertex (GC2000's) */
    int probe_refuse_objects;           /* tests: 1: every program with the objects' passes
                                         * (reflections, wakes, shadows, refractions) taken as
                                         * refused (GC2000's since the reflections' ellipse) */
    int cpu_loop_blend;                 /* 1: blend the streamed tables' loop frames on the
                                         * CPU (tables/stream.h) even where the GPU can draw
                                         * the blend (stream_gpu.c; tests compare the two; the
                                         * environment's SWELL_LOOP_BLEND=cpu does the same) */
    int cpu_vertex_terms;               /* 1: on gles2-min the terms of each vertex on the CPU
                                         * (vshade.h) from the start; default 0: only where the
                                         * driver refuses ocean.vert's (renderer_create) */
    int detile;                         /* enum detile_mode (detile.h; swell --detile);
                                         * default AUTO.
                                         * The CPU query (sea.h) takes renderer_detile's flag */
    int debug_uncovered;                /* 1: clear to magenta (255, 0, 255) before the sky and
                                         * the sea, so a pixel neither covers shows (swell
                                         * --debug uncovered, the frame tests); default 0: a
                                         * dark sea colour */
    int linear_output;                  /* 1: write the radiance times the exposure, linear,
                                         * for the application to tone-map (an RGBA8 target
                                         * clips it at 1); default 0: the display transform
                                         * (optics/tonemap.h) */
    int slope_output;                   /* tests: 1: the sea's pixels hold the slope drawn
                                         * and the variance below it (ocean.frag
                                         * SWELL_SLOPE_OUT), not a radiance */
    int texture_unit_first;             /* the first texture unit the renderer binds; default
                                         * 0. An embedding application keeps those below */
    int texture_unit_count;             /* how many from there it may bind; default 0 = as
                                         * many as the device has (fewer: fewer patterns in
                                         * the fragment shader, the rest per vertex) */
    int reflections;                    /* 1: local reflections of the application's objects
                                         * (reflect.c): a texture unit and a reflection target
                                         * (renderer_reflection_begin); default 0: the sky alone */
    int wakes;                          /* 1: a Kelvin wake behind a moving hull (wake.c): a
                                         * texture unit, renderer_set_wake; default 0 */
    int shadows;                        /* 1: the sun's shadows of the application's objects
                                         * (shadow.c): a texture unit, a 512^2 target,
                                         * renderer_shadow_begin; default 0 */
    int refractions;                    /* 1: the application's objects under the water seen
                                         * through it (refract.c): a texture unit, a target
                                         * as the reflection's, renderer_refraction_begin;
                                         * default 0 */
    int wave_mask;                      /* 1: the waves' amplitude by a coarse mask (mask.c,
                                         * geometry/mask.h): a block of the Fresnel atlas, the
                                         * grid on the CPU, renderer_set_mask; default 0 */
    int debug_variants;                 /* 1: each run of sea rows drawn in one flat colour
                                         * naming the ocean program it is drawn with, no sky
                                         * (white): the screen's share of each program
                                         * (renderer_pixel_variant; swell --debug variants,
                                         * tools/devices.py's cost model) */
};

/* A pixel of a debug_variants frame (RGBA8): the ocean program it was drawn with, as k * 5 + kw
 * (k pattern and kw whitecap fetches, the probe's "ocean k=K kw=KW" names), or one of these. */
enum { RENDERER_PIXEL_SKY = -1, RENDERER_PIXEL_MIXED = -2,
       RENDERER_OCEAN_VARIANTS = (SWELL_MAX_PATTERNS + 1) * (SWELL_MAX_PATTERNS + 1) };
int renderer_pixel_variant(const uint8_t rgba[4]);

struct renderer_stats {
    uint64_t gpu_bytes;                 /* accounted GPU bytes held by the renderer */
    uint64_t cpu_bytes_per_frame;       /* bytes streamed to the GPU each frame */
    int vertices, triangles;
    int sea_draws;                      /* runs of rows drawn in the last frame (renderer.c) */
    int sea_draws_wc_const;             /* ...of them, runs where a fetched slot's whitecaps
                                         * entered as its patch's constants */
    int sea_draws_resolved_drop;        /* ...of them, runs dropping a pattern whose mip means
                                         * are nearly flat there, before its 1x1 level */
    int run_lod;                        /* pattern tables fetched at one LOD per run */
    int vtf;                            /* grid built and displaced in the vertex shader */
    int detile;                         /* 1: the lattice of random offsets is on */
    int cpu_vertex_terms;               /* gles2-min: the terms of each vertex on the CPU
                                         * (vshade.h): the driver refused ocean.vert's */
    int refused;                        /* ocean variants the start-up probe found refused
                                         * (their rows drawn with fewer fetches) */
    double camera_raise_m;              /* the last frame drew the camera this much higher, m:
                                         * it was less than CAMERA_CLEARANCE_M above the local
                                         * surface (renderer_frame) */
};

struct renderer;

int  renderer_create(const struct renderer_desc *d, struct renderer **out, struct swell_err *err);
/* gpu_init on the current context (forced_tier -1: the best) and renderer_create with the
 * fallbacks a driver's refusal calls for, so a device gets a sea whenever any program runs:
 * where no program of d->quality runs on the chosen tier, the same quality on gles2-min (its
 * vertex shaders are smaller: VideoCore IV), then the other quality. note (may be NULL) hears
 * each fallback taken; d->quality and d->gpu are updated. On failure gpu is shut down. */
int  renderer_open(struct renderer_desc *d, struct gpu *gpu, int forced_tier, uint64_t budget,
                   void (*note)(void *user, const char *msg), void *user, struct renderer **out,
                   struct swell_err *err);
/* Draw one frame at time t_s (s) into the framebuffer bound now, viewport width x height.
 * A camera less than CAMERA_CLEARANCE_M above the sea surface under it (the displaced
 * surface this frame draws) is drawn from that height above it instead. A view wider than
 * the grid covers (camera_fov_covered: panoramic strips past 8.5:1) is drawn with its vertical
 * field of view narrowed to fit. */
int  renderer_frame(struct renderer *r, const struct camera *cam, double t_s, int width,
                    int height, struct swell_err *err);

/* The same into an application's frame: its viewport, its projection, its choice of clearing
 * (within the viewport only) and of the sky. renderer_frame is this with the viewport at 0, 0,
 * the camera's own projection, a clear and the sky (unless desc no_sky). */
enum { RENDERER_CLEAR = 1, RENDERER_SKY = 2 };
struct renderer_view {
    struct camera cam;                  /* position, heading, pitch, fov, clip planes */
    int x, y, width, height;            /* the viewport, pixels */
    const float *proj;                  /* NULL: from cam; else 16 floats, column-major, a
                                         * symmetric perspective with cam's fov and planes */
    const float *view;                  /* NULL: from cam; else its world-to-eye rotation
                                         * (column-major, translation ignored), the same as
                                         * cam's heading, pitch and roll */
    unsigned flags;                     /* RENDERER_CLEAR | RENDERER_SKY */
};
int  renderer_draw(struct renderer *r, const struct renderer_view *v, double t_s,
                   struct swell_err *err);
/* The view renderer_frame draws cam with, at width x height (its field of view narrowed to
 * what the grid covers): a program drawing its own objects with the sea takes it for their
 * matrices (camera_frame_make of out->cam) and its reflection pass. */
void renderer_frame_view(const struct renderer *r, const struct camera *cam, int width,
                         int height, struct renderer_view *out);
/* Local reflections (renderer_desc reflections; Hu 2006 §2.2, Bruneton 2010 §6): begin binds
 * the reflection target (its viewport, colour and depth cleared, front faces clockwise: the
 * mirror turns the winding) and gives the view the application draws its objects above the
 * sea with: the camera mirrored in the sea plane z = 0 and its view (world-to-eye rotation,
 * a reflection), and the projection widened a little, its near plane the sea plane, so what is
 * under the water is cut. Objects write their display colour (their linear radiance with
 * linear_output) and alpha 1. end builds the map's mipmaps and restores the framebuffer,
 * viewport, front face, clear colour, depth mask and scissor test begin found; the next draw
 * reads the map, later ones only after another pass. */
struct renderer_pass {
    double camera_pos[3];               /* the pass's eye (mirrored, the sun's, scaled), m */
    float view[16];                     /* world-to-eye, column-major, translation 0 */
    float proj[16];                     /* eye-to-clip, column-major */
    int viewport[4];                    /* the target's: 0, 0, width, height */
    float attenuation_per_m;            /* refraction: write alpha = exp(this z) for a point
                                         * at height z < 0 (the water's transmittance down to
                                         * it, refract.c); 0 for the other passes */
};
struct renderer_reflection {
    float distance_m;                   /* the objects' distance from the camera, m: how far
                                         * their reflections move with the waves (parallax,
                                         * ocean.frag); 0 = far away */
};
int  renderer_reflection_begin(struct renderer *r, const struct renderer_view *v,
                               const struct renderer_reflection *d, struct renderer_pass *out,
                               struct swell_err *err);
int  renderer_reflection_end(struct renderer *r, struct swell_err *err);
/* Refractions (renderer_desc refractions; Hu 2006 §2.2, §5.2, eq. 4): begin binds the
 * refraction target (cleared to transparent, depth to 1) and gives the view of the scene under
 * the water scaled along the vertical by 1/n (what lies above the sea plane is cut); the
 * application draws its underwater objects with it, their display colour and alpha =
 * exp(attenuation_per_m z) at each point's height z. end restores the state begin found; the
 * next draw shows them through the surface (eq. 4's fog per channel), shifted by the waves'
 * slopes as a point depth_m deep and distance_m away would be. */
struct renderer_refraction {
    float depth_m;                      /* 0: 2 */
    float distance_m;                   /* 0: 30 */
};
int  renderer_refraction_begin(struct renderer *r, const struct renderer_view *v,
                               const struct renderer_refraction *d, struct renderer_pass *out,
                               struct swell_err *err);
int  renderer_refraction_end(struct renderer *r, struct swell_err *err);
/* Sun shadows (renderer_desc shadows; Bruneton 2010 §6, Hu 2006 §2.2): begin binds the shadow
 * target (colour cleared to 0, depth to 1) and gives the sun's view of the sea around the
 * camera: an orthographic projection along the sun's rays over a square of distance_m either
 * side of the point half of it ahead of the camera, objects up to height_m tall. The
 * application draws the objects that cast shadows with it, alpha 1 (any colour); end builds
 * the map's mipmaps and restores the state begin found. The next draw takes the sun's glitter
 * and the sun's share of the water body's and (high quality) the foam's light away where the
 * map covers the sea; later draws only after another pass. */
struct renderer_shadow {
    float distance_m;                   /* 0: 150 */
    float height_m;                     /* 0: 30 */
};
int  renderer_shadow_begin(struct renderer *r, const struct renderer_view *v,
                           const struct renderer_shadow *d, struct renderer_pass *out,
                           struct swell_err *err);
int  renderer_shadow_end(struct renderer *r, struct swell_err *err);
/* The Kelvin wake (renderer_desc wakes; geometry/kelvin.h; Bruneton 2010 §6): a hull at pos
 * (world, m; its middle on the water line) sailing along heading_deg (CCW from +x) at
 * speed_mps leaves a wake whose slopes, slope variance and foam the next draws add to the
 * sea's. Its map is built again (about 30 ms for 512 x 256) only when the hull or the speed
 * changes by more than 2 %; moving and turning cost nothing. NULL or speed 0: no wake. */
struct renderer_wake {
    double pos[2];
    float heading_deg;
    float speed_mps;                    /* 0: none; else KELVIN_MIN..MAX_SPEED_MPS */
    float hull_length_m, beam_m;        /* 0: 9 m and a third of the length */
};
int  renderer_set_wake(struct renderer *r, const struct renderer_wake *w, struct swell_err *err);
/* The wave mask (renderer_desc wave_mask), as wave_mask_init checked it: its bytes are copied;
 * NULL: none (the open sea). */
int  renderer_set_mask(struct renderer *r, const struct wave_mask *m, struct swell_err *err);
/* Move the sun (degrees above the horizon in (0, 90], azimuth CCW from +x): re-bakes the sky
 * map (about 11 M instructions at 256^2) and the automatic exposure; not for every frame. */
int  renderer_set_sun(struct renderer *r, float elev_deg, float azim_deg, struct swell_err *err);
void renderer_get_stats(const struct renderer *r, struct renderer_stats *out);
/* 1 when the renderer reads the patterns through the lattice (desc detile resolved): the flag
 * sea.h's query takes to give the surface this renderer draws. */
int  renderer_detile(const struct renderer *r);
/* 1 when the renderer draws the objects' passes it was asked for (reflections, wakes, shadows,
 * refractions); 0 without any, or where the driver refused every program with them and
 * renderer_open made the sea without them (the passes then fail, saying so). */
int  renderer_objects(const struct renderer *r);
/* Ocean program v's name (k * 5 + kw, renderer_pixel_variant): "ocean k=K kw=KW QUALITY",
 * " no-detile" appended without the lattice; the start-up probe's labels, swell's shares. */
void renderer_program_name(const struct renderer *r, int v, char *buf, size_t size);
/* One line per choice made (tier, geometry path, texture path, shading) into buf. */
void renderer_describe(const struct renderer *r, char *buf, size_t size);
void renderer_destroy(struct renderer *r);

const char *render_quality_name(int q);
int render_quality_from_name(const char *name);

#endif
