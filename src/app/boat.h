/* boat.h - the swell program's demo boat (issue 18): an object of the application's, as an
 * embedding program would have one: a generated mesh (hull, deck, cabin, mast; no asset files),
 * sailing at a set speed and heading, floating on the sea the renderer draws by the CPU query
 * (heave, pitch and roll from four hull points, geometry/sea.h), drawn into the renderer's
 * reflection pass and then over the sea, depth-tested against it.
 */
#ifndef SWELL_BOAT_H
#define SWELL_BOAT_H

#include "swell.h"

#define BOAT_LENGTH_M 9.0         /* overall, bow to transom */
#define BOAT_BEAM_M 3.0
#define BOAT_HEIGHT_M 3.0         /* the cabin's roof above the water (the mast is higher) */
#define BOAT_MAST_M 7.0

struct boat_desc {
    double x0, y0;                /* where it is at t0_s, m */
    double t0_s;
    float heading_deg;            /* its course, CCW from east */
    float speed_mps;              /* its speed through the water, m/s (0: at rest) */
};

/* Where it floats at a time: the waterline centre, its attitude, its model matrices. */
struct boat_pose {
    double pos[3];                /* world, m: heave in pos[2] */
    float pitch_deg, roll_deg;    /* bow up, port side up */
    float rot[9];                 /* boat frame -> world, column-major */
};

struct boat;

/* Its program (glapp.h; swell_tier: the ocean's, for the shader labels) and mesh. */
int  boat_create(const struct boat_desc *d, int swell_tier, struct boat **out,
                 struct swell_err *err);
/* Its pose at t_s on the sea (detile as the ocean draws it, swell_ocean_stats): the water
 * under its bow, stern and both sides at mid-length by swell_sea_sample, low-passed to waves
 * longer than the hull; heave the mean, pitch and roll their slopes. */
int  boat_pose_at(struct boat *b, const swell_sea *sea, int detile, double t_s,
                  struct swell_err *err);
const struct boat_pose *boat_pose(const struct boat *b);
const struct boat_desc *boat_get_desc(const struct boat *b);
/* Draw it with a view (world-to-eye rotation, column-major) and projection relative to the eye
 * at eye (the camera's, or a pass's), lit by the sun (towards it, world). attenuation_per_m >
 * 0 (a refraction pass's): colour times alpha = exp(it z) at each point's height z < 0, the
 * water's transmittance down to it (what lies above the water is cut by the pass); 0: alpha 1.
 * Depth-tested with GL_LEQUAL; no culling; leaves its program and buffer bound. */
void boat_draw(const struct boat *b, const float view[16], const float proj[16],
               const double eye[3], const float sun_dir[3], float attenuation_per_m);
void boat_destroy(struct boat *b);

#endif
