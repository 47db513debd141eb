// common.glsl - shared by the ocean and sky shaders. Every value here stays fp16-safe:
// directions are unit vectors, radiances are relative to the extraterrestrial sun (E0 = 1).

#define PI 3.14159265
#define EARTH_R 6.371e6             // camera.h EARTH_RADIUS_M, m
#define EARTH_R2 4.0589641e13       // its square, m^2

// The lattice of random offsets that keeps every pattern from repeating on its tile (detile.h,
// where the construction is; test_detile checks these against it).
#define DETILE_CELLS 2.0            // cells per tile
#define DETILE_N 128.0              // the hash's period, cells
#define DETILE_OFFSETS 8.0          // an offset is (b >> 3, b & 7) / 8 tiles, b the hash byte

// uv's lattice cell c (detile.h), the position f in it, and the atlas coordinate of its hash
// texel (sh: the cell shift of detile_camera_shift; atlas: 1 / the atlas size, the hash rows' v;
// renderer.c atlas_hash_frame). Integer cell arithmetic below DETILE_N + a wrapped uv: exact
// in fp16.
vec2 detile_cell(vec2 uv, vec2 sh, vec4 atlas, out vec2 c, out vec2 f)
{
    vec2 q = uv * DETILE_CELLS;
    c = floor(q);
    f = q - c;
    vec2 hc = c + sh;
    hc -= DETILE_N * floor(hc * (1.0 / DETILE_N));
    return (hc + 0.5) * atlas.xy + vec2(0.0, atlas.z);
}

// The hash bytes of f's triangle's corners (0, 0), the middle vertex, (1, 1) from its cell's
// texel h, and their barycentric weights normalised to sum w^2 = 1.
vec3 detile_bytes(vec4 h, vec2 f)
{
    return vec3(h.r, f.y > f.x ? h.b : h.g, h.a);
}

vec3 detile_weights(vec2 f)
{
    vec3 w = vec3(1.0 - max(f.x, f.y), abs(f.x - f.y), min(f.x, f.y));
    return w * inversesqrt(dot(w, w));
}

// The offsets of three hash bytes t (as fetched: b / 255, b < 64), x and y: 255 t is within
// 0.04 of b in fp16, and b's two 3-bit halves come out exact (test_detile).
void detile_offsets(vec3 t, out vec3 ox, out vec3 oy)
{
    vec3 b = floor(t * 255.0 + 0.5);
    vec3 hi = floor(b * (1.0 / DETILE_OFFSETS));
    ox = hi * (1.0 / DETILE_OFFSETS);
    oy = (b - DETILE_OFFSETS * hi) * (1.0 / DETILE_OFFSETS);
}

// Effective Fresnel, Bruneton 2010 eq. 26, of the bumped view's exact Fresnel f (Hu's texture A)
// for a slope standard deviation sig in the view direction: Schlick's (1 - cos)^5 is
// (f - R0) / (1 - R0), raised to exp(-2.69 sig) as the equation has it (fresnel.c
// fresnel_effective_tex; test_glsl compares the two on the GPU). R0 = fresnel_exact(1, 1.333).
#define FRESNEL_R0 0.020373
// ...split into the terms of sig alone, fresnel_eff_e(sig) = exp(-2.69 sig) and
// fresnel_eff_k(sig) = (1 - R0) / (1 + 22.7 sig^1.5), which low quality evaluates per vertex,
// and the pixel's part.
float fresnel_eff_e(float sig)
{
    return exp(-2.69 * sig);
}

float fresnel_eff_k(float sig)
{
    return (1.0 - FRESNEL_R0) / (1.0 + 22.7 * sig * sqrt(sig));
}

float fresnel_eff_terms(float f, float e, float k)
{
    float s = max((f - FRESNEL_R0) * (1.0 / (1.0 - FRESNEL_R0)), 1e-4);
    return FRESNEL_R0 + k * exp2(e * log2(s));
}

float fresnel_eff(float f, float sig)
{
    return fresnel_eff_terms(f, fresnel_eff_e(sig), fresnel_eff_k(sig));
}

// The sky map's texels hold the radiance's square root (sky.c: RGBA8 over each channel's
// largest, so a dim horizon keeps its steps; half floats over 1): squared, times the
// channel's scale (sky.h sky_texel_radiance).
vec3 sky_decode(vec3 c, vec3 scale)
{
    return c * c * scale;
}

// Stereographic sky-map coordinates of a direction (Bruneton 2010 §5.2): zenith at the centre,
// horizon on the circle of radius SKY_HORIZON of the half-width (sky.h SKY_MAP_HORIZON), the
// ring outside it the radiance below the horizon (Bruneton §6's multiple reflections). A
// direction below the horizon is read at the ring's middle: z raised to SKY_BELOW_Z (sky.h
// SKY_MAP_BELOW_Z), which also keeps the coordinates within the map.
#define SKY_HORIZON 0.9375
#define SKY_BELOW_Z -0.0328
vec2 sky_map_uv(vec3 r)
{
    r.z = max(r.z, SKY_BELOW_Z);
    r = normalize(r);
    return vec2(0.5) + (0.5 * SKY_HORIZON) * r.xy / (1.0 + r.z);
}

