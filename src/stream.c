/* stream.c - loop-frame blending of RGBA8 tables (stream.h). */
#include <math.h>
#include "stream.h"

void stream_loop_phase(double t_s, double period_s, int frames, struct stream_phase *out)
{
    double u = period_s > 0.0 ? fmod(t_s, period_s) / period_s : 0.0;
    if (u < 0.0)
        u += 1.0;
    /* One integer phase for the whole loop so t and t + T land on the same value. */
    long long q = (long long)floor(u * (double)frames * STREAM_W_ONE + 0.5);
    long long total = (long long)frames * STREAM_W_ONE;
    q %= total;
    out->f0 = (int)(q / STREAM_W_ONE);
    out->w = (int)(q % STREAM_W_ONE);
    out->f1 = frames > 0 ? (out->f0 + 1) % frames : 0;
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

void stream_blend(const struct swell_table *t, const struct stream_phase *ph, uint8_t *dst)
{
    int f0 = ph->f0 < t->layers ? ph->f0 : 0, f1 = ph->f1 < t->layers ? ph->f1 : 0;
    /* 16-bit arithmetic so compilers vectorise: a w0 + b w1 + 128 <= 255 * 256 + 128 < 2^16 */
    uint16_t w1 = (uint16_t)ph->w, w0 = (uint16_t)(STREAM_W_ONE - w1);
    for (int l = 0; l < t->levels; l++) {
        const uint8_t *restrict a = t->data + table_offset(t, l, f0);
        const uint8_t *restrict b = t->data + table_offset(t, l, f1);
        size_t n = table_level_bytes(t, l);
        uint8_t *restrict d = dst + stream_level_offset(t, l);
        if (w1 == 0) {
            for (size_t i = 0; i < n; i++)
                d[i] = a[i];
            continue;
        }
        for (size_t i = 0; i < n; i++)
            d[i] = (uint8_t)((uint16_t)(a[i] * w0 + b[i] * w1 + STREAM_W_ONE / 2) >> 8);
    }
}
