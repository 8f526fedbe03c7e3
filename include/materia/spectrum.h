/*
 * materia/spectrum.h -- sampled spectra to RGB, as pbrt-v2's RGB build does
 * it (spectrum.h RGBSpectrum::FromSampled): the piecewise-linear spectrum is
 * interpolated at each 1 nm wavelength of pbrt-v2's CIE 1931 tables (360-830
 * nm, constant beyond the first and last samples), summed against xbar,
 * ybar, zbar and divided by the sum of ybar to give XYZ, and XYZ goes to RGB
 * with its XYZToRGB matrix. SPD files are the two-column wavelength/value
 * text format of pbrt-v2's spds/ directory.
 *
 * Thread safety: every function may be called from any thread (mt_spd_read
 * writes only to what it allocates).
 */
#ifndef MATERIA_SPECTRUM_H
#define MATERIA_SPECTRUM_H

#include "materia/error.h"
#include "materia/rgb.h"

#ifdef __cplusplus
extern "C" {
#endif

/* pbrt-v2 RGBSpectrum::FromSampled: lambda in nm, in any order (pbrt-v2
 * sorts the (lambda, value) pairs). Black when n <= 0 or when a number is
 * not finite or beyond float's range. A repeated wavelength makes a step, as
 * in pbrt-v2. */
MT_API mt_rgb mt_spectrum_from_sampled(const double *lambda, const double *values, int n);
/* pbrt-v2's XYZToRGB and RGBToXYZ matrices. */
MT_API mt_rgb mt_xyz_to_rgb(const double xyz[3]);
MT_API void mt_rgb_to_xyz(mt_rgb rgb, double xyz[3]);
/* pbrt-v2 ParamSet::AddBlackbodySpectrum: scale times the blackbody
 * emission at temperature kelvin normalized to 1 at 555 nm, as RGB. Black
 * for kelvin <= 0 (as pbrt-v2) and where the normalized emission overflows
 * (below about 100 K; the parameter layer rejects those). */
MT_API mt_rgb mt_blackbody_rgb(double kelvin, double scale);

/* Reads an SPD file: pairs of (wavelength nm, value); '#' starts a comment.
 * *lambda and *values (n values each) are allocated with malloc: the caller
 * frees them with free(); on failure both are NULL and *n is 0. Errors
 * (MT_ERR_IO, MT_ERR_PARSE, MT_ERR_NOMEM) name the file and line. */
MT_API mt_status mt_spd_read(const char *path, double **lambda, double **values, int *n,
                             mt_error *err);

#ifdef __cplusplus
}
#endif

#endif
