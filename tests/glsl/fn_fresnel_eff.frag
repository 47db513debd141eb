// fn_fresnel_eff.frag - test_glsl: common.glsl's fresnel_eff over a grid of inputs, the bumped
// view's Fresnel f along x (fn_in.xy: f = x + y px) and the slope deviation along y (z + w py),
// written as 16 bits of [0, 1] in R (high byte) and G (low).
#include "common.glsl"

uniform vec4 fn_in;

void main()
{
    float f = fn_in.x + fn_in.y * gl_FragCoord.x;
    float sig = fn_in.z + fn_in.w * gl_FragCoord.y;
    float v = clamp(fresnel_eff(f, sig), 0.0, 1.0) * 255.0;
    float hi = floor(v);
    gl_FragColor = vec4(hi / 255.0, v - hi, 0.0, 1.0);
}
