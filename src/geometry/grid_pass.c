/* grid_pass.c - grid_update (grid.h): per frame, the rest positions (grid_project.c), then the
 * per-vertex passes over them in fixed blocks of VBLK vertices that -O2 vectorises: the
 * displacement of every pattern with Bruneton 2010 eq. 2 weights, read at the lattice's three
 * offsets (detile.h), and the slope and whitecap moments of the CPU and k-only patterns at the
 * mip level of each vertex's footprint (Bruneton §4.1, Dupuy eq. 6-8), then the vertices
 * written. It owns nothing across frames: the per-frame constants are on the stack, the
 * arrays are struct grid's. */
#include <math.h>
#include <string.h>
#include "geometry/grid_internal.h"
#include "geometry/kelvin.h"

#define COORD_MAX 1073741824.0f  /* 2^30: float texel coordinates are clamped to +-COORD_MAX */

/* One frame's constants of a pattern's lattice (detile.h): a rest point's cell coordinates are
 * q = q0 + rest qk (camera-relative, float), its hash cell floor(q) + sh (the shaders' shift,
 * detile_camera_shift: the camera's cell and the pattern's shift modulo DETILE_N). */
struct detile_frame {
    const uint8_t *hash;      /* detile_hash_table's (the grid's copy); NULL: no lattice, one tap
                                 at no offset (grid_desc no_detile) */
    float q0x, q0y, qk;
    int shx, shy;
};

static void detile_frame_set(struct detile_frame *f, const uint8_t *hash, int pattern,
                             double inv_l, const struct camera *cam)
{
    float sh[3];
    f->hash = hash;
    if (!hash)
        return;
    f->qk = (float)(inv_l * DETILE_CELLS);
    double ux = cam->pos[0] * inv_l, uy = cam->pos[1] * inv_l;
    /* cell q = DETILE_CELLS (floor(cam / L) + frac(cam / L) + rest / L) */
    f->q0x = (float)((ux - floor(ux)) * DETILE_CELLS);
    f->q0y = (float)((uy - floor(uy)) * DETILE_CELLS);
    detile_camera_shift(pattern, cam->pos[0], cam->pos[1], inv_l, sh);
    f->shx = (int)sh[0];
    f->shy = (int)sh[1];
}

static inline void detile_at(const struct detile_frame *f, float rx, float ry,
                             struct detile_taps *t)
{
    if (!f->hash) {
        detile_taps_off(t);
        return;
    }
    float qx = f->q0x + rx * f->qk, qy = f->q0y + ry * f->qk;
    /* floor by conversion (floorf is a call on x86-64's SSE2); |q| < 2^31 where a pattern's
     * eq. 2 weight is not 0 (a cell is half a tile) */
    int ix = (int)qx, iy = (int)qy;
    ix -= qx < (float)ix;
    iy -= qy < (float)iy;
    detile_taps_cell(f->hash, (long)ix + f->shx, (long)iy + f->shy, qx - (float)ix,
                     qy - (float)iy, t);
}

/* One frame's constants of a CPU pattern for the moment pass: texel coordinates of moment level
 * l are x = mx0[l] + rest_x mk[l] (the uv offset and the half-texel shift folded in, in double). */
struct pattern_frame {
    struct grid_pattern *p;
    struct detile_frame dt;   /* its lattice (detile.h) */
    double mx0[16], my0[16], mk[16];
    float lev_k;              /* level-0 texels per metre of footprint: width / L_i */
    float u0x, u0y;           /* level-0 texel coordinates of the camera: the uv offset times the
                               * width (level l's are 2^-l of level 0's, less half a texel) */
};

/* One frame's constants of a pattern that displaces some vertex (eq. 2 weight > 0): texel
 * coordinates of its displacement image x = x0 + rest_x kx, in float. */
struct disp_frame {
    struct f4_image *im;      /* the pattern's displacement image */
    const float *data;        /* its texels */
    float x0, y0, kx, ky;
    float lambda_m;           /* eq. 2's characteristic wavelength, m */
    struct detile_frame dt;   /* its lattice (detile.h) */
    float foot_zero;          /* footprints from this one up give weight 0, m */
    float coord_max;          /* COORD_MAX */
    int wm, hm, wshift;
    size_t stride;            /* bytes per padded image row */
};

/* Each block's smallest footprint: eq. 2's weight falls with the footprint, so a pattern whose
 * weight is 0 there has weight 0 for the whole block. n is a multiple of VBLK. */
static void block_foot(int n, const float *restrict foot, float *restrict out)
{
    for (int b = 0; b < n; b += VBLK) {
        float m[VBLK / 2];
        for (int e = 0; e < VBLK / 2; e++)
            m[e] = foot[b + e + VBLK / 2] < foot[b + e] ? foot[b + e + VBLK / 2] : foot[b + e];
        for (int e = 1; e < VBLK / 2; e++)
            m[0] = m[e] < m[0] ? m[e] : m[0];
        out[b / VBLK] = m[0];
    }
}

/* For the vertices of the nr runs [run[2r], run[2r + 1]) (whole blocks): the weights of
 * Bruneton eq. 2 for each vertex's cell of size foot (times the fade), the texel coordinates
 * x = x0 + rest_x kx in float, floored (rest positions are camera-relative floats and x0 a
 * wrapped offset: float keeps what the inputs hold), and the first texels (oix, oiy) of the
 * bilinear footprints. By quads: a fixed loop of 4 over restrict-qualified arrays is what -O2's
 * vectorisers turn into straight vector code. */
