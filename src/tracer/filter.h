/*
 * Internal: pbrt-v2's pixel reconstruction filters (the files in filters/) with their
 * parameters and defaults, evaluated exactly (pbrt-v2 looks values up in a
 * 16x16 table of the filter at cell centres; the difference is below the
 * table's resolution and has no effect on the expected image of a box
 * filter).
 *
 *   box       xwidth 0.5, ywidth 0.5                       1
 *   gaussian  xwidth 2, ywidth 2, alpha 2                  max(0, e^{-a x^2} - e^{-a w^2}) per axis
 *   mitchell  xwidth 2, ywidth 2, B 1/3, C 1/3             Mitchell-Netravali of 2|x|/w per axis
 *   triangle  xwidth 2, ywidth 2                           max(0, w - |x|) per axis
 *   sinc      xwidth 4, ywidth 4, tau 3                    windowed sinc of |x|/w per axis
 */
#ifndef MT_TRACER_FILTER_H
#define MT_TRACER_FILTER_H

#include "materia/params.h"

typedef enum mt__filter_kind {
    MT__FILTER_BOX,
    MT__FILTER_GAUSSIAN,
    MT__FILTER_MITCHELL,
    MT__FILTER_TRIANGLE,
    MT__FILTER_SINC
} mt__filter_kind;

typedef struct mt__filter {
    mt__filter_kind kind;
    mt_real xwidth, ywidth, inv_xwidth, inv_ywidth;
    mt_real alpha, exp_x, exp_y; /* gaussian */
    mt_real B, C;                /* mitchell */
    mt_real tau;                 /* sinc */
} mt__filter;

/* The filter named `name` from its parameters (marked used); MT_ERR_NOT_FOUND
 * for an unknown name, MT_ERR_INVALID for a width that is not positive. */
mt_status mt__filter_create(mt__filter *f, const char *name, const mt_paramset *ps,
                            mt_error *err);

/* The filter's value at offset (x, y) from the sample, |x| <= xwidth,
 * |y| <= ywidth. */
mt_real mt__filter_eval(const mt__filter *f, mt_real x, mt_real y);

#endif
