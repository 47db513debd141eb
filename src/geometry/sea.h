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

/* A query of the water above a point, optionally low-passed: pattern i enters with weight[i],
 * Bruneton eq. 2's weight of its band wavelength over cells of min_wavelength / GRID_FILTER_NMIN
 * (1 for every pattern without a minimum), as the grid weighs what its cells cannot hold. */
struct sea_query {
    int detile;
    int height_only;            /* 1: sea_query_point fills height and disp alone (normal up,
                                 * velocity 0): one displacement instead of five */
    float weight[SWELL_MAX_PATTERNS];
};
void sea_query_init(const struct swell_tables *t, int detile, double min_wavelength_m,
                    struct sea_query *q);

struct sea_point {
    double height;              /* of the displaced surface above (x, y), m */
    double disp[3];             /* displacement of the rest point that lands there, m */
    double normal[3];           /* unit normal of the displaced surface there */
    double velocity[3];         /* d/dt of that rest point's displacement, m/s: the loop
                                 * frames' difference over their spacing (the drawn motion) */
};
/* The water above (x, y) at t_s: the rest point by sea_surface_height's inversion, the normal
 * from central differences of the displaced surface over a quarter of the finest texel. */
void sea_query_point(const struct swell_tables *t, const struct sea_query *q, double x, double y,
                     double t_s, struct sea_point *out);

#endif