static void disp_coords(const struct disp_frame *f, int nr, const int *restrict run,
                               const float *restrict rx, const float *restrict ry,
                               const float *restrict foot, const float *restrict fade,
                               const float *unit, float *restrict wv, float *restrict fx,
                               float *restrict fy, int *restrict oix, int *restrict oiy,
                               float ext[4])
{
    const float lambda_m = f->lambda_m, x0 = f->x0, y0 = f->y0, kx = f->kx, ky = f->ky;
    float xl[4], xh[4], yl[4], yh[4];
    const int wm = f->wm, hm = f->hm;
    /* bounds loaded, not constants: with constants GCC threads the clamps' branches (w is 0 or
     * 1 there) and can then no longer vectorise the loop, or selects by masks, not max/min */
    const float u_lo = unit[0], u_hi = unit[1], ft_lo = unit[2];
    const float c_lo = -f->coord_max, c_hi = f->coord_max;
    for (int e = 0; e < 4; e++) {
        xl[e] = yl[e] = c_hi;
        xh[e] = yh[e] = c_lo;
    }
    for (int r = 0; r < nr; r++)
        for (int q = run[2 * r]; q < run[2 * r + 1]; q += 4)
            for (int e = q; e < q + 4; e++) {
                float ft = foot[e];
                ft = ft > ft_lo ? ft : ft_lo;
                float u = (lambda_m / ft - GRID_FILTER_NMIN) * (1.0f / (GRID_FILTER_NMAX - GRID_FILTER_NMIN));
                u = u > u_lo ? u : u_lo;
                u = u < u_hi ? u : u_hi;
                wv[e] = fade[e] * (u * u * (3.0f - 2.0f * u));
                /* clamped so the conversion is defined (|x| < 2^30 texels: 2^6 texel per ulp) */
                float x = x0 + rx[e] * kx, y = y0 + ry[e] * ky;
                x = x > c_lo ? x : c_lo;
                x = x < c_hi ? x : c_hi;
                y = y > c_lo ? y : c_lo;
                y = y < c_hi ? y : c_hi;
                xl[e - q] = x < xl[e - q] ? x : xl[e - q];
                xh[e - q] = x > xh[e - q] ? x : xh[e - q];
                yl[e - q] = y < yl[e - q] ? y : yl[e - q];
                yh[e - q] = y > yh[e - q] ? y : yh[e - q];
                /* floor: truncation rounds negatives up, so one less where the fraction is
                 * negative (x - trunc x is exact; 1 + it rounds to within 2^-24 texel) */
                int ix = (int)x, iy = (int)y;
                float sx = x - (float)ix, sy = y - (float)iy;
                int nx = sx < 0.0f, ny = sy < 0.0f;
                fx[e] = sx + (float)nx;
                fy[e] = sy + (float)ny;
                oix[e] = (ix - nx) & wm;
                oiy[e] = (iy - ny) & hm;
            }
    ext[0] = ext[2] = c_hi;
    ext[1] = ext[3] = c_lo;
    for (int e = 0; e < 4; e++) {
        ext[0] = xl[e] < ext[0] ? xl[e] : ext[0];
        ext[1] = xh[e] > ext[1] ? xh[e] : ext[1];
        ext[2] = yl[e] < ext[2] ? yl[e] : ext[2];
        ext[3] = yh[e] > ext[3] ? yh[e] : ext[3];
    }
}

/* floor(x) for |x| <= COORD_MAX */
static inline int floor_int(float x)
{
    int i = (int)x;
    return i - (x < (float)i);
}

/* Four taps' byte offsets into a displacement image: the whole-texel offsets (x | y << 16) of
 * the hash bytes at lattice indices idx, added to the footprints' first texels (x4, y4),
 * wrapped and addressed, 16 (y (w + 1) + x). */
static inline i32x4 tap_offsets(i32x4 idx, const uint8_t *restrict hash, const int *oxy,
                                i32x4 x4, i32x4 y4, int wm, int hm, int wshift)
{
    i32x4 o = { oxy[hash[idx[0]]], oxy[hash[idx[1]]], oxy[hash[idx[2]]], oxy[hash[idx[3]]] };
    i32x4 tx = (x4 + (o & 0xffff)) & wm, ty = (y4 + (o >> 16)) & hm;
    return ((ty << wshift) + ty + tx) << 4;
}

/* The displacement of the vertices of the nr runs: each reads the pattern at its lattice
 * triangle's three random offsets (detile.h, as detile_taps_cell; the same bilinear fractions
 * for the three, the offsets being whole texels) and adds their blend times its eq. 2 weight
 * wv to acc, or stores it there for the first pattern. */
