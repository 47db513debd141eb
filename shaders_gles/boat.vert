// boat.vert - the swell program's demo boat (src/app/boat.c): an application's object, lit per
// vertex by the sun (Lambert) and the sky (a constant), in display colour.
attribute vec3 a_pos;               // boat frame: x forward, y to port, z up, m
attribute vec3 a_normal;
attribute vec3 a_color;             // albedo, display colour
uniform mat4 mvp;                   // boat frame -> clip (the eye's, or a reflection pass's)
uniform mat3 model_rot;             // boat frame -> world rotation (heading, pitch, roll)
uniform vec3 sun_dir;               // towards the sun, world
uniform vec2 attenuation;           // a refraction pass's attenuation per m (0: none); the
                                    // pose's heave, m
varying vec4 v_color;               // alpha: the water's transmittance down to the point

void main()
{
    vec3 n = model_rot * a_normal;
    // two-sided: the mesh is drawn without culling
    float lambert = abs(dot(n, sun_dir));
    float z = attenuation.y + (model_rot * a_pos).z;
    v_color = vec4(a_color * (0.35 + 0.65 * lambert * step(0.0, sun_dir.z)),
                   exp(attenuation.x * min(z, 0.0)));
    gl_Position = mvp * vec4(a_pos, 1.0);
}
