/* Internal: BSDF access for the mix material (pbrt-v2's friend class). */
#ifndef MT_BSDF_INTERNAL_H
#define MT_BSDF_INTERNAL_H

#include "materia/bsdf.h"

/* Replaces component i (0 <= i < count) by x. */
void mt__bsdf_set_component(mt_bsdf *b, int i, mt_bxdf *x);

#endif
