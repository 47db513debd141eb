/* grid.c - CPU ocean geometry (grid.h): projected grid or near/far patches, displaced by the
 * looping displacement tables with Bruneton 2010 eq. 2 filter weights. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "geometry/detile.h"
#include "geometry/grid.h"
#include "tables/quantize.h"

#define EARTH_R2 ((float)(EARTH_RADIUS_M * EARTH_RADIUS_M))

/* The sphere's drop below the camera's level plane at horizontal distance r (from r^2):
 * R - sqrt(R^2 - r^2), written r^2 / (R + sqrt(R^2 - r^2)) so that it is exact near the camera
 * (r^2 / 2R) as well as at orbit's horizon, where the parabola put the limb 2 px high. */
static inline float sphere_drop(float r2)
{
    float q = EARTH_R2 - r2;
    return r2 / ((float)EARTH_RADIUS_M + sqrtf(q > 0.0f ? q : 0.0f));
}
#define GRID_MARGIN 0.02      /* NDC beyond the bounding box of what displacement can reach */
#define FILTER_NMIN 2.0f      /* Bruneton eq. 2: waves shorter than Nmin cells are cancelled... */
#define FILTER_NMAX 4.0f      /* ...and kept in full from Nmax cells up */
#define NEAR_N 129            /* near patch vertices per side (128 cells) */
#define FAR_RINGS 32          /* far patch rings from the near patch border to the far plane */
#define NEAR_RINGS ((NEAR_N - 1) / 2)  /* square rings of cells the near patch is drawn in */
#define NEAR_FADE 0.1         /* last tenth of the near patch fades the displacement to 0 */
#define BLEND_BLOCK 16        /* RGBA8 bytes (4 texels) blended to floats per vectorised block */
#define TILE_LOG2 4           /* lazily blended tiles of 16 x 16 texels */
#define COORD_BIAS 1073741824.0  /* 2^30: a multiple of every table size; makes texel coords > 0 */
#define VBLK 8                /* vertices per fixed-size block of the vectorised per-vertex passes */
#define COORD_MAX 1073741824.0f  /* 2^30: float texel coordinates are clamped to +-COORD_MAX */

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
    uint32_t gen;             /* bumped when the phase changes */
    struct stream_phase ph;   /* phase of generation gen */
    int box[4];               /* displacement: footprints blended for generation box_gen, */
    uint32_t box_gen;         /* first texels from box[0] over box[1] columns, box[2] and [3] rows */
};

/* One frame's constants of a pattern's lattice (detile.h): a rest point's cell coordinates are
 * q = q0 + rest qk (camera-relative, float), its hash cell floor(q) + sh (the shaders' shift,
 * detile_camera_shift: the camera's cell and the pattern's shift modulo DETILE_N). */
struct detile_frame {
    const uint8_t *hash;      /* detile_hash_table's (the grid's copy); NULL: no lattice, one tap
                                 at no offset (grid_desc no_detile) */
    float q0x, q0y, qk;
    int shx, shy;
};

static void detile_frame_set(struct detile_frame *f, const uint8_t *hash, int pattern,
                             double inv_l, const struct camera *cam)
{
    float sh[3];
    f->hash = hash;
    if (!hash)
        return;
    f->qk = (float)(inv_l * DETILE_CELLS);
    double ux = cam->pos[0] * inv_l, uy = cam->pos[1] * inv_l;
    /* cell q = DETILE_CELLS (floor(cam / L) + frac(cam / L) + rest / L) */
    f->q0x = (float)((ux - floor(ux)) * DETILE_CELLS);
    f->q0y = (float)((uy - floor(uy)) * DETILE_CELLS);
    detile_camera_shift(pattern, cam->pos[0], cam->pos[1], inv_l, sh);
    f->shx = (int)sh[0];
    f->shy = (int)sh[1];
}

static inline void detile_at(const struct detile_frame *f, float rx, float ry,
                             struct detile_taps *t)
{
    if (!f->hash) {
        detile_taps_off(t);
        return;
    }
    float qx = f->q0x + rx * f->qk, qy = f->q0y + ry * f->qk;
    /* floor by conversion (floorf is a call on x86-64's SSE2); |q| < 2^31 where a pattern's
     * eq. 2 weight is not 0 (a cell is half a tile) */
    int ix = (int)qx, iy = (int)qy;
    ix -= qx < (float)ix;
    iy -= qy < (float)iy;
    detile_taps_cell(f->hash, (long)ix + f->shx, (long)iy + f->shy, qx - (float)ix,
                     qy - (float)iy, t);
}

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

/* One frame's constants of a CPU pattern for the moment pass: texel coordinates of moment level
 * l are x = mx0[l] + rest_x mk[l] (the uv offset and the half-texel shift folded in, in double). */
struct pattern_frame {
    struct grid_pattern *p;
    struct detile_frame dt;   /* its lattice (detile.h) */
    double mx0[16], my0[16], mk[16];
    float lev_k;              /* level-0 texels per metre of footprint: width / L_i */
};

/* One frame's constants of a pattern that displaces some vertex (eq. 2 weight > 0): texel
 * coordinates of its displacement image x = x0 + rest_x kx, in float. */
struct disp_frame {
    struct f4_image *im;      /* the pattern's displacement image */
    const float *data;        /* its texels */
    float x0, y0, kx, ky;
    float lambda_m;           /* eq. 2's characteristic wavelength, m */
    struct detile_frame dt;   /* its lattice (detile.h) */
    float foot_zero;          /* footprints from this one up give weight 0, m */
    float coord_max;          /* COORD_MAX */
    int wm, hm, wshift;
    size_t stride;            /* bytes per padded image row */
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
};

float grid_filter_weight(float a, float b, float x)
{
    float u = (x - a) / (b - a);
    u = u < 0.0f ? 0.0f : (u > 1.0f ? 1.0f : u);
    return u * u * (3.0f - 2.0f * u);
}

int grid_vertex_count(const struct grid *g) { return g->nverts; }
int grid_index_count(const struct grid *g) { return g->nidx; }
const uint16_t *grid_indices(const struct grid *g) { return g->idx; }

void grid_uv_offset(const struct swell_tables *t, int pattern, const struct camera *cam,
                    float out[2])
{
    double l = t->pattern[pattern].size_m > 0.0f ? t->pattern[pattern].size_m : 1.0;
    for (int c = 0; c < 2; c++) {
        double u = cam->pos[c] / l;
        out[c] = (float)(u - floor(u));
    }
}

static void quad(uint16_t *idx, int *n, int a, int b, int c, int d)
{
    /* a b over c d: two triangles */
    idx[(*n)++] = (uint16_t)a; idx[(*n)++] = (uint16_t)c; idx[(*n)++] = (uint16_t)b;
    idx[(*n)++] = (uint16_t)b; idx[(*n)++] = (uint16_t)c; idx[(*n)++] = (uint16_t)d;
}

static int build_topology(struct grid *g, struct swell_err *err)
{
    int n = 0;
    if (g->kind == 0) {
        g->nverts = g->w * g->h;
        g->idx = malloc(sizeof(uint16_t) * 6 * (size_t)(g->w - 1) * (size_t)(g->h - 1));
        if (!g->idx)
            return swell_fail(err, SWELL_E_NOMEM, "grid: no memory for %d x %d indices", g->w, g->h);
        /* Row 0 is the horizon: far rows are drawn first so nearer waves cover farther ones
         * even without a depth buffer. */
        for (int j = 0; j + 1 < g->h; j++)
            for (int i = 0; i + 1 < g->w; i++)
                quad(g->idx, &n, j * g->w + i, j * g->w + i + 1, (j + 1) * g->w + i,
                     (j + 1) * g->w + i + 1);
    } else {
        int per = 4 * (NEAR_N - 1), rings = FAR_RINGS + 1;
        int near0 = rings * per;
        g->nverts = near0 + NEAR_N * NEAR_N;
        g->idx = malloc(sizeof(uint16_t) * 6 * ((size_t)FAR_RINGS * per +
                                                (size_t)(NEAR_N - 1) * (NEAR_N - 1)));
        if (!g->idx)
            return swell_fail(err, SWELL_E_NOMEM, "grid: no memory for patch indices");
        /* Far patch outermost ring first, then the near patch (Hu 2006 §3). */
        for (int k = FAR_RINGS - 1; k >= 0; k--)
            for (int m = 0; m < per; m++) {
                int m1 = (m + 1) % per;
                quad(g->idx, &n, (k + 1) * per + m, (k + 1) * per + m1, k * per + m, k * per + m1);
            }
        /* The near patch as square rings of cells around its centre, where the camera is,
         * outermost first: each ring spans a narrow range of distances, so the run of rows it
         * is drawn in fetches at its own level (a row across the patch ran from under the
         * camera to the border, and a run's level is its nearest vertex's). */
        for (int k = NEAR_RINGS - 1; k >= 0; k--) {
            int lo = NEAR_RINGS - 1 - k, hi = NEAR_RINGS + k;
            for (int j = lo; j <= hi; j++)
                for (int i = lo; i <= hi; i++) {
                    if (j != lo && j != hi && i != lo && i != hi)
                        continue;
                    quad(g->idx, &n, near0 + j * NEAR_N + i, near0 + j * NEAR_N + i + 1,
                         near0 + (j + 1) * NEAR_N + i, near0 + (j + 1) * NEAR_N + i + 1);
                }
        }
    }
    g->nidx = n;
    return 0;
}

static size_t f4_texels(int w, int h)
{
    return (size_t)(w + 1) * (size_t)(h + 1);
}

/* Dequantisation of a blend of RGBA8 texels (w0 + w1 = STREAM_W_ONE): exact,
 * value = bias + scale (a w0 + b w1) / (255 STREAM_W_ONE), or rounded to a byte v first,
 * value = bias + scale v / 255. */
static void dequant(const struct swell_table *t, int rounded, float sc[4], float bi[4])
{
    for (int c = 0; c < 4; c++) {
        sc[c] = (float)(t->scale[c] / (255.0 * (rounded ? 1 : STREAM_W_ONE)));
        bi[c] = t->bias[c];
    }
}

static int tiles_of(int n)
{
    return (n + (1 << TILE_LOG2) - 1) >> TILE_LOG2;
}

/* Lay out image im (level l of t) at *texels floats / *tiles stamps into the memory at
 * data / stamp (both NULL: only count). */
static void image_layout(struct f4_image *im, const struct swell_table *t, int l, const float *sc,
                         const float *bi, float *data, uint32_t *stamp, size_t *texels,
                         size_t *tiles)
{
    int w = table_level_width(t, l), h = table_level_height(t, l);
    if (data) {
        *im = (struct f4_image){ .data = data + 4 * *texels, .stamp = stamp + *tiles, .t = t,
                                 .sc = sc, .bi = bi, .level = l, .w = w, .h = h,
                                 .tiles_x = tiles_of(w), .gen = 1 };
        im->ph.f0 = -1;
        if (t->kind != TABLE_DISP) {
            im->rnd = STREAM_W_ONE / 2;
            im->shift = 8;      /* log2(STREAM_W_ONE) */
        }
    }
    *texels += f4_texels(w, h);
    *tiles += (size_t)tiles_of(w) * (size_t)tiles_of(h);
}

/* From the level whose texels' means hold less than this fraction of the foam memory's
 * variance over the patch (the rest within the texels), k_moment_pass takes the patch's top
 * texel instead of sampling: the means are nearly flat there, and eq. 6 of the top texel's
 * moments differs little (renderer.c DROP_RESOLVED for the slopes). */
#define K_FLAT 0.02

/* The first level l of whitecap table t (its first loop frame) from which every coarser level's
 * means hold less than K_FLAT of the variance: within(top) - within(l) < K_FLAT within(top),
 * within(l) the mean over level l's texels of <m^2> - <m>^2. */
