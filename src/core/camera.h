/* camera.h - the viewer: position, heading, pitch; matrices; scripted paths.
 *
 * Conventions (stated once, used everywhere): world x east, y north, z up, right-handed, metres.
 * Heading: degrees CCW from +x (0 looks east, 90 north). Pitch: degrees, negative looks down.
 * Roll: degrees about the view axis, positive raises the camera's right side.
 * Matrices: cglm column-major mat4, OpenGL clip space (NDC z in [-1, 1]), radians inside.
 * The renderer works camera-relative: world positions minus the camera's, so nothing a shader
 * sees grows with distance (fp16 safety, DESIGN.md).
 */
#ifndef SWELL_CAMERA_H
#define SWELL_CAMERA_H

#include <cglm/cglm.h>

struct camera {
    double pos[3];          /* world position, m (z = altitude above mean sea level) */
    float heading_deg;      /* default 0 */
    float pitch_deg;        /* default -10 */
    float roll_deg;         /* bank about the view axis: positive turns the camera's right side
                               up (the horizon then falls to the right on screen); default 0 */
    float fov_y_deg;        /* vertical field of view; default 45 */
    float near_m, far_m;    /* clip planes; default 0 = chosen from the height above the
                               local surface */
    double surface_z_m;     /* height of the sea surface under the camera, m; default 0 = the
                               mean sea level (the renderer fills it, renderer_frame) */
};

/* Nothing draws a camera closer than this above the local sea surface (renderer_frame raises
 * it, as a boat's or a buoy's camera floats): swell has no view from under the water. */
#define CAMERA_CLEARANCE_M 0.3

/* The Earth's mean radius: the sea is drawn on a sphere (its drop r^2 / (2 R) at distance r;
 * the horizon's dip acos(R / (R + h)) below the level), m. */
#define EARTH_RADIUS_M 6.371e6

enum camera_path {
    CAMERA_PATH_NONE = 0,   /* fixed camera as given */
    CAMERA_PATH_SURFACE,    /* 5 m above the sea, slowly turning */
    CAMERA_PATH_1KM,        /* 1 km altitude, looking at the horizon */
    CAMERA_PATH_10KM,       /* 10 km altitude */
    CAMERA_PATH_ORBIT,      /* 400 km: low Earth orbit, the limb in view */
    CAMERA_PATH_COUNT
};

void camera_defaults(struct camera *c);
/* Camera of a scripted path at time t_s (paths loop). */
void camera_path_at(int path, double t_s, struct camera *out);
int camera_path_from_name(const char *name);   /* CAMERA_PATH_* or -1 */
const char *camera_path_name(int path);

/* The field of view when the camera's is 0, degrees. */
#define CAMERA_FOV_DEFAULT_DEG 45.0f
/* The widest view the projected grid covers: half its diagonal field of view at most 75 deg
 * (the projector keeps its rays within 81 deg of its axis, geometry/grid_project.c). A 45 deg
 * view is within it up to an aspect of 8.5:1; 16:1 had left the sides of the horizon bare. */
#define CAMERA_HALF_DIAGONAL_MAX_DEG 75.0
/* Pixel footprints are taken from at least this altitude, m (a camera at the surface). */
#define CAMERA_FOOTPRINT_MIN_ALT_M 0.5

/* What a frame's users need of the camera, made once per frame (camera_frame_make) and passed
 * down to the renderer's modules, the grid and the sky: none of them recomputes a default, a
 * clip plane, a basis or a matrix from the camera's angles. */
struct camera_frame {
    struct camera cam;          /* as drawn (renderer_frame fills surface_z_m and keeps it
                                 * CAMERA_CLEARANCE_M above the sea) */
    int x, y, width, height;    /* the viewport, pixels (camera_frame_make: 0, 0, w, h) */
    float aspect;               /* width / height (1 without a height) */
    float near_m, far_m;        /* camera_clip_planes */
    double fov_y_rad;           /* the vertical field of view, the default applied */
    double tan_lrbt[4];         /* the frustum's edges, tangents from the view axis: left,
                                 * right, bottom, top (camera_frame_make: symmetric, -t a, t a,
                                 * -t, t with t = tan(fov / 2), a the aspect; an application's
                                 * off-axis projection moves them, renderer_view_frame) */
    double fwd[3], right[3], up[3];  /* the view's orthonormal basis, world axes (rolled) */
    float pixel_rad;            /* one pixel's vertical angle, rad: 2 tan(fov / 2) / height */
    double footprint_alt_m;     /* altitude for pixel footprints, >= CAMERA_FOOTPRINT_MIN_ALT_M */
    mat4 view_rel, proj;        /* camera-relative view (translation removed), projection */
    mat4 world_to_clip;         /* proj x view_rel: camera-relative world to clip space */
};

/* fov_y_deg (0: the default) narrowed where a view of this aspect would pass
 * CAMERA_HALF_DIAGONAL_MAX_DEG: a panoramic strip keeps the widest diagonal the sea covers
 * and loses vertical angle ("Vert-"), instead of drawing bare sides. */
float camera_fov_covered(float fov_y_deg, float aspect);

void camera_frame_make(const struct camera *c, int width, int height, struct camera_frame *out);

/* The basis of a view along heading h and pitch p (degrees): forward, right (horizontal), up. */
void camera_basis(double h_deg, double p_deg, double fwd[3], double right[3], double up[3]);

/* Camera-relative view (translation removed) and projection for an aspect ratio. */
void camera_view_rel(const struct camera *c, mat4 view);
void camera_projection(const struct camera *c, float aspect, mat4 proj);
/* The clip planes camera_projection uses, m. */
void camera_clip_planes(const struct camera *c, float *near_m, float *far_m);

#endif
