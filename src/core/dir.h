/*
 * Internal: admission of caller-supplied directions at the public entry
 * points. A NaN, infinite or zero direction is rejected (the caller gets black
 * and pdf 0); one whose length is clearly not 1 is normalized. Unit vectors as
 * callers compute them pass through bit for bit, so pbrt-v2's answers are kept.
 */
#ifndef MT_CORE_DIR_H
#define MT_CORE_DIR_H

#include "materia/vec.h"

static inline int mt__admit_dir(mt_vec3 *v)
{
    mt_real l2;
    if (!mt_v3_is_finite(*v)) return 0;
    l2 = mt_v3_len2(*v);
    if (l2 > (mt_real)0.999 && l2 < (mt_real)1.001) return 1;
    if (mt_v3_is_zero(*v)) return 0;
    if (!(l2 > 0) || !mt_is_finite(l2)) {
        /* the square under- or overflowed: rescale by the largest component */
        mt_real m = mt_max(mt_fabs(v->x), mt_max(mt_fabs(v->y), mt_fabs(v->z)));
        *v = mt_v3(v->x / m, v->y / m, v->z / m);
        l2 = mt_v3_len2(*v);
    }
    *v = mt_v3_scale(*v, 1 / mt_sqrt(l2));
    return 1;
}

#endif
