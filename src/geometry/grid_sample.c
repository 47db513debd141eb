/* grid_sample.c - the CPU texture sampler of the grid (grid_internal.h): a pattern's RGBA8
 * displacement and moment tables blended between their two loop frames (stream.h's phase) and
 * dequantised into float4 images, lazily by tiles or by the box a frame's footprints read, in
 * vectors (GCC/Clang vector extensions: SSE2, NEON or plain lanes). It lays out the images in
 * the memory grid_create allocates for them (struct grid_pattern's disp_mem, stamp_mem); the
 * bilinear samples themselves (texel_sample, tap4) and the mip level of a footprint are
 * inline in grid_internal.h. */
#include <stdlib.h>
#include <string.h>
#include "geometry/grid_internal.h"

#define BLEND_BLOCK 16        /* RGBA8 bytes (4 texels) blended to floats per vectorised block */

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
        if (t->kind == TABLE_WHITECAP && l < 2)
            im->mix_s = (t->scale[0] / 255.0f) * (t->scale[0] / 255.0f);
    }
    *texels += f4_texels(w, h);
    *tiles += (size_t)tiles_of(w) * (size_t)tiles_of(h);
}

/* The float images of pattern i: its displacement, and its moment chains if it is a CPU
 * pattern. Stamps start at 0, older than any generation. */
int pattern_images(struct grid_pattern *p, int i, struct swell_err *err)
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
void blend_tile(struct f4_image *im, int tx, int ty)
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
    if (im->mix_s > 0.0f) {
        /* channel 2: the blend's own variance of the foam memory (stream.h), 0 on a frame
         * alone */
        float k = f0 != f1 ? im->mix_s * (float)w0 * (float)w1 *
                                 (1.0f / (STREAM_W_ONE * STREAM_W_ONE)) : 0.0f;
        for (int y = y0; y <= y1; y++) {
            size_t src = (size_t)(y & (im->h - 1)) * row;
            float *o = im->data + (size_t)y * stride;
            for (int x = x0; x <= x1; x++) {
                size_t at = src + 4 * (size_t)(x & (im->w - 1));
                int d = a[at] - b[at];
                o[4 * (size_t)x + 2] = k * (float)(d * d);
            }
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
int box_blended(const struct f4_image *im, int sx, int mx, int sy, int my)
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
void blend_box(struct f4_image *im, int sx, int mx, int sy, int my)
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

int grid_mip_level(float r, int levels)
{
    return mip_level(r, levels - 1);
}
