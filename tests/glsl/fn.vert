// fn.vert - test_glsl: a fullscreen triangle; the fragment shader takes its inputs from
// gl_FragCoord.
attribute vec2 a_pos;

void main()
{
    gl_Position = vec4(a_pos, 0.0, 1.0);
}
