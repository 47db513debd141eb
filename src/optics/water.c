/* water.c - the water body's colour from its inherent optical properties (water.h). */
#include "optics/water.h"

#include <math.h>

static const double lambda_nm[3] = { 680.0, 550.0, 440.0 };
static const double a_water[3] = { 0.465, 0.0565, 0.00635 };     /* Pope & Fry 1997, 1 / m */
/* Bricaud et al. 1995: a_ph = A C^E at 676 (the red peak, for 680), 555, 440 nm */
static const double a_ph_a[3] = { 0.0206, 0.0047, 0.0654 };
static const double a_ph_e[3] = { 0.80, 0.71, 0.728 };

/* Channel k's absorption a, scattering b and backscattering b_b, 1 / m (water.h). */
static void iops(double c, int k, double *a, double *b, double *b_b)
{
    double a_ph440 = a_ph_a[2] * pow(c, a_ph_e[2]);
    double a_g440 = 0.2 * (a_water[2] + a_ph440);
    double l = lambda_nm[k];
    *a = a_water[k] + a_ph_a[k] * pow(c, a_ph_e[k]) + a_g440 * exp(-0.014 * (l - 440.0));
    double b_w = 0.00288 * pow(l / 500.0, -4.32), b_p = 0.3 * pow(c, 0.62) * (550.0 / l);
    *b = b_w + b_p;
    *b_b = 0.5 * b_w + 0.01 * b_p;
}

void water_reflectance(double c, double r[3])
{
    for (int k = 0; k < 3; k++) {
        double a, b, b_b;
        iops(c, k, &a, &b, &b_b);
        r[k] = 0.33 * b_b / (a + b_b);
    }
}

void water_attenuation(double c, double out[3])
{
    for (int k = 0; k < 3; k++) {
        double a, b, b_b;
        iops(c, k, &a, &b, &b_b);
        out[k] = a + b;
    }
}

void water_albedo(double c, float albedo[3])
{
    double r[3];
    water_reflectance(c, r);
    for (int k = 0; k < 3; k++)
        albedo[k] = (float)(0.98 / 1.78 * r[k]);
}
