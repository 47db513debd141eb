/* bake.c - the whole bake: sea state -> patterns -> looping fields -> whitecaps -> tables.
 *
 * How the patterns combine for breaking (the issue asks us to decide and show it holds):
 * the n patterns sample disjoint bands, so their Jacobian perturbations are independent. Each
 * pattern i gets its own lambda_min_i (Tessendorf 2023 §2, of J_i = I + lambda grad D_i) and its
 * own looping foam map O_i (eq. 7-8) on its own periodic grid - the only grid on which a map can
 * loop in space and time and be mipmapped. One threshold lambda_T is shared, solved so that the
 * union of the patterns' whitecaps, W = 1 - prod_i (1 - W_i) with W_i from eq. 11, equals the
 * wind-speed model (algorithm 1 applied to the union). The renderer combines the maps the same
 * way. tests/unit/test_bake.c checks on a common fine grid that the union's coverage matches
 * the model and that its foam lies where the full multi-pattern Jacobian breaks.
 *
 * Only patterns at least FOAM_MIN_PATTERN_M across carry whitecaps (always the largest): a
 * pattern of a few metres repeats every few metres, and foam (and Dupuy's k_i) drawn from it
 * showed as a visible lattice in storm scenes. Whitecaps are features of the dominant waves;
 * the small patterns keep their slopes and contribute the constant 1/n to Dupuy's j (eq. 7).
 *
 * Foam input is sub-texel: eq. 8's Theta per texel becomes the share B of the texel's area
 * (4 x 4 sub-samples of the bilinear lambda_min) below lambda_T (whitecap.h), so the foam's edge
 * follows the breaking contour instead of the texel grid. Algorithm 1's <Theta> is the mean of
 * that same B, and the final lambda_T is bisected on the loop's measured eq. 9 fraction.
 */
#include "bake.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fresnel.h"
#include "ocean.h"
#include "quantize.h"
#include "spectrum.h"
#include "whitecap.h"

#define FRESNEL_SIZE 64
#define FOAM_MIN_PATTERN_M 16.0f

struct size_choice { int n_fs, frames; };

/* Preference order: smooth animation (F >= 16) before resolution, then resolution. */
static const struct size_choice size_choices[] = {
    { 256, 32 }, { 256, 16 }, { 128, 32 }, { 128, 16 }, { 64, 32 }, { 64, 16 },
    { 128, 8 }, { 64, 8 }, { 32, 16 }, { 32, 8 },
};

static int geo_size_for(int n_fs) { return n_fs >= 128 ? 64 : n_fs / 2; }

static int ilog2(int v)
{
    int l = 0;
    while ((1 << (l + 1)) <= v)
        l++;
    return l;
}

static uint64_t rgba8_chain_bytes(int n, int levels)
{
    uint64_t b = 0;
    for (int l = 0; l < levels; l++) {
        uint64_t s = (uint64_t)(n >> l > 0 ? n >> l : 1);
        b += s * s * 4;
    }
    return b;
}

uint64_t bake_resident_bytes(int patterns, int n_fs)
{
    /* streamed per-pattern slope + whitecap textures (one frame each, full mips) */
    uint64_t streamed = (uint64_t)patterns * 2 * rgba8_chain_bytes(n_fs, ilog2(n_fs) + 1);
    return streamed + SWELL_RENDERER_RESERVE_BYTES;
}

uint64_t bake_table_bytes(int patterns, int n_fs, int n_geo, int frames)
{
    uint64_t per_pattern = (uint64_t)frames * (2 * rgba8_chain_bytes(n_fs, ilog2(n_fs) + 1) +
                                               (uint64_t)n_geo * (uint64_t)n_geo * 4);
    uint64_t fresnel = 2ull * FRESNEL_SIZE * FRESNEL_SIZE * 4;
    return (uint64_t)patterns * per_pattern + fresnel;
}

static uint64_t total_bytes(const struct seastate *s, int n_fs, int frames)
{
    int n_geo = s->size_geo ? s->size_geo : geo_size_for(n_fs);
    return bake_table_bytes(s->patterns, n_fs, n_geo, frames) +
           bake_resident_bytes(s->patterns, n_fs);
}

