// ocean.frag - sea shading (Bruneton 2010 §4-5, Hu 2006 §5, Dupuy 2012 eq. 6-8).
// validate: FS_PATTERNS=0 FS_WHITECAPS=0 | FS_PATTERNS=1 FS_WHITECAPS=1 | FS_PATTERNS=2 FS_WHITECAPS=2 | FS_PATTERNS=3 FS_WHITECAPS=2 | FS_PATTERNS=4 FS_WHITECAPS=2 | FS_PATTERNS=4 FS_WHITECAPS=4 | FS_PATTERNS=3 FS_WHITECAPS=0
// FS_PATTERNS: pattern slots fetched here (largest first); the renderer draws each run of grid
// rows with the variant whose smaller patterns are not yet fully filtered there, and passes the
// rest as constants (their top mip level: mean and variance over the whole patch, Bruneton §4.1).
// FS_WHITECAPS <= FS_PATTERNS: leading slots whose patterns carry whitecaps (bake.c).
// QUALITY_HIGH: Ross BRDF sun (eq. 15), filtered sky (eq. 27 by LOD bias), effective Fresnel
// (eq. 26) on Hu's Fresnel texture, refracted light (eq. 28), whitecaps (Dupuy eq. 6).
// Otherwise Hu's single pass: Fresnel texture, bumped sky lookup, Phong sun, linearised in the
// slope by ocean.vert and mixed in display space as Hu's LDR pass was: the renderer binds a
// tone-mapped sky map and a Fresnel texture whose R holds Hu's Phong term for the current sun.
#include "common.glsl"

uniform sampler2D fresnel_tex;      // Hu §5.1: RGB = 0.5 + 0.5 view vector, A = Fresnel
uniform sampler2D sky_tex;
uniform float sky_map_scale;
uniform float sky_map_size;         // texels
uniform vec3 sun_dir_world;
uniform vec3 sun_irr;               // sun irradiance at the sea, relative to E0 (x exposure)
uniform vec3 sea_radiance;          // eq. 28's L_sea: water body lit by sun and sky (x exposure)
uniform vec3 foam_radiance;         // Lambertian 0.4 foam lit by sun and sky (x exposure)
uniform vec4 const_slope;           // patterns not fetched: mean slope xy, variance xy
uniform vec3 const_k;               // ...their Dupuy k mean, k variance, foam clear fraction
uniform vec2 unresolved_var;        // slope variance below every table, x/y (Bruneton eq. 4)
uniform float whitecap_epsilon;     // Dupuy eq. 3 threshold on j
uniform vec4 slope_scale[4];        // RGBA8 dequantisation per fragment pattern slot
uniform vec4 slope_bias[4];
uniform vec4 wc_scale[4];
uniform vec4 wc_bias[4];
#if FS_PATTERNS > 0
uniform sampler2D slope_tex0;
varying vec2 v_uv0;
#endif
#if FS_PATTERNS > 1
uniform sampler2D slope_tex1;
varying vec2 v_uv1;
#endif
#if FS_PATTERNS > 2
uniform sampler2D slope_tex2;
varying vec2 v_uv2;
#endif
#if FS_PATTERNS > 3
uniform sampler2D slope_tex3;
varying vec2 v_uv3;
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

#ifdef QUALITY_HIGH
varying vec3 v_view_dir;
varying vec4 v_geo_slope;
varying vec3 v_geo_k;
#else
varying vec4 v_lin;                 // ocean.vert: lookup coordinates at the vertex's slope...
varying vec4 v_lin_dx;              // ...and their derivatives in the slope
varying vec4 v_lin_dy;
uniform vec3 sea_display;           // low: tone-mapped eq. 28 water colour
uniform vec3 sun_display;           // low: display-space colour of Hu's Phong highlight
#endif

// Running sums over patterns: mean slope, resolved slope variance <s^2> - <s>^2 (Bruneton
// §4.1, mip-filtered moments), Dupuy's k mean and variance, product of (1 - foam opacity).
vec2 g_slope;
vec2 g_var;
float g_mu;
float g_kvar;
float g_clear;

void add_slope(vec4 s)
{
    g_slope += s.xy;
    g_var += max(s.zw - s.xy * s.xy, vec2(0.0));
}

