/* Internal: the checked form of mt_blackbody_rgb, for the parameter layer. */
#ifndef MT_PARAMS_SPECTRUM_INTERNAL_H
#define MT_PARAMS_SPECTRUM_INTERNAL_H

#include "materia/error.h"
#include "materia/rgb.h"

/* *out = scale times the normalized blackbody at kelvin (black for kelvin <=
 * 0, as pbrt-v2). MT_ERR_INVALID, *out black, when an argument is not finite
 * or the result overflows (temperatures below about 100 K). */
mt_status mt__blackbody_rgb(double kelvin, double scale, mt_rgb *out);

#endif
