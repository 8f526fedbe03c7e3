/*
 * BRDFToBTDF (pbrt-v2 reflection.h/.cpp): a BRDF mirrored through the surface,
 * f(wo, wi) = brdf(wo, (wi.x, wi.y, -wi.z)); the type swaps reflection for
 * transmission. The translucent material builds its transmission this way.
 *
 * In corrected mode the mirrored BRDF is always evaluated from the +z side:
 * wo and the mirrored wi lie on one side, and moving both to +z is a
 * symmetry of every pbrt-v2 BRDF except a microfacet lobe whose Fresnel
 * term knows the side (the microfacet-fresnel-cosine correction). Without
 * this, that correction would see the sheet's coat from outside one way and
 * from inside the other, and transmission would stop being reciprocal.
 */
#include "bxdfs/kinds.h"

typedef struct brdf_to_btdf {
    mt_bxdf base;
    const mt_bxdf *brdf;
} brdf_to_btdf;

static mt_vec3 other_hemisphere(mt_vec3 w) { return mt_v3(w.x, w.y, -w.z); }

/* Corrected mode evaluates the BRDF from +z: from below, (wo, mirrored wi)
 * are both mirrored again, which turns the pair into (mz(wo), wi). */
static int from_below(const mt_bxdf *b, mt_vec3 wo)
{
    return (b->mode & MT_FIX_MICROFACET_FRESNEL) && wo.z < 0;
}

static mt_rgb btdf_f(const mt_bxdf *b, mt_vec3 wo, mt_vec3 wi)
{
    const mt_bxdf *r = ((const brdf_to_btdf *)b)->brdf;
    if (from_below(b, wo)) return r->ops->f(r, other_hemisphere(wo), wi);
    return r->ops->f(r, wo, other_hemisphere(wi));
}

static mt_rgb btdf_sample_f(const mt_bxdf *b, mt_vec3 wo, mt_vec3 *wi, mt_real u1, mt_real u2,
                            mt_real *pdf)
{
    const mt_bxdf *r = ((const brdf_to_btdf *)b)->brdf;
    mt_rgb f;
    if (from_below(b, wo)) return r->ops->sample_f(r, other_hemisphere(wo), wi, u1, u2, pdf);
    f = r->ops->sample_f(r, wo, wi, u1, u2, pdf);
    *wi = other_hemisphere(*wi);
    return f;
}

static mt_real btdf_pdf(const mt_bxdf *b, mt_vec3 wo, mt_vec3 wi)
{
    const mt_bxdf *r = ((const brdf_to_btdf *)b)->brdf;
    if (from_below(b, wo)) return r->ops->pdf(r, other_hemisphere(wo), wi);
    return r->ops->pdf(r, wo, other_hemisphere(wi));
}

static mt_rgb btdf_rho_hd(const mt_bxdf *b, mt_vec3 wo, int n, const mt_real *samples)
{
    const mt_bxdf *r = ((const brdf_to_btdf *)b)->brdf;
    return r->ops->rho_hd(r, other_hemisphere(wo), n, samples);
}

static mt_rgb btdf_rho_hh(const mt_bxdf *b, int n, const mt_real *s1, const mt_real *s2)
{
    const mt_bxdf *r = ((const brdf_to_btdf *)b)->brdf;
    return r->ops->rho_hh(r, n, s1, s2);
}

static const mt_bxdf_ops brdf_to_btdf_ops = {
    .name = "brdf_to_btdf",
    .f = btdf_f,
    .sample_f = btdf_sample_f,
    .pdf = btdf_pdf,
    .rho_hd = btdf_rho_hd,
    .rho_hh = btdf_rho_hh,
};

mt_bxdf *mt_brdf_to_btdf_create(mt_arena *a, mt_mode mode, mt_bxdf *brdf, mt_error *err)
{
    brdf_to_btdf *t;
    mt_error_clear(err);
    if (!brdf) return NULL; /* a failed creator: err already says why */
    t = mt_bxdf_alloc(a, sizeof *t, &brdf_to_btdf_ops,
                      brdf->type ^ (MT_BSDF_REFLECTION | MT_BSDF_TRANSMISSION), mode, err);
    if (!t) return NULL;
    t->brdf = brdf;
    return &t->base;
}
