/*
 * Deliberately wrong BxDFs, built only into the suite, to prove it has the
 * power to catch what it is meant to catch: a pdf off by 5% (consistent
 * between Sample_f and Pdf, so only the statistics can see it), a sampler
 * that ignores the roughness (it reports the true pdf of what it samples from
 * the wrong lobe), and a wrong Fresnel (specular transmission weighted with
 * the reflectance seen from the wrong side).
 */
#include "conformance.h"

/* ---- pdf x 1.05 ------------------------------------------------------------ */
typedef struct wrap1 {
    mt_bxdf base;
    const mt_bxdf *inner;
} wrap1;

static mt_rgb pdf5_f(const mt_bxdf *b, mt_vec3 wo, mt_vec3 wi)
{
    const mt_bxdf *x = ((const wrap1 *)b)->inner;
    return x->ops->f(x, wo, wi);
}
static mt_rgb pdf5_sample(const mt_bxdf *b, mt_vec3 wo, mt_vec3 *wi, mt_real u1, mt_real u2, mt_real *pdf)
{
    const mt_bxdf *x = ((const wrap1 *)b)->inner;
    mt_rgb f = x->ops->sample_f(x, wo, wi, u1, u2, pdf);
    *pdf *= (mt_real)1.05;
    return f;
}
static mt_real pdf5_pdf(const mt_bxdf *b, mt_vec3 wo, mt_vec3 wi)
{
    const mt_bxdf *x = ((const wrap1 *)b)->inner;
    return x->ops->pdf(x, wo, wi) * (mt_real)1.05;
}
static const mt_bxdf_ops pdf5_ops = {"broken_pdf_5pct", pdf5_f, pdf5_sample, pdf5_pdf,
                                     mt_bxdf_default_rho_hd, mt_bxdf_default_rho_hh};

/* ---- sampling that ignores roughness --------------------------------------- */
typedef struct wrap2 {
    mt_bxdf base;
    const mt_bxdf *truth, *sampler;
} wrap2;

static mt_rgb rough_f(const mt_bxdf *b, mt_vec3 wo, mt_vec3 wi)
{
    const mt_bxdf *x = ((const wrap2 *)b)->truth;
    return x->ops->f(x, wo, wi);
}
static mt_real rough_pdf(const mt_bxdf *b, mt_vec3 wo, mt_vec3 wi)
{
    const mt_bxdf *x = ((const wrap2 *)b)->truth;
    return x->ops->pdf(x, wo, wi);
}
static mt_rgb rough_sample(const mt_bxdf *b, mt_vec3 wo, mt_vec3 *wi, mt_real u1, mt_real u2, mt_real *pdf)
{
    const wrap2 *w = (const wrap2 *)b;
    w->sampler->ops->sample_f(w->sampler, wo, wi, u1, u2, pdf);
    if (*pdf == 0) return mt_rgb_black();
    *pdf = rough_pdf(b, wo, *wi);
    return rough_f(b, wo, *wi);
}
static const mt_bxdf_ops rough_ops = {"broken_ignores_roughness", rough_f, rough_sample, rough_pdf,
                                      mt_bxdf_default_rho_hd, mt_bxdf_default_rho_hh};

/* ---- transmission with the Fresnel of the wrong side ----------------------- */
typedef struct wrongf {
    mt_bxdf base;
    mt_real eta;
} wrongf;

static mt_rgb wrongf_f(const mt_bxdf *b, mt_vec3 wo, mt_vec3 wi) { return mt_rgb_black(); }
static mt_real wrongf_pdf(const mt_bxdf *b, mt_vec3 wo, mt_vec3 wi) { return 0; }
static mt_rgb wrongf_sample(const mt_bxdf *b, mt_vec3 wo, mt_vec3 *wi, mt_real u1, mt_real u2, mt_real *pdf)
{
    mt_real eta = ((const wrongf *)b)->eta, ei = 1, et = eta, e, s2, c;
    mt_fresnel fr = mt_fresnel_dielectric(1, eta);
    int entering = wo.z > 0;
    if (!entering) {
        ei = eta;
        et = 1;
    }
    e = ei / et;
    s2 = e * e * mt_sin_theta2(wo);
    if (s2 >= 1 || wo.z == 0) return mt_rgb_black();
    c = mt_sqrt(1 - s2);
    *wi = mt_v3(-e * wo.x, -e * wo.y, entering ? -c : c);
    *pdf = 1;
    /* the error: the reflectance of the other side, at the other cosine */
    return mt_rgb_divs(mt_rgb_sub(mt_rgb_gray(1), mt_fresnel_evaluate(&fr, -wi->z)), c);
}
static const mt_bxdf_ops wrongf_ops = {"broken_fresnel_side", wrongf_f, wrongf_sample, wrongf_pdf,
                                       mt_bxdf_default_rho_hd, mt_bxdf_default_rho_hh};