static int k_flat_level(const struct swell_table *t)
{
    int top = t->levels - 1, flat = top;
    float all = table_level_within_var(t, top, 0, 1);
    while (flat > 0 && all - table_level_within_var(t, flat - 1, 0, 1) < K_FLAT * all)
        flat--;
    return flat;
}

/* The float images of pattern i: its displacement, and its moment chains if it is a CPU
 * pattern. Stamps start at 0, older than any generation. */
static int pattern_images(struct grid_pattern *p, int i, struct swell_err *err)
{
    size_t texels = 0, tiles = 0;
    dequant(p->disp, 0, p->disp_sc, p->disp_bi);
    /* the displacement's fourth channel is unused: 0, so the summed float4 is (x, y, z, 0) */
    p->disp_sc[3] = p->disp_bi[3] = 0.0f;
    dequant(p->slope, 1, p->slope_sc, p->slope_bi);
    dequant(p->wc, 1, p->wc_sc, p->wc_bi);
    for (int pass = 0; pass < 2; pass++) {
        float *data = pass ? p->disp_mem : NULL;
        uint32_t *stamp = pass ? p->stamp_mem : NULL;
        texels = tiles = 0;
        image_layout(&p->disp_f, p->disp, 0, p->disp_sc, p->disp_bi, data, stamp, &texels, &tiles);
        for (int l = 0; (p->cpu || p->kcpu) && l < p->levels; l++) {
            if (p->cpu)
                image_layout(&p->slope_f[l], p->slope, l, p->slope_sc, p->slope_bi, data, stamp,
                             &texels, &tiles);
            image_layout(&p->wc_f[l], p->wc, l, p->wc_sc, p->wc_bi, data, stamp, &texels, &tiles);
        }
        if (pass == 0) {
            p->disp_mem = calloc(4 * texels, sizeof(float));   /* finite before blending */
            p->stamp_mem = calloc(tiles, sizeof(uint32_t));
            if (!p->disp_mem || !p->stamp_mem)
                return swell_fail(err, SWELL_E_NOMEM, "grid: no memory for pattern %d images", i);
        }
    }
    return 0;
}

/* The displacement factor depends on the vertex only: 1 on the projected grid; on the patches 0
 * on the far rings and fading to 0 over the near patch's last NEAR_FADE (Hu 2006 §3). */
static void init_fade(struct grid *g)
{
    int near0 = (FAR_RINGS + 1) * 4 * (NEAR_N - 1);
    double inv = 1.0 / (NEAR_N - 1);
    if (g->kind == 0) {
        for (int k = 0; k < g->nverts; k++)
            g->fade[k] = 1.0f;
        return;
    }
    for (int k = 0; k < near0; k++)
        g->fade[k] = 0.0f;
    for (int j = 0; j < NEAR_N; j++)
        for (int i = 0; i < NEAR_N; i++) {
            double x = -1.0 + 2.0 * i * inv, y = -1.0 + 2.0 * j * inv;
            double edge = 1.0 - fmax(fabs(x), fabs(y));
            g->fade[near0 + j * NEAR_N + i] = (float)fmin(edge / NEAR_FADE, 1.0);
        }
}

void grid_destroy(struct grid *g)
{
    if (!g)
        return;
    for (int i = 0; i < SWELL_MAX_PATTERNS; i++) {
        free(g->p[i].disp_mem);
        free(g->p[i].stamp_mem);
    }
    free(g->row_foot);
    free(g->acc);
    free(g->wv);
    free(g->fx);
    free(g->fy);
    free(g->ix);
    free(g->iy);
    free(g->blk_foot);
    free(g->run);
    free(g->fade);
    free(g->foot);
    free(g->rx);
    free(g->ry);
    free(g->row_d2);
    free(g->col_sx);
    free(g->row_x);
    free(g->row_y);
    free(g->idx);
    free(g);
}

int grid_create(const struct grid_desc *d, struct grid **out, struct swell_err *err)
{
    const struct swell_tables *t = d->tables;
    struct grid *g = NULL;
    int rc;
    *out = NULL;
    if (!t || t->patterns < 1 || t->patterns > SWELL_MAX_PATTERNS)
        return swell_fail(err, SWELL_E_ARG, "grid: tables missing or with %d patterns (1..%d)",
                          t ? t->patterns : 0, SWELL_MAX_PATTERNS);
    g = calloc(1, sizeof(*g));
    if (!g)
        return swell_fail(err, SWELL_E_NOMEM, "grid: no memory");
    g->t = t;
    g->kind = d->kind;
    g->w = d->w > 0 ? d->w : 80;
    g->h = d->h > 0 ? d->h : 56;
    if (g->kind == 0 && (g->w < 2 || g->h < 2 || g->w * g->h > 65536)) {
        rc = swell_fail(err, SWELL_E_ARG, "grid: %d x %d vertices; need 2..65536 in all "
                        "(16-bit indices on GLES2)", g->w, g->h);
        goto fail;
    }
    if ((rc = build_topology(g, err)))
        goto fail;
    g->rows = g->kind == 0 ? g->h - 1 : FAR_RINGS + NEAR_RINGS;
    g->npad = (g->nverts + VBLK - 1) / VBLK * VBLK;
    g->ws = (g->w + VBLK - 1) / VBLK * VBLK;
    {
        size_t n = (size_t)g->npad + (size_t)g->w + VBLK;
        g->row_foot = calloc((size_t)g->rows, sizeof(float));
        g->acc = calloc(4 * (size_t)g->npad, sizeof(float));
        g->wv = calloc((size_t)g->npad, sizeof(float));
        g->fx = calloc((size_t)g->npad, sizeof(float));
        g->fy = calloc((size_t)g->npad, sizeof(float));
        g->ix = calloc((size_t)g->npad, sizeof(int));
        g->iy = calloc((size_t)g->npad, sizeof(int));
        g->blk_foot = calloc((size_t)g->npad / VBLK, sizeof(float));
        g->run = calloc((size_t)g->npad / VBLK + 1, sizeof(int));
        g->foot = calloc(n, sizeof(float));
        g->fade = calloc(n, sizeof(float));
        g->rx = calloc(n, sizeof(float));
        g->ry = calloc(n, sizeof(float));
        g->row_d2 = calloc((size_t)g->h, sizeof(float));
        g->col_sx = calloc((size_t)g->ws, sizeof(double));
        g->row_x = calloc((size_t)g->ws, sizeof(float));
        g->row_y = calloc((size_t)g->ws, sizeof(float));
    }
    if (!g->foot || !g->fade || !g->row_foot || !g->rx || !g->ry || !g->row_d2 ||
        !g->col_sx || !g->row_x || !g->row_y || !g->acc || !g->wv || !g->fx || !g->fy ||
        !g->ix || !g->iy || !g->blk_foot || !g->run) {
        rc = swell_fail(err, SWELL_E_NOMEM, "grid: no memory for %d vertices", g->nverts);
        goto fail;
    }
    init_fade(g);
    detile_hash_table(g->hash);
    g->detile = !d->no_detile;
    g->unit[0] = 0.0f;
    g->unit[1] = 1.0f;
    g->unit[2] = 1e-6f;
    for (int i = 0; i < t->patterns; i++) {
        struct grid_pattern *p = &g->p[i];
        const struct swell_pattern_info *pi = &t->pattern[i];
        p->disp = tables_find(t, TABLE_DISP, i);
        p->slope = tables_find(t, TABLE_SLOPE, i);
        p->wc = tables_find(t, TABLE_WHITECAP, i);
        if (!p->disp || !p->slope || !p->wc || p->disp->format != FORMAT_RGBA8 ||
            p->slope->format != FORMAT_RGBA8 || p->wc->format != FORMAT_RGBA8) {
            rc = swell_fail(err, SWELL_E_FORMAT, "grid: pattern %d lacks rgba8 disp/slope/whitecap "
                            "tables; re-bake the tables for the gles2-min format", i);
            goto fail;
        }
        if (p->disp->width < DETILE_OFFSETS || p->disp->height < DETILE_OFFSETS) {
            /* the taps' offsets are whole texels from 8 up (detile.h); swell-bake makes 8+ */
            rc = swell_fail(err, SWELL_E_FORMAT, "grid: pattern %d's displacement table is %d x "
                            "%d texels; the lattice's offsets need at least %d x %d: re-bake "
                            "(size_geo >= %d)", i, p->disp->width, p->disp->height,
                            DETILE_OFFSETS, DETILE_OFFSETS, DETILE_OFFSETS);
            goto fail;
        }
        p->inv_l = 1.0 / (pi->size_m > 0.0f ? pi->size_m : 1.0f);
        /* One wavelength stands for the pattern's band in eq. 2: the geometric mean of its
         * [k_min, k_max], else a quarter of the patch. */
        p->lambda_m = grid_band_wavelength(pi);
        {
            /* the largest |Dz| the table holds, over every frame */
            float top = 0.0f, side = 0.0f;
            for (size_t k = 0; k < table_bytes(p->disp); k += 4) {
                top = fmaxf(top, fabsf(quantize_decode(p->disp, 2, p->disp->data[k + 2])));
                side = fmaxf(side, fabsf(quantize_decode(p->disp, 0, p->disp->data[k])));
                side = fmaxf(side, fabsf(quantize_decode(p->disp, 1, p->disp->data[k + 1])));
            }
            /* read at three offsets blended (detile.h): at most sqrt(3) times a tap */
            float gain = g->detile ? DETILE_GAIN_MAX : 1.0f;
            g->crest_m += gain * top;
            g->chop_m += gain * side;
        }
        {
            /* the foam memory's mean: its top level's texels over the loop (detile.h blends
             * the deviation from it) */
            const struct swell_table *wc = p->wc;
            int top = wc->levels - 1;
            size_t n = (size_t)table_level_width(wc, top) * (size_t)table_level_height(wc, top);
            double sum = 0.0;
            for (int l = 0; l < wc->layers; l++)
                for (size_t k = 0; k < n; k++)
                    sum += quantize_decode(wc, 0, wc->data[table_offset(wc, top, l) + 4 * k]);
            p->k_mean = (float)(sum / ((double)n * wc->layers));
        }
        p->cpu = (d->cpu_patterns >> i) & 1u;
        if (p->cpu) {
            if (p->slope->levels > 16 || p->wc->levels > 16 ||
                p->slope->width != p->wc->width || p->slope->levels != p->wc->levels ||
                p->slope->width != p->slope->height) {
                rc = swell_fail(err, SWELL_E_FORMAT, "grid: pattern %d slope/whitecap tables "
                                "differ in size, are not square or have over 16 levels", i);
                goto fail;
            }
            p->levels = p->slope->levels;
        }
        p->kcpu = !p->cpu && ((d->k_patterns >> i) & 1u);
        if (p->kcpu) {
            if (p->wc->levels > 16 || p->wc->width != p->wc->height) {
                rc = swell_fail(err, SWELL_E_FORMAT, "grid: pattern %d's whitecap table is not "
                                "square or has over 16 levels", i);
                goto fail;
            }
            p->levels = p->wc->levels;
            p->k_flat = k_flat_level(p->wc);
            p->k_w0 = table_level_within_var(p->wc, 0, 0, 1);
        }
        if ((rc = pattern_images(p, i, err)))
            goto fail;
    }
    *out = g;
    return 0;
fail:
    grid_destroy(g);
    return rc;
}

/* Byte and 16-bit lanes widened by interleaving with zeros (punpckl/h on SSE2, zip on NEON):
 * the zero goes in the high half of each wider lane, whose place depends on the byte order. */
