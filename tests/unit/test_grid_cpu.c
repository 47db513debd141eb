/* test_grid_cpu.c - the CPU geometry's fast paths against brute-force references:
 * stream_blend's vectorised blocks against the integer formula on random bytes of every level
 * size, the mip level read from the float's exponent against the halving loop, and
 * grid_update's displaced vertices and moments (lazily blended float tiles) against a direct
 * double-precision evaluation of the same definitions from the RGBA8 tables.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>
#include "geometry/detile.h"
#include "geometry/grid.h"
#include "geometry/mask.h"
#include "tables/quantize.h"
#include "geometry/sea.h"
#include "tables/stream.h"

/* The camera's frame at 1280 x 720 (aspect 16:9), as renderer_frame makes it. */
static const struct camera_frame *frame_of(const struct camera *c)
{
    static struct camera_frame view;
    camera_frame_make(c, 1280, 720, &view);
    return &view;
}

#define F 4

static uint32_t rng = 12345u;
static float frand(void)
{
    rng = rng * 1664525u + 1013904223u;
    return (float)(rng >> 8) / 16777216.0f;
}

/* With g_moments, the whitecap tables' second channel is the first's square plus a little
 * (a foam memory's <m^2>, as the bake's): their means then hold the variance to finer levels
 * than the independent channels' (grid.c k_flat_level), so vertices read level 0. */
static int g_moments;

/* Pattern i's disp (n_geo, 1 level), slope and whitecap (n, all levels) tables of random,
 * smooth-ish values (a few sines plus noise), quantised as the bake does. */
static void add_pattern(struct swell_tables *s, int i, int n_geo, int n, float size_m,
                        float amp_m)
{
    static const int kinds[3] = { TABLE_DISP, TABLE_SLOPE, TABLE_WHITECAP };
    struct swell_err err;
    s->pattern[i].size_m = size_m;
    s->pattern[i].period_s = s->loop_period_s / (float)(i + 1);
    for (int k = 0; k < 3; k++) {
        struct swell_table *t = &s->table[s->count++];
        int w = kinds[k] == TABLE_DISP ? n_geo : n, levels = 1;
        while (kinds[k] != TABLE_DISP && (w >> (levels - 1)) > 1)
            levels++;
        float *chain = calloc(quantize_chain_floats(w, w, F, levels), sizeof(float));
        assert_non_null(chain);
        t->kind = kinds[k];
        t->pattern = i;
        t->format = FORMAT_RGBA8;
        t->width = t->height = w;
        t->layers = F;
        t->levels = levels;
        for (int f = 0; f < F; f++)
            for (int y = 0; y < w; y++)
                for (int x = 0; x < w; x++)
                    for (int c = 0; c < 4; c++) {
                        double ph = 2 * M_PI * (x * (c + 1) + y * (2 - c % 2)) / w + f * 1.3 + c;
                        chain[(((size_t)f * w + y) * w + x) * 4 + c] =
                            (float)(amp_m * (sin(ph) + 0.2 * frand()) + (c == 2 ? 0.5 : 0.0));
                    }
        if (g_moments && kinds[k] == TABLE_WHITECAP)
            for (size_t e = 0; e < (size_t)F * w * w; e++)
                chain[4 * e + 1] = chain[4 * e] * chain[4 * e] + 0.01f * (float)frand();
        quantize_build_mips(chain, w, w, F, levels);
        assert_int_equal(quantize_table(t, chain, &err), 0);
        free(chain);
    }
}

/* Two patterns, the long one first (as bakes order them) or, reversed, the short one first;
 * narrow: the short one's displacement 2x2, under a blend block wide (blended by tiles). */
static void make_tables_order(struct swell_tables *s, int reversed, int narrow)
{
    memset(s, 0, sizeof(*s));
    s->patterns = 2;
    s->frames = F;
    s->loop_period_s = 4.0f;
    add_pattern(s, reversed, 16, 32, 60.0f, 1.5f);
    add_pattern(s, !reversed, narrow ? 2 : 8, 16, 7.0f, 0.3f);
}

static void make_tables(struct swell_tables *s)
{
    make_tables_order(s, 0, 0);
}

/* Every byte of every level of a 64x64 chain (4096 down to 1 texels) and a 16x2 one (32, 8 and
 * 2 texels: the 64-byte loop, single 16-byte blocks and the byte tail) against
 * (a w0 + b w1 + 128) >> 8, for weights 0 (the copy), 1, 255 and others. */
static void random_table(struct swell_table *t, int kind, int width, int height, int levels)
{
    struct swell_err err;
    memset(t, 0, sizeof(*t));
    t->kind = kind;
    t->format = FORMAT_RGBA8;
    t->width = width;
    t->height = height;
    t->layers = 3;
    t->levels = levels;
    assert_int_equal(table_alloc(t, &err), 0);
    /* a whitecap table's channel 2 is 0 as baked (stream.h) */
    for (size_t i = 0; i < table_bytes(t); i++)
        t->data[i] = kind == TABLE_WHITECAP && (i & 3) == 2 ? 0 : (uint8_t)(frand() * 256.0f);
}

