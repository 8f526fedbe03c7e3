/*
 * ScaledBxDF (pbrt-v2 reflection.h/.cpp): a BxDF times a spectrum, used by the
 * mix material. pbrt-v2 gives it no Pdf(), so the base class's cosine pdf
 * answers for it (erratum scaled-pdf); corrected mode asks the wrapped BxDF.
 */
#include "bxdfs/kinds.h"

typedef struct scaled {
    mt_bxdf base;
    const mt_bxdf *inner;
    mt_rgb s;
} scaled;

static mt_rgb scaled_f(const mt_bxdf *b, mt_vec3 wo, mt_vec3 wi)
{
    const scaled *sc = (const scaled *)b;
    return mt_rgb_mul(sc->s, sc->inner->ops->f(sc->inner, wo, wi));
}

static mt_rgb scaled_sample_f(const mt_bxdf *b, mt_vec3 wo, mt_vec3 *wi, mt_real u1, mt_real u2,
                              mt_real *pdf)
{
    const scaled *sc = (const scaled *)b;
    return mt_rgb_mul(sc->s, sc->inner->ops->sample_f(sc->inner, wo, wi, u1, u2, pdf));
}

static mt_real scaled_pdf(const mt_bxdf *b, mt_vec3 wo, mt_vec3 wi)
{
    const scaled *sc = (const scaled *)b;
    if (b->mode & MT_FIX_SCALED_PDF) return sc->inner->ops->pdf(sc->inner, wo, wi);
    return mt_bxdf_default_pdf(b, wo, wi);
}

static mt_rgb scaled_rho_hd(const mt_bxdf *b, mt_vec3 wo, int n, const mt_real *samples)
{
    const scaled *sc = (const scaled *)b;
    return mt_rgb_mul(sc->s, sc->inner->ops->rho_hd(sc->inner, wo, n, samples));
}

static mt_rgb scaled_rho_hh(const mt_bxdf *b, int n, const mt_real *s1, const mt_real *s2)
{
    const scaled *sc = (const scaled *)b;
    return mt_rgb_mul(sc->s, sc->inner->ops->rho_hh(sc->inner, n, s1, s2));
}

static const mt_bxdf_ops scaled_ops = {
    .name = "scaled",
    .f = scaled_f,
    .sample_f = scaled_sample_f,
    .pdf = scaled_pdf,
    .rho_hd = scaled_rho_hd,
    .rho_hh = scaled_rho_hh,
};

mt_bxdf *mt_scaled_bxdf_create(mt_arena *a, mt_mode mode, mt_bxdf *bxdf, mt_rgb scale,
                               mt_error *err)
{
    scaled *sc;
    mt_error_clear(err);
    if (!bxdf) return NULL; /* a failed creator: err already says why */
    if (!mt__check_rgb(scale, "scale", "scaled", err)) return NULL;
    sc = mt__bxdf_alloc(a, sizeof *sc, &scaled_ops, bxdf->type, mode, err);
    if (!sc) return NULL;
    sc->inner = bxdf;
    sc->s = scale;
    return &sc->base;
}
