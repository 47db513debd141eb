/* detile.h - no pattern repeats on its tile: each pattern table is read at three random offsets
 * blended across a lattice (issue 13 item 2; the tiling-and-blending of Heitz & Neyret 2018,
 * "High-performance by-example noise using a histogram-preserving blending operator").
 *
 * A pattern's waves are a Gaussian random field periodic on its tile L. Lay a lattice of
 * DETILE_CELLS x DETILE_CELLS square cells per tile over uv = world / L, each cell split along
 * its diagonal (0,0)-(1,1) into two triangles; give every lattice vertex a random offset
 * o = (b >> 3, b & 7) / 8 tiles from its hash byte b < 64: one of 8 x 8 points spread over the
 * tile, so two vertices' taps are independent samples of every wave (an offset along a line
 * left the waves crossing that line correlated: one tile over, 0.15; test_detile), and a whole
 * number of texels of every table of 8 texels or more (the CPU grid shares one bilinear
 * footprint's fractions between its three taps). A point reads the
 * table at uv + o_j of its triangle's three vertices and blends with its barycentric weights
 * w_j normalised to sum w_j^2 = 1:
 *
 *     f(uv) = sum_j n w_j f0(uv + o_j),   n = 1 / sqrt(sum_j w_j^2).
 *
 * The taps are independent samples of one Gaussian field, so the blend has the table's mean
 * (0), variance and spectrum wherever the weights vary slowly (Heitz & Neyret §3), and it is
 * continuous: a vertex's weight is 0 on the edges where it leaves the triangle. Two points a
 * tile apart are two cells apart, in triangles with no vertex in common: independent offsets,
 * so the repetition is gone (test_tiling). Moments of the field blend the same way: a mean by
 * n w_j, a variance (a prefiltered second moment minus the mean squared) by (n w_j)^2; a field
 * whose mean mu is not 0 (the foam memory, bake.c) blends its deviation from mu.
 *
 * The offsets repeat after DETILE_N cells, DETILE_N / DETILE_CELLS = 64 tiles (25 km for a
 * 400 m pattern; where a tile spans 20 px, once per 1280 px); each pattern reads the hash
 * shifted by its own (7 i, 13 i). With 32 cells the storm's 70 m pattern repeated its foam
 * every 1.1 km, inside a 3 km nadir view (test_tiling r 0.27).
 *
 * One specification for every stage: the CPU grid and the CPU query (grid.c, sea.c) call
 * detile_taps; ocean.vert (vertex texture fetch) and ocean.frag read the same hash from the
 * renderer's atlas (detile_cell_table: per cell the bytes of its four corners) and compute the
 * same weights. The fragment stage also orders the taps by vertex colour ((x + y) mod 3, one of
 * each per triangle), so a tap changes its offset only where its weight is 0 and the implicit
 * mip level of its fetch stays the neighbours' (otherwise a 2x2 quad across a cell edge would
 * fetch the coarsest level at full weight: a grid of blurred lines).
 */
#ifndef SWELL_DETILE_H
#define SWELL_DETILE_H

#include <stddef.h>
#include <stdint.h>

/* Whether the renderer reads the patterns through this lattice (swell --detile): AUTO is ON in
 * high quality and OFF in low (Hu's single pass for the weakest GPUs, where the lattice would
 * cost 2-3.5x the frame on llvmpipe; docs/measurements.md), and OFF in high quality too where the driver
 * refuses more of its programs with the lattice than without (renderer.c renderer_create);
 * OFF reads each pattern once, at no offset, so its tiles repeat. */
enum detile_mode { DETILE_MODE_AUTO = 0, DETILE_MODE_ON, DETILE_MODE_OFF, DETILE_MODE_COUNT };
const char *detile_mode_name(int m);            /* "auto", "on", "off" */
int detile_mode_from_name(const char *name);    /* DETILE_MODE_* or -1 */

#define DETILE_CELLS 2            /* lattice cells per tile, per axis */
#define DETILE_N 128              /* the hash's period, cells (a power of two): 64 tiles */
#define DETILE_OFFSETS 8          /* an offset is (b >> 3, b & 7) / 8 tiles, b the hash byte */
#define DETILE_SHIFT_X 7          /* pattern i reads the hash at (x + 7 i, y + 13 i) */
#define DETILE_SHIFT_Y 13
#define DETILE_GAIN_MAX 1.7320508f /* sup of n sum_j w_j = sqrt(3): bounds the blend's extremes */

/* The hash byte (< DETILE_OFFSETS^2) of lattice vertex (x, y), any integers (modulo DETILE_N). */
uint8_t detile_hash(int x, int y);

/* All of them, out[y DETILE_N + x] (DETILE_N^2 bytes): what a caller of detile_taps_cell in a
 * loop passes instead of hashing per call. */
void detile_hash_table(uint8_t *out);

/* Per cell (x, y) of the DETILE_N x DETILE_N hash, RGBA8: the bytes of its corners (x, y),
 * (x + 1, y), (x, y + 1), (x + 1, y + 1); row y at out + y stride (stride >= 4 DETILE_N bytes). */
void detile_cell_table(uint8_t *out, size_t stride);

/* The three taps of pattern `pattern` at uv (tiles, world / L: any magnitude, in double so a
 * day's drift keeps its cell): weights w[j] (normalised, sum w^2 = 1) and offsets du[j], dv[j]
 * (tiles) in corner order (0,0), the middle vertex, (1,1). */
struct detile_taps {
    float w[3];
    float du[3], dv[3];
};
void detile_taps(int pattern, double u, double v, struct detile_taps *t);

/* The taps without the lattice (renderer_desc detile OFF): the first at no offset with weight
 * 1, the others weight 0. */
void detile_taps_off(struct detile_taps *t);

/* The same for a point given by its hash cell (hx, hy) (its lattice cell plus the pattern's
 * shift, any integers: taken modulo DETILE_N) and the position (fx, fy) in [0, 1) inside it:
 * what the camera-relative stages use, with detile_camera_shift. hash: detile_hash_table's, or
 * NULL (hashed per call). */
void detile_taps_cell(const uint8_t *hash, long hx, long hy, float fx, float fy,
                      struct detile_taps *t);

/* For the shaders, which take the cell of a camera-relative uv (frac(camera / L) + rest / L):
 * pattern `pattern`'s camera cell DETILE_CELLS floor(camera / L) (inv_l = 1 / L) as the shift
 * they add to a cell's index before the hash, out[0..1] = that plus the pattern's shift modulo
 * DETILE_N, and out[2] = the sum of its two coordinates modulo 3, for the vertex colours. */
void detile_camera_shift(int pattern, double cam_x, double cam_y, double inv_l, float out[3]);

#endif