static void disp_fetch(const struct disp_frame *f, const uint8_t *restrict hash, int nr,
                       const int *restrict run, const float *restrict rx,
                       const float *restrict ry, const float *restrict wv,
                       const float *restrict fx, const float *restrict fy,
                       const int *restrict ix, const int *restrict iy, float *restrict acc,
                       const int first)
{
    const char *base = (const char *)f->data, *base_c = base + f->stride;
    const struct detile_frame *d = &f->dt;
    const int m = DETILE_N - 1, shx = d->shx, shy = d->shy;
    const int wm = f->wm, hm = f->hm, wshift = f->wshift;
    const f4 one = { 1.0f, 1.0f, 1.0f, 1.0f };
    /* each hash byte's offset in texels, (h >> 3, h & 7) eighths of the tile (tables are
     * POT and >= 8 texels, grid_create) */
    int oxy[DETILE_OFFSETS * DETILE_OFFSETS];   /* x | y << 16 (images are at most 2^15 wide) */
    for (int h = 0; h < DETILE_OFFSETS * DETILE_OFFSETS; h++)
        oxy[h] = (h / DETILE_OFFSETS) * ((wm + 1) / DETILE_OFFSETS) |
                 (h % DETILE_OFFSETS) * ((hm + 1) / DETILE_OFFSETS) << 16;
    for (int r = 0; r < nr; r++)
        for (int e = run[2 * r]; e < run[2 * r + 1]; e += 4) {
            /* by quads (runs are whole blocks): the lattice cell, its hash indices and the
             * barycentric weights in vectors */
            f4 qx = d->q0x + ld4(rx + e) * d->qk, qy = d->q0y + ld4(ry + e) * d->qk;
            i32x4 cx = __builtin_convertvector(qx, i32x4), cy = __builtin_convertvector(qy, i32x4);
            cx += (i32x4)(qx < __builtin_convertvector(cx, f4));   /* floor: -1 where below */
            cy += (i32x4)(qy < __builtin_convertvector(cy, f4));
            f4 ux = qx - __builtin_convertvector(cx, f4), uy = qy - __builtin_convertvector(cy, f4);
            i32x4 hx = (cx + shx) & m, hy = (cy + shy) & m;
            i32x4 hx1 = (hx + 1) & m, hy1 = (hy + 1) & m, up = (i32x4)(uy > ux);
            i32x4 i0 = hy * DETILE_N + hx, i2 = hy1 * DETILE_N + hx1;
            i32x4 i1 = ((hy1 * DETILE_N + hx) & up) | ((hy * DETILE_N + hx1) & ~up);
            f4 hi = max4(ux, uy), lo = ux + uy - hi;
            f4 w0 = one - hi, w1 = hi - lo, w2 = lo, s2 = w0 * w0 + w1 * w1 + w2 * w2;
            f4 ww = ld4(wv + e), nn;
            for (int k = 0; k < 4; k++)
                nn[k] = ww[k] / sqrtf(s2[k]);
            /* the taps' byte offsets by vectors (with the lanes read in the tap loop GCC kept
             * a dozen pointers on the stack and reloaded them per tap: 1.38 M instructions a
             * frame, now 1.14 M; surface view, rough, callgrind) */
            i32x4 x4, y4;
            memcpy(&x4, ix + e, sizeof(x4));
            memcpy(&y4, iy + e, sizeof(y4));
            i32x4 to[3] = { tap_offsets(i0, hash, oxy, x4, y4, wm, hm, wshift),
                            tap_offsets(i1, hash, oxy, x4, y4, wm, hm, wshift),
                            tap_offsets(i2, hash, oxy, x4, y4, wm, hm, wshift) };
            f4 tw[3] = { w0 * nn, w1 * nn, w2 * nn };
            for (int k = 0; k < 4; k++) {
                int v = e + k;
                const f4 vx = { fx[v], fx[v], fx[v], fx[v] }, vy = { fy[v], fy[v], fy[v], fy[v] };
                f4 sum = tw[0][k] * bilerp(base, base_c, to[0][k], vx, vy) +
                         tw[1][k] * bilerp(base, base_c, to[1][k], vx, vy) +
                         tw[2][k] * bilerp(base, base_c, to[2][k], vx, vy);
                if (!first)
                    sum += ld4(acc + 4 * (size_t)v);
                memcpy(acc + 4 * (size_t)v, &sum, sizeof(sum));
            }
        }
}

/* disp_fetch without the lattice (grid_desc no_detile): one tap at no offset. */
static void disp_fetch_one(const struct disp_frame *f, int nr, const int *restrict run,
                           const float *restrict wv, const float *restrict fx,
                           const float *restrict fy, const int *restrict ix,
                           const int *restrict iy, float *restrict acc, const int first)
{
    const char *base = (const char *)f->data, *base_c = base + f->stride;
    const int wm = f->wm, hm = f->hm, wshift = f->wshift;
    for (int r = 0; r < nr; r++)
        for (int v = run[2 * r]; v < run[2 * r + 1]; v++) {
            const f4 vx = { fx[v], fx[v], fx[v], fx[v] }, vy = { fy[v], fy[v], fy[v], fy[v] };
            f4 sum = wv[v] * tap4(base, base_c, ix[v], iy[v], 0, 0, wm, hm, wshift, vx, vy);
            if (!first)
                sum += ld4(acc + 4 * (size_t)v);
            memcpy(acc + 4 * (size_t)v, &sum, sizeof(sum));
        }
}

/* Sum the displacement of the nd patterns at df, weighted by Bruneton eq. 2, into acc (a float4
 * per vertex), pattern by pattern over the runs of blocks of VBLK vertices whose smallest
 * footprint gives the pattern a weight > 0. The pattern with the longest wavelength goes first:
 * its blocks hold every other pattern's, so it stores and the others add. Returns the footprint
 * from which blocks were not displaced (write_vertices). */
