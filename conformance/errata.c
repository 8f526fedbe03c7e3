/*
 * materia-conformance --errata: the size of each BxDF- and BSDF-layer
 * erratum, measured by running the same queries with and without its fix
 * (the mode bit alone). The figures go into conformance/ERRATA.md.
 */
#include <stdio.h>
#include <string.h>
#include "conformance.h"

static mt_bsdf *bsdf_at(mt_arena *a, mt_mode m, const mt_diffgeom *dg, mt_vec3 ng, mt_real eta)
{
    mt_error err;
    return mt_bsdf_create(a, m, dg, ng, eta, &err);
}

/* Largest relative difference of f and of pdf between two BSDFs over random
 * direction pairs, and the fraction of pairs where either differs. */
static void compare_pairs(const mt_bsdf *x, const mt_bsdf *y, double *df, double *dp, double *frac)
{
    mt_rng r;
    int i, differ = 0, n = 200000;
    *df = *dp = 0;
    mt_rng_seed(&r, 11, 12);
    for (i = 0; i < n; ++i) {
        mt_vec3 wo = mt_uniform_sample_sphere(mt_rng_uniform(&r), mt_rng_uniform(&r));
        mt_vec3 wi = mt_uniform_sample_sphere(mt_rng_uniform(&r), mt_rng_uniform(&r));
        mt_rgb f1 = mt_bsdf_f(x, wo, wi, MT_BSDF_ALL), f2 = mt_bsdf_f(y, wo, wi, MT_BSDF_ALL);
        double p1 = mt_bsdf_pdf(x, wo, wi, MT_BSDF_ALL), p2 = mt_bsdf_pdf(y, wo, wi, MT_BSDF_ALL);
        double a = fabs(f1.c[1] - f2.c[1]) / fmax(fmax(f1.c[1], f2.c[1]), 1e-30);
        double b = fabs(p1 - p2) / fmax(fmax(p1, p2), 1e-30);
        if (a > 1e-6 || b > 1e-6) differ++;
        *df = fmax(*df, a);
        *dp = fmax(*dp, b);
    }
    *frac = (double)differ / n;
}

/* Monte Carlo reflectance with the BSDF's sampler (biased when the pdf it
 * reports is not the density it samples) and the fraction of samples that
 * return a pdf but no f. */
static double mc_rho(const mt_bsdf *b, mt_vec3 wo, double *empty)
{
    mt_rng r;
    int i, n = 400000, e = 0;
    double s = 0;
    mt_rng_seed(&r, 5, 6);
    for (i = 0; i < n; ++i) {
        mt_bsdf_sample sm = mt_bsdf_sample_f(b, wo, mt_rng_uniform(&r), mt_rng_uniform(&r), mt_rng_uniform(&r), MT_BSDF_ALL);
        if (sm.pdf > 0) {
            s += sm.f.c[1] * fabs(mt_v3_dot(sm.wi, mt_bsdf_frame(b).n)) / sm.pdf;
            if (mt_rgb_is_black(sm.f)) e++;
        }
    }
    if (empty) *empty = (double)e / n;
    return s / n;
}