static void check_stream_blend_exact(int width, int height, int levels)
{
    struct swell_table t;
    random_table(&t, TABLE_SLOPE, width, height, levels);
    uint8_t *dst = malloc(stream_blended_bytes(&t));
    static const int ws[] = { 0, 1, 37, 128, 200, 255 };
    for (size_t k = 0; k < sizeof(ws) / sizeof(ws[0]); k++) {
        struct stream_phase ph = { .f0 = 2, .f1 = 0, .w = ws[k] };
        memset(dst, 0xa5, stream_blended_bytes(&t));
        stream_blend(&t, &ph, dst);
        for (int l = 0; l < t.levels; l++) {
            const uint8_t *a = t.data + table_offset(&t, l, 2), *b = t.data + table_offset(&t, l, 0);
            const uint8_t *d = dst + stream_level_offset(&t, l);
            for (size_t i = 0; i < table_level_bytes(&t, l); i++) {
                unsigned ref = (a[i] * (256u - (unsigned)ws[k]) + b[i] * (unsigned)ws[k] + 128u) >> 8;
                assert_int_equal(d[i], ref);
            }
        }
    }
    free(dst);
    free(t.data);
}

/* stream_blend_whitecap: stream_blend's bytes but channel 2 of levels 0 and 1, there the loop
 * blend's own variance of channel 0 as stream.h encodes it, B = 4 (1 - w) w d^2 / 255, within
 * 1.5 (the 16-bit squares' low bytes and the weight's factor rounded: measured 1.08), and 0
 * on a frame alone. A 64x64 chain (16-byte steps) and a 4x2 one (16-byte steps at level 0, the texel tail at 1). */
static void check_stream_blend_whitecap(int width, int height, int levels)
{
    struct swell_table t;
    random_table(&t, TABLE_WHITECAP, width, height, levels);
    uint8_t *dst = malloc(stream_blended_bytes(&t)), *ref = malloc(stream_blended_bytes(&t));
    static const int ws[] = { 0, 1, 37, 128, 200, 255 };
    double worst = 0.0;
    for (size_t k = 0; k < sizeof(ws) / sizeof(ws[0]); k++) {
        struct stream_phase ph = { .f0 = 2, .f1 = 0, .w = ws[k] };
        stream_blend(&t, &ph, ref);
        stream_blend_whitecap(&t, &ph, dst);
        double w = ws[k] / 256.0;
        for (int l = 0; l < t.levels; l++) {
            const uint8_t *a = t.data + table_offset(&t, l, 2), *b = t.data + table_offset(&t, l, 0);
            size_t o = stream_level_offset(&t, l);
            for (size_t i = 0; i < table_level_bytes(&t, l); i++) {
                if ((i & 3) != 2 || l >= 2) {
                    assert_int_equal(dst[o + i], ref[o + i]);
                    continue;
                }
                double d = (double)b[i - 2] - a[i - 2], exact = 4.0 * (1.0 - w) * w * d * d / 255.0;
                worst = fmax(worst, fabs(dst[o + i] - exact));
                assert_true(fabs(dst[o + i] - exact) <= 1.5);
            }
        }
    }
    print_message("whitecap blend %dx%d: channel 2 at most %.2f off (4 (1 - w) w d^2 / 255)\n",
                  width, height, worst);
    /* the top level alone (render/stream_gpu.c blends the rest): the same bytes there,
     * nothing else written */
    for (size_t k = 0; k < sizeof(ws) / sizeof(ws[0]); k++) {
        struct stream_phase ph = { .f0 = 2, .f1 = 0, .w = ws[k] };
        size_t top = stream_level_offset(&t, t.levels - 1), n = table_level_bytes(&t, t.levels - 1);
        stream_blend_whitecap(&t, &ph, ref);
        memset(dst, 0xa5, stream_blended_bytes(&t));
        stream_blend_whitecap_coarse(&t, &ph, t.levels - 1, dst);
        assert_memory_equal(dst + top, ref + top, n);
        for (size_t i = 0; i < top; i++)
            assert_int_equal(dst[i], 0xa5);
        memset(dst, 0xa5, stream_blended_bytes(&t));
        stream_blend(&t, &ph, ref);
        stream_blend_coarse(&t, &ph, t.levels - 1, dst);
        assert_memory_equal(dst + top, ref + top, n);
        for (size_t i = 0; i < top; i++)
            assert_int_equal(dst[i], 0xa5);
    }
    free(dst);
    free(ref);
    free(t.data);
}

static void test_stream_blend_exact(void **state)
{
    (void)state;
    check_stream_blend_exact(64, 64, 7);
    check_stream_blend_exact(16, 2, 5);
    check_stream_blend_whitecap(64, 64, 7);
    check_stream_blend_whitecap(4, 2, 3);
    check_stream_blend_whitecap(2, 1, 2);   /* the top is level 1: its channel 2 blended too */
}

static int mip_loop(float r, int levels)
{
    int lev = 0;
    while (r >= 2.0f && lev < levels - 1) {
        r *= 0.5f;
        lev++;
    }
    return lev;
}

/* grid_mip_level against the halving loop it replaces, at powers of two, their neighbours,
 * random values over 40 octaves and the odd cases. */
static void test_mip_level(void **state)
{
    (void)state;
    static const float odd[] = { 0.0f, -0.0f, -3.0f, 1e-40f, 1.0f, 1.9999999f, 2.0f, INFINITY,
                                 -INFINITY, NAN, 3.4e38f };
    for (int levels = 1; levels <= 12; levels++) {
        for (size_t i = 0; i < sizeof(odd) / sizeof(odd[0]); i++)
            assert_int_equal(grid_mip_level(odd[i], levels), mip_loop(odd[i], levels));
        for (int e = -20; e < 20; e++) {
            float p = ldexpf(1.0f, e);
            assert_int_equal(grid_mip_level(p, levels), mip_loop(p, levels));
            assert_int_equal(grid_mip_level(nextafterf(p, 0.0f), levels),
                             mip_loop(nextafterf(p, 0.0f), levels));
            assert_int_equal(grid_mip_level(nextafterf(p, INFINITY), levels),
                             mip_loop(nextafterf(p, INFINITY), levels));
        }
        for (int k = 0; k < 10000; k++) {
            float r = ldexpf(frand(), (int)(frand() * 40.0f) - 10);
            assert_int_equal(grid_mip_level(r, levels), mip_loop(r, levels));
        }
    }
}

