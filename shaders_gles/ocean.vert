// ocean.vert - CPU-displaced sea vertices (gles2-min: no vertex texture fetch). Positions are
// validate: FS_PATTERNS=0 FS_WHITECAPS=0 | FS_PATTERNS=1 FS_WHITECAPS=1 | FS_PATTERNS=2 FS_WHITECAPS=0 | FS_PATTERNS=3 FS_WHITECAPS=2 | FS_PATTERNS=4 FS_WHITECAPS=2 | FS_PATTERNS=4 FS_WHITECAPS=0 VTF_PATTERNS=4 | FS_PATTERNS=2 FS_WHITECAPS=1 VTF_PATTERNS=3 | FS_PATTERNS=1 FS_WHITECAPS=0 VTF_PATTERNS=1 | FS_PATTERNS=4 FS_WHITECAPS=0 VTF_PATTERNS=4 SWELL_NO_DETILE
// camera-relative; texture coordinates are a per-pattern offset wrapped on the CPU in double
// plus the camera-relative rest position over the patch size, so they stay small.
//
// Shading is linearised here in the fine-scale slope: the two lookups of both passes depend on
// the pixel only through its slope s = s0 + ds, so this stage evaluates their coordinates (Hu
// §5.1's Fresnel texture at the bumped view vector, Bruneton §5.2's sky map at the reflected
// ray) at the vertex's mean slope s0 and their central differences over +-h (h: the fetched
// patterns' slope deviation), and the fragment stage only adds d(uv)/ds ds: two multiply-adds
// instead of two normalisations, a reflection and a stereographic division per pixel in
// mediump. The slowly varying factors of the Ross BRDF are evaluated here too.
#include "common.glsl"

#ifdef VTF_PATTERNS
// Tiers with vertex texture fetch: the projected grid (Bruneton 2010 §3) is built here from a
// static grid of parameters, and displaced by the streamed displacement tables with the eq. 2
// filter weights, as grid.c does on the CPU for gles2-min (same formulas, see there).
attribute vec2 a_grid;                  // (i, j) / (w - 1, h - 1)
uniform vec3 grid_fwd;                  // camera basis, world
uniform vec3 grid_right;
uniform vec3 grid_up;
uniform vec4 grid_frame;                // column shares at the screen's edges (grid.h
                                        // col_split), altitude, projector height
uniform vec4 grid_range;                // column angles: left, screen left, right, right edge
uniform vec4 grid_rows;                 // the camera's depression at the top row and the
                                        // screen bottom, their rows' share, its height (grid.h)
uniform vec3 grid_rows_hz;              // the horizon rows: 1 / one row, u*, the even slope
uniform vec3 grid_margin;               // projector angles of the screen bottom and the last
                                        // row; minus the projector's pitch, radians
uniform vec3 grid_step;                 // one cell in a_grid units (x, y); far distance, m
uniform vec4 disp_scale[4];             // RGBA8 dequantisation of each pattern's table; w: the
uniform vec4 disp_bias[4];              // blend weight of loop frame b (frames a, b bound)
uniform vec4 disp_pattern[4];           // uv offset xy, 1 / L_i, eq. 2 wavelength, m
uniform sampler2D disp_a0;
uniform sampler2D disp_b0;
uniform sampler2D detile_tex;           // the Fresnel atlas (renderer.c fresnel_atlas): its hash
uniform vec4 detile_atlas_v;            // 1 / its size, the hash rows' origin (v)
uniform vec2 disp_cell[4];              // the camera's lattice cell modulo DETILE_N plus the
                                        // pattern's own shift (detile.h)
#if VTF_PATTERNS > 1
uniform sampler2D disp_a1;
uniform sampler2D disp_b1;
#endif
#if VTF_PATTERNS > 2
uniform sampler2D disp_a2;
uniform sampler2D disp_b2;
#endif
#if VTF_PATTERNS > 3
uniform sampler2D disp_a3;
uniform sampler2D disp_b3;
#endif

