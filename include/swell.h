/* swell.h - the ocean renderer swell as a C library: bake or load a sea, ask it for the water
 * under a point on the CPU, and draw it with OpenGL ES 2 into the application's own context.
 * C99; needs only <stddef.h> and <stdint.h>. Link with `pkg-config --cflags --libs swell`.
 *
 * Conventions, for every function:
 *   - World axes: x east, y north, z up, right-handed; metres, seconds, degrees where named _deg.
 *   - Descriptors: a zeroed descriptor asks for every default; each field's default is stated.
 *   - Errors: a function that can fail returns 0 (SWELL_OK) or a SWELL_E_* code and, when `err`
 *     is not NULL, fills it with a message that says what was wrong and what to do. Nothing is
 *     printed. On failure no output handle is created and nothing is half-written.
 *   - Threads: a swell_sea is immutable once made; swell_sea_sample may run on many threads at
 *     once on one sea. A swell_ocean belongs to the GL context current when it was created and
 *     is used from that context's thread only.
 *   - Symbols: everything the library exports starts with swell_ (types, functions, macros
 *     SWELL_).
 *
 * Papers: Hu et al. 2006 (looping tables), Bruneton et al. 2010 (projected grid, lighting),
 * Dupuy & Bruneton 2012 (whitecaps), Tessendorf et al. 2023 (whitecap fraction).
 */
#ifndef SWELL_H
#define SWELL_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define SWELL_VERSION_MAJOR 0
#define SWELL_VERSION_MINOR 8
#define SWELL_VERSION_PATCH 0
#define SWELL_VERSION_STRING "0.8.0"
/* (major << 16) | (minor << 8) | patch, comparable with swell_version() */
#define SWELL_VERSION_NUMBER \
    ((SWELL_VERSION_MAJOR << 16) | (SWELL_VERSION_MINOR << 8) | SWELL_VERSION_PATCH)

#if defined(__GNUC__) || defined(__clang__)
#define SWELL_API __attribute__((visibility("default")))
#else
#define SWELL_API
#endif

/* ---- errors ---------------------------------------------------------------------------- */

enum swell_error_code {
    SWELL_OK = 0,
    SWELL_E_NOMEM,          /* out of memory */
    SWELL_E_ARG,            /* invalid argument: a value out of its range, a NULL handle */
    SWELL_E_IO,             /* a file could not be read or written */
    SWELL_E_FORMAT,         /* a file is malformed */
    SWELL_E_VERSION,        /* a file's version is not supported */
    SWELL_E_CHECKSUM,       /* a file's checksum does not match: corrupt */
    SWELL_E_BUDGET,         /* the GPU memory budget is too small for the request */
    SWELL_E_FFT,            /* the FFT library failed */
    SWELL_E_EGL,            /* EGL failed */
    SWELL_E_GL,             /* OpenGL ES failed */
    SWELL_E_SHADER,         /* a shader did not compile or link */
    SWELL_E_TIER,           /* the GL context lacks what the lowest tier needs */
    SWELL_E_DRM,            /* DRM/KMS failed */
    SWELL_E_UNSUPPORTED,    /* not supported (yet) */
    SWELL_ERR_COUNT
};

struct swell_err {
    int code;               /* SWELL_OK or a SWELL_E_* value */
    char msg[1024];         /* the specific message; "" when code is SWELL_OK */
};

/* A short generic text for a code ("checksum mismatch"); never NULL. */
SWELL_API const char *swell_err_name(int code);
/* SWELL_VERSION_NUMBER of the library linked at run time. */
SWELL_API uint32_t swell_version(void);

/* ---- the sea: baked tables ------------------------------------------------------------- */

typedef struct swell_sea swell_sea;

/* The range of swell_sea_desc wind_speed_mps (and of swell-bake --wind), m/s. */
#define SWELL_WIND_SPEED_MIN_MPS 0.5
#define SWELL_WIND_SPEED_MAX_MPS 40.0

