/*
 * materia/bsdf.h -- the BSDF: up to eight BxDFs in a shading frame.
 *
 * pbrt-v2's BSDF class. The frame is n = the shading normal, s = dpdu
 * normalized, t = n x s. f() follows the light-leak rule: with respect to the
 * *geometric* normal, directions on the same side select only the reflection
 * components, opposite sides only the transmission ones. sample_f() chooses a
 * component from u_component as pbrt-v2 does, averages the pdf over the
 * matching components and (for a non-specular choice) sums f over the
 * matching non-specular ones.
 *
 * All directions are in world space and point away from the surface.
 *
 * Thread safety: a BSDF is built (mt_bsdf_create, mt_bsdf_add) by one
 * thread in its arena; once built it is read-only, and every query below
 * may be made on it from any number of threads at once, while its arena is
 * not reset.
 */
#ifndef MATERIA_BSDF_H
#define MATERIA_BSDF_H

#include "materia/bxdf.h"
#include "materia/diffgeom.h"
#include "materia/frame.h"
#include "materia/rng.h"

#ifdef __cplusplus
extern "C" {
#endif

#define MT_MAX_BXDFS 8

typedef struct mt_bsdf mt_bsdf;

/* A BSDF in the arena, with no component yet, for the shading geometry dgs
 * (copied) and geometric normal ng, with relative index eta (pbrt-v2's
 * BSDF::eta, 1 for opaque surfaces). It lives until the arena is reset or
 * destroyed. NULL (err filled) when the arena is exhausted, or the normals
 * or eta are not finite or the normals zero. */
MT_API mt_bsdf *mt_bsdf_create(mt_arena *a, mt_mode mode, const mt_diffgeom *dgs, mt_vec3 ng,
                               mt_real eta, mt_error *err);

/* Adds a component (the BSDF keeps the pointer: bxdf must live in the same
 * arena, or longer); a ninth is MT_ERR_LIMIT. The one exception to error.h's
 * reset: given a NULL b or bxdf -- what a failed creator returns -- it
 * returns the status already in err and leaves err as it is, so that
 * creators can be passed straight in:
 *   mt_bsdf_add(b, mt_lambertian_create(arena, mode, kd, &err), &err)
 * (MT_ERR_INVALID when err holds no failure). */
MT_API mt_status mt_bsdf_add(mt_bsdf *b, mt_bxdf *bxdf, mt_error *err);

/* The components matching flags (pbrt-v2's NumComponents), all of them, and
 * the i-th (0 <= i < mt_bsdf_count; borrowed, in the arena). */
MT_API int mt_bsdf_num_components(const mt_bsdf *b, unsigned flags);
MT_API int mt_bsdf_count(const mt_bsdf *b);
MT_API mt_bxdf *mt_bsdf_component(const mt_bsdf *b, int i);
/* What the BSDF was created with: eta, mode, the shading geometry (borrowed),
 * the geometric normal; its orthonormal frame, and the change of frame
 * between world directions and the local ones the BxDFs see. */
MT_API mt_real mt_bsdf_eta(const mt_bsdf *b);
MT_API mt_mode mt_bsdf_mode(const mt_bsdf *b);
MT_API const mt_diffgeom *mt_bsdf_shading(const mt_bsdf *b);
MT_API mt_vec3 mt_bsdf_ng(const mt_bsdf *b);
MT_API mt_frame mt_bsdf_frame(const mt_bsdf *b);
MT_API mt_vec3 mt_bsdf_world_to_local(const mt_bsdf *b, mt_vec3 v);
MT_API mt_vec3 mt_bsdf_local_to_world(const mt_bsdf *b, mt_vec3 v);

/* pbrt-v2's BSDF::f: the sum over the components matching flags, with the
 * light-leak rule above; black for directions that are not finite or zero.
 * Finite for finite input. */
MT_API mt_rgb mt_bsdf_f(const mt_bsdf *b, mt_vec3 wo, mt_vec3 wi, unsigned flags);

typedef struct mt_bsdf_sample {
    mt_vec3 wi;    /* zero when sampling failed */
    mt_rgb f;
    mt_real pdf;   /* 0 when sampling failed */
    unsigned type; /* the sampled component's flags, 0 when sampling failed */
} mt_bsdf_sample;

/* pbrt-v2's BSDF::Sample_f from three uniform numbers in [0, 1): the
 * component chosen by u_component, a direction from (u1, u2), and f and pdf
 * as described above; the fields say "failed" as documented in the struct.
 * mt_bsdf_pdf: pbrt-v2's BSDF::Pdf, the average over the matching
 * non-specular components. */
MT_API mt_bsdf_sample mt_bsdf_sample_f(const mt_bsdf *b, mt_vec3 wo, mt_real u_component,
                                       mt_real u1, mt_real u2, unsigned flags);
MT_API mt_real mt_bsdf_pdf(const mt_bsdf *b, mt_vec3 wo, mt_vec3 wi, unsigned flags);

/* pbrt-v2 BSDF::rho: Monte Carlo reflectance from sqrt_samples^2 jittered
 * stratified samples (pbrt-v2 default 6) drawn from rng. In pbrt-v2 mode wo is
 * passed to the BxDFs without conversion to the local frame, as pbrt-v2 does. */
MT_API mt_rgb mt_bsdf_rho_hd(const mt_bsdf *b, mt_vec3 wo, mt_rng *rng, unsigned flags,
                             int sqrt_samples);
MT_API mt_rgb mt_bsdf_rho_hh(const mt_bsdf *b, mt_rng *rng, unsigned flags, int sqrt_samples);

#ifdef __cplusplus
}
#endif

#endif
