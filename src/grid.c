/* grid.c - CPU ocean geometry (grid.h): projected grid or near/far patches, displaced by the
 * looping displacement tables with Bruneton 2010 eq. 2 filter weights. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "grid.h"
#include "quantize.h"

#define GRID_MARGIN 0.15      /* NDC margin so displaced edges never uncover the screen border */
#define FILTER_NMIN 2.0f      /* Bruneton eq. 2: waves shorter than Nmin cells are cancelled... */
#define FILTER_NMAX 4.0f      /* ...and kept in full from Nmax cells up */
#define NEAR_N 129            /* near patch vertices per side (128 cells) */
#define FAR_RINGS 32          /* far patch rings from the near patch border to the far plane */
#define NEAR_FADE 0.1         /* last tenth of the near patch fades the displacement to 0 */

struct grid_pattern {
    const struct swell_table *disp, *slope, *wc;
    float *disp_f;            /* blended, dequantised displacement, N_geo^2 * 3 */
    uint8_t *slope_b, *wc_b;  /* blended RGBA8 chains (CPU patterns only) */
    size_t slope_off[16], wc_off[16];   /* byte offset of each level in those chains */
    int level_size[16];                 /* width (= height) of each level */
    double inv_l;             /* 1 / L_i */
    float lambda_m;           /* characteristic wavelength for the eq. 2 weight, m */
    int cpu;
    struct stream_phase phase;  /* of this pattern's own loop period (bake.c) */
    int phase_valid;
};

struct grid {
    const struct swell_tables *t;
    int kind, w, h;
    int nverts, nidx;
    uint16_t *idx;
    float *foot;              /* per-vertex footprint (cell size on the sea plane), m */
    float *fade;              /* per-vertex displacement factor (patches) */
    float *row_foot;          /* per row of triangles: smallest squared distance, m^2 */
    int rows;
    struct grid_pattern p[SWELL_MAX_PATTERNS];
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
        for (int j = 0; j + 1 < NEAR_N; j++)
            for (int i = 0; i + 1 < NEAR_N; i++)
                quad(g->idx, &n, near0 + j * NEAR_N + i, near0 + j * NEAR_N + i + 1,
                     near0 + (j + 1) * NEAR_N + i, near0 + (j + 1) * NEAR_N + i + 1);
    }
    g->nidx = n;
    return 0;
}

void grid_destroy(struct grid *g)
{
    if (!g)
        return;
    for (int i = 0; i < SWELL_MAX_PATTERNS; i++) {
        free(g->p[i].disp_f);
        free(g->p[i].slope_b);
        free(g->p[i].wc_b);
    }
    free(g->row_foot);
    free(g->fade);
    free(g->foot);
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
    g->w = d->w > 0 ? d->w : 96;
    g->h = d->h > 0 ? d->h : 64;
    if (g->kind == 0 && (g->w < 2 || g->h < 2 || g->w * g->h > 65536)) {
        rc = swell_fail(err, SWELL_E_ARG, "grid: %d x %d vertices; need 2..65536 in all "
                        "(16-bit indices on GLES2)", g->w, g->h);
        goto fail;
    }
    if ((rc = build_topology(g, err)))
        goto fail;
    g->rows = g->kind == 0 ? g->h - 1 : FAR_RINGS + NEAR_N - 1;
    g->row_foot = calloc((size_t)g->rows, sizeof(float));
    g->foot = malloc(sizeof(float) * (size_t)g->nverts);
    g->fade = malloc(sizeof(float) * (size_t)g->nverts);
    if (!g->foot || !g->fade || !g->row_foot) {
        rc = swell_fail(err, SWELL_E_NOMEM, "grid: no memory for %d vertices", g->nverts);
        goto fail;
    }
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
        p->inv_l = 1.0 / (pi->size_m > 0.0f ? pi->size_m : 1.0f);
        /* One wavelength stands for the pattern's band in eq. 2: the geometric mean of its
         * [k_min, k_max], else a quarter of the patch. */
        p->lambda_m = pi->k_min > 0.0f && pi->k_max > 0.0f
                          ? (float)(2.0 * M_PI / sqrt((double)pi->k_min * pi->k_max))
                          : 0.25f * pi->size_m;
        p->disp_f = malloc(sizeof(float) * 3 * (size_t)p->disp->width * p->disp->height);
        if (!p->disp_f) {
            rc = swell_fail(err, SWELL_E_NOMEM, "grid: no memory for pattern %d displacement", i);
            goto fail;
        }
        {
            /* the largest |Dz| the table holds, over every frame */
            float top = 0.0f, side = 0.0f;
            for (size_t k = 0; k < table_bytes(p->disp); k += 4) {
                top = fmaxf(top, fabsf(quantize_decode(p->disp, 2, p->disp->data[k + 2])));
                side = fmaxf(side, fabsf(quantize_decode(p->disp, 0, p->disp->data[k])));
                side = fmaxf(side, fabsf(quantize_decode(p->disp, 1, p->disp->data[k + 1])));
            }
            g->crest_m += top;
            g->chop_m += side;
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
            for (int l = 0; l < p->slope->levels; l++) {
                p->level_size[l] = table_level_width(p->slope, l);
                p->slope_off[l] = stream_level_offset(p->slope, l);
                p->wc_off[l] = stream_level_offset(p->wc, l);
            }
            p->slope_b = malloc(stream_blended_bytes(p->slope));
            p->wc_b = malloc(stream_blended_bytes(p->wc));
            if (!p->slope_b || !p->wc_b) {
                rc = swell_fail(err, SWELL_E_NOMEM, "grid: no memory for pattern %d moments", i);
                goto fail;
            }
        }
    }
    *out = g;
    return 0;
