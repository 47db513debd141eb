// upscale.vert - render scale (src/render/upscale.h): one triangle strip over the output.
attribute vec2 a_ndc;
varying vec2 v_uv;

void main()
{
    v_uv = a_ndc * 0.5 + 0.5;
    gl_Position = vec4(a_ndc, 0.0, 1.0);
}
