// ocean.frag - sea shading (Bruneton 2010 §4-5, Hu 2006 §5, Dupuy 2012 eq. 6-8).
// validate: FS_PATTERNS=0 FS_WHITECAPS=0 | FS_PATTERNS=1 FS_WHITECAPS=1 | FS_PATTERNS=2 FS_WHITECAPS=2 | FS_PATTERNS=3 FS_WHITECAPS=2 | FS_PATTERNS=4 FS_WHITECAPS=2 | FS_PATTERNS=4 FS_WHITECAPS=4 | FS_PATTERNS=3 FS_WHITECAPS=0 | FS_PATTERNS=2 FS_WHITECAPS=1 | FS_PATTERNS=4 FS_WHITECAPS=1 | FS_PATTERNS=4 FS_WHITECAPS=0 |
// validate: FS_PATTERNS=4 FS_WHITECAPS=2 SWELL_RUN_LOD | FS_PATTERNS=1 FS_WHITECAPS=0 SWELL_RUN_LOD | FS_PATTERNS=4 FS_WHITECAPS=2 SWELL_NO_DETILE | FS_PATTERNS=3 FS_WHITECAPS=0 SWELL_NO_DETILE | FS_PATTERNS=4 FS_WHITECAPS=2 SWELL_LINEAR_OUT |
// validate: FS_PATTERNS=3 FS_WHITECAPS=2 SWELL_REFLECT REFL_RIP_M=4 | FS_PATTERNS=3 FS_WHITECAPS=0 SWELL_REFLECT REFL_RIP_M=4 | FS_PATTERNS=3 FS_WHITECAPS=2 SWELL_REFLECT REFL_RIP_M=4 SWELL_LINEAR_OUT |
// validate: FS_PATTERNS=2 FS_WHITECAPS=2 SWELL_WAKE | FS_PATTERNS=2 FS_WHITECAPS=0 SWELL_WAKE SWELL_REFLECT REFL_RIP_M=4 | FS_PATTERNS=0 FS_WHITECAPS=0 SWELL_WAKE SWELL_RUN_LOD |
// validate: FS_PATTERNS=2 FS_WHITECAPS=2 SWELL_SHADOW | FS_PATTERNS=1 FS_WHITECAPS=1 SWELL_SHADOW SWELL_WAKE SWELL_REFLECT REFL_RIP_M=4 |
// validate: FS_PATTERNS=2 FS_WHITECAPS=2 SWELL_REFRACT | FS_PATTERNS=1 FS_WHITECAPS=0 SWELL_REFRACT SWELL_SHADOW SWELL_WAKE SWELL_REFLECT REFL_RIP_M=4 SWELL_LINEAR_OUT |
// validate: FS_PATTERNS=2 FS_WHITECAPS=2 SWELL_MASK | FS_PATTERNS=1 FS_WHITECAPS=0 SWELL_MASK | FS_PATTERNS=3 FS_WHITECAPS=1 SWELL_MASK SWELL_WAKE
// FS_PATTERNS: pattern slots fetched here (largest first); the renderer draws each run of grid
// rows with the variant whose smaller patterns are not yet fully filtered there, and passes the
// rest as constants (their top mip level: mean and variance over the whole patch, Bruneton §4.1).
// FS_WHITECAPS <= FS_PATTERNS: leading slots whose patterns carry whitecaps (bake.c).
// SWELL_RUN_LOD (software rasterisers, gpu.c): the pattern tables are fetched at one whole mip
// level per draw, the one nearest the LOD the hardware would pick at the run's rows
// (renderer.c draw_runs), by texture2D of that level's own texture, which has no mips
// (renderer.c chain_tex); the Fresnel texture, a smooth function of the bumped view, at level
// 0 likewise, and the sky map at two neighbouring levels of an atlas blended by the pixel's
// footprint (sky_run). Elsewhere the per-pixel implicit LOD (the sky: sky_eq27).
//
// Per pixel only what depends on the pixel's own slope moments is evaluated: ocean.vert
// linearises the rest about the vertex's mean slope s0 (see there), so the pixel adds the
// fetched deviation ds to two lookup coordinates and evaluates the Gaussians of its variance.
// QUALITY_HIGH: Ross BRDF sun (eq. 15), filtered sky (eq. 27 by LOD bias), effective Fresnel
// (eq. 26) on Hu's Fresnel texture, refracted light (eq. 28), whitecaps (Dupuy eq. 6).
// Otherwise (low quality, Hu's single pass made the same sea, cheaper): the same slope
// moments, Ross sun, effective Fresnel and refracted light, the sky filtered (eq. 27) at the
// vertex's variance, the whitecap coverage and the haze per vertex (no whitecap table).
#include "common.glsl"

uniform sampler2D fresnel_tex;      // Hu §5.1: A = Fresnel at the bumped view vector; an
                                    // atlas that also holds the lattice hash (renderer.c)
uniform vec2 fresnel_uv_max;        // the Fresnel texels' far corner in the atlas (the guard
                                    // row and column included; textures.c)
uniform sampler2D sky_tex;           // with SWELL_RUN_LOD an atlas of its levels (sky_run)
#ifdef SWELL_RUN_LOD
uniform vec4 sky_run_lod;           // the run's blend of two sky levels: w = x V_FOOT + y; the
                                    // half texel of each level in its uv (renderer.c set_run_lods)
uniform vec4 sky_run_blk[2];        // the two levels' blocks in the atlas: scale xy, offset zw
#endif
uniform vec4 slope_scale[4];        // RGBA8 dequantisation per fragment pattern slot
uniform vec4 slope_bias[4];
uniform vec3 detile_shift[4];       // per slot: the camera's lattice cell modulo DETILE_N plus
                                    // the pattern's shift (detile.h), the cell's colour shift
uniform vec4 detile_atlas;          // 1 / the atlas size, the hash rows' origin (v)
uniform vec4 slope_mean[4];         // per slot: the mean slope over its patch (its top level);
                                    // the mean within-texel variance at the level fetched, xy
                                    // (low quality: the dequantisation's bias less that mean)
