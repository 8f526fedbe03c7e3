/*
 * Checks that are not per configuration: the light-leak rule with a tilted
 * geometric normal, the normalization of the microfacet distributions,
 * CONFORMANCE.md's furnace table and the rejection of invalid parameters.
 * (Reciprocity and Helmholtz are the core's, per configuration: pairs.c,
 * delta.c.)
 */
#include <float.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include "conformance.h"

#if MT_USE_DOUBLE
#define EPS DBL_EPSILON
#else
#define EPS FLT_EPSILON
#endif

static mt_vec3 random_dir(mt_rng *r)
{
    return mt_uniform_sample_sphere(mt_rng_uniform(r), mt_rng_uniform(r));
}

static void row(cf_rows *rows, const char *subject, const char *mode, const char *check, int ok,
                const char *bound, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 7, 8)))
#endif
    ;

static void row(cf_rows *rows, const char *subject, const char *mode, const char *check, int ok,
                const char *bound, const char *fmt, ...)
{
    cf_row r;
    va_list ap;
    memset(&r, 0, sizeof r);
    snprintf(r.subject, sizeof r.subject, "%s", subject);
    snprintf(r.mode, sizeof r.mode, "%s", mode);
    snprintf(r.check, sizeof r.check, "%s", check);
    snprintf(r.bound, sizeof r.bound, "%s", bound);
    va_start(ap, fmt);
    vsnprintf(r.statistic, sizeof r.statistic, fmt, ap);
    va_end(ap);
    r.verdict = ok ? CF_PASS : CF_FAIL;
    cf_rows_add(rows, &r);
}

/* The light-leak rule, with the geometric normal tilted from the shading
 * normal: red reflection, green transmission, so f tells which was used. */
void cf_light_leak(cf_rows *rows)
{
    int mi;
    for (mi = 0; mi < 2; ++mi) {
        mt_mode mode = mi ? MT_MODE_CORRECTED : MT_MODE_PBRT_V2;
        mt_arena *a = mt_arena_create(0);
        mt_diffgeom dg = mt_diffgeom_default();
        mt_vec3 ng = mt_v3_normalize(mt_v3(0.5f, 0.1f, 0.8f));
        mt_error err;
        mt_bsdf *b = mt_bsdf_create(a, mode, &dg, ng, 1, &err);
        mt_rng rng;
        int i, bad = 0, both = 0, refl = 0;
        mt_bsdf_add(b, mt_lambertian_create(a, mode, mt_rgb_make(1, 0, 0), &err), &err);
        mt_bsdf_add(b, mt_brdf_to_btdf_create(a, mode, mt_lambertian_create(a, mode, mt_rgb_make(0, 1, 0), &err), &err),
                    &err);
        mt_rng_seed(&rng, 7, 7);
        for (i = 0; i < 20000; ++i) {
            mt_vec3 wo = random_dir(&rng), wi = random_dir(&rng);
            mt_rgb f = mt_bsdf_f(b, wo, wi, MT_BSDF_ALL);
            mt_bsdf_sample sm = mt_bsdf_sample_f(b, wo, mt_rng_uniform(&rng), mt_rng_uniform(&rng),
                                                 mt_rng_uniform(&rng), MT_BSDF_ALL);
            int reflect = mt_v3_dot(wo, ng) * mt_v3_dot(wi, ng) > 0;
            refl += reflect;
            if (f.c[0] != 0 && f.c[1] != 0) both++;
            /* BRDFs are evaluated with |cos|, so each lobe is non-zero on
             * both sides: only the geometric normal can zero one of them */
            if (reflect ? (f.c[1] != 0 || f.c[0] == 0) : (f.c[0] != 0 || f.c[1] == 0)) bad++;
            if (sm.pdf > 0) {
                int sr = mt_v3_dot(wo, ng) * mt_v3_dot(sm.wi, ng) > 0;
                if (sr ? sm.f.c[1] != 0 : sm.f.c[0] != 0) bad++;
            }
        }
        row(rows, "light leak (ng tilted 37 deg)", mt_mode_name(mode), "leak rule", bad == 0 && both == 0,
            "0 violations", "%d violations in 20000 pairs + samples (%d reflection pairs)", bad, refl);
        mt_arena_destroy(a);
    }
}