typedef struct swell_sea_desc {
    const char *preset;         /* NULL, or a preset applied first: "calm", "moderate",
                                 * "rough", "storm" (swell-bake --help), or a .preset path */
    float wind_speed_mps;       /* U10 wind speed, m/s, 0.5..40; 0 = the preset's or 10 */
    float wind_dir_deg;         /* direction the wind blows towards, CCW from east; 0 = east */
    float fetch_km;             /* fetch, km, 0.1..10000; 0 = the preset's or 100 */
    float depth_m;              /* water depth, m, 1..10000; 0 = deep water */
    uint32_t seed;              /* random seed; 0 = the preset's or 1 */
    uint64_t budget_bytes;      /* GPU memory the tables and the renderer may take, bytes,
                                 * 1 MiB..1 GiB; 0 = the preset's or 16 MiB */
    const char *const *options; /* NULL, or every other value of the sea state by swell-bake's
                                 * option names, as name and value pairs ending in NULL:
                                 * { "--spread", "4", "--patterns", "2", NULL }. Applied in
                                 * order after the fields above; "--preset" loads a preset
                                 * there. The names and ranges: swell_sea_usage, swell_sea_option */
    void (*progress)(void *user, double done, const char *stage);
                                /* NULL, or called while baking with done in [0, 1] and the
                                 * stage's name ("spectrum", "whitecaps") */
    void *progress_user;        /* progress's first argument */
} swell_sea_desc;

/* Bake a sea from a sea state (0.6 s at the default 16 MiB budget on a 2-core x86 VM). */
SWELL_API int swell_sea_bake(const swell_sea_desc *desc, swell_sea **out, struct swell_err *err);
/* Check a sea state as swell_sea_bake would, without baking: SWELL_E_ARG naming the first bad
 * value (an option's text, a range, a preset), SWELL_E_BUDGET when it cannot fit its budget. */
SWELL_API int swell_sea_check(const swell_sea_desc *desc, struct swell_err *err);
/* 1 when name is an option swell_sea_desc options takes ("--wind", "--preset"), else 0. */
SWELL_API int swell_sea_option(const char *name);
enum swell_usage { SWELL_USAGE_SEA = 0, SWELL_USAGE_TABLES, SWELL_USAGE_DATA };
/* --help text, one line per option with its argument, unit, default and range: the sea's
 * options (SWELL_USAGE_SEA), the tables' (SWELL_USAGE_TABLES), or where presets and shaders
 * are looked for (SWELL_USAGE_DATA). Written as snprintf does: at most cap bytes with the
 * terminating 0 (buf may be NULL when cap is 0); returns the whole text's length. */
SWELL_API size_t swell_sea_usage(int what, char *buf, size_t cap);
/* Load tables baked by swell-bake (or swell_sea_save) from a directory. */
SWELL_API int swell_sea_load(const char *dir, swell_sea **out, struct swell_err *err);
/* The same for oceans that may take budget_bytes of GPU memory (1 MiB..1 GiB; 0: the budget
 * the set was baked for): refused with SWELL_E_BUDGET, before any table is read, when an ocean
 * of this set needs more; the sea's oceans then keep within budget_bytes. */
SWELL_API int swell_sea_load_budget(const char *dir, uint64_t budget_bytes, swell_sea **out,
                                    struct swell_err *err);
/* Write the sea's tables to a directory, atomically (a reader sees the old set or the new). */
SWELL_API int swell_sea_save(const swell_sea *sea, const char *dir, struct swell_err *err);
SWELL_API void swell_sea_destroy(swell_sea *sea);

typedef struct swell_sea_info {
    float wind_speed_mps;       /* the sea state's */
    float significant_height_m; /* Hs = 4 sqrt(variance of the height), m */
    float loop_period_s;        /* every table repeats after this many seconds */
    int patterns;               /* wave patterns of different sizes (Dupuy 2012) */
    float pattern_size_m[4];    /* each pattern's tile side, m */
    uint64_t table_bytes;       /* bytes of all tables (swell_sea_check_dir: of their files) */
    /* the rest of the sea state (swell-bake --help) */
    const char *spectrum;       /* "pm", "jonswap" or "tma" */
    float wind_dir_deg;         /* direction the wind blows towards, CCW from east */
    float fetch_km, depth_m;    /* depth 0: deep water */
    uint32_t seed;
    int frames;                 /* loop frames over the period */
    int table_size;             /* the slope and whitecap tables' side, texels */
    int geometry_size;          /* the displacement tables' side, texels */
    /* what the bake measured */
    double mss_resolved[2];     /* mean square slope the tables hold, along x and y */
    double mss_unresolved[2];   /* the slope variance of waves finer than they hold (drawn as
                                 * roughness, Bruneton 2010 §4.1), x and y */
    float whitecap_epsilon;     /* Dupuy 2012 eq. 3's threshold on the summed foam memory */
    float whitecap_breaking_fraction; /* the share of the sea breaking at a time */
    float foam_recovery_per_s;  /* how fast the foam memory falls, per second */
    const char *whitecap_model; /* "mom80" or "wu88": the whitecap fraction W from the wind */
    float whitecap_fraction_model;    /* W by that model */
    float whitecap_fraction_measured; /* the fraction the baked foam covers */
    uint64_t resident_bytes;    /* RAM besides the tables: the streamed loop frames, a margin */
    uint64_t gpu_bytes_max;     /* GPU memory a renderer of this sea takes at most (any tier,
                                 * geometry, quality) */
    uint64_t budget_bytes;      /* the budget it was baked for */
    int tables;                 /* how many tables (swell_sea_get_table) */
} swell_sea_info;
SWELL_API void swell_sea_get_info(const swell_sea *sea, swell_sea_info *out);

