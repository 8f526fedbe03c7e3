/*
 * Internal: a renderer's BSSRDF queries. kdsubsurface inverts the dipole's
 * diffuse reflectance at every hit (pbrt-v2's SubsurfaceFromDiffuse: 16
 * bisection steps with two exponentials each, per channel); a thread keeps
 * the last inversion and reuses it while Kd, the mean free path and the
 * index are the same bits (with constant textures, every hit), which gives
 * the same sigma_a and sigma'_s as the inversion itself.
 */
#ifndef MT_MATERIALS_BSSRDF_CACHE_H
#define MT_MATERIALS_BSSRDF_CACHE_H

#include "materia/material.h"

typedef struct mt__bssrdf_cache {
    int valid;
    mt_real key[5]; /* Kd, meanfreepath, index */
    mt_rgb sigma_a, sigma_prime_s;
} mt__bssrdf_cache;

/* mt_material_get_bssrdf with the thread's cache (NULL: none). */
int mt__material_get_bssrdf_cached(const mt_material *m, const mt_diffgeom *dg_shading,
                                   mt__bssrdf_cache *cache, mt_bssrdf *out);

/* mt_subsurface_from_diffuse through the cache (NULL: none). */
void mt__subsurface_from_diffuse_cached(mt__bssrdf_cache *cache, mt_rgb kd, mt_real mfp, mt_real eta,
                                        mt_rgb *sigma_a, mt_rgb *sigma_prime_s);

#endif
