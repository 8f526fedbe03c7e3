/* Internal: BSDF access for the mix material (pbrt-v2's friend class). */
#ifndef MT_BSDF_INTERNAL_H
#define MT_BSDF_INTERNAL_H

#include "materia/bsdf.h"

/* Replaces component i (0 <= i < count) by x. */
void mt__bsdf_set_component(mt_bsdf *b, int i, mt_bxdf *x);

/* f and pdf of one pair of world directions, as mt_bsdf_f and mt_bsdf_pdf
 * give them, with the directions admitted and taken to the shading frame
 * once: mt__bsdf_f_pair fills pair, mt__bsdf_pdf_pair reuses it (direct
 * lighting asks for the pdf only when the light is unoccluded). */
typedef struct mt__bsdf_pair {
    mt_vec3 wo, wi; /* local */
    int ok;         /* both directions admitted */
} mt__bsdf_pair;
mt_rgb mt__bsdf_f_pair(const mt_bsdf *b, mt_vec3 wo, mt_vec3 wi, unsigned flags, mt__bsdf_pair *pair);
mt_real mt__bsdf_pdf_pair(const mt_bsdf *b, const mt__bsdf_pair *pair, unsigned flags);

#endif