typedef struct swell_table_info {
    char name[48];              /* its name, "slope_p0" (swell_sea_check_dir: its file's name,
                                 * "slope_p0.ktx") */
    const char *kind;           /* "slope", "whitecap", "disp", "fresnel", "fresnel_eff" */
    const char *format;         /* "rgba8" and the like */
    int pattern;                /* the wave pattern it belongs to; -1 for none */
    int width, height, layers, levels;  /* texels, loop frames, mip levels */
    uint64_t bytes;             /* all its levels and layers (swell_sea_check_dir: the file's) */
} swell_table_info;
/* Table i (0 <= i < info.tables) of a sea; SWELL_E_ARG when there is none. */
SWELL_API int swell_sea_get_table(const swell_sea *sea, int i, swell_table_info *out,
                                  struct swell_err *err);

/* Check the tables in dir without loading them: each table's file against the manifest's
 * length and checksum, and its header. fn (may be NULL) is called once per table the manifest
 * lists (listed 1) and per other .ktx file in dir (listed 0, its kind and format "?"), with
 * status SWELL_OK or the SWELL_E_* code of its first problem and msg saying it ("" when ok).
 * info (may be NULL) gets the manifest's sea state and measures, or is zeroed when the manifest
 * cannot be read (info->patterns 0). Returns SWELL_OK when every table is sound, else the first
 * problem's code with err saying it. */
typedef void (*swell_table_check_fn)(void *user, const swell_table_info *table, int listed,
                                     int status, const char *msg);
SWELL_API int swell_sea_check_dir(const char *dir, swell_table_check_fn fn, void *user,
                                  swell_sea_info *info, struct swell_err *err);

/* ---- the sea on the CPU ---------------------------------------------------------------- */

struct swell_wake;              /* below: the objects on the sea */
struct swell_mask;              /* below: local wave amplitude */
typedef struct swell_sample_desc {
    double min_wavelength_m;    /* 0: every wave the tables hold; else waves shorter than this
                                 * fade out (Bruneton 2010 eq. 2's weight, waves of 1 to 2 x
                                 * this blended), so a hull of that size is not shaken by
                                 * ripples */
    int no_detile;              /* 1: the patterns read once, at no offset, as an ocean made
                                 * with swell_ocean_desc detile SWELL_DETILE_OFF draws them
                                 * (the default, 0, matches the default high quality) */
    int height_only;            /* 1: height_m and displacement alone (normal straight up,
                                 * velocity 0), a fifth of the work: a hull's buoyancy points,
                                 * a camera's height above the water */
    const struct swell_wake *wake;  /* NULL: the open sea; else this hull's Kelvin wake is
                                 * added, as an ocean drawing it (swell_ocean_set_wake) draws
                                 * it: its height (to height_m and displacement[2]), its slope
                                 * (to the normal) and the rate its height changes as the hull
                                 * sails on (to velocity[2]; the wake's orbital motion sideways
                                 * is not modelled), under min_wavelength_m's filter by its
                                 * longest, transverse wave. About 0.2 us a point. A hull
                                 * floating on the sea leaves its own wake out: it would pitch
                                 * it on its own stern wave (swell's demo boat does) */
    const struct swell_mask *mask;  /* NULL: the open sea everywhere; else the waves scaled
                                 * by this mask's amplitude at (x, y), as an ocean drawing it
                                 * (swell_ocean_set_mask) draws them: heights, displacements,
                                 * slopes and velocities times a (the wake is not scaled) */
} swell_sample_desc;