uniform vec4 slot_lod[4];           // per slot: its weight's terms (slot_weight)
uniform vec2 lod_cmax[4];           // per slot: the largest contrast factor, slopes, whitecaps
uniform vec3 sky_map_scale;         // per channel (sky_decode)
uniform float sky_map_inv_size;     // 1 / texels
uniform float sky_level_scale;      // sky map A (0..1) -> its level index (sky.h)
uniform float sky_top_level;        // the sky map's last mip level
uniform float sky_bias_max;         // the device's largest LOD bias (gpu.c)
uniform vec3 sun_irr;               // sun irradiance at the sea, relative to E0 (x exposure)
uniform vec3 sea_radiance;          // eq. 28's L_sea: water body lit by sun and sky (x exposure)
#ifdef SWELL_REFLECT
uniform sampler2D refl_tex;         // the application's objects mirrored in the sea plane, their
                                    // colour premultiplied by coverage: an atlas of the map's
                                    // levels (reflect.c)
uniform mat3 refl_mat;              // a reflected ray (any length) -> the map's uv times w
uniform vec4 refl_screen;           // gl_FragCoord -> the flat sea's map uv: scale xy, offset zw
uniform vec4 refl_ray;              // gl_FragCoord -> the view ray in the eye frame, (x, y, -1)
uniform vec4 refl_down;             // the eye frame's components of world -z; c / D_o
uniform vec2 refl_blur;             // twice the map's level-0 texels per 2 rad, across (x) and
                                    // along (y) (reflect.c)
uniform vec4 refl_levels;           // the map's last level across; 1 / its width, height;
                                    // log2 of its height (the atlas's last version)
uniform vec2 refl_axes;             // squares of the world vertical's direction on the map
#endif
#ifdef SWELL_WAKE
uniform sampler2D wake_tex;         // the hull's Kelvin wake (geometry/kelvin.h): mean slope,
                                    // mean square slope, foam; mipmapped, clamped (wake.c)
uniform mat3 wake_mat;              // gl_FragCoord -> the flat sea's point in the hull's frame,
                                    // (P, Q / spread) times w (wake.c)
uniform vec4 wake_warp;             // (P, Q) -> the map's (u, v) (geometry/kelvin.h)
uniform vec4 wake_rot;              // the map's R, G -> world slope: xy per R, zw per G...
uniform vec3 wake_k;                // ...plus xy; z: B -> the mean square slope
uniform vec3 wake_foam;             // low quality: the foam's radiance (x exposure)
#endif
#ifdef SWELL_REFRACT
uniform sampler2D refr_tex;         // the application's objects under the water, the scene
                                    // scaled by 1/n in z: display colour times alpha, alpha the
                                    // green transmittance down to them (refract.c)
uniform vec4 refr_screen;           // gl_FragCoord -> the map's uv: scale xy, offset zw
uniform mat2 refr_shift;            // the slope deviation -> the map's uv shift
uniform vec3 refr_tau;              // each channel's beam attenuation over green's
#endif
#ifdef SWELL_MASK
uniform vec4 mask_box;              // the wave mask's block in the Fresnel atlas (a border of
                                    // 1 around it, mask.c): its border texels' centres
uniform mat3 mask_mat;              // gl_FragCoord -> the flat sea's point's atlas uv times w
uniform float mask_foam;            // the whitecap coverage's exponent of a (geometry/mask.h)
#endif
#ifdef SWELL_SHADOW
uniform sampler2D shadow_tex;       // the application's shadow casters seen from the sun: their
                                    // coverage in alpha, mipmapped, clamped (shadow.c)
uniform mat3 shadow_mat;            // gl_FragCoord -> the flat sea's point in the map, uv times w
uniform vec3 shadow_sea;            // the sun's share of sea_radiance (x exposure)...
uniform vec3 shadow_foam;           // ...and of the foam's radiance
#endif
#ifdef QUALITY_HIGH
varying vec4 v_sun;                 // zeta_h - s0, ln(Ross factor / (2 pi)), x weight of var_v
uniform vec2 slope_var[4];          // per slot: the slope variance over its patch less the
                                    // level's mean within-texel variance, T - W, xy
uniform vec3 foam_radiance;         // Lambertian 0.4 foam lit by sun and sky (x exposure)
uniform vec4 wc_mean[4];            // per slot: the foam memory's mean over its patch; of its
                                    // variance: c0, -W, T - W (add_whitecap)
uniform vec2 foam_detail;           // 1 / the detail's slope variance x + y (main); the least
                                    // share of c0 kept as eq. 6's blur (add_whitecap)
uniform vec4 wc_trust[4];           // per slot: B and s at V_FOOT = 0, and their slopes per
                                    // unit of it (add_whitecap)
uniform vec4 wc_lod[4];             // per slot: its whitecaps' weight's terms
uniform float whitecap_epsilon;     // Dupuy eq. 3 threshold on j
uniform vec2 foam_gain;             // eq. 6's gain by footprint: x V_FOOT + y (lod.c
                                    // foam_gain_line)
uniform vec4 wc_scale[4];
uniform vec4 wc_bias[4];
uniform vec3 haze_ray;              // sky.h sky_haze's horizon terms (x exposure); low quality
uniform vec3 haze_mie;              // takes them in ocean.vert instead
uniform vec3 haze_tau_ratio;        // each channel's optical depth over green's
varying vec4 v_base;                // slope variance xy and k mean, k variance not fetched here;
                                    // with no whitecap fetched, z: the coverage (ocean.vert)
varying vec4 v_extra;               // the haze's Mie and Rayleigh phase weights (vterms.glsl),
                                    // its green transmittance; the footprint (lod_foot)
#define V_FOOT v_extra.w
#else
varying vec4 v_sun;                 // zeta_h - s0, ln of the Ross factor over 2 pi sigma_x sigma_y,
                                    // eq. 26's exponent (ocean.vert: the variance per vertex)
varying vec4 v_fog;                 // the haze's in-scattered light and foam, the clear sea's
                                    // factor (ocean.vert)
varying vec4 v_base;                // 0.5 / the slope variance xy, eq. 26's k, the footprint
                                    // (ocean.vert lod_foot)
