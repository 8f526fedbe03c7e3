/*
 * Sampled spectra to RGB as pbrt-v2's default (RGB) build does it
 * (spectrum.h RGBSpectrum::FromSampled, spectrum.cpp): the piecewise-linear
 * spectrum is evaluated at each 1 nm wavelength of the CIE tables
 * (InterpolateSpectrumSamples, constant beyond the first and last samples),
 * summed against xbar, ybar, zbar, divided by the sum of ybar, and taken to
 * RGB by XYZToRGB. The arithmetic is mt_real in pbrt-v2's order, so the float
 * build reproduces pbrt-v2's float sums.
 */
#include <math.h>
#include "materia/spectrum.h"
#include "params/cie.h"
#include "params/numcheck.h"
#include "params/spectrum_internal.h"

mt_rgb mt_xyz_to_rgb(const double xyz[3])
{
    /* pbrt-v2 spectrum.h XYZToRGB */
    mt_real x = (mt_real)xyz[0], y = (mt_real)xyz[1], z = (mt_real)xyz[2];
    return mt_rgb_make((mt_real)3.240479 * x - (mt_real)1.537150 * y - (mt_real)0.498535 * z,
                       (mt_real)-0.969256 * x + (mt_real)1.875991 * y + (mt_real)0.041556 * z,
                       (mt_real)0.055648 * x - (mt_real)0.204043 * y + (mt_real)1.057311 * z);
}

void mt_rgb_to_xyz(mt_rgb rgb, double xyz[3])
{
    /* pbrt-v2 spectrum.h RGBToXYZ */
    const mt_real *c = rgb.c;
    xyz[0] = (mt_real)0.412453 * c[0] + (mt_real)0.357580 * c[1] + (mt_real)0.180423 * c[2];
    xyz[1] = (mt_real)0.212671 * c[0] + (mt_real)0.715160 * c[1] + (mt_real)0.072169 * c[2];
    xyz[2] = (mt_real)0.019334 * c[0] + (mt_real)0.119193 * c[1] + (mt_real)0.950227 * c[2];
}

/* Sample pairs are ordered as pbrt-v2 sorts them (std::sort of (lambda,
 * value) pairs): by wavelength, then by value. */
static int pair_less(mt_real la, mt_real va, mt_real lb, mt_real vb)
{
    return la < lb || (la == lb && va < vb);
}

/*
 * The value pbrt-v2's InterpolateSpectrumSamples gives at l once the samples
 * are sorted (first and last: the indices of the first and last sorted
 * samples), found without sorting: the first sorted sample when l is at or
 * below it, the last when at or above it, otherwise the segment from the
 * greatest sample below l to the least sample at or above l (its first
 * segment that contains l, which is never one of zero width: a repeated
 * wavelength is a step).
 */
static mt_real interpolate(const double *lambda, const double *v, int n, int first, int last,
                           mt_real l)
{
    int i, lo = -1, hi = -1;
    mt_real t;
    if (l <= (mt_real)lambda[first]) return (mt_real)v[first];
    if (l >= (mt_real)lambda[last]) return (mt_real)v[last];
    for (i = 0; i < n; ++i) {
        mt_real li = (mt_real)lambda[i], vi = (mt_real)v[i];
        if (li < l) {
            if (lo < 0 || pair_less((mt_real)lambda[lo], (mt_real)v[lo], li, vi)) lo = i;
        } else if (hi < 0 || pair_less(li, vi, (mt_real)lambda[hi], (mt_real)v[hi])) {
            hi = i;
        }
    }
    /* pbrt-v2: t = (l - lambda[i]) / (lambda[i+1] - lambda[i]); Lerp(t, v0, v1) */
    t = (l - (mt_real)lambda[lo]) / ((mt_real)lambda[hi] - (mt_real)lambda[lo]);
    return mt_lerp(t, (mt_real)v[lo], (mt_real)v[hi]);
}

