// refl_copy.frag - the reflection atlas's versions (src/render/reflect.c): level l of the map's
// mip chain, halved m times along its vertical, drawn at (w >> l) x (h >> (l + m)): the implicit
// LOD is l + m, the bias -m brings it to l; each fetch at the boundary of two rows of level l is
// their mean, and n of them two rows apart the mean of the 2n rows under the pixel (n = 1 at
// m = 0: the row itself, at its centre). Eight taps always, the unused weighted 0: no branch
// for compilers without flow control (lima).
uniform sampler2D frame_tex;
uniform vec2 copy_step;     // a row of level l in uv; n
uniform float copy_bias;    // -m
varying vec2 v_uv;

void main()
{
    vec4 c = vec4(0.0);
    for (int i = 0; i < 8; i++) {
        float fi = float(i);
        c += step(fi + 0.5, copy_step.y) *
             texture2D(frame_tex, v_uv + vec2(0.0, (2.0 * fi + 1.0 - copy_step.y) * copy_step.x),
                       copy_bias);
    }
    gl_FragColor = c / copy_step.y;
}