/* Resolve frames/size_fs/size_geo against the budget (DESIGN.md "Budgets"). */
static int choose_sizes(struct seastate *s, struct swell_err *err)
{
    int nc = (int)(sizeof size_choices / sizeof size_choices[0]);
    for (int i = 0; i < nc; i++) {
        int n = s->size_fs ? s->size_fs : size_choices[i].n_fs;
        int f = s->frames ? s->frames : size_choices[i].frames;
        if (total_bytes(s, n, f) <= s->budget_bytes) {
            s->size_fs = n;
            s->frames = f;
            if (!s->size_geo)
                s->size_geo = geo_size_for(n);
            if (s->size_geo > s->size_fs)
                return swell_fail(err, SWELL_E_ARG,
                                  "size_geo = %d exceeds size_fs = %d: the displacement table is "
                                  "a mip level of the slope table's grid",
                                  s->size_geo, s->size_fs);
            return 0;
        }
    }
    int n = s->size_fs ? s->size_fs : 32, f = s->frames ? s->frames : 8;
    return swell_fail(err, SWELL_E_BUDGET,
                      "the smallest configuration (%d patterns, %dx%d tables, %d frames) needs "
                      "%llu bytes but the budget is %llu bytes: raise --budget to at least %llu, "
                      "or lower --patterns/--frames/--size",
                      s->patterns, n, n, f, (unsigned long long)total_bytes(s, n, f),
                      (unsigned long long)s->budget_bytes,
                      (unsigned long long)total_bytes(s, n, f));
}

static void progress(const struct bake_opts *o, double done, const char *stage)
{
    if (o && o->progress)
        o->progress(o->user, done, stage);
}

struct pattern_work {
    struct ocean *ocean;
    float *slope, *white, *disp;  /* float chains, level 0 filled per frame */
    float *lmin;                  /* F * N * N */
    struct whitecap_cover cover;  /* sub-texel breaking coverage of lmin (breaking patterns) */
    double k_mean, k_var;
    int breaks;                   /* carries whitecaps (see top) */
    double alpha;                 /* eq. 11's per-frame foam decay for this pattern's dt */
};

static void pattern_work_free(struct pattern_work *w)
{
    ocean_destroy(w->ocean);
    free(w->slope);
    free(w->white);
    free(w->disp);
    whitecap_cover_destroy(&w->cover);
    free(w->lmin);
    memset(w, 0, sizeof *w);
}

static int add_table(struct swell_tables *out, const char *name, int kind, int pattern, int w,
                     int h, int layers, int levels, const float *chain, struct swell_err *err)
{
    if (out->count >= SWELL_MAX_TABLES)
        return swell_fail(err, SWELL_E_ARG, "too many tables (max %d)", SWELL_MAX_TABLES);
    struct swell_table *t = &out->table[out->count];
    memset(t, 0, sizeof *t);
    snprintf(t->name, sizeof t->name, "%s", name);
    t->kind = kind;
    t->pattern = pattern;
    t->format = FORMAT_RGBA8;
    t->width = w;
    t->height = h;
    t->layers = layers;
    t->levels = levels;
    int r = quantize_table(t, chain, err);
    if (r) {
        free(t->data);
        t->data = NULL;
        return r;
    }
    out->count++;
    return 0;
}

/* Hu 2006 §2.1 plays each pattern cyclically; with one period T for all, F frames could only
 * carry waves slower than (F/2 - 1) 2 pi / T (about 8 m wavelength for F = 16, T = 16 s) and the
 * small patterns would lose nearly all their waves. So pattern i loops with T_i = T / m_i, the
 * largest divisor-period whose frames still sample the band's fastest wave; T stays a period of
 * the whole sea, so frame t and t + T are identical everywhere. */
static float pattern_period(const struct seastate *s, const struct swell_pattern_info *pi)
{
    double w_max = spectrum_omega(pi->k_max, s->depth_m);
    double w_frames = (s->frames / 2 - 1) * 2.0 * M_PI;   /* = w_max * T_i at the limit */
    int m = 1;
    while (m < 4096 && w_max * s->loop_period_s / m > w_frames)
        m++;
    return s->loop_period_s / (float)m;
}

