// boat.frag - the swell program's demo boat (src/app/boat.c, boat.vert): its colour, alpha 1
// (what swell's reflection pass reads as covered).
varying vec3 v_color;

void main()
{
    gl_FragColor = vec4(v_color, 1.0);
}
