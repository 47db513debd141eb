// fn_vterms.vert - test_glsl: vterms.glsl's vertex_terms (ocean.vert on the tiers with vertex
// texture fetch) at one vertex per point: a_p is its camera-relative position, a_rest its rest
// point and the CPU patterns' slope variance, a_slope their mean slope, a_px its pixel (x, y). The value selected by fn_mask (weights over the terms, vshade.h's
// order: lin, lin_dx, lin_dy, sun, (geo, 0), (fog, 0)), after log2 if fn_log, is mapped to
// [0, 1] by fn_range (lo, 1 / (hi - lo)) and split here, in highp, into a high and a low byte
// for the fragment stage.
#include "common.glsl"
#include "vterms.glsl"

attribute vec3 a_p;
attribute vec4 a_rest;
attribute vec2 a_slope;
attribute vec2 a_px;
uniform vec4 fn_mask[6];
uniform vec2 fn_range;
uniform vec2 fn_size;       // the target, px
uniform float fn_log;       // 1: compare log2 of the value (at least 1e-12)
varying vec2 v_bytes;

void main()
{
    vec4 lin, lin_dx, lin_dy, sun;
    vec3 geo, fog;
    vertex_terms(a_p, a_rest.xy, a_slope, a_rest.zw, lin, lin_dx, lin_dy, sun, geo, fog);
    float x = dot(lin, fn_mask[0]) + dot(lin_dx, fn_mask[1]) + dot(lin_dy, fn_mask[2]) +
              dot(sun, fn_mask[3]) + dot(vec4(geo, 0.0), fn_mask[4]) +
              dot(vec4(fog, 0.0), fn_mask[5]);
    if (fn_log > 0.5)
        x = log2(max(x, 1e-12));
    float v = clamp((x - fn_range.x) * fn_range.y, 0.0, 1.0) * 255.0;
    float hi = floor(v);
    v_bytes = vec2(hi / 255.0, v - hi);
    gl_Position = vec4(2.0 * (a_px + 0.5) / fn_size - 1.0, 0.0, 1.0);
    gl_PointSize = 1.0;
}
