// fn_whitecap_cover.frag - test_glsl: common.glsl's whitecap_cover (Dupuy eq. 6, erf_as) over a
// grid of foam-memory means mu along x (fn_in.xy: mu = x + y px) and variances along y
// (z + w py), at threshold 0, written as 16 bits of [0, 1] in R (high byte) and G (low).
#include "common.glsl"

uniform vec4 fn_in;

void main()
{
    float mu = fn_in.x + fn_in.y * gl_FragCoord.x;
    float kvar = fn_in.z + fn_in.w * gl_FragCoord.y;
    float v = whitecap_cover(0.0, mu, kvar) * 255.0;
    float hi = floor(v);
    gl_FragColor = vec4(hi / 255.0, v - hi, 0.0, 1.0);
}