#define V_FOOT v_base.w
#endif
varying vec4 v_lin;                 // ocean.vert: Fresnel-texture uv, sky-map uv at s0...
varying vec4 v_lin_dx;              // ...and their derivatives in s.x
varying vec4 v_lin_dy;              // ...and in s.y
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
#if FS_PATTERNS > 0
uniform sampler2D slope_tex0;
#endif
#if FS_PATTERNS > 1
uniform sampler2D slope_tex1;
#endif
#if FS_PATTERNS > 2
uniform sampler2D slope_tex2;
#endif
#if FS_PATTERNS > 3
uniform sampler2D slope_tex3;
#endif
#ifdef QUALITY_HIGH
#if FS_WHITECAPS > 0
uniform sampler2D wc_tex0;
#endif
#if FS_WHITECAPS > 1
uniform sampler2D wc_tex1;
#endif
#if FS_WHITECAPS > 2
uniform sampler2D wc_tex2;
#endif
#if FS_WHITECAPS > 3
uniform sampler2D wc_tex3;
#endif
#endif

// Running sums over the fetched patterns: slope deviation, resolved slope variance
// <s^2> - <s>^2 (Bruneton §4.1, mip-filtered moments), the mean and variance of the foam
// memory of Dupuy's k (eq. 7-8 on m_i; bake.c).
vec2 g_ds;
vec2 g_var;
float g_mu;
float g_kvar;
float g_dvar;                       // the foam memory's variance drawn as detail (add_whitecap)
vec2 g_dsw;                         // g_ds of the slots up to the last with whitecaps
#if defined(QUALITY_HIGH) && defined(SWELL_ORDER_FETCHES)
// The fetches in order (issue 15; on which GPU and why: gpu.c gpu_orders_fetches): SERIAL(uv)
// is uv plus the sums so far times a uniform never set, so 0 (GLES: a program's uniforms start
// at 0), which no compiler can fold; each slot's taps then wait for the slot before.
uniform float serial_zero;
#define SERIAL(uv) (uv + vec2((g_var.x + g_kvar) * serial_zero))
#else
#define SERIAL(uv) (uv)
#endif

// No pattern repeats on its tile (detile.h): a slot's tables are read at the three random
// offsets of its lattice triangle, with weights g_tw (normalised: sum g_tw^2 = 1) and uv
// offsets (g_ox, g_oy) (detile_offsets). The taps are ordered by their vertex's colour (x + y) mod 3, so a
// tap's offset changes only where its weight is 0 and the implicit LOD of its fetch (no
// gradients on gles2-min) stays its neighbours'.
vec3 g_tw;
vec3 g_ox;
vec3 g_oy;

void detile(vec2 uv, vec3 sh)
{
    vec2 c, f;
    vec4 h = texture2D(fresnel_tex, detile_cell(uv, sh.xy, detile_atlas, c, f));
    vec3 t = detile_bytes(h, f);
    vec3 w = detile_weights(f);
    // corner (0, 0) has colour s, the middle vertex s + 1, corner (1, 1) s + 2
    float s = c.x + c.y + sh.z;
    s -= 3.0 * floor((s + 0.5) * (1.0 / 3.0));
    // rotated by s without a branch (an if/else here made gles2-min low 4x slower on
    // llvmpipe, 355 -> 1300 M instructions a frame): s = 1 takes .zxy, s = 2 .yzx
    float a = step(0.5, s), b = step(1.5, s);
    t = mix(mix(t, t.zxy, a), t.yzx, b);
    w = mix(mix(w, w.zxy, a), w.yzx, b);
    g_tw = w;
    detile_offsets(t, g_ox, g_oy);
}

#ifdef SWELL_NO_DETILE
// renderer_desc no_detile: one tap at no offset, full weight; the tile repeats.
#define DETILE(uv, sh) g_tw = vec3(1.0, 0.0, 0.0)
#define TAP(tex, uv, j) texture2D(tex, uv)
#define TAPS(tex, uv) TAP(tex, uv, x), vec4(0.0), vec4(0.0)
#else
#define DETILE(uv, sh) detile(uv, sh)
#define TAP(tex, uv, j) texture2D(tex, uv + vec2(g_ox.j, g_oy.j))
#define TAPS(tex, uv) TAP(tex, uv, x), TAP(tex, uv, y), TAP(tex, uv, z)
#endif

// No seam where the renderer changes how it reads a pattern (renderer.c set_slot_lods): a
// slot's fetched deviation from its patch's mean enters with the weight g of its terms l,
// clamp(l.x f + l.y, 0, 1) clamp(l.w + l.z f, 0, cmax) at the pixel's footprint f (log2 m): the first factor
// fades it out over the rows before those that stop fetching it, the second, in a run fetching
// one whole mip level (SWELL_RUN_LOD), scales it to the contrast of the level the footprint
// asks for (1 elsewhere). The within-texel variance v fetched fades likewise towards its mean
// W over the level's texels, and the variance the means lose moves to within the pixel: with
// T the patch's variance (the top level's, = W + the means' variance), the pixel's is
// g v + (1 - g) W + (1 - g^2) (T - W), whose mean over the patch is T at every g. So the mean
// radiance stays and at g = 0 the slot is its patch's constants, as where it is not fetched.
// (The patches' means and variances T of the slots fetched are summed into the vertex's
// constants, v_base, by the renderer, set_ocean_uniforms: a slot adds only what depends on
// its taps, T + h (v - W - h (T - W)) written as its last part, with h = min(g, 1) below.)
// Where the contrast factor takes g above 1 the variance takes min(g, 1): the fetched v as it
// is, never less (the bookkeeping's (1 - g^2) would take the patch's variance back, to below
// zero on tables of a few waves, where the level contrasts are extreme).
float slot_weight(vec4 l, float cmax)
{
    return clamp(l.x * V_FOOT + l.y, 0.0, 1.0) * clamp(l.w + l.z * V_FOOT, 0.0, cmax);
}

#ifdef QUALITY_HIGH
// The blend of three taps of a moment table (detile.h): means by w_j about the patch's mean m
// (m + sum_j w_j (s_j - m); m itself is in the vertex's constants, so ds gets the rest),
// variances by w_j^2; both weighted by g (slot_weight) about the level's mean within-texel
// variance W = m.zw, d = T - W.
void add_slope(vec4 b, vec4 sc, vec4 m, vec2 d, float g, vec4 a0, vec4 a1, vec4 a2)
{
    vec4 s0 = b + sc * a0, s1 = b + sc * a1, s2 = b + sc * a2;
    g_ds += g * (g_tw.x * s0.xy + g_tw.y * s1.xy + g_tw.z * s2.xy -
                 dot(g_tw, vec3(1.0)) * m.xy);
    vec3 w2 = g_tw * g_tw;
    vec2 v = w2.x * max(s0.zw - s0.xy * s0.xy, vec2(0.0)) +
             w2.y * max(s1.zw - s1.xy * s1.xy, vec2(0.0)) +
             w2.z * max(s2.zw - s2.xy * s2.xy, vec2(0.0));
    float h = min(g, 1.0);
    g_var += h * (v - m.zw - h * d);
}
#define SLOPE(i, tex, uv) DETILE(uv, detile_shift[i]); add_slope(slope_bias[i], slope_scale[i], slope_mean[i], slope_var[i], slot_weight(slot_lod[i], lod_cmax[i].x), TAPS(tex, uv))