fail:
    grid_destroy(g);
    return rc;
}

/* Blend loop frames f0, f1 of every pattern once per phase change; each pattern loops with its
 * own period T_i (a whole fraction of T, bake.c). */
static void blend_tables(struct grid *g, double t_s)
{
    for (int i = 0; i < g->t->patterns; i++) {
        struct grid_pattern *p = &g->p[i];
        struct stream_phase phs;
        const struct stream_phase *ph = &phs;
        stream_loop_phase(t_s, tables_pattern_period(g->t, i), g->t->frames, &phs);
        if (p->phase_valid && phs.f0 == p->phase.f0 && phs.w == p->phase.w)
            continue;
        p->phase = phs;
        p->phase_valid = 1;
        const struct swell_table *d = p->disp;
        int f0 = ph->f0 < d->layers ? ph->f0 : 0, f1 = ph->f1 < d->layers ? ph->f1 : 0;
        const uint8_t *a = d->data + table_offset(d, 0, f0);
        const uint8_t *b = d->data + table_offset(d, 0, f1);
        float w1 = (float)ph->w / STREAM_W_ONE, w0 = 1.0f - w1;
        size_t texels = (size_t)d->width * d->height;
        float sc[3], bi[3];
        for (int c = 0; c < 3; c++) {
            sc[c] = d->scale[c] / 255.0f;
            bi[c] = d->bias[c];
        }
        for (size_t k = 0; k < texels; k++)
            for (int c = 0; c < 3; c++)
                p->disp_f[3 * k + c] = bi[c] + sc[c] * (w0 * a[4 * k + c] + w1 * b[4 * k + c]);
        if (p->cpu) {
            stream_blend(p->slope, ph, p->slope_b);
            stream_blend(p->wc, ph, p->wc_b);
        }
    }
}

/* floor() without a libm call (baseline x86-64 and ARMv7 have no rounding instruction). */
static inline long long floor_ll(double x)
{
    long long i = (long long)x;
    return i - (x < (double)i);
}

/* Bilinear, wrapped (power-of-two size) sample of a float3 image at texture coords (u, v). */
static void sample_disp(const struct grid_pattern *p, double u, double v, float out[3])
{
    int n = p->disp->width, m = p->disp->height;
    double x = u * n - 0.5, y = v * m - 0.5;
    long long ix = floor_ll(x), iy = floor_ll(y);
    float fx = (float)(x - (double)ix), fy = (float)(y - (double)iy);
    int x0 = (int)(ix & (n - 1)), y0 = (int)(iy & (m - 1));
    int x1 = (x0 + 1) & (n - 1), y1 = (y0 + 1) & (m - 1);
    const float *a = p->disp_f + 3 * ((size_t)y0 * n + x0), *b = p->disp_f + 3 * ((size_t)y0 * n + x1);
    const float *c = p->disp_f + 3 * ((size_t)y1 * n + x0), *d = p->disp_f + 3 * ((size_t)y1 * n + x1);
    for (int k = 0; k < 3; k++) {
        float top = a[k] + (b[k] - a[k]) * fx, bot = c[k] + (d[k] - c[k]) * fx;
        out[k] = top + (bot - top) * fy;
    }
}

