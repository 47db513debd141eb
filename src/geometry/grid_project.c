/* grid_project.c - where the grid's vertices rest on the sea plane this frame, their footprints
 * and the rows' distances: the projected grid (Bruneton 2010 §3, cast from Johanson 2004's
 * projector; its range bounds every rest position whose displaced image can reach the frustum,
 * coverage by construction) or the near/far patches (Hu 2006 §3), over a sphere's drop. Also
 * the projected grid's frame alone for the vertex-texture-fetch tiers (grid_projection). Writes
 * struct grid's rest, footprint and row arrays; owns nothing. */
#include <math.h>
#include <string.h>
#include "geometry/grid_internal.h"

#define GRID_MARGIN 0.02      /* NDC beyond the bounding box of what displacement can reach */

/* How far the grid reaches: the farthest crest the camera can see over a sphere, its own
 * horizon sqrt(2 R h + h^2) plus a crest's, sqrt(2 R crest) (within the far plane). */
static float far_distance(const struct grid *g, const struct camera_frame *view)
{
    const struct camera *cam = &view->cam;
    float f = view->far_m;
    double h = fmax(cam->pos[2] - cam->surface_z_m, CAMERA_CLEARANCE_M) + fmax(cam->surface_z_m, 0.0);
    double d = sqrt(2.0 * EARTH_RADIUS_M * h + h * h) + sqrt(2.0 * EARTH_RADIUS_M * grid_crest(g));
    return (float)fmin(0.9 * f, 1.02 * d);
}

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

#define HULL_MAX 128          /* 32 polytope vertices x 4 corners of the choppy dilation */
#define PROJ_COS_MIN 0.15     /* projector rays stay within 81 degrees of its axis... */
#define PROJ_STEP_DEG 2.0     /* ...lowering its pitch by this step until they do */
#define SCREEN_SHARE 0.8      /* of the grid's rows and columns, on the camera's screen */

/* Sea-plane points (camera-relative x, y) that bound every rest position whose displaced
 * image can lie in the camera's frustum: the frustum (near plane to dmax along the view) cut
 * by the slab z in [zlo, zhi] that displacement can reach has as vertices its corners inside
 * the slab and its 12 edges' crossings of the two planes; their horizontal shadow, widened by
 * the largest sideways displacement (a square of half-side chop), is convex, so the convex hull
 * of these points contains it. Returns the number of points. */
static int frustum_slab_points(const double fwd[3], const double right[3], const double up[3],
                               const double tan_lrbt[4], double n, double f, double zlo,
                               double zhi, double chop, double q[HULL_MAX][2])
{
    double c[8][3];
    static const int edge[12][2] = { { 0, 1 }, { 1, 3 }, { 3, 2 }, { 2, 0 }, { 4, 5 }, { 5, 7 },
                                     { 7, 6 }, { 6, 4 }, { 0, 4 }, { 1, 5 }, { 2, 6 }, { 3, 7 } };
    double pts[32][2];
    int np = 0, nq = 0;
    for (int k = 0; k < 8; k++) {
        double a = tan_lrbt[k & 1], b = tan_lrbt[k & 2 ? 3 : 2], d = k & 4 ? f : n;
        for (int e = 0; e < 3; e++)
            c[k][e] = d * (fwd[e] + a * right[e] + b * up[e]);
        if (c[k][2] >= zlo && c[k][2] <= zhi) {
            pts[np][0] = c[k][0];
            pts[np++][1] = c[k][1];
        }
    }
    for (int k = 0; k < 12; k++) {
        const double *a = c[edge[k][0]], *b = c[edge[k][1]];
        for (int s = 0; s < 2; s++) {
            double z = s ? zhi : zlo, da = a[2] - z, db = b[2] - z;
            if ((da < 0.0) != (db < 0.0)) {
                double u = da / (da - db);
                pts[np][0] = a[0] + u * (b[0] - a[0]);
                pts[np++][1] = a[1] + u * (b[1] - a[1]);
            }
        }
    }
    for (int k = 0; k < np; k++)
        for (int s = 0; s < 4; s++) {
            q[nq][0] = pts[k][0] + (s & 1 ? chop : -chop);
            q[nq++][1] = pts[k][1] + (s & 2 ? chop : -chop);
        }
    return nq;
}

