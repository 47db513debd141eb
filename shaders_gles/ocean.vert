// ocean.vert - the sea's vertices. On gles2-min (no vertex texture fetch) the CPU displaces
// validate: FS_PATTERNS=2 FS_WHITECAPS=1 CPU_VERTEX_TERMS | FS_PATTERNS=4 FS_WHITECAPS=2 CPU_VERTEX_TERMS | FS_PATTERNS=0 FS_WHITECAPS=0 | FS_PATTERNS=1 FS_WHITECAPS=1 | FS_PATTERNS=2 FS_WHITECAPS=0 | FS_PATTERNS=3 FS_WHITECAPS=2 | FS_PATTERNS=4 FS_WHITECAPS=2 | FS_PATTERNS=4 FS_WHITECAPS=0 VTF_PATTERNS=4 | FS_PATTERNS=2 FS_WHITECAPS=1 VTF_PATTERNS=3 | FS_PATTERNS=1 FS_WHITECAPS=0 VTF_PATTERNS=1 | FS_PATTERNS=4 FS_WHITECAPS=0 VTF_PATTERNS=4 SWELL_NO_DETILE | FS_PATTERNS=2 FS_WHITECAPS=1 SWELL_MASK | FS_PATTERNS=2 FS_WHITECAPS=0 SWELL_MASK CPU_VERTEX_TERMS
// them and this stage evaluates the terms of the vertex alone (vterms.glsl vertex_terms), or,
// where the driver refuses that (CPU_VERTEX_TERMS: Vivante GC2000's 256 instructions), the CPU
// evaluates them too (src/geometry/vshade.c) and this stage only adds each run's constants; on the
// tiers with vertex texture fetch it builds and displaces the projected grid and evaluates
// the terms itself. Positions are
// camera-relative; texture coordinates are a per-pattern offset wrapped on the CPU in double
// plus the camera-relative rest position over the patch size, so they stay small.
//
// Shading is linearised per vertex in the fine-scale slope: the two lookups of both passes
// depend on the pixel only through its slope s = s0 + ds, so the vertex's terms hold their
// coordinates (Hu §5.1's Fresnel texture at the bumped view vector, Bruneton §5.2's sky map at
// the reflected ray) at the vertex's mean slope s0 and their differences over h (h: the
// patterns' slope deviation), and the fragment stage only adds d(uv)/ds ds: two multiply-adds
// instead of two normalisations, a reflection and a stereographic division per pixel in
// mediump. The slowly varying factors of the Ross BRDF are per vertex too.
#include "common.glsl"
#ifndef CPU_VERTEX_TERMS
// vertex_terms and its uniforms
#include "vterms.glsl"
#endif

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
// as detile.c detile_taps_cell), weighted by Bruneton eq. 2: 0 for waves shorter than 2 cells,
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
#elif defined(CPU_VERTEX_TERMS)
// gles2-min, the driver refusing the vertex shaders below: the CPU displaced the vertex and
// evaluated every term of the vertex alone (src/geometry/vshade.h: vterms.glsl's functions, compared by
// test_vshade); this stage adds the run's constants.
attribute vec4 a_pos;       // displaced, camera-relative, m; w: lod_foot
attribute vec4 a_rest;      // rest position on the sea plane, camera-relative, m; the CPU
                            // patterns' resolved slope variance xy
attribute vec4 a_geo;       // the CPU patterns' foam memory mean, variance (Dupuy eq. 7-8); the
                            // sky LOD offset; the haze's green transmittance
attribute vec4 a_lin;       // the lookups at s0 and their derivatives in s (v_lin ...)
attribute vec4 a_lin_dx;
attribute vec4 a_lin_dy;
attribute vec4 a_sun;       // zeta_h - s0, the Ross factor, eq. 25's x weight
attribute vec4 a_fog;       // low quality: in-scattered light of the path to the camera;
                            // high: the haze's phase weights (vterms.glsl); w: the wave
                            // mask's amplitude (SWELL_MASK)