void add_whitecap(vec4 k)
{
    // Dupuy eq. 7-8 per pattern; the variance is summed per pattern (sum <k_i^2> - <k_i>^2), the
    // same uncorrelated-pattern assumption as eq. 8 without its cross terms of the means.
    g_mu += k.x;
    g_kvar += max(k.y - k.x * k.x, 0.0);
    g_clear *= 1.0 - clamp(k.z, 0.0, 1.0);
}

#define SLOPE(i, tex, uv) add_slope(slope_bias[i] + slope_scale[i] * texture2D(tex, uv))
#define WHITECAP(i, tex, uv) add_whitecap(wc_bias[i] + wc_scale[i] * texture2D(tex, uv))

// Smith's shadowing/masking of the Ross BRDF for a Gaussian of variance var seen at cos_t:
// Lambda(a) = (e^{-a^2} / (a sqrt(pi)) - erfc(a)) / 2, a = 1 / (sqrt(2) sigma tan theta), by the
// rational fit of Walter et al. 2007 (eq. 27, the same Gaussian/Beckmann Lambda; relative error
// below 0.35 % for the shadowing term 1 / (1 + Lambda)), no exp or erf per pixel.
float ross_lambda(float cos_t, float var)
{
    float c = clamp(cos_t, 0.01, 0.9999);
    float a = c / sqrt((1.0 - c * c) * 2.0 * var);
    if (a >= 1.6)
        return 0.0;
    return (1.0 - 1.259 * a + 0.396 * a * a) / (3.535 * a + 2.181 * a * a);
}

