/* grid_internal.h - what the grid's four files share, for them alone (grid.h is the
 * interface): the grid's state (struct grid, its patterns' float images, the layout constants
 * its arrays are sized by), the float4 vector types, the sphere's drop, and the CPU sampler's
 * per-sample half (texel_sample, tap4, mip_level: inline, as the vertex passes call them per
 * vertex and tap). The files: grid.c (lifetime, topology, row spans), grid_project.c (rest
 * positions per frame), grid_sample.c (the tables blended to float images), grid_pass.c
 * (grid_update's per-vertex passes). */
#ifndef SWELL_GRID_INTERNAL_H
#define SWELL_GRID_INTERNAL_H

#include <math.h>
#include <stdint.h>
#include <string.h>
#include "geometry/detile.h"
#include "geometry/grid.h"
#include "geometry/mask.h"

#define EARTH_R2 ((float)(EARTH_RADIUS_M * EARTH_RADIUS_M))

/* The sphere's drop below the camera's level plane at horizontal distance r (from r^2):
 * R - sqrt(R^2 - r^2), written r^2 / (R + sqrt(R^2 - r^2)) so that it is exact near the camera
 * (r^2 / 2R) as well as at orbit's horizon, where the parabola put the limb 2 px high. */
static inline float sphere_drop(float r2)
{
    float q = EARTH_R2 - r2;
    return r2 / ((float)EARTH_RADIUS_M + sqrtf(q > 0.0f ? q : 0.0f));
}

#define NEAR_N 129            /* near patch vertices per side (128 cells) */
#define FAR_RINGS 32          /* far patch rings from the near patch border to the far plane */
#define NEAR_RINGS ((NEAR_N - 1) / 2)  /* square rings of cells the near patch is drawn in */
#define TILE_LOG2 3           /* lazily blended tiles of 8 x 8 texels */
#define COORD_BIAS 1073741824.0  /* 2^30: a multiple of every table size; makes texel coords > 0 */
#define VBLK 8                /* vertices per fixed-size block of the vectorised per-vertex passes */

/* A float4 texel as one vector, and the byte and integer vectors of the blend (GCC/Clang vector
 * extensions: SSE2 or NEON registers, or plain lanes where the target has neither; no
 * intrinsics); ld4 reads a float4 from any alignment. */
typedef float f4 __attribute__((vector_size(16)));
typedef uint8_t u8x16 __attribute__((vector_size(16)));
typedef uint16_t u16x8 __attribute__((vector_size(16)));
typedef int32_t i32x4 __attribute__((vector_size(16)));
static inline f4 ld4(const float *p)
{
    f4 v;
    memcpy(&v, p, sizeof(v));
    return v;
}

/* Lane-wise max(a, b) by a compare and a bitwise select (NaN in a gives b). On SSE the one
 * instruction that does exactly that, MAXPS (GCC does not fold the select into it): grid_update
 * at the surface, rough, gles2-min low quality, 2.049 -> 1.996 M instructions a frame
 * (tools/cg-frame.sh). */
#if defined(__SSE__) && (defined(__GNUC__) || defined(__clang__))
#define GRID_SSE 1   /* GCC/Clang's SSE builtins (x86-64 always); ARM keeps the portable code */
#else
#define GRID_SSE 0
#endif

static inline f4 max4(f4 a, f4 b)
{
#if GRID_SSE
    return __builtin_ia32_maxps(a, b);
#else
    i32x4 gt = a > b, ia, ib;
    memcpy(&ia, &a, sizeof(ia));
    memcpy(&ib, &b, sizeof(ib));
    ia = (ia & gt) | (ib & ~gt);
    memcpy(&a, &ia, sizeof(a));
    return a;
#endif
}

/* sphere_drop of four r^2 at once (the same IEEE operations, so the same floats): grid_update
 * at the surface (as max4's) 1.996 -> 1.924 M instructions a frame, a sqrtss and a divss per
 * vertex before */