typedef struct dn_ctx {
    mt_distribution d;
    mt_mode mode;
} dn_ctx;

static void dn_integrand(void *ctx, double phi, double z, double *out)
{
    const dn_ctx *c = ctx;
    out[0] = mt_distribution_d(&c->d, mt_sphere_direction(phi, z), c->mode) * z;
}

/* The integral of D(wh) cos(theta_h) over the hemisphere is 1. */
void cf_distribution_normalization(cf_rows *rows)
{
    static const double ex[] = {0.5, 10, 1000, 10000, 10, 1, 1000, 0.5};
    static const double ey[] = {-1, -1, -1, -1, 10, 100, 10, 0.5};
    int i;
    for (i = 0; i < 8; ++i) {
        dn_ctx c;
        mt_cubature_result r;
        char name[96];
        double e = fmax(ex[i], ey[i]), tol = 3 * e * EPS + 1e-6;
        c.d = ey[i] < 0 ? mt_blinn((mt_real)ex[i]) : mt_anisotropic((mt_real)ex[i], (mt_real)ey[i]);
        c.mode = MT_MODE_CORRECTED;
        mt_cubature(dn_integrand, &c, 1, 0, 6.283185307179586, 0, 1, 8, 64, 1e-9, 1e-10, 20000000, &r, NULL);
        if (ey[i] < 0)
            snprintf(name, sizeof name, "blinn D e=%g", ex[i]);
        else
            snprintf(name, sizeof name, "anisotropic D %gx%g", ex[i], ey[i]);
        row(rows, name, "both", "int D cos = 1", fabs(r.value[0] - 1) <= tol, "|int - 1| <= tol",
            "%.9f (tol %.1g)", r.value[0], tol);
    }
}

/* Creation rejects what is not a valid parameter, with a message. */
void cf_rejects_invalid(cf_rows *rows)
{
    mt_arena *a = mt_arena_create(0);
    mt_error err;
    mt_diffgeom dg = mt_diffgeom_default();
    mt_bsdf *b;
    mt_real nan = (mt_real)NAN, inf = (mt_real)INFINITY;
    int i, ok = 1;
    struct {
        const char *what;
        mt_bxdf *x;
    } cases[10];
    cases[0].what = "lambertian R = NaN";
    cases[0].x = mt_lambertian_create(a, 0, mt_rgb_make(nan, 0, 0), &err);
    cases[1].what = "orennayar sigma = inf";
    cases[1].x = mt_orennayar_create(a, 0, mt_rgb_gray(1), inf, &err);
    cases[2].what = "specular transmission eta = -1";
    cases[2].x = mt_specular_transmission_create(a, 0, mt_rgb_gray(1), 1, -1, &err);
    cases[3].what = "specular transmission eta = 0";
    cases[3].x = mt_specular_transmission_create(a, 0, mt_rgb_gray(1), 0, 1.5f, &err);
    cases[4].what = "microfacet exponent -1";
    cases[4].x = mt_microfacet_create(a, 0, mt_rgb_gray(1), mt_fresnel_noop(), mt_blinn(-1), &err);
    cases[5].what = "conductor k = -1";
    cases[5].x = mt_microfacet_create(a, 0, mt_rgb_gray(1), mt_fresnel_conductor(mt_rgb_gray(1), mt_rgb_gray(-1)),
                                      mt_blinn(10), &err);
    cases[6].what = "fresnelblend Rs = inf";
    cases[6].x = mt_fresnelblend_create(a, 0, mt_rgb_gray(1), mt_rgb_gray(inf), mt_blinn(10), &err);
    cases[7].what = "scaled scale = NaN";
    cases[7].x = mt_scaled_bxdf_create(a, 0, mt_lambertian_create(a, 0, mt_rgb_gray(1), &err), mt_rgb_gray(nan), &err);
    cases[8].what = "anisotropic ex = -2";
    cases[8].x = mt_fresnelblend_create(a, 0, mt_rgb_gray(1), mt_rgb_gray(1), mt_anisotropic(-2, 1), &err);
    cases[9].what = "specular reflection dielectric eta_t = NaN";
    cases[9].x = mt_specular_reflection_create(a, 0, mt_rgb_gray(1), mt_fresnel_dielectric(1, nan), &err);
    for (i = 0; i < 10; ++i) {
        mt_error_clear(&err);
        if (cases[i].x) ok = 0;
    }
    row(rows, "invalid parameters", "both", "rejected", ok, "all 10 NULL", "%s", ok ? "10 of 10 rejected" : "accepted");
    /* every creator's message names its parameter */
    mt_error_clear(&err);
    mt_orennayar_create(a, 0, mt_rgb_gray(1), nan, &err);
    row(rows, "invalid parameters", "both", "message", err.status == MT_ERR_INVALID && !strcmp(err.param, "sigma"),
        "names the parameter", "\"%s\" (param %s)", err.message, err.param);
    /* a ninth BxDF is an error, never an overflow */
    b = mt_bsdf_create(a, 0, &dg, dg.n, 1, &err);
    for (i = 0; i < 8; ++i) mt_bsdf_add(b, mt_lambertian_create(a, 0, mt_rgb_gray(0.1f), &err), &err);
    mt_error_clear(&err);
    row(rows, "bsdf with 9 BxDFs", "both", "limit",
        mt_bsdf_add(b, mt_lambertian_create(a, 0, mt_rgb_gray(0.1f), &err), &err) == MT_ERR_LIMIT &&
            mt_bsdf_count(b) == 8,
        "MT_ERR_LIMIT, 8 kept", "%s", err.message);
    dg.n = mt_v3(nan, 0, 1);
    row(rows, "bsdf with NaN normal", "both", "rejected", mt_bsdf_create(a, 0, &dg, mt_v3(0, 0, 1), 1, &err) == NULL,
        "NULL", "%s", err.message);
    mt_arena_destroy(a);
}

