/*
 * materia/bxdf.h -- BxDFs: pbrt-v2's reflection and transmission models.
 *
 * A BxDF works in the local shading frame (normal +z) on unit directions;
 * wo and wi both point away from the surface. Every BxDF lives in an arena
 * and is described by a kind (an operations table, mt_bxdf_ops) and its type
 * flags, exactly pbrt-v2's BxDFType bits.
 *
 * Each kind has pbrt-v2's name, mathematics, flags and sampling mappings:
 * the same (u1, u2) give the same direction as pbrt-v2. Creators allocate the
 * BxDF in the arena they are given (it lives until the arena is reset or
 * destroyed, and is never freed alone) and return NULL with err filled when
 * the arena is exhausted (MT_ERR_NOMEM) or a parameter is NaN or infinite
 * (MT_ERR_INVALID).
 *
 * Thread safety: creators write only to the arena they are given (one
 * thread at a time per arena); a BxDF is read-only once created, and f,
 * sample_f, pdf and the rho functions may be called on one BxDF from any
 * number of threads at once. The Fresnel and distribution functions are
 * functions of their arguments.
 */
#ifndef MATERIA_BXDF_H
#define MATERIA_BXDF_H

#include "materia/arena.h"
#include "materia/error.h"
#include "materia/mode.h"
#include "materia/rgb.h"
#include "materia/vec.h"