mt_rgb mt_spectrum_from_sampled(const double *lambda, const double *values, int n)
{
    mt_real x = 0, y = 0, z = 0, yint = 0;
    double xyz[3];
    int i, first = 0, last = 0;
    if (!lambda || !values || n <= 0) return mt_rgb_black();
    for (i = 0; i < n; ++i) /* outside float's range the input is not a spectrum */
        if (!mt__fits_real(lambda[i]) || !mt__fits_real(values[i])) return mt_rgb_black();
    for (i = 1; i < n; ++i) {
        mt_real li = (mt_real)lambda[i], vi = (mt_real)values[i];
        if (pair_less(li, vi, (mt_real)lambda[first], (mt_real)values[first])) first = i;
        if (pair_less((mt_real)lambda[last], (mt_real)values[last], li, vi)) last = i;
    }
    for (i = 0; i < MT_CIE_SAMPLES; ++i) {
        mt_real val = interpolate(lambda, values, n, first, last,
                                  (mt_real)(MT_CIE_LAMBDA_MIN + i));
        yint += (mt_real)mt__cie_y[i];
        x += val * (mt_real)mt__cie_x[i];
        y += val * (mt_real)mt__cie_y[i];
        z += val * (mt_real)mt__cie_z[i];
    }
    xyz[0] = x / yint;
    xyz[1] = y / yint;
    xyz[2] = z / yint;
    return mt_xyz_to_rgb(xyz);
}

/*
 * pbrt-v2 spectrum.cpp Blackbody: Planck's law normalized to 1 at 555 nm,
 * computed in double and stored as float, C2 = hc/k in nm K. Where the
 * exponentials over- or underflow (very low or very high temperatures) the
 * same ratio is taken in a form that does not.
 */
static double planck_ratio(double wl, double kelvin)
{
    const double c2 = 1.4388e7;
    double a0 = c2 / (555.0 * kelvin), a = c2 / (wl * kelvin);
    double norm = pow(555.0, 5.0) * (exp(a0) - 1.), den = pow(wl, 5.0) * (exp(a) - 1.);
    if (isfinite(norm) && isfinite(den) && den > 0) return norm / den;
    if (a > 700 || a0 > 700) return pow(555.0 / wl, 5.0) * exp(a0 - a);
    return pow(555.0 / wl, 5.0) * (expm1(a0) / expm1(a));
}

mt_status mt__blackbody_rgb(double kelvin, double scale, mt_rgb *out)
{
    double lambda[MT_CIE_SAMPLES], v[MT_CIE_SAMPLES];
    mt_rgb rgb;
    int i;
    *out = mt_rgb_black();
    if (!isfinite(kelvin) || !isfinite(scale)) return MT_ERR_INVALID;
    if (kelvin <= 0) return MT_OK; /* pbrt-v2: a zero spectrum */
    for (i = 0; i < MT_CIE_SAMPLES; ++i) {
        double d;
        lambda[i] = MT_CIE_LAMBDA_MIN + i;
        d = planck_ratio(lambda[i], kelvin);
        /* a sample beyond float is infinite in pbrt-v2 (and its conversion
         * undefined in C): an error in both builds */
        if (!mt__fits_real(d)) return MT_ERR_INVALID;
        v[i] = (mt_real)d;
    }
    /* pbrt-v2 ParamSet::AddBlackbodySpectrum: scale * FromSampled(...) */
    rgb = mt_rgb_scale(mt_spectrum_from_sampled(lambda, v, MT_CIE_SAMPLES), (mt_real)scale);
    /* beyond float, pbrt-v2's values are infinite: an error in both builds */
    for (i = 0; i < 3; ++i)
        if (!mt__fits_real(rgb.c[i])) return MT_ERR_INVALID;
    *out = rgb;
    return MT_OK;
}

mt_rgb mt_blackbody_rgb(double kelvin, double scale)
{
    mt_rgb rgb;
    mt__blackbody_rgb(kelvin, scale, &rgb);
    return rgb;
}
