/*
 * Perfect specular reflection and transmission (pbrt-v2 reflection.h/.cpp
 * SpecularReflection, SpecularTransmission): delta lobes, so f and Pdf are 0
 * and only Sample_f returns energy, with pdf 1.
 */
#include "bxdfs/kinds.h"

typedef struct specular_reflection {
    mt_bxdf base;
    mt_rgb R;
    mt_fresnel fresnel;
} specular_reflection;

typedef struct specular_transmission {
    mt_bxdf base;
    mt_rgb T;
    mt_real etai, etat;
    mt_fresnel fresnel;
} specular_transmission;

static mt_rgb delta_f(const mt_bxdf *b, mt_vec3 wo, mt_vec3 wi) { return mt_rgb_black(); }
static mt_real delta_pdf(const mt_bxdf *b, mt_vec3 wo, mt_vec3 wi) { return 0; }

static mt_rgb specular_reflection_sample_f(const mt_bxdf *b, mt_vec3 wo, mt_vec3 *wi,
                                           mt_real u1, mt_real u2, mt_real *pdf)
{
    const specular_reflection *s = (const specular_reflection *)b;
    *wi = mt_v3(-wo.x, -wo.y, wo.z);
    if (wo.z == 0) {
        /* pbrt-v2 divides by |cos theta_i| = 0 here (erratum grazing-division). */
        *pdf = 0;
        return mt_rgb_black();
    }
    *pdf = 1;
    return mt_rgb_divs(mt_rgb_mul(mt_fresnel_evaluate(&s->fresnel, mt_cos_theta(wo)), s->R),
                       mt_abs_cos_theta(*wi));
}

static mt_rgb specular_transmission_sample_f(const mt_bxdf *b, mt_vec3 wo, mt_vec3 *wi,
                                             mt_real u1, mt_real u2, mt_real *pdf)
{
    const specular_transmission *s = (const specular_transmission *)b;
    int entering = mt_cos_theta(wo) > 0;
    mt_real ei = s->etai, et = s->etat, sini2, eta, sint2, cost;
    mt_rgb F, w;
    if (!entering) {
        mt_real t = ei;
        ei = et;
        et = t;
    }
    sini2 = mt_sin_theta2(wo);
    eta = ei / et;
    sint2 = eta * eta * sini2;
    if (sint2 >= 1) return mt_rgb_black(); /* total internal reflection: no sample */
    cost = mt_sqrt(mt_max(0, 1 - sint2));
    if (entering) cost = -cost;
    *wi = mt_v3(eta * -wo.x, eta * -wo.y, cost);
    {
        /* pbrt-v2 scales wo's x and y but takes sin^2 from 1 - z^2; in float
         * the two disagree by ~1e-7 near the normal, and eta = 100 makes that
         * a 2e-4 error in |wi|. Such a direction is renormalized; ordinary
         * ones (error ~1e-7) are left bit for bit as pbrt-v2 computes them.
         * A wo clearly not unit itself (beyond 1e-5: a direction rounded to
         * float and read in double is unit to 1e-9) comes from pbrt-v2's frame
         * that is not orthonormal (erratum bsdf-frame), where every sampled
         * direction has the frame's lengths: that wi is kept as pbrt-v2
         * computes it too. */
        mt_real l2 = mt_v3_len2(*wi);
        if (mt_fabs(l2 - 1) > 64 * MT_REAL_EPSILON && mt_fabs(mt_v3_len2(wo) - 1) <= (mt_real)1e-5)
            *wi = mt_v3_scale(*wi, 1 / mt_sqrt(l2));
    }
    *pdf = 1;
    F = mt_fresnel_evaluate(&s->fresnel, mt_cos_theta(wo));
    /* pbrt-v2 leaves the (ei/et)^2 radiance factor commented out (erratum
     * specular-transmission-eta2); the option applies it. */
    w = mt_rgb_mul(mt_rgb_sub(mt_rgb_gray(1), F), s->T);
    if (b->mode & MT_OPT_RADIANCE_TRANSMISSION) w = mt_rgb_scale(w, (ei * ei) / (et * et));
    return mt_rgb_divs(w, mt_abs_cos_theta(*wi));
}

/* Reflectances of delta lobes: pbrt-v2's base-class estimators, which reduce
 * to the lobe's weight (the sample does not depend on the uniform numbers). */
static const mt_bxdf_ops specular_reflection_ops = {
    "specular_reflection", delta_f, specular_reflection_sample_f, delta_pdf,
    mt_bxdf_default_rho_hd, mt_bxdf_default_rho_hh};

static const mt_bxdf_ops specular_transmission_ops = {
    "specular_transmission", delta_f, specular_transmission_sample_f, delta_pdf,
    mt_bxdf_default_rho_hd, mt_bxdf_default_rho_hh};

mt_bxdf *mt_specular_reflection_create(mt_arena *a, mt_mode mode, mt_rgb R, mt_fresnel fresnel,
                                       mt_error *err)
{
    specular_reflection *s;
    if (!mt__check_rgb(R, "R", "specular_reflection", err) ||
        !mt__check_fresnel(&fresnel, "specular_reflection", err))
        return NULL;
    s = mt_bxdf_alloc(a, sizeof *s, &specular_reflection_ops,
                      MT_BSDF_REFLECTION | MT_BSDF_SPECULAR, mode, err);
    if (!s) return NULL;
    s->R = R;
    s->fresnel = fresnel;
    return &s->base;
}

mt_bxdf *mt_specular_transmission_create(mt_arena *a, mt_mode mode, mt_rgb T, mt_real etai,
                                         mt_real etat, mt_error *err)
{
    specular_transmission *s;
    mt_fresnel fr = mt_fresnel_dielectric(etai, etat);
    if (!mt__check_rgb(T, "T", "specular_transmission", err) ||
        !mt__check_fresnel(&fr, "specular_transmission", err))
        return NULL;
    s = mt_bxdf_alloc(a, sizeof *s, &specular_transmission_ops,
                      MT_BSDF_TRANSMISSION | MT_BSDF_SPECULAR, mode, err);
    if (!s) return NULL;
    s->T = T;
    s->etai = etai;
    s->etat = etat;
    s->fresnel = fr;
    return &s->base;
}