/* Bake one pattern's frames into its float chains. */
static int bake_pattern_fields(const struct seastate *s, const struct swell_pattern_info *pi,
                               int index, struct pattern_work *w, const struct bake_opts *opts,
                               struct swell_tables *out, struct swell_err *err)
{
    int n = s->size_fs, F = s->frames, levels = ilog2(n) + 1;
    size_t texels = (size_t)n * (size_t)n;
    size_t chain = quantize_chain_floats(n, n, F, levels);
    struct ocean_desc od = {
        .state = s, .n = n, .size_m = pi->size_m, .k_min = pi->k_min, .k_max = pi->k_max,
        .frames = F, .period_s = pi->period_s, .lambda = pi->lambda,
        /* per-pattern seeds: distinct, deterministic (golden-ratio stride) */
        .seed = s->seed + 0x9e3779b9u * (uint32_t)(index + 1),
    };
    int r = ocean_create(&od, &w->ocean, err);
    if (r)
        return swell_err_context(err, "pattern %d (L = %.2f m)", index, pi->size_m);
    w->slope = calloc(chain, sizeof(float));
    w->white = calloc(chain, sizeof(float));
    /* displacement: level 0 per frame now, box-filtered down to the geometry size later */
    w->disp = calloc(quantize_chain_floats(n, n, F, ilog2(n / s->size_geo) + 1), sizeof(float));
    w->lmin = calloc(texels * (size_t)F, sizeof(float));
    if (!w->slope || !w->white || !w->disp || !w->lmin)
        return swell_fail(err, SWELL_E_NOMEM, "pattern %d: cannot allocate %zu floats of fields",
                          index, chain * 2 + texels * 5 * (size_t)F);
    double ksum = 0.0, ksum2 = 0.0;
    for (int f = 0; f < F; f++) {
        struct ocean_fields fl;
        if ((r = ocean_eval(w->ocean, f, &fl, err)))
            return swell_err_context(err, "pattern %d frame %d", index, f);
        float *sl = w->slope + texels * 4 * (size_t)f;
        float *wh = w->white + texels * 4 * (size_t)f;
        float *dp = w->disp + texels * 4 * (size_t)f;
        float *lm = w->lmin + texels * (size_t)f;
        for (size_t i = 0; i < texels; i++) {
            float a = fl.jxx[i], b = fl.jyy[i], c = fl.jxy[i];
            float k = w->breaks ? whitecap_dupuy_k(a, b, c, s->patterns)  /* Dupuy eq. 7 */
                                : 1.0f / (float)s->patterns;
            float lmn = whitecap_lambda_min(a, b, c);
            sl[i * 4 + 0] = fl.sx[i];
            sl[i * 4 + 1] = fl.sy[i];
            sl[i * 4 + 2] = fl.sx[i] * fl.sx[i];
            sl[i * 4 + 3] = fl.sy[i] * fl.sy[i];
            wh[i * 4 + 0] = k;
            wh[i * 4 + 1] = k * k;   /* eq. 8 */
            wh[i * 4 + 2] = 0.0f;    /* foam opacity, after the threshold is known */
            wh[i * 4 + 3] = lmn;
            dp[i * 4 + 0] = fl.dx[i];
            dp[i * 4 + 1] = fl.dy[i];
            dp[i * 4 + 2] = fl.dz[i];
            dp[i * 4 + 3] = 0.0f;
            lm[i] = lmn;
            ksum += k;
            ksum2 += (double)k * k;
        }
        progress(opts, (index + (f + 1.0) / F) / (s->patterns + 1.0), "patterns");
    }
    double cnt = (double)texels * F;
    w->k_mean = ksum / cnt;
    w->k_var = ksum2 / cnt - w->k_mean * w->k_mean;
    if (w->breaks) {
        /* foam from the share of each texel's area that breaks, not a yes/no at its centre */
        struct whitecap_cover_desc cd = { .lambda_min = w->lmin, .width = n, .height = n,
                                          .frames = F };
        if ((r = whitecap_cover_create(&cd, &w->cover, err)))
            return swell_err_context(err, "pattern %d", index);
    }

    struct ocean_stats st;
    ocean_get_stats(w->ocean, &st);
    struct swell_pattern_info *po = &out->pattern[index];
    po->var_h = (float)st.var_h;
    po->mss_x = (float)st.mss_x;
    po->mss_y = (float)st.mss_y;
    out->mss_unresolved_x += (float)st.mss_fast_x;
    out->mss_unresolved_y += (float)st.mss_fast_y;
    return 0;
}

/* Smallest and largest lambda_min sub-sample over the first np patterns. */
static void lmin_range(const struct pattern_work *w, int np, float *lo, float *hi)
{
    whitecap_cover_extent(&w[0].cover, lo, hi);
    for (int i = 1; i < np; i++) {
        float l, h;
        whitecap_cover_extent(&w[i].cover, &l, &h);
        *lo = fminf(*lo, l);
        *hi = fmaxf(*hi, h);
    }
}