/* The sea-plane row seen from the projector at angle theta above its axis, at forward
 * distance s = alt_ray / tan(dp) (dp = -(pitch + theta), its depression), is seen by the
 * camera at depression atan2(row_h, s); and back. Both work past the nadir (dp > 90 deg). */
static double cam_depression(const struct grid_projection *p, double theta)
{
    double dp = -(p->pitch + theta);
    return atan2(p->row_h * sin(dp), p->alt_ray * cos(dp));
}

/* The horizon rows of grid.h: the top row no farther than dmax (rays between the projector's
 * horizon and there all end at dmax), and from it the distance row_h / tan dc halving per row
 * (dc doubling: small angles) until that spacing reaches the even one's, x' = row_a; so
 * row_a delta / ln 2 = dc0 2^(u* / delta), and x(1) = the even rows' span fixes row_a (a few
 * fixed-point steps; the even rows then lie 0.5-10 % farther apart: 10 % at 0.3 m up, 6 % at
 * 8 m, 0.5 % at 1 km). None where the top row's dc already exceeds one even row / ln 2 (views from high
 * up or looking down), and it comes in continuously (u* from 0) as the camera lowers. */
static void horizon_rows(struct grid_projection *p, int h)
{
    double dc_far = atan(p->row_h / fmax(p->dmax, 1.0));
    if (p->row_cam[0] < dc_far && p->row_cam[1] > dc_far)
        p->row_cam[0] = dc_far;
    double dc0 = p->row_cam[0], span = p->row_cam[1] - dc0;
    double delta = 1.0 / fmax((h - 1) * p->row_split, 1.0), a = span, us = 0.0;
    for (int it = 0; it < 12 && dc0 > 0.0; it++) {
        double r = a * delta / (dc0 * M_LN2);
        us = r > 1.0 ? fmin(delta * log2(r), 0.5) : 0.0;
        a = (span - dc0 * (exp2(us / delta) - 1.0)) / (1.0 - us);
    }
    p->row_inv_delta = 1.0 / delta;
    p->row_ustar = us;
    p->row_a = a;
    p->row_xs = dc0 * (exp2(us / delta) - 1.0);
}

/* The projected grid's frame for a camera (grid.h); 0 when no sea is in view.
 *
 * Coverage by construction: the grid spans, in the projector's NDC, the bounding box of the
 * points frustum_slab_points finds; the projective map from the sea plane to that NDC keeps
 * convex sets convex where every point is in front of the projector, so the box holds every
 * rest position a visible surface point can come from, and the displaced grid's border lies
 * outside the frustum. A ray from the camera (kept CAMERA_CLEARANCE_M above the local surface
 * by the renderer) that goes below the slab within the frustum must then cross the displaced
 * grid. The projector is the camera where that is possible (views from above every crest: the
 * grid's rows follow the screen's), else raised above the crests and pitched down until the
 * points near and behind the camera are in front of it. */
