/*
 * The catalog of configurations the suite checks: every analytic BxDF over
 * its parameters (extremes included) and the combinations the materials
 * build, each with the furnace expectation CONFORMANCE.md gives for it.
 * p[] holds the builder's parameters; colours are albedo 1 where the
 * furnace has an expectation.
 */
#include "conformance.h"

#define ADD(x)                                                  \
    do {                                                        \
        mt_status st_ = mt_bsdf_add(b, (x), err);               \
        if (st_) return st_;                                    \
    } while (0)

static mt_bsdf *new_bsdf(mt_arena *a, mt_mode mode, mt_real eta, mt_error *err)
{
    mt_diffgeom dg = mt_diffgeom_default();
    return mt_bsdf_create(a, mode, &dg, dg.n, eta, err);
}

static mt_rgb rgb3(const double *p) { return mt_rgb_make((mt_real)p[0], (mt_real)p[1], (mt_real)p[2]); }

/* p[0] kind: 0 Blinn(p[1]), 1 Anisotropic(p[1], p[2]) */
static mt_distribution dist_of(const double *p)
{
    return p[0] == 0 ? mt_blinn((mt_real)p[1]) : mt_anisotropic((mt_real)p[1], (mt_real)p[2]);
}

/* p[0] kind: 0 NoOp, 1 dielectric(p[1], p[2]), 2 conductor(eta p[1], k p[2]) */
static mt_fresnel fresnel_of(const double *p)
{
    if (p[0] == 1) return mt_fresnel_dielectric((mt_real)p[1], (mt_real)p[2]);
    if (p[0] == 2) return mt_fresnel_conductor(mt_rgb_gray((mt_real)p[1]), mt_rgb_gray((mt_real)p[2]));
    return mt_fresnel_noop();
}

static mt_status b_lambertian(const cf_subject *s, mt_arena *a, mt_mode m, mt_bsdf **out, mt_error *err)
{
    mt_bsdf *b = *out = new_bsdf(a, m, 1, err);
    if (!b) return err->status;
    ADD(mt_lambertian_create(a, m, rgb3(s->p), err));
    return MT_OK;
}

static mt_status b_orennayar(const cf_subject *s, mt_arena *a, mt_mode m, mt_bsdf **out, mt_error *err)
{
    mt_bsdf *b = *out = new_bsdf(a, m, 1, err);
    if (!b) return err->status;
    ADD(mt_orennayar_create(a, m, mt_rgb_gray(1), (mt_real)s->p[0], err));
    return MT_OK;
}

/* p = fresnel kind and arguments */
static mt_status b_specular_reflection(const cf_subject *s, mt_arena *a, mt_mode m, mt_bsdf **out,
                                       mt_error *err)
{
    mt_bsdf *b = *out = new_bsdf(a, m, 1, err);
    if (!b) return err->status;
    ADD(mt_specular_reflection_create(a, m, mt_rgb_gray(1), fresnel_of(s->p), err));
    return MT_OK;
}

/* glass: p[0] = eta, p[1] = 1 to include the reflection lobe */
static mt_status b_glass(const cf_subject *s, mt_arena *a, mt_mode m, mt_bsdf **out, mt_error *err)
{
    mt_real eta = (mt_real)s->p[0];
    mt_bsdf *b = *out = new_bsdf(a, m, eta, err);
    if (!b) return err->status;
    if (s->p[1] != 0)
        ADD(mt_specular_reflection_create(a, m, mt_rgb_gray(1), mt_fresnel_dielectric(1, eta), err));
    ADD(mt_specular_transmission_create(a, m, mt_rgb_gray(1), 1, eta, err));
    return MT_OK;
}

/* p[0..2] distribution, p[3..5] fresnel */
static mt_status b_microfacet(const cf_subject *s, mt_arena *a, mt_mode m, mt_bsdf **out, mt_error *err)
{
    mt_bsdf *b = *out = new_bsdf(a, m, 1, err);
    if (!b) return err->status;
    ADD(mt_microfacet_create(a, m, mt_rgb_gray(1), fresnel_of(s->p + 3), dist_of(s->p), err));
    return MT_OK;
}

/* p[0..2] distribution, p[3] Rd, p[4] Rs */
static mt_status b_fresnelblend(const cf_subject *s, mt_arena *a, mt_mode m, mt_bsdf **out, mt_error *err)
{
    mt_bsdf *b = *out = new_bsdf(a, m, 1, err);
    if (!b) return err->status;
    ADD(mt_fresnelblend_create(a, m, mt_rgb_gray((mt_real)s->p[3]), mt_rgb_gray((mt_real)s->p[4]),
                               dist_of(s->p), err));
    return MT_OK;
}

