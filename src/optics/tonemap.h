/* tonemap.h - the display transform, as common.glsl tone_map (test_glsl compares the two):
 * Reinhard on the largest channel of a radiance already scaled by the exposure, x / (1 + max),
 * so the channels keep their ratios (the hue of a sunset glitter stays orange where a
 * per-channel curve turned it white) and none exceeds 1; then gamma 2 (sqrt) as the sRGB
 * transfer. */
#ifndef SWELL_TONEMAP_H
#define SWELL_TONEMAP_H

#include <math.h>

static inline void tone_map_rgb(const float in[3], float out[3])
{
    float x[3], m = 0.0f;
    for (int c = 0; c < 3; c++) {
        x[c] = fminf(fmaxf(in[c], 0.0f), 1.0e4f);
        m = fmaxf(m, x[c]);
    }
    for (int c = 0; c < 3; c++)
        out[c] = sqrtf(x[c] / (1.0f + m));
}

#endif
