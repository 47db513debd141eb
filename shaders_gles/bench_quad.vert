// bench_quad.vert - the benchmark baseline (src/app/bench.c): one fullscreen quad, the texture
// repeated uv_scale times across the screen so its level of detail is fixed by the caller.
attribute vec2 a_ndc;
uniform vec2 uv_scale;              // texture repeats across the screen, per axis
varying vec2 v_uv;

void main()
{
    v_uv = (a_ndc * 0.5 + 0.5) * uv_scale;
    gl_Position = vec4(a_ndc, 0.0, 1.0);
}
