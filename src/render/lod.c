/* lod.c - the texture level of each run of rows (render/internal.h): where a pattern is
 * dropped (its mip means nearly flat, or its patch under a pixel), the whole level fetched per
 * run on software rasterisers, and the weights that keep the fetched detail's contrast and the
 * unresolved variance continuous across runs (Bruneton §4.1 eq. 17-19; Dupuy eq. 6-8 for the
 * whitecaps' moments), so no seam shows where a run's level changes.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "render/internal.h"

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
float row_footprint(float d2, float alt, float pix_angle)
{
    return (d2 + alt * alt) / alt * pix_angle;
}

int slots_needed(const struct renderer *r, float d2, float alt, float pix_angle,
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
uint32_t run_lod_key(const struct renderer *r, float foot, int k, int kw)
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
 * du/dzeta = h / (1 + r_z) (h = SKY_MAP_HORIZON, sky.h), as ocean.vert and ocean.frag take it
 * per pixel, here with sigma^2 the unresolved variance, the top variance of the slots not
 * fetched and each fetched slot's mean within-texel variance at the level f asks (between
 * whole levels geometric: continuous in f, so neighbouring runs agree where they meet; the
 * larger of x and y, as the shader); r_z the reflected view's on a flat sea. */
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
           log2f(2.0f * SKY_MAP_HORIZON * (float)r->sky.size / (1.0f + rz));
}

/* The levels of a run from its key, bound as textures, and the sky map's two levels
 * (ocean.frag SWELL_RUN_LOD): eq. 27's footprint (sky_run_foot) at the run's farthest and
 * nearest rows (squared distances d2_far, d2_near), as a line in the pixel's footprint V_FOOT
 * between them, blends level L = floor of the smaller and L + 1, read from the sky atlas
 * (sky_atlas_at), each clamped half a texel inside its block as clamp-to-edge would. Before,
 * a run read one whole level: where the next run read another, the brightness stepped (6-9 %
 * at a 1 km view, test_seams test_sky_levels_continuous). */
void set_run_lods(struct renderer *r, int k, int kw, uint32_t key, float d2_far,
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
        bind_tex(r, unit_patterns(r) + s, chain_at(&r->slot[s].slope_tex, sl[s]), -1);
        if (s < kw)
            bind_tex(r, unit_patterns(r) + r->nfs + s, chain_at(&r->slot[s].wc_tex, wl[s]), -1);
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

/* eq. 6's gain (tables/foam_bias.h) as a line in the footprint through its values half a level
 * nearer than the run's nearest row and one farther than its farthest (as the variance's
 * knots; a row's vertices off the screen's centre lie farther): ocean.frag foam_gain,
 * ocean.vert foam_gain_v, unclamped (two instructions fewer: with them VideoCore VI spilled
 * a register in a high-quality program) */
static void foam_gain_line(const struct renderer *r, float lf_near, float lf_far, float out[2])
{
    float f0 = lf_near - 0.5f, f1 = fmaxf(lf_far + 1.0f, f0 + 0.5f);
    float g0 = foam_bias_at(&r->foam_bias, f0), g1 = foam_bias_at(&r->foam_bias, f1);
    out[0] = (g1 - g0) / (f1 - f0);
    out[1] = g0 - out[0] * f0;
}

void set_slot_lods(struct renderer *r, int k, int kw, uint32_t key, float alt, float pix,
                   float lf_far, float lf_near)
{
    const GLint *u = r->ou[VARIANT(k, kw)];
    {
        float gain[2];
        foam_gain_line(r, lf_near, lf_far, gain);
        glUniform2fv(u[OU_FOAM_GAIN], 1, gain);
        glUniform2fv(u[OU_FOAM_GAIN_V], 1, gain);
    }
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
