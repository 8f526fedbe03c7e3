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
    mt_real l2, m;
    if (!mt_v3_is_finite(*v)) return 0;
    m = mt_max(mt_fabs(v->x), mt_max(mt_fabs(v->y), mt_fabs(v->z)));
    if (m == 0) return 0;
    if (m > (mt_real)1e15 || m < (mt_real)1e-15) {
        /* the square would over- or underflow: rescale by the largest component */
        *v = mt_v3(v->x / m, v->y / m, v->z / m);
    }
    l2 = mt_v3_len2(*v);
    if (l2 > (mt_real)0.999 && l2 < (mt_real)1.001) return 1;
    *v = mt_v3_scale(*v, 1 / mt_sqrt(l2));
    return 1;
}

#endif
