/*
 * Internal: whether a material's BSDF is the same at every point -- what a
 * renderer may leave out of the shading geometry it hands over.
 */
#ifndef MT_MATERIALS_UNIFORM_H
#define MT_MATERIALS_UNIFORM_H

#include "materia/material.h"

/* 1 when the material reads nothing of the shading geometry but its point,
 * normal and partial derivatives (the frame, and a BSSRDF's point): only
 * constant textures, the bump map included (for a mix, its amount and both
 * of its materials). Its BSDF then does not depend on (u, v) or the screen-space
 * differentials. 0 when it may. */
int mt__material_is_uniform(const mt_material *m);

#endif
