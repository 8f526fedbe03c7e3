/* A BSDF built from pbrt-v2's BxDFs, evaluated and sampled. */
#include <stdio.h>
#include <materia.h>

int main(void)
{
    mt_error err = MT_ERROR_INIT;
    mt_arena *arena = mt_arena_create(0); /* one per thread; BxDFs and BSDFs live in it */
    mt_diffgeom dg = mt_diffgeom_default(); /* n = +z, dpdu = +x */
    mt_bsdf *bsdf = mt_bsdf_create(arena, MT_MODE_PBRT_V2, &dg, dg.n, 1, &err);
    mt_vec3 wo = mt_v3(0, 0.6f, 0.8f), wi = mt_v3(0, -0.6f, 0.8f);
    char msg[1024];
    if (mt_bsdf_add(bsdf, mt_lambertian_create(arena, MT_MODE_PBRT_V2, mt_rgb_gray(0.5f), &err), &err) ||
        mt_bsdf_add(bsdf, mt_microfacet_create(arena, MT_MODE_PBRT_V2, mt_rgb_gray(0.25f),
                                               mt_fresnel_dielectric(1.5f, 1), mt_blinn(100), &err), &err)) {
        fprintf(stderr, "%s\n", mt_error_format(&err, msg, sizeof msg));
        return 1;
    }
    mt_rgb f = mt_bsdf_f(bsdf, wo, wi, MT_BSDF_ALL);
    mt_bsdf_sample s = mt_bsdf_sample_f(bsdf, wo, 0.3f, 0.25f, 0.75f, MT_BSDF_ALL);
    printf("f = %.5f, pdf = %.5f\n", f.c[0], mt_bsdf_pdf(bsdf, wo, wi, MT_BSDF_ALL));
    printf("sampled wi = (%.4f %.4f %.4f), f = %.5f, pdf = %.5f\n", s.wi.x, s.wi.y, s.wi.z, s.f.c[0], s.pdf);
    mt_arena_destroy(arena); /* frees every BxDF and BSDF made in it */
    return 0;
}
