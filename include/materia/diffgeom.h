/*
 * materia/diffgeom.h -- differential geometry at a surface point.
 *
 * The fields of pbrt-v2's DifferentialGeometry that materials, textures and
 * bump mapping read. n is the (unit) normal, dpdu/dpdv/dndu/dndv the partial
 * derivatives of position and normal, and the screen-space differentials
 * (dpdx, dpdy, dudx, ...) are zero when the caller has no ray differentials.
 *
 * Thread safety: a value type; mt_diffgeom_default may be called from any
 * thread.
 */
#ifndef MATERIA_DIFFGEOM_H
#define MATERIA_DIFFGEOM_H

#include "materia/vec.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct mt_diffgeom {
    mt_vec3 p;
    mt_vec3 n;
    mt_vec3 dpdu, dpdv;
    mt_vec3 dndu, dndv;
    mt_real u, v;
    mt_vec3 dpdx, dpdy;
    mt_real dudx, dvdx, dudy, dvdy;
    /* The shape's ReverseOrientation xor its transform's handedness swap
     * (pbrt-v2 Shape::ReverseOrientation ^ TransformSwapsHandedness). */
    int flip;
} mt_diffgeom;

/* The standard shading point of the query protocol: p = 0, n = +z,
 * dpdu = +x, dpdv = +y, (u, v) = (0.5, 0.5), everything else zero. */
MT_API mt_diffgeom mt_diffgeom_default(void);

#ifdef __cplusplus
}
#endif

#endif