/* p[0] 0: scaled Lambertian, 1: scaled Blinn(p[2]) microfacet; p[1] scale */
static mt_status b_scaled(const cf_subject *s, mt_arena *a, mt_mode m, mt_bsdf **out, mt_error *err)
{
    mt_bsdf *b = *out = new_bsdf(a, m, 1, err);
    mt_bxdf *inner;
    if (!b) return err->status;
    inner = s->p[0] == 0 ? mt_lambertian_create(a, m, mt_rgb_gray(1), err)
                         : mt_microfacet_create(a, m, mt_rgb_gray(1), mt_fresnel_noop(),
                                                mt_blinn((mt_real)s->p[2]), err);
    ADD(mt_scaled_bxdf_create(a, m, inner, mt_rgb_gray((mt_real)s->p[1]), err));
    return MT_OK;
}

/* p[0] 0: Lambertian, 1: Blinn(p[1]) with dielectric (p[2], p[3]) */
static mt_status b_btdf(const cf_subject *s, mt_arena *a, mt_mode m, mt_bsdf **out, mt_error *err)
{
    mt_bsdf *b = *out = new_bsdf(a, m, 1, err);
    mt_bxdf *inner;
    if (!b) return err->status;
    inner = s->p[0] == 0 ? mt_lambertian_create(a, m, mt_rgb_gray(1), err)
                         : mt_microfacet_create(a, m, mt_rgb_gray(1),
                                                mt_fresnel_dielectric((mt_real)s->p[2], (mt_real)s->p[3]),
                                                mt_blinn((mt_real)s->p[1]), err);
    ADD(mt_brdf_to_btdf_create(a, m, inner, err));
    return MT_OK;
}

/* plastic as pbrt-v2 builds it: Lambertian(kd) + Microfacet(ks, (1.5, 1) or
 * corrected (1, 1.5), Blinn(1/roughness)); p = kd, ks, roughness */
static mt_status b_plastic(const cf_subject *s, mt_arena *a, mt_mode m, mt_bsdf **out, mt_error *err)
{
    mt_bsdf *b = *out = new_bsdf(a, m, 1, err);
    mt_fresnel fr = (m & MT_FIX_DIELECTRIC_SIDE) ? mt_fresnel_dielectric(1, 1.5f)
                                                 : mt_fresnel_dielectric(1.5f, 1);
    if (!b) return err->status;
    ADD(mt_lambertian_create(a, m, mt_rgb_gray((mt_real)s->p[0]), err));
    ADD(mt_microfacet_create(a, m, mt_rgb_gray((mt_real)s->p[1]), fr, mt_blinn((mt_real)(1 / s->p[2])),
                             err));
    return MT_OK;
}

/* translucent as pbrt-v2 builds it, kd = ks = p[0], reflect = transmit = p[1] */
static mt_status b_translucent(const cf_subject *s, mt_arena *a, mt_mode m, mt_bsdf **out, mt_error *err)
{
    mt_real k = (mt_real)s->p[0], rt = (mt_real)s->p[1];
    mt_bsdf *b = *out = new_bsdf(a, m, 1.5f, err);
    mt_fresnel fr = (m & MT_FIX_DIELECTRIC_SIDE) ? mt_fresnel_dielectric(1, 1.5f)
                                                 : mt_fresnel_dielectric(1.5f, 1);
    if (!b) return err->status;
    ADD(mt_lambertian_create(a, m, mt_rgb_gray(k * rt), err));
    ADD(mt_brdf_to_btdf_create(a, m, mt_lambertian_create(a, m, mt_rgb_gray(k * rt), err), err));
    ADD(mt_microfacet_create(a, m, mt_rgb_gray(k * rt), fr, mt_blinn(10), err));
    ADD(mt_brdf_to_btdf_create(a, m, mt_microfacet_create(a, m, mt_rgb_gray(k * rt), fr, mt_blinn(10), err),
                               err));
    return MT_OK;
}

/* a mix as pbrt-v2's MixMaterial builds it: matte and plastic components
 * scaled by (1 - amount) and amount; p[0] = amount */
static mt_status b_mix(const cf_subject *s, mt_arena *a, mt_mode m, mt_bsdf **out, mt_error *err)
{
    mt_real t = (mt_real)s->p[0];
    mt_bsdf *b = *out = new_bsdf(a, m, 1, err);
    if (!b) return err->status;
    ADD(mt_scaled_bxdf_create(a, m, mt_lambertian_create(a, m, mt_rgb_gray(1), err), mt_rgb_gray(1 - t), err));
    ADD(mt_scaled_bxdf_create(a, m, mt_lambertian_create(a, m, mt_rgb_gray(0.5f), err), mt_rgb_gray(t), err));
    ADD(mt_scaled_bxdf_create(a, m, mt_microfacet_create(a, m, mt_rgb_gray(0.5f), mt_fresnel_noop(),
                                                         mt_blinn(10), err),
                              mt_rgb_gray(t), err));
    return MT_OK;
}