/* Dequantised blend of loop frames in double: bias + scale / 255 (a (1 - w) + b w), the blend
 * rounded to a byte for the moment tables (as stream_blend gives the fragment shader). */
/* Channel c of texel (x, y) of level blended at phase ph; c = -1: the blend's own variance of
 * channel 0 (stream.h stream_blend_whitecap) */
static double texel(const struct swell_table *t, int level, const struct stream_phase *ph,
                    int x, int y, int c)
{
    int n = table_level_width(t, level);
    x &= n - 1;
    y &= n - 1;
    size_t o = 4 * ((size_t)y * n + x) + (c < 0 ? 0 : c);
    double a = t->data[table_offset(t, level, ph->f0) + o];
    double b = t->data[table_offset(t, level, ph->f1) + o];
    double w = ph->w / (double)STREAM_W_ONE;
    if (c < 0) {   /* the blend's own variance of channel 0, (1 - w) w (m1 - m0)^2 */
        double d = t->scale[0] / 255.0 * (b - a);
        return ph->f0 == ph->f1 ? 0.0 : (1.0 - w) * w * d * d;
    }
    double v = a * (1.0 - w) + b * w;
    if (t->kind != TABLE_DISP)
        v = floor(v + 0.5);    /* (a w0 + b w1 + 128) >> 8: v is an exact multiple of 1/256 */
    return t->bias[c] + t->scale[c] / 255.0 * v;
}

static double bilinear(const struct swell_table *t, int level, const struct stream_phase *ph,
                       double u, double v, int c)
{
    int n = table_level_width(t, level);
    double x = u * n - 0.5, y = v * n - 0.5, fx, fy;
    int ix = (int)floor(x), iy = (int)floor(y);
    fx = x - ix;
    fy = y - iy;
    return (1 - fy) * ((1 - fx) * texel(t, level, ph, ix, iy, c) + fx * texel(t, level, ph, ix + 1, iy, c)) +
           fy * ((1 - fx) * texel(t, level, ph, ix, iy + 1, c) + fx * texel(t, level, ph, ix + 1, iy + 1, c));
}

/* grid_update's vertices against the definitions evaluated directly: rest + sum_i w_i D_i with
 * Bruneton eq. 2's w_i for the vertex's footprint (texel coordinates in double here, in float
 * in grid.c), and pattern 0's (the CPU pattern's) moments at the mip level of the footprint;
 * over changing phases (images re-blended), a repeated phase (the view turned: more texels)
 * and a return to an earlier one;
 * with the longer pattern first or second (grid.c sums from the longest, which stores), near
 * the origin and 40 km out (wrapped texture offsets), and with a displacement image narrower
 * than a blend block. */
/* k-only vertices checked, by lattice (off, on) and by whether they took the flat top texel */
static int g_k_checked[2][2];
static int g_k_magnified;   /* ...of them at a magnified level 0 (grid_pass.c magnified_var) */
static int g_k_mixed;       /* ...of those with a loop blend's own variance */
static double g_alt = 6.0;  /* the camera's altitude, m */

/* detile 0: grid_desc no_detile, the reference reads one tap at no offset; k_only: pattern 0
 * is not a CPU pattern but one whose whitecap moments alone are resolved per vertex (grid.h
 * k_patterns): the same foam memory, no slopes */
