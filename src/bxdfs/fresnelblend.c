/*
 * FresnelBlend (Ashikhmin and Shirley 2000; pbrt-v2 reflection.h/.cpp): a
 * diffuse substrate under a glossy specular coat, with Schlick's Fresnel.
 */
#include "bxdfs/kinds.h"
#include "materia/sampling.h"

typedef struct fresnelblend {
    mt_bxdf base;
    mt_rgb Rd, Rs;
    mt_distribution dist;
} fresnelblend;

/* x^5 by multiplication: pbrt-v2 calls powf(x, 5), which this matches to a
 * couple of ulps at a fraction of the cost (three of these per evaluation). */
static mt_real pow5(mt_real x)
{
    mt_real x2 = x * x;
    return x2 * x2 * x;
}

static mt_rgb schlick(const fresnelblend *fb, mt_real costheta)
{
    return mt_rgb_add(fb->Rs, mt_rgb_scale(mt_rgb_sub(mt_rgb_gray(1), fb->Rs), pow5(1 - costheta)));
}

static mt_rgb fresnelblend_f(const mt_bxdf *b, mt_vec3 wo, mt_vec3 wi)
{
    const fresnelblend *fb = (const fresnelblend *)b;
    mt_real ci = mt_abs_cos_theta(wi), co = mt_abs_cos_theta(wo), den;
    /* (28/(23 pi)) Rd (1 - Rs) (1 - (1 - cos_i/2)^5) (1 - (1 - cos_o/2)^5),
     * multiplied left to right as in pbrt-v2 */
    /* the two direction factors in a fixed order (larger cosine first), so
     * that swapping wo and wi rounds the same way */
    mt_real fi = 1 - pow5(1 - (mt_real)0.5 * mt_max(ci, co)), fo = 1 - pow5(1 - (mt_real)0.5 * mt_min(ci, co));
    mt_rgb diffuse = mt_rgb_scale(
        mt_rgb_scale(mt_rgb_mul(mt_rgb_scale(fb->Rd, 28 / (23 * MT_PI)),
                                mt_rgb_sub(mt_rgb_gray(1), fb->Rs)),
                     fi),
        fo);
    mt_vec3 wh;
    mt_real widotwh, wodotwh;
    if (mt_v3_is_zero(mt_v3_add(wi, wo))) return mt_rgb_black();
    /* Dot(wi, wh), symmetric in wo and wi for directions of one length (see
     * mt__half_cosines) */
    widotwh = mt__half_cosines(wo, wi, &wh, &wodotwh);
    den = 4 * mt_fabs(widotwh) * mt_max(ci, co);
    /* Both directions grazing (or wi = -wo up to rounding): pbrt-v2 divides by
     * zero; such directions carry no energy (erratum grazing-division). */
    if (den == 0) return diffuse;
    return mt_rgb_add(diffuse, mt_rgb_scale(schlick(fb, widotwh),
                                            mt_distribution_d(&fb->dist, wh, b->mode) / den));
}

static mt_real fresnelblend_pdf(const mt_bxdf *b, mt_vec3 wo, mt_vec3 wi)
{
    if (!mt_same_hemisphere(wo, wi)) return 0;
    return (mt_real)0.5 * (mt_abs_cos_theta(wi) * MT_INV_PI +
                           mt_distribution_pdf(&((const fresnelblend *)b)->dist, wo, wi, b->mode));
}

static mt_rgb fresnelblend_sample_f(const mt_bxdf *b, mt_vec3 wo, mt_vec3 *wi, mt_real u1,
                                    mt_real u2, mt_real *pdf)
{
    /* Half the samples cosine-weighted, half from the distribution. */
    if (u1 < 0.5f) {
        u1 = 2 * u1;
        *wi = mt_cosine_sample_hemisphere(u1, u2);
        if (wo.z < 0) wi->z *= -1;
    } else {
        u1 = 2 * (u1 - 0.5f);
        mt_distribution_sample(&((const fresnelblend *)b)->dist, wo, u1, u2, wi, pdf, b->mode);
        if (!mt_same_hemisphere(wo, *wi)) {
            /* pbrt-v2 keeps the distribution's pdf (erratum glossy-sample-pdf). */
            if (b->mode & MT_FIX_GLOSSY_SAMPLE_PDF) *pdf = 0;
            return mt_rgb_black();
        }
    }
    *pdf = fresnelblend_pdf(b, wo, *wi);
    return fresnelblend_f(b, wo, *wi);
}

static const mt_bxdf_ops fresnelblend_ops = {
    "fresnelblend", fresnelblend_f, fresnelblend_sample_f, fresnelblend_pdf,
    mt_bxdf_default_rho_hd, mt_bxdf_default_rho_hh};

mt_bxdf *mt_fresnelblend_create(mt_arena *a, mt_mode mode, mt_rgb Rd, mt_rgb Rs,
                                mt_distribution dist, mt_error *err)
{
    fresnelblend *fb;
    if (!mt__check_rgb(Rd, "Rd", "fresnelblend", err) ||
        !mt__check_rgb(Rs, "Rs", "fresnelblend", err) ||
        !mt__check_distribution(&dist, "fresnelblend", err))
        return NULL;
    fb = mt_bxdf_alloc(a, sizeof *fb, &fresnelblend_ops, MT_BSDF_REFLECTION | MT_BSDF_GLOSSY,
                       mode, err);
    if (!fb) return NULL;
    fb->Rd = Rd;
    fb->Rs = Rs;
    fb->dist = dist;
    return &fb->base;
}