#if __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
#define ZIP8_LO(v, z) __builtin_shufflevector(z, v, 0, 16, 1, 17, 2, 18, 3, 19, 4, 20, 5, 21, 6, 22, 7, 23)
#define ZIP8_HI(v, z) __builtin_shufflevector(z, v, 8, 24, 9, 25, 10, 26, 11, 27, 12, 28, 13, 29, 14, 30, 15, 31)
#define ZIP16_LO(v, z) __builtin_shufflevector(z, v, 0, 8, 1, 9, 2, 10, 3, 11)
#define ZIP16_HI(v, z) __builtin_shufflevector(z, v, 4, 12, 5, 13, 6, 14, 7, 15)
#else
#define ZIP8_LO(v, z) __builtin_shufflevector(v, z, 0, 16, 1, 17, 2, 18, 3, 19, 4, 20, 5, 21, 6, 22, 7, 23)
#define ZIP8_HI(v, z) __builtin_shufflevector(v, z, 8, 24, 9, 25, 10, 26, 11, 27, 12, 28, 13, 29, 14, 30, 15, 31)
#define ZIP16_LO(v, z) __builtin_shufflevector(v, z, 0, 8, 1, 9, 2, 10, 3, 11)
#define ZIP16_HI(v, z) __builtin_shufflevector(v, z, 4, 12, 5, 13, 6, 14, 7, 15)
#endif

/* 4 RGBA8 texels of loop frames f0 (a) and f1 (b) blended in 16 bits (a w0 + b w1 + rnd <=
 * 255 * 256 + 128), shifted and dequantised to floats (sc, bi: one texel's four channels), in
 * vectors: -O2's vectoriser left the 16-bit array of a plain loop on the stack. rnd and shift are
 * constants where it is inlined (a variable shift costs twice the instructions). */
static inline void blend_block(float *restrict out, const uint8_t *restrict a,
                               const uint8_t *restrict b, f4 sc, f4 bi, uint16_t w0,
                               uint16_t w1, const uint16_t rnd, const int shift)
{
    const u8x16 z = { 0 };
    const u16x8 zw = { 0 };
    u8x16 va, vb;
    memcpy(&va, a, sizeof(va));
    memcpy(&vb, b, sizeof(vb));
    u16x8 lo = (u16x8)ZIP8_LO(va, z) * w0 + (u16x8)ZIP8_LO(vb, z) * w1;
    u16x8 hi = (u16x8)ZIP8_HI(va, z) * w0 + (u16x8)ZIP8_HI(vb, z) * w1;
    lo = (u16x8)(lo + rnd) >> shift;
    hi = (u16x8)(hi + rnd) >> shift;
    f4 t[4] = { bi + sc * __builtin_convertvector((i32x4)ZIP16_LO(lo, zw), f4),
                bi + sc * __builtin_convertvector((i32x4)ZIP16_HI(lo, zw), f4),
                bi + sc * __builtin_convertvector((i32x4)ZIP16_LO(hi, zw), f4),
                bi + sc * __builtin_convertvector((i32x4)ZIP16_HI(hi, zw), f4) };
    memcpy(out, t, sizeof(t));
}

/* n bytes (a multiple of BLEND_BLOCK) of a row from ra / rb. */
static inline void blend_span(float *restrict o, const uint8_t *restrict ra,
                              const uint8_t *restrict rb, size_t n, f4 sc, f4 bi, uint16_t w0,
                              uint16_t w1, const uint16_t rnd, const int shift)
{
    for (size_t k = 0; k < n; k += BLEND_BLOCK)
        blend_block(o + k, ra + k, rb + k, sc, bi, w0, w1, rnd, shift);
}

/* One texel from ea / eb. */
static inline void blend_texel(float *restrict o, const uint8_t *restrict ea,
                               const uint8_t *restrict eb, f4 sc, f4 bi, uint16_t w0,
                               uint16_t w1, const uint16_t rnd, const int shift)
{
    f4 v;
    for (int c = 0; c < 4; c++)
        v[c] = (float)((uint16_t)(ea[c] * w0 + eb[c] * w1 + rnd) >> shift);
    v = bi + sc * v;
    memcpy(o, &v, sizeof(v));
}

/* One row of a tile: n bytes (a multiple of BLEND_BLOCK) from ra / rb, then the texel after
 * them from ea / eb (the next column, or column 0 where the row wraps). */
static inline void blend_row(float *restrict o, const uint8_t *restrict ra,
                             const uint8_t *restrict rb, const uint8_t *restrict ea,
                             const uint8_t *restrict eb, size_t n, f4 sc, f4 bi, uint16_t w0,
                             uint16_t w1, const uint16_t rnd, const int shift)
{
    blend_span(o, ra, rb, n, sc, bi, w0, w1, rnd, shift);
    blend_texel(o + n, ea, eb, sc, bi, w0, w1, rnd, shift);
}

/* Blend tile (tx, ty) of im for its phase: texels [x0, x0 + TILE] x [y0, y0 + TILE] clipped to
 * the padded image, the last column and row being the next tile's first (or the wrap copy). */
static void blend_tile(struct f4_image *im, int tx, int ty)
{
    const struct swell_table *t = im->t;
    const struct stream_phase *ph = &im->ph;
    int f0 = ph->f0 < t->layers ? ph->f0 : 0, f1 = ph->f1 < t->layers ? ph->f1 : 0;
    uint16_t w1 = (uint16_t)ph->w, w0 = (uint16_t)(STREAM_W_ONE - w1);
    int x0 = tx << TILE_LOG2, y0 = ty << TILE_LOG2;
    int x1 = x0 + (1 << TILE_LOG2) < im->w ? x0 + (1 << TILE_LOG2) : im->w;
    int y1 = y0 + (1 << TILE_LOG2) < im->h ? y0 + (1 << TILE_LOG2) : im->h;
    size_t row = 4 * (size_t)im->w, stride = 4 * (size_t)(im->w + 1);
    size_t span = 4 * (size_t)(x1 - x0);
    size_t last = 4 * (size_t)(x1 & (im->w - 1));   /* source of the column after the span */
    const uint8_t *a = im->t->data + table_offset(t, im->level, f0);
    const uint8_t *b = im->t->data + table_offset(t, im->level, f1);
    const f4 sc = ld4(im->sc), bi = ld4(im->bi);
    if (span % BLEND_BLOCK) {
        /* images narrower than a block: one texel at a time */
        for (int y = y0; y <= y1; y++) {
            size_t src = (size_t)(y & (im->h - 1)) * row;
            float *o = im->data + (size_t)y * stride + 4 * (size_t)x0;
            for (size_t k = 0; k <= span; k += 4)
                blend_row(o + k, NULL, NULL, a + src + (k < span ? 4 * (size_t)x0 + k : last),
                          b + src + (k < span ? 4 * (size_t)x0 + k : last), 0, sc, bi, w0, w1,
                          im->rnd, im->shift);
        }
    } else {
        for (int y = y0; y <= y1; y++) {
            size_t src = (size_t)(y & (im->h - 1)) * row;
            const uint8_t *ra = a + src + 4 * (size_t)x0, *rb = b + src + 4 * (size_t)x0;
            float *o = im->data + (size_t)y * stride + 4 * (size_t)x0;
            if (im->shift)
                blend_row(o, ra, rb, a + src + last, b + src + last, span, sc, bi, w0, w1,
                          STREAM_W_ONE / 2, 8);
            else
                blend_row(o, ra, rb, a + src + last, b + src + last, span, sc, bi, w0, w1, 0, 0);
        }
    }
    im->stamp[ty * im->tiles_x + tx] = im->gen;
}

/* Padded indices [r[0], r[1]) (and [r[2], r[3])) holding the bilinear footprints whose first
 * index runs over m from s, circularly in [0, n): index n is the copy of 0. Returns 1 or 2. */
static int pad_ranges(int s, int m, int n, int r[4])
{
    if (m >= n) {
        r[0] = 0;
        r[1] = n + 1;
        return 1;
    }
    if (s + m <= n) {
        r[0] = s;
        r[1] = s + m + 1;
        return 1;
    }
    r[0] = s;
    r[1] = n + 1;
    r[2] = 0;
    r[3] = s + m - n + 1;
    return 2;
}

/* Whether the displacement image im holds, for its phase, every footprint whose first texel is
 * in mx columns from sx and my rows from sy (circularly). */
static int box_blended(const struct f4_image *im, int sx, int mx, int sy, int my)
{
    if (im->box_gen != im->gen)
        return 0;
    return (im->box[1] >= im->w || ((sx - im->box[0]) & (im->w - 1)) + mx <= im->box[1]) &&
           (im->box[3] >= im->h || ((sy - im->box[2]) & (im->h - 1)) + my <= im->box[3]);
}

/* Blend, for its phase, the texels of the displacement image im that the bilinear footprints
 * with first texels in mx columns from sx and my rows from sy (circularly) read: rows by
 * vector spans of whole blocks, plus the padded column from column 0. Images narrower than a
 * block are blended whole by tiles. */
static void blend_box(struct f4_image *im, int sx, int mx, int sy, int my)
{
    const struct swell_table *t = im->t;
    const struct stream_phase *ph = &im->ph;
    int f0 = ph->f0 < t->layers ? ph->f0 : 0, f1 = ph->f1 < t->layers ? ph->f1 : 0;
    uint16_t w1 = (uint16_t)ph->w, w0 = (uint16_t)(STREAM_W_ONE - w1);
    size_t row = 4 * (size_t)im->w, stride = 4 * (size_t)(im->w + 1);
    const uint8_t *a = t->data + table_offset(t, im->level, f0);
    const uint8_t *b = t->data + table_offset(t, im->level, f1);
    const f4 sc = ld4(im->sc), bi = ld4(im->bi);
    int xr[4], yr[4], nxr, nyr;
    if (row % BLEND_BLOCK) {
        int ntiles = im->tiles_x * tiles_of(im->h);
        for (int k = 0; k < ntiles; k++)
            if (im->stamp[k] != im->gen)
                blend_tile(im, k % im->tiles_x, k / im->tiles_x);
        sx = sy = 0;
        mx = im->w;
        my = im->h;
    } else {
        nxr = pad_ranges(sx, mx, im->w, xr);
        nyr = pad_ranges(sy, my, im->h, yr);
        for (int j = 0; j < 2 * nyr; j += 2)
            for (int y = yr[j]; y < yr[j + 1]; y++) {
                const uint8_t *ra = a + (size_t)(y & (im->h - 1)) * row;
                const uint8_t *rb = b + (size_t)(y & (im->h - 1)) * row;
                float *o = im->data + (size_t)y * stride;
                for (int i = 0; i < 2 * nxr; i += 2) {
                    /* whole blocks of columns up to the last real one, then the padded one */
                    int c0 = xr[i] & ~3, c1 = xr[i + 1] < im->w ? (xr[i + 1] + 3) & ~3 : im->w;
                    size_t k0 = 4 * (size_t)c0, n = 4 * (size_t)(c1 - c0);
                    if (im->shift)
                        blend_span(o + k0, ra + k0, rb + k0, n, sc, bi, w0, w1, STREAM_W_ONE / 2, 8);
                    else
                        blend_span(o + k0, ra + k0, rb + k0, n, sc, bi, w0, w1, 0, 0);
                    if (xr[i + 1] > im->w)
                        blend_texel(o + row, ra, rb, sc, bi, w0, w1, im->rnd, im->shift);
                }
            }
    }
    im->box[0] = sx;
    im->box[1] = mx;
    im->box[2] = sy;
    im->box[3] = my;
    im->box_gen = im->gen;
}

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

/* Lane-wise max(a, b) by a compare and a bitwise select (no intrinsics; NaN in a gives b). */
static inline f4 max4(f4 a, f4 b)
{
    i32x4 gt = a > b, ia, ib;
    memcpy(&ia, &a, sizeof(ia));
    memcpy(&ib, &b, sizeof(ib));
    ia = (ia & gt) | (ib & ~gt);
    memcpy(&a, &ia, sizeof(a));
    return a;
}

static inline float maxf(float a, float b) { return a > b ? a : b; }
static inline float minf(float a, float b) { return a < b ? a : b; }
static inline float clamp01(float a) { return a < 0.0f ? 0.0f : (a > 1.0f ? 1.0f : a); }

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

