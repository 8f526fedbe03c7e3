/*
 * materia/spectrum.h -- sampled spectra to RGB, as pbrt-v2's RGB build does
 * it (spectrum.h/.cpp): a sampled spectrum is averaged over pbrt-v2's
 * wavelength segments against its CIE 1931 tables to give XYZ, and XYZ goes
 * to RGB with its XYZToRGB matrix. SPD files are the two-column
 * wavelength/value text format of pbrt-v2's spds/ directory.
 */
#ifndef MATERIA_SPECTRUM_H
#define MATERIA_SPECTRUM_H

#include "materia/error.h"
#include "materia/rgb.h"

/* pbrt-v2 RGBSpectrum::FromSampled: lambda in nm (any order; sorted here). */
MT_API mt_rgb mt_spectrum_from_sampled(const double *lambda, const double *values, int n);
MT_API mt_rgb mt_xyz_to_rgb(const double xyz[3]);
MT_API void mt_rgb_to_xyz(mt_rgb rgb, double xyz[3]);
/* pbrt-v2 ParamSet::AddBlackbodySpectrum: scale times the normalized
 * blackbody emission at temperature kelvin, as RGB. */
MT_API mt_rgb mt_blackbody_rgb(double kelvin, double scale);

/* Reads an SPD file: pairs of (wavelength nm, value); '#' starts a comment.
 * *lambda and *values are malloc'ed (free them with free()). Errors name the
 * file and line. */
MT_API mt_status mt_spd_read(const char *path, double **lambda, double **values, int *n,
                             mt_error *err);

#endif
