// sky.frag - the background sky from the tone-mapped (display-space) sky map the renderer
// derives from the baked one, plus the sun disc: no tone mapping per pixel.
#include "common.glsl"

uniform sampler2D sky_tex;          // display-space sky map (renderer.c: tone_map of the bake)
uniform vec3 sun_dir_world;
uniform vec3 sun_display;           // tone-mapped sun disc (sky + sun radiance, x exposure)
varying vec3 v_ray_world;

void main()
{
    vec3 d = normalize(v_ray_world);
    vec3 c = texture2D(sky_tex, sky_map_uv(d)).rgb;
    // Sun disc, angular radius 0.267 deg: cos = 0.999989 is not representable in mediump, so
    // the test compares the squared chord |d - sun|^2 = 2 (1 - cos) with 2.2e-5 instead.
    vec3 e = d - sun_dir_world;
    if (dot(e, e) < 2.2e-5 && d.z > 0.0)
        c = sun_display;
    gl_FragColor = vec4(c, 1.0);
}