static int projection_frame(const struct grid *g, const struct camera_frame *view,
                            struct grid_projection *p)
{
    const struct camera *cam = &view->cam;
    const double *cf = view->fwd, *cr = view->right, *cu = view->up;
    double q[HULL_MAX][2];
    float near_m = view->near_m, far_m = view->far_m;
    memset(p, 0, sizeof(*p));
    p->alt = cam->pos[2];
    p->dmax = far_distance(g, view);
    /* The sea lies on a sphere: at distance r it is r^2 / (2 R) lower, so the slab's floor is
     * lowered by the drop at the farthest point the region reaches (twice: from the flat
     * slab's reach, then from the lowered one's; at most dmax's). */
    double reach = 0.0;
    int nq = 0;
    for (int pass = 0; pass < 3; pass++) {
        double r = fmin(reach, p->dmax);
        nq = frustum_slab_points(cf, cr, cu, view->tan_lrbt, near_m, far_m,
                                 -p->alt - grid_crest(g) - sphere_drop((float)(r * r)),
                                 -p->alt + grid_crest(g), g->chop_m, q);
        for (int k = 0; k < nq; k++)
            reach = fmax(reach, sqrt(q[k][0] * q[k][0] + q[k][1] * q[k][1]));
    }
    if (nq == 0)
        return 0;
    p->alt_ray = fmax(p->alt, fmax(grid_crest(g) + g->chop_m, 1.0));
    /* the projector's pitch: the camera's (at most level), lowered until every point that is
     * not well ahead (q . heading < half its distance) is within acos(PROJ_COS_MIN) of its axis;
     * points well ahead are in front of any projector pitched down */
    double hx = cos(cam->heading_deg * M_PI / 180.0), hy = sin(cam->heading_deg * M_PI / 180.0);
    double pitch = fmin(cam->pitch_deg, -1.0);
    for (;; pitch -= PROJ_STEP_DEG) {
        if (pitch < -89.0)
            pitch = -89.0;
        camera_basis(cam->heading_deg, pitch, p->fwd, p->right, p->up);
        int ok = 1;
        for (int k = 0; k < nq && ok; k++) {
            double d[3] = { q[k][0], q[k][1], -p->alt_ray };
            double dist = sqrt(q[k][0] * q[k][0] + q[k][1] * q[k][1]);
            if (q[k][0] * hx + q[k][1] * hy >= 0.5 * dist)
                continue;
            ok = dot3(d, p->fwd) >= PROJ_COS_MIN * sqrt(dot3(d, d));
        }
        if (ok || pitch <= -89.0)
            break;
    }
    /* the points' angles from the projector's axis, across (phi) and up (theta) */
    double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
    for (int k = 0; k < nq; k++) {
        double d[3] = { q[k][0], q[k][1], -p->alt_ray };
        double fz = fmax(dot3(d, p->fwd), 1e-9 * sqrt(dot3(d, d)));
        double ax = atan(dot3(d, p->right) / fz), ay = atan(dot3(d, p->up) / fz);
        x0 = fmin(x0, ax);
        x1 = fmax(x1, ax);
        y0 = fmin(y0, ay);
        y1 = fmax(y1, ay);
    }
    /* a hair beyond the box, so float rounding of the extreme rays never falls inside it */
    x0 -= GRID_MARGIN;
    x1 += GRID_MARGIN;
    y0 -= GRID_MARGIN;
    y1 += GRID_MARGIN;
    double hz = -pitch * M_PI / 180.0;                  /* the projector's horizon */
    if (hz < y1)
        y1 = hz - 1e-4;
    if (!(y1 > y0))
        return 0;
    /* The screen's part of the range: its side edges' angle, and its bottom edge's ray where
     * it meets the sea plane, seen from the projector. Those spans get SCREEN_SHARE of the
     * columns and rows (more where uniform angles would give them more). */
    double sb = y0, bot[3];
    for (int c = 0; c < 3; c++)
        bot[c] = cf[c] + view->tan_lrbt[2] * cu[c];
    if (bot[2] < 0.0 && p->alt > 0.0) {
        double t = p->alt / -bot[2], d[3] = { t * bot[0], t * bot[1], -p->alt_ray };
        double fz = dot3(d, p->fwd);
        if (fz > 0.0)
            sb = atan(dot3(d, p->up) / fz) - GRID_MARGIN;
    }
    sb = fmin(fmax(sb, y0), y1);
    p->pitch = pitch * M_PI / 180.0;
    p->row_margin[0] = sb;
    p->row_margin[1] = y0;
    p->row_h = fmax(p->alt, CAMERA_CLEARANCE_M);
    p->row_cam[0] = cam_depression(p, y1);
    p->row_cam[1] = cam_depression(p, sb);
    /* the margin's share: what uniform projector angles would give it, at most 1 - SCREEN_SHARE */
    p->row_split = sb > y0 ? fmax(SCREEN_SHARE, (y1 - sb) / (y1 - y0)) : 1.0;
    horizon_rows(p, g->h);
    double c0 = fmin(fmax(atan(view->tan_lrbt[0]), x0), x1);
    double c1 = fmax(fmin(atan(view->tan_lrbt[1]), x1), c0), span = x1 - x0;
    double inner = fmax(SCREEN_SHARE, (c1 - c0) / span);
    double side_l = c0 - x0, side_r = x1 - c1;
    p->col_ang[0] = x0;
    p->col_ang[1] = c0;
    p->col_ang[2] = c1;
    p->col_ang[3] = x1;
    p->col_split[0] = side_l + side_r > 0.0 ? (1.0 - inner) * side_l / (side_l + side_r) : 0.0;
    p->col_split[1] = p->col_split[0] + inner;
    return 1;
}