// The sea-plane point of grid parameter g: its ray from the projector (grid.h: the warped
// angles of grid_warp) meets the sea plane, rays at or above the horizon end at the far
// distance; rest points are camera-relative.
vec2 grid_rest(vec2 g)
{
    float ax = g.x < grid_frame.x ? mix(grid_range.x, grid_range.y, g.x / grid_frame.x)
             : g.x < grid_frame.y ? mix(grid_range.y, grid_range.z,
                                        (g.x - grid_frame.x) / (grid_frame.y - grid_frame.x))
             : mix(grid_range.z, grid_range.w, (g.x - grid_frame.y) / max(1.0 - grid_frame.y, 1e-6));
    // grid_row_tan: rows on the screen in the camera's depression dc, evenly but for the
    // horizon rows' halving distances, seen from the projector at depression
    // atan2(A sin dc, h cos dc); the rest evenly in its own angle
    float u = g.y / grid_rows.z;
    float xs = grid_rows.x * (exp2(grid_rows_hz.y * grid_rows_hz.x) - 1.0);
    float dc = grid_rows.x + (u < grid_rows_hz.y ? grid_rows.x * (exp2(u * grid_rows_hz.x) - 1.0)
                                                 : xs + grid_rows_hz.z * (u - grid_rows_hz.y));
    float ay = g.y < grid_rows.z
        ? grid_margin.z - atan(grid_frame.w * sin(dc), grid_rows.w * cos(dc))
        : mix(grid_margin.x, grid_margin.y, (g.y - grid_rows.z) / max(1.0 - grid_rows.z, 1e-6));
    vec3 d = grid_fwd + tan(min(ax, 1.5)) * grid_right + tan(ay) * grid_up;
    float dxy = length(d.xy);
    float t = -d.z * grid_step.z > grid_frame.w * dxy ? grid_frame.w / -d.z
                                                      : grid_step.z / max(dxy, 1e-12);
    return t * d.xy;
}

// One tap: loop frames a and b blended here in float (no CPU blend, no requantisation).
vec3 disp_tap(sampler2D a, sampler2D b, int i, vec2 uv)
{
    vec3 t = mix(texture2DLod(a, uv, 0.0).xyz, texture2DLod(b, uv, 0.0).xyz, disp_scale[i].w);
    return disp_bias[i].xyz + disp_scale[i].xyz * t;
}

// Pattern i's displacement read at its lattice's three random offsets and blended (detile.h,
// as grid.c detile_taps_cell), weighted by Bruneton eq. 2: 0 for waves shorter than 2 cells,
// 1 from 4 cells up (grid.c).
vec3 displacement(sampler2D a, sampler2D b, int i, vec2 rest, float foot)
{
    float u = clamp((disp_pattern[i].w / foot - 2.0) / 2.0, 0.0, 1.0);
    vec2 uv = disp_pattern[i].xy + rest * disp_pattern[i].z;
#ifdef SWELL_NO_DETILE
    vec3 d = disp_tap(a, b, i, uv);     // renderer_desc no_detile: one tap, the tile repeats
#else
    vec2 c, f;
    vec4 h = texture2DLod(detile_tex, detile_cell(uv, disp_cell[i], detile_atlas_v, c, f), 0.0);
    vec3 ox, oy;
    detile_offsets(detile_bytes(h, f), ox, oy);
    vec3 w = detile_weights(f);
    vec3 d = w.x * disp_tap(a, b, i, uv + vec2(ox.x, oy.x)) +
             w.y * disp_tap(a, b, i, uv + vec2(ox.y, oy.y)) +
             w.z * disp_tap(a, b, i, uv + vec2(ox.z, oy.z));
#endif
    return u * u * (3.0 - 2.0 * u) * d;
}
#else
attribute vec3 a_pos;       // displaced, camera-relative, m
attribute vec2 a_rest;      // rest position on the sea plane, camera-relative, m
attribute vec4 a_geo_slope; // CPU patterns: mean slope xy, resolved slope variance xy
attribute vec2 a_geo_k;     // CPU patterns: foam memory mean, variance (Dupuy eq. 7-8)
#endif

uniform mat4 world_to_clip;             // camera-relative world -> clip
uniform vec2 fresnel_uv_scale;          // the Fresnel texels' share of the atlas (renderer.c)
uniform vec2 pattern_uv_offset[4];      // per fragment-shader pattern slot
uniform float pattern_inv_size[4];      // 1 / L_i, 1/m

uniform vec3 lin_s0;        // xy: mean slope of every fragment pattern slot; z: step h
uniform vec2 lod_frame;     // the camera's altitude squared, log2(pixel angle / altitude):
                            // lod_foot's terms (renderer.c set_lod_frame)
uniform vec3 sun_dir_world;
uniform vec3 haze_tau;      // aerial perspective (sky.h sky_haze): vertical optical depth,
uniform vec2 haze_frame;    // the air mass per metre of path from the camera's height:
                            // (1 - e^{-h/H}) / h; Mie g
