/* grid.c - CPU ocean geometry (grid.h): projected grid or near/far patches, displaced by the
 * looping displacement tables with Bruneton 2010 eq. 2 filter weights. This file: the grid's
 * lifetime (grid_create reads each pattern's tables, bounds its displacement and sizes every
 * per-vertex array; grid_destroy), the index buffer and its rows (Hu 2006 §3's rings for the
 * patches), the fade, and eq. 2's weight and band wavelength. It owns struct grid's memory; the
 * per-frame work is grid_project.c's (rest positions) and grid_pass.c's (grid_update). */
#include <math.h>
#include <stdlib.h>
#include "geometry/grid_internal.h"
#include "core/parse.h"
#include "tables/quantize.h"

static const char *const geometry_names[GEOMETRY_COUNT] = { "grid", "patches" };
const char *geometry_kind_name(int g) { return name_of(geometry_names, GEOMETRY_COUNT, g); }
int geometry_kind_from_name(const char *name)
{
    return parse_name(geometry_names, 0, GEOMETRY_COUNT, name);
}

#define NEAR_FADE 0.1         /* last tenth of the near patch fades the displacement to 0 */

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
    if (g->kind == GEOMETRY_GRID) {
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

/* The displacement factor depends on the vertex only: 1 on the projected grid; on the patches 0
 * on the far rings and fading to 0 over the near patch's last NEAR_FADE (Hu 2006 §3). */
static void init_fade(struct grid *g)
{
    int near0 = (FAR_RINGS + 1) * 4 * (NEAR_N - 1);
    double inv = 1.0 / (NEAR_N - 1);
    if (g->kind == GEOMETRY_GRID) {
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
    if (g->kind == GEOMETRY_GRID && (g->w < 2 || g->h < 2 || g->w * g->h > 65536)) {
        rc = swell_fail(err, SWELL_E_ARG, "grid: %d x %d vertices; need 2..65536 in all "
                        "(16-bit indices on GLES2)", g->w, g->h);
        goto fail;
    }
    if ((rc = build_topology(g, err)))
        goto fail;
    g->rows = g->kind == GEOMETRY_GRID ? g->h - 1 : FAR_RINGS + NEAR_RINGS;
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

int grid_k_flat_level(const struct swell_table *wc)
{
    return k_flat_level(wc);
}

int grid_row_count(const struct grid *g) { return g->rows; }

void grid_row_span(const struct grid *g, int row, int *first, int *count, float *dist2_min)
{
    int per_row = g->kind == GEOMETRY_GRID ? 6 * (g->w - 1) : 6 * 4 * (NEAR_N - 1);
    int far_idx = g->kind == GEOMETRY_GRID ? 0 : FAR_RINGS * per_row;
    if (g->kind == GEOMETRY_GRID || row < FAR_RINGS) {
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

/* One wavelength stands for pattern i's band in eq. 2: the geometric mean of its [k_min, k_max],
 * else a quarter of the patch. */
float grid_band_wavelength(const struct swell_pattern_info *pi)
{
    return pi->k_min > 0.0f && pi->k_max > 0.0f
               ? (float)(2.0 * M_PI / sqrt((double)pi->k_min * pi->k_max))
               : 0.25f * pi->size_m;
}
