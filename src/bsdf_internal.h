/* Internal: BSDF access for the mix material (pbrt-v2's friend class). */
#ifndef MT_BSDF_INTERNAL_H
#define MT_BSDF_INTERNAL_H

#include "materia/bsdf.h"

/* mt_bsdf_create without the reset of err, for a material's GetBSDF, which
 * has reset it on entry (once per shading point). */
mt_bsdf *mt__bsdf_create(mt_arena *a, mt_mode mode, const mt_diffgeom *dgs, mt_vec3 ng,
                         mt_real eta, mt_error *err);

/* mt_bsdf_add without the reset of err, for the materials (their GetBSDF
 * has reset it): the same treatment of a NULL BSDF or BxDF. */
mt_status mt__bsdf_add(mt_bsdf *b, mt_bxdf *bxdf, mt_error *err);

/* Replaces component i (0 <= i < count) by x. */
void mt__bsdf_set_component(mt_bsdf *b, int i, mt_bxdf *x);

/* wo admitted (mt_bsdf_f's rules) and in the shading frame, once for the
 * several queries a path vertex makes with it. */
typedef struct mt__bsdf_wo {
    mt_vec3 w, local; /* admitted world direction, and local */
    int ok;           /* admitted */
} mt__bsdf_wo;
void mt__bsdf_wo_init(const mt_bsdf *b, mt_vec3 wo, mt__bsdf_wo *o);
/* mt_bsdf_sample_f with wo prepared by mt__bsdf_wo_init. */
mt_bsdf_sample mt__bsdf_sample_f_wo(const mt_bsdf *b, const mt__bsdf_wo *wo, mt_real uc, mt_real u1,
                                    mt_real u2, unsigned flags);

/* f and pdf of one pair of world directions, as mt_bsdf_f and mt_bsdf_pdf
 * give them, with the directions admitted and taken to the shading frame
 * once: mt__bsdf_f_pair fills pair, mt__bsdf_pdf_pair reuses it (direct
 * lighting asks for the pdf only when the light is unoccluded). */
typedef struct mt__bsdf_pair {
    mt_vec3 wo, wi; /* local */
    int ok;         /* both directions admitted */
} mt__bsdf_pair;
mt_rgb mt__bsdf_f_pair(const mt_bsdf *b, const mt__bsdf_wo *wo, mt_vec3 wi, unsigned flags, mt__bsdf_pair *pair);
mt_real mt__bsdf_pdf_pair(const mt_bsdf *b, const mt__bsdf_pair *pair, unsigned flags);

#endif
