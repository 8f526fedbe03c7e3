/*
 * Torrance-Sparrow microfacet reflection (pbrt-v2 reflection.h/.cpp
 * Microfacet): f = R D(wh) G(wo, wi, wh) F(wi.wh) / (4 cos theta_o cos theta_i)
 * with the V-cavity shadowing term G.
 */
#include "bxdfs/kinds.h"

typedef struct microfacet {
    mt_bxdf base;
    mt_rgb R;
    mt_fresnel fresnel;
    mt_distribution dist;
} microfacet;

/* The V-cavity G (Torrance and Sparrow 1967), given |wo.wh|. When it is 0
 * pbrt-v2 divides by zero and its min() then yields 1; that value is
 * returned directly. */
static mt_real vcavity_g(mt_vec3 wo, mt_vec3 wi, mt_vec3 wh, mt_real wodotwh)
{
    mt_real ndotwh = mt_abs_cos_theta(wh), ndotwo = mt_abs_cos_theta(wo),
            ndotwi = mt_abs_cos_theta(wi);
    if (wodotwh == 0) return 1;
    return mt_min(1, mt_min((2 * ndotwh * ndotwo / wodotwh), (2 * ndotwh * ndotwi / wodotwh)));
}

static mt_rgb microfacet_f(const mt_bxdf *b, mt_vec3 wo, mt_vec3 wi)
{
    const microfacet *m = (const microfacet *)b;
    mt_real costhetao = mt_abs_cos_theta(wo), costhetai = mt_abs_cos_theta(wi), costhetah, wodotwh;
    mt_vec3 wh;
    mt_rgb F;
    if (costhetai == 0 || costhetao == 0) return mt_rgb_black();
    if (mt_v3_is_zero(mt_v3_add(wi, wo))) return mt_rgb_black();
    /* Dot(wi, wh) and AbsDot(wo, wh) (see mt__half_cosines) */
    costhetah = mt__half_cosines(wo, wi, &wh, &wodotwh);
    /* pbrt-v2 takes Dot(wi, wh), never negative for wh = normalize(wo + wi);
     * corrected mode turns wh to +z first, so a dielectric seen from below
     * uses its inside index (erratum microfacet-fresnel-cosine). */
    if ((b->mode & MT_FIX_MICROFACET_FRESNEL) && wh.z < 0) costhetah = -costhetah;
    F = mt_fresnel_evaluate(&m->fresnel, costhetah);
    /* R * D * G * F / (4 cos cos), multiplied in pbrt-v2's order */
    return mt_rgb_divs(mt_rgb_mul(mt_rgb_scale(mt_rgb_scale(m->R, mt_distribution_d(&m->dist, wh,
                                                                                    b->mode)),
                                               vcavity_g(wo, wi, wh, wodotwh)),
                                  F),
                       4 * costhetai * costhetao);
}

static mt_rgb microfacet_sample_f(const mt_bxdf *b, mt_vec3 wo, mt_vec3 *wi, mt_real u1,
                                  mt_real u2, mt_real *pdf)
{
    const microfacet *m = (const microfacet *)b;
    mt_distribution_sample(&m->dist, wo, u1, u2, wi, pdf, b->mode);
    if (!mt_same_hemisphere(wo, *wi)) {
        /* pbrt-v2 keeps the distribution's pdf (erratum glossy-sample-pdf). */
        if (b->mode & MT_FIX_GLOSSY_SAMPLE_PDF) *pdf = 0;
        return mt_rgb_black();
    }
    return microfacet_f(b, wo, *wi);
}

static mt_real microfacet_pdf(const mt_bxdf *b, mt_vec3 wo, mt_vec3 wi)
{
    if (!mt_same_hemisphere(wo, wi)) return 0;
    return mt_distribution_pdf(&((const microfacet *)b)->dist, wo, wi, b->mode);
}

static const mt_bxdf_ops microfacet_ops = {
    "microfacet", microfacet_f, microfacet_sample_f, microfacet_pdf,
    mt_bxdf_default_rho_hd, mt_bxdf_default_rho_hh};

mt_bxdf *mt_microfacet_create(mt_arena *a, mt_mode mode, mt_rgb R, mt_fresnel fresnel,
                              mt_distribution dist, mt_error *err)
{
    microfacet *m;
    if (!mt__check_rgb(R, "R", "microfacet", err) ||
        !mt__check_fresnel(&fresnel, "microfacet", err) ||
        !mt__check_distribution(&dist, "microfacet", err))
        return NULL;
    m = mt_bxdf_alloc(a, sizeof *m, &microfacet_ops, MT_BSDF_REFLECTION | MT_BSDF_GLOSSY, mode,
                      err);
    if (!m) return NULL;
    m->R = R;
    m->fresnel = fresnel;
    m->dist = dist;
    return &m->base;
}
