// boat.frag - the swell program's demo boat (src/app/boat.c, boat.vert): its colour, alpha 1
// (what swell's reflection and shadow passes read as covered); in a refraction pass its colour
// times alpha, the water's transmittance down to it (what the pass asks).
varying vec4 v_color;

void main()
{
    gl_FragColor = vec4(v_color.rgb * v_color.a, v_color.a);
}