static inline float maxf(float a, float b) { return a > b ? a : b; }
static inline float clamp01(float a) { return a < 0.0f ? 0.0f : (a > 1.0f ? 1.0f : a); }

/* Bilinear wrapped sample of one level of the blended slope and whitecap chains (same size),
 * dequantised: out[0..3] slope moments, out[4..7] whitecap channels. */
static void sample_moments(const struct grid_pattern *p, int level, double u, double v,
                           float out[8])
{
    int n = p->level_size[level];
    const uint8_t *img[2] = { p->slope_b + p->slope_off[level], p->wc_b + p->wc_off[level] };
    const struct swell_table *t[2] = { p->slope, p->wc };
    double x = u * n - 0.5, y = v * n - 0.5;
    long long ix = floor_ll(x), iy = floor_ll(y);
    float fx = (float)(x - (double)ix), fy = (float)(y - (double)iy);
    size_t x0 = (size_t)(ix & (n - 1)), y0 = (size_t)(iy & (n - 1));
    size_t x1 = (x0 + 1) & (size_t)(n - 1), y1 = (y0 + 1) & (size_t)(n - 1);
    size_t o00 = 4 * (y0 * n + x0), o01 = 4 * (y0 * n + x1), o10 = 4 * (y1 * n + x0),
           o11 = 4 * (y1 * n + x1);
    for (int k = 0; k < 8; k++) {
        const uint8_t *m = img[k >> 2];
        int c = k & 3;
        float top = m[o00 + c] + (m[o01 + c] - m[o00 + c]) * fx;
        float bot = m[o10 + c] + (m[o11 + c] - m[o10 + c]) * fx;
        out[k] = t[k >> 2]->bias[c] + t[k >> 2]->scale[c] * (1.0f / 255.0f) * (top + (bot - top) * fy);
    }
}

/* Displace vertex k (rest position already in verts) and fill its CPU-pattern moments. */
static void shade_vertex(struct grid *g, float *vx, float foot, float fade, const double off[][2])
{
    double rx = vx[GRID_A_REST], ry = vx[GRID_A_REST + 1];
    float disp[3] = { 0.0f, 0.0f, 0.0f };
    float sl[2] = { 0.0f, 0.0f }, sv[2] = { 0.0f, 0.0f }, km = 0.0f, kv = 0.0f, clear = 1.0f;
    float inv_foot = 1.0f / (foot > 1e-6f ? foot : 1e-6f);
    for (int i = 0; i < g->t->patterns; i++) {
        struct grid_pattern *p = &g->p[i];
        double u = off[i][0] + rx * p->inv_l, v = off[i][1] + ry * p->inv_l;
        /* Bruneton eq. 2: weight of the pattern's waves for a cell of size foot. */
        float w = fade * grid_filter_weight(FILTER_NMIN, FILTER_NMAX, p->lambda_m * inv_foot);
        if (w > 0.0f) {
            float d3[3];
            sample_disp(p, u, v, d3);
            for (int c = 0; c < 3; c++)
                disp[c] += w * d3[c];
        }
        if (p->cpu) {
            /* Mip level whose texel matches the vertex footprint: the mip texel then holds the
             * footprint's first and second moments (Bruneton §4.1, Dupuy eq. 7-8). */
            int lev = 0;
            float r = foot * (float)p->slope->width * (float)p->inv_l, m[8];
            while (r >= 2.0f && lev < p->slope->levels - 1) {
                r *= 0.5f;
                lev++;
            }
            sample_moments(p, lev, u, v, m);
            sl[0] += m[0];
            sl[1] += m[1];
            sv[0] += maxf(m[2] - m[0] * m[0], 0.0f);
            sv[1] += maxf(m[3] - m[1] * m[1], 0.0f);
            km += m[4];
            kv += maxf(m[5] - m[4] * m[4], 0.0f);
            clear *= 1.0f - clamp01(m[6]);
        }
    }
    vx[GRID_A_POS + 0] = (float)rx + disp[0];
    vx[GRID_A_POS + 1] = (float)ry + disp[1];
    vx[GRID_A_POS + 2] += disp[2];
    vx[GRID_A_SLOPE] = sl[0];
    vx[GRID_A_SLOPE + 1] = sl[1];
    vx[GRID_A_SVAR] = sv[0];
    vx[GRID_A_SVAR + 1] = sv[1];
    vx[GRID_A_K] = km;
    vx[GRID_A_K + 1] = kv;
    vx[GRID_A_FOAM] = 1.0f - clear;
}