#ifndef QUALITY_HIGH
uniform vec3 haze_ray;      // the horizon's Rayleigh and Mie radiances before the phase
uniform vec3 haze_mie;      // functions (x exposure)
#endif
#ifndef QUALITY_HIGH
varying vec4 v_fog;         // in-scattered light, the sea's transmittance
#endif
varying vec4 v_lin;         // Fresnel-texture uv, sky-map uv at s0
varying vec4 v_lin_dx;      // their derivatives in s.x ...
varying vec4 v_lin_dy;      // ... and s.y
uniform vec4 const_slope;               // slots not fetched: -, -, slope variance xy
uniform vec2 const_k;                   // ...their foam memory mean and variance
uniform vec2 unresolved_var;            // slope variance below every table (Bruneton eq. 4)
uniform vec2 total_var;                 // every pattern's slope variance + unresolved_var
#if FS_WHITECAPS == 0 || !defined(QUALITY_HIGH)
uniform float whitecap_epsilon_v;       // Dupuy eq. 3's threshold (ocean.frag's, own name: a
                                        // uniform in both stages needs one precision)
#endif
varying vec4 v_sun;         // zeta_h - s0, the Ross factor, eq. 25's x weight (low: the Ross
                            // factor over 2 pi sigma_x sigma_y, eq. 26's exponent)
#ifdef QUALITY_HIGH
uniform float sky_map_size;             // texels
varying vec4 v_base;        // slope variance xy, foam memory mean and variance not fetched
varying vec4 v_extra;       // coverage (no whitecap fetched), sky LOD offset, the haze's
                            // transmittance, lod_foot (so high quality's varyings fit GLES2's
                            // 8 rows)
#else
uniform vec4 var_knot_v[2];             // the fetched slots' pixel slope variance at 4
uniform vec2 var_knot_frame_v;          // footprints (x; y), the first's footprint, knots per
                                        // unit of footprint (fetched_var)
uniform vec3 foam_radiance;             // Lambertian 0.4 foam lit by sun and sky (x exposure)
varying vec4 v_base;        // 0.5 / the slope variance, xy; eq. 26's k; lod_foot
#endif
// the slots' uv in pairs (vec4: one varying row, one store on Mali-400's vertex unit)
#if FS_PATTERNS > 1
varying vec4 v_uv01;
#elif FS_PATTERNS > 0
varying vec2 v_uv01;
#endif
#if FS_PATTERNS > 3
varying vec4 v_uv23;
#elif FS_PATTERNS > 2
varying vec2 v_uv23;
#endif

// The two lookups for view v and sea slope s: Hu §5.1's Fresnel texture at the view vector
// bumped by the normal's tilt (kept in the unit disc the texture covers) and the sky map at the
// reflected ray; normals facing away from the viewer are reflected first (Bruneton §3.2).
vec3 facing_normal(vec3 v, vec2 s)
{
    vec3 n = vec3(-s, 1.0);
    return normalize(n - 2.0 * min(dot(n, v), 0.0) * v);
}

vec4 lookups(vec3 v, vec2 s)
{
    vec3 n = facing_normal(v, s);
    vec2 fv = v.xy - n.xy;
    float rho = length(fv);
    // fresnel.h: radius r = 1 - sqrt(1 - theta / (pi / 2)), theta = asin(rho)
    float r = 1.0 - sqrt(max(1.0 - asin(min(rho, 1.0)) / (0.5 * PI), 0.0));
    fv *= r / max(rho, 1e-6);
    return vec4((vec2(0.5) + 0.5 * fv) * fresnel_uv_scale, sky_map_uv(reflect(-v, n)));
}

// Aerial perspective from the sky model (sky.h sky_haze): the path of length |p| to the
// camera has air mass |p| (1 - e^{-h/H}) / h through the exponential atmosphere, transmittance
// e^{-tau m} per channel, and scatters in (1 - T) times the horizon sky of its azimuth.
vec3 haze_trans(vec3 p)
{
    return exp(-haze_tau * (length(p) * haze_frame.x));
}

#ifdef QUALITY_HIGH
// High quality: the green channel's transmittance only (GLES2's 8 varying rows are full);
// ocean.frag derives the others from it and evaluates the in-scattered horizon sky per pixel.
float haze_t(vec3 p)
{
    return haze_trans(p).g;
}
#else
vec4 haze(vec3 p)
{
    vec3 t = haze_trans(p);
    float cg = dot(p.xy / max(length(p.xy), 1e-6), sun_dir_world.xy);
    vec3 sky_h = horizon_sky(cg, haze_frame.y, haze_ray, haze_mie);
    // low quality: each channel's in-scattered light, green's transmittance for the sea's
    // every channel (ocean.frag mixes before the tone map, as high quality does with each
    // channel's; with green's for the in-scattered light too the sea 10 km out was 7 % off
    // high's in the 8-row means, test_quality_match, with blue's 7 % at 1 km)
    return vec4(sky_h * (1.0 - t), t.g);
}
#endif