static float displace(struct grid *g, struct disp_frame *df, int nd)
{
    const int nblk = g->npad / VBLK;
    int top = 0;
    block_foot(g->npad, g->foot, g->blk_foot);
    for (int i = 1; i < nd; i++)
        top = df[i].foot_zero > df[top].foot_zero ? i : top;
    for (int j = 0; j < nd; j++) {
        struct disp_frame *f = &df[j == 0 ? top : (j <= top ? j - 1 : j)];
        int nr = 0, in = 0;
        for (int k = 0; k < nblk; k++) {
            int on = g->blk_foot[k] < f->foot_zero;
            if (on != in)
                g->run[nr++] = k * VBLK;    /* a run starts or ends */
            in = on;
        }
        if (in)
            g->run[nr++] = nblk * VBLK;
        nr /= 2;
        float ext[4];
        if (nr == 0)
            continue;
        disp_coords(f, nr, g->run, g->rx, g->ry, g->foot, g->fade, g->unit, g->wv, g->fx, g->fy,
                    g->ix, g->iy, ext);
        {
            /* the image's texels under the footprints (first texels floor(x) from the smallest
             * to the largest x, then up to a tile further for the taps' offsets), blended
             * unless they already are for this phase */
            int on = f->dt.hash != NULL;
            int xl = floor_int(ext[0]), yl = floor_int(ext[2]);
            int mx = floor_int(ext[1]) - xl + 1 + (on ? f->wm : 0);
            int my = floor_int(ext[3]) - yl + 1 + (on ? f->hm : 0);
            xl &= f->wm;
            yl &= f->hm;
            if (!box_blended(f->im, xl, mx, yl, my))
                blend_box(f->im, xl, mx, yl, my);
        }
        if (!f->dt.hash)
            disp_fetch_one(f, nr, g->run, g->wv, g->fx, g->fy, g->ix, g->iy, g->acc, j == 0);
        else if (j == 0)
            disp_fetch(f, g->hash, nr, g->run, g->rx, g->ry, g->wv, g->fx, g->fy, g->ix, g->iy,
                       g->acc, 1);
        else
            disp_fetch(f, g->hash, nr, g->run, g->rx, g->ry, g->wv, g->fx, g->fy, g->ix, g->iy,
                       g->acc, 0);
    }
    return df[top].foot_zero;
}

/* The vertex attributes of n vertices from their rest positions and summed displacements d
 * (x, y, z, 0); the moments are 0 without CPU patterns. */
static inline void write_tail(float *restrict vx, int n, const float *restrict rx,
                              const float *restrict ry, const float *restrict d, float z, int cpu)
{
    for (int e = 0; e < n; e++, vx += GRID_FLOATS) {
        vx[GRID_A_POS + 0] = rx[e] + d[4 * e + 0];
        vx[GRID_A_POS + 1] = ry[e] + d[4 * e + 1];
        vx[GRID_A_POS + 2] = z - sphere_drop(rx[e] * rx[e] + ry[e] * ry[e]) + d[4 * e + 2];
        vx[GRID_A_REST] = rx[e];
        vx[GRID_A_REST + 1] = ry[e];
        if (!cpu)
            for (int c = GRID_A_SLOPE; c <= GRID_A_PAD; c++)
                vx[c] = 0.0f;
    }
}

/* One vertex from its position p (lane 3: the rest x) and rest y. */
static inline void write_one(float *restrict vx, f4 p, float y, const int cpu)
{
    memcpy(vx + GRID_A_POS, &p, sizeof(p));
    if (cpu) {
        vx[GRID_A_REST + 1] = y;
    } else {
        f4 r = { y, 0.0f, 0.0f, 0.0f }, zero = { 0.0f, 0.0f, 0.0f, 0.0f };
        memcpy(vx + GRID_A_REST + 1, &r, sizeof(r));
        memcpy(vx + GRID_A_REST + 5, &zero, sizeof(zero));
    }
}

/* write_tail for 4 vertices by vectors: the rest positions transposed to (x, y, z, x) per
 * vertex (lane 3 of d is 0), unrolled by hand (GCC -O2 keeps a loop over them). */
static inline void write_quad(float *restrict vx, const float *restrict rx,
                              const float *restrict ry, const float *restrict d, f4 zz,
                              const int cpu)
{
    f4 x = ld4(rx), y = ld4(ry);
    f4 r2 = x * x + y * y;
    zz -= sphere_drop4(r2);   /* the sea's drop on a sphere (camera.h) */
    f4 xy_lo = __builtin_shufflevector(x, y, 0, 4, 1, 5), xy_hi = __builtin_shufflevector(x, y, 2, 6, 3, 7);
    f4 zx_lo = __builtin_shufflevector(zz, x, 0, 4, 1, 5), zx_hi = __builtin_shufflevector(zz, x, 2, 6, 3, 7);
    write_one(vx, __builtin_shufflevector(xy_lo, zx_lo, 0, 1, 4, 5) + ld4(d), y[0], cpu);
    write_one(vx + GRID_FLOATS, __builtin_shufflevector(xy_lo, zx_lo, 2, 3, 6, 7) + ld4(d + 4),
              y[1], cpu);
    write_one(vx + 2 * GRID_FLOATS, __builtin_shufflevector(xy_hi, zx_hi, 0, 1, 4, 5) + ld4(d + 8),
              y[2], cpu);
    write_one(vx + 3 * GRID_FLOATS, __builtin_shufflevector(xy_hi, zx_hi, 2, 3, 6, 7) + ld4(d + 12),
              y[3], cpu);
}

/* The vertices: d is acc for the blocks displace() reached (smallest footprint under
 * foot_disp), else zeros; cpu constant where write_quad is inlined. */
static void write_vertices(const struct grid *g, float *verts, float z, int cpu, float foot_disp)
{
    _Static_assert(VBLK == 8, "write_vertices writes a block as two quads");
    static const float none[4 * VBLK];
    const f4 zz = { z, z, z, z };
    int b = 0;
    for (; b + VBLK <= g->nverts; b += VBLK) {
        const float *d = g->blk_foot[b / VBLK] < foot_disp ? g->acc + 4 * (size_t)b : none;
        float *vx = verts + (size_t)b * GRID_FLOATS;
        if (cpu) {
            write_quad(vx, g->rx + b, g->ry + b, d, zz, 1);
            write_quad(vx + 4 * GRID_FLOATS, g->rx + b + 4, g->ry + b + 4, d + 16, zz, 1);
        } else {
            write_quad(vx, g->rx + b, g->ry + b, d, zz, 0);
            write_quad(vx + 4 * GRID_FLOATS, g->rx + b + 4, g->ry + b + 4, d + 16, zz, 0);
        }
    }
    if (b < g->nverts)
        write_tail(verts + (size_t)b * GRID_FLOATS, g->nverts - b, g->rx + b, g->ry + b,
                   g->blk_foot[b / VBLK] < foot_disp ? g->acc + 4 * (size_t)b : none, z, cpu);
}