static float far_distance(const struct camera *cam, float aspect)
{
    mat4 proj;
    camera_projection(cam, aspect, proj);
    /* perspective: P[3][2] = -2fn/(f-n), P[2][2] = -(f+n)/(f-n) => f = P[3][2] / (P[2][2] + 1) */
    float f = proj[3][2] / (proj[2][2] + 1.0f);
    return 0.9f * (f > 0.0f ? f : 5.0e4f);
}

static void basis(const struct camera *cam, double fwd[3], double right[3], double up[3])
{
    double h = cam->heading_deg * M_PI / 180.0, p = cam->pitch_deg * M_PI / 180.0;
    fwd[0] = cos(p) * cos(h); fwd[1] = cos(p) * sin(h); fwd[2] = sin(p);
    right[0] = sin(h); right[1] = -cos(h); right[2] = 0.0;
    up[0] = right[1] * fwd[2] - right[2] * fwd[1];
    up[1] = right[2] * fwd[0] - right[0] * fwd[2];
    up[2] = right[0] * fwd[1] - right[1] * fwd[0];
}

/* Bruneton 2010 §3 / Hinsinger 2002: screen-space grid rays intersected with the sea plane. */
static int update_projected(struct grid *g, const struct camera *cam, float aspect, float *verts)
{
    double fwd[3], right[3], up[3];
    double alt = cam->pos[2] > 0.5 ? cam->pos[2] : 0.5;
    /* Rays meet a plane raised by the highest crest (at most half-way up to the camera), so
     * crests near the screen's bottom edge never uncover it; rest points stay on z = -alt. */
    double alt_ray = fmax(alt - g->crest_m, 0.5 * alt);
    double fov = (cam->fov_y_deg > 0.0f ? cam->fov_y_deg : 45.0f) * M_PI / 180.0;
    double ty = tan(0.5 * fov), tx = ty * aspect;
    double dmax = far_distance(cam, aspect);
    /* Choppy displacement pulls the edge vertices sideways by up to chop_m, and a crest lifts a
     * bottom-edge vertex by up to crest_m; at the nearest visible distance (about alt_ray) that
     * is an angle of (chop_m + crest_m) / alt_ray, so widen the grid's margin by as much in NDC
     * (the storm golden frame showed an uncovered corner with the sideways term alone). */
    double margin = GRID_MARGIN + fmin((g->chop_m + g->crest_m) / alt_ray / ty, 1.5);
    double top = 1.0 + margin, bot = -1.0 - margin;
    basis(cam, fwd, right, up);
    if (up[2] * ty > 1e-9) {
        double hz = -fwd[2] / (ty * up[2]);   /* NDC y of the horizon */
        if (hz < top)
            top = hz;
    }
    if (top <= bot)
        return 0;
    for (int j = 0; j < g->h; j++) {
        double sy = top + (bot - top) * j / (g->h - 1);
        for (int i = 0; i < g->w; i++) {
            double sx = -1.0 - margin + 2.0 * (1.0 + margin) * i / (g->w - 1);
            double d[3], t, dxy;
            float *vx = verts + (size_t)(j * g->w + i) * GRID_FLOATS;
            for (int c = 0; c < 3; c++)
                d[c] = fwd[c] + sx * tx * right[c] + sy * ty * up[c];
            dxy = sqrt(d[0] * d[0] + d[1] * d[1]);
            /* Rays at or above the horizon end at the far distance along their azimuth. */
            t = -d[2] * dmax > alt_ray * dxy ? alt_ray / -d[2] : dmax / (dxy > 1e-12 ? dxy : 1e-12);
            vx[GRID_A_REST] = (float)(t * d[0]);
            vx[GRID_A_REST + 1] = (float)(t * d[1]);
            vx[GRID_A_POS + 2] = (float)-alt;
        }
    }
    for (int j = 0; j < g->h; j++)
        for (int i = 0; i < g->w; i++) {
            const float *a = verts + (size_t)(j * g->w + i) * GRID_FLOATS + GRID_A_REST;
            const float *bx = a + (i + 1 < g->w ? GRID_FLOATS : -GRID_FLOATS);
            const float *by = a + (j + 1 < g->h ? 1 : -1) * g->w * GRID_FLOATS;
            float fx = maxf(fabsf(bx[0] - a[0]), fabsf(bx[1] - a[1]));
            float fy = maxf(fabsf(by[0] - a[0]), fabsf(by[1] - a[1]));
            g->foot[j * g->w + i] = maxf(fx, fy);
            g->fade[j * g->w + i] = 1.0f;
        }
    return g->nidx;
}