static inline f4 sphere_drop4(f4 r2)
{
#if GRID_SSE
    const f4 rr = { EARTH_R2, EARTH_R2, EARTH_R2, EARTH_R2 };
    const f4 r = { (float)EARTH_RADIUS_M, (float)EARTH_RADIUS_M, (float)EARTH_RADIUS_M,
                   (float)EARTH_RADIUS_M };
    return r2 / (r + __builtin_ia32_sqrtps(max4(rr - r2, (f4){ 0.0f, 0.0f, 0.0f, 0.0f })));
#else
    for (int e = 0; e < 4; e++)
        r2[e] = sphere_drop(r2[e]);
    return r2;
#endif
}

/* A blended, dequantised level of a table as float4 texels, with its first column and row
 * repeated after its last so a bilinear footprint never wraps: texel (x, y) is at
 * data + 4 (y (w + 1) + x). A moment level is blended lazily, by tiles of 16 x 16 texels (plus
 * the next column and row), the first time a sample needs one in the current phase: views near
 * the sea touch a few of the finest level's tiles. A displacement image (at most 64 x 64 as
 * baked) is blended whole when its phase moves and a vertex needs it: at the surface most of
 * it is sampled, and a per-sample tile test cost more than the texels it spared. */
struct f4_image {
    float *data;              /* (w + 1) (h + 1) texels */
    uint32_t *stamp;          /* per tile: the generation it was blended for */
    const struct swell_table *t;
    const float *sc, *bi;     /* dequantisation of a blend (a w0 + b w1 + rnd) >> shift */
    uint16_t rnd;             /* 0 and shift 0: the exact blend (displacement); 128 and 8: */
    int shift;                /* rounded to bytes as stream_blend does (moments, which the
                                 fragment shader's patterns read from such bytes too) */
    int level, w, h, tiles_x;
    float mix_s;              /* > 0: a whitecap table's level 0 or 1, whose channel 2 blend_tile
                               * fills with the blend's own variance (1 - w) w (m1 - m0)^2 as
                               * stream_blend_whitecap does for the GPU: (channel-0 scale / 255)^2 */
    uint32_t gen;             /* bumped when the phase changes */
    struct stream_phase ph;   /* phase of generation gen */
    int box[4];               /* displacement: footprints blended for generation box_gen, */
    uint32_t box_gen;         /* first texels from box[0] over box[1] columns, box[2] and [3] rows */
};

struct grid_pattern {
    const struct swell_table *disp, *slope, *wc;
    float *disp_mem;          /* owned storage of every image below */
    uint32_t *stamp_mem;      /* and of their tile stamps */
    struct f4_image disp_f;   /* displacement (x, y, z, unused), m */
    struct f4_image slope_f[16], wc_f[16];  /* moment chains per level (CPU patterns; wc_f
                                             * also for k-only patterns) */
    float disp_sc[4], disp_bi[4];           /* dequantisation of a blend a w0 + b w1 */
    float slope_sc[4], slope_bi[4], wc_sc[4], wc_bi[4];
    double inv_l;             /* 1 / L_i */
    float lambda_m;           /* characteristic wavelength for the eq. 2 weight, m */
    float k_mean;             /* the foam memory's mean over the patch (its top mip texel) */
    int cpu, kcpu, levels;    /* kcpu: its whitecap moments alone per vertex (grid.h) */
    int k_flat;               /* kcpu: the first level whose texels' means hold less than
                               * K_FLAT of the foam memory's variance (k_flat_level) */
    float k_w0;               /* kcpu: level 0's mean within-texel variance (magnified_var) */
};

/* Per-vertex arrays are structures of arrays over npad = nverts rounded up to VBLK entries (plus
 * a row and a block more, which the footprint pass reads past the end): fixed blocks of VBLK
 * vertices are what -O2's very-cheap vectoriser accepts. Padding vertices have fade 0, so eq. 2
 * gives them weight 0 and no pass samples for them. */
