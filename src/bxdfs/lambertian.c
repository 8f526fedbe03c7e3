/* Lambertian reflection: f = R / pi (pbrt-v2 reflection.h Lambertian). */
#include "materia/sampling.h"
#include "bxdfs/kinds.h"

typedef struct lambertian {
    mt_bxdf base;
    mt_rgb R;
} lambertian;

static mt_rgb lambertian_f(const mt_bxdf *b, mt_vec3 wo, mt_vec3 wi)
{
    (void)wo;
    (void)wi;
    return mt_rgb_scale(((const lambertian *)b)->R, MT_INV_PI);
}

/* pbrt-v2 BxDF::Sample_f (mt_bxdf_default_sample_f) with this BxDF's pdf
 * and f called directly: the same arithmetic, without the two calls
 * through the operations table on the renderer's most common sample. */
static mt_rgb lambertian_sample_f(const mt_bxdf *b, mt_vec3 wo, mt_vec3 *wi, mt_real u1, mt_real u2,
                                  mt_real *pdf)
{
    *wi = mt_cosine_sample_hemisphere(u1, u2);
    if (wo.z < 0) wi->z *= -1;
    *pdf = mt_bxdf_default_pdf(b, wo, *wi);
    return lambertian_f(b, wo, *wi);
}

/* The reflectances are exactly R, as pbrt-v2's overrides return. */
static mt_rgb lambertian_rho_hd(const mt_bxdf *b, mt_vec3 wo, int n, const mt_real *s)
{
    return ((const lambertian *)b)->R;
}

static mt_rgb lambertian_rho_hh(const mt_bxdf *b, int n, const mt_real *s1, const mt_real *s2)
{
    return ((const lambertian *)b)->R;
}

static const mt_bxdf_ops lambertian_ops = {
    .name = "lambertian",
    .f = lambertian_f,
    .sample_f = lambertian_sample_f,
    .pdf = mt_bxdf_default_pdf,
    .rho_hd = lambertian_rho_hd,
    .rho_hh = lambertian_rho_hh,
};

mt_bxdf *mt_lambertian_create(mt_arena *a, mt_mode mode, mt_rgb R, mt_error *err)
{
    lambertian *l;
    mt_error_clear(err);
    if (!mt__check_rgb(R, "R", "lambertian", err)) return NULL;
    l = mt__bxdf_alloc(a, sizeof *l, &lambertian_ops, MT_BSDF_REFLECTION | MT_BSDF_DIFFUSE, mode,
                       err);
    if (!l) return NULL;
    l->R = R;
    return &l->base;
}