double grid_row_tan(const struct grid_projection *p, double v)
{
    double theta;
    if (v < p->row_split) {
        double u = v / p->row_split, dc0 = p->row_cam[0], us = p->row_ustar;
        double dc = dc0 + (u < us ? dc0 * (exp2(u * p->row_inv_delta) - 1.0)
                                  : p->row_xs + p->row_a * (u - us));
        theta = -p->pitch - atan2(p->alt_ray * sin(dc), p->row_h * cos(dc));
    } else {
        theta = p->row_margin[0] + (p->row_margin[1] - p->row_margin[0]) * (v - p->row_split) /
                                       fmax(1.0 - p->row_split, 1e-12);
    }
    return tan(theta);
}

double grid_warp(double x, const double *a, const double *s, int n)
{
    double lo = 0.0;
    for (int k = 0; k < n - 2; k++) {
        if (x < s[k])
            return a[k] + (a[k + 1] - a[k]) * (x - lo) / (s[k] - lo);
        lo = s[k];
    }
    return lo < 1.0 ? a[n - 2] + (a[n - 1] - a[n - 2]) * (x - lo) / (1.0 - lo) : a[n - 1];
}

/* Footprint of vertex (i, j) of the projected grid: the larger distance to the next vertex
 * along the row and down the column (the previous one for the last). */
static float grid_foot_at(const struct grid *g, int i, int j)
{
    size_t k = (size_t)j * g->w + i;
    size_t kx = i + 1 < g->w ? k + 1 : k - 1, ky = j + 1 < g->h ? k + g->w : k - g->w;
    float fx = maxf(fabsf(g->rx[kx] - g->rx[k]), fabsf(g->ry[kx] - g->ry[k]));
    float fy = maxf(fabsf(g->rx[ky] - g->rx[k]), fabsf(g->ry[ky] - g->ry[k]));
    return maxf(fx, fy);
}

/* Rest positions t_row (row + sx rgt) of n (a multiple of VBLK) rays of a row that all meet
 * the sea plane within dmax; restrict parameters let the compiler vectorise without alias
 * checks. */
static void project_row(int n, double t_row, const double row[3], const double rgt[2],
                        const double *restrict sx, float *restrict x, float *restrict y)
{
    const double r0 = row[0], r1 = row[1], g0 = rgt[0], g1 = rgt[1];
    for (int b = 0; b < n; b += VBLK)
        for (int e = 0; e < VBLK; e++) {
            x[b + e] = (float)(t_row * (r0 + sx[b + e] * g0));
            y[b + e] = (float)(t_row * (r1 + sx[b + e] * g1));
        }
}

/* grid_foot_at for n (a multiple of VBLK) vertices of a flat row-major grid of row width w,
 * reading vertex k + 1 and k + w, right for all but the last column and the last row. */
static void foot_blocks(int n, int w, const float *restrict rx, const float *restrict ry,
                        float *restrict foot)
{
    for (int b = 0; b < n; b += VBLK)
        for (int e = 0; e < VBLK; e++) {
            int k = b + e;
            float fx = maxf(fabsf(rx[k + 1] - rx[k]), fabsf(ry[k + 1] - ry[k]));
            float fy = maxf(fabsf(rx[k + w] - rx[k]), fabsf(ry[k + w] - ry[k]));
            foot[k] = maxf(fx, fy);
        }
}

