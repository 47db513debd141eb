/* stream.c - loop-frame blending of RGBA8 tables (stream.h). */
#include <math.h>
#include <string.h>
#include "tables/stream.h"

/* u in [0, 1): how far through the loop. */
static void phase_of(double u, int frames, struct stream_phase *out)
{
    /* One integer phase for the whole loop so t and t + T land on the same value. */
    long long q = (long long)floor(u * (double)frames * STREAM_W_ONE + 0.5);
    long long total = (long long)frames * STREAM_W_ONE;
    q = total > 0 ? q % total : 0;
    out->f0 = (int)(q / STREAM_W_ONE);
    out->w = (int)(q % STREAM_W_ONE);
    out->f1 = frames > 0 ? (out->f0 + 1) % frames : 0;
}

static double loop_fraction(double t_s, double period_s)
{
    double u = period_s > 0.0 ? fmod(t_s, period_s) / period_s : 0.0;
    return u < 0.0 ? u + 1.0 : u;
}

void stream_loop_phase(double t_s, double period_s, int frames, struct stream_phase *out)
{
    phase_of(loop_fraction(t_s, period_s), frames, out);
}

void stream_pattern_phase(const struct swell_tables *s, int pattern, double t_s, int frames,
                          struct stream_phase *out)
{
    double T = s->loop_period_s, Ti = tables_pattern_period(s, pattern);
    double m = T > 0.0 && Ti > 0.0 ? floor(T / Ti + 0.5) : 1.0;   /* T_i = T / m, m whole */
    double u = loop_fraction(t_s, T) * (m >= 1.0 ? m : 1.0);
    phase_of(u - floor(u), frames, out);
}

size_t stream_level_offset(const struct swell_table *t, int level)
{
    size_t off = 0;
    for (int l = 0; l < level; l++)
        off += table_level_bytes(t, l);
    return off;
}

size_t stream_blended_bytes(const struct swell_table *t)
{
    return stream_level_offset(t, t->levels);
}

#define STREAM_BLOCK 16       /* bytes blended per vectorised block */

/* 16 bytes of dst = a w0 + b w1, rounded: each 16-bit word holds two bytes, blended in place
 * (the low byte shifted down, the high byte masked), so the products never leave 16 bits:
 * a w0 + b w1 + 128 <= 255 * 256 + 128 < 2^16. A fixed block of restrict-qualified bytes is what
 * -O2's very-cheap vectoriser accepts (no peeling, no runtime alias checks): one SSE2 or NEON
 * vector per block, no intrinsics. The byte order of a word does not matter. */
static inline void blend_block(uint8_t *restrict d, const uint8_t *restrict a,
                               const uint8_t *restrict b, uint16_t w0, uint16_t w1)
{
    uint16_t x[STREAM_BLOCK / 2], y[STREAM_BLOCK / 2], z[STREAM_BLOCK / 2];
    memcpy(x, a, STREAM_BLOCK);
    memcpy(y, b, STREAM_BLOCK);
    for (int k = 0; k < STREAM_BLOCK / 2; k++) {
        uint16_t lo = (uint16_t)((x[k] & 0xffu) * w0 + (y[k] & 0xffu) * w1 + STREAM_W_ONE / 2);
        uint16_t hi = (uint16_t)((x[k] >> 8) * w0 + (y[k] >> 8) * w1 + STREAM_W_ONE / 2);
        z[k] = (uint16_t)((lo >> 8) | (hi & 0xff00u));
    }
    memcpy(d, z, STREAM_BLOCK);
}

/* d[i] = (a[i] w0 + b[i] w1 + 128) >> 8 for n bytes that do not overlap d (a may equal b). */
static void stream_blend_bytes(uint8_t *restrict d, const uint8_t *restrict a,
                               const uint8_t *restrict b, size_t n, int w)
{
    uint16_t w1 = (uint16_t)w, w0 = (uint16_t)(STREAM_W_ONE - w1);
    size_t i = 0;
    if (w1 == 0 || a == b) {
        memcpy(d, a, n);
        return;
    }
    /* four blocks per iteration: the loop overhead falls to 1.5 instructions per 64 bytes
     * (about 1.3 instructions a byte on x86 in all) */
    for (; i + 4 * STREAM_BLOCK <= n; i += 4 * STREAM_BLOCK) {
        blend_block(d + i, a + i, b + i, w0, w1);
        blend_block(d + i + STREAM_BLOCK, a + i + STREAM_BLOCK, b + i + STREAM_BLOCK, w0, w1);
        blend_block(d + i + 2 * STREAM_BLOCK, a + i + 2 * STREAM_BLOCK, b + i + 2 * STREAM_BLOCK,
                    w0, w1);
        blend_block(d + i + 3 * STREAM_BLOCK, a + i + 3 * STREAM_BLOCK, b + i + 3 * STREAM_BLOCK,
                    w0, w1);
    }
    for (; i + STREAM_BLOCK <= n; i += STREAM_BLOCK)
        blend_block(d + i, a + i, b + i, w0, w1);
    for (; i < n; i++)
        d[i] = (uint8_t)((uint16_t)(a[i] * w0 + b[i] * w1 + STREAM_W_ONE / 2) >> 8);
}

