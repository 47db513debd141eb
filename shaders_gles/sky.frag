// sky.frag - the background sky: one fetch of the tone-mapped (display-space) sky map the
// renderer derives from the baked one. With SUN_DISC: the sun's disc (angular radius 0.267 deg)
// drawn as a quad the renderer places, tone-mapped sun plus sky.
// validate: | SUN_DISC
#include "common.glsl"

#ifdef SUN_DISC
uniform vec3 sun_display;           // tone-mapped sun disc (sun + sky radiance, x exposure)
varying vec2 v_disc;
#else
uniform sampler2D sky_tex;          // display-space sky map (renderer.c: tone_map of the bake)
varying vec2 v_uv;
#endif

void main()
{
#ifdef SUN_DISC
    if (dot(v_disc, v_disc) > 1.0)
        discard;
    gl_FragColor = vec4(sun_display, 1.0);
#else
    gl_FragColor = vec4(texture2D(sky_tex, v_uv).rgb, 1.0);
#endif
}