/* Shared lambda_T so that the union of the patterns' whitecaps equals the model (see top).
 * <Theta> of eq. 11-12 is the mean sub-texel coverage B over the same sub-samples the foam
 * loop uses (eq. 8 with B: <W> = <B> + a <W> - a <B W>, so eq. 11 holds with <Theta> = <B>).
 * Over all samples: whitecap_cdf() follows eq. 12 literally (lambda_min >= 0 only), but the
 * foam update fires on negative lambda_min too (folded crests), so the fraction the threshold
 * targets must count them or the measured fraction (eq. 9) overshoots the model. */
static float solve_threshold(struct pattern_work *w, int np, double target, double *theta_union)
{
    float lo, hi;
    lmin_range(w, np, &lo, &hi);
    hi = nextafterf(hi, INFINITY);
    for (int it = 0; it < 64; it++) {
        float mid = 0.5f * (lo + hi);
        if (mid <= lo || mid >= hi)
            break;   /* adjacent floats */
        double keep = 1.0;
        for (int i = 0; i < np; i++)
            keep *= 1.0 - whitecap_ensemble_fraction(whitecap_cover_mean(&w[i].cover, mid),
                                                     w[i].alpha);
        if (1.0 - keep < target)
            lo = mid;
        else
            hi = mid;
    }
    double keep = 1.0;
    for (int i = 0; i < np; i++)
        keep *= 1.0 - whitecap_cover_mean(&w[i].cover, hi);
    *theta_union = 1.0 - keep;
    return hi;
}

#define THRESHOLD_ITERATIONS 16

/* Foam loops (eq. 8 with the sub-texel coverage B) of every pattern at threshold lt;
 * *keep = prod (1 - W_i), W_i by eq. 9.
 * With store set, the opacities go into the whitecap chains. */
static int foam_union(const struct seastate *s, const struct swell_tables *out,
                      struct pattern_work *w, int np, float lt, float *tmp, int store,
                      double *keep, struct swell_err *err)
{
    size_t texels = (size_t)s->size_fs * (size_t)s->size_fs, count = texels * (size_t)s->frames;
    *keep = 1.0;
    for (int i = 0; i < np; i++) {
        float dt = out->pattern[i].period_s / s->frames;
        int r = whitecap_foam_loop(&w[i].cover, lt, dt, s->foam_half_life_s, tmp, err);
        if (r)
            return r;
        if (store)
            for (size_t j = 0; j < count; j++)
                w[i].white[j * 4 + 2] = tmp[j];
        *keep *= 1.0 - whitecap_measured_fraction(tmp, count);
    }
    return 0;
}

int swell_bake(const struct seastate *state, const struct bake_opts *opts,
               struct swell_tables *out, struct swell_err *err)
{
    struct pattern_work work[SWELL_MAX_PATTERNS];
    float *tmp = NULL;
    int r;
    memset(out, 0, sizeof *out);
    memset(work, 0, sizeof work);

    struct seastate s = *state;
    seastate_resolve(&s);
    if ((r = seastate_validate(&s, err)) || (r = choose_sizes(&s, err)))
        return r;
    out->state = s;
    out->patterns = s.patterns;
    out->frames = s.frames;
    out->loop_period_s = s.loop_period_s;

    double beyond_x = 0.0, beyond_y = 0.0;
    progress(opts, 0.0, "spectrum");
    if ((r = ocean_plan_patterns(&s, s.patterns, s.size_fs, out->pattern, &beyond_x, &beyond_y,
                                 err)))
        goto fail;
    out->mss_unresolved_x = (float)beyond_x;
    out->mss_unresolved_y = (float)beyond_y;

    int n = s.size_fs, F = s.frames, levels = ilog2(n) + 1;
    size_t texels = (size_t)n * (size_t)n, count = texels * (size_t)F;
    int foam_patterns = 0;   /* patterns are largest first: whitecaps on a leading run */
    for (int i = 0; i < s.patterns; i++) {
        out->pattern[i].period_s = pattern_period(&s, &out->pattern[i]);
        work[i].breaks = i == 0 || out->pattern[i].size_m >= FOAM_MIN_PATTERN_M;
        foam_patterns += work[i].breaks;
    }
    for (int i = 0; i < s.patterns; i++)
        if ((r = bake_pattern_fields(&s, &out->pattern[i], i, &work[i], opts, out, err)))
            goto fail;

