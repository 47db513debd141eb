// bench_quad.frag - the benchmark baseline (src/app/bench.c): one trilinear texture fetch per pixel.
uniform sampler2D quad_tex;
varying vec2 v_uv;

void main()
{
    gl_FragColor = texture2D(quad_tex, v_uv);
}
