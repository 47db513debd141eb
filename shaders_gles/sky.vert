// sky.vert - the background sky as a coarse screen mesh (renderer.c): each vertex's view ray in
// camera-relative world space (sky.frag shades it per pixel: the limb seen from orbit is a
// thin band). With SUN_DISC: the quad of the sun.
// validate: | SUN_DISC
#include "common.glsl"

attribute vec2 a_ndc;
#ifdef SUN_DISC
uniform vec4 sun_ndc;               // disc centre x, y and radius x, y, NDC
varying vec2 v_disc;                // position in the disc, unit radius
#else
uniform mat4 clip_to_world_rel;     // inverse(projection * camera_view_rel)
varying vec3 v_dir;
#endif

void main()
{
#ifdef SUN_DISC
    v_disc = a_ndc;
    gl_Position = vec4(sun_ndc.xy + a_ndc * sun_ndc.zw, 0.999999, 1.0);
#else
    // Unproject the near-plane point: the far plane is thousands of kilometres away and its
    // inverse is so ill-conditioned in float that every corner came out the same direction.
    vec4 p = clip_to_world_rel * vec4(a_ndc, -1.0, 1.0);
    v_dir = normalize(p.xyz / p.w);
    gl_Position = vec4(a_ndc, 0.999999, 1.0);
#endif
}
