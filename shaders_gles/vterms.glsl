// vterms.glsl - the terms of a sea vertex alone, for ocean.vert; src/geometry/vshade.c evaluates the same
// on the CPU where a driver refuses the vertex shaders that do (CPU_VERTEX_TERMS; the uniforms
// here are the fields of its struct vshade_frame), and test_glsl's test_vshade compares the two
// on the GPU through tests/glsl/fn_vterms.vert. Needs common.glsl; QUALITY_HIGH takes the
// haze's phase weights instead of its fog.
// the terms of the vertex alone (vshade.h's frame: on gles2-min the CPU evaluates them)
uniform vec2 fresnel_uv_scale;          // the Fresnel texels' share of the atlas (renderer.c)
uniform vec3 lin_s0;        // xy: mean slope of every fragment pattern slot; z: step h
uniform vec2 lod_frame;     // the camera's altitude squared, log2(pixel angle / altitude):
                            // lod_foot's terms (renderer.c vertex_frame)
uniform vec3 sun_dir_world;
uniform vec3 haze_tau;      // aerial perspective (sky.h sky_haze): vertical optical depth,
uniform vec2 haze_frame;    // the air mass per metre of path from the camera's height:
                            // (1 - e^{-h/H}) / h; Mie g
uniform vec2 total_var;     // every pattern's slope variance + unresolved_var
uniform float sky_map_size; // texels
#ifndef QUALITY_HIGH
uniform vec3 haze_ray;      // the horizon's Rayleigh and Mie radiances before the phase
uniform vec3 haze_mie;      // functions (x exposure)
#endif

// The two lookups for view v and sea slope s: Hu §5.1's Fresnel texture at the view vector
// bumped by the normal's tilt (kept in the unit disc the texture covers) and the sky map at the
// reflected ray; normals facing away from the viewer are reflected first (Bruneton §3.2).
vec3 facing_normal(vec3 v, vec2 s)
{
    vec3 n = vec3(-s, 1.0);
    return normalize(n - 2.0 * min(dot(n, v), 0.0) * v);
}

vec4 lookups(vec3 v, vec2 s)
{
    vec3 n = facing_normal(v, s);
    vec2 fv = v.xy - n.xy;
    float rho = length(fv);
    // fresnel.h: radius r = 1 - sqrt(1 - theta / (pi / 2)), theta = asin(rho)
    float r = 1.0 - sqrt(max(1.0 - asin(min(rho, 1.0)) / (0.5 * PI), 0.0));
    fv *= r / max(rho, 1e-6);
    return vec4((vec2(0.5) + 0.5 * fv) * fresnel_uv_scale, sky_map_uv(reflect(-v, n)));
}

// The terms of the vertex alone, with vshade.h's layout (vshade.c evaluates the same): position
// p and rest point rest, camera-relative; the patterns resolved on the CPU (grid.c) add their
// mean slope s_cpu and slope variance svar (0 on the tiers with vertex texture fetch).
void vertex_terms(vec3 p, vec2 rest, vec2 s_cpu, vec2 svar, out vec4 lin, out vec4 lin_dx,
                  out vec4 lin_dy, out vec4 sun, out vec3 geo, out vec3 fog)
{
    vec3 v = normalize(-p);
    // the sphere's own slope at the rest point (its drop R - sqrt(R^2 - r^2) differentiated)
    // tilts every distant normal towards the camera's vertical
    vec2 s0 = s_cpu + lin_s0.xy - rest * inversesqrt(max(EARTH_R2 - dot(rest, rest), 1.0));
    float h = lin_s0.z;
    // The value at s0 and forward differences over h: three lookups. Central differences
    // (five) cost 45 more of a vertex shader's 365 instructions on Vivante per pair; the mean of
    // four at s0 +- h instead of the value moved the rows below the horizon by up to 35 of 255
    // (the lookups bend there: the sky map's horizon clamp). The forward difference is the
    // derivative at s0 + h/2; the pixel's ds has mean 0, so its mean stays f(s0).
    lin = lookups(v, s0);
    lin_dx = (lookups(v, s0 + vec2(h, 0.0)) - lin) / h;
    lin_dy = (lookups(v, s0 + vec2(0.0, h)) - lin) / h;
    // Ross BRDF (Bruneton eq. 15) = p(zeta_h) F(v.h) / (4 cos_v cos^4 theta_h (1 + L(v) + L(l))):
    // the slope density p is the pixel's (ocean.frag); the rest varies slowly and is evaluated
    // here at the vertex's mean normal, the shadowing with the sea's whole slope variance.
    vec3 l = sun_dir_world;
    vec3 n = facing_normal(v, s0);
    vec3 hv = normalize(v + l);
    vec3 tx = normalize(vec3(n.z, 0.0, -n.x));
    vec3 ty = cross(n, tx);
    vec2 vt = vec2(dot(v, tx), dot(v, ty));
    float wx = dot(vt, vt) > 1e-6 ? vt.x * vt.x / dot(vt, vt) : 0.5;   // eq. 25's weights
    float cos_v = max(dot(v, n), 0.01), cos_l = dot(l, n);
    float hn = max(dot(hv, n), 0.05);
    float var_v = mix(total_var.y + svar.y, total_var.x + svar.x, wx);
    float c5 = 1.0 - clamp(dot(v, hv), 0.0, 1.0);
    float fs = 0.02 + 0.98 * c5 * c5 * c5 * c5 * c5;   // Schlick, as in eq. 15
    vec2 lam = ross_lambda2(vec2(cos_v, cos_l), var_v);
    float shadow = 1.0 + lam.x + lam.y;
    float ross = cos_l > 0.0 ? fs / (8.0 * PI * hn * hn * hn * hn * cos_v * shadow) : 0.0;
    sun = vec4(-hv.xy / max(hv.z, 0.05) - s0, ross, wx);
    // eq. 27's footprint in texels is 2 sigma size du/dzeta, du/dzeta = h / (1 + r_z) (h the
    // horizon's radius on the map, common.glsl SKY_HORIZON)
    vec3 r = reflect(-v, n);
    // aerial perspective from the sky model (sky.h sky_haze): the path of length |p| to the
    // camera has air mass |p| (1 - e^{-h/H}) / h through the exponential atmosphere,
    // transmittance e^{-tau m} per channel, and scatters in (1 - T) times the horizon sky of
    // its azimuth, the view's (high quality: the phase weights here, each channel's T from
    // green's per pixel in ocean.frag; low quality gives the sea green's T in every channel,
    // ocean.vert: with green's for the in-scattered light too the sea 10 km out was 7 % off
    // high's in the 8-row means, test_quality_match, with blue's 7 % at 1 km)
    vec3 t = exp(-haze_tau * (length(p) * haze_frame.x));
    // log2 of the pixel footprint along the view at rest point p on the sea plane, m: (d^2 +
    // a^2) / a times the pixel's angle at horizontal distance d from a camera at altitude a,
    // as the renderer takes it per row (renderer.c row_footprint); ocean.frag fades each
    // pattern by it where the renderer stops fetching it, and matches its run's level to it.
    geo = vec3(log2(dot(rest, rest) + lod_frame.x) + lod_frame.y,
               log2((2.0 * SKY_HORIZON) * sky_map_size / (1.0 + max(r.z, 0.0))), t.g);
    float cg = dot(p.xy / max(length(p.xy), 1e-6), sun_dir_world.xy);
#ifdef QUALITY_HIGH
    fog = vec3(haze_phases(cg, haze_frame.y), 0.0);
#else
    fog = horizon_sky(cg, haze_frame.y, haze_ray, haze_mie) * (1.0 - t);
#endif
}