/* Vertex k's mip level of pattern frame f (its footprint's), its texel coordinates there, the
 * level's width lw (the lattice's offsets are in its texels) and its lattice taps (detile.h).
 * A CPU pattern's slope and whitecap levels are the same size (grid_create). */
static inline int vertex_level(const struct grid *g, const struct pattern_frame *f, int k,
                               double *x, double *y, double *lw, struct detile_taps *t)
{
    int lev = mip_level(g->foot[k] * f->lev_k, f->p->levels - 1);
    *lw = f->p->wc_f[lev].w;
    *x = f->mx0[lev] + g->rx[k] * f->mk[lev];
    *y = f->my0[lev] + g->ry[k] * f->mk[lev];
    detile_at(&f->dt, g->rx[k], g->ry[k], t);
    return lev;
}

/* Add CPU pattern f's slope and whitecap moments to every vertex: from the mip level whose
 * texel matches the vertex footprint, the mip texel then holding the footprint's first and
 * second moments (Bruneton §4.1, Dupuy eq. 7-8; of the foam memory m_i, bake.c). */
static void moment_pass(const struct grid *g, struct pattern_frame *f, float *verts)
{
    struct grid_pattern *p = f->p;
    /* lanes 0, 1: the mean slope; 2, 3: the resolved variance <s^2> - <s>^2 (floored at 0) */
    const f4 var_lanes = { 0.0f, 0.0f, 1.0f, 1.0f };
    const f4 var_floor = { -INFINITY, -INFINITY, 0.0f, 0.0f };
    _Static_assert(GRID_A_SVAR == GRID_A_SLOPE + 2, "slope mean and variance are one vector");
    for (int k = 0; k < g->nverts; k++) {
        float *vx = verts + (size_t)k * GRID_FLOATS;
        double x, y, lw;
        struct detile_taps t;
        int lev = vertex_level(g, f, k, &x, &y, &lw, &t);
        /* three taps blended (detile.h): means by w_j, variances by w_j^2, the foam memory's
         * deviation from its mean */
        f4 acc = ld4(vx + GRID_A_SLOPE);
        float km = p->k_mean;
        for (int j = 0; j < (f->dt.hash ? 3 : 1); j++) {
            f4 m, q;
            float w = t.w[j];
            f4 wl = { w, w, w * w, w * w };
            sample_f4x2(&p->slope_f[lev], &p->wc_f[lev], x + t.du[j] * lw, y + t.dv[j] * lw,
                        &m, &q);
            f4 mm = __builtin_shufflevector(m, m, 0, 1, 0, 1);
            acc += wl * max4(m - mm * mm * var_lanes, var_floor);
            km += w * (q[0] - p->k_mean);
            vx[GRID_A_K + 1] += w * w * maxf(q[1] - q[0] * q[0], 0.0f);
        }
        memcpy(vx + GRID_A_SLOPE, &acc, sizeof(acc));
        vx[GRID_A_K] += km;
    }
}

/* The foam memory's mean, within-texel variance <m^2> - <m>^2 (floored at 0) and the loop
 * blend's own variance (grid_internal.h f4_image mix_s; 0 from level 2 up) of k-only pattern p
 * at texel coordinates (x, y) of level lev; from its flat level up the top texel's, flat (unless
 * NULL: sampled), and no blend variance. */
static inline void k_texel(struct grid_pattern *p, int lev, double x, double y,
                           const float flat[2], float out[3])
{
    if (flat && lev >= p->k_flat) {
        out[0] = flat[0];
        out[1] = flat[1];
        out[2] = 0.0f;
        return;
    }
    struct texel_at a;
    texel_locate(&p->wc_f[lev], x, y, &a);
    f4 q = texel_sample(&p->wc_f[lev], &a);
    out[0] = q[0];
    out[1] = maxf(q[1] - q[0] * q[0], 0.0f);
    out[2] = q[2];
}

/* A vertex's within-footprint variance of k-only pattern p's foam memory where level 0 is
 * magnified (footprint r texels, r < 1) from the fetched <m^2> - <m>^2, v: there v is the
 * bilinear mix of neighbouring texels' moments, not variance within the footprint (it draws
 * the texel grid). As high quality's pixels take it (ocean.frag add_whitecap: B = 0 there, level
 * 0's mean W0 instead, part of it as blur and the rest as detail of the same expected
 * coverage), W0 in its place, from r = 1/2 down; v from r = 1, linear in r between. Taking
 * v to 0 instead (W0 unused) matched high's rows as well but drew the vertices' triangles as
 * a staircase along the foam's edges (storm from 5 m). Not where level 0 is already the flat
 * level (the patch's top texel, k_texel). The loop blend's own variance mix, which v holds too,
 * stays with W0 (stream.h stream_blend_whitecap: without it the blend averaged the foam away
 * between frames up close). */
static inline float magnified_var(const struct grid_pattern *p, float r, float v, float mix)
{
    float s = 2.0f * r - 1.0f;
    s = s < 0.0f ? 0.0f : s > 1.0f ? 1.0f : s;
    return p->k_w0 + mix + (v - p->k_w0 - mix) * s;
}

