// fn_sky_lookup.frag - test_glsl: the sky map's lookup as ocean.frag makes it, one fetch of
// fn_tex (the baked RGBA8 map, level 0) at common.glsl's sky_map_uv of a direction, decoded
// (sky_decode) with the channel's scale fn_scale.x: azimuths along x (fn_in.x + fn_in.y px,
// radians), elevations along y (fn_in.z + fn_in.w py), channel SKY_CHANNEL as 16 bits of
// radiance / fn_scale.y in R (high byte) and G (low).
#include "common.glsl"

uniform vec4 fn_in;
uniform sampler2D fn_tex;
uniform vec4 fn_scale;

void main()
{
    float az = fn_in.x + fn_in.y * gl_FragCoord.x;
    float el = fn_in.z + fn_in.w * gl_FragCoord.y;
    vec3 r = vec3(cos(el) * cos(az), cos(el) * sin(az), sin(el));
    vec3 sky = sky_decode(texture2D(fn_tex, sky_map_uv(r)).rgb, vec3(fn_scale.x));
    float v = clamp(sky[SKY_CHANNEL] / fn_scale.y, 0.0, 1.0) * 255.0;
    float hi = floor(v);
    gl_FragColor = vec4(hi / 255.0, v - hi, 0.0, 1.0);
}