/* CONFORMANCE.md's furnace table, reproduced by quadrature: Blinn with the
 * V-cavity G at normal incidence (about 0.44 for e = 0.5, 0.90-0.99 for
 * e = 10, 1.000 from e = 50), and the maxima over incidence of Oren-Nayar
 * (<= 1.02; pbrt-v2's qualitative model gains energy at grazing) and of
 * FresnelBlend (<= 0.98). */
void cf_furnace_table(cf_rows *rows)
{
    static const struct {
        double e, lo, hi;
    } blinn[] = {{0.5, 0.43, 0.45}, {10, 0.90, 0.99}, {50, 0.999, 1.001}, {1000, 0.999, 1.001}, {10000, 0.999, 1.001}};
    static const double sigmas[] = {5, 10, 15, 20};
    mt_arena *a = mt_arena_create(0);
    mt_error err;
    char name[96];
    size_t i;
    int k;
    for (i = 0; i < sizeof blinn / sizeof blinn[0]; ++i) {
        mt_bxdf *b = mt_microfacet_create(a, MT_MODE_CORRECTED, mt_rgb_gray(1), mt_fresnel_noop(),
                                          mt_blinn((mt_real)blinn[i].e), &err);
        double r = mt_bxdf_rho_quad(b, mt_v3(0, 0, 1), 1e-7).c[0];
        snprintf(name, sizeof name, "furnace table: blinn e=%g at normal", blinn[i].e);
        row(rows, name, "both", "furnace", r >= blinn[i].lo && r <= blinn[i].hi, "CONFORMANCE.md [Q]",
            "rho %.6f (expected %g..%g)", r, blinn[i].lo, blinn[i].hi);
    }
    for (i = 0; i < sizeof sigmas / sizeof sigmas[0]; ++i) {
        mt_bxdf *b = mt_orennayar_create(a, MT_MODE_CORRECTED, mt_rgb_gray(1), (mt_real)sigmas[i], &err);
        double best = 0, at = 0;
        for (k = 0; k <= 60; ++k) {
            double c = pow(10.0, -3.0 * k / 60), s = sqrt(1 - c * c), r;
            r = mt_bxdf_rho_quad(b, mt_v3((mt_real)s, 0, (mt_real)c), 1e-7).c[0];
            if (r > best) {
                best = r;
                at = c;
            }
        }
        snprintf(name, sizeof name, "furnace table: orennayar sigma=%g, max over incidence", sigmas[i]);
        row(rows, name, "both", "furnace", best <= 1.02, "rho <= 1.02", "max rho %.6f (gain %.2f%%) at cos %.3g", best,
            100 * (best - 1), at);
    }
    for (k = 0; k < 2; ++k) {
        mt_real rs = k ? 0.5f : 0.04f;
        mt_bxdf *b = mt_fresnelblend_create(a, MT_MODE_CORRECTED, mt_rgb_gray(1), mt_rgb_gray(rs), mt_anisotropic(10, 10), &err);
        double best = 0, at = 0;
        int j;
        for (j = 0; j <= 40; ++j) {
            double c = pow(10.0, -3.0 * j / 40), s = sqrt(1 - c * c), r;
            r = mt_bxdf_rho_quad(b, mt_v3((mt_real)s, 0, (mt_real)c), 1e-7).c[0];
            if (r > best) {
                best = r;
                at = c;
            }
        }
        snprintf(name, sizeof name, "furnace table: fresnelblend Rd=1 Rs=%g, max over incidence", (double)rs);
        row(rows, name, "both", "furnace", best <= 0.98, "rho <= 0.98", "max rho %.6f at cos %.3g", best, at);
    }
    mt_arena_destroy(a);
}