static void check_grid_against_reference(int reversed, int narrow, double cx, double cy,
                                         int detile, int k_only)
{
    struct swell_tables s;
    struct grid *g;
    struct grid_desc d = { 0 };
    struct camera c;
    struct swell_err err;
    int w = 33, h = 25, checked_disp = 0, checked_zero = 0;
    static const double times[] = { 0.0, 0.37, 0.37, 0.37, 1.91, 0.37, 3.99 };
    static const float heading[] = { 70.0f, 160.0f, 250.0f, 300.0f, 250.0f, 70.0f, 300.0f };
    make_tables_order(&s, reversed, narrow);
    d.tables = &s;
    d.w = w;
    d.h = h;
    d.cpu_patterns = k_only ? 0u : 1u;
    d.k_patterns = k_only ? 1u : 0u;
    d.no_detile = !detile;
    if (narrow) {
        /* narrower than the lattice's offsets (detile.h): refused, said why */
        assert_int_not_equal(grid_create(&d, &g, &err), 0);
        assert_non_null(strstr(err.msg, "need at least 8 x 8"));
        tables_destroy(&s);
        return;
    }
    assert_int_equal(grid_create(&d, &g, &err), 0);
    float *verts = calloc((size_t)grid_vertex_count(g) * GRID_FLOATS, sizeof(float));
    double k_mean = 0.0;   /* pattern 0's foam memory mean: its top level over the loop */
    {
        const struct swell_table *wt = tables_find(&s, TABLE_WHITECAP, 0);
        int top = wt->levels - 1, nt = table_level_width(wt, top) * table_level_height(wt, top);
        for (int l = 0; l < wt->layers; l++)
            for (int k = 0; k < nt; k++)
                k_mean += wt->bias[0] + wt->scale[0] / 255.0 *
                          wt->data[table_offset(wt, top, l) + 4 * (size_t)k];
        k_mean /= (double)nt * wt->layers;
    }
    camera_defaults(&c);
    c.pos[0] = cx;
    c.pos[1] = cy;
    c.pos[2] = g_alt;
    c.heading_deg = 70.0f;
    c.pitch_deg = -20.0f;
    for (size_t ti = 0; ti < sizeof(times) / sizeof(times[0]); ti++) {
        double t_s = times[ti];
        /* turning: a repeated phase with another view must blend the texels it adds */
        c.heading_deg = heading[ti];
        struct stream_phase ph[2];
        float off[2][2];
        assert_true(grid_update(g, frame_of(&c), t_s, verts) > 0);
        for (int i = 0; i < 2; i++) {
            stream_pattern_phase(&s, i, t_s, F, &ph[i]);
            grid_uv_offset(&s, i, &c, off[i]);
        }
        for (int j = 0; j < h; j++)
            for (int i = 0; i < w; i++) {
                const float *vx = verts + (size_t)(j * w + i) * GRID_FLOATS;
                const float *bx = vx + (i + 1 < w ? 1 : -1) * GRID_FLOATS;
                const float *by = vx + (j + 1 < h ? 1 : -1) * w * GRID_FLOATS;
                double rx = vx[GRID_A_REST], ry = vx[GRID_A_REST + 1];
                double foot = fmax(fmax(fabs(bx[GRID_A_REST] - rx), fabs(bx[GRID_A_REST + 1] - ry)),
                                   fmax(fabs(by[GRID_A_REST] - rx), fabs(by[GRID_A_REST + 1] - ry)));
                double disp[3] = { 0, 0, 0 };
                for (int p = 0; p < 2; p++) {
                    const struct swell_table *dt = tables_find(&s, TABLE_DISP, p);
                    double lambda = grid_band_wavelength(&s.pattern[p]);
                    double wgt = grid_filter_weight(2.0f, 4.0f, (float)(lambda / fmax(foot, 1e-6)));
                    double u = off[p][0] + rx / s.pattern[p].size_m;
                    double v = off[p][1] + ry / s.pattern[p].size_m;
                    struct detile_taps tp;
                    detile_taps_off(&tp);
                    if (detile)   /* read at three offsets blended (detile.h) */
                        detile_taps(p, (cx + rx) / s.pattern[p].size_m,
                                    (cy + ry) / s.pattern[p].size_m, &tp);
                    for (int q = 0; q < 3; q++)
                        for (int k = 0; k < 3 && wgt > 0.0; k++)
                            disp[k] += wgt * tp.w[q] *
                                       bilinear(dt, 0, &ph[p], u + tp.du[q], v + tp.dv[q], k);
                }
                double ref[3] = { rx + disp[0], ry + disp[1],
                                  -c.pos[2] - (rx * rx + ry * ry) / (2.0 * EARTH_RADIUS_M) + disp[2] };
                for (int k = 0; k < 3; k++)
                    assert_true(fabs(vx[GRID_A_POS + k] - ref[k]) <= 2e-5 * fmax(1.0, fabs(ref[k])));
                if (fabs(disp[2]) > 1e-3)
                    checked_disp++;
                else
                    checked_zero++;
                /* pattern 0's moments, within a hundredth of a quantisation step */
                const struct swell_table *st = tables_find(&s, TABLE_SLOPE, 0);
                const struct swell_table *wt = tables_find(&s, TABLE_WHITECAP, 0);
                int lev = mip_loop((float)(foot * st->width / s.pattern[0].size_m), st->levels);
                double u = off[0][0] + rx / s.pattern[0].size_m, v = off[0][1] + ry / s.pattern[0].size_m;
                /* three taps blended (detile.h): means by w, variances by w^2, the foam memory's
                 * deviation from its mean over the patch */
                struct detile_taps tp;
                detile_taps_off(&tp);
                if (detile)
                    detile_taps(0, (cx + rx) / s.pattern[0].size_m,
                                (cy + ry) / s.pattern[0].size_m, &tp);
                double mean[2] = { 0, 0 }, var2 = 0.0, km = k_mean, kv = 0.0, kx = 0.0;
                /* k-only: from the flat level up the top texel (grid_k_flat_level) */
                int klev = k_only && lev >= grid_k_flat_level(wt) ? wt->levels - 1 : lev;
                g_k_checked[detile != 0][klev != lev] += k_only;
                for (int tap = 0; tap < 3; tap++) {
                    double m[4], q[4], wj = tp.w[tap];
                    for (int k = 0; k < 4; k++) {
                        m[k] = bilinear(st, lev, &ph[0], u + tp.du[tap], v + tp.dv[tap], k);
                        q[k] = bilinear(wt, klev, &ph[0], u + tp.du[tap], v + tp.dv[tap], k);
                    }
                    mean[0] += wj * m[0];
                    mean[1] += wj * m[1];
                    var2 += wj * wj * fmax(m[2] - m[0] * m[0], 0.0);
                    km += wj * (q[0] - k_mean);
                    kv += wj * wj * fmax(q[1] - q[0] * q[0], 0.0);
                    if (klev == 0)
                        kx += wj * wj * bilinear(wt, 0, &ph[0], u + tp.du[tap], v + tp.dv[tap], -1);
                }
                /* k-only, level 0 magnified (r texels per footprint under 1): level 0's mean
                 * within-texel variance W0 in place of the bilinear mix's, from r = 1/2 down,
                 * linear in r up to 1, the loop blend's own variance kept (grid_pass.c
                 * magnified_var) */
                double r0 = foot * wt->width / s.pattern[0].size_m;
                if (k_only && klev == 0 && r0 < 1.0) {
                    double w0 = table_level_within_var(wt, 0, 0, 1);
                    kv = w0 + kx + (kv - w0 - kx) * fmax(2.0 * r0 - 1.0, 0.0);
                    g_k_magnified++;
                    g_k_mixed += kx > 0.0;
                }
                double tol_s = 0.01 * st->scale[0] / 255.0, tol_w = 0.01 * wt->scale[0] / 255.0;
                /* and what the float rest position's rounding (2 ulp of its distance) moves at
                 * the level's texel: the horizon rows (grid.h) put far vertices on fine levels */
                double ulp = 2.0 * 1.2e-7 * fmax(fabs(rx), fabs(ry)) * st->width /
                             (s.pattern[0].size_m * (double)(1 << lev));
                if (k_only) {
                    for (int k = GRID_A_SLOPE; k < GRID_A_K; k++)
                        assert_true(vx[k] == 0.0f);
                } else {
                    assert_true(fabs(vx[GRID_A_SLOPE] - mean[0]) <=
                                tol_s + 1e-6 + ulp * st->scale[0]);
                    assert_true(fabs(vx[GRID_A_SLOPE + 1] - mean[1]) <=
                                0.01 * st->scale[1] / 255.0 + 1e-6 + ulp * st->scale[1]);
                    assert_true(fabs(vx[GRID_A_SVAR] - var2) <=
                                1e-3 * st->scale[2] / 255.0 + 1e-5 + ulp * st->scale[2]);
                }
                assert_true(fabs(vx[GRID_A_K] - km) <= tol_w + 1e-6 + ulp * wt->scale[0]);
                assert_true(fabs(vx[GRID_A_K + 1] - kv) <=
                            0.02 * wt->scale[1] / 255.0 + 1e-5 + ulp * wt->scale[1]);
            }
    }
    /* the view covers displaced near vertices and fully filtered far ones */
    assert_true(checked_disp > 100);
    assert_true(checked_zero > 10);
    free(verts);
    grid_destroy(g);
    tables_destroy(&s);
}