// log2 of the pixel footprint along the view at rest point p on the sea plane, m: (d^2 + a^2) /
// a times the pixel's angle at horizontal distance d from a camera at altitude a, as the
// renderer takes it per row (renderer.c row_footprint); ocean.frag fades each pattern by it
// where the renderer stops fetching it, and matches its run's mip level to it.
float lod_foot(vec2 p)
{
    return log2(dot(p, p) + lod_frame.x) + lod_frame.y;
}

#ifndef QUALITY_HIGH
// Low quality takes the pixel's slope variance per vertex: each fetched slot's, as high
// quality's g v + (1 - g) W + (1 - g^2) (T - W) (ocean.frag add_slope) with the fetched
// within-texel variance v at its mean W over the level read there. It depends on the vertex's
// footprint f alone, so renderer.c (pixel_var_at) tabulates it per run at 4 footprints and
// this reads it back linearly: 20 instructions on Vivante for any number of slots, where the
// loop over the slots cost 28 each (8 knots cost Mali-400 23 more: its 2- to 4-slot programs
// passed 512).
vec2 fetched_var(float f)
{
#if FS_PATTERNS > 0
    // linear between knots as the sum of their hat functions: no dynamic index (one, into
    // 16 knots, cost Mali-400 and Vivante as much)
    float t = clamp((f - var_knot_frame_v.x) * var_knot_frame_v.y, 0.0, 3.0);
    vec4 w = max(1.0 - abs(vec4(t) - vec4(0.0, 1.0, 2.0, 3.0)), 0.0);
    return vec2(dot(w, var_knot_v[0]), dot(w, var_knot_v[1]));
#else
    return vec2(0.0);
#endif
}
#endif

