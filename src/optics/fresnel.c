#include "optics/fresnel.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "tables/quantize.h"

#define SQRT_2PI 2.5066282746310002

double fresnel_exact(double cos_i, double n)
{
    double c = cos_i < 0.0 ? 0.0 : cos_i > 1.0 ? 1.0 : cos_i;
    double g2 = n * n + c * c - 1.0;   /* Hu eq. 2: g^2 = eta^2 + c^2 - 1 */
    if (!(g2 > 0.0))
        return 1.0;   /* total internal reflection (n < 1), or grazing into n = 1 */
    double g = sqrt(g2);
    double a = (g - c) / (g + c);
    double b = (c * (g + c) - 1.0) / (c * (g - c) + 1.0);
    return 0.5 * a * a * (1.0 + b * b);
}

/* 8-point Gauss-Legendre rule on [-1, 1] (nodes +-x, weights w), exact to degree 15. */
static const double gl_x[4] = { 0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                                0.9602898564975363 };
static const double gl_w[4] = { 0.3626837833783620, 0.3137066458778873, 0.2223810344533745,
                                0.1012285362903763 };

/* Slopes beyond 8 standard deviations carry < 1e-15 of the Gaussian's mass. */
#define EFF_U_MAX 8.0

struct eff_result {
    double exact;     /* int q_evn F(v.f) (eq. 23 with q_evn) */
    double schlick;   /* int q_evn (1 - v.f)^5 (eq. 24's integral) */
};

/* The q_evn averages of eq. 23/24 for v = (sin theta_v, 0, cos theta_v) - the isotropic
 * distribution makes phi_v irrelevant. In standard-normal variables u = zeta / sigma the
 * integrand is phi(u_x) phi(u_y) max(v.f, 0) / f_z * F(v.f) / ((1 + Lambda) cos theta_v), with
 * f = (-zeta_x, -zeta_y, 1) / sqrt(1 + |zeta|^2) (eq. 6), so max(v.f, 0) / f_z
 * = max(cos - sin zeta_x, 0): zero past u_x = cot theta_v / sigma, where the u_x integral is cut
 * (Gauss-Legendre panels then only see smooth integrands). Even in u_y: [0, U] doubled. */
static struct eff_result eff_integrate(double c, double sigma, double n)
{
    struct eff_result r;
    double s = sqrt(1.0 - c * c);
    if (!(sigma > 0.0)) {
        r.exact = fresnel_exact(c, n);
        r.schlick = pow(1.0 - c, 5.0);
        return r;
    }
    double ss = s * sigma;
    double cut = ss > 0.0 ? c / ss : EFF_U_MAX;
    double hi = cut < EFF_U_MAX ? cut : EFF_U_MAX, lo = -EFF_U_MAX;
    int px = (int)ceil((hi - lo) / 2.0), py = 4;   /* panels of width <= 2 */
    double hx = (hi - lo) / px, hy = EFF_U_MAX / py;
    double sum_f = 0.0, sum_s = 0.0;
    for (int i = 0; i < px; i++)
        for (int a = 0; a < 8; a++) {
            double xi = a < 4 ? -gl_x[a] : gl_x[a - 4], wxi = gl_w[a & 3];
            double ux = lo + hx * (i + 0.5 + 0.5 * xi);
            double proj = c - ss * ux;   /* max(v.f, 0) / f_z, > 0 inside the cut */
            if (proj <= 0.0)
                continue;
            double wx = 0.5 * hx * wxi * exp(-0.5 * ux * ux) / SQRT_2PI * proj;
            double zx = sigma * ux;
            for (int j = 0; j < py; j++)
                for (int b = 0; b < 8; b++) {
                    double yi = b < 4 ? -gl_x[b] : gl_x[b - 4], wyi = gl_w[b & 3];
                    double uy = hy * (j + 0.5 + 0.5 * yi);
                    double wy = hy * wyi * exp(-0.5 * uy * uy) / SQRT_2PI;   /* 2 x half */
                    double zy = sigma * uy;
                    double vf = proj / sqrt(1.0 + zx * zx + zy * zy);
                    double m = 1.0 - vf, m2 = m * m;
                    sum_f += wx * wy * fresnel_exact(vf, n);
                    sum_s += wx * wy * m2 * m2 * m;
                }
        }
    /* (1 + Lambda(a_v)) cos theta_v, eq. 8-9 with a_v = cos / (sqrt2 sigma sin), written as
     * cos + sigma sin (exp(-a^2) - a sqrt(pi) erfc(a)) / sqrt(2 pi) so grazing views
     * (cos -> 0, Lambda -> inf) stay finite */
    double norm = c;
    if (ss > 0.0) {
        double av = c / (M_SQRT2 * ss);
        norm += ss * (exp(-av * av) - av * sqrt(M_PI) * erfc(av)) / SQRT_2PI;
    }
    r.exact = sum_f / norm;
    r.schlick = sum_s / norm;
    return r;
}

static double clamp01(double x)
{
    return x < 0.0 ? 0.0 : x > 1.0 ? 1.0 : x;
}

static double sigma_of(double sigma2)
{
    return sigma2 > 0.0 ? sqrt(sigma2) : 0.0;
}

double fresnel_effective(double cos_v, double sigma2)
{
    return eff_integrate(clamp01(cos_v), sigma_of(sigma2), SWELL_WATER_IOR).exact;
}