#ifdef __cplusplus
extern "C" {
#endif

/* pbrt-v2 BxDFType bits. */
enum {
    MT_BSDF_REFLECTION = 1 << 0,
    MT_BSDF_TRANSMISSION = 1 << 1,
    MT_BSDF_DIFFUSE = 1 << 2,
    MT_BSDF_GLOSSY = 1 << 3,
    MT_BSDF_SPECULAR = 1 << 4,
    MT_BSDF_ALL_TYPES = MT_BSDF_DIFFUSE | MT_BSDF_GLOSSY | MT_BSDF_SPECULAR,
    MT_BSDF_ALL_REFLECTION = MT_BSDF_REFLECTION | MT_BSDF_ALL_TYPES,
    MT_BSDF_ALL_TRANSMISSION = MT_BSDF_TRANSMISSION | MT_BSDF_ALL_TYPES,
    MT_BSDF_ALL = MT_BSDF_ALL_REFLECTION | MT_BSDF_ALL_TRANSMISSION
};

typedef struct mt_bxdf mt_bxdf;

/* ---- local-frame trigonometry (pbrt-v2 reflection.h) ---------------------- */
static inline mt_real mt_cos_theta(mt_vec3 w) { return w.z; }
static inline mt_real mt_abs_cos_theta(mt_vec3 w) { return mt_fabs(w.z); }
static inline mt_real mt_sin_theta2(mt_vec3 w) { return mt_max(0, 1 - w.z * w.z); }
static inline mt_real mt_sin_theta(mt_vec3 w) { return mt_sqrt(mt_sin_theta2(w)); }
static inline mt_real mt_cos_phi(mt_vec3 w)
{
    mt_real s = mt_sin_theta(w);
    return s == 0 ? 1 : mt_clamp(w.x / s, -1, 1);
}
static inline mt_real mt_sin_phi(mt_vec3 w)
{
    mt_real s = mt_sin_theta(w);
    return s == 0 ? 0 : mt_clamp(w.y / s, -1, 1);
}
static inline int mt_same_hemisphere(mt_vec3 a, mt_vec3 b) { return a.z * b.z > 0; }

/* ---- Fresnel reflectance ----------------------------------------------------
 * A value type: pbrt-v2's Fresnel class hierarchy (FresnelConductor,
 * FresnelDielectric, FresnelNoOp) as a tagged struct. */
typedef enum mt_fresnel_kind {
    MT_FRESNEL_NOOP,
    MT_FRESNEL_CONDUCTOR,
    MT_FRESNEL_DIELECTRIC
} mt_fresnel_kind;

typedef struct mt_fresnel {
    mt_fresnel_kind kind;
    mt_rgb eta, k;        /* conductor */
    mt_real eta_i, eta_t; /* dielectric: index outside (cos > 0) and inside */
} mt_fresnel;

/* The three kinds, by value: a conductor of index eta and absorption k, a
 * dielectric between eta_i (outside) and eta_t (inside), and no Fresnel
 * factor (1 everywhere). */
MT_API mt_fresnel mt_fresnel_conductor(mt_rgb eta, mt_rgb k);
MT_API mt_fresnel mt_fresnel_dielectric(mt_real eta_i, mt_real eta_t);
MT_API mt_fresnel mt_fresnel_noop(void);
/* Fresnel::Evaluate: reflectance for the cosine of the incident angle; for
 * dielectrics a negative cosine means the direction is inside (eta_t side). */
MT_API mt_rgb mt_fresnel_evaluate(const mt_fresnel *f, mt_real cosi);
/* pbrt-v2 FrDiel: unpolarized dielectric reflectance for cosines cosi, cost. */
MT_API mt_rgb mt_fr_diel(mt_real cosi, mt_real cost, mt_rgb etai, mt_rgb etat);
/* pbrt-v2 FrCond: the conductor approximation for cosi >= 0. */
MT_API mt_rgb mt_fr_cond(mt_real cosi, mt_rgb eta, mt_rgb k);
/* pbrt-v2 FresnelApproxEta / FresnelApproxK: the eta and k of a conductor with
 * normal-incidence reflectance Fr (clamped to [0, 0.999]), for shinymetal. */
MT_API mt_rgb mt_fresnel_approx_eta(mt_rgb fr);
MT_API mt_rgb mt_fresnel_approx_k(mt_rgb fr);

/* ---- microfacet distributions -----------------------------------------------
 * pbrt-v2's Blinn and Anisotropic (Ashikhmin-Shirley) distributions. Exponents
 * above 10000 or NaN become 10000, as in pbrt-v2. */
typedef enum mt_distribution_kind { MT_DIST_BLINN, MT_DIST_ANISOTROPIC } mt_distribution_kind;

typedef struct mt_distribution {
    mt_distribution_kind kind;
    mt_real exponent; /* Blinn */
    mt_real ex, ey;   /* Anisotropic */
} mt_distribution;

/* Blinn with one exponent, Anisotropic with one along x and one along y. */
MT_API mt_distribution mt_blinn(mt_real exponent);
MT_API mt_distribution mt_anisotropic(mt_real ex, mt_real ey);
/* D(wh): microfacet normal density, with integral of D cos over the hemisphere 1. */
MT_API mt_real mt_distribution_d(const mt_distribution *d, mt_vec3 wh, mt_mode mode);
/* Samples wi by sampling wh and reflecting wo about it; *pdf is the density of
 * wi per solid angle (0 when wo and wh face away from each other). */
MT_API void mt_distribution_sample(const mt_distribution *d, mt_vec3 wo, mt_real u1,
                                   mt_real u2, mt_vec3 *wi, mt_real *pdf, mt_mode mode);
MT_API mt_real mt_distribution_pdf(const mt_distribution *d, mt_vec3 wo, mt_vec3 wi,
                                   mt_mode mode);

/* ---- creators ------------------------------------------------------------- */
/* Lambertian: R / pi. */
MT_API mt_bxdf *mt_lambertian_create(mt_arena *a, mt_mode mode, mt_rgb R, mt_error *err);
/* OrenNayar: pbrt-v2's qualitative model; sigma is in degrees. */
MT_API mt_bxdf *mt_orennayar_create(mt_arena *a, mt_mode mode, mt_rgb R, mt_real sigma_deg,
                                    mt_error *err);
/* SpecularReflection: R times the Fresnel reflectance, a delta lobe. */
MT_API mt_bxdf *mt_specular_reflection_create(mt_arena *a, mt_mode mode, mt_rgb R,
                                              mt_fresnel fresnel, mt_error *err);
/* SpecularTransmission: T (1 - F) through a dielectric with index etai on the
 * +z side and etat on the -z side. Indices must be positive and finite. */
MT_API mt_bxdf *mt_specular_transmission_create(mt_arena *a, mt_mode mode, mt_rgb T,
                                                mt_real etai, mt_real etat, mt_error *err);
/* Microfacet: Torrance-Sparrow with the V-cavity G. */
MT_API mt_bxdf *mt_microfacet_create(mt_arena *a, mt_mode mode, mt_rgb R, mt_fresnel fresnel,
                                     mt_distribution dist, mt_error *err);
/* FresnelBlend: Ashikhmin-Shirley's diffuse substrate under a glossy coat. */
MT_API mt_bxdf *mt_fresnelblend_create(mt_arena *a, mt_mode mode, mt_rgb Rd, mt_rgb Rs,
                                       mt_distribution dist, mt_error *err);
/* ScaledBxDF: scale times bxdf (a mix's components). */
MT_API mt_bxdf *mt_scaled_bxdf_create(mt_arena *a, mt_mode mode, mt_bxdf *bxdf, mt_rgb scale,
                                      mt_error *err);
/* BRDFToBTDF: the BRDF mirrored into the other hemisphere. */
MT_API mt_bxdf *mt_brdf_to_btdf_create(mt_arena *a, mt_mode mode, mt_bxdf *brdf,
                                       mt_error *err);

/* ---- evaluation ------------------------------------------------------------
 * Directions that are NaN, infinite or zero give black and pdf 0; directions
 * of other lengths are normalized first. */
/* f(wo, wi) in the local frame. */
MT_API mt_rgb mt_bxdf_f(const mt_bxdf *b, mt_vec3 wo, mt_vec3 wi);
/* Samples *wi for wo from (u1, u2) in [0,1)^2; returns f(wo, *wi) and sets
 * *pdf (0 when no direction could be sampled). Every kind keeps this
 * contract when *wi lies on its own side (wo's for reflection, the other for
 * transmission): the BSDF relies on it. */
MT_API mt_rgb mt_bxdf_sample_f(const mt_bxdf *b, mt_vec3 wo, mt_real u1, mt_real u2,
                               mt_vec3 *wi, mt_real *pdf);
/* The density per solid angle with which sample_f gives wi for wo. */
MT_API mt_real mt_bxdf_pdf(const mt_bxdf *b, mt_vec3 wo, mt_vec3 wi);
/* pbrt-v2's Monte Carlo reflectances: hemispherical-directional from n 2D
 * samples (samples holds 2 n values in [0, 1)), hemispherical-hemispherical
 * from two arrays of n 2D samples. */
MT_API mt_rgb mt_bxdf_rho_hd(const mt_bxdf *b, mt_vec3 wo, int n, const mt_real *samples);
MT_API mt_rgb mt_bxdf_rho_hh(const mt_bxdf *b, int n, const mt_real *s1, const mt_real *s2);

/* The BxDF's MT_BSDF_* type bits, its kind's name ("lambertian", ...) as a
 * static string, and the mode it was created with. */
MT_API unsigned mt_bxdf_type(const mt_bxdf *b);
MT_API const char *mt_bxdf_name(const mt_bxdf *b);
MT_API mt_mode mt_bxdf_mode(const mt_bxdf *b);
/* pbrt-v2 BxDF::MatchesFlags: every bit of the type is in flags. */
static inline int mt_type_matches(unsigned type, unsigned flags) { return (type & flags) == type; }

/* ---- extension interface ----------------------------------------------------
 * A kind of BxDF is an operations table. A new kind embeds mt_bxdf as the first
 * member of its struct, points ops at its table, and is allocated by
 * mt_bxdf_alloc. Every function of the table is required (point sample_f,
 * pdf and the rho ones at the default_* functions below for pbrt-v2's BxDF
 * base-class behaviour: cosine sampling and pdf, Monte Carlo rho); each must
 * be safe to call from any number of threads at once on one BxDF, return
 * finite values for finite input and keep mt_bxdf_sample_f's contract. ops
 * and its name must outlive the BxDF (a static table). */
typedef struct mt_bxdf_ops {
    const char *name;
    mt_rgb (*f)(const mt_bxdf *b, mt_vec3 wo, mt_vec3 wi);
    mt_rgb (*sample_f)(const mt_bxdf *b, mt_vec3 wo, mt_vec3 *wi, mt_real u1, mt_real u2,
                       mt_real *pdf);
    mt_real (*pdf)(const mt_bxdf *b, mt_vec3 wo, mt_vec3 wi);
    mt_rgb (*rho_hd)(const mt_bxdf *b, mt_vec3 wo, int n, const mt_real *samples);
    mt_rgb (*rho_hh)(const mt_bxdf *b, int n, const mt_real *s1, const mt_real *s2);
} mt_bxdf_ops;

struct mt_bxdf {
    const mt_bxdf_ops *ops;
    unsigned type;
    mt_mode mode;
};

/* size bytes (at least sizeof(mt_bxdf)) from the arena, with the base
 * initialized and the rest uninitialized. NULL (err filled) when the arena is
 * exhausted. */
MT_API void *mt_bxdf_alloc(mt_arena *a, size_t size, const mt_bxdf_ops *ops, unsigned type,
                           mt_mode mode, mt_error *err);
MT_API mt_rgb mt_bxdf_default_sample_f(const mt_bxdf *b, mt_vec3 wo, mt_vec3 *wi, mt_real u1,
                                       mt_real u2, mt_real *pdf);
MT_API mt_real mt_bxdf_default_pdf(const mt_bxdf *b, mt_vec3 wo, mt_vec3 wi);
MT_API mt_rgb mt_bxdf_default_rho_hd(const mt_bxdf *b, mt_vec3 wo, int n,
                                     const mt_real *samples);
MT_API mt_rgb mt_bxdf_default_rho_hh(const mt_bxdf *b, int n, const mt_real *s1,
                                     const mt_real *s2);

#ifdef __cplusplus
}
#endif

#endif