static void test_grid_against_reference(void **state)
{
    (void)state;
    check_grid_against_reference(0, 0, 1234.5, -321.25, 1, 0);
    check_grid_against_reference(1, 0, 1234.5, -321.25, 1, 0);
    check_grid_against_reference(0, 0, -40000.375, 38000.5, 1, 0);
    check_grid_against_reference(0, 1, 1234.5, -321.25, 1, 0);
    check_grid_against_reference(0, 0, 1234.5, -321.25, 0, 0);
    check_grid_against_reference(1, 0, -40000.375, 38000.5, 0, 0);
    /* whitecaps alone per vertex (low quality's fragment patterns), each table order with and
     * without the lattice: the synthetic tables' flat levels (grid_k_flat_level) differ, so
     * both sampled and flat vertices are checked in both */
    check_grid_against_reference(0, 0, 1234.5, -321.25, 1, 1);
    check_grid_against_reference(1, 0, -40000.375, 38000.5, 0, 1);
    check_grid_against_reference(0, 0, 1234.5, -321.25, 0, 1);
    check_grid_against_reference(1, 0, -40000.375, 38000.5, 1, 1);
    /* low enough that the nearest vertices' footprints are under a texel */
    g_alt = 0.3;
    g_moments = 1;
    check_grid_against_reference(0, 0, 1234.5, -321.25, 0, 1);
    check_grid_against_reference(0, 0, 1234.5, -321.25, 1, 1);
    g_moments = 0;
    g_alt = 6.0;
    for (int d = 0; d < 2; d++)
        for (int flat = 0; flat < 2; flat++)
            assert_true(g_k_checked[d][flat] > 10);
    print_message("whitecaps per vertex: %d vertices at a magnified level 0, %d of them with "
                  "the loop blend's own variance\n", g_k_magnified, g_k_mixed);
    assert_true(g_k_magnified > 10);
    assert_true(g_k_mixed > 10);
}

/* The projected grid's rest positions (by blocks of vertices, the rows whose rays all meet the
 * sea within the far distance vectorised) against the ray-plane intersection of Bruneton §3
 * evaluated per vertex in double from grid_projection's frame, and each row's smallest squared
 * distance against the brute-force minimum over its two grid rows; for widths that are and are
 * not a multiple of the block, and views down, at the horizon (rows ending at the far distance)
 * and from high up. */
