/* quantize.h - float RGBA images -> mip chains -> RGBA8 with per-channel scale/bias (the
 * gles2-min table format, tables.h), or RGBA16F for tiers with half floats.
 *
 * Mips are 2x2 box filters of the float data: every channel swell stores is linear in what the
 * renderer filters (slopes, their squares, Dupuy's k and k^2, opacity), so a mip texel is the
 * footprint's mean - exactly what the shaders assume (prefilter moments, never derived values).
 */
#ifndef SWELL_QUANTIZE_H
#define SWELL_QUANTIZE_H

#include <stddef.h>
#include <stdint.h>
#include "core/err.h"
#include "tables/tables.h"

/* 2x2 box filter of a w x h RGBA float image (w, h powers of two, >= 2 in the halved axis or 1)
 * into dst of max(1,w/2) x max(1,h/2). */
void quantize_downsample(const float *src, int w, int h, float *dst);

/* Fill the float mip chain in KTX order (level-major, then layer) from level-0 layers:
 * `chain` holds all levels; level 0 of every layer must already be in place. */
void quantize_build_mips(float *chain, int w, int h, int layers, int levels);

/* Number of floats in a chain (4 per texel, all levels, all layers). */
size_t quantize_chain_floats(int w, int h, int layers, int levels);

/* t has its geometry set (width, height, layers, levels, format) and data == NULL: allocate and
 * fill from a float chain in the same order. RGBA8: scale/bias per channel from the chain's
 * min/max over all levels and layers (a constant channel gets scale 1), round to nearest, so
 * |dequantised - value| <= scale / 510. RGBA16F: IEEE half, round to nearest even. */
int quantize_table(struct swell_table *t, const float *chain, struct swell_err *err);

/* Dequantise texel c of RGBA8 byte v. */
static inline float quantize_decode(const struct swell_table *t, int c, uint8_t v)
{
    return t->bias[c] + t->scale[c] * ((float)v * (1.0f / 255.0f));
}

uint16_t quantize_half_from_float(float f);
float quantize_float_from_half(uint16_t h);

#endif
