/* Internal: named media for the subsurface material. */
#ifndef MT_MATERIALS_MEDIA_H
#define MT_MATERIALS_MEDIA_H

#include "materia/material.h"

/* pbrt-v2 GetVolumeScatteringProperties: 1 and the coefficients (mm^-1) when
 * name is one of its measured media, 0 otherwise. */
int mt__medium_lookup(const char *name, mt_rgb *sigma_a, mt_rgb *sigma_prime_s);

/* The i-th medium of the table (its name, and its coefficients), or NULL
 * past the end (docs/REFERENCE.md lists them). */
const char *mt__medium_at(int i, mt_rgb *sigma_a, mt_rgb *sigma_prime_s);

#endif