static void test_projection_against_reference(void **state)
{
    static const int sizes[][2] = { { 33, 25 }, { 40, 20 }, { 96, 64 }, { 7, 3 } };
    static const float pitch[] = { -20.0f, 2.0f, -60.0f };
    static const double alt[] = { 6.0, 1.5, 1000.0 };
    struct swell_tables s;
    struct swell_err err;
    (void)state;
    make_tables(&s);
    for (size_t si = 0; si < sizeof(sizes) / sizeof(sizes[0]); si++)
        for (size_t ci = 0; ci < sizeof(pitch) / sizeof(pitch[0]); ci++) {
            struct grid_desc d = { 0 };
            struct grid *g;
            struct camera c;
            struct grid_projection p;
            int w = sizes[si][0], h = sizes[si][1], far_rays = 0;
            d.tables = &s;
            d.w = w;
            d.h = h;
            assert_int_equal(grid_create(&d, &g, &err), 0);
            float *verts = calloc((size_t)grid_vertex_count(g) * GRID_FLOATS, sizeof(float));
            camera_defaults(&c);
            c.pos[0] = -5000.25;
            c.pos[1] = 777.0;
            c.pos[2] = alt[ci];
            c.heading_deg = 33.0f;
            c.pitch_deg = pitch[ci];
            assert_true(grid_update(g, frame_of(&c), 1.25, verts) > 0);
            /* grid_projection fills the frame (its own row distances are overwritten below) */
            assert_true(grid_projection(g, frame_of(&c), &p) > 0);
            assert_true(grid_update(g, frame_of(&c), 1.25, verts) > 0);
            for (int j = 0; j < h; j++)
                for (int i = 0; i < w; i++) {
                    const float *vx = verts + (size_t)(j * w + i) * GRID_FLOATS;
                    double sx = tan(grid_warp((double)i / (w - 1), p.col_ang, p.col_split, 4));
                    double sy = grid_row_tan(&p, (double)j / (h - 1));
                    double r[3];
                    for (int k = 0; k < 3; k++)
                        r[k] = p.fwd[k] + sy * p.up[k] + sx * p.right[k];
                    double dxy = sqrt(r[0] * r[0] + r[1] * r[1]), t;
                    if (-r[2] > 0.0 && dxy < -r[2] * p.dmax / p.alt_ray) {
                        t = p.alt_ray / -r[2];
                    } else {
                        t = p.dmax / fmax(dxy, 1e-12);
                        far_rays++;
                    }
                    for (int k = 0; k < 2; k++)
                        assert_true(fabs(vx[GRID_A_REST + k] - t * r[k]) <= 1e-6 * fmax(1.0, t * dxy));
                    assert_true(isfinite(vx[GRID_A_POS + 2]));
                }
            for (int r = 0; r < grid_row_count(g); r++) {
                int first, count;
                float d2, m = INFINITY;
                grid_row_span(g, r, &first, &count, &d2);
                for (int i = 0; i < 2 * w; i++) {
                    const float *vx = verts + (size_t)(r * w + i) * GRID_FLOATS + GRID_A_REST;
                    float e2 = vx[0] * vx[0] + vx[1] * vx[1];
                    m = e2 < m ? e2 : m;
                }
                assert_true(d2 == m);
            }
            /* the horizon view has rows ending at the far distance, the others none */
            if (pitch[ci] > 0.0f)
                assert_true(far_rays > 0);
            free(verts);
            grid_destroy(g);
        }
    tables_destroy(&s);
}

/* Hu 2006 near/far patches through the same block passes: only vertices inside the near
 * patch's border (max(8 alt, 64 m) from the camera on each axis) are displaced, the border and
 * the far rings keep their rest position on the sphere (z = -alt - r^2 / 2R), and every
 * attribute is finite. */
static void test_patches(void **state)
{
    struct swell_tables s;
    struct grid *g;
    struct grid_desc d = { 0 };
    struct camera c;
    struct swell_err err;
    int moved = 0, still = 0;
    (void)state;
    make_tables(&s);
    d.tables = &s;
    d.kind = 1;
    assert_int_equal(grid_create(&d, &g, &err), 0);
    float *verts = calloc((size_t)grid_vertex_count(g) * GRID_FLOATS, sizeof(float));
    camera_defaults(&c);
    c.pos[0] = 321.5;
    c.pos[1] = -99.0;
    c.pos[2] = 6.0;
    assert_true(grid_update(g, frame_of(&c), 0.6, verts) > 0);
    for (int k = 0; k < grid_vertex_count(g); k++) {
        const float *vx = verts + (size_t)k * GRID_FLOATS;
        for (int a = 0; a < GRID_FLOATS; a++)
            assert_true(isfinite(vx[a]));
        double r2 = (double)vx[GRID_A_REST] * vx[GRID_A_REST] +
                    (double)vx[GRID_A_REST + 1] * vx[GRID_A_REST + 1];
        double drop = r2 / (EARTH_RADIUS_M + sqrt(fmax(EARTH_RADIUS_M * EARTH_RADIUS_M - r2, 0.0)));
        /* the sphere's, R - sqrt(R^2 - r^2) below the level (grid.c) */
        if (vx[GRID_A_POS] == vx[GRID_A_REST] && vx[GRID_A_POS + 1] == vx[GRID_A_REST + 1] &&
            fabs(vx[GRID_A_POS + 2] + 6.0 + drop) < 1e-5 + 1e-6 * drop) {
            still++;
        } else {
            moved++;
            /* strictly inside the border, which is at 64 m (64 cells of 1 m) around the
             * camera snapped to the cell: x in [-64.5, 63.5], y in [-64, 64] */
            assert_true(fabs(vx[GRID_A_REST] + 0.5) < 63.75 && fabs(vx[GRID_A_REST + 1]) < 63.75);
        }
    }
    assert_true(moved > 1000);
    assert_true(still > 1000);
    free(verts);
    grid_destroy(g);
    tables_destroy(&s);
}

/* sea.h's CPU query is the displacement the grid draws: at vertices whose cells are fine
 * enough for eq. 2 to keep every pattern in full (footprint under a quarter of the shortest
 * band's wavelength), the displaced vertex is rest + sea_displacement (the displacement images
 * blend the loop frames in float, as sea.c does); and sea_surface_height inverts the choppy
 * map: at the displaced vertex's x, y it gives the vertex's height. With the lattice and
 * without it (detile 0: grid_desc no_detile and the query's flag). */