void main()
{
#ifdef VTF_PATTERNS
    vec2 a_rest = grid_rest(a_grid);
    // footprint: the larger side of the cell towards the next column and row (grid.c)
    vec2 ex = abs(grid_rest(a_grid + vec2(grid_step.x, 0.0)) - a_rest);
    vec2 ey = abs(grid_rest(a_grid + vec2(0.0, grid_step.y)) - a_rest);
    float foot = max(max(ex.x, ex.y), max(ey.x, ey.y));
    vec3 disp = displacement(disp_a0, disp_b0, 0, a_rest, foot);
#if VTF_PATTERNS > 1
    disp += displacement(disp_a1, disp_b1, 1, a_rest, foot);
#endif
#if VTF_PATTERNS > 2
    disp += displacement(disp_a2, disp_b2, 2, a_rest, foot);
#endif
#if VTF_PATTERNS > 3
    disp += displacement(disp_a3, disp_b3, 3, a_rest, foot);
#endif
    // the sphere's drop R - sqrt(R^2 - r^2), in its exact-near-the-camera form (grid.c)
    float r2 = dot(a_rest, a_rest);
    vec3 a_pos = vec3(a_rest + disp.xy,
                      disp.z - grid_frame.z - r2 / (EARTH_R + sqrt(max(EARTH_R2 - r2, 0.0))));
    vec4 a_geo_slope = vec4(0.0);   // no CPU patterns on these tiers
    vec2 a_geo_k = vec2(0.0);
#endif
    vec3 v = normalize(-a_pos);
    // the sphere's own slope at the rest point (its drop R - sqrt(R^2 - r^2) differentiated) tilts
    // every distant normal towards the camera's vertical
    vec2 s0 = a_geo_slope.xy + lin_s0.xy -
              a_rest * inversesqrt(max(EARTH_R2 - dot(a_rest, a_rest), 1.0));
    float h = lin_s0.z;
    // The value at s0 and forward differences over h: three lookups. Central differences
    // (five) cost 45 more of a vertex shader's 365 instructions on Vivante per pair; the mean of
    // four at s0 +- h instead of the value moved the rows below the horizon by up to 35 of 255
    // (the lookups bend there: the sky map's horizon clamp). The forward difference is the
    // derivative at s0 + h/2; the pixel's ds has mean 0, so its mean stays f(s0).
    v_lin = lookups(v, s0);
    v_lin_dx = (lookups(v, s0 + vec2(h, 0.0)) - v_lin) / h;
    v_lin_dy = (lookups(v, s0 + vec2(0.0, h)) - v_lin) / h;
    // Ross BRDF (Bruneton eq. 15) = p(zeta_h) F(v.h) / (4 cos_v cos^4 theta_h (1 + L(v) + L(l))):
    // the slope density p is the pixel's (ocean.frag); the rest varies slowly and is evaluated
    // here at the vertex's mean normal, the shadowing with the sea's whole slope variance.
    vec3 l = sun_dir_world;
    vec3 n = facing_normal(v, s0);
    vec3 hv = normalize(v + l);
    vec3 tx = normalize(vec3(n.z, 0.0, -n.x));
    vec3 ty = cross(n, tx);
    vec2 vt = vec2(dot(v, tx), dot(v, ty));
    float wx = dot(vt, vt) > 1e-6 ? vt.x * vt.x / dot(vt, vt) : 0.5;   // eq. 25's weights
    float cos_v = max(dot(v, n), 0.01), cos_l = dot(l, n);
    float hn = max(dot(hv, n), 0.05);
    float var_v = mix(total_var.y, total_var.x, wx) + dot(a_geo_slope.zw, vec2(wx, 1.0 - wx));
    float c5 = 1.0 - clamp(dot(v, hv), 0.0, 1.0);
    float fs = 0.02 + 0.98 * c5 * c5 * c5 * c5 * c5;   // Schlick, as in eq. 15
    vec2 lam = ross_lambda2(vec2(cos_v, cos_l), var_v);
    float shadow = 1.0 + lam.x + lam.y;
    float ross = cos_l > 0.0 ? fs / (8.0 * PI * hn * hn * hn * hn * cos_v * shadow) : 0.0;
    vec2 zeta = -hv.xy / max(hv.z, 0.05) - s0;
    vec2 var_base = a_geo_slope.zw + const_slope.zw + unresolved_var;
    vec2 k_base = a_geo_k.xy + const_k.xy;
#ifdef QUALITY_HIGH
    v_sun = vec4(zeta, ross, wx);
    v_base = vec4(var_base, k_base);
    // eq. 27's footprint in texels is 2 sigma size du/dzeta, du/dzeta = 1 / (1 + r_z)
    vec3 r = reflect(-v, n);
    v_extra = vec4(0.0, log2(2.0 * sky_map_size / (1.0 + max(r.z, 0.0))),
                   haze_t(a_pos), lod_foot(a_rest));
#if FS_WHITECAPS == 0
    // No whitecap table fetched in this run: Dupuy eq. 6's coverage depends on the vertex's
    // moments alone, so it is evaluated here and v_extra.x carries it (exact where no pattern
    // is resolved per vertex, as the moments are then the same at every vertex).
    v_extra.x = whitecap_cover(whitecap_epsilon_v, v_base.z, v_base.w);
#endif
#else
    // Low quality: the pixel's slope variance per vertex (fetched_var), so the vertex carries
    // the Gaussian's inverse variances and normalisation with the Ross factor (ocean.frag)
    // and eq. 26's terms of sigma (common.glsl fresnel_eff_terms).
    float lf = lod_foot(a_rest);
    vec2 var = max(var_base + fetched_var(lf), vec2(1e-4));
    float sig_v = sqrt(mix(var.y, var.x, wx));
    v_sun = vec4(zeta, ross * inversesqrt(var.x * var.y), fresnel_eff_e(sig_v));
    v_base = vec4(0.5 / var, fresnel_eff_k(sig_v), lf);
#endif
#define SLOT_UV(i) (pattern_uv_offset[i] + a_rest * pattern_inv_size[i])
#if FS_PATTERNS > 1
    v_uv01 = vec4(SLOT_UV(0), SLOT_UV(1));
#elif FS_PATTERNS > 0
    v_uv01 = SLOT_UV(0);
#endif
#if FS_PATTERNS > 3
    v_uv23 = vec4(SLOT_UV(2), SLOT_UV(3));
#elif FS_PATTERNS > 2
    v_uv23 = SLOT_UV(2);
#endif
#ifndef QUALITY_HIGH
    // and no whitecap table: eq. 6's coverage from the vertex's moments, as high quality's
    // runs without whitecap fetches take it, mixed in with the haze: the pixel's radiance is
    // its clear sea times v_fog.a plus v_fog.rgb.
    float cover = whitecap_cover(whitecap_epsilon_v, k_base.x, k_base.y);
    vec4 fog = haze(a_pos);
    v_fog = vec4(fog.rgb + foam_radiance * (cover * fog.a), (1.0 - cover) * fog.a);
#endif
    gl_Position = world_to_clip * vec4(a_pos, 1.0);
}
