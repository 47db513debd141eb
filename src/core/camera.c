/* camera.c - the viewer (camera.h): defaults, scripted paths, camera-relative matrices. */
#include <math.h>
#include <string.h>
#include "core/camera.h"
#include "core/parse.h"

#define CAM_PI 3.14159265358979323846

static const char *const path_names[CAMERA_PATH_COUNT] = { "none", "surface", "1km", "10km",
                                                                 "orbit" };

void camera_defaults(struct camera *c)
{
    memset(c, 0, sizeof(*c));
    c->pos[2] = 10.0;
    c->heading_deg = 0.0f;
    c->pitch_deg = -10.0f;
    c->fov_y_deg = 45.0f;
}

/* Paths loop every 120 s so a long run revisits the same views; the heading turns slowly
 * (3 deg/s at most) so consecutive frames stay comparable. */
void camera_path_at(int path, double t_s, struct camera *out)
{
    double u = fmod(t_s, 120.0) / 120.0;
    if (u < 0.0)
        u += 1.0;
    camera_defaults(out);
    switch (path) {
    case CAMERA_PATH_SURFACE:
        out->pos[0] = 0.0;
        out->pos[1] = 0.0;
        out->pos[2] = 5.0;
        out->heading_deg = (float)(360.0 * u);
        out->pitch_deg = -8.0f;
        break;
    case CAMERA_PATH_1KM:
        out->pos[0] = 400.0 * t_s;     /* slow flight east, 400 m/s: a jet at cruise */
        out->pos[2] = 1000.0;
        out->heading_deg = (float)(20.0 * sin(2.0 * CAM_PI * u));
        out->pitch_deg = -12.0f;
        break;
    case CAMERA_PATH_10KM:
        out->pos[0] = 250.0 * t_s;
        out->pos[2] = 10000.0;
        out->heading_deg = (float)(360.0 * u);
        out->pitch_deg = -25.0f;
        break;
    case CAMERA_PATH_ORBIT:
        /* low Earth orbit, 400 km, 7.7 km/s east, looking ahead and down at the limb (20 deg
         * below the level there), turning slowly towards the sun's side and back */
        out->pos[0] = 7700.0 * t_s;
        out->pos[2] = 400000.0;
        out->heading_deg = (float)(30.0 * sin(2.0 * CAM_PI * u));
        out->pitch_deg = -28.0f;
        break;
    default:
        break;
    }
}

int camera_path_from_name(const char *name)
{
    return parse_name(path_names, 0, CAMERA_PATH_COUNT, name);
}

const char *camera_path_name(int path)
{
    return name_of(path_names, CAMERA_PATH_COUNT, path);
}

void camera_view_rel(const struct camera *c, mat4 view)
{
    float h = glm_rad(c->heading_deg), p = glm_rad(c->pitch_deg);
    vec3 eye = { 0.0f, 0.0f, 0.0f };
    vec3 fwd = { cosf(p) * cosf(h), cosf(p) * sinf(h), sinf(p) };
    vec3 up = { 0.0f, 0.0f, 1.0f };
    /* Looking straight up or down makes z a degenerate up vector: use the heading instead. */
    if (fabsf(fwd[2]) > 0.9999f) {
        up[0] = -cosf(h) * (fwd[2] > 0.0f ? 1.0f : -1.0f);
        up[1] = -sinf(h) * (fwd[2] > 0.0f ? 1.0f : -1.0f);
        up[2] = 0.0f;
    }
    if (c->roll_deg != 0.0f) {
        /* the level up vector turned about the view axis: up' = cos r up - sin r right, with
         * right = fwd x up (normalised) */
        float r = glm_rad(c->roll_deg);
        vec3 right, lvl;
        glm_vec3_cross(fwd, up, right);
        glm_vec3_normalize(right);
        glm_vec3_cross(right, fwd, lvl);
        glm_vec3_normalize(lvl);
        for (int k = 0; k < 3; k++)
            up[k] = cosf(r) * lvl[k] - sinf(r) * right[k];
    }
    glm_look(eye, fwd, up, view);
}

/* Near/far from altitude when not given: near a tenth of the height above the local surface
 * (at least 5 cm; a camera CAMERA_CLEARANCE_M above a crest still sees the water below it)
 * keeps the nearest waves in front of it; far reaches past the geometric horizon of a curved
 * Earth, 2 sqrt(2 R h), with a 50 km floor for surface views. */
