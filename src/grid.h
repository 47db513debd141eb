/* grid.h - ocean geometry on the CPU for tiers without vertex texture fetch (DESIGN.md):
 * the projected grid (Bruneton 2010 §3) or near/far patches (Hu 2006 §3), displaced by the
 * baked looping displacement tables with Bruneton eq. 2 filter weights, plus the per-vertex
 * slope and whitecap moments of the patterns the fragment shader has no texture unit for.
 *
 * Everything is camera-relative (camera.h): positions are world minus camera, metres.
 */
#ifndef SWELL_GRID_H
#define SWELL_GRID_H

#include <stdint.h>
#include <cglm/cglm.h>
#include "camera.h"
#include "err.h"
#include "stream.h"
#include "tables.h"

/* Vertex layout, floats: displaced position (3), rest position on the sea plane (2), mean
 * slope of the CPU patterns (2), resolved slope variance of the CPU patterns (2), Dupuy k mean
 * and variance of the CPU patterns (2), foam opacity of the CPU patterns (1). */
enum grid_attr {
    GRID_A_POS = 0, GRID_A_REST = 3, GRID_A_SLOPE = 5, GRID_A_SVAR = 7, GRID_A_K = 9,
    GRID_A_FOAM = 11, GRID_FLOATS = 12
};

struct grid_desc {
    const struct swell_tables *tables;  /* not owned */
    int kind;                 /* enum geometry_kind (renderer.h): 0 projected grid, 1 patches */
    int w, h;                 /* projected grid vertices; default 96 x 64 (cells of about 13 x 11 pixels at 1280x720) */
    unsigned cpu_patterns;    /* bit i: pattern i's slope/whitecap moments resolved per vertex */
};

struct grid;

int  grid_create(const struct grid_desc *d, struct grid **out, struct swell_err *err);
void grid_destroy(struct grid *g);

int grid_vertex_count(const struct grid *g);
int grid_index_count(const struct grid *g);
const uint16_t *grid_indices(const struct grid *g);

/* Per frame: fill verts[grid_vertex_count * GRID_FLOATS] for the camera (proj gives the far
 * plane and the projected grid's frustum). Returns the number of indices to draw (0 when no sea
 * is in view). Allocates nothing. */
int grid_update(struct grid *g, const struct camera *cam, float aspect, double t_s, float *verts);

/* Rows of triangles in draw order (far to near): the projected grid's h - 1 rows of cells, or
 * the far rings then the near patch's rows. After grid_update, row r spans indices
 * [*first, *first + *count) and *dist2_min is the smallest squared horizontal distance (m^2)
 * from the camera of its vertices' rest positions; the renderer derives the pixel footprint
 * from it and picks per run of rows which patterns still need a texture fetch. */
int grid_row_count(const struct grid *g);
void grid_row_span(const struct grid *g, int row, int *first, int *count, float *dist2_min);

/* The projected grid's frame for a camera (grid.c), for building the grid in a vertex shader:
 * ray(sx, sy) = fwd + sx tx right + sy ty up, NDC sx in [-1 - margin, 1 + margin], sy from top
 * (the horizon, or above the screen) to bot; rays meet z = -alt_ray, else end at dmax. */
struct grid_projection {
    double fwd[3], right[3], up[3];
    double tx, ty, alt, alt_ray, dmax, margin, top, bot;
};

/* Fill p for the camera and the rows' distances (grid_row_span) without building vertices.
 * Returns the number of indices to draw, 0 when no sea is in view (or for patches). */
int grid_projection(struct grid *g, const struct camera *cam, float aspect,
                    struct grid_projection *p);

/* Texture-coordinate offset of pattern i for this camera: frac(camera_xy / L_i), wrapped in
 * double so an hour in looks like the first second; uv = offset + rest_xy / L_i. */
void grid_uv_offset(const struct swell_tables *t, int pattern, const struct camera *cam,
                    float out[2]);

/* The wavelength eq. 2 weighs pattern i's band by (grid.c and ocean.vert's VTF grid). */
float grid_band_wavelength(const struct swell_pattern_info *pi);

/* Mip level of a CPU pattern's moment chain for a footprint of r level-0 texels: the level
 * whose texel matches it, floor(log2 r) for r >= 2, else 0, at most levels - 1. */
int grid_mip_level(float r, int levels);

/* Bruneton 2010 eq. 2 filter weight w(a, b, x) = 3 x'^2 - 2 x'^3, x' = clamp((x-a)/(b-a)). */
float grid_filter_weight(float a, float b, float x);

#endif
