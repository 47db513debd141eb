// stream_blend.frag - a streamed table's loop blend on the GPU (src/render/stream_gpu.c): level l
// of the two loop frames the animation is between, each texel read at its centre (the viewport
// is the level's size, the sources' filter NEAREST_MIPMAP_NEAREST, the implicit LOD l), mixed by
// the phase's weight as tables/stream.c stream_blend does in bytes: a + (b - a) w, w in 1/256ths.
// A whitecap table (m, <m^2>, 0, k) has in channel 2 of levels 0 and 1 the blend's own variance
// of the foam memory, 4 (1 - w) w (m_b - m_a)^2 in the bytes' units (stream.h
// stream_blend_whitecap: B = 4 (1 - w) w d^2 / 255, d the bytes' difference); blend_mix holds
// 4 (1 - w) w there, 0 above level 1 and for slope tables, and blend_keep 1 for slope tables
// (channel 2 blended as the others), 0 for whitecap tables.
uniform sampler2D frame_a;
uniform sampler2D frame_b;
uniform vec3 blend_w;       // w, blend_mix, blend_keep
varying vec2 v_uv;

void main()
{
    vec4 a = texture2D(frame_a, v_uv), b = texture2D(frame_b, v_uv);
    vec4 c = a + (b - a) * blend_w.x;
    float d = b.r - a.r;
    c.b = c.b * blend_w.z + blend_w.y * d * d;
    gl_FragColor = c;
}