/* k_moment_pass without the lattice (low quality's default): one tap of weight 1, by quads of
 * vertices. The level, its texel coordinates (level l's are level 0's times 2^-l, less half a
 * texel; the exponent built from l), their floors and fractions in vectors, in float (rest
 * positions are camera-relative floats and the offset is under a tile: as disp_coords); then
 * per vertex the level's bilinear sample; a quad whose four vertices take the flat top texel
 * skips the rest. Grid_update (rough, gles2-min, low quality, callgrind, instructions a frame)
 * at the surface 2.14 -> 1.94 M, 1 km 1.31 -> 1.22 M, 10 km 0.77 -> 0.69 M, with the double
 * coordinates and their per-level tables per vertex before (without the flat quads' skip 10 km
 * took 0.83 M; both k-only patterns in one pass, with the variance in vectors, 1.95 M at the
 * surface). k_texel's results within the float coordinates' rounding (test_grid_cpu). */
static void k_moment_quads(const struct grid *g, const struct pattern_frame *f, float *verts,
                           const float q_top[2])
{
    struct grid_pattern *p = f->p;
    const int top = p->levels - 1, kflat = p->k_flat;
    const float k0 = (float)(p->wc_f[0].w * p->inv_l);   /* level-0 texels per metre */
    const f4 lk = { f->lev_k, f->lev_k, f->lev_k, f->lev_k }, kk = { k0, k0, k0, k0 };
    const f4 ux = { f->u0x, f->u0x, f->u0x, f->u0x }, uy = { f->u0y, f->u0y, f->u0y, f->u0y };
    const f4 half = { 0.5f, 0.5f, 0.5f, 0.5f }, two = { 2.0f, 2.0f, 2.0f, 2.0f };
    const f4 one = { 1.0f, 1.0f, 1.0f, 1.0f }, zero = { 0.0f, 0.0f, 0.0f, 0.0f };
    const f4 cmax = { COORD_MAX, COORD_MAX, COORD_MAX, COORD_MAX };
    const i32x4 topv = { top, top, top, top };
    /* the sampled levels' images (below k_flat), their masks and row strides at hand */
    struct {
        struct f4_image *im;
        int wm, hm;
        size_t stride;
    } lv[16];
    for (int l = 0; l < kflat && l < 16; l++) {
        lv[l].im = &p->wc_f[l];
        lv[l].wm = p->wc_f[l].w - 1;
        lv[l].hm = p->wc_f[l].h - 1;
        lv[l].stride = 4 * (size_t)(p->wc_f[l].w + 1);
    }
    const float kw0 = p->k_w0;   /* a local: vx's stores would make it reloaded per vertex */
    for (int e = 0; e < g->nverts; e += 4) {   /* the arrays are padded to VBLK (grid.h) */
        f4 r = ld4(g->foot + e) * lk;
        i32x4 rb, lev, sb;
        memcpy(&rb, &r, sizeof(rb));
        /* mip_level: the exponent from r >= 2 (0 below and for NaN), at most the top */
        lev = ((rb >> 23) - 127) & (i32x4)(r >= two);
        lev = (lev & (lev < topv)) | (topv & ~(lev < topv));
        int n = g->nverts - e < 4 ? g->nverts - e : 4;
        if (lev[0] >= kflat && lev[1] >= kflat && lev[2] >= kflat && lev[3] >= kflat) {
            /* far views: most quads take the top texel */
            for (int k = 0; k < n; k++) {
                float *vx = verts + (size_t)(e + k) * GRID_FLOATS;
                vx[GRID_A_K] += q_top[0];
                vx[GRID_A_K + 1] += q_top[1];
            }
            continue;
        }
        sb = (127 - lev) << 23;
        f4 sc, x, y;
        memcpy(&sc, &sb, sizeof(sc));
        x = (ux + ld4(g->rx + e) * kk) * sc - half;
        y = (uy + ld4(g->ry + e) * kk) * sc - half;
        x = -max4(-max4(x, -cmax), -cmax);   /* clamped to +-COORD_MAX: the conversion defined */
        y = -max4(-max4(y, -cmax), -cmax);
        i32x4 ix = __builtin_convertvector(x, i32x4), iy = __builtin_convertvector(y, i32x4);
        ix += (i32x4)(x < __builtin_convertvector(ix, f4));   /* floor: -1 where below */
        iy += (i32x4)(y < __builtin_convertvector(iy, f4));
        f4 fx = x - __builtin_convertvector(ix, f4), fy = y - __builtin_convertvector(iy, f4);
        /* magnified_var's weight of the sampled variance at level 0 (1 elsewhere) */
        f4 ms = -max4(-max4(r + r - one, zero), -one);
        ms = (f4)(((i32x4)ms & (lev == 0)) | ((i32x4)one & (lev != 0)));
        for (int k = 0; k < n; k++) {
            float *vx = verts + (size_t)(e + k) * GRID_FLOATS;
            int l = lev[k];
            if (l >= kflat) {
                vx[GRID_A_K] += q_top[0];
                vx[GRID_A_K + 1] += q_top[1];
                continue;
            }
            struct texel_at a;
            int xi = ix[k] & lv[l].wm, yi = iy[k] & lv[l].hm;
            a.tx = xi >> TILE_LOG2;
            a.ty = yi >> TILE_LOG2;
            a.tile = a.ty * lv[l].im->tiles_x + a.tx;
            a.stride = lv[l].stride;
            a.off = (size_t)yi * a.stride + 4 * (size_t)xi;
            a.vx = (f4){ fx[k], fx[k], fx[k], fx[k] };
            a.vy = (f4){ fy[k], fy[k], fy[k], fy[k] };
            f4 q = texel_sample(lv[l].im, &a);
            float v = maxf(q[1] - q[0] * q[0], 0.0f);
            vx[GRID_A_K] += q[0];
            /* magnified_var */
            vx[GRID_A_K + 1] += kw0 + q[2] + (v - kw0 - q[2]) * ms[k];
        }
    }
}