int grid_mip_level(float r, int levels)
{
    return mip_level(r, levels - 1);
}

/* Each block's smallest footprint: eq. 2's weight falls with the footprint, so a pattern whose
 * weight is 0 there has weight 0 for the whole block. n is a multiple of VBLK. */
static void block_foot(int n, const float *restrict foot, float *restrict out)
{
    for (int b = 0; b < n; b += VBLK) {
        float m[VBLK / 2];
        for (int e = 0; e < VBLK / 2; e++)
            m[e] = foot[b + e + VBLK / 2] < foot[b + e] ? foot[b + e + VBLK / 2] : foot[b + e];
        for (int e = 1; e < VBLK / 2; e++)
            m[0] = m[e] < m[0] ? m[e] : m[0];
        out[b / VBLK] = m[0];
    }
}

/* For the vertices of the nr runs [run[2r], run[2r + 1]) (whole blocks): the weights of
 * Bruneton eq. 2 for each vertex's cell of size foot (times the fade), the texel coordinates
 * x = x0 + rest_x kx in float, floored (rest positions are camera-relative floats and x0 a
 * wrapped offset: float keeps what the inputs hold), and the first texels (oix, oiy) of the
 * bilinear footprints. By quads: a fixed loop of 4 over restrict-qualified arrays is what -O2's
 * vectorisers turn into straight vector code. */
static void disp_coords(const struct disp_frame *f, int nr, const int *restrict run,
                               const float *restrict rx, const float *restrict ry,
                               const float *restrict foot, const float *restrict fade,
                               const float *unit, float *restrict wv, float *restrict fx,
                               float *restrict fy, int *restrict oix, int *restrict oiy,
                               float ext[4])
{
    const float lambda_m = f->lambda_m, x0 = f->x0, y0 = f->y0, kx = f->kx, ky = f->ky;
    float xl[4], xh[4], yl[4], yh[4];
    const int wm = f->wm, hm = f->hm;
    /* bounds loaded, not constants: with constants GCC threads the clamps' branches (w is 0 or
     * 1 there) and can then no longer vectorise the loop, or selects by masks, not max/min */
    const float u_lo = unit[0], u_hi = unit[1], ft_lo = unit[2];
    const float c_lo = -f->coord_max, c_hi = f->coord_max;
    for (int e = 0; e < 4; e++) {
        xl[e] = yl[e] = c_hi;
        xh[e] = yh[e] = c_lo;
    }
    for (int r = 0; r < nr; r++)
        for (int q = run[2 * r]; q < run[2 * r + 1]; q += 4)
            for (int e = q; e < q + 4; e++) {
                float ft = foot[e];
                ft = ft > ft_lo ? ft : ft_lo;
                float u = (lambda_m / ft - FILTER_NMIN) * (1.0f / (FILTER_NMAX - FILTER_NMIN));
                u = u > u_lo ? u : u_lo;
                u = u < u_hi ? u : u_hi;
                wv[e] = fade[e] * (u * u * (3.0f - 2.0f * u));
                /* clamped so the conversion is defined (|x| < 2^30 texels: 2^6 texel per ulp) */
                float x = x0 + rx[e] * kx, y = y0 + ry[e] * ky;
                x = x > c_lo ? x : c_lo;
                x = x < c_hi ? x : c_hi;
                y = y > c_lo ? y : c_lo;
                y = y < c_hi ? y : c_hi;
                xl[e - q] = x < xl[e - q] ? x : xl[e - q];
                xh[e - q] = x > xh[e - q] ? x : xh[e - q];
                yl[e - q] = y < yl[e - q] ? y : yl[e - q];
                yh[e - q] = y > yh[e - q] ? y : yh[e - q];
                /* floor: truncation rounds negatives up, so one less where the fraction is
                 * negative (x - trunc x is exact; 1 + it rounds to within 2^-24 texel) */
                int ix = (int)x, iy = (int)y;
                float sx = x - (float)ix, sy = y - (float)iy;
                int nx = sx < 0.0f, ny = sy < 0.0f;
                fx[e] = sx + (float)nx;
                fy[e] = sy + (float)ny;
                oix[e] = (ix - nx) & wm;
                oiy[e] = (iy - ny) & hm;
            }
    ext[0] = ext[2] = c_hi;
    ext[1] = ext[3] = c_lo;
    for (int e = 0; e < 4; e++) {
        ext[0] = xl[e] < ext[0] ? xl[e] : ext[0];
        ext[1] = xh[e] > ext[1] ? xh[e] : ext[1];
        ext[2] = yl[e] < ext[2] ? yl[e] : ext[2];
        ext[3] = yh[e] > ext[3] ? yh[e] : ext[3];
    }
}

/* floor(x) for |x| <= COORD_MAX */
static inline int floor_int(float x)
{
    int i = (int)x;
    return i - (x < (float)i);
}

/* One tap's bilinear fetch: the tap's whole-texel offset (ox, oy) added to the footprint's
 * first texel (x, y). */
static inline f4 tap4(const char *restrict base, const char *restrict base_c, int x, int y,
                      int ox, int oy, int wm, int hm, int wshift, f4 vx, f4 vy)
{
    x = (x + ox) & wm;
    y = (y + oy) & hm;
    int off = 16 * ((y << wshift) + y + x);   /* bytes: 16 (y (w + 1) + x) */
    const float *a = (const float *)(base + off), *c = (const float *)(base_c + off);
    f4 a0 = ld4(a), a1 = ld4(a + 4), c0 = ld4(c), c1 = ld4(c + 4);
    f4 top = a0 + (a1 - a0) * vx, bot = c0 + (c1 - c0) * vx;
    return top + (bot - top) * vy;
}

/* The displacement of the vertices of the nr runs: each reads the pattern at its lattice
 * triangle's three random offsets (detile.h, as detile_taps_cell; the same bilinear fractions
 * for the three, the offsets being whole texels) and adds their blend times its eq. 2 weight
 * wv to acc, or stores it there for the first pattern. */
static void disp_fetch(const struct disp_frame *f, const uint8_t *restrict hash, int nr,
                       const int *restrict run, const float *restrict rx,
                       const float *restrict ry, const float *restrict wv,
                       const float *restrict fx, const float *restrict fy,
                       const int *restrict ix, const int *restrict iy, float *restrict acc,
                       const int first)
{
    const char *base = (const char *)f->data, *base_c = base + f->stride;
    const struct detile_frame *d = &f->dt;
    const int m = DETILE_N - 1, shx = d->shx, shy = d->shy;
    const int wm = f->wm, hm = f->hm, wshift = f->wshift;
    const f4 one = { 1.0f, 1.0f, 1.0f, 1.0f };
    /* each hash byte's offset in texels, (h >> 3, h & 7) eighths of the tile (tables are
     * POT and >= 8 texels, grid_create) */
    int ox[DETILE_OFFSETS * DETILE_OFFSETS], oy[DETILE_OFFSETS * DETILE_OFFSETS];
    for (int h = 0; h < DETILE_OFFSETS * DETILE_OFFSETS; h++) {
        ox[h] = (h / DETILE_OFFSETS) * ((wm + 1) / DETILE_OFFSETS);
        oy[h] = (h % DETILE_OFFSETS) * ((hm + 1) / DETILE_OFFSETS);
    }
    for (int r = 0; r < nr; r++)
        for (int e = run[2 * r]; e < run[2 * r + 1]; e += 4) {
            /* by quads (runs are whole blocks): the lattice cell, its hash indices and the
             * barycentric weights in vectors */
            f4 qx = d->q0x + ld4(rx + e) * d->qk, qy = d->q0y + ld4(ry + e) * d->qk;
            i32x4 cx = __builtin_convertvector(qx, i32x4), cy = __builtin_convertvector(qy, i32x4);
            cx += (i32x4)(qx < __builtin_convertvector(cx, f4));   /* floor: -1 where below */
            cy += (i32x4)(qy < __builtin_convertvector(cy, f4));
            f4 ux = qx - __builtin_convertvector(cx, f4), uy = qy - __builtin_convertvector(cy, f4);
            i32x4 hx = (cx + shx) & m, hy = (cy + shy) & m;
            i32x4 hx1 = (hx + 1) & m, hy1 = (hy + 1) & m, up = (i32x4)(uy > ux);
            i32x4 i0 = hy * DETILE_N + hx, i2 = hy1 * DETILE_N + hx1;
            i32x4 i1 = ((hy1 * DETILE_N + hx) & up) | ((hy * DETILE_N + hx1) & ~up);
            f4 hi = max4(ux, uy), lo = ux + uy - hi;
            f4 w0 = one - hi, w1 = hi - lo, w2 = lo, s2 = w0 * w0 + w1 * w1 + w2 * w2;
            f4 ww = ld4(wv + e);
            for (int k = 0; k < 4; k++) {
                int v = e + k;
                float n = ww[k] / sqrtf(s2[k]);
                const f4 vx = { fx[v], fx[v], fx[v], fx[v] }, vy = { fy[v], fy[v], fy[v], fy[v] };
                f4 sum = (w0[k] * n) * tap4(base, base_c, ix[v], iy[v], ox[hash[i0[k]]], oy[hash[i0[k]]],
                                            wm, hm, wshift, vx, vy) +
                         (w1[k] * n) * tap4(base, base_c, ix[v], iy[v], ox[hash[i1[k]]], oy[hash[i1[k]]],
                                            wm, hm, wshift, vx, vy) +
                         (w2[k] * n) * tap4(base, base_c, ix[v], iy[v], ox[hash[i2[k]]], oy[hash[i2[k]]],
                                            wm, hm, wshift, vx, vy);
                if (!first)
                    sum += ld4(acc + 4 * (size_t)v);
                memcpy(acc + 4 * (size_t)v, &sum, sizeof(sum));
            }
        }
}

/* disp_fetch without the lattice (grid_desc no_detile): one tap at no offset. */
static void disp_fetch_one(const struct disp_frame *f, int nr, const int *restrict run,
                           const float *restrict wv, const float *restrict fx,
                           const float *restrict fy, const int *restrict ix,
                           const int *restrict iy, float *restrict acc, const int first)
{
    const char *base = (const char *)f->data, *base_c = base + f->stride;
    const int wm = f->wm, hm = f->hm, wshift = f->wshift;
    for (int r = 0; r < nr; r++)
        for (int v = run[2 * r]; v < run[2 * r + 1]; v++) {
            const f4 vx = { fx[v], fx[v], fx[v], fx[v] }, vy = { fy[v], fy[v], fy[v], fy[v] };
            f4 sum = wv[v] * tap4(base, base_c, ix[v], iy[v], 0, 0, wm, hm, wshift, vx, vy);
            if (!first)
                sum += ld4(acc + 4 * (size_t)v);
            memcpy(acc + 4 * (size_t)v, &sum, sizeof(sum));
        }
}

/* Sum the displacement of the nd patterns at df, weighted by Bruneton eq. 2, into acc (a float4
 * per vertex), pattern by pattern over the runs of blocks of VBLK vertices whose smallest
 * footprint gives the pattern a weight > 0. The pattern with the longest wavelength goes first:
 * its blocks hold every other pattern's, so it stores and the others add. Returns the footprint
 * from which blocks were not displaced (write_vertices). */