#else
// gles2-min: the CPU displaced the vertex (grid.c); the terms of the vertex alone are
// evaluated here.
attribute vec3 a_pos;       // displaced, camera-relative, m
attribute vec2 a_rest;      // rest position on the sea plane, camera-relative, m
attribute vec4 a_geo_slope; // CPU patterns: mean slope xy, resolved slope variance xy
attribute vec3 a_geo_k;     // CPU patterns: foam memory mean, variance (Dupuy eq. 7-8);
                            // the wave mask's amplitude (SWELL_MASK)
#endif
#ifdef SWELL_MASK
// The wave mask (render/mask.c, geometry/mask.h): the CPU scaled the vertex's displacement,
// its CPU patterns' slopes and variances by the amplitude a at its rest point; the variances
// added here (the patches' constants, the unresolved, low quality's fetched) take a^2, the
// whitecap coverage evaluated here a^mask_foam_v.
uniform float mask_foam_v;
#endif

uniform mat4 world_to_clip;             // camera-relative world -> clip
uniform vec2 pattern_uv_offset[4];      // per fragment-shader pattern slot
uniform float pattern_inv_size[4];      // 1 / L_i, 1/m
#ifndef QUALITY_HIGH
varying vec4 v_fog;         // in-scattered light, the sea's transmittance
#endif
varying vec4 v_lin;         // Fresnel-texture uv, sky-map uv at s0
varying vec4 v_lin_dx;      // their derivatives in s.x ...
varying vec4 v_lin_dy;      // ... and s.y
uniform vec4 const_slope;               // slots not fetched: -, -, slope variance xy (high
                                        // quality: the fetched slots' patch variances too)
uniform vec2 const_k;                   // ...their foam memory mean and variance (likewise)
uniform vec2 unresolved_var;            // slope variance below every table (Bruneton eq. 4)
#if FS_WHITECAPS == 0 || !defined(QUALITY_HIGH)
uniform float whitecap_epsilon_v;       // Dupuy eq. 3's threshold (ocean.frag's, own name: a
                                        // uniform in both stages needs one precision)
uniform vec2 foam_gain_v;               // eq. 6's gain by footprint over the run (ocean.frag
                                        // foam_gain's, own name likewise)
#endif
varying vec4 v_sun;         // zeta_h - s0, ln of the Ross factor, eq. 25's x weight (low: ln
                            // of the Ross factor over 2 pi sigma_x sigma_y, eq. 26's exponent)
#ifdef QUALITY_HIGH
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
    vec4 lin, lin_dx, lin_dy, sun;
    vec3 pos, geo, fog;     // geo: lod_foot, the sky LOD offset, the haze's green T
    vec2 rest, svar, k_geo; // svar, k_geo: the CPU patterns' slope variance and foam moments
#ifdef VTF_PATTERNS
    rest = grid_rest(a_grid);
    // footprint: the larger side of the cell towards the next column and row (grid.c)
    vec2 ex = abs(grid_rest(a_grid + vec2(grid_step.x, 0.0)) - rest);
    vec2 ey = abs(grid_rest(a_grid + vec2(0.0, grid_step.y)) - rest);
    float foot = max(max(ex.x, ex.y), max(ey.x, ey.y));
    vec3 disp = displacement(disp_a0, disp_b0, 0, rest, foot);
#if VTF_PATTERNS > 1
    disp += displacement(disp_a1, disp_b1, 1, rest, foot);
#endif
#if VTF_PATTERNS > 2
    disp += displacement(disp_a2, disp_b2, 2, rest, foot);
#endif
#if VTF_PATTERNS > 3
    disp += displacement(disp_a3, disp_b3, 3, rest, foot);
#endif
    // the sphere's drop R - sqrt(R^2 - r^2), in its exact-near-the-camera form (grid.c)
    float r2 = dot(rest, rest);
    pos = vec3(rest + disp.xy,
               disp.z - grid_frame.z - r2 / (EARTH_R + sqrt(max(EARTH_R2 - r2, 0.0))));
    svar = vec2(0.0);       // no CPU patterns on these tiers
    k_geo = vec2(0.0);
    vertex_terms(pos, rest, vec2(0.0), svar, lin, lin_dx, lin_dy, sun, geo, fog);
#elif defined(CPU_VERTEX_TERMS)
    pos = a_pos.xyz;
    rest = a_rest.xy;
    svar = a_rest.zw;
    k_geo = a_geo.xy;
    lin = a_lin;
    lin_dx = a_lin_dx;
    lin_dy = a_lin_dy;
    sun = a_sun;
    geo = vec3(a_pos.w, a_geo.zw);
    fog = a_fog.xyz;
