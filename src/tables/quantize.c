#include "tables/quantize.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

void quantize_downsample(const float *src, int w, int h, float *dst)
{
    int dw = w > 1 ? w / 2 : 1, dh = h > 1 ? h / 2 : 1;
    int sx = w > 1 ? 2 : 1, sy = h > 1 ? 2 : 1;
    float norm = 1.0f / (float)(sx * sy);
    for (int y = 0; y < dh; y++)
        for (int x = 0; x < dw; x++)
            for (int c = 0; c < 4; c++) {
                float acc = 0.0f;
                for (int j = 0; j < sy; j++)
                    for (int i = 0; i < sx; i++)
                        acc += src[((size_t)(y * sy + j) * (size_t)w + (size_t)(x * sx + i)) * 4 + c];
                dst[((size_t)y * (size_t)dw + (size_t)x) * 4 + c] = acc * norm;
            }
}

static size_t level_floats(int w, int h, int level)
{
    size_t lw = (size_t)(w >> level > 0 ? w >> level : 1);
    size_t lh = (size_t)(h >> level > 0 ? h >> level : 1);
    return lw * lh * 4;
}

size_t quantize_chain_floats(int w, int h, int layers, int levels)
{
    size_t n = 0;
    for (int l = 0; l < levels; l++)
        n += level_floats(w, h, l) * (size_t)layers;
    return n;
}

void quantize_build_mips(float *chain, int w, int h, int layers, int levels)
{
    size_t off = 0;
    for (int l = 0; l + 1 < levels; l++) {
        size_t lf = level_floats(w, h, l), nf = level_floats(w, h, l + 1);
        size_t next = off + lf * (size_t)layers;
        int lw = w >> l > 0 ? w >> l : 1, lh = h >> l > 0 ? h >> l : 1;
        for (int a = 0; a < layers; a++)
            quantize_downsample(chain + off + lf * (size_t)a, lw, lh, chain + next + nf * (size_t)a);
        off = next;
    }
}

uint16_t quantize_half_from_float(float f)
{
    union { float f; uint32_t u; } v = { f };
    uint32_t sign = (v.u >> 16) & 0x8000u;
    uint32_t abs = v.u & 0x7fffffffu;
    if (abs >= 0x7f800000u)                       /* inf or NaN */
        return (uint16_t)(sign | 0x7c00u | (abs > 0x7f800000u ? 0x200u : 0u));
    if (abs >= 0x477ff000u)                       /* rounds past 65504: inf */
        return (uint16_t)(sign | 0x7c00u);
    if (abs < 0x38800000u) {                      /* half subnormal or zero */
        if (abs < 0x33000000u)
            return (uint16_t)sign;
        uint32_t mant = (abs & 0x7fffffu) | 0x800000u;
        int shift = 126 - (int)(abs >> 23);       /* 14..24 */
        uint32_t half = mant >> (shift);
        uint32_t rem = mant & ((1u << shift) - 1u), mid = 1u << (shift - 1);
        if (rem > mid || (rem == mid && (half & 1u)))
            half++;
        return (uint16_t)(sign | half);
    }
    uint32_t h = ((abs - 0x38000000u) >> 13);     /* rebias exponent 127 -> 15 */
    uint32_t rem = abs & 0x1fffu;
    if (rem > 0x1000u || (rem == 0x1000u && (h & 1u)))
        h++;
    return (uint16_t)(sign | h);
}

float quantize_float_from_half(uint16_t h)
{
    uint32_t sign = (uint32_t)(h & 0x8000u) << 16;
    uint32_t exp = (h >> 10) & 0x1fu, mant = h & 0x3ffu;
    union { uint32_t u; float f; } v;
    if (exp == 0) {
        float m = ldexpf((float)mant, -24);
        return sign ? -m : m;
    }
    if (exp == 31)
        v.u = sign | 0x7f800000u | (mant << 13);
    else
        v.u = sign | ((exp + 112u) << 23) | (mant << 13);
    return v.f;
}

int quantize_table(struct swell_table *t, const float *chain, struct swell_err *err)
{
    size_t n = quantize_chain_floats(t->width, t->height, t->layers, t->levels);
    for (size_t i = 0; i < n; i++)
        if (!isfinite(chain[i]))
            return swell_fail(err, SWELL_E_ARG,
                              "table %s: value %zu (channel %zu) is not finite; the bake "
                              "produced NaN/Inf (report this with the sea state)",
                              t->name, i / 4, i % 4);
    int r = table_alloc(t, err);
    if (r)
        return r;
    if (t->format == FORMAT_RGBA16F) {
        uint16_t *dst = (uint16_t *)t->data;
        for (size_t i = 0; i < n; i++)
            dst[i] = quantize_half_from_float(chain[i]);
        for (int c = 0; c < 4; c++) {
            t->scale[c] = 1.0f;
            t->bias[c] = 0.0f;
        }
        return 0;
    }
    float lo[4] = { FLT_MAX, FLT_MAX, FLT_MAX, FLT_MAX };
    float hi[4] = { -FLT_MAX, -FLT_MAX, -FLT_MAX, -FLT_MAX };
    for (size_t i = 0; i < n; i++) {
        int c = (int)(i & 3u);
        if (chain[i] < lo[c]) lo[c] = chain[i];
        if (chain[i] > hi[c]) hi[c] = chain[i];
    }
    float inv[4];
    for (int c = 0; c < 4; c++) {
        t->bias[c] = lo[c];
        t->scale[c] = hi[c] > lo[c] ? hi[c] - lo[c] : 1.0f;
        inv[c] = 255.0f / t->scale[c];
    }
    for (size_t i = 0; i < n; i++) {
        int c = (int)(i & 3u);
        float q = (chain[i] - t->bias[c]) * inv[c];
        long v = lrintf(q);
        t->data[i] = (uint8_t)(v < 0 ? 0 : v > 255 ? 255 : v);
    }
    return 0;
}