static float displace(struct grid *g, struct disp_frame *df, int nd)
{
    const int nblk = g->npad / VBLK;
    int top = 0;
    block_foot(g->npad, g->foot, g->blk_foot);
    for (int i = 1; i < nd; i++)
        top = df[i].foot_zero > df[top].foot_zero ? i : top;
    for (int j = 0; j < nd; j++) {
        struct disp_frame *f = &df[j == 0 ? top : (j <= top ? j - 1 : j)];
        int nr = 0, in = 0;
        for (int k = 0; k < nblk; k++) {
            int on = g->blk_foot[k] < f->foot_zero;
            if (on != in)
                g->run[nr++] = k * VBLK;    /* a run starts or ends */
            in = on;
        }
        if (in)
            g->run[nr++] = nblk * VBLK;
        nr /= 2;
        float ext[4];
        if (nr == 0)
            continue;
        disp_coords(f, nr, g->run, g->rx, g->ry, g->foot, g->fade, g->unit, g->wv, g->fx, g->fy,
                    g->ix, g->iy, ext);
        {
            /* the image's texels under the footprints (first texels floor(x) from the smallest
             * to the largest x, then up to a tile further for the taps' offsets), blended
             * unless they already are for this phase */
            int on = f->dt.hash != NULL;
            int xl = floor_int(ext[0]), yl = floor_int(ext[2]);
            int mx = floor_int(ext[1]) - xl + 1 + (on ? f->wm : 0);
            int my = floor_int(ext[3]) - yl + 1 + (on ? f->hm : 0);
            xl &= f->wm;
            yl &= f->hm;
            if (!box_blended(f->im, xl, mx, yl, my))
                blend_box(f->im, xl, mx, yl, my);
        }
        if (!f->dt.hash)
            disp_fetch_one(f, nr, g->run, g->wv, g->fx, g->fy, g->ix, g->iy, g->acc, j == 0);
        else if (j == 0)
            disp_fetch(f, g->hash, nr, g->run, g->rx, g->ry, g->wv, g->fx, g->fy, g->ix, g->iy,
                       g->acc, 1);
        else
            disp_fetch(f, g->hash, nr, g->run, g->rx, g->ry, g->wv, g->fx, g->fy, g->ix, g->iy,
                       g->acc, 0);
    }
    return df[top].foot_zero;
}

/* The vertex attributes of n vertices from their rest positions and summed displacements d
 * (x, y, z, 0); the moments are 0 without CPU patterns. */
static inline void write_tail(float *restrict vx, int n, const float *restrict rx,
                              const float *restrict ry, const float *restrict d, float z, int cpu)
{
    for (int e = 0; e < n; e++, vx += GRID_FLOATS) {
        vx[GRID_A_POS + 0] = rx[e] + d[4 * e + 0];
        vx[GRID_A_POS + 1] = ry[e] + d[4 * e + 1];
        vx[GRID_A_POS + 2] = z - sphere_drop(rx[e] * rx[e] + ry[e] * ry[e]) + d[4 * e + 2];
        vx[GRID_A_REST] = rx[e];
        vx[GRID_A_REST + 1] = ry[e];
        if (!cpu)
            for (int c = GRID_A_SLOPE; c <= GRID_A_PAD; c++)
                vx[c] = 0.0f;
    }
}

/* One vertex from its position p (lane 3: the rest x) and rest y. */
static inline void write_one(float *restrict vx, f4 p, float y, const int cpu)
{
    memcpy(vx + GRID_A_POS, &p, sizeof(p));
    if (cpu) {
        vx[GRID_A_REST + 1] = y;
    } else {
        f4 r = { y, 0.0f, 0.0f, 0.0f }, zero = { 0.0f, 0.0f, 0.0f, 0.0f };
        memcpy(vx + GRID_A_REST + 1, &r, sizeof(r));
        memcpy(vx + GRID_A_REST + 5, &zero, sizeof(zero));
    }
}

/* write_tail for 4 vertices by vectors: the rest positions transposed to (x, y, z, x) per
 * vertex (lane 3 of d is 0), unrolled by hand (GCC -O2 keeps a loop over them). */
static inline void write_quad(float *restrict vx, const float *restrict rx,
                              const float *restrict ry, const float *restrict d, f4 zz,
                              const int cpu)
{
    f4 x = ld4(rx), y = ld4(ry);
    f4 r2 = x * x + y * y;
    for (int e = 0; e < 4; e++)
        zz[e] -= sphere_drop(r2[e]);   /* the sea's drop on a sphere (camera.h) */
    f4 xy_lo = __builtin_shufflevector(x, y, 0, 4, 1, 5), xy_hi = __builtin_shufflevector(x, y, 2, 6, 3, 7);
    f4 zx_lo = __builtin_shufflevector(zz, x, 0, 4, 1, 5), zx_hi = __builtin_shufflevector(zz, x, 2, 6, 3, 7);
    write_one(vx, __builtin_shufflevector(xy_lo, zx_lo, 0, 1, 4, 5) + ld4(d), y[0], cpu);
    write_one(vx + GRID_FLOATS, __builtin_shufflevector(xy_lo, zx_lo, 2, 3, 6, 7) + ld4(d + 4),
              y[1], cpu);
    write_one(vx + 2 * GRID_FLOATS, __builtin_shufflevector(xy_hi, zx_hi, 0, 1, 4, 5) + ld4(d + 8),
              y[2], cpu);
    write_one(vx + 3 * GRID_FLOATS, __builtin_shufflevector(xy_hi, zx_hi, 2, 3, 6, 7) + ld4(d + 12),
              y[3], cpu);
}

/* The vertices: d is acc for the blocks displace() reached (smallest footprint under
 * foot_disp), else zeros; cpu constant where write_quad is inlined. */
static void write_vertices(const struct grid *g, float *verts, float z, int cpu, float foot_disp)
{
    _Static_assert(VBLK == 8, "write_vertices writes a block as two quads");
    static const float none[4 * VBLK];
    const f4 zz = { z, z, z, z };
    int b = 0;
    for (; b + VBLK <= g->nverts; b += VBLK) {
        const float *d = g->blk_foot[b / VBLK] < foot_disp ? g->acc + 4 * (size_t)b : none;
        float *vx = verts + (size_t)b * GRID_FLOATS;
        if (cpu) {
            write_quad(vx, g->rx + b, g->ry + b, d, zz, 1);
            write_quad(vx + 4 * GRID_FLOATS, g->rx + b + 4, g->ry + b + 4, d + 16, zz, 1);
        } else {
            write_quad(vx, g->rx + b, g->ry + b, d, zz, 0);
            write_quad(vx + 4 * GRID_FLOATS, g->rx + b + 4, g->ry + b + 4, d + 16, zz, 0);
        }
    }
    if (b < g->nverts)
        write_tail(verts + (size_t)b * GRID_FLOATS, g->nverts - b, g->rx + b, g->ry + b,
                   g->blk_foot[b / VBLK] < foot_disp ? g->acc + 4 * (size_t)b : none, z, cpu);
}

/* Vertex k's mip level of pattern frame f (its footprint's), its texel coordinates there, the
 * level's width lw (the lattice's offsets are in its texels) and its lattice taps (detile.h).
 * A CPU pattern's slope and whitecap levels are the same size (grid_create). */
static inline int vertex_level(const struct grid *g, const struct pattern_frame *f, int k,
                               double *x, double *y, double *lw, struct detile_taps *t)
{
    int lev = mip_level(g->foot[k] * f->lev_k, f->p->levels - 1);
    *lw = f->p->wc_f[lev].w;
    *x = f->mx0[lev] + g->rx[k] * f->mk[lev];
    *y = f->my0[lev] + g->ry[k] * f->mk[lev];
    detile_at(&f->dt, g->rx[k], g->ry[k], t);
    return lev;
}

/* Add CPU pattern f's slope and whitecap moments to every vertex: from the mip level whose
 * texel matches the vertex footprint, the mip texel then holding the footprint's first and
 * second moments (Bruneton §4.1, Dupuy eq. 7-8; of the foam memory m_i, bake.c). */
static void moment_pass(const struct grid *g, struct pattern_frame *f, float *verts)
{
    struct grid_pattern *p = f->p;
    /* lanes 0, 1: the mean slope; 2, 3: the resolved variance <s^2> - <s>^2 (floored at 0) */
    const f4 var_lanes = { 0.0f, 0.0f, 1.0f, 1.0f };
    const f4 var_floor = { -INFINITY, -INFINITY, 0.0f, 0.0f };
    _Static_assert(GRID_A_SVAR == GRID_A_SLOPE + 2, "slope mean and variance are one vector");
    for (int k = 0; k < g->nverts; k++) {
        float *vx = verts + (size_t)k * GRID_FLOATS;
        double x, y, lw;
        struct detile_taps t;
        int lev = vertex_level(g, f, k, &x, &y, &lw, &t);
        /* three taps blended (detile.h): means by w_j, variances by w_j^2, the foam memory's
         * deviation from its mean */
        f4 acc = ld4(vx + GRID_A_SLOPE);
        float km = p->k_mean;
        for (int j = 0; j < (f->dt.hash ? 3 : 1); j++) {
            f4 m, q;
            float w = t.w[j];
            f4 wl = { w, w, w * w, w * w };
            sample_f4x2(&p->slope_f[lev], &p->wc_f[lev], x + t.du[j] * lw, y + t.dv[j] * lw,
                        &m, &q);
            f4 mm = __builtin_shufflevector(m, m, 0, 1, 0, 1);
            acc += wl * max4(m - mm * mm * var_lanes, var_floor);
            km += w * (q[0] - p->k_mean);
            vx[GRID_A_K + 1] += w * w * maxf(q[1] - q[0] * q[0], 0.0f);
        }
        memcpy(vx + GRID_A_SLOPE, &acc, sizeof(acc));
        vx[GRID_A_K] += km;
    }
}

/* The foam memory's mean and within-texel variance <m^2> - <m>^2 (floored at 0) of k-only
 * pattern p at texel coordinates (x, y) of level lev; from its flat level up the top texel's,
 * flat (unless NULL: sampled). */
static inline void k_texel(struct grid_pattern *p, int lev, double x, double y,
                           const float flat[2], float out[2])
{
    if (flat && lev >= p->k_flat) {
        out[0] = flat[0];
        out[1] = flat[1];
        return;
    }
    struct texel_at a;
    texel_locate(&p->wc_f[lev], x, y, &a);
    f4 q = texel_sample(&p->wc_f[lev], &a);
    out[0] = q[0];
    out[1] = maxf(q[1] - q[0] * q[0], 0.0f);
}

/* A vertex's within-footprint variance of k-only pattern p's foam memory where level 0 is
 * magnified (footprint r texels, r < 1) from the fetched <m^2> - <m>^2, v: there v is the
 * bilinear mix of neighbouring texels' moments, not variance within the footprint (it draws
 * the texel grid). As high quality's pixels take it (ocean.frag add_whitecap: B = 0 there, level
 * 0's mean W0 instead, part of it as blur and the rest as detail of the same expected
 * coverage), W0 in its place, from r = 1/2 down; v from r = 1, linear in r between. Taking
 * v to 0 instead (W0 unused) matched high's rows as well but drew the vertices' triangles as
 * a staircase along the foam's edges (storm from 5 m). Not where level 0 is already the flat
 * level (the patch's top texel, k_texel). */
static inline float magnified_var(const struct grid_pattern *p, float r, float v)
{
    float s = 2.0f * r - 1.0f;
    s = s < 0.0f ? 0.0f : s > 1.0f ? 1.0f : s;
    return p->k_w0 + (v - p->k_w0) * s;
}

/* Add pattern f's whitecap moments alone to every vertex (grid.h k_patterns: low quality's
 * fragment-shader patterns, whose whitecaps no fragment shader fetches), as moment_pass does
 * for a CPU pattern, at the mip level of the vertex's footprint: Dupuy's eq. 6 then sees the
 * foam memory's first and second moments there, as high quality's fragment shader does per
 * pixel, where the patch's constants alone gave every vertex the same coverage. From
 * k_flat up it takes the top texel, unsampled. Its cost (callgrind, rough tables, gles2-min,
 * no lattice, grid_update + stream_blend a frame): surface 1.45 -> 2.54 M, 1 km 1.01 ->
 * 1.81 M, 10 km 0.81 -> 1.24 M, most of it the bilinear samples and their tiles' blends.
 * One level, as moment_pass: two blended by the footprint took 3.18 M (2.47 M with one) and
 * changed no row-to-row brightness step (storm from 5 m: the largest 8.0 % vs 8.4 %, the
 * foam's own patches). */