static mt_bsdf *new_bsdf(mt_arena *a, mt_mode m, mt_real eta, mt_error *err)
{
    mt_diffgeom dg = mt_diffgeom_default();
    return mt_bsdf_create(a, m, &dg, dg.n, eta, err);
}

static mt_status b_pdf5(const cf_subject *s, mt_arena *a, mt_mode m, mt_bsdf **out, mt_error *err)
{
    mt_bsdf *b = *out = new_bsdf(a, m, 1, err);
    mt_bxdf *inner = mt_microfacet_create(a, m, mt_rgb_gray(1), mt_fresnel_noop(), mt_blinn((mt_real)s->p[0]), err);
    wrap1 *w;
    if (!b || !inner) return err->status;
    w = mt_bxdf_alloc(a, sizeof *w, &pdf5_ops, inner->type, m, err);
    if (!w) return err->status;
    w->inner = inner;
    return mt_bsdf_add(b, &w->base, err);
}

static mt_status b_rough(const cf_subject *s, mt_arena *a, mt_mode m, mt_bsdf **out, mt_error *err)
{
    mt_bsdf *b = *out = new_bsdf(a, m, 1, err);
    mt_bxdf *truth = mt_microfacet_create(a, m, mt_rgb_gray(1), mt_fresnel_noop(), mt_blinn((mt_real)s->p[0]), err);
    mt_bxdf *sampler = mt_microfacet_create(a, m, mt_rgb_gray(1), mt_fresnel_noop(), mt_blinn((mt_real)s->p[1]), err);
    wrap2 *w;
    if (!b || !truth || !sampler) return err->status;
    w = mt_bxdf_alloc(a, sizeof *w, &rough_ops, truth->type, m, err);
    if (!w) return err->status;
    w->truth = truth;
    w->sampler = sampler;
    return mt_bsdf_add(b, &w->base, err);
}

static mt_status b_wrongf(const cf_subject *s, mt_arena *a, mt_mode m, mt_bsdf **out, mt_error *err)
{
    mt_real eta = (mt_real)s->p[0];
    mt_bsdf *b = *out = new_bsdf(a, m, eta, err);
    wrongf *w;
    mt_status st;
    if (!b) return err->status;
    st = mt_bsdf_add(b, mt_specular_reflection_create(a, m, mt_rgb_gray(1), mt_fresnel_dielectric(1, eta), err), err);
    if (st) return st;
    w = mt_bxdf_alloc(a, sizeof *w, &wrongf_ops, MT_BSDF_TRANSMISSION | MT_BSDF_SPECULAR, m, err);
    if (!w) return err->status;
    w->eta = eta;
    return mt_bsdf_add(b, &w->base, err);
}

static const cf_subject broken[] = {
    {"BROKEN pdf off by 5% (blinn e=10)", "broken", b_pdf5, {10}, CF_BROKEN | CF_FURNACE_LE1, 0, 10, NULL},
    {"BROKEN pdf off by 5% (blinn e=0.5)", "broken", b_pdf5, {0.5}, CF_BROKEN | CF_FURNACE_LE1, 0, 0.5, NULL},
    {"BROKEN sampling ignores roughness (e=100 by 10)", "broken", b_rough, {100, 10}, CF_BROKEN | CF_FURNACE_LE1, 0, 100, NULL},
    {"BROKEN sampling e=10 by 12 (sensitivity, informative)", "broken", b_rough, {10, 12, 0, 0, 0, 0, 0, 1}, CF_BROKEN | CF_FURNACE_LE1, 0, 12, NULL},
    {"BROKEN wrong Fresnel side (glass 1.5)", "broken", b_wrongf, {1.5}, CF_BROKEN | CF_FURNACE_EXACT | CF_NO_CHI2 | CF_TWO_SIDED, 1, 0, NULL},
};

const cf_subject *cf_broken_subjects(int *count)
{
    *count = (int)(sizeof broken / sizeof broken[0]);
    return broken;
}