static void blend_level(const struct swell_table *t, const struct stream_phase *ph, int level,
                        uint8_t *dst)
{
    int f0 = ph->f0 < t->layers ? ph->f0 : 0, f1 = ph->f1 < t->layers ? ph->f1 : 0;
    stream_blend_bytes(dst + stream_level_offset(t, level), t->data + table_offset(t, level, f0),
                       t->data + table_offset(t, level, f1), table_level_bytes(t, level), ph->w);
}

void stream_blend(const struct swell_table *t, const struct stream_phase *ph, uint8_t *dst)
{
    for (int l = 0; l < t->levels; l++)
        blend_level(t, ph, l, dst);
}

void stream_blend_coarse(const struct swell_table *t, const struct stream_phase *ph, int from,
                         uint8_t *dst)
{
    for (int l = from < 0 ? 0 : from; l < t->levels; l++)
        blend_level(t, ph, l, dst);
}

uint16_t stream_wc_mix_factor(int w)
{
    /* 4 (w / 256) (1 - w / 256) 256 / 255 in 1/256ths: 4 w (256 - w) / 255, rounded */
    long v = 4L * w * (STREAM_W_ONE - w);
    return (uint16_t)((v + 127) / 255);
}

typedef uint16_t wc_u16x8 __attribute__((vector_size(16)));
typedef uint32_t wc_u32x4 __attribute__((vector_size(16)));

/* Channel 2 of 4 texels (16 bytes) of d from the channel-0 bytes of a and b (stream.h), in
 * place: as 16-bit words a texel is (c0 | c1 << 8, c2 | c3 << 8) on a little-endian machine,
 * so every word's low byte is differenced and squared (the odd words' results are dropped),
 * and a 32-bit shift by 16 moves each texel's result into its channel-2 byte. In 16 bits:
 * d^2 + 128 <= 65153, its high byte times k <= 254 x 257, plus 128, stays under 2^16 (the
 * square of the difference wrapped to 16 bits is the square's low 16 bits, all of it). At the
 * surface (rough, gles2-min, high, callgrind) 0.21 M instructions a frame; gathering channel 0
 * by byte shuffles and storing eight bytes apart took 0.60 M. */
static inline void wc_mix4(uint8_t *restrict d, const uint8_t *restrict a,
                           const uint8_t *restrict b, uint16_t k)
{
    wc_u16x8 x, y;
    wc_u32x4 z;
    memcpy(&x, a, 16);
    memcpy(&y, b, 16);
    memcpy(&z, d, 16);
    wc_u16x8 e = (x & 0xff) - (y & 0xff);
    wc_u16x8 m = (wc_u16x8)((wc_u16x8)(e * e + 128) >> 8) * k + 128;
    m >>= 8;
    z = (z & 0xff00ffffu) | ((wc_u32x4)m << 16);
    memcpy(d, &z, 16);
}

void stream_blend_whitecap(const struct swell_table *t, const struct stream_phase *ph,
                           uint8_t *dst)
{
    stream_blend(t, ph, dst);
    stream_wc_blend_var(t, ph, dst);
}

/* stream_wc_blend_var for one level (nothing from level 2 up) */
static void wc_blend_var_level(const struct swell_table *t, const struct stream_phase *ph,
                               int l, uint8_t *dst)
{
    int f0 = ph->f0 < t->layers ? ph->f0 : 0, f1 = ph->f1 < t->layers ? ph->f1 : 0;
    uint16_t k = stream_wc_mix_factor(ph->w);
    uint8_t *d = dst + stream_level_offset(t, l);
    const uint8_t *a = t->data + table_offset(t, l, f0), *b = t->data + table_offset(t, l, f1);
    size_t n = table_level_bytes(t, l), i = 0;
    if (l >= 2 || k == 0 || a == b)
        return;   /* a frame alone: the blend of zeros, 0 */
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
    for (; i + 16 <= n; i += 16)
        wc_mix4(d + i, a + i, b + i, k);
#endif
    for (; i + 4 <= n; i += 4) {
        int e = a[i] - b[i];
        d[i + 2] = (uint8_t)(((((unsigned)(e * e) + 128u) >> 8) * k + 128u) >> 8);
    }
}

void stream_wc_blend_var(const struct swell_table *t, const struct stream_phase *ph,
                         uint8_t *dst)
{
    for (int l = 0; l < 2 && l < t->levels; l++)
        wc_blend_var_level(t, ph, l, dst);
}

void stream_blend_whitecap_coarse(const struct swell_table *t, const struct stream_phase *ph,
                                  int from, uint8_t *dst)
{
    for (int l = from < 0 ? 0 : from; l < t->levels; l++) {
        blend_level(t, ph, l, dst);
        wc_blend_var_level(t, ph, l, dst);
    }
}