struct grid {
    const struct swell_tables *t;
    int kind, w, h;
    int nverts, nidx;
    int npad;                 /* nverts rounded up to VBLK */
    int ws;                   /* projected grid row width rounded up to VBLK */
    uint16_t *idx;
    float *rx, *ry;           /* per-vertex rest position on the sea plane, m */
    float *foot;              /* per-vertex footprint (cell size on the sea plane), m */
    float *fade;              /* per-vertex displacement factor (1 on the projected grid) */
    float *row_d2;            /* per projected grid row: smallest squared distance, m^2 */
    float *acc;               /* per-vertex summed displacement (x, y, z, 0), m (displace) */
    float *wv, *fx, *fy;      /* per vertex, one pattern's eq. 2 weight and bilinear fractions */
    int *ix, *iy;             /* and the first texel of its bilinear footprint (disp_coords) */
    float *blk_foot;          /* per block of VBLK vertices: its smallest footprint this frame, m */
    int *run;                 /* [start, end) vertices of the runs of blocks a pattern displaces */
    float unit[3];            /* 0, 1 and 1e-6 m: clamp bounds (disp_coords says why a field) */
    double *col_sx;           /* per projected grid column (ws): NDC x of its rays */
    float *row_x, *row_y;     /* one projected grid row's rest positions (ws), m */
    float foot_lo, foot_hi;   /* smallest and largest footprint this frame */
    float foot_lo_wet;        /* smallest footprint of the vertices with fade > 0 */
    float *row_foot;          /* per row of triangles: smallest squared distance, m^2 */
    int rows;
    struct grid_pattern p[SWELL_MAX_PATTERNS];
    uint8_t hash[DETILE_N * DETILE_N];  /* detile_hash_table */
    int detile;               /* 0: grid_desc no_detile */
    double crest_m;           /* bound on the summed vertical displacement, m */
    double chop_m;            /* bound on the summed horizontal (choppy) displacement, m */
    struct grid_wake wake;    /* grid_set_wake; wake.map NULL: none */
    double wake_crest_m;      /* the wake map's largest |height|, m (0 without one) */
    int mask_attr;            /* grid_set_mask: 1: every vertex's GRID_A_PAD holds its mask
                               * amplitude (1 without a mask) */
    struct wave_mask mask;    /* mask.amp NULL: none */
};

/* The bound on the summed vertical displacement: the patterns' and the wake's. */
static inline double grid_crest(const struct grid *g)
{
    return g->crest_m + g->wake_crest_m;
}

static inline float maxf(float a, float b) { return a > b ? a : b; }
static inline float minf(float a, float b) { return a < b ? a : b; }
static inline float clamp01(float a) { return a < 0.0f ? 0.0f : (a > 1.0f ? 1.0f : a); }

/* grid_sample.c: the float images of pattern i (grid_create), a tile of an image blended for
 * its phase, and a displacement image's bilinear footprints blended (displace). */
int pattern_images(struct grid_pattern *p, int i, struct swell_err *err);
void blend_tile(struct f4_image *im, int tx, int ty);
int box_blended(const struct f4_image *im, int sx, int mx, int sy, int my);
void blend_box(struct f4_image *im, int sx, int mx, int sy, int my);

/* Start a new generation of im when the pattern's phase has moved: every tile is stale. */
static inline void image_phase(struct f4_image *im, const struct stream_phase *ph)
{
    if (ph->f0 == im->ph.f0 && ph->w == im->ph.w)
        return;
    im->ph = *ph;
    im->gen++;
}

/* Bilinear samples at texel coordinates (x, y), wrapped (power-of-two sizes), of two float4
 * images of the same size (slope and whitecaps), blending their tiles first if they are stale;
 * each texel's four channels as one vector.
 * COORD_BIAS, a multiple of the size, makes the coordinates positive so truncation floors them
 * (|x| < 2^30 texels; the fraction keeps 2^-22 texel). */
static inline f4 lerp4(f4 a, f4 b, f4 t) { return a + (b - a) * t; }

