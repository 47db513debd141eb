// fn_vterms.frag - test_glsl: writes fn_vterms.vert's two bytes (R high, G low).
varying vec2 v_bytes;

void main()
{
    gl_FragColor = vec4(v_bytes, 0.0, 1.0);
}