typedef struct swell_sample {
    double height_m;            /* height of the water surface above (x, y), m */
    double displacement[3];     /* (Dx, Dy, Dz) of the rest point that moves to above (x, y):
                                 * the choppy waves move water sideways, m */
    float normal[3];            /* unit normal of the displaced surface there */
    float velocity[3];          /* velocity of that water, m/s */
} swell_sample;

/* The water above n points xy[2 i], xy[2 i + 1] at time t_s: the surface the renderer draws
 * (the same tables, loop frames blended at the same phase, the same bilinear filtering), at
 * full detail where the desc asks none (desc may be NULL). Thread-safe. Equal at t_s and
 * t_s + the loop period. */
SWELL_API int swell_sea_sample(const swell_sea *sea, const swell_sample_desc *desc,
                               const double *xy, size_t n, double t_s, swell_sample *out,
                               struct swell_err *err);

/* ---- the ocean on the GPU -------------------------------------------------------------- */

typedef struct swell_ocean swell_ocean;

enum swell_quality { SWELL_QUALITY_HIGH = 0, SWELL_QUALITY_LOW };
enum swell_geometry { SWELL_GEOMETRY_GRID = 0, SWELL_GEOMETRY_PATCHES };
enum swell_detile { SWELL_DETILE_AUTO = 0, SWELL_DETILE_ON, SWELL_DETILE_OFF };
enum swell_tier { SWELL_TIER_BEST = 0, SWELL_TIER_GLES2_MIN, SWELL_TIER_GLES2_EXT, SWELL_TIER_GLES3 };

typedef struct swell_ocean_desc {
    int quality;                /* enum swell_quality; default HIGH (LOW: Hu's single pass for
                                 * the weakest GPUs) */
    int geometry;               /* enum swell_geometry; default GRID (Bruneton's projected grid) */
    int tier;                   /* enum swell_tier: the highest tier to use; default the best the
                                 * context offers (the fastest on GPUs where that is lower:
                                 * VideoCore IV, gles2-min) */
    int detile;                 /* enum swell_detile; default AUTO (on in high quality) */
    float sun_elev_deg;         /* sun elevation above the horizon, (0, 90]; default 30 */
    float sun_azim_deg;         /* sun azimuth, CCW from east; default 0 */
    const char *shader_dir;     /* NULL: the installed shaders ($SWELL_DATA_DIR overrides) */
    int linear_output;          /* 1: write linear radiance times the exposure (no display
                                 * transform; a float or sRGB target and your own tone map);
                                 * default 0: display-ready colour (Reinhard on the largest
                                 * channel, then gamma 2). Compiled into the ocean's shaders, so
                                 * fixed per ocean: for both, two oceans on the same sea */
    int texture_unit_first;     /* the first texture unit swell binds; default 0 (units below
                                 * are the application's, never touched) */
    int texture_unit_count;     /* how many from there swell may bind, at least 3; default 0 =
                                 * as many as the device has (fewer: fewer wave patterns
                                 * shaded per pixel, the rest per vertex) */
    int reflections;            /* 1: the application's objects reflect in the sea
                                 * (swell_ocean_begin_reflection): one more texture unit and
                                 * a target of half the viewport's size as a power of two,
                                 * at most 512 x 512, RGBA8 with mipmaps and 16-bit depth, and
                                 * an atlas of its levels (2.4 MiB at 1280 x 720, 4.8 MiB at
                                 * most); default 0: the sea reflects the sky alone */
    int wakes;                  /* 1: a moving hull leaves a Kelvin wake (swell_ocean_set_wake):
                                 * one more texture unit and a 512 x 256 RGBA8 map with mipmaps
                                 * (683 KiB), its heights on the CPU (683 KiB of RAM), and the
                                 * grid displaced on the CPU on every tier; default 0 */
    int wave_mask;              /* 1: the waves' amplitude varies by a coarse mask
                                 * (swell_ocean_set_mask; calmer water in an island's lee):
                                 * no texture unit (the mask joins the Fresnel atlas, which
                                 * grows by 384 KiB), the grid displaced on the CPU on every
                                 * tier, as with wakes; default 0 */
    int shadows;                /* 1: the application's objects shadow the sun on the sea
                                 * (swell_ocean_begin_shadow): one more texture unit and a
                                 * 512 x 512 RGBA8 target with mipmaps and 16-bit depth
                                 * (1.8 MiB); default 0 */
    int refractions;            /* 1: the application's objects under the water show through it
                                 * (swell_ocean_begin_refraction): one more texture unit and a
                                 * target as the reflection's, without mipmaps (1.1 MiB at
                                 * 1280 x 720); default 0 */
    int pixel_lod;              /* 1: the texture level chosen per pixel everywhere; default 0:
                                 * where the device prefers it (software rasterisers), one
                                 * whole level per run of rows, faded between runs */
    void (*note)(void *user, const char *msg);
                                /* NULL, or told each fallback swell_ocean_create takes (a
                                 * program the driver refused and what is drawn instead), one
                                 * message per call, lines separated by '\n' */
    void *note_user;            /* note's first argument */
    int debug_programs;         /* 1: a diagnostic frame: every run of sea rows drawn in one
                                 * flat colour naming its shader program (swell_ocean_program_at;
                                 * read back from an RGBA8 target: fewer bits blur the colours),
                                 * the rest white, no sky; default 0 */
} swell_ocean_desc;