/* The light-leak rule on every material: with the geometric normal tilted
 * 37 degrees, f must be the sum of exactly the components on the side the
 * geometric normal decides (reflection when wo and wi are on the same side
 * of it, transmission otherwise), each evaluated in the shading frame. */
void cf_material_leak(cf_rows *rows)
{
    int n, k, mi;
    const cf_subject *subs = cf_material_subjects(&n);
    for (k = 0; k < n; ++k)
        for (mi = 0; mi < 2; ++mi) {
            mt_mode mode = mi ? MT_MODE_CORRECTED : MT_MODE_PBRT_V2;
            cf_subject s = subs[k];
            mt_arena *a = mt_arena_create(0);
            mt_bsdf *b = NULL;
            mt_error err;
            mt_rng rng;
            int i, c, bad = 0, pairs = 0;
            double worst = 0;
            char name[128];
            mt_vec3 ng = mt_v3_normalize(mt_v3(0.5f, 0.1f, 0.8f));
            s.p[0] = ng.x;
            s.p[1] = ng.y;
            s.p[2] = ng.z;
            mt_error_clear(&err);
            if (s.build(&s, a, mode, &b, &err)) {
                row(rows, s.name, mt_mode_name(mode), "leak rule", 0, "builds", "%s", err.message);
                mt_arena_destroy(a);
                continue;
            }
            mt_rng_seed(&rng, 21, 4);
            for (i = 0; i < 5000; ++i) {
                mt_vec3 wo = random_dir(&rng), wi = random_dir(&rng);
                mt_vec3 lo = mt_bsdf_world_to_local(b, wo), li = mt_bsdf_world_to_local(b, wi);
                int reflect = mt_v3_dot(wo, ng) * mt_v3_dot(wi, ng) > 0;
                mt_rgb f = mt_bsdf_f(b, wo, wi, MT_BSDF_ALL), want = mt_rgb_black();
                for (c = 0; c < mt_bsdf_count(b); ++c) {
                    const mt_bxdf *x = mt_bsdf_component(b, c);
                    if (!(mt_bxdf_type(x) & MT_BSDF_REFLECTION) == !reflect) want = mt_rgb_add(want, mt_bxdf_f(x, lo, li));
                }
                for (c = 0; c < 3; ++c) {
                    double d = fabs(f.c[c] - want.c[c]) / fmax(fabs(want.c[c]), 1e-30);
                    worst = fmax(worst, d);
                    if (d > 1e-5) bad++;
                }
                pairs++;
            }
            snprintf(name, sizeof name, "%s (ng tilted)", s.name);
            row(rows, name, mt_mode_name(mode), "leak rule", bad == 0, "0 violations",
                "%d violations in %d pairs (max rel %.2g)", bad, pairs, worst);
            mt_arena_destroy(a);
        }
}
