/* stream.h - loop-frame interpolation on the CPU (DESIGN.md gles2-min): every frame, layers f and
 * f+1 of a looping RGBA8 table are blended into one image per table (all mip levels; the blend of
 * the mips equals the mips of the blend because both are linear), which the renderer streams into
 * a single texture and the geometry samples for the CPU-resolved patterns.
 */
#ifndef SWELL_STREAM_H
#define SWELL_STREAM_H

#include <stddef.h>
#include <stdint.h>
#include "tables/tables.h"

/* Blend weight resolution: the weight between two loop frames is quantised to 1/STREAM_W_ONE so
 * time t and t + T give bit-identical frames (the phase is an integer, see stream_loop_phase). */
#define STREAM_W_ONE 256

struct stream_phase {
    int f0, f1;     /* loop frames blended: f1 = (f0 + 1) mod F */
    int w;          /* weight of f1 in [0, STREAM_W_ONE) */
};

/* Phase in the loop of `frames` frames over period_s at time t_s (any sign, any size). */
void stream_loop_phase(double t_s, double period_s, int frames, struct stream_phase *out);
/* The same for pattern i of set s at time t_s: its loop T_i = T / m (bake.c) taken as m
 * turns of the set's loop T, from t mod T, so t and t + kT agree for any k. (t mod T_i drifted:
 * T_i = 16/3 s is not a float, and at a day the frames were 0.0005 of a loop off.) */
void stream_pattern_phase(const struct swell_tables *s, int pattern, double t_s, int frames,
                          struct stream_phase *out);

/* Bytes of one blended image of t (one layer, every level) and the offset of a level in it. */
size_t stream_blended_bytes(const struct swell_table *t);
size_t stream_level_offset(const struct swell_table *t, int level);

/* dst = layer f0 + (layer f1 - layer f0) * w / STREAM_W_ONE, byte-wise, rounded to nearest, for
 * every level of an RGBA8 table. */
void stream_blend(const struct swell_table *t, const struct stream_phase *ph, uint8_t *dst);
/* stream_blend of the levels from `from` up alone, at their offsets in dst (where the GPU
 * blends the finer ones, render/stream_gpu.c) */
void stream_blend_coarse(const struct swell_table *t, const struct stream_phase *ph, int from,
                         uint8_t *dst);

/* A whitecap table's blend (TABLE_WHITECAP: m, <m^2>, 0, k) with, in channel 2 of levels 0 and
 * 1, the blend's own variance of the foam memory: a texel that is m0 in one frame and m1 in the
 * next is, blended, a mixture of variance (1 - w) w (m1 - m0)^2 about its mean. The fetched
 * <m^2> - <m>^2 holds it too, but near the camera the renderer takes level 0's mean
 * within-texel variance in place of the fetched one (its rounding and bilinear mix draw dots
 * and blocks, lod.c wc_trust_terms), and without this the blend averaged the foam memory's rare
 * deep minima away between frames (test_render test_foam_amount). The byte is
 * B = 4 (1 - w) w d^2 / 255 (d the frames' channel-0 bytes' difference; in 16 bits: d^2 / 256
 * times 4 (1 - w) w 256 / 255 in 1/256ths), so B / 255 times STREAM_WC_MIX_SCALE(s), s the
 * channel-0 scale, is that variance. Levels from 2 up keep 0 there (read where the fetched
 * variance is trusted whole). */
#define STREAM_WC_MIX_SCALE(s) (0.25f * (s) * (s))
void stream_blend_whitecap(const struct swell_table *t, const struct stream_phase *ph,
                           uint8_t *dst);
/* stream_blend_whitecap's second pass alone: channel 2 of levels 0-1 over stream_blend's bytes
 * (apart so the bench's callgrind counts it beside stream_blend, tools/bench.sh cg_own) */
void stream_wc_blend_var(const struct swell_table *t, const struct stream_phase *ph,
                         uint8_t *dst);
/* The 1/256ths factor of weight w (0..STREAM_W_ONE) of stream_blend_whitecap: 4 (1 - w) w 256 /
 * 255 of the 16-bit squares' high bytes. */
uint16_t stream_wc_mix_factor(int w);
/* stream_blend_whitecap of the levels from `from` up alone (as stream_blend_coarse) */
void stream_blend_whitecap_coarse(const struct swell_table *t, const struct stream_phase *ph,
                                  int from, uint8_t *dst);

#endif
