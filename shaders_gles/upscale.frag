// upscale.frag - render scale (src/render/upscale.h): the smaller frame, one bilinear fetch a pixel
// (clamped to its edges by the texture's wrap mode).
uniform sampler2D frame_tex;
varying vec2 v_uv;

void main()
{
    gl_FragColor = texture2D(frame_tex, v_uv);
}
