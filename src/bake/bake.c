/* bake.c - the whole bake: sea state -> patterns -> looping fields -> whitecaps -> tables.
 *
 * How the patterns combine for breaking (issue 13: foam baked per pattern repeated on each
 * pattern's own tile, identical clusters on a 50 m lattice seen from above): breaking and foam
 * are thresholds on the patterns' summed Dupuy k (eq. 7), which no single tile repeats. Each
 * breaking pattern bakes k_i and its foam memory m_i (whitecap_memory_loop: the (min, +) form of
 * Tessendorf 2023 eq. 8, rising at a rate r since the last break), both loop on the pattern's
 * own grid and are mipmapped. The patterns are independent (disjoint bands), so the
 * distribution of a sum is the convolution of the per-pattern histograms (whitecap_sum): one
 * epsilon makes the instantaneous breaking {sum k_i < epsilon} eq. 13's <Theta> (algorithm 1's
 * threshold from the CDF, on the combined field), and r is bisected so that the foam
 * {sum m_i < epsilon} covers the wind model's W - the fraction eq. 11 says eq. 8 sustains. The
 * renderer sums the prefiltered means and variances of m_i (Dupuy eq. 6-8) against epsilon.
 *
 * Only patterns at least FOAM_MIN_PATTERN_M across carry whitecaps (always the largest): a
 * pattern of a few metres repeats every few metres, and its k_i drawn as foam showed as a
 * visible lattice in storm scenes. Whitecaps are features of the dominant waves; the small
 * patterns keep their slopes and contribute the constant 1/n to Dupuy's j (eq. 7).
 */
#include "bake/bake.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "optics/fresnel.h"
#include "bake/ocean.h"
#include "tables/budget.h"
#include "tables/quantize.h"
#include "bake/spectrum.h"
#include "bake/whitecap.h"

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

/* The choice of n_fs and frames as a resolved state, costed by tables/budget.h. */
static struct seastate candidate(const struct seastate *s, int n_fs, int frames)
{
    struct seastate c = *s;
    c.size_fs = n_fs;
    c.frames = frames;
    c.size_geo = s->size_geo ? s->size_geo : geo_size_for(n_fs);
    return c;
}

/* Resolve frames/size_fs/size_geo against the budget (DESIGN.md "Budgets"): the tables with
 * their streamed part and a margin (held in RAM, streamed from), and the renderer's GPU memory
 * on any tier and geometry (budget.h), each within it. */