void add_whitecap(vec4 b, vec4 sc, vec4 mu, vec4 tr, float g, vec4 a0, vec4 a1, vec4 a2)
{
    // Dupuy eq. 7-8 per pattern, on the foam memory m_i of k_i; the variance is summed per
    // pattern (sum <m_i^2> - <m_i>^2), the same uncorrelated-pattern assumption as eq. 8
    // without its cross terms of the means. The taps blend m's deviation from its mean mu.x;
    // weighted by g as the slopes are (mu.z, mu.w: -W the level's mean within-texel variance,
    // T - W, T the patch's). The fetched within-texel variance v = <m^2> - <m>^2 of two 8-bit
    // channels is not all signal: on fine levels it is their rounding (and llvmpipe's 8-bit
    // filtering), and where level 0 is magnified it is the variance of the bilinear mix of
    // neighbouring texels, largest between texel centres. Through eq. 6's erf the first drew
    // a mesh of dots in the foam up close, the second the texel grid (blocks). So the pixel
    // takes B v + (1 - B) c0: B = S^2 / (S^2 + N^2) the share of v to trust at the level it
    // reads (renderer.c wc_trust_terms: S that level's mean, N the rounding's deviation; 0
    // where level 0 is magnified), c0 level 0's mean in the rest's place. B and s, the share
    // of c0 left to eq. 6's blur, are lines in the pixel's footprint V_FOOT, clamped (tr;
    // c0 = mu.y), so they follow the pixel on either LOD path: s is 1 down to level 0 and
    // falls to foam_detail.y where a texel spans two pixels; the rest of c0 is drawn as
    // detail (g_dvar, main), or with no detail to draw (foam_detail.y = 1) stays blur.
    // (mu.x and T are in the vertex's constants, as the slopes' are: the slot adds
    // h (B v + (1 - B) s c0 - W - h (T - W)), the first two at h = 1)
    // c0 arrives per texel in z with the loop blend's own variance added (stream.h
    // stream_blend_whitecap: (1 - w) w (m1 - m0)^2 over bias c0; the same uniform mu.y without
    // the blend's): where the fetched variance is set aside, without it the blend averaged the
    // memory's rare deep minima away between frames (test_render test_foam_amount: from 20 m
    // at 8 m/s 0.54 W drawn, now 0.61 W; 0.82-0.86 W on a frame).
    vec4 k0 = b + sc * a0, k1 = b + sc * a1, k2 = b + sc * a2;
    g_mu += g * dot(g_tw, vec3(k0.x, k1.x, k2.x) - vec3(mu.x));
    vec3 w2 = g_tw * g_tw;
    float v = dot(w2, max(vec3(k0.y - k0.x * k0.x, k1.y - k1.x * k1.x,
                               k2.y - k2.x * k2.x), vec3(0.0)));
#ifdef SWELL_NO_DETILE
    float c0 = k0.z;    // (one tap: what the dot below is, which compilers did not fold)
#else
    float c0 = dot(w2, vec3(k0.z, k1.z, k2.z));
#endif
    vec2 bc = clamp(tr.xy + V_FOOT * tr.zw, vec2(0.0, foam_detail.y), vec2(1.0));
    float h = min(g, 1.0);
    g_kvar += h * (mix(bc.y * c0, v, bc.x) + mu.z - h * mu.w);
    // (the detail's share without h and 1 - B: s < 1 only where a texel spans pixels, where B
    // is 0 and no fade runs)
    g_dvar += (1.0 - bc.y) * c0;
    g_dsw = g_ds;
}
// (one line each: GLSL ES 1.00 has no line continuation)
#define WHITECAP(i, tex, uv) add_whitecap(wc_bias[i], wc_scale[i], wc_mean[i], wc_trust[i], slot_weight(wc_lod[i], lod_cmax[i].y), TAPS(tex, uv))
#else
// Low quality takes the variance per vertex (ocean.vert fetched_var): the mean slope only,
// g (sum_j w_j s_j - (sum_j w_j) m) (m is in s0, ocean.vert), the bias less m in
// slope_mean.zw.
#ifdef SWELL_NO_DETILE
#define SLOPE(i, tex, uv) g_ds += slot_weight(slot_lod[i], lod_cmax[i].x) * (slope_mean[i].zw + slope_scale[i].xy * TAP(tex, uv, x).xy)
#else
#define SLOPE(i, tex, uv) detile(uv, detile_shift[i]); g_ds += slot_weight(slot_lod[i], lod_cmax[i].x) * (dot(g_tw, vec3(1.0)) * slope_mean[i].zw + slope_scale[i].xy * (g_tw.x * TAP(tex, uv, x).xy + g_tw.y * TAP(tex, uv, y).xy + g_tw.z * TAP(tex, uv, z).xy))
#endif
#endif

#ifdef SWELL_RUN_LOD
// The sky map at the run's footprint: two neighbouring levels of the atlas blended by the
// pixel's footprint, so the level changes continuously from run to run (no brightness steps).
vec3 sky_run(vec2 uv)
{
    float w = clamp(sky_run_lod.x * V_FOOT + sky_run_lod.y, 0.0, 1.0);
    vec2 u0 = clamp(uv, vec2(sky_run_lod.z), vec2(1.0 - sky_run_lod.z));
    vec2 u1 = clamp(uv, vec2(sky_run_lod.w), vec2(1.0 - sky_run_lod.w));
    vec3 c0 = texture2D(sky_tex, u0 * sky_run_blk[0].xy + sky_run_blk[0].zw).rgb;
    vec3 c1 = texture2D(sky_tex, u1 * sky_run_blk[1].xy + sky_run_blk[1].zw).rgb;
    return mix(c0, c1, w);
}

