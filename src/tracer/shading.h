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
    int ncomp, ncomp_nonspecular; /* the BSDF's components, and its non-specular ones */
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

/* pbrt-v2's UniformSampleOneLight (one light chosen uniformly, its
 * EstimateDirect times the light count) split into its two strategies, whose
 * expectations are kept light by light:
 * - the light strategy: pair 0 of the vertex's block chooses the light with
 *   its first value and, rescaled within the choice, gives the light's
 *   sample with its second (each light receives a stratified subset of the
 *   pixel's samples); pair 1's first value is the light's component
 *   (ShapeSet). Weighted by the power heuristic against the non-specular
 *   BSDF pdf, times the light count, as EstimateDirect's light sample.
 * - the BSDF strategy: one BSDF sample serves every light -- whichever light
 *   the ray finds first (or every infinite light, when it leaves the scene)
 *   counts with EstimateDirect's weight against that light's own pdf and no
 *   light-count factor. Per light this is EstimateDirect's BSDF term, the
 *   same expectation, whatever the BSDF's sampling density (errata
 *   included), as long as the sample is drawn as EstimateDirect draws it
 *   (non-specular components).
 * mt__bsdf_strategy draws it from pair k and traces its own ray; the path
 * integrator uses its continuation instead where the BSDF has no specular
 * component (the two distributions are then the same), with
 * mt__mis_emission at the continuation's first hit. */
mt_rgb mt__light_strategy_one(mt__thread_ctx *tc, const mt__vertex *v, int vertex);
/* For measurements (mt_scene.measure_chosen_bsdf): pbrt-v2's own
 * combination, EstimateDirect for the chosen light with a BSDF sample of its
 * own (pair 3) that counts only when it finds that light, times the light
 * count. */
mt_rgb mt__one_light_chosen_bsdf(mt__thread_ctx *tc, const mt__vertex *v, int vertex);
mt_rgb mt__bsdf_strategy(mt__thread_ctx *tc, const mt__vertex *v, int vertex, unsigned k);
/* The radiance of the light found along a BSDF-sampled ray (hit NULL: the
 * ray left the scene), MIS-weighted (power heuristic) between the BSDF
 * sample's pdf and that light's pdf in the ray's direction. */
mt_rgb mt__mis_emission(const mt_scene *s, const mt__vertex *v, mt_real bsdf_pdf, const mt_ray *ray,
                        const mt_hit *hit);
/* BSDF::Sample_f with the two values of one pair: the component choice
 * from the first value, which, rescaled within the choice, is also the
 * direction's first coordinate. */
mt_bsdf_sample mt__sample_bsdf_pair(const mt__vertex *v, const mt_real u[2], unsigned flags);
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
