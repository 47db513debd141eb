// sky.vert - full-screen quad; the view ray of each corner in camera-relative world space.
attribute vec2 a_ndc;
uniform mat4 clip_to_world_rel;     // inverse(projection * camera_view_rel)
varying vec3 v_ray_world;

void main()
{
    // Unproject the near-plane corner: the far plane is thousands of kilometres away and its
    // inverse is so ill-conditioned in float that every corner came out the same direction.
    vec4 p = clip_to_world_rel * vec4(a_ndc, -1.0, 1.0);
    v_ray_world = p.xyz / p.w;
    gl_Position = vec4(a_ndc, 0.999999, 1.0);
}