int update_projected(struct grid *g, const struct camera_frame *view)
{
    struct grid_projection p;
    if (!projection_frame(g, view, &p))
        return 0;
    const double *fwd = p.fwd, *right = p.right, *up = p.up;
    double alt_ray = p.alt_ray, dmax = p.dmax;
    const int w = g->w, h = g->h;
    double *restrict col_sx = g->col_sx;
    float *restrict row_x = g->row_x, *restrict row_y = g->row_y;
    /* Per row the ray is d = row + sx right with row = fwd + sy up (sx, sy: the tangents of the
     * warped angles, grid_warp); right is horizontal, so d_z and the sea-plane hit distance
     * alt_ray / -d_z are the row's; a ray hits the plane within dmax when
     * |d_xy| < -d_z dmax / alt_ray. */
    double rgt[2] = { right[0], right[1] };
    for (int i = 0; i < g->ws; i++)
        col_sx[i] = tan(grid_warp(i < w ? (double)i / (w - 1) : 1.0, p.col_ang, p.col_split, 4));
    for (int j = 0; j < h; j++) {
        double sy = grid_row_tan(&p, (double)j / (h - 1));
        double row[3], t_row = 0.0, lim2 = -1.0;
        for (int c = 0; c < 3; c++)
            row[c] = fwd[c] + sy * up[c];
        if (-row[2] > 0.0) {
            double lim = -row[2] * dmax / alt_ray;
            t_row = alt_ray / -row[2];
            lim2 = lim * lim;
        }
        /* |d_xy|^2 is convex in sx: when both end rays hit the plane within dmax, all do */
        double ex0 = row[0] + col_sx[0] * rgt[0], ey0 = row[1] + col_sx[0] * rgt[1];
        double ex1 = row[0] + col_sx[w - 1] * rgt[0], ey1 = row[1] + col_sx[w - 1] * rgt[1];
        if (ex0 * ex0 + ey0 * ey0 < lim2 && ex1 * ex1 + ey1 * ey1 < lim2) {
            project_row(g->ws, t_row, row, rgt, col_sx, row_x, row_y);
        } else {
            for (int i = 0; i < w; i++) {
                double sx = col_sx[i];
                double dx = row[0] + sx * rgt[0], dy = row[1] + sx * rgt[1];
                double dxy2 = dx * dx + dy * dy, t;
                /* Rays at or above the horizon end at the far distance along their azimuth. */
                t = dxy2 < lim2 ? t_row : dmax / (dxy2 > 1e-24 ? sqrt(dxy2) : 1e-12);
                row_x[i] = (float)(t * dx);
                row_y[i] = (float)(t * dy);
            }
        }
        memcpy(g->rx + (size_t)j * w, row_x, sizeof(float) * (size_t)w);
        memcpy(g->ry + (size_t)j * w, row_y, sizeof(float) * (size_t)w);
    }
    /* footprints (grid_foot_at) by blocks over the flat arrays, reading the next vertex and the
     * one a row down; the last column and the last row, whose neighbours are the previous ones,
     * are redone one by one, and the padding copies the last vertex (neutral for lo and hi) */
    const float *restrict rx = g->rx, *restrict ry = g->ry;
    float *restrict foot = g->foot;
    float lo8[VBLK], hi8[VBLK];
    foot_blocks(g->npad, w, rx, ry, foot);
    for (int j = 0; j < h; j++)
        foot[(size_t)j * w + w - 1] = grid_foot_at(g, w - 1, j);
    for (int i = 0; i < w; i++)
        foot[(size_t)(h - 1) * w + i] = grid_foot_at(g, i, h - 1);
    for (int k = g->nverts; k < g->npad; k++)
        foot[k] = foot[g->nverts - 1];
    for (int e = 0; e < VBLK; e++) {
        lo8[e] = INFINITY;
        hi8[e] = 0.0f;
    }
    for (int b = 0; b < g->npad; b += VBLK)
        for (int e = 0; e < VBLK; e++) {
            float f = foot[b + e];
            lo8[e] = f < lo8[e] ? f : lo8[e];
            hi8[e] = f > hi8[e] ? f : hi8[e];
        }
    float lo = INFINITY, hi = 0.0f;
    for (int e = 0; e < VBLK; e++) {
        lo = lo8[e] < lo ? lo8[e] : lo;
        hi = maxf(hi, hi8[e]);
    }
    g->foot_lo = g->foot_lo_wet = lo;
    g->foot_hi = hi;
    /* each grid row's smallest squared distance (row_distances) */
    for (int j = 0; j < h; j++) {
        const float *x = rx + (size_t)j * w, *y = ry + (size_t)j * w;
        float m8[VBLK], m = INFINITY;
        int i = 0;
        for (int e = 0; e < VBLK; e++)
            m8[e] = INFINITY;
        for (; i + VBLK <= w; i += VBLK)
            for (int e = 0; e < VBLK; e++) {
                float d2 = x[i + e] * x[i + e] + y[i + e] * y[i + e];
                m8[e] = d2 < m8[e] ? d2 : m8[e];
            }
        for (; i < w; i++) {
            float d2 = x[i] * x[i] + y[i] * y[i];
            m = d2 < m ? d2 : m;
        }
        for (int e = 0; e < VBLK; e++)
            m = m8[e] < m ? m8[e] : m;
        g->row_d2[j] = m;
    }
    return g->nidx;
}