/* Hu 2006 §3: a square near patch of fine cells around the camera, snapped to its cell size in
 * world space (no swimming), whose displacement fades to zero on its border (Hu: border heights
 * forced to zero so the patches stitch), and a flat far patch of FAR_RINGS square rings growing
 * geometrically from the near border to the far plane, bump-mapped only. */
static int update_patches(struct grid *g, const struct camera *cam, float aspect, float *verts)
{
    double alt = cam->pos[2] > 0.5 ? cam->pos[2] : 0.5;
    double half = fmin(fmax(8.0 * alt, 64.0), 4000.0);
    double cell = 2.0 * half / (NEAR_N - 1);
    double ox = -(cam->pos[0] - cell * floor(cam->pos[0] / cell));
    double oy = -(cam->pos[1] - cell * floor(cam->pos[1] / cell));
    double dmax = far_distance(cam, aspect);
    double q = pow(fmax(dmax / half, 1.0001), 1.0 / FAR_RINGS);
    int per = 4 * (NEAR_N - 1), near0 = (FAR_RINGS + 1) * per;
    double inv = 1.0 / (NEAR_N - 1);
    for (int k = 0; k <= FAR_RINGS; k++) {
        double s = half * pow(q, k);
        float foot = (float)fmax(s * (q - 1.0), 2.0 * s * inv);
        for (int m = 0; m < per; m++) {
            int side = m / (NEAR_N - 1), e = m % (NEAR_N - 1);
            double a = -1.0 + 2.0 * e * inv, x, y;
            float *vx = verts + (size_t)(k * per + m) * GRID_FLOATS;
            switch (side) {
            case 0: x = a; y = -1.0; break;
            case 1: x = 1.0; y = a; break;
            case 2: x = -a; y = 1.0; break;
            default: x = -1.0; y = -a; break;
            }
            vx[GRID_A_REST] = (float)(ox + s * x);
            vx[GRID_A_REST + 1] = (float)(oy + s * y);
            vx[GRID_A_POS + 2] = (float)-alt;
            g->foot[k * per + m] = foot;
            g->fade[k * per + m] = 0.0f;
        }
    }
    for (int j = 0; j < NEAR_N; j++)
        for (int i = 0; i < NEAR_N; i++) {
            double x = -1.0 + 2.0 * i * inv, y = -1.0 + 2.0 * j * inv;
            double edge = 1.0 - fmax(fabs(x), fabs(y));
            float *vx = verts + (size_t)(near0 + j * NEAR_N + i) * GRID_FLOATS;
            vx[GRID_A_REST] = (float)(ox + half * x);
            vx[GRID_A_REST + 1] = (float)(oy + half * y);
            vx[GRID_A_POS + 2] = (float)-alt;
            g->foot[near0 + j * NEAR_N + i] = (float)cell;
            g->fade[near0 + j * NEAR_N + i] = (float)fmin(edge / NEAR_FADE, 1.0);
        }
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
        *first = far_idx + (row - FAR_RINGS) * 6 * (NEAR_N - 1);
        *count = 6 * (NEAR_N - 1);
    }
    *dist2_min = g->row_foot[row];
}

