// sky.frag - the background sky from the baked stereographic sky map, plus the sun disc.
#include "common.glsl"

uniform sampler2D sky_tex;
uniform float sky_map_scale;        // texel * scale = radiance x exposure
uniform vec3 sun_dir_world;
uniform vec3 sun_radiance;          // sun irradiance / solid angle x exposure, fp16-safe
varying vec3 v_ray_world;

void main()
{
    vec3 d = normalize(v_ray_world);
    vec3 l = texture2D(sky_tex, sky_map_uv(d)).rgb * sky_map_scale;
    // Sun disc, angular radius 0.267 deg: cos = 0.999989 is not representable in mediump, so
    // the test compares the squared chord |d - sun|^2 = 2 (1 - cos) with 2.2e-5 instead.
    vec3 c = d - sun_dir_world;
    if (dot(c, c) < 2.2e-5 && d.z > 0.0)
        l += sun_radiance;
    gl_FragColor = vec4(tone_map(l), 1.0);
}
