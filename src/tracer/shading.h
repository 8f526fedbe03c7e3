/*
 * Internal: what the integrators share -- a shaded path vertex (pbrt-v2's
 * Intersection::GetBSDF and Le) and direct lighting (core/integrator.cpp
 * EstimateDirect, UniformSampleOneLight, UniformSampleAllLights).
 */
#ifndef MT_TRACER_SHADING_H
#define MT_TRACER_SHADING_H

#include "tracer/scene.h"
#include "bsdf_internal.h"

typedef struct mt__vertex {
    mt_surface sf;             /* the intersection (geometric dg, error bounds) */
    mt_diffgeom dgs;           /* storage for the shading geometry, when it is not sf.dg */
    const mt_diffgeom *sh;     /* the shape's shading geometry: &sf.dg or &dgs */
    mt_bsdf *bsdf;
    const mt__prim_info *info;
    mt_vec3 p, n, wo;          /* pbrt-v2's bsdf->dgShading.p, .nn and -ray.d */
    mt__bsdf_wo bwo;           /* wo admitted and in the BSDF's frame, for its queries */
} mt__vertex;

/* The vertex at hit of ray; rd (may be NULL) gives the ray differentials for
 * texture filtering. 0 when the material cannot build a BSDF there (counted in
 * tc->shading_failures). */
int mt__vertex_shade(mt__thread_ctx *tc, const mt_hit *hit, const mt_ray *ray,
                     const mt_raydiff *rd, mt__vertex *v);

/* Radiance the vertex emits towards wo (its area light, one-sided). */
mt_rgb mt__vertex_le(const mt_scene *s, const mt__vertex *v);

/* (first, pair[0], pair[1]): a component choice and a 2D sample as the
 * light and BSDF sampling routines take them. */
static inline void mt__u3(mt_real out[3], mt_real first, const mt_real pair[2])
{
    out[0] = first;
    out[1] = pair[0];
    out[2] = pair[1];
}

/* EstimateDirect: light sampling and BSDF sampling of one light, combined with
 * the power heuristic; lu = (ucomp, u1, u2) for the light, bu for the BSDF;
 * non-specular BSDF components only. */
mt_rgb mt__estimate_direct(mt__thread_ctx *tc, const mt__light *light, const mt__vertex *v,
                           const mt_real lu[3], const mt_real bu[3]);

/* UniformSampleOneLight at path vertex `vertex` (dimension pairs 0, 1, 2, 3
 * of its block: light choice and component, light position, BSDF component,
 * BSDF direction). comp receives pair 2, whose second value is the path
 * integrator's component choice. */
mt_rgb mt__sample_one_light(mt__thread_ctx *tc, const mt__vertex *v, int vertex, mt_real comp[2]);
/* UniformSampleAllLights: every light with its sample count (pairs 8 + 3j,
 * 9 + 3j, 10 + 3j for light j, as arrays). */
mt_rgb mt__sample_all_lights(mt__thread_ctx *tc, const mt__vertex *v, int vertex);

/* The ray differentials of a specular bounce (pbrt-v2 SpecularReflect,
 * SpecularTransmit): rd the incoming ray, dg the intersection (its dpdx,
 * dpdy), dgs the BSDF's shading geometry (dndu, dndv, and the surface's
 * dudx...), p and n its point and normal, wo = -rd's direction, wi the
 * specular direction, eta the BSDF's; into next's rx/ry (has_differentials 0
 * where they are not finite). */
void mt__specular_differentials(const mt_raydiff *rd, const mt_diffgeom *dg, const mt_diffgeom *dgs,
                                mt_vec3 p, mt_vec3 n, mt_vec3 wo, mt_vec3 wi, int transmit,
                                mt_real eta, mt_raydiff *next);

#endif
