/* vshade.c - ocean.vert's per-vertex shading on the CPU for gles2-min (vshade.h). Each function
 * mirrors the GLSL of the same name (ocean.vert, common.glsl); test_vshade compares them. */
#include "geometry/vshade.h"

#include <math.h>
#include <string.h>
#include "core/camera.h"
#include "geometry/grid.h"
#include "optics/sky.h"

#define PI_F 3.14159265f

/* GLSL's min and max (undefined for NaN): libm's fminf and fmaxf are calls on x86-64, a
 * fifth of this file's cost per vertex (make bench, callgrind) */
static inline float minf(float a, float b)
{
    return a < b ? a : b;
}

static inline float maxf(float a, float b)
{
    return a > b ? a : b;
}

static inline float dot3(const float *a, const float *b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static inline void normalize3(float *a)
{
    float l = sqrtf(dot3(a, a));
    float s = l > 0.0f ? 1.0f / l : 0.0f;
    a[0] *= s;
    a[1] *= s;
    a[2] *= s;
}

/* The normal of slope s, reflected about the view plane when it faces away from v
 * (Bruneton §3.2; ocean.vert facing_normal). */
static void facing_normal(const float *v, const float *s, float *n)
{
    n[0] = -s[0];
    n[1] = -s[1];
    n[2] = 1.0f;
    float d = minf(dot3(n, v), 0.0f);
    for (int c = 0; c < 3; c++)
        n[c] -= 2.0f * d * v[c];
    normalize3(n);
}

/* ocean.vert lookups: the Fresnel-texture uv of view v bumped by slope s (Hu §5.1; fresnel.h's
 * radius 1 - sqrt(1 - theta / (pi / 2)), theta = asin rho) and the sky-map uv of the reflected
 * ray; n: the facing normal (shade_one reuses the one at s0). */
static void lookups(const struct vshade_frame *f, const float *v, const float *s, float *out,
                    float *n)
{
    facing_normal(v, s, n);
    float fv[2] = { v[0] - n[0], v[1] - n[1] };
    float rho = sqrtf(fv[0] * fv[0] + fv[1] * fv[1]);
    float r = 1.0f - sqrtf(maxf(1.0f - asinf(minf(rho, 1.0f)) / (0.5f * PI_F), 0.0f));
    float k = r / maxf(rho, 1e-6f);
    out[0] = (0.5f + 0.5f * fv[0] * k) * f->fresnel_uv_scale[0];
    out[1] = (0.5f + 0.5f * fv[1] * k) * f->fresnel_uv_scale[1];
    float dn = 2.0f * dot3(n, v), refl[3];
    for (int c = 0; c < 3; c++)
        refl[c] = dn * n[c] - v[c];
    sky_map_uv(refl, out + 2);
}

/* common.glsl ross_lambda2 (Walter et al. 2007's fit of the Gaussian Lambda) at one cosine. */
static float ross_lambda1(float cos_t, float var)
{
    float c = minf(maxf(cos_t, 0.01f), 0.9999f);
    float q = (1.0f - c * c) * (2.0f * var);
    if (q <= 0.0f)
        return 0.0f;
    float a = c / sqrtf(q);
    if (a >= 1.6f)
        return 0.0f;
    return (1.0f - 1.259f * a + 0.396f * a * a) / (3.535f * a + 2.181f * a * a);
}

/* common.glsl haze_phases: the Rayleigh and Mie phase functions at cosine cg, Mie g. */
static void haze_phases(float cg, float g, float ph[2])
{
    float hg = 1.0f + g * g - 2.0f * g * cg;
    ph[0] = 3.0f / (16.0f * PI_F) * (1.0f + cg * cg);
    ph[1] = (1.0f - g * g) / (4.0f * PI_F * hg * sqrtf(hg));
}

/* One vertex: ocean.vert main's terms of the vertex alone. */
static void shade_one(const struct vshade_frame *f, const float *gv, float *o)
{
    const float *p = gv + GRID_A_POS, *rest = gv + GRID_A_REST;
    const float *svar = gv + GRID_A_SVAR;
    float v[3] = { -p[0], -p[1], -p[2] };
    normalize3(v);
    float rr2 = rest[0] * rest[0] + rest[1] * rest[1];
    /* the sphere's own slope at the rest point (ocean.vert) */
    float curv = (float)(1.0 / sqrt(fmax(EARTH_RADIUS_M * EARTH_RADIUS_M - (double)rr2, 1.0)));
    float s0[2] = { gv[GRID_A_SLOPE] + f->lin_s0[0] - rest[0] * curv,
                    gv[GRID_A_SLOPE + 1] + f->lin_s0[1] - rest[1] * curv };
    float h = f->lin_s0[2];
    float sx[2] = { s0[0] + h, s0[1] }, sy[2] = { s0[0], s0[1] + h };
    float ax[4], ay[4], n[3], nd[3];
    lookups(f, v, s0, o + VSHADE_LIN, n);
    lookups(f, v, sx, ax, nd);
    lookups(f, v, sy, ay, nd);
    for (int c = 0; c < 4; c++) {
        o[VSHADE_LIN_DX + c] = (ax[c] - o[VSHADE_LIN + c]) / h;
        o[VSHADE_LIN_DY + c] = (ay[c] - o[VSHADE_LIN + c]) / h;
    }
    /* Ross BRDF (Bruneton eq. 15) but for the slope density: at the vertex's mean normal, the
     * shadowing with the sea's whole slope variance (ocean.vert) */
    const float *l = f->sun_dir;
    float hv[3] = { v[0] + l[0], v[1] + l[1], v[2] + l[2] };   /* n: facing_normal(v, s0) */
    normalize3(hv);
    float tx[3] = { n[2], 0.0f, -n[0] };
    normalize3(tx);
    float ty[3] = { n[1] * tx[2] - n[2] * tx[1], n[2] * tx[0] - n[0] * tx[2],
                    n[0] * tx[1] - n[1] * tx[0] };
    float vtx = dot3(v, tx), vty = dot3(v, ty), vt2 = vtx * vtx + vty * vty;
    float wx = vt2 > 1e-6f ? vtx * vtx / vt2 : 0.5f;      /* eq. 25's weights */
    float cos_v = maxf(dot3(v, n), 0.01f), cos_l = dot3(l, n);
    float hn = maxf(dot3(hv, n), 0.05f);
    float var_v = f->total_var[1] + (f->total_var[0] - f->total_var[1]) * wx +
                  svar[0] * wx + svar[1] * (1.0f - wx);
    float c5 = 1.0f - minf(maxf(dot3(v, hv), 0.0f), 1.0f);
    float fs = 0.02f + 0.98f * c5 * c5 * c5 * c5 * c5;  /* Schlick, as in eq. 15 */
    float shadow = 1.0f + ross_lambda1(cos_v, var_v) + ross_lambda1(cos_l, var_v);
    o[VSHADE_SUN + 0] = -hv[0] / maxf(hv[2], 0.05f) - s0[0];
    o[VSHADE_SUN + 1] = -hv[1] / maxf(hv[2], 0.05f) - s0[1];
    o[VSHADE_SUN + 2] = cos_l > 0.0f ? fs / (8.0f * PI_F * hn * hn * hn * hn * cos_v * shadow)
                                     : 0.0f;
    o[VSHADE_SUN + 3] = wx;
    /* eq. 27's footprint in texels, 2 sigma size du/dzeta, du/dzeta = h / (1 + r_z) (h the
     * horizon's radius on the map, sky.h) */
    float rz = 2.0f * dot3(n, v) * n[2] - v[2];
    float plen = sqrtf(dot3(p, p)), m = plen * f->haze_frame[0];
    float t[3] = { 0.0f, expf(-f->haze_tau[1] * m), 0.0f };   /* green's; the others for fog */
    memcpy(o + VSHADE_POS, p, 3 * sizeof(float));
    o[VSHADE_POS + 3] = log2f(rr2 + f->lod_frame[0]) + f->lod_frame[1];
    o[VSHADE_REST + 0] = rest[0];
    o[VSHADE_REST + 1] = rest[1];
    o[VSHADE_REST + 2] = svar[0];
    o[VSHADE_REST + 3] = svar[1];
    o[VSHADE_GEO + 0] = gv[GRID_A_K];
    o[VSHADE_GEO + 1] = gv[GRID_A_K + 1];
    o[VSHADE_GEO + 2] = log2f(2.0f * SKY_MAP_HORIZON * f->sky_map_size /
                              (1.0f + maxf(rz, 0.0f)));
    o[VSHADE_GEO + 3] = t[1];
    o[VSHADE_FOG + 3] = gv[GRID_A_PAD];   /* the wave mask's amplitude (grid_set_mask) */
    /* aerial perspective (vterms.glsl): (1 - T) times the horizon sky of the view's azimuth */
    float pxy = maxf(sqrtf(p[0] * p[0] + p[1] * p[1]), 1e-6f);
    float cg = (p[0] * f->sun_dir[0] + p[1] * f->sun_dir[1]) / pxy, ph[2];
    haze_phases(cg, f->haze_frame[1], ph);
    if (!f->fog) {   /* high quality: the phase weights (ocean.frag applies each channel's T) */
        o[VSHADE_FOG + 0] = ph[0];
        o[VSHADE_FOG + 1] = ph[1];
        o[VSHADE_FOG + 2] = 0.0f;
        return;
    }
    t[0] = expf(-f->haze_tau[0] * m);
    t[2] = expf(-f->haze_tau[2] * m);
    for (int c = 0; c < 3; c++)
        o[VSHADE_FOG + c] = (f->haze_ray[c] * ph[0] + f->haze_mie[c] * ph[1]) * (1.0f - t[c]);
}

void vshade_fill(const struct vshade_frame *f, const float *grid_verts, int n, float *out)
{
    for (int i = 0; i < n; i++)
        shade_one(f, grid_verts + (size_t)i * GRID_FLOATS, out + (size_t)i * VSHADE_FLOATS);
}