static void k_moment_pass(const struct grid *g, struct pattern_frame *f, float *verts)
{
    struct grid_pattern *p = f->p;
    const int top = p->levels - 1;
    /* from k_flat up the top texel (one texel: one tap at no offset reads it anywhere; its
     * level follows the loop phase, grid_update) */
    float q_top[2];
    k_texel(p, top, 0.0, 0.0, NULL, q_top);
    if (!f->dt.hash) {
        /* without the lattice (low quality's default) one tap of weight 1, no taps to build:
         * grid_update 2.47 -> 2.01 M instructions a frame at 15 m/s from 10 m */
        for (int k = 0; k < g->nverts; k++) {
            float *vx = verts + (size_t)k * GRID_FLOATS;
            int lev = mip_level(g->foot[k] * f->lev_k, top);
            float q[2];
            k_texel(p, lev, f->mx0[lev] + g->rx[k] * f->mk[lev],
                    f->my0[lev] + g->ry[k] * f->mk[lev], q_top, q);
            vx[GRID_A_K] += q[0];
            vx[GRID_A_K + 1] += lev || p->k_flat == 0 ? q[1]
                                                      : magnified_var(p, g->foot[k] * f->lev_k, q[1]);
        }
        return;
    }
    for (int k = 0; k < g->nverts; k++) {
        float *vx = verts + (size_t)k * GRID_FLOATS;
        double x, y, lw;
        struct detile_taps t;
        int lev = vertex_level(g, f, k, &x, &y, &lw, &t);
        /* the foam memory's deviation from its mean by w_j, its within-texel variance by w_j^2 */
        float km = p->k_mean, kv = 0.0f;
        for (int j = 0; j < 3; j++) {
            float w = t.w[j], q[2];
            k_texel(p, lev, x + t.du[j] * lw, y + t.dv[j] * lw, q_top, q);
            km += w * (q[0] - p->k_mean);
            kv += w * w * q[1];
        }
        vx[GRID_A_K] += km;
        /* (the taps' weights: sum w_j^2 = 1, detile.h) */
        vx[GRID_A_K + 1] += lev || p->k_flat == 0 ? kv
                                                  : magnified_var(p, g->foot[k] * f->lev_k, kv);
    }
}

int grid_k_flat_level(const struct swell_table *wc)
{
    return k_flat_level(wc);
}

/* How far the grid reaches: the farthest crest the camera can see over a sphere, its own
 * horizon sqrt(2 R h + h^2) plus a crest's, sqrt(2 R crest) (within the far plane). */
static float far_distance(const struct grid *g, const struct camera *cam)
{
    float n, f;
    double h = fmax(cam->pos[2] - cam->surface_z_m, CAMERA_CLEARANCE_M) + fmax(cam->surface_z_m, 0.0);
    camera_clip_planes(cam, &n, &f);
    double d = sqrt(2.0 * EARTH_RADIUS_M * h + h * h) + sqrt(2.0 * EARTH_RADIUS_M * g->crest_m);
    return (float)fmin(0.9 * f, 1.02 * d);
}

/* Camera basis for heading h and pitch p (degrees): forward, right (horizontal), up. */
static void basis_hp(double h_deg, double p_deg, double fwd[3], double right[3], double up[3])
{
    double h = h_deg * M_PI / 180.0, p = p_deg * M_PI / 180.0;
    fwd[0] = cos(p) * cos(h); fwd[1] = cos(p) * sin(h); fwd[2] = sin(p);
    right[0] = sin(h); right[1] = -cos(h); right[2] = 0.0;
    up[0] = right[1] * fwd[2] - right[2] * fwd[1];
    up[1] = right[2] * fwd[0] - right[0] * fwd[2];
    up[2] = right[0] * fwd[1] - right[1] * fwd[0];
}

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

#define HULL_MAX 128          /* 32 polytope vertices x 4 corners of the choppy dilation */
#define PROJ_COS_MIN 0.15     /* projector rays stay within 81 degrees of its axis... */
#define PROJ_STEP_DEG 2.0     /* ...lowering its pitch by this step until they do */
#define SCREEN_SHARE 0.8      /* of the grid's rows and columns, on the camera's screen */

/* Sea-plane points (camera-relative x, y) that bound every rest position whose displaced
 * image can lie in the camera's frustum: the frustum (near plane to dmax along the view) cut
 * by the slab z in [zlo, zhi] that displacement can reach has as vertices its corners inside
 * the slab and its 12 edges' crossings of the two planes; their horizontal shadow, widened by
 * the largest sideways displacement (a square of half-side chop), is convex, so the convex hull
 * of these points contains it. Returns the number of points. */
static int frustum_slab_points(const double fwd[3], const double right[3], const double up[3],
                               double tx, double ty, double n, double f, double zlo, double zhi,
                               double chop, double q[HULL_MAX][2])
{
    double c[8][3];
    static const int edge[12][2] = { { 0, 1 }, { 1, 3 }, { 3, 2 }, { 2, 0 }, { 4, 5 }, { 5, 7 },
                                     { 7, 6 }, { 6, 4 }, { 0, 4 }, { 1, 5 }, { 2, 6 }, { 3, 7 } };
    double pts[32][2];
    int np = 0, nq = 0;
    for (int k = 0; k < 8; k++) {
        double a = k & 1 ? 1.0 : -1.0, b = k & 2 ? 1.0 : -1.0, d = k & 4 ? f : n;
        for (int e = 0; e < 3; e++)
            c[k][e] = d * (fwd[e] + a * tx * right[e] + b * ty * up[e]);
        if (c[k][2] >= zlo && c[k][2] <= zhi) {
            pts[np][0] = c[k][0];
            pts[np++][1] = c[k][1];
        }
    }
    for (int k = 0; k < 12; k++) {
        const double *a = c[edge[k][0]], *b = c[edge[k][1]];
        for (int s = 0; s < 2; s++) {
            double z = s ? zhi : zlo, da = a[2] - z, db = b[2] - z;
            if ((da < 0.0) != (db < 0.0)) {
                double u = da / (da - db);
                pts[np][0] = a[0] + u * (b[0] - a[0]);
                pts[np++][1] = a[1] + u * (b[1] - a[1]);
            }
        }
    }
    for (int k = 0; k < np; k++)
        for (int s = 0; s < 4; s++) {
            q[nq][0] = pts[k][0] + (s & 1 ? chop : -chop);
            q[nq++][1] = pts[k][1] + (s & 2 ? chop : -chop);
        }
    return nq;
}

/* The sea-plane row seen from the projector at angle theta above its axis, at forward
 * distance s = alt_ray / tan(dp) (dp = -(pitch + theta), its depression), is seen by the
 * camera at depression atan2(row_h, s); and back. Both work past the nadir (dp > 90 deg). */
static double cam_depression(const struct grid_projection *p, double theta)
{
    double dp = -(p->pitch + theta);
    return atan2(p->row_h * sin(dp), p->alt_ray * cos(dp));
}

/* The horizon rows of grid.h: the top row no farther than dmax (rays between the projector's
 * horizon and there all end at dmax), and from it the distance row_h / tan dc halving per row
 * (dc doubling: small angles) until that spacing reaches the even one's, x' = row_a; so
 * row_a delta / ln 2 = dc0 2^(u* / delta), and x(1) = the even rows' span fixes row_a (a few
 * fixed-point steps; the even rows then lie 0.5-10 % farther apart: 10 % at 0.3 m up, 6 % at
 * 8 m, 0.5 % at 1 km). None where the top row's dc already exceeds one even row / ln 2 (views from high
 * up or looking down), and it comes in continuously (u* from 0) as the camera lowers. */
static void horizon_rows(struct grid_projection *p, int h)
{
    double dc_far = atan(p->row_h / fmax(p->dmax, 1.0));
    if (p->row_cam[0] < dc_far && p->row_cam[1] > dc_far)
        p->row_cam[0] = dc_far;
    double dc0 = p->row_cam[0], span = p->row_cam[1] - dc0;
    double delta = 1.0 / fmax((h - 1) * p->row_split, 1.0), a = span, us = 0.0;
    for (int it = 0; it < 12 && dc0 > 0.0; it++) {
        double r = a * delta / (dc0 * M_LN2);
        us = r > 1.0 ? fmin(delta * log2(r), 0.5) : 0.0;
        a = (span - dc0 * (exp2(us / delta) - 1.0)) / (1.0 - us);
    }
    p->row_inv_delta = 1.0 / delta;
    p->row_ustar = us;
    p->row_a = a;
    p->row_xs = dc0 * (exp2(us / delta) - 1.0);
}

/* The projected grid's frame for a camera (grid.h); 0 when no sea is in view.
 *
 * Coverage by construction: the grid spans, in the projector's NDC, the bounding box of the
 * points frustum_slab_points finds; the projective map from the sea plane to that NDC keeps
 * convex sets convex where every point is in front of the projector, so the box holds every
 * rest position a visible surface point can come from, and the displaced grid's border lies
 * outside the frustum. A ray from the camera (kept CAMERA_CLEARANCE_M above the local surface
 * by the renderer) that goes below the slab within the frustum must then cross the displaced
 * grid. The projector is the camera where that is possible (views from above every crest: the
 * grid's rows follow the screen's), else raised above the crests and pitched down until the
 * points near and behind the camera are in front of it. */