    /* Whitecaps: Tessendorf 2023 algorithm 1 on the union of patterns, then eq. 7-8 per pattern */
    progress(opts, s.patterns / (s.patterns + 1.0), "whitecaps");
    /* eq. 11's alpha: the per-frame decay each pattern's foam loop actually applies (eq. 7
     * with the half-life over that pattern's frame spacing), so the eq. 9 fraction of the baked
     * loop is what eq. 11 predicts; the paper's fixed SWELL_WHITECAP_ALPHA belongs to its own
     * time step. */
    for (int i = 0; i < s.patterns; i++)
        work[i].alpha = exp(-(out->pattern[i].period_s / F) * log(2.0) / s.foam_half_life_s);
    double w_model = whitecap_model_fraction(s.whitecap_model, s.wind_speed_mps);
    double theta_union = 0.0;
    out->whitecap_fraction_model = (float)w_model;
    float lt = solve_threshold(work, foam_patterns, w_model, &theta_union);
    out->lambda_t_algorithm1 = lt;
    tmp = malloc(count * sizeof(float));
    if (!tmp) {
        r = swell_fail(err, SWELL_E_NOMEM, "cannot allocate the foam buffer (%zu floats)", count);
        goto fail;
    }
    /* Algorithm 1 (eq. 11-13) assumes breaking uncorrelated from frame to frame; in a loop the
     * same crests break every period, so the eq. 9 fraction of the baked loop falls short of
     * the model. Refine lambda_T by bisection on the measured union fraction of the loop,
     * starting from algorithm 1's value (monotone: a higher threshold only adds foam). */
    float lo, hi;
    lmin_range(work, foam_patterns, &lo, &hi);
    double keep = 1.0;
    for (int it = 0; it < THRESHOLD_ITERATIONS + 1; it++) {
        if ((r = foam_union(&s, out, work, foam_patterns, lt, tmp, it == THRESHOLD_ITERATIONS,
                            &keep, err)))
            goto fail;
        if (it == THRESHOLD_ITERATIONS)
            break;
        if (1.0 - keep < w_model)
            lo = lt;
        else
            hi = lt;
        lt = 0.5f * (lo + hi);
    }
    out->lambda_t = lt;
    double mu = 0.0, var = 0.0, var_h = 0.0;
    for (int i = 0; i < s.patterns; i++) {
        mu += work[i].k_mean;
        var += work[i].k_var;
        var_h += out->pattern[i].var_h;
    }
    out->whitecap_fraction_measured = (float)(1.0 - keep);
    out->whitecap_epsilon = (float)whitecap_dupuy_epsilon(theta_union, mu, var);
    out->hs_m = (float)(4.0 * sqrt(var_h));

    /* Tables: per pattern slope + whitecap (mipmapped), displacement (geometry size) */
    progress(opts, 0.95, "quantise");
    int geo_level = ilog2(n / s.size_geo);
    for (int i = 0; i < s.patterns; i++) {
        char name[32];
        quantize_build_mips(work[i].slope, n, n, F, levels);
        quantize_build_mips(work[i].white, n, n, F, levels);
        snprintf(name, sizeof name, "slope_p%d", i);
        if ((r = add_table(out, name, TABLE_SLOPE, i, n, n, F, levels, work[i].slope, err)))
            goto fail;
        snprintf(name, sizeof name, "whitecap_p%d", i);
        if ((r = add_table(out, name, TABLE_WHITECAP, i, n, n, F, levels, work[i].white, err)))
            goto fail;
        /* displacement: the box-filtered level of the fine grid at the geometry size */
        quantize_build_mips(work[i].disp, n, n, F, geo_level + 1);
        size_t off = quantize_chain_floats(n, n, F, geo_level);
        snprintf(name, sizeof name, "disp_p%d", i);
        if ((r = add_table(out, name, TABLE_DISP, i, s.size_geo, s.size_geo, F, 1,
                           work[i].disp + off, err)))
            goto fail;
        pattern_work_free(&work[i]);
    }

    if (out->count + 2 > SWELL_MAX_TABLES) {
        r = swell_fail(err, SWELL_E_ARG, "too many tables");
        goto fail;
    }
    if ((r = fresnel_hu_table(FRESNEL_SIZE, &out->table[out->count], err)))
        goto fail;
    out->count++;
    if ((r = fresnel_eff_table(FRESNEL_SIZE, &out->table[out->count], err)))
        goto fail;
    out->count++;

    free(tmp);
    progress(opts, 1.0, "done");
    return 0;

fail:
    free(tmp);
    for (int i = 0; i < SWELL_MAX_PATTERNS; i++)
        pattern_work_free(&work[i]);
    tables_destroy(out);
    memset(out, 0, sizeof *out);
    return r;
}