static void check_sea_query(int detile)
{
    struct swell_tables s;
    struct swell_err err;
    struct grid_desc d = { 0 };
    struct grid *g;
    struct camera c;
    make_tables(&s);
    d.tables = &s;
    d.w = 96;
    d.h = 64;
    d.no_detile = !detile;
    assert_int_equal(grid_create(&d, &g, &err), 0);
    float *verts = calloc((size_t)grid_vertex_count(g) * GRID_FLOATS, sizeof(float));
    camera_defaults(&c);
    c.pos[0] = 1234.5;
    c.pos[1] = -77.25;
    c.pos[2] = 3.0;
    c.pitch_deg = -70.0f;
    double t = 2.7, lam_min = INFINITY, worst = 0.0, worst_h = 0.0;
    for (int i = 0; i < s.patterns; i++)
        lam_min = fmin(lam_min, grid_band_wavelength(&s.pattern[i]));
    assert_true(grid_update(g, frame_of(&c), t, verts) > 0);
    int w = 96, h = 64, checked = 0, off_h = 0;
    for (int j = 0; j + 1 < h; j++)
        for (int i = 0; i + 1 < w; i++) {
            const float *v = verts + (size_t)(j * w + i) * GRID_FLOATS;
            const float *vx = v + GRID_FLOATS, *vy = v + (size_t)w * GRID_FLOATS;
            double foot = fmax(fmax(fabs(vx[3] - v[3]), fabs(vx[4] - v[4])),
                               fmax(fabs(vy[3] - v[3]), fabs(vy[4] - v[4])));
            if (foot > 0.25 * lam_min * 0.95)
                continue;
            double dd[3], wx = c.pos[0] + v[GRID_A_REST], wy = c.pos[1] + v[GRID_A_REST + 1];
            sea_displacement(&s, detile, wx, wy, t, dd);
            worst = fmax(worst, fabs(v[0] - (v[GRID_A_REST] + dd[0])));
            worst = fmax(worst, fabs(v[1] - (v[GRID_A_REST + 1] + dd[1])));
            double r2 = (double)v[GRID_A_REST] * v[GRID_A_REST] +
                        (double)v[GRID_A_REST + 1] * v[GRID_A_REST + 1];
            worst = fmax(worst, fabs(v[2] - (dd[2] - c.pos[2] - r2 / (2.0 * EARTH_RADIUS_M))));
            checked++;
        }
    /* the inversion, at random rest points where the choppy map contracts (the row sums of its
     * Jacobian, by central differences, below 0.5 at the rest point, the displaced point and
     * between them, where the fixed-point steps go: the noise tables fold elsewhere; with the
     * largest partial derivative alone below 0.5, one point contracted by 0.83 a step only) */
    int inverted = 0;
    for (int k = 0; k < 8000; k++) {
        double px = 500.0 * frand(), py = 500.0 * frand(), d0[3], e = 0.01, j = 0.0;
        sea_displacement(&s, detile, px, py, t, d0);
        for (int at = 0; at < 5; at++) {
            double qx = px + 0.25 * at * d0[0], qy = py + 0.25 * at * d0[1];
            double dx[3], dy[3], dxm[3], dym[3];
            sea_displacement(&s, detile, qx + e, qy, t, dx);
            sea_displacement(&s, detile, qx - e, qy, t, dxm);
            sea_displacement(&s, detile, qx, qy + e, t, dy);
            sea_displacement(&s, detile, qx, qy - e, t, dym);
            /* the Jacobian's row sums: the fixed-point map's contraction in the max norm */
            for (int c2 = 0; c2 < 2; c2++)
                j = fmax(j, (fabs(dx[c2] - dxm[c2]) + fabs(dy[c2] - dym[c2])) / (2.0 * e));
        }
        if (j > 0.5)
            continue;
        double zh = sea_surface_height(&s, detile, px + d0[0], py + d0[1], t);
        worst_h = fmax(worst_h, fabs(zh - d0[2]));
        off_h += fabs(zh - d0[2]) > 1e-3;
        inverted++;
    }
    print_message("sea query (detile %s) vs %d fully displaced grid vertices: %.2e m; height "
                  "by inverting the choppy map at %d points: %d off by over 1 mm, at most %.2e m\n",
                  detile ? "on" : "off", checked, worst, inverted, off_h, worst_h);
    assert_true(checked > 500);
    assert_true(worst < 2e-4);
    assert_true(inverted > 1000);
    assert_true(worst_h < 1e-3);
    free(verts);
    grid_destroy(g);
    tables_destroy(&s);
}

static void test_sea_query(void **state)
{
    (void)state;
    check_sea_query(1);
    check_sea_query(0);
}

/* grid_warp: the knots, linear between them. */
static void test_warp(void **state)
{
    static const double a[4] = { -1.0, -0.5, 0.5, 2.0 }, k[2] = { 0.1, 0.9 };
    (void)state;
    assert_true(fabs(grid_warp(0.0, a, k, 4) - -1.0) < 1e-12);
    assert_true(fabs(grid_warp(0.05, a, k, 4) - -0.75) < 1e-12);
    assert_true(fabs(grid_warp(0.1, a, k, 4) - -0.5) < 1e-12);
    assert_true(fabs(grid_warp(0.5, a, k, 4) - 0.0) < 1e-12);
    assert_true(fabs(grid_warp(0.95, a, k, 4) - 1.25) < 1e-12);
    assert_true(fabs(grid_warp(1.0, a, k, 4) - 2.0) < 1e-12);
}

