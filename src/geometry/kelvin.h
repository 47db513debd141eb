/* kelvin.h - the Kelvin wake of a hull moving at constant speed (issue 18; Bruneton et al.
 * 2010 §6 and Fig. 12: local waves added with their slopes and slope variances), and the map
 * of it the renderer reads (render/wake.c).
 *
 * The wake is the stationary-phase solution of a point source moving over deep water (Kelvin
 * 1887; Lighthill, Waves in Fluids, §3.10). Seen from the source, a wave travelling at angle
 * theta to the track stands still when its phase speed is U cos theta, so k(theta) =
 * g / (U^2 cos^2 theta). A point r behind the source, at angle alpha to the track, gets the
 * waves whose phase phi = (g r / U^2) cos(theta - alpha) / cos^2 theta is stationary in theta:
 * tan(theta - alpha) = 2 tan theta, i.e. 2 a t^2 + t + a = 0 with t = tan theta, a = tan alpha,
 * real only for a^2 <= 1/8: the wake's half-angle asin(1/3) = 19.47 deg, whatever the speed.
 * Of the two roots the smaller |t| is the transverse wave, the larger the divergent one. Each
 * contributes A(theta) sqrt(2 pi / |phi''|) cos(phi +- pi/4); at the cusp line phi'' = 0 and
 * the amplitude is held at Airy's scale (|phi'''| r)^(-1/3) instead of diverging.
 *
 * Not in the papers, stated here: the source strength (a height of KELVIN_HEIGHT_COEF L Fr^2 for
 * the transverse wave one hull length behind the bow, Fr^2 = U^2 / (g L)); the hull's filter
 * of short waves, exp(-(k B / 4)^2) for beam B (a source of the beam's size makes no waves much
 * shorter than it); the near field faded in over a hull length; and the foam: the stern's
 * turbulent strip (the beam wide, slowly widening) and where the wake's slope exceeds a
 * breaking slope, both decaying with the time since the hull passed by Tessendorf et al. 2023's
 * half-life (eq. 7-8).
 */
#ifndef SWELL_KELVIN_H
#define SWELL_KELVIN_H

#include <stddef.h>
#include <stdint.h>
#include "core/err.h"

#define KELVIN_HALF_ANGLE_DEG 19.4712206   /* asin(1/3) */
#define KELVIN_HEIGHT_COEF 0.2
#define KELVIN_MIN_SPEED_MPS SWELL_WAKE_SPEED_MIN_MPS   /* swell.h */
#define KELVIN_MAX_SPEED_MPS 30.0

struct kelvin_desc {
    double speed_mps;           /* through the water, KELVIN_MIN..MAX_SPEED_MPS */
    double hull_length_m;       /* bow to stern, 1..400 */
    double beam_m;              /* 0.2..100 */
    double foam_half_life_s;    /* Tessendorf 2023 eq. 7-8; 0.05..60 */
};

/* hull_length_m 0: 9 m; beam_m 0: a third of the length (swell.h swell_wake's defaults). */
void kelvin_desc_defaults(struct kelvin_desc *d);

/* Refused with a message naming the field and its range: 0, else SWELL_E_ARG. */
int kelvin_check(const struct kelvin_desc *d, struct swell_err *err);

/* The wake at (x, y) in the hull's frame, m: x forward along the track from the hull's middle,
 * y to port. Height eta, m; slope (d eta / dx, d eta / dy); foam coverage 0..1. */
struct kelvin_sample {
    double eta;
    double slope[2];
    double foam;
};
void kelvin_eval(const struct kelvin_desc *d, double x, double y, struct kelvin_sample *out);

/* The map covers the wedge, finer near the hull: with X = hull/2 - x the distance behind the
 * bow, P = (X + ahead_m) / span_m and Q = y / span_m (P in [0, 1]),
 *     u = (sqrt(P + e) - sqrt(e)) / (sqrt(1 + e) - sqrt(e)),   v = 1/2 + Q / (spread (P + spread_offset)),
 * e = u_offset, i.e. along the track the texels grow with the square root of the distance from
 * a hull length before the map's front (a fifth of a metre at the bow of a 9 m hull at 5 m/s,
 * 1.3 m at the map's end; no singular derivative for the fetch's LOD), across it the map spans
 * spread / 2 (1.1 x tan 19.47 deg) of the distance from a point spread_offset span_m before the
 * map's front (the hull's own width at the bow). RGBA8 per texel: R, G the mean slope (d/dx,
 * d/dy) as the byte 128 + 127 s / slope_scale; B the mean square slope |s|^2 / slope_scale^2
 * (with R, G the slope variance within the texel, Bruneton §4.1); A the foam coverage. Its
 * edges are the still sea (slopes 0), so a clamped fetch beyond it adds nothing. Levels: a mip
 * chain of box means of the moments in (u, v) (each quantised from float means), level 0 a
 * 2 x 2 supersampled box. */
#define KELVIN_MAP_LEVELS_MAX 16
struct kelvin_map {
    int w, h, levels;
    double ahead_m, span_m;     /* the map's front before the bow, its length from there */
    double u_offset, spread, spread_offset;
    double slope_scale;         /* the largest root mean square slope of a texel */
    double hull_length_m;       /* the hull's it was built for */
    uint8_t *rgba;              /* every level, level 0 first */
    float *height;              /* the mean height of each texel, m: every level, level 0 first,
                                 * level l at offset[l] / 4 (the geometry's) */
    double height_max_m;        /* the largest |height| of level 0 */
    size_t offset[KELVIN_MAP_LEVELS_MAX];   /* each level's first byte in rgba */
};
/* w x h texels (powers of two, 16..4096). The map's length: the wake's first 24 transverse
 * wavelengths (2 pi U^2 / g each) behind the hull's middle, at least 6 hull lengths; the
 * wake's amplitude fades to 0 over its last fifth. */
int kelvin_map_build(const struct kelvin_desc *d, int w, int h, struct kelvin_map *out,
                     struct swell_err *err);
void kelvin_map_free(struct kelvin_map *m);
/* The wake's height at hull-frame (x, y), m, read from the map's heights as from a mipmapped
 * texture: bilinear at the two levels around the footprint (foot_m, the sea's extent a vertex
 * stands for; the level whose texel's longer side is half of it), blended linearly, so waves
 * shorter than a few footprints average out and no level steps (Bruneton eq. 2's concern for
 * the patterns). 0 off the map. */
float kelvin_map_height(const struct kelvin_map *m, double x, double y, float foot_m);
/* The hull-frame point (x, y) of map coordinates (u, v). */
void kelvin_map_point(const struct kelvin_map *m, double hull_length_m, double u, double v,
                      double *x, double *y);

#endif