int cf_errata_report(void)
{
    mt_arena *a = mt_arena_create(0);
    mt_error err;
    mt_diffgeom dg = mt_diffgeom_default();
    mt_vec3 n = dg.n, wo = mt_v3(0.6f, 0, 0.8f);
    double df, dp, frac, e1, e2;
    int k;
    mt_bsdf *x, *y;
    printf("# Measured effect of each BxDF/BSDF erratum (materia-conformance --errata, %s build)\n\n", mt_precision());

    /* scaled-pdf: the mix-like combination of the catalog */
    {
        int ns;
        const cf_subject *s = cf_subjects(&ns), *mix = NULL;
        for (k = 0; k < ns; ++k)
            if (!strcmp(s[k].family, "combination") && strstr(s[k].name, "mix")) mix = &s[k];
        mix->build(mix, a, MT_MODE_PBRT_V2 | MT_FIX_GLOSSY_SAMPLE_PDF, &x, &err);
        mix->build(mix, a, MT_FIX_SCALED_PDF | MT_FIX_GLOSSY_SAMPLE_PDF, &y, &err);
        compare_pairs(x, y, &df, &dp, &frac);
        printf("scaled-pdf: %s: Pdf() differs on %.1f%% of direction pairs, by up to %.0f%%;\n"
               "  Monte Carlo reflectance at cos 0.8: %.4f with pbrt-v2's pdf, %.4f corrected (quadrature %.4f)\n",
               mix->name, 100 * frac, 100 * dp, mc_rho(x, wo, NULL), mc_rho(y, wo, NULL),
               (double)mt_rgb_y(mt_bsdf_rho_quad(y, wo, MT_BSDF_ALL, 1e-6)));
    }
    /* glossy-sample-pdf */
    {
        static const double expo[] = {0.5, 10, 100, 1000};
        for (k = 0; k < 4; ++k) {
            double wz[] = {0.9999, 0.3, 0.03};
            int j;
            printf("glossy-sample-pdf: microfacet blinn e=%g:", expo[k]);
            for (j = 0; j < 3; ++j) {
                mt_vec3 w = mt_v3((mt_real)sqrt(1 - wz[j] * wz[j]), 0, (mt_real)wz[j]);
                x = bsdf_at(a, MT_MODE_PBRT_V2, &dg, n, 1);
                mt_bsdf_add(x, mt_microfacet_create(a, 0, mt_rgb_gray(1), mt_fresnel_noop(), mt_blinn((mt_real)expo[k]), &err), &err);
                mc_rho(x, w, &e1);
                printf(" cos %.4g: %.2f%% of samples carry a pdf but no f;", wz[j], 100 * e1);
            }
            printf("\n");
        }
        {
            int ns;
            const cf_subject *s = cf_subjects(&ns), *tr = NULL;
            for (k = 0; k < ns; ++k)
                if (strstr(s[k].name, "translucent-like k=0.25")) tr = &s[k];
            tr->build(tr, a, MT_MODE_PBRT_V2, &x, &err);
            tr->build(tr, a, MT_FIX_GLOSSY_SAMPLE_PDF, &y, &err);
            printf("glossy-sample-pdf: %s: Monte Carlo reflectance at cos 0.8 %.4f (pbrt-v2) vs %.4f (fixed), "
                   "quadrature %.4f\n",
                   tr->name, mc_rho(x, wo, &e1), mc_rho(y, wo, &e2), (double)mt_rgb_y(mt_bsdf_rho_quad(y, wo, MT_BSDF_ALL, 1e-6)));
        }
    }
    /* microfacet-fresnel-cosine: a dielectric coat seen from below */
    {
        mt_vec3 below = mt_v3(0.6f, 0, -0.8f), below2 = mt_v3(0.954f, 0, -0.3f);
        mt_bxdf *bx = mt_microfacet_create(a, 0, mt_rgb_gray(1), mt_fresnel_dielectric(1, 1.5f), mt_blinn(10), &err);
        mt_bxdf *by = mt_microfacet_create(a, MT_FIX_MICROFACET_FRESNEL, mt_rgb_gray(1), mt_fresnel_dielectric(1, 1.5f), mt_blinn(10), &err);
        x = bsdf_at(a, 0, &dg, n, 1);
        mt_bsdf_add(x, bx, &err);
        y = bsdf_at(a, MT_FIX_MICROFACET_FRESNEL, &dg, n, 1);
        mt_bsdf_add(y, by, &err);
        compare_pairs(x, y, &df, &dp, &frac);
        printf("microfacet-fresnel-cosine: blinn e=10, dielectric (1, 1.5): f differs on %.1f%% of direction pairs "
               "(those below the surface), by up to %.0f%%;\n  reflectance from below at cos 0.8: %.4f (pbrt-v2) vs %.4f, "
               "at cos 0.3: %.4f vs %.4f\n",
               100 * frac, 100 * df, (double)mt_bxdf_rho_quad(bx, below, 1e-6).c[1],
               (double)mt_bxdf_rho_quad(by, below, 1e-6).c[1], (double)mt_bxdf_rho_quad(bx, below2, 1e-6).c[1],
               (double)mt_bxdf_rho_quad(by, below2, 1e-6).c[1]);
    }
    /* rho-world-space: a frame turned away from the world axes */
    {
        mt_diffgeom t = dg;
        mt_rgb r1, r2, rt;
        mt_vec3 w = mt_v3(0, 0.6f, 0.8f);
        t.n = mt_v3_normalize(mt_v3(0.5f, 0, 0.866f));
        t.dpdu = mt_v3_cross(mt_v3(0, 1, 0), t.n);
        x = bsdf_at(a, 0, &t, t.n, 1);
        mt_bsdf_add(x, mt_microfacet_create(a, 0, mt_rgb_gray(1), mt_fresnel_noop(), mt_blinn(10), &err), &err);
        y = bsdf_at(a, MT_FIX_RHO_LOCAL, &t, t.n, 1);
        mt_bsdf_add(y, mt_microfacet_create(a, 0, mt_rgb_gray(1), mt_fresnel_noop(), mt_blinn(10), &err), &err);
        r1 = mt_bsdf_rho_quad(x, w, MT_BSDF_ALL, 1e-6);
        r2 = mt_bsdf_rho_quad(y, w, MT_BSDF_ALL, 1e-6);
        rt = mt_bxdf_rho_quad(mt_bsdf_component(y, 0), mt_bsdf_world_to_local(y, w), 1e-6);
        printf("rho-world-space: blinn e=10, normal tilted 30 deg, wo at 37 deg from it in world: rho %.4f (pbrt-v2) vs "
               "%.4f (true %.4f)\n", (double)r1.c[1], (double)r2.c[1], (double)rt.c[1]);
    }
    /* anisotropic-normal */
    {
        mt_distribution d = mt_anisotropic(10, 100);
        printf("anisotropic-normal: D(n) for 10x100: %g (pbrt-v2) vs %g (limit); pdf at wo = wi = n: %g vs %g; "
               "a single direction: no integral changes\n",
               (double)mt_distribution_d(&d, n, 0), (double)mt_distribution_d(&d, n, MT_FIX_ANISOTROPIC_NORMAL),
               (double)mt_distribution_pdf(&d, n, n, 0), (double)mt_distribution_pdf(&d, n, n, MT_FIX_ANISOTROPIC_NORMAL));
    }
    /* bsdf-frame: dpdu 30 degrees out of the tangent plane */
    {
        mt_diffgeom t = dg;
        t.dpdu = mt_v3(0.866f, 0, 0.5f);
        x = bsdf_at(a, 0, &t, n, 1);
        mt_bsdf_add(x, mt_microfacet_create(a, 0, mt_rgb_gray(1), mt_fresnel_noop(), mt_anisotropic(10, 100), &err), &err);
        y = bsdf_at(a, MT_FIX_BSDF_FRAME, &t, n, 1);
        mt_bsdf_add(y, mt_microfacet_create(a, 0, mt_rgb_gray(1), mt_fresnel_noop(), mt_anisotropic(10, 100), &err), &err);
        compare_pairs(x, y, &df, &dp, &frac);
        printf("bsdf-frame: anisotropic 10x100 with dpdu 30 deg out of the tangent plane: f differs on %.1f%% of pairs, "
               "by up to %.0f%%; |local(n)| = 1 but |local(s)| = %.4f\n",
               100 * frac, 100 * df, (double)mt_v3_len(mt_bsdf_world_to_local(x, mt_v3(1, 0, 0))));
    }
    /* tangent-plane */
    {
        mt_vec3 graze = mt_v3(1, 0, 0);
        x = bsdf_at(a, 0, &dg, n, 1);
        mt_bsdf_add(x, mt_brdf_to_btdf_create(a, 0, mt_lambertian_create(a, 0, mt_rgb_gray(1), &err), &err), &err);
        printf("tangent-plane: a transmission-only Lambertian with wi exactly grazing: f = %g (pbrt-v2) vs 0; "
               "the set has measure zero\n", (double)mt_bsdf_f(x, wo, graze, MT_BSDF_ALL).c[0]);
    }
    mt_arena_destroy(a);
    return 0;
}