/* shinymetal-like: Microfacet + SpecularReflection with one conductor */
static mt_status b_shiny(const cf_subject *s, mt_arena *a, mt_mode m, mt_bsdf **out, mt_error *err)
{
    mt_bsdf *b = *out = new_bsdf(a, m, 1, err);
    /* as shinymetal.cpp: FresnelApproxEta, k = 0 */
    mt_fresnel fr = mt_fresnel_conductor(mt_fresnel_approx_eta(mt_rgb_gray((mt_real)s->p[0])), mt_rgb_black());
    if (!b) return err->status;
    ADD(mt_microfacet_create(a, m, mt_rgb_gray(1), fr, mt_blinn(10), err));
    ADD(mt_specular_reflection_create(a, m, mt_rgb_gray(1), fr, err));
    return MT_OK;
}

#define LE1 CF_FURNACE_LE1
#define EXACT CF_FURNACE_EXACT
#define DELTA CF_NO_CHI2
#define BOTH CF_TWO_SIDED

static const cf_subject subjects[] = {
    {"lambertian R=1", "lambertian", b_lambertian, {1, 1, 1}, EXACT, 1, 0, NULL},
    {"lambertian R=(0.2,0.5,0.9)", "lambertian", b_lambertian, {0.2, 0.5, 0.9}, LE1, 0, 0, NULL},
    {"orennayar sigma=5", "orennayar", b_orennayar, {5}, CF_FURNACE_LE, 1.02, 0, NULL},
    {"orennayar sigma=10", "orennayar", b_orennayar, {10}, CF_FURNACE_LE, 1.02, 0, NULL},
    {"orennayar sigma=15", "orennayar", b_orennayar, {15}, CF_FURNACE_LE, 1.02, 0, NULL},
    {"orennayar sigma=30", "orennayar", b_orennayar, {30}, CF_FURNACE_LE, 1.02, 0, NULL},
    {"orennayar sigma=90", "orennayar", b_orennayar, {90}, CF_FURNACE_LE, 1.02, 0, NULL},
    {"specular_reflection noop (mirror)", "specular_reflection", b_specular_reflection, {0}, EXACT | DELTA | BOTH, 1, 0, NULL},
    {"specular_reflection conductor eta=0.2 k=3", "specular_reflection", b_specular_reflection, {2, 0.2, 3}, LE1 | DELTA, 0, 0, NULL},
    {"specular_reflection conductor eta=1.5 k=0", "specular_reflection", b_specular_reflection, {2, 1.5, 0}, LE1 | DELTA, 0, 0, NULL},
    {"specular_reflection dielectric 1/1.5", "specular_reflection", b_specular_reflection, {1, 1, 1.5}, LE1 | DELTA | BOTH, 0, 0, NULL},
    {"glass eta=1.5", "specular_transmission", b_glass, {1.5, 1}, EXACT | DELTA | BOTH, 1, 0, NULL},
    {"glass eta=1.000001", "specular_transmission", b_glass, {1.000001, 1}, EXACT | DELTA | BOTH, 1, 0, NULL},
    {"glass eta=4", "specular_transmission", b_glass, {4, 1}, EXACT | DELTA | BOTH, 1, 0, NULL},
    {"glass eta=1/1.5", "specular_transmission", b_glass, {1 / 1.5, 1}, EXACT | DELTA | BOTH, 1, 0, NULL},
    {"specular_transmission alone eta=1.5", "specular_transmission", b_glass, {1.5, 0}, LE1 | DELTA | BOTH, 0, 0, NULL},
    /* materia's radiance-transmission option: the energy, Helmholtz and
     * reciprocity in the radiance form */
    {"glass eta=1.5 (radiance transport)", "specular_transmission", b_glass, {1.5, 1}, EXACT | DELTA | BOTH | CF_RADIANCE_OPT, 1, 0, NULL},
    {"glass eta=4 (radiance transport)", "specular_transmission", b_glass, {4, 1}, EXACT | DELTA | BOTH | CF_RADIANCE_OPT, 1, 0, NULL},
    {"microfacet blinn e=0.5 noop", "microfacet", b_microfacet, {0, 0.5, 0, 0}, LE1, 0, 0.5, NULL},
    {"microfacet blinn e=1 noop", "microfacet", b_microfacet, {0, 1, 0, 0}, LE1, 0, 1, NULL},
    {"microfacet blinn e=10 noop", "microfacet", b_microfacet, {0, 10, 0, 0}, LE1, 0, 10, NULL},
    {"microfacet blinn e=50 noop", "microfacet", b_microfacet, {0, 50, 0, 0}, LE1, 0, 50, NULL},
    {"microfacet blinn e=1000 noop", "microfacet", b_microfacet, {0, 1000, 0, 0}, LE1, 0, 1000, NULL},
    {"microfacet blinn e=10000 noop", "microfacet", b_microfacet, {0, 10000, 0, 0}, LE1, 0, 10000, NULL},
    {"microfacet blinn e=10 dielectric 1/1.5", "microfacet", b_microfacet, {0, 10, 0, 1, 1, 1.5}, LE1 | BOTH, 0, 10, NULL},
    {"microfacet blinn e=10 dielectric 1.5/1", "microfacet", b_microfacet, {0, 10, 0, 1, 1.5, 1}, LE1 | BOTH, 0, 10, NULL},
    {"microfacet blinn e=100 conductor eta=0.2 k=3", "microfacet", b_microfacet, {0, 100, 0, 2, 0.2, 3}, LE1, 0, 100, NULL},
    {"microfacet anisotropic 10x10 noop", "microfacet", b_microfacet, {1, 10, 10, 0}, LE1, 0, 10, NULL},
    {"microfacet anisotropic 1x100 noop", "microfacet", b_microfacet, {1, 1, 100, 0}, LE1, 0, 100, NULL},
    {"microfacet anisotropic 1000x10 noop", "microfacet", b_microfacet, {1, 1000, 10, 0}, LE1, 0, 1000, NULL},
    {"microfacet anisotropic 0.5x0.5 noop", "microfacet", b_microfacet, {1, 0.5, 0.5, 0}, LE1, 0, 0.5, NULL},
    {"fresnelblend aniso 10x10 Rd=1 Rs=0.04", "fresnelblend", b_fresnelblend, {1, 10, 10, 1, 0.04}, CF_FURNACE_LE, 0.98, 10, NULL},
    {"fresnelblend aniso 10x10 Rd=1 Rs=0.5", "fresnelblend", b_fresnelblend, {1, 10, 10, 1, 0.5}, CF_FURNACE_LE, 0.98, 10, NULL},
    {"fresnelblend aniso 1x100 Rd=0.5 Rs=0.5", "fresnelblend", b_fresnelblend, {1, 1, 100, 0.5, 0.5}, CF_FURNACE_LE, 0.98, 100, NULL},
    {"fresnelblend blinn 1000 Rd=1 Rs=0.04", "fresnelblend", b_fresnelblend, {0, 1000, 0, 1, 0.04}, CF_FURNACE_LE, 0.98, 1000, NULL},
    {"scaled lambertian x0.5", "scaled", b_scaled, {0, 0.5}, CF_FURNACE_EXACT, 0.5, 0, NULL},
    {"scaled microfacet blinn 10 x0.7", "scaled", b_scaled, {1, 0.7, 10}, LE1, 0, 10, NULL},
    {"brdf_to_btdf lambertian", "brdf_to_btdf", b_btdf, {0}, EXACT | BOTH, 1, 0, NULL},
    {"brdf_to_btdf microfacet blinn 10 dielectric 1/1.5", "brdf_to_btdf", b_btdf, {1, 10, 1, 1.5}, LE1 | BOTH, 0, 10, NULL},
    {"brdf_to_btdf microfacet blinn 10 dielectric 1.5/1", "brdf_to_btdf", b_btdf, {1, 10, 1.5, 1}, LE1 | BOTH, 0, 10, NULL},
    {"plastic-like kd=0.25 ks=0.25 r=0.1", "combination", b_plastic, {0.25, 0.25, 0.1}, LE1 | BOTH, 0, 10, NULL},
    {"plastic-like kd=0.5 ks=0.5 r=0.001", "combination", b_plastic, {0.5, 0.5, 0.001}, LE1, 0, 1000, NULL},
    {"translucent-like k=0.5 r=t=1 (additive)", "combination", b_translucent, {0.5, 1}, BOTH, 0, 10, NULL},
    {"translucent-like k=0.25 r=t=0.5", "combination", b_translucent, {0.25, 0.5}, LE1 | BOTH, 0, 10, NULL},
    {"mix-like amount=0.3", "combination", b_mix, {0.3}, LE1, 0, 10, NULL},
    {"shinymetal-like Ks=Kr=0.5", "combination", b_shiny, {0.5}, 0, 0, 10, NULL},
};

const cf_subject *cf_subjects(int *count)
{
    *count = (int)(sizeof subjects / sizeof subjects[0]);
    return subjects;
}