/* Where (x, y) falls in an image: its texel's offset, tile and the bilinear fractions. */
struct texel_at {
    size_t off, stride;
    int tile, tx, ty;
    f4 vx, vy;
};

static inline void texel_locate(const struct f4_image *im, double x, double y, struct texel_at *a)
{
    const int wm = im->w - 1, hm = im->h - 1;
    double bx = x + COORD_BIAS, by = y + COORD_BIAS;
    long long ix = (long long)bx, iy = (long long)by;
    float fx = (float)(bx - (double)ix), fy = (float)(by - (double)iy);
    int xi = (int)(ix & wm), yi = (int)(iy & hm);
    a->tx = xi >> TILE_LOG2;
    a->ty = yi >> TILE_LOG2;
    a->tile = a->ty * im->tiles_x + a->tx;
    a->stride = 4 * (size_t)(wm + 2);
    a->off = (size_t)yi * a->stride + 4 * (size_t)xi;
    a->vx = (f4){ fx, fx, fx, fx };
    a->vy = (f4){ fy, fy, fy, fy };
}

/* The bilinear sample at a, blending its tile first if it is stale. */
static inline f4 texel_sample(struct f4_image *im, const struct texel_at *a)
{
    if (im->stamp[a->tile] != im->gen)
        blend_tile(im, a->tx, a->ty);
    const float *p = im->data + a->off, *c = p + a->stride;
    return lerp4(lerp4(ld4(p), ld4(p + 4), a->vx), lerp4(ld4(c), ld4(c + 4), a->vx), a->vy);
}

static inline void sample_f4x2(struct f4_image *im, struct f4_image *im2, double x, double y,
                               f4 *out, f4 *out2)
{
    struct texel_at a;
    texel_locate(im, x, y, &a);
    *out = texel_sample(im, &a);
    *out2 = texel_sample(im2, &a);
}

/* Mip level whose texel matches a footprint of r level-0 texels: floor(log2 r) for r >= 2, else
 * 0, at most top; read from the float's exponent (r * 2^-k is exact, so this is the level the
 * halving loop `while (r >= 2) r *= 0.5` stops at). */
static inline int mip_level(float r, int top)
{
    uint32_t bits;
    int e;
    if (!(r >= 2.0f))
        return 0;
    memcpy(&bits, &r, sizeof(bits));
    e = (int)(bits >> 23) - 127;    /* r >= 2 is positive and normal (or infinite) */
    return e < top ? e : top;
}

/* A bilinear fetch from the texel off bytes into the image's row (base) and the next (base_c),
 * fractions vx, vy. */
static inline f4 bilerp(const char *restrict base, const char *restrict base_c, int off, f4 vx,
                        f4 vy)
{
    const float *a = (const float *)(base + off), *c = (const float *)(base_c + off);
    f4 a0 = ld4(a), a1 = ld4(a + 4), c0 = ld4(c), c1 = ld4(c + 4);
    f4 top = a0 + (a1 - a0) * vx, bot = c0 + (c1 - c0) * vx;
    return top + (bot - top) * vy;
}

/* One tap's bilinear fetch: the tap's whole-texel offset (ox, oy) added to the footprint's
 * first texel (x, y). */
static inline f4 tap4(const char *restrict base, const char *restrict base_c, int x, int y,
                      int ox, int oy, int wm, int hm, int wshift, f4 vx, f4 vy)
{
    x = (x + ox) & wm;
    y = (y + oy) & hm;
    return bilerp(base, base_c, 16 * ((y << wshift) + y + x), vx, vy);   /* 16 (y (w + 1) + x) */
}

/* grid_project.c: the rest positions and footprints of a frame (0 when no sea is in view, else
 * the index count), and the rows' distances from them (grid_row_span). */
int update_projected(struct grid *g, const struct camera_frame *view);
int update_patches(struct grid *g, const struct camera_frame *view);
void row_distances(struct grid *g);

#endif