/* Create the GPU side of a sea in the GL context current on this thread (OpenGL ES 2.0 or
 * later). The sea must outlive the ocean. Compiles the shaders and probes which the driver
 * runs; a program the driver refuses is replaced by one fetching less, never by no sea. Where
 * the driver refuses every program with the objects' passes (reflections, wakes, shadows,
 * refractions, the wave mask; Vivante GC2000 does), the ocean is made without them: it draws
 * the sea, and swell_ocean_begin_*, swell_ocean_set_wake and swell_ocean_set_mask fail with
 * SWELL_E_ARG, saying why. */
SWELL_API int swell_ocean_create(const swell_sea *sea, const swell_ocean_desc *desc,
                                 swell_ocean **out, struct swell_err *err);

/* Flags of swell_view: what a draw does besides the sea. */
enum swell_draw_flags {
    SWELL_DRAW_CLEAR = 1,       /* clear colour and depth of the viewport first */
    SWELL_DRAW_SKY = 2          /* draw the sky behind the sea (else the sea alone) */
};

typedef struct swell_view {
    double camera_pos[3];       /* the eye in world coordinates, m (double: a sea of any size;
                                 * the renderer works relative to it) */
    float view[16];             /* world-to-eye, column-major as glUniformMatrix4fv takes it: a
                                 * rotation, any heading and roll, pitch within -89..89 deg;
                                 * its translation is ignored (the eye is camera_pos) */
    float proj[16];             /* eye-to-clip, column-major: a perspective, NDC z in [-1, 1],
                                 * symmetric (as gluPerspective or glm_perspective build it) or
                                 * off-axis (glFrustum: a stereo eye, one tile of a wall of
                                 * displays), its corners within 85 deg of its axis; the sea
                                 * ends at 0.9 x its far plane */
    int viewport[4];            /* x, y, width, height in pixels of the bound framebuffer */
    unsigned flags;             /* enum swell_draw_flags */
} swell_view;

/* Draw the sea at time t_s into the framebuffer bound now, depth-tested and writing depth (so
 * the application can draw after it and test against the sea). GL state: swell binds its
 * programs, buffers and textures (on its units, swell_ocean_desc), sets blend, depth, cull,
 * scissor and the viewport as it draws, and restores all of them, the vertex attributes 0-7,
 * the active unit and the clear colour to what they were before the call (and on GLES 3 it
 * draws with vertex array 0 bound, the application's bound again after). It never clears
 * outside the viewport, and inside it only with SWELL_DRAW_CLEAR. */
SWELL_API int swell_ocean_draw(swell_ocean *ocean, const swell_view *view, double t_s,
                               struct swell_err *err);
/* ---- objects on the sea: reflections (Hu et al. 2006 §2.2, Bruneton et al. 2010 §6) ---- */

/* The view a pass's objects are drawn with. Draw each object as with a swell_view: its world
 * position less camera_pos (in double), then view, then proj. */
