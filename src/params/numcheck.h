/* Internal: the range of numbers a scene may give. */
#ifndef MT_PARAMS_NUMCHECK_H
#define MT_PARAMS_NUMCHECK_H

#include <math.h>

/* The most values one parameter may hold (keeps 3 * count within an int). */
#define MT__MAX_VALUES (1 << 28)

/*
 * pbrt-v2 reads every number as a float ((float)atof in pbrtlex.ll): a value
 * that rounds to infinity in float -- at or beyond the midpoint between
 * FLT_MAX and 2^128 -- is infinite in pbrt-v2 and rejected here, in both
 * builds. The comparison avoids converting an out-of-range double to float,
 * which C leaves undefined.
 */
static inline int mt__fits_real(double v)
{
    return isfinite(v) && fabs(v) < 0x1.ffffffp127;
}

#endif