static int projection_frame(const struct grid *g, const struct camera *cam, float aspect,
                            struct grid_projection *p)
{
    double fov = (cam->fov_y_deg > 0.0f ? cam->fov_y_deg : 45.0f) * M_PI / 180.0;
    double cf[3], cr[3], cu[3], q[HULL_MAX][2];
    float near_m, far_m;
    memset(p, 0, sizeof(*p));
    camera_clip_planes(cam, &near_m, &far_m);
    double ty = tan(0.5 * fov), tx = ty * aspect;
    p->alt = cam->pos[2];
    p->dmax = far_distance(g, cam);
    basis_hp(cam->heading_deg, cam->pitch_deg, cf, cr, cu);
    /* The sea lies on a sphere: at distance r it is r^2 / (2 R) lower, so the slab's floor is
     * lowered by the drop at the farthest point the region reaches (twice: from the flat
     * slab's reach, then from the lowered one's; at most dmax's). */
    double reach = 0.0;
    int nq = 0;
    for (int pass = 0; pass < 3; pass++) {
        double r = fmin(reach, p->dmax);
        nq = frustum_slab_points(cf, cr, cu, tx, ty, near_m, far_m,
                                 -p->alt - g->crest_m - sphere_drop((float)(r * r)),
                                 -p->alt + g->crest_m, g->chop_m, q);
        for (int k = 0; k < nq; k++)
            reach = fmax(reach, sqrt(q[k][0] * q[k][0] + q[k][1] * q[k][1]));
    }
    if (nq == 0)
        return 0;
    p->alt_ray = fmax(p->alt, fmax(g->crest_m + g->chop_m, 1.0));
    /* the projector's pitch: the camera's (at most level), lowered until every point that is
     * not well ahead (q . heading < half its distance) is within acos(PROJ_COS_MIN) of its axis;
     * points well ahead are in front of any projector pitched down */
    double hx = cos(cam->heading_deg * M_PI / 180.0), hy = sin(cam->heading_deg * M_PI / 180.0);
    double pitch = fmin(cam->pitch_deg, -1.0);
    for (;; pitch -= PROJ_STEP_DEG) {
        if (pitch < -89.0)
            pitch = -89.0;
        basis_hp(cam->heading_deg, pitch, p->fwd, p->right, p->up);
        int ok = 1;
        for (int k = 0; k < nq && ok; k++) {
            double d[3] = { q[k][0], q[k][1], -p->alt_ray };
            double dist = sqrt(q[k][0] * q[k][0] + q[k][1] * q[k][1]);
            if (q[k][0] * hx + q[k][1] * hy >= 0.5 * dist)
                continue;
            ok = dot3(d, p->fwd) >= PROJ_COS_MIN * sqrt(dot3(d, d));
        }
        if (ok || pitch <= -89.0)
            break;
    }
    /* the points' angles from the projector's axis, across (phi) and up (theta) */
    double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
    for (int k = 0; k < nq; k++) {
        double d[3] = { q[k][0], q[k][1], -p->alt_ray };
        double fz = fmax(dot3(d, p->fwd), 1e-9 * sqrt(dot3(d, d)));
        double ax = atan(dot3(d, p->right) / fz), ay = atan(dot3(d, p->up) / fz);
        x0 = fmin(x0, ax);
        x1 = fmax(x1, ax);
        y0 = fmin(y0, ay);
        y1 = fmax(y1, ay);
    }
    /* a hair beyond the box, so float rounding of the extreme rays never falls inside it */
    x0 -= GRID_MARGIN;
    x1 += GRID_MARGIN;
    y0 -= GRID_MARGIN;
    y1 += GRID_MARGIN;
    double hz = -pitch * M_PI / 180.0;                  /* the projector's horizon */
    if (hz < y1)
        y1 = hz - 1e-4;
    if (!(y1 > y0))
        return 0;
    /* The screen's part of the range: its side edges' angle, and its bottom edge's ray where
     * it meets the sea plane, seen from the projector. Those spans get SCREEN_SHARE of the
     * columns and rows (more where uniform angles would give them more). */
    double sx = fmin(atan(tx), fmax(x1, -x1)), sb = y0;
    double bot[3];
    for (int c = 0; c < 3; c++)
        bot[c] = cf[c] - ty * cu[c];
    if (bot[2] < 0.0 && p->alt > 0.0) {
        double t = p->alt / -bot[2], d[3] = { t * bot[0], t * bot[1], -p->alt_ray };
        double fz = dot3(d, p->fwd);
        if (fz > 0.0)
            sb = atan(dot3(d, p->up) / fz) - GRID_MARGIN;
    }
    sb = fmin(fmax(sb, y0), y1);
    p->pitch = pitch * M_PI / 180.0;
    p->row_margin[0] = sb;
    p->row_margin[1] = y0;
    p->row_h = fmax(p->alt, CAMERA_CLEARANCE_M);
    p->row_cam[0] = cam_depression(p, y1);
    p->row_cam[1] = cam_depression(p, sb);
    /* the margin's share: what uniform projector angles would give it, at most 1 - SCREEN_SHARE */
    p->row_split = sb > y0 ? fmax(SCREEN_SHARE, (y1 - sb) / (y1 - y0)) : 1.0;
    horizon_rows(p, g->h);
    double c0 = fmax(-sx, x0), c1 = fmin(sx, x1), span = x1 - x0;
    double inner = fmax(SCREEN_SHARE, (c1 - c0) / span);
    double side_l = c0 - x0, side_r = x1 - c1;
    p->col_ang[0] = x0;
    p->col_ang[1] = c0;
    p->col_ang[2] = c1;
    p->col_ang[3] = x1;
    p->col_split[0] = side_l + side_r > 0.0 ? (1.0 - inner) * side_l / (side_l + side_r) : 0.0;
    p->col_split[1] = p->col_split[0] + inner;
    return 1;
}

double grid_row_tan(const struct grid_projection *p, double v)
{
    double theta;
    if (v < p->row_split) {
        double u = v / p->row_split, dc0 = p->row_cam[0], us = p->row_ustar;
        double dc = dc0 + (u < us ? dc0 * (exp2(u * p->row_inv_delta) - 1.0)
                                  : p->row_xs + p->row_a * (u - us));
        theta = -p->pitch - atan2(p->alt_ray * sin(dc), p->row_h * cos(dc));
    } else {
        theta = p->row_margin[0] + (p->row_margin[1] - p->row_margin[0]) * (v - p->row_split) /
                                       fmax(1.0 - p->row_split, 1e-12);
    }
    return tan(theta);
}

double grid_warp(double x, const double *a, const double *s, int n)
{
    double lo = 0.0;
    for (int k = 0; k < n - 2; k++) {
        if (x < s[k])
            return a[k] + (a[k + 1] - a[k]) * (x - lo) / (s[k] - lo);
        lo = s[k];
    }
    return lo < 1.0 ? a[n - 2] + (a[n - 1] - a[n - 2]) * (x - lo) / (1.0 - lo) : a[n - 1];
}

/* Footprint of vertex (i, j) of the projected grid: the larger distance to the next vertex
 * along the row and down the column (the previous one for the last). */
static float grid_foot_at(const struct grid *g, int i, int j)
{
    size_t k = (size_t)j * g->w + i;
    size_t kx = i + 1 < g->w ? k + 1 : k - 1, ky = j + 1 < g->h ? k + g->w : k - g->w;
    float fx = maxf(fabsf(g->rx[kx] - g->rx[k]), fabsf(g->ry[kx] - g->ry[k]));
    float fy = maxf(fabsf(g->rx[ky] - g->rx[k]), fabsf(g->ry[ky] - g->ry[k]));
    return maxf(fx, fy);
}

/* Rest positions t_row (row + sx rgt) of n (a multiple of VBLK) rays of a row that all meet
 * the sea plane within dmax; restrict parameters let the compiler vectorise without alias
 * checks. */
static void project_row(int n, double t_row, const double row[3], const double rgt[2],
                        const double *restrict sx, float *restrict x, float *restrict y)
{
    const double r0 = row[0], r1 = row[1], g0 = rgt[0], g1 = rgt[1];
    for (int b = 0; b < n; b += VBLK)
        for (int e = 0; e < VBLK; e++) {
            x[b + e] = (float)(t_row * (r0 + sx[b + e] * g0));
            y[b + e] = (float)(t_row * (r1 + sx[b + e] * g1));
        }
}

/* grid_foot_at for n (a multiple of VBLK) vertices of a flat row-major grid of row width w,
 * reading vertex k + 1 and k + w, right for all but the last column and the last row. */
static void foot_blocks(int n, int w, const float *restrict rx, const float *restrict ry,
                        float *restrict foot)
{
    for (int b = 0; b < n; b += VBLK)
        for (int e = 0; e < VBLK; e++) {
            int k = b + e;
            float fx = maxf(fabsf(rx[k + 1] - rx[k]), fabsf(ry[k + 1] - ry[k]));
            float fy = maxf(fabsf(rx[k + w] - rx[k]), fabsf(ry[k + w] - ry[k]));
            foot[k] = maxf(fx, fy);
        }
}

static int update_projected(struct grid *g, const struct camera *cam, float aspect)
{
    struct grid_projection p;
    if (!projection_frame(g, cam, aspect, &p))
        return 0;
    const double *fwd = p.fwd, *right = p.right, *up = p.up;
    double alt_ray = p.alt_ray, dmax = p.dmax;
    const int w = g->w, h = g->h;
    double *restrict col_sx = g->col_sx;
    float *restrict row_x = g->row_x, *restrict row_y = g->row_y;
    /* Per row the ray is d = row + sx right with row = fwd + sy up (sx, sy: the tangents of the
     * warped angles, grid_warp); right is horizontal, so d_z and the sea-plane hit distance
     * alt_ray / -d_z are the row's; a ray hits the plane within dmax when
     * |d_xy| < -d_z dmax / alt_ray. */
    double rgt[2] = { right[0], right[1] };
    for (int i = 0; i < g->ws; i++)
        col_sx[i] = tan(grid_warp(i < w ? (double)i / (w - 1) : 1.0, p.col_ang, p.col_split, 4));
    for (int j = 0; j < h; j++) {
        double sy = grid_row_tan(&p, (double)j / (h - 1));
        double row[3], t_row = 0.0, lim2 = -1.0;
        for (int c = 0; c < 3; c++)
            row[c] = fwd[c] + sy * up[c];
        if (-row[2] > 0.0) {
            double lim = -row[2] * dmax / alt_ray;
            t_row = alt_ray / -row[2];
            lim2 = lim * lim;
        }
        /* |d_xy|^2 is convex in sx: when both end rays hit the plane within dmax, all do */
        double ex0 = row[0] + col_sx[0] * rgt[0], ey0 = row[1] + col_sx[0] * rgt[1];
        double ex1 = row[0] + col_sx[w - 1] * rgt[0], ey1 = row[1] + col_sx[w - 1] * rgt[1];
        if (ex0 * ex0 + ey0 * ey0 < lim2 && ex1 * ex1 + ey1 * ey1 < lim2) {
            project_row(g->ws, t_row, row, rgt, col_sx, row_x, row_y);
        } else {
            for (int i = 0; i < w; i++) {
                double sx = col_sx[i];
                double dx = row[0] + sx * rgt[0], dy = row[1] + sx * rgt[1];
                double dxy2 = dx * dx + dy * dy, t;
                /* Rays at or above the horizon end at the far distance along their azimuth. */
                t = dxy2 < lim2 ? t_row : dmax / (dxy2 > 1e-24 ? sqrt(dxy2) : 1e-12);
                row_x[i] = (float)(t * dx);
                row_y[i] = (float)(t * dy);
            }
        }
        memcpy(g->rx + (size_t)j * w, row_x, sizeof(float) * (size_t)w);
        memcpy(g->ry + (size_t)j * w, row_y, sizeof(float) * (size_t)w);
    }
    /* footprints (grid_foot_at) by blocks over the flat arrays, reading the next vertex and the
     * one a row down; the last column and the last row, whose neighbours are the previous ones,
     * are redone one by one, and the padding copies the last vertex (neutral for lo and hi) */
    const float *restrict rx = g->rx, *restrict ry = g->ry;
    float *restrict foot = g->foot;
    float lo8[VBLK], hi8[VBLK];
    foot_blocks(g->npad, w, rx, ry, foot);
    for (int j = 0; j < h; j++)
        foot[(size_t)j * w + w - 1] = grid_foot_at(g, w - 1, j);
    for (int i = 0; i < w; i++)
        foot[(size_t)(h - 1) * w + i] = grid_foot_at(g, i, h - 1);
    for (int k = g->nverts; k < g->npad; k++)
        foot[k] = foot[g->nverts - 1];
    for (int e = 0; e < VBLK; e++) {
        lo8[e] = INFINITY;
        hi8[e] = 0.0f;
    }
    for (int b = 0; b < g->npad; b += VBLK)
        for (int e = 0; e < VBLK; e++) {
            float f = foot[b + e];
            lo8[e] = f < lo8[e] ? f : lo8[e];
            hi8[e] = f > hi8[e] ? f : hi8[e];
        }
    float lo = INFINITY, hi = 0.0f;
    for (int e = 0; e < VBLK; e++) {
        lo = lo8[e] < lo ? lo8[e] : lo;
        hi = maxf(hi, hi8[e]);
    }
    g->foot_lo = g->foot_lo_wet = lo;
    g->foot_hi = hi;
    /* each grid row's smallest squared distance (row_distances) */
    for (int j = 0; j < h; j++) {
        const float *x = rx + (size_t)j * w, *y = ry + (size_t)j * w;
        float m8[VBLK], m = INFINITY;
        int i = 0;
        for (int e = 0; e < VBLK; e++)
            m8[e] = INFINITY;
        for (; i + VBLK <= w; i += VBLK)
            for (int e = 0; e < VBLK; e++) {
                float d2 = x[i + e] * x[i + e] + y[i + e] * y[i + e];
                m8[e] = d2 < m8[e] ? d2 : m8[e];
            }
        for (; i < w; i++) {
            float d2 = x[i] * x[i] + y[i] * y[i];
            m = d2 < m ? d2 : m;
        }
        for (int e = 0; e < VBLK; e++)
            m = m8[e] < m ? m8[e] : m;
        g->row_d2[j] = m;
    }
    return g->nidx;
}