typedef struct swell_pass {
    double camera_pos[3];       /* the eye mirrored in the sea plane z = 0, m */
    float view[16];             /* world-to-eye, column-major, translation 0: the view's
                                 * rotation times the mirror (its determinant is -1) */
    float proj[16];             /* eye-to-clip, column-major: the view's projection a little
                                 * wider, its near plane the sea plane (what lies under the
                                 * water is cut; the depth is not the view's) */
    int viewport[4];            /* the target's, already set: 0, 0, width, height */
    float attenuation_per_m;    /* a refraction pass's: write alpha = exp(attenuation_per_m z)
                                 * for a point at height z (< 0, m; the water's transmittance
                                 * down to it) and colour times that alpha; 0 in the others */
} swell_pass;

/* Begin drawing the application's objects into the reflection map of the next
 * swell_ocean_draw (an ocean created with reflections = 1). view is the one that draw will
 * take; desc (may be NULL: defaults) says where the objects are. swell binds its reflection
 * target (its own framebuffer of about half the viewport's size, a power of two), sets the viewport, clears colour to 0 and depth to 1, and sets the
 * front face to clockwise (the mirror turns every triangle's winding: culling keeps working).
 * Draw the objects that stand above the water with the pass's matrices, writing their colour
 * as you draw it to the screen (linear radiance with linear_output) and alpha 1; what is left
 * at alpha 0 shows the sky. Leave depth testing as your objects need it. */
typedef struct swell_reflection_desc {
    float object_distance_m;    /* how far the objects stand from the camera, m: the sea
                                 * nearer the camera moves and blurs their reflections with
                                 * the waves by 1 - its distance / this of what an object at
                                 * infinity's would (a wave's tilt meets a near object
                                 * sooner), the sea at and beyond it not at all; 0 = far away
                                 * (an island, a coast on the horizon) */
} swell_reflection_desc;
SWELL_API int swell_ocean_begin_reflection(swell_ocean *ocean, const swell_view *view,
                                           const swell_reflection_desc *desc, swell_pass *out,
                                           struct swell_err *err);
/* End the pass: builds the map's mipmaps and restores the framebuffer binding, viewport,
 * front face, clear colour, depth mask and scissor test found at begin (and the active unit
 * and its binding). The next swell_ocean_draw reads the map (the water reflects the objects,
 * blurred by the waves as eq. 27 blurs the sky, and they hide the sun's glitter they stand in
 * front of); a draw with no pass before it reflects the sky alone. */
SWELL_API int swell_ocean_end_reflection(swell_ocean *ocean, struct swell_err *err);

/* ---- objects under the sea: refraction (Hu et al. 2006 §2.2, §5.2, eq. 4) --------------- */

/* Begin drawing the application's objects under the water into the refraction map of the next
 * swell_ocean_draw (an ocean created with refractions = 1). swell binds its target (cleared to
 * transparent, depth to 1) and gives the view of the scene under the water compressed along
 * the vertical by the water's index of refraction (Hu's approximation of the refraction at the
 * surface); what lies above the sea plane is cut. Draw the objects with the pass's matrices,
 * writing colour times alpha and alpha = exp(pass.attenuation_per_m z) at each point's height z:
 * the sea shows them through its surface's transmission (1 - Fresnel), fading into the water's
 * own colour with depth per colour channel (eq. 4), moved by the waves' slopes. */
typedef struct swell_refraction_desc {
    float object_depth_m;       /* how deep they lie, m: the waves move them by this times the
                                 * refracted rays' tilt; 0 = 2 m */
    float object_distance_m;    /* how far from the camera, m; 0 = 30 m */
} swell_refraction_desc;
SWELL_API int swell_ocean_begin_refraction(swell_ocean *ocean, const swell_view *view,
                                           const swell_refraction_desc *desc, swell_pass *out,
                                           struct swell_err *err);
/* End the pass (as swell_ocean_end_reflection). */
SWELL_API int swell_ocean_end_refraction(swell_ocean *ocean, struct swell_err *err);

/* ---- objects on the sea: the sun's shadows (Bruneton et al. 2010 §6) ------------------ */

/* Begin drawing the objects that cast shadows on the sea into the shadow map of the next
 * swell_ocean_draw (an ocean created with shadows = 1), as with a reflection pass: swell binds
 * its target (cleared to transparent, depth to 1) and gives the sun's view of the sea around
 * view's camera (an orthographic projection along the sun's rays; draw with it as with a
 * swell_pass). Draw each caster with alpha 1, any colour; depth testing as you like. Where the
 * map covers a point of the sea the sun's glitter is gone and the water and the foam are lit
 * by the sky alone. */
