// sky.frag - the background sky seen from the camera's altitude (sky.h sky_view_gains, Bruneton
// 2010 §6: from the ground to space): per pixel, the Rayleigh and Mie gains of the view's
// elevation from a 512 x 2 table (row 0 Rayleigh, row 1 Mie, each channel scaled to 8 bits)
// times the phase functions at the angle to the sun (common.glsl horizon_sky, the same single
// scattering as the baked sky map), tone-mapped. From the sea it is the sky map's sky; from
// orbit black space over a glowing limb. With SUN_DISC: the sun's disc (angular radius
// 0.267 deg) drawn as a quad the renderer places, tone-mapped sun plus sky.
// validate: | SUN_DISC | SWELL_LINEAR_OUT
#include "common.glsl"

#ifdef SUN_DISC
uniform vec3 sun_display;           // tone-mapped sun disc (sun + sky radiance, x exposure)
varying vec2 v_disc;
#else
uniform sampler2D sky_view;         // gains by elevation, u = (1 + sin(elevation)) / 2
uniform vec3 sky_view_scale[2];     // texel x scale = gain x exposure: Rayleigh, Mie
uniform vec4 sky_sun;               // the sun's direction; Henyey-Greenstein g
varying vec3 v_dir;
#endif

void main()
{
#ifdef SUN_DISC
    if (dot(v_disc, v_disc) > 1.0)
        discard;
    gl_FragColor = vec4(sun_display, 1.0);
#else
    vec3 d = normalize(v_dir);
    float u = 0.5 + 0.5 * d.z;   // the table is even in sin(elevation) (sky.h)
    vec3 ray = texture2D(sky_view, vec2(u, 0.25)).rgb * sky_view_scale[0];
    vec3 mie = texture2D(sky_view, vec2(u, 0.75)).rgb * sky_view_scale[1];
    gl_FragColor = vec4(tone_map(horizon_sky(dot(d, sky_sun.xyz), sky_sun.w, ray, mie)), 1.0);
#endif
}
