/* slots.c - which pattern each fragment-shader slot shades (render/internal.h), the rest
 * resolved per vertex, and the per-level statistics of a slot's tables the run LODs use: mean
 * within-texel variance per mip level (Bruneton §4.1), the correlation of consecutive loop
 * frames, the level from which the mip means are nearly flat (DROP_RESOLVED).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "render/internal.h"

static void slot_tables_stats(struct renderer *r, struct fs_slot *sl);

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

void assign_patterns(struct renderer *r)
{
    int order[SWELL_MAX_PATTERNS], n = r->t->patterns, breaks[SWELL_MAX_PATTERNS];
    int units = r->gpu->caps.texture_units > 0 ? r->gpu->caps.texture_units : 8;
    if (r->d.texture_unit_count > 0 && r->d.texture_unit_count < units)
        units = r->d.texture_unit_count;     /* the application keeps the rest */
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
        if (unit_patterns(r) + fs + nwc <= units)
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
float loop_gain(float rho, int w_fixed)
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

/* Low quality fetches no whitecaps: the fragment patterns whose whitecaps vary, which the CPU
 * grid's vertices carry at their footprint's mip level (grid_pass.c k_moment_pass), so eq. 6 per
 * vertex sees the foam's patches as high quality's pixels do; with the patch's constants alone
 * every vertex had the same coverage (15 m/s from 10 m: low's rows up to 24 % darker than
 * high's near the camera, now 7 %: test_render test_quality_match). 0 in high quality. */
unsigned low_foam_mask(const struct renderer *r)
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
 * test_render test_tiers_low). Nor with wakes: the wake's heights are added per vertex on the
 * CPU (grid_set_wake). */
int choose_vtf(const struct renderer *r)
{
    GLint combined = 0;
    int n = r->t->patterns;
    int hash = renderer_detile(r);
    if (r->d.cpu_geometry || r->d.geometry != GEOMETRY_GRID || r->cpu_mask || low_foam_mask(r) ||
        r->d.wakes || r->d.wave_mask ||
        r->gpu->caps.vertex_texture_units < 2 * n + hash)
        return 0;
    glGetIntegerv(GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS, &combined);
    /* a unit per loop frame of every pattern and one for the lattice hash (detile.h) */
    int need = unit_patterns(r) + r->nfs + r->nwc + 2 * n + hash;
    if (combined < r->d.texture_unit_first + need ||
        (r->d.texture_unit_count > 0 && r->d.texture_unit_count < need))
        return 0;
    for (int i = 0; i < n; i++) {
        const struct swell_table *d = tables_find(r->t, TABLE_DISP, i);
        if (!d || d->format != FORMAT_RGBA8)
            return 0;
    }
    return 1;
}
