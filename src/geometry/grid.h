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
#include "core/camera.h"
#include "core/err.h"
#include "tables/stream.h"
#include "tables/tables.h"

/* Vertex layout, floats: displaced position (3), rest position on the sea plane (2), mean
 * slope of the CPU patterns (2), resolved slope variance of the CPU patterns (2), Dupuy k mean
 * and variance of the CPU patterns (2), the wave mask's amplitude at the rest position
 * (grid_set_mask; else padding) (48 bytes a vertex, whole vectors). */
enum grid_attr {
    GRID_A_POS = 0, GRID_A_REST = 3, GRID_A_SLOPE = 5, GRID_A_SVAR = 7, GRID_A_K = 9,
    GRID_A_PAD = 11, GRID_FLOATS = 12
};

/* The geometry of the sea: Bruneton's projected grid, or Hu's near and far patches. */
enum geometry_kind { GEOMETRY_GRID = 0, GEOMETRY_PATCHES, GEOMETRY_COUNT };
const char *geometry_kind_name(int g);          /* "grid", "patches" */
int geometry_kind_from_name(const char *name);  /* GEOMETRY_* or -1 */

struct grid_desc {
    const struct swell_tables *tables;  /* not owned */
    int kind;                 /* enum geometry_kind */
    int w, h;                 /* projected grid vertices; default 96 x 64 (cells of about 13 x 11 pixels at 1280x720) */
    unsigned cpu_patterns;    /* bit i: pattern i's slope/whitecap moments resolved per vertex */
    unsigned k_patterns;      /* bit i (not a CPU pattern): its whitecap moments alone resolved
                               * per vertex (low quality's fragment-shader patterns, whose
                               * whitecaps no fragment shader fetches) */
    int no_detile;            /* 1: each pattern read once, at no offset (detile.h): its tile
                               * repeats, at the CPU cost before the lattice (swell --detile off) */
};

struct grid;

int  grid_create(const struct grid_desc *d, struct grid **out, struct swell_err *err);
void grid_destroy(struct grid *g);

int grid_vertex_count(const struct grid *g);
int grid_index_count(const struct grid *g);
const uint16_t *grid_indices(const struct grid *g);

/* Per frame: fill verts[grid_vertex_count * GRID_FLOATS] for the frame's camera (its far plane,
 * field of view and basis bound the projected grid's frustum). Returns the number of indices to
 * draw (0 when no sea is in view). Allocates nothing. */
int grid_update(struct grid *g, const struct camera_frame *view, double t_s, float *verts);

/* A Kelvin wake whose heights grid_update adds to the displaced vertices (issue 18; kelvin.h,
 * render/wake.c): each vertex gets kelvin_map_height at its rest position in the hull's frame,
 * at its footprint. hull_xy is the hull's middle less the camera's position (the frame's
 * camera), fwd its course's unit vector. The projected grid's range widens by the map's
 * largest height (coverage). */
struct kelvin_map;
struct grid_wake {
    const struct kelvin_map *map;   /* not owned; NULL: no wake */
    double hull_xy[2];
    double fwd[2];
};
void grid_set_wake(struct grid *g, const struct grid_wake *w);   /* NULL: none */

/* A coarse mask of the waves' amplitude (mask.h): grid_update scales each vertex's
 * displacement and the CPU patterns' slopes by its amplitude a at the vertex's rest position
 * (world: the frame camera's position plus it), their slope variances by a^2, and writes a to
 * GRID_A_PAD (ocean.vert takes it to scale the variances it adds). on 0: none of it (the pad
 * left as it is); on 1 with m NULL: a = 1 everywhere. m's bytes must outlive its use. */
struct wave_mask;
void grid_set_mask(struct grid *g, int on, const struct wave_mask *m);

/* Rows of triangles in draw order (far to near): the projected grid's h - 1 rows of cells, or
 * the far rings then the near patch's rows. After grid_update, row r spans indices
 * [*first, *first + *count) and *dist2_min is the smallest squared horizontal distance (m^2)
 * from the camera of its vertices' rest positions; the renderer derives the pixel footprint
 * from it and picks per run of rows which patterns still need a texture fetch. */
int grid_row_count(const struct grid *g);
void grid_row_span(const struct grid *g, int row, int *first, int *count, float *dist2_min);