/* Hu 2006 §3: a square near patch of fine cells around the camera, snapped to its cell size in
 * world space (no swimming), whose displacement fades to zero on its border (Hu: border heights
 * forced to zero so the patches stitch), and a flat far patch of FAR_RINGS square rings growing
 * geometrically from the near border to the far plane, bump-mapped only. */
static int update_patches(struct grid *g, const struct camera *cam, float aspect)
{
    double alt = cam->pos[2] > 0.5 ? cam->pos[2] : 0.5;
    double half = fmin(fmax(8.0 * alt, 64.0), 4000.0);
    double cell = 2.0 * half / (NEAR_N - 1);
    double ox = -(cam->pos[0] - cell * floor(cam->pos[0] / cell));
    double oy = -(cam->pos[1] - cell * floor(cam->pos[1] / cell));
    double dmax = far_distance(g, cam);
    double q = pow(fmax(dmax / half, 1.0001), 1.0 / FAR_RINGS);
    int per = 4 * (NEAR_N - 1), near0 = (FAR_RINGS + 1) * per;
    double inv = 1.0 / (NEAR_N - 1);
    for (int k = 0; k <= FAR_RINGS; k++) {
        double s = half * pow(q, k);
        float foot = (float)fmax(s * (q - 1.0), 2.0 * s * inv);
        for (int m = 0; m < per; m++) {
            int side = m / (NEAR_N - 1), e = m % (NEAR_N - 1);
            double a = -1.0 + 2.0 * e * inv, x, y;
            switch (side) {
            case 0: x = a; y = -1.0; break;
            case 1: x = 1.0; y = a; break;
            case 2: x = -a; y = 1.0; break;
            default: x = -1.0; y = -a; break;
            }
            g->rx[k * per + m] = (float)(ox + s * x);
            g->ry[k * per + m] = (float)(oy + s * y);
            g->foot[k * per + m] = foot;
        }
    }
    for (int j = 0; j < NEAR_N; j++)
        for (int i = 0; i < NEAR_N; i++) {
            double x = -1.0 + 2.0 * i * inv, y = -1.0 + 2.0 * j * inv;
            g->rx[near0 + j * NEAR_N + i] = (float)(ox + half * x);
            g->ry[near0 + j * NEAR_N + i] = (float)(oy + half * y);
            g->foot[near0 + j * NEAR_N + i] = (float)cell;
        }
    /* the rings' footprints grow outwards from the near patch's cell; only the near patch has
     * fade > 0 */
    g->foot_lo = g->foot_lo_wet = (float)cell;
    g->foot_hi = fmaxf((float)cell, g->foot[FAR_RINGS * per]);
    for (int k = 0; k < FAR_RINGS * per; k += per)
        g->foot_lo = fminf(g->foot_lo, g->foot[k]);
    return g->nidx;
}

int grid_row_count(const struct grid *g) { return g->rows; }

void grid_row_span(const struct grid *g, int row, int *first, int *count, float *dist2_min)
{
    int per_row = g->kind == 0 ? 6 * (g->w - 1) : 6 * 4 * (NEAR_N - 1);
    int far_idx = g->kind == 0 ? 0 : FAR_RINGS * per_row;
    if (g->kind == 0 || row < FAR_RINGS) {
        *first = row * per_row;
        *count = per_row;
    } else {
        /* near ring k (build_topology): 8 k + 4 cells, after the (2 R)^2 - (2 k + 2)^2 cells of
         * the rings outside it */
        int k = NEAR_RINGS - 1 - (row - FAR_RINGS);
        *first = far_idx + 6 * (4 * NEAR_RINGS * NEAR_RINGS - (2 * k + 2) * (2 * k + 2));
        *count = 6 * (8 * k + 4);
    }
    *dist2_min = g->row_foot[row];
}

/* Smallest squared horizontal distance from the camera of each row's vertices, from their rest
 * positions: on the projected grid the smaller of its two grid rows' (update_projected); on a
 * far ring, of its two borders' vertices; on near ring k, a bound from below: the distance to
 * the square of vertices its cells surround (0 for the innermost, which holds the camera). */
static void row_distances(struct grid *g)
{
    int per = 4 * (NEAR_N - 1), near0 = (FAR_RINGS + 1) * per, mid = NEAR_RINGS;
    for (int r = 0; r < g->rows; r++) {
        if (g->kind == 0) {
            float a = g->row_d2[r], b = g->row_d2[r + 1];
            g->row_foot[r] = b < a ? b : a;
            continue;
        }
        if (r >= FAR_RINGS) {
            int k = NEAR_RINGS - 1 - (r - FAR_RINGS);
            float m = 0.0f;
            if (k > 0) {
                const float *xs = g->rx + near0 + (size_t)mid * NEAR_N;   /* x by column */
                float x0 = fabsf(xs[mid - k]), x1 = fabsf(xs[mid + k]);
                float y0 = fabsf(g->ry[near0 + (size_t)(mid - k) * NEAR_N + mid]);
                float y1 = fabsf(g->ry[near0 + (size_t)(mid + k) * NEAR_N + mid]);
                m = minf(minf(x0, x1), minf(y0, y1));
            }
            g->row_foot[r] = m * m;
            continue;
        }
        /* ring k = FAR_RINGS - 1 - r is drawn r-th (outermost first) */
        int k = FAR_RINGS - 1 - r, a0 = k * per, b0 = (k + 1) * per;
        float m = INFINITY;
        for (int e = 0; e < 2; e++) {
            const float *x = g->rx + (e ? b0 : a0), *y = g->ry + (e ? b0 : a0);
            for (int i = 0; i < per; i++) {
                float d2 = x[i] * x[i] + y[i] * y[i];
                m = d2 < m ? d2 : m;    /* fminf is a libm call at -O2 on x86 */
            }
        }
        g->row_foot[r] = m;
    }
}

int grid_update(struct grid *g, const struct camera *cam, float aspect, double t_s, float *verts)
{
    struct pattern_frame pf[SWELL_MAX_PATTERNS];    /* the CPU patterns' */
    struct disp_frame df[SWELL_MAX_PATTERNS];       /* the displacing patterns' */
    int n, np = 0, nd = 0;
    n = g->kind == 0 ? update_projected(g, cam, aspect) : update_patches(g, cam, aspect);
    if (n == 0)
        return 0;
    float foot_lo = g->foot_lo_wet > 1e-6f ? g->foot_lo_wet : 1e-6f;
    for (int i = 0; i < g->t->patterns; i++) {
        struct grid_pattern *p = &g->p[i];
        struct pattern_frame *f = &pf[np];
        struct stream_phase ph;
        float o[2];
        /* eq. 2's weight is 0 for every vertex when it is 0 at the smallest wet footprint (the
         * float expressions are monotonic in the footprint) */
        int disp_on = p->lambda_m / foot_lo > FILTER_NMIN;
        if (!disp_on && !p->cpu && !p->kcpu)
            continue;
        grid_uv_offset(g->t, i, cam, o);
        stream_loop_phase(t_s, tables_pattern_period(g->t, i), g->t->frames, &ph);
        if (disp_on) {
            struct disp_frame *d = &df[nd++];
            int nx = p->disp->width, ny = p->disp->height;
            image_phase(&p->disp_f, &ph);
            d->im = &p->disp_f;
            d->data = p->disp_f.data;
            d->lambda_m = p->lambda_m;
            detile_frame_set(&d->dt, g->detile ? g->hash : NULL, i, p->inv_l, cam);
            /* a block is skipped from a hair above lambda / Nmin, where the weight is 0 (the
             * exact per-vertex weight decides the rest) */
            d->foot_zero = p->lambda_m / FILTER_NMIN * (1.0f + 1e-5f);
            d->kx = (float)(p->inv_l * nx);
            d->ky = (float)(p->inv_l * ny);
            d->x0 = (float)((double)o[0] * nx - 0.5);
            d->y0 = (float)((double)o[1] * ny - 0.5);
            d->wm = nx - 1;
            d->hm = ny - 1;
            d->wshift = __builtin_ctz((unsigned)nx);
            d->stride = sizeof(f4) * ((size_t)nx + 1);
            d->coord_max = COORD_MAX;
        }
        if (p->cpu || p->kcpu) {
            int top = p->levels - 1, lo, hi;
            f->p = p;
            detile_frame_set(&f->dt, g->detile ? g->hash : NULL, i, p->inv_l, cam);
            f->lev_k = (float)p->wc->width * (float)p->inv_l;
            lo = mip_level(g->foot_lo * f->lev_k, top);
            hi = mip_level(g->foot_hi * f->lev_k, top);
            for (int l = lo; l <= hi; l++) {
                int lw = p->wc_f[l].w;
                f->mk[l] = p->inv_l * lw;
                f->mx0[l] = (double)o[0] * lw - 0.5;
                f->my0[l] = (double)o[1] * lw - 0.5;
                if (p->cpu)
                    image_phase(&p->slope_f[l], &ph);
                image_phase(&p->wc_f[l], &ph);
            }
            if (p->kcpu) {   /* k_moment_pass reads the top texel wherever the vertices are */
                image_phase(&p->wc_f[top], &ph);
            }
            np++;
        }
    }
    if (np) {
        for (int k = 0; k < g->nverts; k++) {
            float *vx = verts + (size_t)k * GRID_FLOATS;
            for (int c = GRID_A_SLOPE; c <= GRID_A_PAD; c++)
                vx[c] = 0.0f;
        }
        for (int i = 0; i < np; i++)
            if (pf[i].p->cpu)
                moment_pass(g, &pf[i], verts);
            else
                k_moment_pass(g, &pf[i], verts);
    }
    float foot_disp = nd ? displace(g, df, nd) : -INFINITY;
    write_vertices(g, verts, (float)-cam->pos[2], np > 0, foot_disp);
    row_distances(g);
    return n;
}

/* The projected grid's frame for a camera, as update_projected() builds it (tiers with vertex
 * texture fetch build the vertices in ocean.vert from it). Also fills the rows' distances from
 * each row's nearest ray (the centre column's: right is horizontal and perpendicular to the
 * view's azimuth, so along a row of constant NDC y the horizontal distance is least at x = 0,
 * or at the column nearest it).
 * Returns 0 when no sea is in view. */
int grid_projection(struct grid *g, const struct camera *cam, float aspect,
                    struct grid_projection *p)
{
    if (!projection_frame(g, cam, aspect, p) || g->kind != 0)
        return 0;
    for (int r = 0; r < g->rows; r++) {
        /* row r spans grid rows r (farther) and r + 1 (nearer) */
        double sy = grid_row_tan(p, (double)(r + 1) / (g->h - 1));
        double sx = tan(fmin(fmax(0.0, p->col_ang[0]), p->col_ang[3])), d[3], dxy, t;
        for (int c = 0; c < 3; c++)
            d[c] = p->fwd[c] + sx * p->right[c] + sy * p->up[c];
        dxy = sqrt(d[0] * d[0] + d[1] * d[1]);
        t = -d[2] * p->dmax > p->alt_ray * dxy ? p->alt_ray / -d[2] : p->dmax / fmax(dxy, 1e-12);
        g->row_foot[r] = (float)(t * t * dxy * dxy);
    }
    return g->nidx;
}

/* One wavelength stands for pattern i's band in eq. 2: the geometric mean of its [k_min, k_max],
 * else a quarter of the patch. */
float grid_band_wavelength(const struct swell_pattern_info *pi)
{
    return pi->k_min > 0.0f && pi->k_max > 0.0f
               ? (float)(2.0 * M_PI / sqrt((double)pi->k_min * pi->k_max))
               : 0.25f * pi->size_m;
}