static int choose_sizes(struct seastate *s, struct swell_err *err)
{
    int nc = (int)(sizeof size_choices / sizeof size_choices[0]);
    for (int i = 0; i < nc; i++) {
        int n = s->size_fs ? s->size_fs : size_choices[i].n_fs;
        int f = s->frames ? s->frames : size_choices[i].frames;
        struct seastate c = candidate(s, n, f);
        if (budget_sizing_bytes(&c) <= s->budget_bytes && budget_gpu_bytes(&c) <= s->budget_bytes) {
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
    struct seastate c = candidate(s, n, f);
    uint64_t tables = budget_sizing_bytes(&c), gpu = budget_gpu_bytes(&c);
    uint64_t need = tables > gpu ? tables : gpu;
    return swell_fail(err, SWELL_E_BUDGET,
                      "the smallest configuration (%d patterns, %dx%d tables, %d frames) needs "
                      "%llu bytes of tables with their streamed part and %llu of GPU memory but "
                      "the budget is %llu bytes: raise --budget to at least %llu, or lower "
                      "--patterns/--frames/--size",
                      s->patterns, n, n, f, (unsigned long long)tables,
                      (unsigned long long)gpu, (unsigned long long)s->budget_bytes,
                      (unsigned long long)need);
}

static void progress(const struct bake_opts *o, double done, const char *stage)
{
    if (o && o->progress)
        o->progress(o->user, done, stage);
}

struct pattern_work {
    struct ocean *ocean;
    float *slope, *white, *disp;  /* float chains, level 0 filled per frame */
    float *k;                     /* Dupuy's k_i (eq. 7), F * N * N */
    float *mem;                   /* its foam memory m_i at the current rate, F * N * N */
    int breaks;                   /* carries whitecaps (see top) */
};

static void pattern_work_free(struct pattern_work *w)
{
    ocean_destroy(w->ocean);
    free(w->slope);
    free(w->white);
    free(w->disp);
    free(w->k);
    free(w->mem);
    memset(w, 0, sizeof *w);
}

/* Quantise chain into the next table of the set's layout (tables_layout: name and geometry). */
static int add_table(struct swell_tables *out, const struct swell_table *shape, const float *chain,
                     struct swell_err *err)
{
    struct swell_table *t = &out->table[out->count];
    *t = *shape;
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
    if (w->breaks) {   /* the others' k is the constant 1/n: nothing to remember */
        w->k = calloc(texels * (size_t)F, sizeof(float));
        w->mem = calloc(texels * (size_t)F, sizeof(float));
    }
    if (!w->slope || !w->white || !w->disp || (w->breaks && (!w->k || !w->mem)))
        return swell_fail(err, SWELL_E_NOMEM, "pattern %d: cannot allocate %zu floats of fields",
                          index, chain * 2 + texels * 6 * (size_t)F);
    for (int f = 0; f < F; f++) {
        struct ocean_fields fl;
        if ((r = ocean_eval(w->ocean, f, &fl, err)))
            return swell_err_context(err, "pattern %d frame %d", index, f);
        float *sl = w->slope + texels * 4 * (size_t)f;
        float *wh = w->white + texels * 4 * (size_t)f;
        float *dp = w->disp + texels * 4 * (size_t)f;
        float *kf = w->k ? w->k + texels * (size_t)f : NULL;
        for (size_t i = 0; i < texels; i++) {
            float a = fl.jxx[i], b = fl.jyy[i], c = fl.jxy[i];
            float k = w->breaks ? whitecap_dupuy_k(a, b, c, s->patterns)  /* Dupuy eq. 7 */
                                : 1.0f / (float)s->patterns;
            sl[i * 4 + 0] = fl.sx[i];
            sl[i * 4 + 1] = fl.sy[i];
            sl[i * 4 + 2] = fl.sx[i] * fl.sx[i];
            sl[i * 4 + 3] = fl.sy[i] * fl.sy[i];
            wh[i * 4 + 0] = k;       /* the foam memory m_i, once its rate is solved */
            wh[i * 4 + 1] = k * k;   /* eq. 8 */
            wh[i * 4 + 2] = 0.0f;
            wh[i * 4 + 3] = k;
            dp[i * 4 + 0] = fl.dx[i];
            dp[i * 4 + 1] = fl.dy[i];
            dp[i * 4 + 2] = fl.dz[i];
            dp[i * 4 + 3] = 0.0f;
            if (kf)
                kf[i] = k;
        }
        progress(opts, (index + (f + 1.0) / F) / (s->patterns + 1.0), "patterns");
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

/* A frame's foam memory m (n x n, periodic) as the moments its whitecap table holds (Dupuy
 * eq. 8): m, and the second moment m^2 + W of the continuous field over the texel, W the
 * variance of its linear variation across the texel, (m_x^2 + m_y^2) / 12 in texel units
 * (central differences on the tile). A texel is an area, not a point: with W = 0 at level 0
 * eq. 6's coverage is a step of the bilinear m, whose contours follow the texel grid (square
 * blocks of foam up close), and the 8-bit remainder <m^2> - <m>^2 there, noise of a
 * quantisation step, drew a mesh of dots inside them. The mips average both moments, so
 * every level holds the variance within its texels of this continuous field. */
static void foam_moments(const float *m, int n, float *out)
{
    for (int y = 0; y < n; y++)
        for (int x = 0; x < n; x++) {
            size_t i = (size_t)y * n + x;
            float gx = 0.5f * (m[(size_t)y * n + (x + 1) % n] - m[(size_t)y * n + (x + n - 1) % n]);
            float gy = 0.5f * (m[(size_t)((y + 1) % n) * n + x] - m[(size_t)((y + n - 1) % n) * n + x]);
            out[4 * i + 0] = m[i];
            out[4 * i + 1] = m[i] * m[i] + (gx * gx + gy * gy) * (1.0f / 12.0f);
        }
}

/* P(offset + sum_i X_i < x) for the breaking patterns' X_i = k_i (memory 0) or m_i (1). */
static int pattern_sum(const struct seastate *s, struct pattern_work *w, int np, int memory,
                       struct whitecap_sum *out, struct swell_err *err)
{
    const float *smp[SWELL_MAX_PATTERNS];
    size_t cnt[SWELL_MAX_PATTERNS];
    for (int i = 0; i < np; i++) {
        smp[i] = memory ? w[i].mem : w[i].k;
        cnt[i] = (size_t)s->size_fs * (size_t)s->size_fs * (size_t)s->frames;
    }
    /* the patterns that carry no whitecaps add their constant 1/n each (eq. 7) */
    return whitecap_sum_create(smp, cnt, np, (double)(s->patterns - np) / s->patterns, out, err);
}

/* Every breaking pattern's foam memory at rate r (k per second, per its own frame spacing). */
static int memory_at(const struct seastate *s, const struct swell_tables *out,
                     struct pattern_work *w, int np, double rate, struct swell_err *err)
{
    size_t texels = (size_t)s->size_fs * (size_t)s->size_fs;
    for (int i = 0; i < np; i++) {
        float step = (float)(rate * out->pattern[i].period_s / s->frames);
        int r = whitecap_memory_loop(w[i].k, texels, s->frames, step, w[i].mem, err);
        if (r)
            return r;
    }
    return 0;
}

#define RATE_ITERATIONS 28

/* Algorithm 1 on the combined field, then the foam memory's rate (see top): epsilon from the
 * CDF of sum k_i at eq. 13's <Theta>; the rate by bisection in log r so that
 * P(sum m_i < epsilon) = W (monotone: a faster rise leaves less foam). The memories are left at
 * the solved rate. */
static int solve_whitecaps(const struct seastate *s, struct swell_tables *out,
                           struct pattern_work *w, int np, struct swell_err *err)
{
    struct whitecap_sum sum;
    double w_model = whitecap_model_fraction(s->whitecap_model, s->wind_speed_mps);
    /* eq. 13's alpha: eq. 7's decay over the largest pattern's frame spacing */
    double alpha = exp2(-(out->pattern[0].period_s / s->frames) / s->foam_half_life_s);
    double theta = whitecap_breaking_fraction(w_model, alpha);
    int r = pattern_sum(s, w, np, 0, &sum, err);
    if (r)
        return r;
    double eps = whitecap_sum_quantile(&sum, theta);
    whitecap_sum_destroy(&sum);
    /* log2 of the rate: from far slower than any loop (2^-20 k/s) to a rise of 2^10 k/s, at
     * which no memory outlasts a frame */
    double lo = -20.0, hi = 10.0, covered = 0.0;
    for (int it = 0; it <= RATE_ITERATIONS; it++) {
        double mid = it == RATE_ITERATIONS ? hi : 0.5 * (lo + hi);
        if ((r = memory_at(s, out, w, np, exp2(mid), err)) ||
            (r = pattern_sum(s, w, np, 1, &sum, err)))
            return r;
        covered = whitecap_sum_cdf(&sum, eps);
        whitecap_sum_destroy(&sum);
        if (covered > w_model)
            lo = mid;
        else
            hi = mid;
    }
    out->whitecap_fraction_model = (float)w_model;
    out->whitecap_fraction_measured = (float)covered;
    out->whitecap_breaking_fraction = (float)theta;
    out->whitecap_epsilon = (float)eps;
    out->foam_recovery_per_s = (float)exp2(hi);
    return 0;
}

int bake_check(const struct seastate *state, struct swell_err *err)
{
    struct seastate s = *state;
    seastate_resolve(&s);
    int r = seastate_validate(&s, err);
    return r ? r : choose_sizes(&s, err);
}

int swell_bake(const struct seastate *state, const struct bake_opts *opts,
               struct swell_tables *out, struct swell_err *err)
{
    struct pattern_work work[SWELL_MAX_PATTERNS];
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
    /* below every table: the spectrum's tail beyond the last pattern, and what the spectrum
     * lacks of Cox & Munk's total in strong wind (spectrum_mss_deficit) */
    double deficit_x, deficit_y;
    spectrum_mss_deficit(&s, &deficit_x, &deficit_y);
    out->mss_unresolved_x = (float)(beyond_x + deficit_x);
    out->mss_unresolved_y = (float)(beyond_y + deficit_y);

    int n = s.size_fs, F = s.frames, levels = ilog2(n) + 1;
    size_t texels = (size_t)n * (size_t)n;
    int foam_patterns = 0;   /* patterns are largest first: whitecaps on a leading run */
    for (int i = 0; i < s.patterns; i++) {
        out->pattern[i].period_s = pattern_period(&s, &out->pattern[i]);
        work[i].breaks = i == 0 || out->pattern[i].size_m >= FOAM_MIN_PATTERN_M;
        foam_patterns += work[i].breaks;
    }
    for (int i = 0; i < s.patterns; i++)
        if ((r = bake_pattern_fields(&s, &out->pattern[i], i, &work[i], opts, out, err)))
            goto fail;

    /* Whitecaps: Tessendorf 2023 algorithm 1 on the patterns combined, the foam memory */
    progress(opts, s.patterns / (s.patterns + 1.0), "whitecaps");
    if ((r = solve_whitecaps(&s, out, work, foam_patterns, err)))
        goto fail;
    double var_h = 0.0;
    for (int i = 0; i < s.patterns; i++) {
        var_h += out->pattern[i].var_h;
        if (!work[i].breaks)
            continue;
        for (int f = 0; f < F; f++)
            foam_moments(work[i].mem + texels * (size_t)f, n,
                         work[i].white + 4 * texels * (size_t)f);
    }
    out->hs_m = (float)(4.0 * sqrt(var_h));

    /* Tables: per pattern slope + whitecap (mipmapped), displacement (geometry size) */
    progress(opts, 0.95, "quantise");
    int geo_level = ilog2(n / s.size_geo);
    struct swell_table shape[SWELL_MAX_TABLES];
    int shapes = tables_layout(&s, shape);   /* slope, whitecap, disp per pattern; Fresnel */
    for (int i = 0; i < s.patterns; i++) {
        quantize_build_mips(work[i].slope, n, n, F, levels);
        quantize_build_mips(work[i].white, n, n, F, levels);
        if ((r = add_table(out, &shape[out->count], work[i].slope, err)) ||
            (r = add_table(out, &shape[out->count], work[i].white, err)))
            goto fail;
        /* displacement: the box-filtered level of the fine grid at the geometry size */
        quantize_build_mips(work[i].disp, n, n, F, geo_level + 1);
        size_t off = quantize_chain_floats(n, n, F, geo_level);
        if ((r = add_table(out, &shape[out->count], work[i].disp + off, err)))
            goto fail;
        pattern_work_free(&work[i]);
    }
    if ((r = fresnel_hu_table(TABLES_FRESNEL_SIZE, &out->table[out->count], err)))
        goto fail;
    out->count++;
    if ((r = fresnel_eff_table(TABLES_FRESNEL_SIZE, &out->table[out->count], err)))
        goto fail;
    out->count++;
    for (int i = 0; i < shapes; i++)   /* the Fresnel tables name and size themselves */
        if (out->count != shapes || strcmp(out->table[i].name, shape[i].name) != 0 ||
            out->table[i].width != shape[i].width || out->table[i].levels != shape[i].levels) {
            r = swell_fail(err, SWELL_E_ARG, "bake: table %d is '%s', the layout says '%s' "
                           "(src/tables/tables.c tables_layout and the bake disagree)", i,
                           out->table[i].name, shape[i].name);
            goto fail;
        }

    foam_bias_compute(out, &out->foam_bias);    /* eq. 6's gains (tables/foam_bias.h) */
    out->has_foam_bias = 1;
    progress(opts, 1.0, "done");
    return 0;

fail:
    for (int i = 0; i < SWELL_MAX_PATTERNS; i++)
        pattern_work_free(&work[i]);
    tables_destroy(out);
    memset(out, 0, sizeof *out);
    return r;
}
