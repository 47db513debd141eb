// fn_ross_lambda.frag - test_glsl: common.glsl's ross_lambda as the shadowing term
// 1 / (1 + Lambda) over a grid of view cosines along x (fn_in.xy: cos = x + y px) and slope
// variances along y (z + w py), written as 16 bits of [0, 1] in R (high byte) and G (low).
#include "common.glsl"

uniform vec4 fn_in;

void main()
{
    float c = fn_in.x + fn_in.y * gl_FragCoord.x;
    float var = fn_in.z + fn_in.w * gl_FragCoord.y;
    float v = 255.0 / (1.0 + ross_lambda(c, var));
    float hi = floor(v);
    gl_FragColor = vec4(hi / 255.0, v - hi, 0.0, 1.0);
}