/* Add pattern f's whitecap moments alone to every vertex (grid.h k_patterns: low quality's
 * fragment-shader patterns, whose whitecaps no fragment shader fetches), as moment_pass does
 * for a CPU pattern, at the mip level of the vertex's footprint: Dupuy's eq. 6 then sees the
 * foam memory's first and second moments there, as high quality's fragment shader does per
 * pixel, where the patch's constants alone gave every vertex the same coverage. From
 * k_flat up it takes the top texel, unsampled. Its cost (callgrind, rough tables, gles2-min,
 * no lattice, grid_update + stream_blend a frame): surface 1.45 -> 2.54 M, 1 km 1.01 ->
 * 1.81 M, 10 km 0.81 -> 1.24 M, most of it the bilinear samples and their tiles' blends.
 * One level, as moment_pass: two blended by the footprint took 3.18 M (2.47 M with one) and
 * changed no row-to-row brightness step (storm from 5 m: the largest 8.0 % vs 8.4 %, the
 * foam's own patches). */
static void k_moment_pass(const struct grid *g, struct pattern_frame *f, float *verts)
{
    struct grid_pattern *p = f->p;
    const int top = p->levels - 1;
    /* from k_flat up the top texel (one texel: one tap at no offset reads it anywhere; its
     * level follows the loop phase, grid_update) */
    float q_top[3];
    k_texel(p, top, 0.0, 0.0, NULL, q_top);
    if (!f->dt.hash) {
        k_moment_quads(g, f, verts, q_top);
        return;
    }
    for (int k = 0; k < g->nverts; k++) {
        float *vx = verts + (size_t)k * GRID_FLOATS;
        double x, y, lw;
        struct detile_taps t;
        int lev = vertex_level(g, f, k, &x, &y, &lw, &t);
        /* the foam memory's deviation from its mean by w_j, its within-texel variance by w_j^2 */
        float km = p->k_mean, kv = 0.0f, kx = 0.0f;
        for (int j = 0; j < 3; j++) {
            float w = t.w[j], q[3];
            k_texel(p, lev, x + t.du[j] * lw, y + t.dv[j] * lw, q_top, q);
            km += w * (q[0] - p->k_mean);
            kv += w * w * q[1];
            kx += w * w * q[2];
        }
        vx[GRID_A_K] += km;
        /* (the taps' weights: sum w_j^2 = 1, detile.h) */
        vx[GRID_A_K + 1] += lev || p->k_flat == 0
                                ? kv : magnified_var(p, g->foot[k] * f->lev_k, kv, kx);
    }
}

void grid_set_wake(struct grid *g, const struct grid_wake *w)
{
    memset(&g->wake, 0, sizeof(g->wake));
    g->wake_crest_m = 0.0;
    if (w && w->map) {
        g->wake = *w;
        g->wake_crest_m = w->map->height_max_m;
    }
}

/* The wake's heights on the vertices within its map's reach (grid_set_wake): the vertex's
 * drawn position (the rest position moved by the patterns' choppy displacement: where the
 * query, swell_sea_sample, finds it too; the rest position put the wake up to 0.3 m off the
 * query in a moderate sea, test_api test_height_wake) to the hull's frame (x along fwd, y to
 * port), the map's mipmapped height there at the vertex's footprint. */
static void wake_heights(const struct grid *g, float *verts)
{
    const struct kelvin_map *m = g->wake.map;
    double f0 = g->wake.fwd[0], f1 = g->wake.fwd[1];
    double reach = m->span_m + m->ahead_m + m->hull_length_m + g->chop_m;
    for (int k = 0; k < g->nverts; k++) {
        float *p = verts + (size_t)k * GRID_FLOATS + GRID_A_POS;
        double dx = p[0] - g->wake.hull_xy[0], dy = p[1] - g->wake.hull_xy[1];
        if (dx * dx + dy * dy > reach * reach)
            continue;
        p[2] += kelvin_map_height(m, dx * f0 + dy * f1, dy * f0 - dx * f1, g->foot[k]);
    }
}

void grid_set_mask(struct grid *g, int on, const struct wave_mask *m)
{
    g->mask_attr = on;
    memset(&g->mask, 0, sizeof(g->mask));
    if (on && m && m->amp)
        g->mask = *m;
}

/* The mask's amplitude a on every vertex (grid_set_mask): its displacement from the rest
 * point (and the sphere's drop) times a, the CPU patterns' mean slope times a, their resolved
 * variance times a^2; a itself to GRID_A_PAD. */