#endif

// The sky map filtered per eq. 27 for slope deviation sigma (the larger axis's): its footprint
// is 2 sigma du/dzeta in texels, log2 of it log2(sigma) + log2(2 size du/dzeta).
vec3 sky_eq27(vec2 uv, float sigma)
{
#ifndef SWELL_RUN_LOD
    // log2(2 sigma size du/dzeta) with du/dzeta = h / (1 + r_z) of the reflected ray r at the
    // vertex's mean slope, read off its stereographic uv (common.glsl sky_map_uv, h its
    // SKY_HORIZON): with d = uv - 1/2, 4 |d|^2 / h^2 = (1 - r_z) / (1 + r_z), so 2 h / (1 + r_z)
    // = h + 4 |d|^2 / h
    vec2 dq = v_lin.zw - vec2(0.5);
    float foot = log2(sigma * (SKY_HORIZON + (4.0 / SKY_HORIZON) * dot(dq, dq)) /
                      sky_map_inv_size);
#endif
#if defined(SWELL_RUN_LOD)
    // Software rasterisers (gpu.c prefer_run_lod): eq. 27's footprint as the renderer takes
    // it for the run's rows (renderer.c set_run_lods), read from an atlas without mips, two
    // levels blended (sky_run): a per-pixel LOD is llvmpipe's slow path (A/B, rough 1 km:
    // 6.6-6.9x -> 6.0x the quad).
    vec3 sky = sky_run(uv);
#elif defined(SWELL_HAS_TEXTURE_LOD) && defined(SWELL_HAS_DERIVATIVES)
    // With explicit gradients (gles2-ext, gles3): the pixel's own footprint on the map,
    // widened in each direction to at least the filter's (a max, where a bias multiplies).
    vec2 gx = dFdx(uv), gy = dFdy(uv);
    float f = exp2(foot) * sky_map_inv_size;
    gx *= max(1.0, f * inversesqrt(max(dot(gx, gx), 1e-8)));
    gy *= max(1.0, f * inversesqrt(max(dot(gy, gy), 1e-8)));
    vec3 sky = texture2DGradEXT(sky_tex, uv, gx, gy).rgb;
#else
    // gles2-min: no gradients, no explicit LOD, only a bias on the pixel's own LOD lambda.
    // Eq. 27 wants the larger of lambda and the filter's footprint (as the gradient path
    // takes); a bias of the whole footprint gave their sum, which blurred the sky to grey where
    // lambda was high and left pixels of small variance sharp and bright (sparkles). So the
    // bias is what the footprint asks beyond lambda, foot - lambda where positive, with lambda
    // read from the map's A (each level's index, sky.h) by fetches at known biases b: a fetch
    // sees lambda + b clamped to the map's levels [0, top], so it gives lambda = a - b where
    // 0 < a < top (a = top: lambda >= top - b). A read at b = 0 lost every magnified pixel
    // (lambda < 0), and the horizon's grid row, where lambda jumps per triangle down to -5,
    // drew a sawtooth. So b1 = top - foot reads lambda in [foot - top, foot] (a1 = top above
    // it: no bias), and where a1 = 0, b2 = 2 top - foot reads it in [foot - 2 top, foot - top].
    // a1 > 0.02: above level 0 by at least one step of the 8-bit A (1/28 level). Biases stay
    // within the device's limit. Below the window, as where a quad's mediump uv are equal
    // (lambda = -inf), the sky stays too sharp.
    float b1 = min(sky_top_level - foot, sky_bias_max);
    float b2 = min(2.0 * sky_top_level - foot, sky_bias_max);
    float a1 = texture2D(sky_tex, uv, b1).a * sky_level_scale;
    float a2 = texture2D(sky_tex, uv, b2).a * sky_level_scale;
    float lambda = a1 > 0.02 ? a1 - b1 : a2 - b2;
    float bias = clamp(foot - lambda, 0.0, sky_bias_max);
    vec3 sky = texture2D(sky_tex, uv, bias).rgb;
#endif

    return sky;
}

#ifndef SWELL_LINEAR_OUT
// A display colour back to radiance: tone_map (common.glsl) inverted, so a mirror (F = 1) or a
// clear window onto an object shows it as the application drew it.
vec3 display_to_radiance(vec3 c)
{
    vec3 y = c * c;
    float m = min(max(max(y.r, y.g), y.b), 0.96);
    return y / (1.0 - m);
}
#endif

#ifdef SWELL_REFLECT
// Local reflections (Bruneton 2010 §6, Hu 2006 §5.2): the objects' reflection map read along
// the pixel's reflected ray, filtered as eq. 27 filters the sky (reflect.c). The ray comes back
// from its stereographic sky-map uv (common.glsl sky_map_uv inverted up to its length: with
// d = (2 uv - 1) / h, h its SKY_HORIZON, r ~ (2 d, 1 - d.d)), which already carries the pixel's
// slope. The map holds display colours (the application's), premultiplied: they are taken back
// to radiance by inverting tone_map, so a mirror (F = 1) would show an object as the
// application drew it.
// Version (l, m) of the reflection map: level l halved m more times along the map's vertical,
// in the atlas (reflect.c's layout: level l's column at x 0 or 1 - 2^(1 - l), y 0 or 2/3,
// version m 2/3 (2^-l - 2^-(l+m)) above it; the atlas is three heights tall). For s = 2^-l,
// st = 2^-(l + m), up = 1 for l > 0, uv maps to x = s u + up (1 - 2 s), the same for all of a
// level's versions (refl_x), and y = st (v - 2) / 3 + 2 (up + s) / 3 (refl_y's yv = (v - 2) / 3).
float refl_x(float u, float s, float up)
{
    return s * u + up * (1.0 - 2.0 * s);
}

vec4 refl_level(float x, float yv, float s, float st, float up)
{
    return texture2D(refl_tex, vec2(x, st * yv + (2.0 / 3.0) * (up + s)));
}

