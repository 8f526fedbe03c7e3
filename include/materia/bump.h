/*
 * materia/bump.h -- pbrt-v2's Material::Bump.
 *
 * The displacement d is evaluated at the shading point and at points shifted
 * by du = 0.5 (|dudx| + |dudy|) (0.01 when that is 0) along u, likewise dv;
 * dpdu' = dpdu + (d(u+du) - d) / du * n + d * dndu (likewise v), the shading
 * normal is normalize(dpdu' x dpdv'), negated when the shape's orientation is
 * flipped (dg->flip), and turned to the geometric normal's side.
 *
 * Thread safety: a function of its arguments; the displacement texture is
 * read-only.
 */
#ifndef MATERIA_BUMP_H
#define MATERIA_BUMP_H

#include "materia/texture.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Options for studies of the method; materials use 0. */
#define MT_BUMP_DROP_DNDU 1u /* omit the d * dndu terms (what many renderers do) */

MT_API void mt_bump(const mt_texture *d, const mt_diffgeom *dg_geom, const mt_diffgeom *dg_shading,
                    mt_diffgeom *dg_bump, unsigned options);

#ifdef __cplusplus
}
#endif

#endif