/* The projected grid's frame for a camera (grid_project.c), for building the grid in a vertex
 * shader.
 * The grid is cast from a projector at the camera's x, y, alt_ray above the sea plane and
 * pitched down by -pitch (radians) (Johanson 2004's projector; Bruneton 2010 §3 casts from the
 * camera itself): grid parameter (u, v) in [0, 1]^2 is the ray fwd + tan(phi(u)) right +
 * grid_row_tan(v) up. Columns: phi piecewise linear over col_ang (left edge, the screen's left
 * and right edges, right edge), col_split[0..1] of them at the inner two knots (grid_warp).
 * Rows: the first row_split of them over the screen, in the camera's depression angle dc
 * (row_cam: the top row's and the screen bottom's, for a camera row_h above the sea plane),
 * so their spacing on the screen is the camera's whatever the projector: at u in [0, 1) of
 * that share, dc = row_cam[0] + x(u), evenly spaced (x = row_a u) except towards the horizon,
 * where row_h / tan dc, the distance, halves from row to row (x = dc0 (2^(u / delta) - 1),
 * delta one row, up to row_ustar, C1 there; grid_row_tan): rows evenly in dc left the top
 * row at dmax and the next one 10-15x nearer from a boat, and each triangle between them took
 * its varyings mostly from the near vertex (perspective-correct interpolation), so the sun's
 * glitter stepped by 45x per column there. The rest evenly in the projector's angle from
 * row_margin[0] (the screen bottom) to row_margin[1].
 * Rays meet the
 * plane alt_ray below the projector, else end at dmax. The range bounds every sea-plane point
 * whose displaced image can reach the camera's frustum (coverage by construction, grid_project.c).
 * alt is the camera's height above the sea plane. */
struct grid_projection {
    double fwd[3], right[3], up[3];
    double alt, alt_ray, dmax, pitch;
    double col_ang[4], col_split[2];
    double row_margin[2], row_cam[2], row_h, row_split;
    double row_inv_delta, row_ustar, row_a;   /* the horizon rows (above); row_ustar 0: none */
    double row_xs;                            /* x(row_ustar) = dc0 (2^(u* / delta) - 1) */
};

/* The piecewise-linear angle at parameter x in [0, 1] through a[0] at 0, a[1] at s[0], ...,
 * a[n - 1] at 1 (n - 2 interior knots s[], increasing). */
double grid_warp(double x, const double *a, const double *s, int n);

/* tan of the projector angle of grid row parameter v in [0, 1] (see struct grid_projection). */
double grid_row_tan(const struct grid_projection *p, double v);

/* Fill p for the camera and the rows' distances (grid_row_span) without building vertices.
 * Returns the number of indices to draw, 0 when no sea is in view (or for patches). */
int grid_projection(struct grid *g, const struct camera_frame *view, struct grid_projection *p);

/* Texture-coordinate offset of pattern i for this camera: frac(camera_xy / L_i), wrapped in
 * double so an hour in looks like the first second; uv = offset + rest_xy / L_i. */
void grid_uv_offset(const struct swell_tables *t, int pattern, const struct camera *cam,
                    float out[2]);

/* The wavelength eq. 2 weighs pattern i's band by (grid.c and ocean.vert's VTF grid). */
float grid_band_wavelength(const struct swell_pattern_info *pi);

/* Mip level of a CPU pattern's moment chain for a footprint of r level-0 texels: the level
 * whose texel matches it, floor(log2 r) for r >= 2, else 0, at most levels - 1. */
int grid_mip_level(float r, int levels);

/* The first level of a k-only pattern's whitecap table from which grid_update takes the top
 * texel instead of sampling (its coarser levels' means hold under 2 % of the foam memory's
 * variance). */
int grid_k_flat_level(const struct swell_table *wc);

/* Bruneton eq. 2's bounds: waves shorter than Nmin cells are cancelled, kept in full from
 * Nmax cells up (the grid's cells; the CPU query's low-pass, sea.h). */
#define GRID_FILTER_NMIN 2.0f
#define GRID_FILTER_NMAX 4.0f

/* Bruneton 2010 eq. 2 filter weight w(a, b, x) = 3 x'^2 - 2 x'^3, x' = clamp((x-a)/(b-a)). */
float grid_filter_weight(float a, float b, float x);

#endif