vec4 reflect_local(vec2 sky_uv, vec2 sig)
{
    vec2 d = (2.0 / SKY_HORIZON) * sky_uv - vec2(1.0 / SKY_HORIZON);
    vec3 q = refl_mat * vec3(2.0 * d, 1.0 - dot(d, d));
    // Parallax (reflect.c): the objects stand D_o away; the flat sea here is D = c /
    // sin(depression) away (the fragment's view ray). A ray the waves tilt by an angle meets
    // them (D_o - D) further on, which the camera sees as that angle times k = 1 - D / D_o:
    // the map position moves from the flat sea's (the pixel's own) by k of the whole, and the
    // footprint shrinks by k. Beyond the objects, k = 0: the flat mirror, where no object is.
    vec3 e = vec3(gl_FragCoord.xy * refl_ray.xy + refl_ray.zw, -1.0);
    float sin_dep = dot(refl_down.xyz, e) * inversesqrt(dot(e, e));
    float k = clamp(1.0 - refl_down.w / max(sin_dep, 1e-4), 0.0, 1.0);
    vec2 flat_uv = gl_FragCoord.xy * refl_screen.xy + refl_screen.zw;
    vec2 uv = flat_uv + k * (q.xy / max(q.z, 1e-3) - flat_uv);
    // Eq. 27's ellipse, k times: a slope deviation along the view (sig.x) turns the reflected
    // ray in the plane of incidence by twice its angle, one across it (sig.y) turns it across
    // by 2 sin(depression) times it. Their standard deviations on the map in level-0 texels,
    // t = sigma k refl_blur / 2 per axis, with the world vertical's direction c on the map
    // (rolled views: the ellipse's extent along the map's axes). A version of the atlas
    // (reflect.c) is a box of 2^l texels across and 2^(l + m) along, read bilinearly: a kernel
    // of standard deviation 2^l / 2 (box and tent) - so the level across is log2(2 t.x) and
    // along log2(2 t.y), each between whole versions (four fetches). Until this build two taps
    // of one isotropic level kept at most 2:1 of the ellipse: an object's reflection was 5-6x
    // too wide across the view (test_reflect test_blur_width).
    vec2 s2 = sig * sig * vec2(1.0, sin_dep * sin_dep);
    vec2 lv = log2(max(k * refl_blur * sqrt(s2.x * refl_axes + s2.y * refl_axes.yx),
                       vec2(1e-3)));
    float lx = clamp(lv.x, 0.0, refl_levels.x);
    float l0 = floor(lx), l1 = min(l0 + 1.0, refl_levels.x);
    // the level along, l0 + m: no finer than across, below the atlas's last version and within
    // REFL_RIP_M of l0, so versions m0 and m0 + 1 of l0 exist; l1 = l0 + 1 reads the same
    // levels along, versions m0 - 1 (at least 0) and m0
    float m = min(clamp(lv.y, lx, refl_levels.w - 0.001) - l0, float(REFL_RIP_M) - 0.001);
    float m0 = floor(m), tm = exp2(-m0), s0 = exp2(-l0), s1 = s0 * (1.0 - 0.5 * (l1 - l0));
    float up0 = step(0.5, l0), up1 = step(0.5, l1);
    // uv kept half a texel of the coarsest version read inside the map, so no filter reads a
    // neighbour's texels (finer versions then stop a little short of the map's edge)
    vec2 h = 0.5 * refl_levels.yz / vec2(s1, min(0.5 * s0, s1) * tm);
    vec2 u = clamp(uv, h, vec2(1.0) - h);
    float x0 = refl_x(u.x, s0, up0), x1 = refl_x(u.x, s1, up1), yv = (u.y - 2.0) * (1.0 / 3.0);
    vec4 c = mix(mix(refl_level(x0, yv, s0, s0 * tm, up0),
                     refl_level(x0, yv, s0, 0.5 * s0 * tm, up0), m - m0),
                 mix(refl_level(x1, yv, s1, s1 * min(2.0 * tm, 1.0), up1),
                     refl_level(x1, yv, s1, s1 * tm, up1), m - m0), lx - l0);
    // nothing where the ray leaves the map (behind the camera or past its margin)
    vec2 in_uv = step(vec2(0.0), uv) * step(uv, vec2(1.0));
    c *= step(0.0, q.z) * in_uv.x * in_uv.y;
#ifndef SWELL_LINEAR_OUT
    c.rgb = display_to_radiance(c.rgb / max(c.a, 1e-3)) * c.a;
#endif
    return c;
}
#endif

#ifdef SWELL_WAKE
// The wake at the flat sea's point under the pixel (wake.c): its slope in the world's axes
// (xy), the slope variance within the fetch, <s^2> - <s>^2 (z), its foam (w). Outside the map
// (and above the horizon, where w <= 0) nothing; the map's edges are still water, so the
// boundary is not seen.
vec4 wake_sample()
{
    vec3 h = wake_mat * vec3(gl_FragCoord.xy, 1.0);
    // kelvin.h: u = a sqrt(P + e) + b, v = 1/2 + Q / (spread (P + offset)); the map is P in
    // [0, 1], v in [0, 1]; outside, and above the horizon (w <= 0), nothing
    vec2 pq = h.xy / max(h.z, 1e-3);
    float p = max(pq.x, 0.0);
    vec2 uv = vec2(sqrt(p + wake_warp.x) * wake_warp.y + wake_warp.z,
                   0.5 + pq.y / (p + wake_warp.w));
    float in_map = step(0.0, h.z) * step(0.0, pq.x) * step(pq.x, 1.0) * step(0.0, uv.y) *
                   step(uv.y, 1.0);
    vec4 t = texture2D(wake_tex, SERIAL(uv));
    vec2 s = t.r * wake_rot.xy + t.g * wake_rot.zw + wake_k.xy;
    return in_map * vec4(s, max(t.b * wake_k.z - dot(s, s), 0.0), t.a);
}
#endif


#ifdef SWELL_MASK
// The wave mask's amplitude a at the flat sea's point under the pixel (mask.c): its block of
// the Fresnel atlas read within its border (255, the open sea), so beyond the mask the open
// sea; above the horizon (w <= 0) the open sea.
float mask_amp()
{
    vec3 h = mask_mat * vec3(gl_FragCoord.xy, 1.0);
    float a = texture2D(fresnel_tex, SERIAL(clamp(h.xy / max(h.z, 1e-3), mask_box.xy, mask_box.zw))).a;
    return mix(1.0, a, step(0.0, h.z));
}
#endif