typedef struct swell_shadow_desc {
    float distance_m;           /* the sea shadowed: a square this far either side of the
                                 * point half of it ahead of the camera, m; 0 = 150 (the map's
                                 * 512 texels over it: 0.6 m each) */
    float caster_height_m;      /* the tallest caster above the sea, m; 0 = 30 */
} swell_shadow_desc;
SWELL_API int swell_ocean_begin_shadow(swell_ocean *ocean, const swell_view *view,
                                       const swell_shadow_desc *desc, swell_pass *out,
                                       struct swell_err *err);
/* End the pass: builds the map's mipmaps and restores what begin found (as
 * swell_ocean_end_reflection does). */
SWELL_API int swell_ocean_end_shadow(swell_ocean *ocean, struct swell_err *err);

/* ---- objects on the sea: the Kelvin wake (Bruneton et al. 2010 §6, local waves) -------- */

/* A hull sailing at constant speed: its wake's waves (the 19.47 deg wedge of transverse and
 * divergent waves, their lengths set by the speed, 2 pi U^2 / g on the track) add their slopes
 * and slope variance to the sea's, and its foam (the stern's turbulent strip and where the
 * wake breaks, decaying with the sea's foam half-life) to the whitecaps, and its heights
 * (decimetres) to the geometry, per vertex on the CPU (an ocean made with wakes = 1 displaces
 * its grid on the CPU on every tier). swell_sea_sample adds the same wake where its desc names
 * it. */
#define SWELL_WAKE_SPEED_MIN_MPS 0.5    /* the slowest hull that makes a wake, m/s */
typedef struct swell_wake {
    double position_m[2];       /* the hull's middle on the water line, world x, y */
    float heading_deg;          /* its course, CCW from east */
    float speed_mps;            /* through the water, SWELL_WAKE_SPEED_MIN_MPS..30 m/s; 0: no
                                 * wake */
    float hull_length_m;        /* 1..400 m; 0 = 9 m */
    float beam_m;               /* 0.2..100 m; 0 = a third of the length */
} swell_wake;
/* Set (or with NULL or speed 0 remove) the wake the next draws add (an ocean created with
 * wakes = 1); call it every frame the hull moves: moving and turning cost nothing, a change
 * of speed, length or beam by more than 2 % builds the map again (about 0.1 s on a 2-core
 * x86 VM). */
SWELL_API int swell_ocean_set_wake(swell_ocean *ocean, const swell_wake *wake,
                                   struct swell_err *err);

/* ---- local wave parameters: a coarse mask (Bruneton et al. 2010 §6) ------------------ */

/* The sea's waves times a = amplitude / 255 over a world rectangle (255: the open sea, 0:
 * still water; beyond the rectangle the open sea), read bilinearly between texel centres:
 * heights, choppy displacements and slopes times a, slope variances (the sun's glitter, the
 * sky's blur) times a^2, and the whitecaps as the wind a stands for would make them (a fully
 * developed sea's height goes as the wind squared, the whitecap fraction as U^3.41 or U^3.75
 * by the sea's model: coverage times a^1.7 or a^1.9). The mask's gradient is not added to the
 * slopes: keep it coarse and smooth (a texel of tens of metres or more; a blurred island lee).
 * Not modelled: the shorter waves a lighter wind would also bring. */
#define SWELL_MASK_MAX_TEXELS 254   /* a mask's texels along a side, at most */
typedef struct swell_mask {
    const unsigned char *amplitude; /* width x height bytes: row 0 along the rectangle's
                                 * south edge (smallest y), x growing along a row */
    int width, height;          /* texels, 1..SWELL_MASK_MAX_TEXELS each */
    double origin_m[2];         /* world x, y of the rectangle's corner nearest -inf, m */
    double size_m[2];           /* its extent along x and y, m (0..1e6] */
} swell_mask;
/* Set (or with NULL remove) the mask the next draws take (an ocean created with wave_mask =
 * 1). The bytes are copied: free them after the call. Pass the same mask to swell_sea_sample
 * (swell_sample_desc mask) to float things on the water drawn. */
SWELL_API int swell_ocean_set_mask(swell_ocean *ocean, const swell_mask *mask,
                                   struct swell_err *err);

