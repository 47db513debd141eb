// ocean.vert - CPU-displaced sea vertices (gles2-min: no vertex texture fetch). Positions are
// validate: FS_PATTERNS=0 | FS_PATTERNS=1 | FS_PATTERNS=2 | FS_PATTERNS=3 | FS_PATTERNS=4
// camera-relative; texture coordinates are a per-pattern offset wrapped on the CPU in double
// plus the camera-relative rest position over the patch size, so they stay small.
attribute vec3 a_pos;       // displaced, camera-relative, m
attribute vec2 a_rest;      // rest position on the sea plane, camera-relative, m
attribute vec4 a_geo_slope; // CPU patterns: mean slope xy, resolved slope variance xy
attribute vec3 a_geo_k;     // CPU patterns: Dupuy k mean, k variance, foam opacity

uniform mat4 world_to_clip;             // camera-relative world -> clip
uniform vec2 pattern_uv_offset[4];      // per fragment-shader pattern slot
uniform float pattern_inv_size[4];      // 1 / L_i, 1/m

varying vec3 v_view_dir;    // unit vector surface -> camera
varying vec4 v_geo_slope;
varying vec3 v_geo_k;
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

void main()
{
    v_view_dir = normalize(-a_pos);
    v_geo_slope = a_geo_slope;
    v_geo_k = a_geo_k;
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