#ifdef SWELL_REFRACT
// Hu eq. 4 per channel (refract.c): the objects' radiance and, per channel, the water's
// transmittance down to them (1 - alpha_fog), T_c = T_green^(tau_c / tau_green); the lookup at
// the pixel's own place in the map shifted by its slope deviation (the bumped refracted ray).
vec4 refract_local(vec2 ds, out vec3 t)
{
    vec4 c = texture2D(refr_tex, gl_FragCoord.xy * refr_screen.xy + refr_screen.zw +
                                 refr_shift * ds);
    vec3 col = c.rgb / max(c.a, 1e-3);
#ifndef SWELL_LINEAR_OUT
    col = display_to_radiance(col);
#endif
    t = exp2(refr_tau * log2(max(c.a, 1e-4))) * step(1e-4, c.a);
    return vec4(col, c.a);
}
#endif

#ifdef SWELL_SHADOW
// How much of the sun the objects hide from the flat sea's point under the pixel (shadow.c);
// outside the map and above the horizon (w <= 0) nothing.
float shadow_at()
{
    vec3 h = shadow_mat * vec3(gl_FragCoord.xy, 1.0);
    vec2 uv = h.xy / max(h.z, 1e-3);
    vec2 in_uv = step(vec2(0.0), uv) * step(uv, vec2(1.0));
    return step(0.0, h.z) * in_uv.x * in_uv.y * texture2D(shadow_tex, SERIAL(uv)).a;
}
#endif