static void mask_apply(const struct grid *g, const double cam[2], float z, float *verts)
{
    /* the rest point's texel coordinates (mask.h), camera-relative: u = u0 + rx / dx, in
     * double (a far mask's u is large; as a float, even infinite, it reads as outside) */
    const struct wave_mask *m = &g->mask;
    double u0 = 0.0, v0 = 0.0, su = 0.0, sv = 0.0;
    if (m->amp) {
        su = 1.0 / m->dx;
        sv = 1.0 / m->dy;
        u0 = (cam[0] - m->x0) * su - 0.5;
        v0 = (cam[1] - m->y0) * sv - 0.5;
    }
    for (int k = 0; k < g->nverts; k++) {
        float *vx = verts + (size_t)k * GRID_FLOATS;
        float rx = vx[GRID_A_REST], ry = vx[GRID_A_REST + 1];
        float a = m->amp ? wave_mask_texel_at(m, (float)(u0 + rx * su), (float)(v0 + ry * sv))
                         : 1.0f;
        vx[GRID_A_PAD] = a;
        if (a == 1.0f)
            continue;
        float zr = z - sphere_drop(rx * rx + ry * ry);
        vx[GRID_A_POS + 0] = rx + a * (vx[GRID_A_POS + 0] - rx);
        vx[GRID_A_POS + 1] = ry + a * (vx[GRID_A_POS + 1] - ry);
        vx[GRID_A_POS + 2] = zr + a * (vx[GRID_A_POS + 2] - zr);
        vx[GRID_A_SLOPE + 0] *= a;
        vx[GRID_A_SLOPE + 1] *= a;
        vx[GRID_A_SVAR + 0] *= a * a;
        vx[GRID_A_SVAR + 1] *= a * a;
    }
}

int grid_update(struct grid *g, const struct camera_frame *view, double t_s, float *verts)
{
    const struct camera *cam = &view->cam;
    struct pattern_frame pf[SWELL_MAX_PATTERNS];    /* the CPU patterns' */
    struct disp_frame df[SWELL_MAX_PATTERNS];       /* the displacing patterns' */
    int n, np = 0, nd = 0;
    n = g->kind == GEOMETRY_GRID ? update_projected(g, view) : update_patches(g, view);
    if (n == 0)
        return 0;
    float foot_lo = g->foot_lo_wet > 1e-6f ? g->foot_lo_wet : 1e-6f;
    for (int i = 0; i < g->t->patterns; i++) {
        struct grid_pattern *p = &g->p[i];
        struct pattern_frame *f = &pf[np];
        struct stream_phase ph;
        float o[2];
        /* eq. 2's weight is 0 for every vertex when it is 0 at the smallest wet footprint (the
         * float expressions are monotonic in the footprint) */
        int disp_on = p->lambda_m / foot_lo > GRID_FILTER_NMIN;
        if (!disp_on && !p->cpu && !p->kcpu)
            continue;
        grid_uv_offset(g->t, i, cam, o);
        stream_pattern_phase(g->t, i, t_s, g->t->frames, &ph);
        if (disp_on) {
            struct disp_frame *d = &df[nd++];
            int nx = p->disp->width, ny = p->disp->height;
            image_phase(&p->disp_f, &ph);
            d->im = &p->disp_f;
            d->data = p->disp_f.data;
            d->lambda_m = p->lambda_m;
            detile_frame_set(&d->dt, g->detile ? g->hash : NULL, i, p->inv_l, cam);
            /* a block is skipped from a hair above lambda / Nmin, where the weight is 0 (the
             * exact per-vertex weight decides the rest) */
            d->foot_zero = p->lambda_m / GRID_FILTER_NMIN * (1.0f + 1e-5f);
            d->kx = (float)(p->inv_l * nx);
            d->ky = (float)(p->inv_l * ny);
            d->x0 = (float)((double)o[0] * nx - 0.5);
            d->y0 = (float)((double)o[1] * ny - 0.5);
            d->wm = nx - 1;
            d->hm = ny - 1;
            d->wshift = __builtin_ctz((unsigned)nx);
            d->stride = sizeof(f4) * ((size_t)nx + 1);
            d->coord_max = COORD_MAX;
        }
        if (p->cpu || p->kcpu) {
            int top = p->levels - 1, lo, hi;
            f->p = p;
            detile_frame_set(&f->dt, g->detile ? g->hash : NULL, i, p->inv_l, cam);
            f->lev_k = (float)p->wc->width * (float)p->inv_l;
            f->u0x = (float)((double)o[0] * p->wc_f[0].w);
            f->u0y = (float)((double)o[1] * p->wc_f[0].w);
            lo = mip_level(g->foot_lo * f->lev_k, top);
            hi = mip_level(g->foot_hi * f->lev_k, top);
            for (int l = lo; l <= hi; l++) {
                int lw = p->wc_f[l].w;
                f->mk[l] = p->inv_l * lw;
                f->mx0[l] = (double)o[0] * lw - 0.5;
                f->my0[l] = (double)o[1] * lw - 0.5;
                if (p->cpu)
                    image_phase(&p->slope_f[l], &ph);
                image_phase(&p->wc_f[l], &ph);
            }
            if (p->kcpu) {   /* k_moment_pass reads the top texel wherever the vertices are */
                image_phase(&p->wc_f[top], &ph);
            }
            np++;
        }
    }
    if (np) {
        for (int k = 0; k < g->nverts; k++) {
            float *vx = verts + (size_t)k * GRID_FLOATS;
            for (int c = GRID_A_SLOPE; c <= GRID_A_PAD; c++)
                vx[c] = 0.0f;
        }
        for (int i = 0; i < np; i++)
            if (pf[i].p->cpu)
                moment_pass(g, &pf[i], verts);
            else
                k_moment_pass(g, &pf[i], verts);
    }
    float foot_disp = nd ? displace(g, df, nd) : -INFINITY;
    write_vertices(g, verts, (float)-cam->pos[2], np > 0, foot_disp);
    if (g->mask_attr)
        mask_apply(g, cam->pos, (float)-cam->pos[2], verts);
    if (g->wake.map)
        wake_heights(g, verts);
    row_distances(g);
    return n;
}