double fresnel_effective_schlick(double cos_v, double sigma2)
{
    double r0 = fresnel_exact(1.0, SWELL_WATER_IOR);
    return r0 + (1.0 - r0) *
           eff_integrate(clamp01(cos_v), sigma_of(sigma2), SWELL_WATER_IOR).schlick;   /* eq. 24 */
}

double fresnel_effective_fit(double cos_v, double sigma2)
{
    double r0 = fresnel_exact(1.0, SWELL_WATER_IOR), sv = sigma_of(sigma2);
    double c = clamp01(cos_v);
    return r0 + (1.0 - r0) * pow(1.0 - c, 5.0 * exp(-2.69 * sv)) /
                             (1.0 + 22.7 * pow(sv, 1.5));   /* eq. 26 */
}

double fresnel_effective_tex(double f, double sigma)
{
    double r0 = fresnel_exact(1.0, SWELL_WATER_IOR), sv = sigma > 0.0 ? sigma : 0.0;
    double s = (f - r0) / (1.0 - r0);
    s = s > 1e-4 ? s : 1e-4;   /* as the shader: no pow of 0 */
    return r0 + (1.0 - r0) * pow(s, exp(-2.69 * sv)) / (1.0 + 22.7 * pow(sv, 1.5));
}

static int check_size(int size, const char *name, struct swell_err *err)
{
    if (size < 2 || size > 1024 || (size & (size - 1)))
        return swell_fail(err, SWELL_E_ARG,
                          "%s table: size %d is not a power of two in [2, 1024]", name, size);
    return 0;
}

static void set_geometry(struct swell_table *t, const char *name, int kind, int size)
{
    memset(t, 0, sizeof *t);
    strncpy(t->name, name, sizeof t->name - 1);
    t->kind = kind;
    t->pattern = -1;
    t->format = FORMAT_RGBA8;
    t->width = t->height = size;
    t->layers = 1;
    t->levels = 1;
}

static uint8_t quantize_unorm(double x)   /* x in [0, 1] -> nearest of 0..255 */
{
    long v = lrint(clamp01(x) * 255.0);
    return (uint8_t)v;
}

int fresnel_hu_table(int size, struct swell_table *t, struct swell_err *err)
{
    int r = check_size(size, "fresnel", err);
    if (r)
        return r;
    set_geometry(t, "fresnel", TABLE_FRESNEL, size);
    if ((r = table_alloc(t, err)))
        return swell_err_context(err, "Hu 2006 Fresnel texture");
    for (int c = 0; c < 3; c++) {
        t->scale[c] = 2.0f;
        t->bias[c] = -1.0f;
    }
    t->scale[3] = 1.0f;
    t->bias[3] = 0.0f;
    for (int j = 0; j < size; j++)
        for (int i = 0; i < size; i++) {
            /* Texel centre p in [-1, 1]^2 -> the bumped view vector at polar angle
             * theta = (pi / 2) r (2 - r), r = min(|p|, 1), in the direction of p (fresnel.h). */
            double px = (2.0 * i + 1.0) / size - 1.0, py = (2.0 * j + 1.0) / size - 1.0;
            double rho = sqrt(px * px + py * py), rc = rho < 1.0 ? rho : 1.0;
            double theta = 0.5 * M_PI * rc * (2.0 - rc), st = sin(theta);
            double vx = rho > 0.0 ? st * px / rho : 0.0, vy = rho > 0.0 ? st * py / rho : 0.0;
            double vz = rho < 1.0 ? cos(theta) : 0.0;
            uint8_t *p = t->data + ((size_t)j * (size_t)size + (size_t)i) * 4;
            p[0] = quantize_unorm(0.5 + 0.5 * vx);
            p[1] = quantize_unorm(0.5 + 0.5 * vy);
            p[2] = quantize_unorm(0.5 + 0.5 * vz);
            /* Hu §5.1: the surface normal is +z in this frame, so V.N = vz */
            p[3] = quantize_unorm(fresnel_exact(vz, SWELL_WATER_IOR));
        }
    return 0;
}

int fresnel_eff_table(int size, struct swell_table *t, struct swell_err *err)
{
    int r = check_size(size, "fresnel_eff", err);
    if (r)
        return r;
    set_geometry(t, "fresnel_eff", TABLE_FRESNEL_EFF, size);
    float *img = malloc((size_t)size * (size_t)size * 4 * sizeof *img);
    if (!img)
        return swell_fail(err, SWELL_E_NOMEM,
                          "fresnel_eff table: cannot allocate %d x %d float texels", size, size);
    double r0 = fresnel_exact(1.0, SWELL_WATER_IOR);
    for (int j = 0; j < size; j++)
        for (int i = 0; i < size; i++) {
            double c = (double)i / (size - 1);
            double sigma = SWELL_FRESNEL_EFF_SIGMA_MAX * j / (size - 1);
            struct eff_result e = eff_integrate(c, sigma, SWELL_WATER_IOR);
            float *p = img + ((size_t)j * (size_t)size + (size_t)i) * 4;
            p[0] = (float)e.exact;
            p[1] = (float)fresnel_effective_fit(c, sigma * sigma);
            p[2] = (float)(r0 + (1.0 - r0) * e.schlick);
            p[3] = 1.0f;
        }
    r = quantize_table(t, img, err);
    free(img);
    if (r)
        return swell_err_context(err, "effective Fresnel table");
    return 0;
}