/* Hu 2006 §3: a square near patch of fine cells around the camera, snapped to its cell size in
 * world space (no swimming), whose displacement fades to zero on its border (Hu: border heights
 * forced to zero so the patches stitch), and a flat far patch of FAR_RINGS square rings growing
 * geometrically from the near border to the far plane, bump-mapped only. */
int update_patches(struct grid *g, const struct camera_frame *view)
{
    const struct camera *cam = &view->cam;
    double alt = view->footprint_alt_m;
    double half = fmin(fmax(8.0 * alt, 64.0), 4000.0);
    double cell = 2.0 * half / (NEAR_N - 1);
    double ox = -(cam->pos[0] - cell * floor(cam->pos[0] / cell));
    double oy = -(cam->pos[1] - cell * floor(cam->pos[1] / cell));
    double dmax = far_distance(g, view);
    double q = pow(fmax(dmax / half, 1.0001), 1.0 / FAR_RINGS);
    int per = 4 * (NEAR_N - 1), near0 = (FAR_RINGS + 1) * per;
    double inv = 1.0 / (NEAR_N - 1);
    for (int k = 0; k <= FAR_RINGS; k++) {
        double s = half * pow(q, k);
        float foot = (float)fmax(s * (q - 1.0), 2.0 * s * inv);
        for (int m = 0; m < per; m++) {
            int side = m / (NEAR_N - 1), e = m % (NEAR_N - 1);
            double a = -1.0 + 2.0 * e * inv, x, y;
            switch (side) {
            case 0: x = a; y = -1.0; break;
            case 1: x = 1.0; y = a; break;
            case 2: x = -a; y = 1.0; break;
            default: x = -1.0; y = -a; break;
            }
            g->rx[k * per + m] = (float)(ox + s * x);
            g->ry[k * per + m] = (float)(oy + s * y);
            g->foot[k * per + m] = foot;
        }
    }
    for (int j = 0; j < NEAR_N; j++)
        for (int i = 0; i < NEAR_N; i++) {
            double x = -1.0 + 2.0 * i * inv, y = -1.0 + 2.0 * j * inv;
            g->rx[near0 + j * NEAR_N + i] = (float)(ox + half * x);
            g->ry[near0 + j * NEAR_N + i] = (float)(oy + half * y);
            g->foot[near0 + j * NEAR_N + i] = (float)cell;
        }
    /* the rings' footprints grow outwards from the near patch's cell; only the near patch has
     * fade > 0 */
    g->foot_lo = g->foot_lo_wet = (float)cell;
    g->foot_hi = fmaxf((float)cell, g->foot[FAR_RINGS * per]);
    for (int k = 0; k < FAR_RINGS * per; k += per)
        g->foot_lo = fminf(g->foot_lo, g->foot[k]);
    return g->nidx;
}