// The Rayleigh and Mie phase functions at the cosine cg of the angle to the sun (Mie by
// Henyey-Greenstein g): the weights of sky.h sky_haze's horizon terms.
vec2 haze_phases(float cg, float g)
{
    float hg = 1.0 + g * g - 2.0 * g * cg;
    return vec2(3.0 / (16.0 * PI) * (1.0 + cg * cg), (1.0 - g * g) / (4.0 * PI * hg * sqrt(hg)));
}

// The sky's radiance at the horizon in a direction whose angle to the sun has cosine cg
// (sky.h sky_haze: the phase functions times its horizon terms ray, mie): what a long path
// through the air scatters in (vterms.glsl).
vec3 horizon_sky(float cg, float g, vec3 ray, vec3 mie)
{
    vec2 ph = haze_phases(cg, g);
    return ray * ph.x + mie * ph.y;
}

// erf by Abramowitz & Stegun 7.1.25: |error| <= 2.5e-5 in exact arithmetic, well below what
// mediump (fp16, 11-bit mantissa) resolves; three terms instead of 7.1.26's five.
float erf_as(float x)
{
    float a = abs(x);
    float t = 1.0 / (1.0 + 0.47047 * a);
    float y = 1.0 - t * (0.3480242 + t * (-0.0958798 + t * 0.7478556)) * exp(-a * a);
    return x < 0.0 ? -y : y;
}

// Whitecap coverage, Dupuy eq. 6: the fraction of the patterns' summed foam memory
// ~ N(mu, kvar) below the threshold eps (bake.c; both ocean shaders use it: the fragment where
// it fetches whitecap tables, the vertex where no table is fetched).
float whitecap_cover(float eps, float mu, float kvar)
{
    return clamp(0.5 + 0.5 * erf_as((eps - mu) * inversesqrt(2.0 * max(kvar, 1e-6))), 0.0, 1.0);
}

// ...times a gain g (tables/foam_bias.h: what brings its mean over the sea to the bake's
// whitecap fraction at the pixel's footprint), within the one clamp.
float whitecap_cover_gain(float eps, float mu, float kvar, float g)
{
    return clamp(g * (0.5 + 0.5 * erf_as((eps - mu) * inversesqrt(2.0 * max(kvar, 1e-6)))), 0.0,
                 1.0);
}

// Smith's shadowing/masking of the Ross BRDF for a Gaussian of variance var seen at cos_t:
// Lambda(a) = (e^{-a^2} / (a sqrt(pi)) - erfc(a)) / 2, a = 1 / (sqrt(2) sigma tan theta), by the
// rational fit of Walter et al. 2007 (eq. 27, the same Gaussian/Beckmann Lambda; relative error
// below 0.35 % for the shadowing term 1 / (1 + Lambda)); src/optics/ross.h is the C reference
// (test_glsl).
// Two cosines at once (the view's and the sun's, one variance): vector arithmetic, 20 fewer
// vertex instructions on Mali-400 than two calls.
vec2 ross_lambda2(vec2 cos_t, float var)
{
    vec2 c = clamp(cos_t, 0.01, 0.9999);
    vec2 a = c * inversesqrt((1.0 - c * c) * (2.0 * var));
    vec2 l = (1.0 - 1.259 * a + 0.396 * a * a) / (3.535 * a + 2.181 * a * a);
    return l * (1.0 - step(1.6, a));
}

float ross_lambda(float cos_t, float var)
{
    return ross_lambda2(vec2(cos_t), var).x;
}

// Reinhard on the largest channel, x / (1 + max(x)), of a radiance already scaled by the
// exposure (the renderer folds the exposure into every radiance uniform): the channels keep
// their ratios, so the hue stays (a per-channel x / (1 + x) turned a sunset glitter of
// irradiance (1, 0.39, 0.04) white) and none exceeds 1; one division instead of three. Then
// gamma 2 (sqrt) as the sRGB transfer: within 0.03 of the sRGB curve above 0.1, and sqrt is
// one instruction on GLES2 GPUs where pow() is exp2(log2()) per channel (4x slower on
// llvmpipe, measured). src/optics/tonemap.h is the C reference (test_glsl).
vec3 tone_map(vec3 x)
{
    // Clamped before the division: at the sun disc x can reach fp16's infinity, and inf / inf
    // came out as a dark NaN dot where the sun should be brightest.
    x = clamp(x, vec3(0.0), vec3(1.0e4));
#ifdef SWELL_LINEAR_OUT
    return x;   // the application's own display transform follows (renderer_desc linear_output)
#else
    return sqrt(x * (1.0 / (1.0 + max(max(x.r, x.g), x.b))));
#endif
}
