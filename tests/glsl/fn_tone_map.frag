// fn_tone_map.frag - test_glsl: common.glsl's tone_map over a grid of radiances u (c, 1 - c,
// 1/2), the magnitude u along x (fn_in.xy: u = x + y px) and the chroma c along y (z + w py),
// so that each channel is the largest somewhere; channel TM_CHANNEL written as 16 bits of
// [0, 1] in R (high byte) and G (low).
#include "common.glsl"

uniform vec4 fn_in;

void main()
{
    float u = fn_in.x + fn_in.y * gl_FragCoord.x;
    float c = fn_in.z + fn_in.w * gl_FragCoord.y;
    vec3 t = tone_map(u * vec3(c, 1.0 - c, 0.5));
#if TM_CHANNEL == 0
    float v = t.r;
#elif TM_CHANNEL == 1
    float v = t.g;
#else
    float v = t.b;
#endif
    v = clamp(v, 0.0, 1.0) * 255.0;
    float hi = floor(v);
    gl_FragColor = vec4(hi / 255.0, v - hi, 0.0, 1.0);
}
