/*
 * materia/material.h -- pbrt-v2's materials.
 *
 * A material is a reference-counted, read-only handle created from a pbrt-v2
 * parameter list by name (matte, plastic, glass, mirror, metal, shinymetal,
 * substrate, translucent, uber, mix, measured, subsurface, kdsubsurface), with
 * pbrt-v2's parameter names and defaults. At a shading point it builds a BSDF
 * in the caller's arena (bump mapping first when "bumpmap" is given), and the
 * two subsurface materials also give BSSRDF coefficients. Materials are safe
 * to share between threads; each thread passes its own arena.
 */
#ifndef MATERIA_MATERIAL_H
#define MATERIA_MATERIAL_H

#include "materia/bsdf.h"
#include "materia/texture.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct mt_material mt_material;

/* pbrt-v2's BSSRDF: the reduced scattering and absorption coefficients (per
 * mm in the units the scene uses, scale applied) and the relative index. */
typedef struct mt_bssrdf {
    mt_rgb sigma_a, sigma_prime_s;
    mt_real eta;
} mt_bssrdf;

/* Looks up a named material (MakeNamedMaterial) for the mix material; NULL
 * when there is none. Returns a borrowed pointer. A lookup that builds the
 * material and fails (out of memory) may record its error in the mt_error
 * given to the creator: the mix creator then reports that error, not an
 * undefined name. */
typedef const mt_material *(*mt_material_lookup_fn)(void *ctx, const char *name);

typedef struct mt_material_ctx {
    mt_material_lookup_fn lookup; /* may be NULL: then "mix" cannot be created */
    void *lookup_ctx;
    mt_warning_fn warn;           /* warnings (pbrt-v2's); may be NULL */
    void *warn_ctx;
} mt_material_ctx;

/* Creates the material of pbrt-v2 type `type` from tp (TextureParams:
 * geometry parameters first, then the material's), declared under the
 * transform mtl2world. NULL with err naming the parameter for an unknown
 * type, a bad parameter or a file that cannot be read. */
MT_API mt_material *mt_material_create(const char *type, const mt_transform *mtl2world,
                                       const mt_texparams *tp, const mt_material_ctx *ctx,
                                       mt_error *err);

MT_API mt_material *mt_material_retain(mt_material *m);
MT_API void mt_material_release(mt_material *m);
MT_API const char *mt_material_type(const mt_material *m);
MT_API mt_mode mt_material_mode(const mt_material *m);

/* The BSDF at a shading point: dg_geom carries the geometric normal (n) and
 * dg_shading the shading frame, as pbrt-v2's Material::GetBSDF receives them.
 * NULL with err filled when the arena is exhausted or the geometry invalid. */
MT_API mt_bsdf *mt_material_get_bsdf(const mt_material *m, const mt_diffgeom *dg_geom,
                                     const mt_diffgeom *dg_shading, mt_arena *arena,
                                     mt_error *err);

/* 1 and *out filled for the subsurface materials, 0 for the others. */
MT_API int mt_material_get_bssrdf(const mt_material *m, const mt_diffgeom *dg_geom,
                                  const mt_diffgeom *dg_shading, mt_bssrdf *out);

/* pbrt-v2's Fdr: the hemispherically averaged Fresnel reflectance of a
 * dielectric of relative index eta (polynomial fits). */
MT_API mt_real mt_fdr(mt_real eta);

/* pbrt-v2's SubsurfaceFromDiffuse: the sigma_a and sigma'_s that give the
 * dipole a diffuse reflectance kd with mean free path mfp and index eta (per
 * channel, by 16 bisection steps on the reduced albedo). */
MT_API void mt_subsurface_from_diffuse(mt_rgb kd, mt_real mfp, mt_real eta, mt_rgb *sigma_a,
                                       mt_rgb *sigma_prime_s);

/* The material a Shape would get now from the graphics state: the one
 * NamedMaterial selected (created from its MakeNamedMaterial parameters) or
 * the last Material statement's, with shape_params (may be NULL) read first
 * as pbrt-v2's GraphicsState::CreateMaterial does; a mix finds its named
 * materials in the state. NULL with err filled on any error. */
struct mt_state;
MT_API mt_material *mt_material_from_state(const struct mt_state *s, const mt_paramset *shape_params,
                                           mt_error *err);

/* The material MakeNamedMaterial "name" defined (pbrt-v2 creates it at that
 * statement: errors in its parameters show there). NULL with err filled. */
MT_API mt_material *mt_material_named_from_state(const struct mt_state *s, const char *name, mt_error *err);

/* ---- material kinds and the registry ----------------------------------------
 * A kind is one of pbrt-v2's material types. The registry lists every kind
 * once, in MT_MATERIAL_KINDS: X(name) declares the kind's object
 * mt_<name>_material (defined in src/materials/<file>.c), and the registry's
 * functions below iterate the same list. Creating by name (mt_material_create,
 * mt_material_kind_find, a scene) links every kind into a static program;
 * creating from a kind's object (mt_material_create_kind) links that kind and
 * what it uses alone. */
typedef struct mt_material_kind mt_material_kind;

#define MT_MATERIAL_KINDS(X)                                                               \
    X(matte) X(plastic) X(glass) X(mirror) X(metal) X(shinymetal) X(substrate)             \
    X(translucent) X(uber) X(mix) X(measured) X(subsurface) X(kdsubsurface)

#define MT_MATERIAL_KIND_DECLARE_(name) MT_API extern const mt_material_kind mt_##name##_material;
MT_MATERIAL_KINDS(MT_MATERIAL_KIND_DECLARE_)

/* As mt_material_create, for the kind k (e.g. &mt_plastic_material). */
MT_API mt_material *mt_material_create_kind(const mt_material_kind *k, const mt_transform *mtl2world,
                                            const mt_texparams *tp, const mt_material_ctx *ctx,
                                            mt_error *err);
/* The kind's pbrt-v2 name ("plastic"). */
MT_API const char *mt_material_kind_name(const mt_material_kind *k);
/* 1 when the kind gives BSSRDF coefficients (mt_material_get_bssrdf): a
 * renderer needs a subsurface integrator for it. */
MT_API int mt_material_kind_has_bssrdf(const mt_material_kind *k);

/* The registry: the number of kinds, the i-th (0 <= i < count, in
 * MT_MATERIAL_KINDS order; NULL outside), and the kind of a pbrt-v2 name
 * (NULL when there is none). */
MT_API int mt_material_kind_count(void);
MT_API const mt_material_kind *mt_material_kind_at(int i);
MT_API const mt_material_kind *mt_material_kind_find(const char *name);

/* The kinds' names in registry order; *count (may be NULL) receives their
 * number. */
MT_API const char *const *mt_material_types(int *count);

#ifdef __cplusplus
}
#endif

#endif