/* Issue 18, locally varying wave parameters (geometry/mask.h, grid_set_mask): every vertex of
 * the grid with a mask is the open sea's scaled by the mask's amplitude a at its rest point
 * (world: the camera's position plus it): its displacement from the rest point times a, the CPU
 * pattern's mean slope times a and its resolved variance times a^2, the foam memory's moments
 * as they were, a itself in GRID_A_PAD. A mask of a ramp (0 to 255 across 8 texels of 40 m)
 * with a calm hole, seen so the grid spans it. Fails with a read at the camera-relative point
 * (tried: 3,000 vertices off) or the variance times a (off by a). */
static void test_grid_mask(void **state)
{
    (void)state;
    struct swell_tables s;
    struct grid *g;
    struct grid_desc d = { 0 };
    struct swell_err err;
    make_tables(&s);
    d.tables = &s;
    d.w = 33;
    d.h = 25;
    d.cpu_patterns = 1u;
    assert_int_equal(grid_create(&d, &g, &err), 0);
    size_t nf = (size_t)grid_vertex_count(g) * GRID_FLOATS;
    float *open = calloc(nf, sizeof(float)), *masked = calloc(nf, sizeof(float));
    uint8_t amp[8 * 4];
    for (int j = 0; j < 4; j++)
        for (int i = 0; i < 8; i++)
            amp[8 * j + i] = (uint8_t)((i == 3 || i == 4) && (j == 1 || j == 2) ? 0 : 255 * i / 7);
    struct wave_mask m;
    const double origin[2] = { 900.0, -560.0 }, size[2] = { 320.0, 160.0 };
    assert_int_equal(wave_mask_init(&m, "test", amp, 8, 4, origin, size, &err), 0);
    struct camera c;
    camera_defaults(&c);
    c.pos[0] = 1000.0;
    c.pos[1] = -620.0;
    c.pos[2] = 20.0;
    c.heading_deg = 90.0f;
    c.pitch_deg = -25.0f;
    const struct camera_frame *view = frame_of(&c);
    assert_true(grid_update(g, view, 1.3, open) > 0);
    grid_set_mask(g, 1, &m);
    assert_true(grid_update(g, view, 1.3, masked) > 0);
    int n = 0, scaled = 0, calm = 0;
    double worst = 0.0;
    for (int k = 0; k < grid_vertex_count(g); k++) {
        const float *o = open + (size_t)k * GRID_FLOATS, *v = masked + (size_t)k * GRID_FLOATS;
        assert_float_equal(o[GRID_A_REST], v[GRID_A_REST], 0.0f);
        assert_float_equal(o[GRID_A_REST + 1], v[GRID_A_REST + 1], 0.0f);
        double a = wave_mask_at(&m, c.pos[0] + v[GRID_A_REST], c.pos[1] + v[GRID_A_REST + 1]);
        double r2 = (double)v[GRID_A_REST] * v[GRID_A_REST] +
                    (double)v[GRID_A_REST + 1] * v[GRID_A_REST + 1];
        double re = EARTH_RADIUS_M, base[3] = { v[GRID_A_REST], v[GRID_A_REST + 1],
                                                 -c.pos[2] - r2 / (re + sqrt(re * re - r2)) };
        assert_float_equal(v[GRID_A_PAD], a, 2e-5);   /* (its texel coordinates in float) */
        for (int e = 0; e < 3; e++) {
            double want = base[e] + a * (o[GRID_A_POS + e] - base[e]);
            worst = fmax(worst, fabs(v[GRID_A_POS + e] - want));
        }
        for (int e = 0; e < 2; e++) {
            assert_float_equal(v[GRID_A_SLOPE + e], a * o[GRID_A_SLOPE + e],
                               1e-6 + 1e-5 * fabs(o[GRID_A_SLOPE + e]));
            assert_float_equal(v[GRID_A_SVAR + e], a * a * o[GRID_A_SVAR + e],
                               1e-9 + 1e-5 * fabs(o[GRID_A_SVAR + e]));
            assert_float_equal(v[GRID_A_K + e], o[GRID_A_K + e], 0.0f);
        }
        n++;
        scaled += a > 0.02 && a < 0.98;
        calm += a == 0.0;
    }
    print_message("wave mask on the grid: %d vertices, %d at 0 < a < 1, %d calm (a = 0); the "
                  "displacement off a times the open sea's by at most %.2e m\n", n, scaled,
                  calm, worst);
    assert_true(scaled > 50 && calm > 3);
    assert_true(worst < 2e-3);
    /* on with no mask: a = 1, the open sea's vertices */
    grid_set_mask(g, 1, NULL);
    assert_true(grid_update(g, view, 1.3, masked) > 0);
    for (size_t k = 0; k < nf; k++)
        if (k % GRID_FLOATS == GRID_A_PAD)
            assert_float_equal(masked[k], 1.0f, 0.0f);
        else
            assert_float_equal(masked[k], open[k], 0.0f);
    free(open);
    free(masked);
    grid_destroy(g);
    tables_destroy(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_stream_blend_exact),
        cmocka_unit_test(test_mip_level),
        cmocka_unit_test(test_grid_against_reference),
        cmocka_unit_test(test_projection_against_reference),
        cmocka_unit_test(test_patches),
        cmocka_unit_test(test_sea_query),
        cmocka_unit_test(test_warp),
        cmocka_unit_test(test_grid_mask),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