void camera_clip_planes(const struct camera *c, float *n, float *f)
{
    double alt = fabs(c->pos[2] - c->surface_z_m);
    double near_m = c->near_m > 0.0f ? c->near_m : fmax(0.05, fmin(0.1 * alt, 100.0));
    double far_m = c->far_m > 0.0f ? c->far_m
                                    : fmax(5.0e4, 4.0 * sqrt(2.0 * EARTH_RADIUS_M * fmax(alt, 1.0)));
    if (far_m <= near_m)
        far_m = near_m * 2.0;
    *n = (float)near_m;
    *f = (float)far_m;
}

void camera_projection(const struct camera *c, float aspect, mat4 proj)
{
    float n, f;
    float fov = c->fov_y_deg > 0.0f ? c->fov_y_deg : CAMERA_FOV_DEFAULT_DEG;
    camera_clip_planes(c, &n, &f);
    glm_perspective_rh_no(glm_rad(fov), aspect > 0.0f ? aspect : 1.0f, n, f, proj);
}

void camera_basis(double h_deg, double p_deg, double fwd[3], double right[3], double up[3])
{
    double h = h_deg * M_PI / 180.0, p = p_deg * M_PI / 180.0;
    fwd[0] = cos(p) * cos(h); fwd[1] = cos(p) * sin(h); fwd[2] = sin(p);
    right[0] = sin(h); right[1] = -cos(h); right[2] = 0.0;
    up[0] = right[1] * fwd[2] - right[2] * fwd[1];
    up[1] = right[2] * fwd[0] - right[0] * fwd[2];
    up[2] = right[0] * fwd[1] - right[1] * fwd[0];
}

float camera_fov_covered(float fov_y_deg, float aspect)
{
    double fov = fov_y_deg > 0.0f ? fov_y_deg : CAMERA_FOV_DEFAULT_DEG;
    double ty = tan(0.5 * fov * M_PI / 180.0), a = aspect > 0.0f ? aspect : 1.0;
    double tmax = tan(CAMERA_HALF_DIAGONAL_MAX_DEG * M_PI / 180.0);
    if (ty * sqrt(1.0 + a * a) <= tmax)
        return (float)fov;
    return (float)(2.0 * atan(tmax / sqrt(1.0 + a * a)) * 180.0 / M_PI);
}

void camera_frame_make(const struct camera *c, int width, int height, struct camera_frame *out)
{
    memset(out, 0, sizeof *out);
    out->cam = *c;
    out->width = width;
    out->height = height;
    out->aspect = height > 0 ? (float)width / (float)height : 1.0f;
    camera_clip_planes(c, &out->near_m, &out->far_m);
    float fov_deg = c->fov_y_deg > 0.0f ? c->fov_y_deg : CAMERA_FOV_DEFAULT_DEG;
    out->fov_y_rad = fov_deg * M_PI / 180.0;
    double ty = tan(0.5 * out->fov_y_rad), tx = ty * out->aspect;
    out->tan_lrbt[0] = -tx;
    out->tan_lrbt[1] = tx;
    out->tan_lrbt[2] = -ty;
    out->tan_lrbt[3] = ty;
    camera_basis(c->heading_deg, c->pitch_deg, out->fwd, out->right, out->up);
    if (c->roll_deg != 0.0f) {
        double r = c->roll_deg * M_PI / 180.0, cr = cos(r), sr = sin(r);
        for (int k = 0; k < 3; k++) {
            double rk = out->right[k], uk = out->up[k];
            out->right[k] = cr * rk + sr * uk;
            out->up[k] = cr * uk - sr * rk;
        }
    }
    float fov_f = fov_deg * (float)(M_PI / 180.0);
    out->pixel_rad = 2.0f * tanf(0.5f * fov_f) / (float)(height > 0 ? height : 1);
    out->footprint_alt_m = c->pos[2] > CAMERA_FOOTPRINT_MIN_ALT_M ? c->pos[2]
                                                                  : CAMERA_FOOTPRINT_MIN_ALT_M;
    camera_view_rel(c, out->view_rel);
    camera_projection(c, out->aspect, out->proj);
    glm_mat4_mul(out->proj, out->view_rel, out->world_to_clip);
}