/* Smallest squared horizontal distance from the camera of each row's vertices, from their rest
 * positions: on the projected grid the smaller of its two grid rows' (update_projected); on a
 * far ring, of its two borders' vertices; on near ring k, a bound from below: the distance to
 * the square of vertices its cells surround (0 for the innermost, which holds the camera). */
void row_distances(struct grid *g)
{
    int per = 4 * (NEAR_N - 1), near0 = (FAR_RINGS + 1) * per, mid = NEAR_RINGS;
    for (int r = 0; r < g->rows; r++) {
        if (g->kind == GEOMETRY_GRID) {
            float a = g->row_d2[r], b = g->row_d2[r + 1];
            g->row_foot[r] = b < a ? b : a;
            continue;
        }
        if (r >= FAR_RINGS) {
            int k = NEAR_RINGS - 1 - (r - FAR_RINGS);
            float m = 0.0f;
            if (k > 0) {
                const float *xs = g->rx + near0 + (size_t)mid * NEAR_N;   /* x by column */
                float x0 = fabsf(xs[mid - k]), x1 = fabsf(xs[mid + k]);
                float y0 = fabsf(g->ry[near0 + (size_t)(mid - k) * NEAR_N + mid]);
                float y1 = fabsf(g->ry[near0 + (size_t)(mid + k) * NEAR_N + mid]);
                m = minf(minf(x0, x1), minf(y0, y1));
            }
            g->row_foot[r] = m * m;
            continue;
        }
        /* ring k = FAR_RINGS - 1 - r is drawn r-th (outermost first) */
        int k = FAR_RINGS - 1 - r, a0 = k * per, b0 = (k + 1) * per;
        float m = INFINITY;
        for (int e = 0; e < 2; e++) {
            const float *x = g->rx + (e ? b0 : a0), *y = g->ry + (e ? b0 : a0);
            for (int i = 0; i < per; i++) {
                float d2 = x[i] * x[i] + y[i] * y[i];
                m = d2 < m ? d2 : m;    /* fminf is a libm call at -O2 on x86 */
            }
        }
        g->row_foot[r] = m;
    }
}

/* The projected grid's frame for a camera, as update_projected() builds it (tiers with vertex
 * texture fetch build the vertices in ocean.vert from it). Also fills the rows' distances from
 * each row's nearest ray (the centre column's: right is horizontal and perpendicular to the
 * view's azimuth, so along a row of constant NDC y the horizontal distance is least at x = 0,
 * or at the column nearest it).
 * Returns 0 when no sea is in view. */
int grid_projection(struct grid *g, const struct camera_frame *view, struct grid_projection *p)
{
    if (!projection_frame(g, view, p) || g->kind != GEOMETRY_GRID)
        return 0;
    for (int r = 0; r < g->rows; r++) {
        /* row r spans grid rows r (farther) and r + 1 (nearer) */
        double sy = grid_row_tan(p, (double)(r + 1) / (g->h - 1));
        double sx = tan(fmin(fmax(0.0, p->col_ang[0]), p->col_ang[3])), d[3], dxy, t;
        for (int c = 0; c < 3; c++)
            d[c] = p->fwd[c] + sx * p->right[c] + sy * p->up[c];
        dxy = sqrt(d[0] * d[0] + d[1] * d[1]);
        t = -d[2] * p->dmax > p->alt_ray * dxy ? p->alt_ray / -d[2] : p->dmax / fmax(dxy, 1e-12);
        g->row_foot[r] = (float)(t * t * dxy * dxy);
    }
    return g->nidx;
}
