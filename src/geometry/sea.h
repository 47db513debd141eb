/* sea.h - the sea on the CPU: the surface the renderer draws, at a world point and time.
 *
 * Sums every pattern's baked displacement table (Dupuy 2012 eq. 1: the patterns add), sampled
 * bilinearly with GL's texel-centre convention and wrap, the two loop frames blended at the
 * renderer's own phase (stream.h), so it is the displacement the GPU draws at full eq. 2
 * weight (where the grid's cells resolve every pattern, as next to the camera). World x east,
 * y north, z up, metres (camera.h).
 */
#ifndef SWELL_SEA_H
#define SWELL_SEA_H

#include "tables/tables.h"

/* Choppy displacement (Dx, Dy, Dz) of the sea-plane point (x, y) at time t_s, m. detile: each
 * pattern read at its lattice's three random offsets (detile.h), as the renderer draws it by
 * default; 0: once at no offset (renderer_desc no_detile). */
void sea_displacement(const struct swell_tables *t, int detile, double x, double y, double t_s,
                      double out[3]);

/* Height of the displaced surface above the world point (x, y), m: the rest point p with
 * p + D_xy(p) = (x, y) found by fixed-point iteration (the choppy map contracts where the
 * surface does not fold), then D_z(p). */
double sea_surface_height(const struct swell_tables *t, int detile, double x, double y,
                          double t_s);

#endif