void main()
{
    g_ds = vec2(0.0);   // ds = s - s0: the patches' means are in s0 (ocean.vert)
    g_var = vec2(0.0);
#ifdef QUALITY_HIGH
    g_mu = v_base.z;
    g_kvar = v_base.w;
    g_dvar = 0.0;
    g_dsw = vec2(0.0);
#endif
    // each slot's whitecaps with its slopes: they share its taps
#if FS_PATTERNS > 0
    SLOPE(0, slope_tex0, v_uv01.xy);
#if defined(QUALITY_HIGH) && FS_WHITECAPS > 0
    WHITECAP(0, wc_tex0, v_uv01.xy);
#endif
#endif
#if FS_PATTERNS > 1
    SLOPE(1, slope_tex1, SERIAL(v_uv01.zw));
#if defined(QUALITY_HIGH) && FS_WHITECAPS > 1
    WHITECAP(1, wc_tex1, SERIAL(v_uv01.zw));
#endif
#endif
#if FS_PATTERNS > 2
    SLOPE(2, slope_tex2, SERIAL(v_uv23.xy));
#if defined(QUALITY_HIGH) && FS_WHITECAPS > 2
    WHITECAP(2, wc_tex2, SERIAL(v_uv23.xy));
#endif
#endif
#if FS_PATTERNS > 3
    SLOPE(3, slope_tex3, SERIAL(v_uv23.zw));
#if defined(QUALITY_HIGH) && FS_WHITECAPS > 3
    WHITECAP(3, wc_tex3, SERIAL(v_uv23.zw));
#endif
#endif
#ifdef SWELL_MASK
    // Locally varying waves (Bruneton §6; geometry/mask.h): the fetched slopes times the
    // mask's amplitude a, their variances times a^2 (the vertex's are scaled already,
    // ocean.vert); the whitecaps below
    float amp = mask_amp();
    g_ds *= amp;
    g_var *= amp * amp;
#ifdef QUALITY_HIGH
    g_dsw *= amp;
#endif
#endif
#ifdef SWELL_WAKE
    // Local waves (Bruneton §6): the wake's slope joins the pixel's, the variance its fetch
    // averaged joins the unresolved (evenly per axis: the map keeps |s|^2, not each axis's;
    // low quality: below, into the vertex's)
    vec4 wake = wake_sample();
    g_ds += wake.xy;
    g_var += vec2(0.5 * wake.z);
#endif
    // Hu §5.1 Fresnel bump mapping and the reflected sky (Bruneton §5.2), at s0 + ds.
    vec4 uv = v_lin + v_lin_dx * g_ds.x + v_lin_dy * g_ds.y;
    vec4 ftex = texture2D(fresnel_tex, min(uv.xy, fresnel_uv_max));
    vec2 d = v_sun.xy - g_ds;
#ifdef QUALITY_HIGH
    // The sun stays a disc on a flat sea (Bruneton §5.1): variance clamped from below, at 1e-4,
    // normal in fp16. Its product is not (1e-8 flushes to 0, as llvmpipe showed): with a wave
    // mask, whose still water is flat on both axes, eq. 15's normalisation takes each axis's
    // inverse square root (else 0 x inf, NaN: white); elsewhere the unresolved variance keeps
    // one axis well above the floor.
    vec2 var = max(v_base.xy + g_var, vec2(1e-4));
    // Slope variance in the view direction (eq. 25), its x weight from the vertex.
    float sig_v = sqrt(mix(var.y, var.x, v_sun.w));

    // Effective Fresnel, eq. 26 (common.glsl), with the exact Fresnel of the texture for
    // Schlick's term.
    float f_eff = fresnel_eff(ftex.a, sig_v);

    // Sun: Ross BRDF, eq. 15: the Gaussian slope density at the half vector's slope zeta_h,
    // centred on the pixel's mean slope, times the vertex's Fresnel / shadowing factor.
    // (v_sun.z: the factor's logarithm, ocean.vert; no 0 x inf where it is past mediump's range)
#ifdef SWELL_MASK
    float p = exp(v_sun.z - 0.5 * (d.x * d.x / var.x + d.y * d.y / var.y)) * inversesqrt(var.x) *
              inversesqrt(var.y);
#else
    float p = exp(v_sun.z - 0.5 * (d.x * d.x / var.x + d.y * d.y / var.y)) *
              inversesqrt(var.x * var.y);
#endif
#else
    // The same with the variance per vertex (ocean.vert): eq. 26 of the vertex's sigma and
    // the Gaussian of eq. 15 with its inverse variances and normalisation.
    vec2 ib = v_base.xy;    // 0.5 / the slope variance
#ifdef SWELL_WAKE
    // The wake's variance within the fetch joins the vertex's, as high quality's g_var: w =
    // wake.z / 2 per axis, 0.5 / (var + w) = ib g with g = 1 / (1 + 2 w ib); eq. 15's
    // normalisation 1 / (sigma_x sigma_y) times sqrt(g_x g_y). Eq. 26's terms stay the
    // vertex's. Before, the distant wake's waves averaged out of the slopes were lost: its
    // glitter's widening there (test_wake test_low_quality).
    vec2 g = 1.0 / (1.0 + wake.z * ib);
    ib *= g;
#endif
    float f_eff = fresnel_eff_terms(ftex.a, v_sun.w, v_base.z);
    float p = exp(v_sun.z - (d.x * d.x * ib.x + d.y * d.y * ib.y));
#ifdef SWELL_WAKE
    p *= sqrt(g.x * g.y);
#endif
#endif
    // capped where the tone map is white anyway: no fp16 infinity reaches the mix below
    vec3 sun = min(sun_irr * min(p, 3.0e4), vec3(1.0e4));

    // Sky: the filtered lookup of eq. 27 (sky_eq27) at the pixel's variance: low quality's
    // per vertex, from the inverse variances it carries. Until this build low quality read the
    // map at the implicit LOD on GPUs (no eq. 27 filter): at 8 m/s from 10 m, per-pixel LOD,
    // its rows near the camera were 13.8 % darker than high's and those at the horizon 9 %
    // brighter (test_render test_quality_match, now on both LOD paths).
#ifdef QUALITY_HIGH
    float sigma = sqrt(max(var.x, var.y));
#else
    float sigma = inversesqrt(2.0 * min(ib.x, ib.y));
#endif
    vec3 sky = sky_decode(sky_eq27(uv.zw, sigma), sky_map_scale);
#ifdef SWELL_REFLECT
    // an object's reflection covers the sky's, and the sun's where it stands in front of it;
    // eq. 27's slope deviations along the view (eq. 25's) and across it (low quality: the
    // larger, per vertex)
#ifdef QUALITY_HIGH
    vec4 obj = reflect_local(uv.zw, vec2(sig_v, sqrt(mix(var.x, var.y, v_sun.w))));
#else
    vec4 obj = reflect_local(uv.zw, vec2(sigma));
#endif
    sky = sky * (1.0 - obj.a) + obj.rgb;
    sun *= 1.0 - obj.a;
#endif

#ifdef SWELL_SHADOW
    // in an object's shadow: no glitter, the water body lit by the sky alone
    float shade = shadow_at();
    sun *= 1.0 - shade;
    vec3 sea_lit = sea_radiance - shade * shadow_sea;
#else
    vec3 sea_lit = sea_radiance;
#endif
#ifdef SWELL_REFRACT
    // Hu eq. 4: C_refract = alpha_fog C_deep_water + (1 - alpha_fog) C_obj, the water body's
    // light as C_deep_water, through the surface's (1 - F) below
    vec3 refr_t;
    vec4 refr_obj = refract_local(g_ds, refr_t);
    sea_lit = mix(sea_lit, refr_obj.rgb, refr_t);
#endif
    // Refracted light, eq. 28.
    vec3 clear_sea = sun + f_eff * sky + (1.0 - f_eff) * sea_lit;

#ifdef QUALITY_HIGH
    // Whitecaps: Dupuy eq. 6 coverage from the prefiltered moments of the foam memory (summed
    // with the slopes above).
#if FS_WHITECAPS > 0
    // The variance below a texel that add_whitecap took out of eq. 6 is drawn instead:
    // the slope deviation of the slots after the last with whitecaps over its standard
    // deviation, a Gaussian field of shorter waves than the foam's and independent of them
    // (the foam's own slopes are not: foam sits on their crests), times its deviation
    // (foam_detail = 1 / those slots' slope variance x + y, 0 without them).
    vec2 dd = g_ds - g_dsw;
    // Eq. 6 on the moments of a skewed memory is not the covered fraction: times the gain
    // that brings its mean over the sea at this footprint to the bake's W (Tessendorf 2023's
    // fraction from the wind; tables/foam_bias.h), a line over the run's footprints.
    float cover = whitecap_cover_gain(whitecap_epsilon,
                                      g_mu + sqrt(g_dvar * foam_detail.x) * (dd.x + dd.y),
                                      g_kvar, foam_gain.x * V_FOOT + foam_gain.y);
#ifdef SWELL_MASK
    cover *= exp2(mask_foam * log2(max(amp, 1e-4)));   // the wind a stands for: a^(b/2)
#endif
#else
    float cover = v_base.z;    // Dupuy eq. 6 from the vertex's moments alone (ocean.vert)
#endif
#ifdef SWELL_WAKE
    cover = 1.0 - (1.0 - cover) * (1.0 - wake.w);    // the wake's foam with the whitecaps'
#endif
    // Foam: Lambertian, reflectance 0.4 (Dupuy §2), lit by sun and sky.
    // Aerial perspective (vterms.glsl): the path scatters in (1 - T) times the horizon sky of
    // its azimuth (sky.h sky_haze), its phase weights from the vertex
    vec3 haze = haze_ray * v_extra.y + haze_mie * v_extra.x;
    // each channel's transmittance from green's: e^{-tau_c m} = T_g^(tau_c / tau_g)
    vec3 t = exp2(haze_tau_ratio * log2(max(v_extra.z, 1e-4)));
#ifdef SWELL_SHADOW
    vec3 foam_lit = foam_radiance - shade * shadow_foam;
#else
    vec3 foam_lit = foam_radiance;
#endif
    gl_FragColor = vec4(tone_map(mix(haze, mix(clear_sea, foam_lit, cover), t)), 1.0);
#else
    // Low quality: eq. 6's coverage and the haze per vertex (ocean.vert: foam and in-scattered
    // light, the clear sea's share).
#ifdef SWELL_WAKE
    clear_sea = mix(clear_sea, wake_foam, wake.w);  // the wake's foam over what is not whitecap
#endif
    gl_FragColor = vec4(tone_map(clear_sea * v_fog.a + v_fog.rgb), 1.0);
#endif
#ifdef SWELL_SLOPE_OUT
    // tests (renderer_desc slope_output): the slope drawn, as the half vector's slope less the
    // pixel's (d, +-2), and the deviation of the variance below it, x + y (0..0.5)
#ifndef QUALITY_HIGH
    vec2 var = 0.5 / ib;
#endif
    gl_FragColor = vec4(clamp(0.5 + 0.25 * d, 0.0, 1.0), 2.0 * sqrt(var.x + var.y), 1.0);
#endif
}