#else
    pos = a_pos;
    rest = a_rest;
    svar = a_geo_slope.zw;
    k_geo = a_geo_k.xy;
    vertex_terms(pos, rest, a_geo_slope.xy, svar, lin, lin_dx, lin_dy, sun, geo, fog);
#endif
    v_lin = lin;
    v_lin_dx = lin_dx;
    v_lin_dy = lin_dy;
#if defined(SWELL_MASK) && defined(CPU_VERTEX_TERMS)
    float amp2 = a_fog.w * a_fog.w;
#elif defined(SWELL_MASK) && !defined(VTF_PATTERNS)
    float amp2 = a_geo_k.z * a_geo_k.z;
#else
    float amp2 = 1.0;       // (choose_vtf: no mask with vertex texture fetch)
#endif
    vec2 var_base = svar + amp2 * (const_slope.zw + unresolved_var);
    vec2 k_base = k_geo + const_k.xy;
    // The sun's factor goes to the pixel as its logarithm, added to the Gaussian's exponent
    // there (ocean.frag): at grazing views the Ross factor alone reaches 1e5-1e10 (cos_v and
    // hn at their floors, 1 / hn^4), past mediump's 65504, and the pixel's 0 x inf drew the
    // horizon rows white (calm, sun 4 degrees up, gles2-min low) where its Gaussian is 0.
    float ln_sun = log(max(sun.z, 1e-30));
#ifdef QUALITY_HIGH
    v_sun = vec4(sun.xy, ln_sun, sun.w);
    v_base = vec4(var_base, k_base);
#if FS_WHITECAPS == 0
    // No whitecap table fetched in this run: Dupuy eq. 6's coverage depends on the vertex's
    // moments alone, so it is evaluated here and v_base.z carries it (exact where no pattern
    // is resolved per vertex, as the moments are then the same at every vertex).
    v_base.zw = vec2(whitecap_cover_gain(whitecap_epsilon_v, k_base.x, k_base.y,
                                         foam_gain_v.x * geo.x + foam_gain_v.y), 0.0);
#ifdef SWELL_MASK
    v_base.z *= exp2(mask_foam_v * 0.5 * log2(max(amp2, 1e-8)));
#endif
#endif
    // the haze's Mie and Rayleigh weights, its green transmittance, the footprint (the sky
    // map's eq. 27 offset geo.y is derived per pixel from v_lin.zw, ocean.frag)
    v_extra = vec4(fog.y, fog.x, geo.z, geo.x);
#else
    // Low quality: the pixel's slope variance per vertex (fetched_var), so the vertex carries
    // the Gaussian's inverse variances and normalisation with the Ross factor (ocean.frag)
    // and eq. 26's terms of sigma (common.glsl fresnel_eff_terms).
    vec2 var = max(var_base + amp2 * fetched_var(geo.x), vec2(1e-4));
    float sig_v = sqrt(mix(var.y, var.x, sun.w));
    v_sun = vec4(sun.xy, ln_sun - 0.5 * log(var.x * var.y), fresnel_eff_e(sig_v));
    v_base = vec4(0.5 / var, fresnel_eff_k(sig_v), geo.x);
    // and no whitecap table: eq. 6's coverage from the vertex's moments, as high quality's
    // runs without whitecap fetches take it, mixed in with the haze: the pixel's radiance is
    // its clear sea times v_fog.a plus v_fog.rgb.
    // (times the gain that brings its mean to the bake's W at this footprint, ocean.frag)
    float cover = whitecap_cover_gain(whitecap_epsilon_v, k_base.x, k_base.y,
                                      foam_gain_v.x * geo.x + foam_gain_v.y);
#ifdef SWELL_MASK
    cover *= exp2(mask_foam_v * 0.5 * log2(max(amp2, 1e-8)));
#endif
    v_fog = vec4(fog + foam_radiance * (cover * geo.z), (1.0 - cover) * geo.z);
#endif
#define SLOT_UV(i) (pattern_uv_offset[i] + rest * pattern_inv_size[i])
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
    gl_Position = world_to_clip * vec4(pos, 1.0);
}
