// ocean.vert - CPU-displaced sea vertices (gles2-min: no vertex texture fetch). Positions are
// validate: FS_PATTERNS=0 | FS_PATTERNS=1 | FS_PATTERNS=2 | FS_PATTERNS=3 | FS_PATTERNS=4
// camera-relative; texture coordinates are a per-pattern offset wrapped on the CPU in double
// plus the camera-relative rest position over the patch size, so they stay small.
//
// Low quality (Hu 2006 single pass) is linearised here in the fine-scale slope: everything the
// pass looks up depends on the pixel only through its slope s = s0 + ds, so this stage
// evaluates the two lookup coordinates (Hu §5.1's Fresnel texture at the bumped view vector,
// Bruneton §5.2's sky map at the reflected ray) at the vertex's mean slope s0 and their
// central differences over +-h (h: the fetched patterns' slope deviation), and the fragment
// stage only adds d(uv)/ds ds: two multiply-adds instead of two normalisations, a reflection
// and a stereographic division per pixel, in mediump.
#include "common.glsl"

attribute vec3 a_pos;       // displaced, camera-relative, m
attribute vec2 a_rest;      // rest position on the sea plane, camera-relative, m
attribute vec4 a_geo_slope; // CPU patterns: mean slope xy, resolved slope variance xy
attribute vec3 a_geo_k;     // CPU patterns: Dupuy k mean, k variance, foam opacity

uniform mat4 world_to_clip;             // camera-relative world -> clip
uniform vec2 pattern_uv_offset[4];      // per fragment-shader pattern slot
uniform float pattern_inv_size[4];      // 1 / L_i, 1/m

#ifdef QUALITY_HIGH
varying vec3 v_view_dir;    // unit vector surface -> camera
varying vec4 v_geo_slope;
varying vec3 v_geo_k;
#else
uniform vec3 lin_s0;        // xy: mean slope of every fragment pattern slot; z: step h
varying vec4 v_lin;         // Fresnel-texture uv, sky-map uv at s0
varying vec4 v_lin_dx;      // their derivatives in s.x ...
varying vec4 v_lin_dy;      // ... and s.y
#endif
#if FS_PATTERNS > 0
varying vec2 v_uv0;
#endif
#if FS_PATTERNS > 1
varying vec2 v_uv1;
#endif
#if FS_PATTERNS > 2
varying vec2 v_uv2;
#endif
#if FS_PATTERNS > 3
varying vec2 v_uv3;
#endif

#ifndef QUALITY_HIGH
// The single pass's two lookups for view v and sea slope s: Hu §5.1 (the view vector bumped by
// the normal's tilt, kept in the unit disc the texture covers) and the reflected sky (normals
// facing away from the viewer reflected first, Bruneton §3.2).
vec4 lookups(vec3 v, vec2 s)
{
    vec3 n = vec3(-s, 1.0);
    n = normalize(n - 2.0 * min(dot(n, v), 0.0) * v);
    vec2 fv = v.xy - n.xy;
    fv *= min(1.0, 0.999 * inversesqrt(max(dot(fv, fv), 1e-6)));
    return vec4(vec2(0.5) + 0.5 * fv, sky_map_uv(reflect(-v, n)));
}
#endif

void main()
{
    vec3 v = normalize(-a_pos);
#ifdef QUALITY_HIGH
    v_view_dir = v;
    v_geo_slope = a_geo_slope;
    v_geo_k = a_geo_k;
#else
    vec2 s0 = a_geo_slope.xy + lin_s0.xy;
    float h = lin_s0.z;
    v_lin = lookups(v, s0);
    v_lin_dx = (lookups(v, s0 + vec2(h, 0.0)) - lookups(v, s0 - vec2(h, 0.0))) / (2.0 * h);
    v_lin_dy = (lookups(v, s0 + vec2(0.0, h)) - lookups(v, s0 - vec2(0.0, h))) / (2.0 * h);
#endif
#if FS_PATTERNS > 0
    v_uv0 = pattern_uv_offset[0] + a_rest * pattern_inv_size[0];
#endif
#if FS_PATTERNS > 1
    v_uv1 = pattern_uv_offset[1] + a_rest * pattern_inv_size[1];
#endif
#if FS_PATTERNS > 2
    v_uv2 = pattern_uv_offset[2] + a_rest * pattern_inv_size[2];
#endif
#if FS_PATTERNS > 3
    v_uv3 = pattern_uv_offset[3] + a_rest * pattern_inv_size[3];
#endif
    gl_Position = world_to_clip * vec4(a_pos, 1.0);
}