void main()
{
#ifndef QUALITY_HIGH
    // Single pass: the slope's deviation from ocean.vert's s0 (const_slope.zw: the fetched
    // slots' biases minus their means), then the two linearised lookups.
    vec2 ds = const_slope.zw;
#if FS_PATTERNS > 0
    ds += slope_scale[0].xy * texture2D(slope_tex0, v_uv0).xy;
#endif
#if FS_PATTERNS > 1
    ds += slope_scale[1].xy * texture2D(slope_tex1, v_uv1).xy;
#endif
#if FS_PATTERNS > 2
    ds += slope_scale[2].xy * texture2D(slope_tex2, v_uv2).xy;
#endif
#if FS_PATTERNS > 3
    ds += slope_scale[3].xy * texture2D(slope_tex3, v_uv3).xy;
#endif
    vec4 uv = v_lin + v_lin_dx * ds.x + v_lin_dy * ds.y;
    // Hu 2006 eq. 3: F from the Fresnel texture, the sky reflected about the bumped normal, the
    // Phong sun of Hu §5.3 (R: evaluated per texel of the bumped view vector for this sun).
    vec4 ftex = texture2D(fresnel_tex, uv.xy);
    vec3 sky = texture2D(sky_tex, uv.zw).rgb;
    gl_FragColor = vec4(mix(sea_display, sky, ftex.a) + ftex.r * sun_display, 1.0);
#else
    vec3 v = normalize(v_view_dir);
    vec3 l = sun_dir_world;
    g_slope = v_geo_slope.xy + const_slope.xy;
    g_var = v_geo_slope.zw + const_slope.zw;
    g_mu = v_geo_k.x + const_k.x;
    g_kvar = v_geo_k.y + const_k.y;
    g_clear = (1.0 - v_geo_k.z) * const_k.z;
#if FS_PATTERNS > 0
    SLOPE(0, slope_tex0, v_uv0);
#endif
#if FS_PATTERNS > 1
    SLOPE(1, slope_tex1, v_uv1);
#endif
#if FS_PATTERNS > 2
    SLOPE(2, slope_tex2, v_uv2);
#endif
#if FS_PATTERNS > 3
    SLOPE(3, slope_tex3, v_uv3);
#endif
    // Bruneton §3.2: normals that face away from the viewer are reflected about the plane
    // normal to v (one normalize: the sign test works on the unnormalised normal).
    vec3 n = vec3(-g_slope, 1.0);
    n = normalize(n - 2.0 * min(dot(n, v), 0.0) * v);

    // Hu §5.1 Fresnel bump mapping: the view vector bumped by the normal's tilt indexes the
    // 2D Fresnel texture (kept inside the unit disc it was built on).
    vec2 fv = v.xy - n.xy;
    fv *= min(1.0, 0.999 * inversesqrt(max(dot(fv, fv), 1e-6)));
    vec4 ftex = texture2D(fresnel_tex, vec2(0.5) + 0.5 * fv);
    vec3 r = reflect(-v, n);

    vec2 var = g_var + unresolved_var;
    // The sun stays a disc on a flat sea (Bruneton §5.1): variance clamped from below. 1e-4 is
    // also the smallest normal fp16 value squared-safe here.
    var = max(var, vec2(1e-4));
    vec3 tx = normalize(vec3(n.z, 0.0, -n.x));
    vec3 ty = cross(n, tx);
    float cos_v = max(dot(v, n), 0.01);
    float cos_l = dot(l, n);
    // Slope variance in the view direction, eq. 25.
    vec2 vt = vec2(dot(v, tx), dot(v, ty));
    float vt2 = max(dot(vt, vt), 1e-4);
    float var_v = (var.x * vt.x * vt.x + var.y * vt.y * vt.y) / vt2;
    float sig_v = sqrt(var_v);

    // Effective Fresnel, eq. 26, with the exact Fresnel of the texture for Schlick's term.
    const float R0 = 0.02;
    float f_eff = R0 + (ftex.a - R0) * exp(-2.69 * sig_v) / (1.0 + 22.7 * sig_v * sqrt(sig_v));

    // Sun: Ross BRDF, eq. 15, in the frame of the mean normal.
    vec3 sun = vec3(0.0);
    if (cos_l > 0.0) {
        vec3 h = normalize(v + l);
        float hn = max(dot(h, n), 0.05);
        vec2 zh = -vec2(dot(h, tx), dot(h, ty)) / hn;
        float p = exp(-0.5 * (zh.x * zh.x / var.x + zh.y * zh.y / var.y))
                  / (2.0 * PI * sqrt(var.x) * sqrt(var.y));
        float vh = clamp(dot(v, h), 0.0, 1.0);
        float c5 = 1.0 - vh;
        float fs = R0 + (1.0 - R0) * c5 * c5 * c5 * c5 * c5;   // Schlick, as in eq. 15
        float shadow = 1.0 + ross_lambda(cos_v, var_v) + ross_lambda(cos_l, var_v);
        float hn2 = hn * hn;
        // capped where the tone map is white anyway: no fp16 infinity reaches the mix below
        sun = min(sun_irr * min(p * fs / (4.0 * hn2 * hn2 * cos_v * shadow), 3.0e4), vec3(1.0e4));
    }

    // Sky: the filtered lookup of eq. 27 approximated by a LOD bias equal to the filter's
    // footprint 2 sigma du/dzeta in texels (du/dzeta = 1 / (1 + r_z) for this map).
    float rz = max(r.z, 0.0);
    float foot = 2.0 * sqrt(max(var.x, var.y)) * sky_map_size / (1.0 + rz);
    float bias = log2(max(foot, 1.0));
    vec3 sky = texture2D(sky_tex, sky_map_uv(r), bias).rgb * sky_map_scale;

    // Refracted light, eq. 28.
    vec3 clear_sea = sun + f_eff * sky + (1.0 - f_eff) * sea_radiance;

    // Whitecaps: Dupuy eq. 6 coverage from the prefiltered moments, with the baked foam.
#if FS_WHITECAPS > 0
    WHITECAP(0, wc_tex0, v_uv0);
#endif
#if FS_WHITECAPS > 1
    WHITECAP(1, wc_tex1, v_uv1);
#endif
#if FS_WHITECAPS > 2
    WHITECAP(2, wc_tex2, v_uv2);
#endif
#if FS_WHITECAPS > 3
    WHITECAP(3, wc_tex3, v_uv3);
#endif
    float sig_k = sqrt(max(g_kvar, 1e-6));
    float w = 0.5 + 0.5 * erf_as((whitecap_epsilon - g_mu) / (1.41421356 * sig_k));
    float cover = 1.0 - (1.0 - clamp(w, 0.0, 1.0)) * g_clear;
    // Foam: Lambertian, reflectance 0.4 (Dupuy §2), lit by sun and sky.
    vec3 radiance = mix(clear_sea, foam_radiance, cover);
    gl_FragColor = vec4(tone_map(radiance), 1.0);
#endif
}