/* What an ocean is and did. */
typedef struct swell_ocean_stats {
    int tier;                   /* enum swell_tier in use (never SWELL_TIER_BEST) */
    int tier_available;         /* the best tier the context offers */
    int quality;                /* enum swell_quality in use: a driver that refuses every
                                 * high-quality program gets low quality */
    int detile;                 /* 1: the patterns are read detiled (swell_sample_desc no_detile
                                 * 0 samples the same sea), 0: once, at no offset */
    int objects;                /* 1: reflections, wakes, shadows, refractions or a wave mask
                                 * were asked for and the driver runs them; 0:
                                 * swell_ocean_begin_* and _set_wake, _set_mask fail */
    uint64_t gpu_bytes;         /* GPU memory the ocean holds (tables, maps, buffers), bytes */
    uint64_t gpu_bytes_charged; /* all that is charged to its budget: gpu_bytes and the
                                 * targets of its swell_upscale */
    uint64_t budget_bytes;      /* the budget it keeps within */
    int vertices, triangles;    /* of the sea's mesh */
    uint64_t cpu_bytes_per_frame; /* bytes streamed to the GPU per draw: the vertices on the
                                   * CPU's grid, and the tables' loop blend where the CPU
                                   * blends it (not where the GPU does: a loop frame's tables
                                   * are uploaded once, when the loop reaches it) */
    double camera_raise_m;      /* the last draw drew the camera this much higher, m: it was
                                 * less than 0.3 m above the water under it */
} swell_ocean_stats;
SWELL_API void swell_ocean_get_stats(const swell_ocean *ocean, swell_ocean_stats *out);
/* How the ocean draws, in lines of "what: how" (its tier, geometry, programs, fallbacks), as
 * snprintf writes (at most cap bytes with the terminating 0); returns the whole length. */
SWELL_API size_t swell_ocean_describe(const swell_ocean *ocean, char *buf, size_t cap);
/* In a frame drawn with debug_programs: the program that drew a pixel (its RGBA8 as read
 * back), its name written to name ("ocean k=2 kw=1 high", at most cap bytes); returns a
 * program's index >= 0, SWELL_PIXEL_SKY where no sea was drawn, SWELL_PIXEL_MIXED for a
 * colour no program writes (the edge of a run, a blend). */
enum { SWELL_PIXEL_SKY = -1, SWELL_PIXEL_MIXED = -2 };
SWELL_API int swell_ocean_program_at(const swell_ocean *ocean, const uint8_t rgba[4],
                                     char *name, size_t cap);

/* ---- render scale: the frame drawn smaller and stretched over the output ---------------- */

/* For GPUs whose fragment rate cannot shade every output pixel (a Mali-400 at 1080p): the
 * application's frame, sea and objects, drawn into a target of scale x the output's size and
 * stretched over the output by one bilinear fetch a pixel (scale^2 of the pixels shaded; the
 * picture blurs). The target (RGBA8, 16-bit depth when depth_bits > 0) is charged to the
 * ocean's GPU memory budget; creating it draws the stretch once, so a driver that refuses it
 * is told here (SWELL_E_SHADER), not at a frame. */
typedef struct swell_upscale swell_upscale;
#define SWELL_UPSCALE_MIN 0.25
#define SWELL_UPSCALE_MAX 1.0
SWELL_API int swell_upscale_create(swell_ocean *ocean, int out_width, int out_height,
                                   double scale, int depth_bits, swell_upscale **out,
                                   struct swell_err *err);
/* The target's size: round(out x scale), at least 1 pixel; draw the frame at this size. */
SWELL_API void swell_upscale_size(const swell_upscale *up, int *width, int *height);
/* Before the frame: the framebuffer bound now is the output; the target is bound. */
SWELL_API void swell_upscale_begin(swell_upscale *up);
/* After it: the output bound again and the target stretched over all of it (viewport 0, 0,
 * out_width, out_height; the program, buffer, texture binding of the ocean's first unit and
 * vertex attribute 0 restored as swell_ocean_draw restores them). */
SWELL_API int swell_upscale_end(swell_upscale *up, struct swell_err *err);
SWELL_API void swell_upscale_destroy(swell_upscale *up);

/* Move the sun (re-bakes the sky map: not for every frame). */
SWELL_API int swell_ocean_set_sun(swell_ocean *ocean, float elev_deg, float azim_deg,
                                  struct swell_err *err);
SWELL_API void swell_ocean_destroy(swell_ocean *ocean);

#ifdef __cplusplus
}
#endif

#endif
