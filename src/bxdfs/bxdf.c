/*
 * The BxDF base: allocation, the public entry points (which admit the
 * caller's directions), and pbrt-v2's BxDF base-class behaviour -- cosine
 * sampling, the cosine pdf and the Monte Carlo reflectances.
 */
#include "materia/bxdf.h"
#include "bxdfs/kinds.h"
#include "materia/sampling.h"
#include "core/dir.h"

void *mt_bxdf_alloc(mt_arena *a, size_t size, const mt_bxdf_ops *ops, unsigned type, mt_mode mode,
                    mt_error *err)
{
    mt_error_clear(err);
    return mt__bxdf_alloc(a, size, ops, type, mode, err);
}

void *mt__bxdf_alloc(mt_arena *a, size_t size, const mt_bxdf_ops *ops, unsigned type, mt_mode mode,
                     mt_error *err)
{
    mt_bxdf *b = mt_arena_alloc(a, size);
    if (!b) {
        mt_error_set(err, MT_ERR_NOMEM, "out of memory allocating a %s BxDF", ops->name);
        return NULL;
    }
    b->ops = ops;
    b->type = type;
    b->mode = mode;
    return b;
}

mt_rgb mt_bxdf_f(const mt_bxdf *b, mt_vec3 wo, mt_vec3 wi)
{
    if (!mt__admit_dir(&wo) || !mt__admit_dir(&wi)) return mt_rgb_black();
    return b->ops->f(b, wo, wi);
}

mt_rgb mt_bxdf_sample_f(const mt_bxdf *b, mt_vec3 wo, mt_real u1, mt_real u2, mt_vec3 *wi,
                        mt_real *pdf)
{
    mt_rgb f;
    *pdf = 0;
    *wi = mt_v3(0, 0, 0);
    if (!mt__admit_dir(&wo) || !(u1 >= 0 && u1 < 1) || !(u2 >= 0 && u2 < 1))
        return mt_rgb_black();
    f = b->ops->sample_f(b, wo, wi, u1, u2, pdf);
    if (*pdf == 0) {
        *wi = mt_v3(0, 0, 0);
        return mt_rgb_black();
    }
    return f;
}

mt_real mt_bxdf_pdf(const mt_bxdf *b, mt_vec3 wo, mt_vec3 wi)
{
    if (!mt__admit_dir(&wo) || !mt__admit_dir(&wi)) return 0;
    return b->ops->pdf(b, wo, wi);
}

mt_rgb mt_bxdf_rho_hd(const mt_bxdf *b, mt_vec3 wo, int n, const mt_real *samples)
{
    if (n <= 0 || !mt__admit_dir(&wo)) return mt_rgb_black();
    return b->ops->rho_hd(b, wo, n, samples);
}

mt_rgb mt_bxdf_rho_hh(const mt_bxdf *b, int n, const mt_real *s1, const mt_real *s2)
{
    if (n <= 0) return mt_rgb_black();
    return b->ops->rho_hh(b, n, s1, s2);
}

unsigned mt_bxdf_type(const mt_bxdf *b) { return b->type; }
const char *mt_bxdf_name(const mt_bxdf *b) { return b->ops->name; }
mt_mode mt_bxdf_mode(const mt_bxdf *b) { return b->mode; }

/* pbrt-v2 BxDF::Sample_f: cosine-sample the hemisphere, flipped to wo's side. */
mt_rgb mt_bxdf_default_sample_f(const mt_bxdf *b, mt_vec3 wo, mt_vec3 *wi, mt_real u1,
                                mt_real u2, mt_real *pdf)
{
    *wi = mt_cosine_sample_hemisphere(u1, u2);
    if (wo.z < 0) wi->z *= -1;
    *pdf = b->ops->pdf(b, wo, *wi);
    return b->ops->f(b, wo, *wi);
}

/* pbrt-v2 BxDF::Pdf. */
mt_real mt_bxdf_default_pdf(const mt_bxdf *b, mt_vec3 wo, mt_vec3 wi)
{
    (void)b;
    return mt_same_hemisphere(wo, wi) ? mt_abs_cos_theta(wi) * MT_INV_PI : 0;
}

/* pbrt-v2 BxDF::rho(wo, ...): the estimator of rho_hd with the BxDF's sampler. */
mt_rgb mt_bxdf_default_rho_hd(const mt_bxdf *b, mt_vec3 wo, int n, const mt_real *samples)
{
    mt_rgb r = mt_rgb_black();
    int i;
    for (i = 0; i < n; ++i) {
        mt_vec3 wi;
        mt_real pdf = 0;
        mt_rgb f = b->ops->sample_f(b, wo, &wi, samples[2 * i], samples[2 * i + 1], &pdf);
        if (pdf > 0) r = mt_rgb_add(r, mt_rgb_scale(f, mt_abs_cos_theta(wi) / pdf));
    }
    return mt_rgb_scale(r, (mt_real)1 / (mt_real)n);
}

/* pbrt-v2 BxDF::rho(...): rho_hh with uniform wo and the BxDF's sampler. */
mt_rgb mt_bxdf_default_rho_hh(const mt_bxdf *b, int n, const mt_real *s1, const mt_real *s2)
{
    mt_rgb r = mt_rgb_black();
    int i;
    for (i = 0; i < n; ++i) {
        mt_vec3 wo = mt_uniform_sample_hemisphere(s1[2 * i], s1[2 * i + 1]), wi;
        mt_real pdf_o = MT_INV_2PI, pdf_i = 0;
        mt_rgb f = b->ops->sample_f(b, wo, &wi, s2[2 * i], s2[2 * i + 1], &pdf_i);
        if (pdf_i > 0)
            r = mt_rgb_add(r, mt_rgb_scale(f, mt_abs_cos_theta(wi) * mt_abs_cos_theta(wo) /
                                                  (pdf_o * pdf_i)));
    }
    return mt_rgb_scale(r, 1 / (MT_PI * n));
}