/* Smallest squared horizontal distance from the camera of each row's vertices (both edges of
 * the row), from their rest positions. */
static void row_distances(struct grid *g, const float *verts)
{
    int per = 4 * (NEAR_N - 1), near0 = (FAR_RINGS + 1) * per;
    for (int r = 0; r < g->rows; r++) {
        int a0, n, b0;
        if (g->kind == 0) {
            a0 = r * g->w; b0 = a0 + g->w; n = g->w;
        } else if (r < FAR_RINGS) {
            /* ring k = FAR_RINGS - 1 - r is drawn r-th (outermost first) */
            int k = FAR_RINGS - 1 - r;
            a0 = k * per; b0 = (k + 1) * per; n = per;
        } else {
            int j = r - FAR_RINGS;
            a0 = near0 + j * NEAR_N; b0 = a0 + NEAR_N; n = NEAR_N;
        }
        float m = INFINITY;
        for (int e = 0; e < 2; e++) {
            const float *v = verts + (size_t)(e ? b0 : a0) * GRID_FLOATS + GRID_A_REST;
            for (int i = 0; i < n; i++, v += GRID_FLOATS)
                m = fminf(m, v[0] * v[0] + v[1] * v[1]);
        }
        g->row_foot[r] = m;
    }
}

int grid_update(struct grid *g, const struct camera *cam, float aspect, double t_s, float *verts)
{
    double off[SWELL_MAX_PATTERNS][2];
    int n;
    blend_tables(g, t_s);
    n = g->kind == 0 ? update_projected(g, cam, aspect, verts)
                     : update_patches(g, cam, aspect, verts);
    if (n == 0)
        return 0;
    for (int i = 0; i < g->t->patterns; i++) {
        float o[2];
        grid_uv_offset(g->t, i, cam, o);
        off[i][0] = o[0];
        off[i][1] = o[1];
    }
    for (int k = 0; k < g->nverts; k++)
        shade_vertex(g, verts + (size_t)k * GRID_FLOATS, g->foot[k], g->fade[k], off);
    row_distances(g, verts);
    return n;
}

/* The projected grid's frame for a camera, as update_projected() builds it (tiers with vertex
 * texture fetch build the vertices in ocean.vert from it). Also fills the rows' distances from
 * each row's nearest ray (the centre column's: right is horizontal and perpendicular to the
 * view's azimuth, so along a row of constant NDC y the horizontal distance is least at x = 0).
 * Returns 0 when no sea is in view. */
int grid_projection(struct grid *g, const struct camera *cam, float aspect,
                    struct grid_projection *p)
{
    double alt = cam->pos[2] > 0.5 ? cam->pos[2] : 0.5;
    double fov = (cam->fov_y_deg > 0.0f ? cam->fov_y_deg : 45.0f) * M_PI / 180.0;
    memset(p, 0, sizeof(*p));
    p->alt = alt;
    p->alt_ray = fmax(alt - g->crest_m, 0.5 * alt);
    p->ty = tan(0.5 * fov);
    p->tx = p->ty * aspect;
    p->dmax = far_distance(cam, aspect);
    p->margin = GRID_MARGIN + fmin((g->chop_m + g->crest_m) / p->alt_ray / p->ty, 1.5);
    p->top = 1.0 + p->margin;
    p->bot = -1.0 - p->margin;
    basis(cam, p->fwd, p->right, p->up);
    if (p->up[2] * p->ty > 1e-9) {
        double hz = -p->fwd[2] / (p->ty * p->up[2]);
        if (hz < p->top)
            p->top = hz;
    }
    if (g->kind != 0 || p->top <= p->bot)
        return 0;
    for (int r = 0; r < g->rows; r++) {
        /* row r spans grid rows r (farther) and r + 1 (nearer) */
        double sy = p->top + (p->bot - p->top) * (r + 1) / (g->h - 1), d[3], dxy, t;
        for (int c = 0; c < 3; c++)
            d[c] = p->fwd[c] + sy * p->ty * p->up[c];
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
