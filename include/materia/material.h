/*
 * materia/material.h -- pbrt-v2's materials.
 *
 * A material is made from a pbrt-v2 parameter list by type name (matte,
 * plastic, glass, mirror, metal, shinymetal, substrate, translucent, uber,
 * mix, measured, subsurface, kdsubsurface), with pbrt-v2's parameter names
 * and defaults (docs/REFERENCE.md lists them, with their ranges). At a
 * shading point it builds a BSDF in the caller's arena (bump mapping first
 * when "bumpmap" is given), and the two subsurface materials also give BSSRDF
 * coefficients.
 *
 * The short ways: mt_material_from_text (pbrt-v2 statements) and
 * mt_material_from_params (typed parameters), below. mt_material_from_state
 * makes the material a graphics state holds; mt_material_create is the
 * low-level constructor they are built on.
 *
 * Lifetime: every function that returns a material returns a new reference,
 * which mt_material_destroy ends; mt_material_retain gives another. A
 * material holds references to its textures and measured data: they live as
 * long as it does.
 *
 * Thread safety: a material is read-only once created: any number of
 * threads may build BSDFs from it at once, each in its own arena, and
 * retain and destroy it (atomic reference counts).
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

/* For mt_material_create: looks up a named material (MakeNamedMaterial) for
 * the mix material; NULL when there is none. Returns a borrowed pointer,
 * valid until the creator returns (the mix retains what it keeps). A lookup
 * that builds the material and fails (out of memory) may record its error in
 * the mt_error given to the creator: the mix creator then reports that
 * error, not an undefined name. */
typedef const mt_material *(*mt_material_lookup_fn)(void *ctx, const char *name);

typedef struct mt_material_ctx {
    mt_material_lookup_fn lookup; /* may be NULL: then "mix" cannot be created */
    void *lookup_ctx;
} mt_material_ctx;

/* The low-level constructor: the material of pbrt-v2 type `type` from tp
 * (pbrt-v2's TextureParams: the geometry's parameters first, then the
 * material's; named textures from tp->textures, which may be NULL; tp->mode),
 * declared under the transform mtl2world (NULL: the identity). ctx may be
 * NULL (no named materials). The lists are read, not kept, and their
 * parameters marked used: reporting those left unused is the caller's
 * (mt_paramset_report_unused); mt_material_from_text and
 * mt_material_from_params do it. A new reference, or NULL with err naming
 * the parameter: an unknown type (MT_ERR_NOT_FOUND), a parameter of the
 * wrong type or out of its range, an undefined texture, a file that cannot
 * be read. */
MT_API mt_material *mt_material_create(const char *type, const mt_transform *mtl2world,
                                       const mt_texparams *tp, const mt_material_ctx *ctx,
                                       mt_error *err);

/* Another reference to m (returned; m may be NULL), and the end of one. */
MT_API mt_material *mt_material_retain(mt_material *m);
MT_API void mt_material_destroy(mt_material *m);
/* The type name ("plastic", a static string) and the mode it was made in. */
MT_API const char *mt_material_type(const mt_material *m);
MT_API mt_mode mt_material_mode(const mt_material *m);

/* pbrt-v2's Material::GetBSDF: the BSDF at a shading point, in arena (see
 * bsdf.h: valid until the arena is reset). dg_geom carries the geometric
 * normal (its n) and dg_shading the shading frame, as pbrt-v2 passes them;
 * they may be the same. Textures read dg_shading's p, u, v and
 * differentials. NULL with err filled when the arena is exhausted, the
 * geometry is not finite or a texture gives a value the BxDF rejects.
 * err may be NULL (the renderer's inner loop); resetting it costs six
 * stores. */
MT_API mt_bsdf *mt_material_get_bsdf(const mt_material *m, const mt_diffgeom *dg_geom,
                                     const mt_diffgeom *dg_shading, mt_arena *arena,
                                     mt_error *err);

/* 1 for the materials that have a BSSRDF (subsurface, kdsubsurface), 0 for
 * the others. */
MT_API int mt_material_has_bssrdf(const mt_material *m);

/* pbrt-v2's Material::GetBSSRDF: *out at the (unbumped) shading point, MT_OK.
 * MT_ERR_INVALID for a material without one (mt_material_has_bssrdf). */
MT_API mt_status mt_material_get_bssrdf(const mt_material *m, const mt_diffgeom *dg_geom,
                                        const mt_diffgeom *dg_shading, mt_bssrdf *out,
                                        mt_error *err);

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
 * materials in the state. Unused parameters are not reported (the renderer
 * and the query tool report them; mt_material_from_text does). A new
 * reference, or NULL with err filled on any error. */
struct mt_state;
MT_API mt_material *mt_material_from_state(const struct mt_state *s, const mt_paramset *shape_params,
                                           mt_error *err);

/* The material MakeNamedMaterial "name" defined (pbrt-v2 creates it at that
 * statement: errors in its parameters show there). A new reference, or NULL
 * with err filled (MT_ERR_NOT_FOUND when no such name is in scope). */
MT_API mt_material *mt_material_named_from_state(const struct mt_state *s, const char *name, mt_error *err);

/* A material from pbrt-v2 statements given as text, in one call:
 *   mt_material *m = mt_material_from_text(
 *       "Material \"plastic\" \"rgb Kd\" [0.5 0.5 0.5] \"float roughness\" 0.05",
 *       NULL, &err);
 * The statements (Texture, Material, MakeNamedMaterial, NamedMaterial,
 * transforms, AttributeBegin/End: mt_state_apply_text) are applied to state,
 * then the material they leave current is made (mt_material_from_state):
 * the last Material statement's, or the NamedMaterial selected. The text
 * must hold at least one Material or NamedMaterial statement.
 *
 * state may be NULL: a temporary state in pbrt-v2 mode is used and
 * destroyed, so the text must define the textures and named materials it
 * uses. With a state of the caller's (mt_state_create), named textures and
 * materials defined by earlier calls, mt_state_apply_text or
 * mt_state_set_texture are found, this call's definitions stay in it, and
 * its mode, current transform and warning callback apply. Relative file
 * names (image maps, measured data, SPD files) resolve against the current
 * directory.
 *
 * Parameters that nothing read (a misspelt "Kdd", a "float Kd" where a
 * spectrum is read) go to the state's warning callback, one warning each;
 * when there is none (always with a NULL state) the first is an error,
 * MT_ERR_INVALID naming it and its line. Nothing is silently ignored.
 *
 * Returns a new reference (mt_material_destroy), or NULL with err filled:
 * a malformed statement (MT_ERR_PARSE, with line and column), a statement
 * other than those above, an unknown type (MT_ERR_NOT_FOUND), a parameter
 * out of range or of the wrong type, an undefined texture or named
 * material, an unreadable file. The statements before a failing one stay
 * applied to the caller's state. Thread safety: with a NULL state any
 * number of threads may call this at once; a state is used by one thread at
 * a time (state.h). */
MT_API mt_material *mt_material_from_text(const char *text, struct mt_state *state, mt_error *err);

/* A material of pbrt-v2 type `type` ("plastic", ...) from a list of typed
 * parameters (params.h's helpers), in one call:
 *   const mt_param p[] = {mt_param_rgb("Kd", 0.5, 0.5, 0.5), mt_param_float("roughness", 0.05)};
 *   mt_material *m = mt_material_from_params("plastic", p, 2, NULL, &err);
 * the same as the text `Material "plastic" "rgb Kd" [0.5 0.5 0.5] "float
 * roughness" 0.05`, with pbrt-v2's names and defaults (docs/REFERENCE.md).
 * params (nparams of them; NULL when 0) are copied: they may go away after
 * the call. state may be NULL: then pbrt-v2 mode, the identity transform,
 * no named textures (a "texture" parameter fails with MT_ERR_NOT_FOUND) and
 * no named materials (a "mix" fails). With a state, its named textures and
 * materials, mode, current transform and warning callback are used; the
 * state is not modified. Unused parameters and errors as for
 * mt_material_from_text. Returns a new reference, or NULL with err filled.
 * Thread safety: with a NULL state any number of threads may call this at
 * once; a state is used by one thread at a time (state.h). */
MT_API mt_material *mt_material_from_params(const char *type, const mt_param *params, int nparams,
                                            const struct mt_state *state, mt_error *err);

/* ---- material kinds and the registry ----------------------------------------
 * A kind is one of pbrt-v2's material types. The registry lists every kind
 * once, in MT_MATERIAL_KINDS: X(name) declares the kind's object
 * mt_<name>_material (defined in src/materials/<file>.c), and the registry's
 * functions below iterate the same list. Creating by name (mt_material_create,
 * mt_material_kind_find, a scene) links every kind into a static program;
 * creating from a kind's object (mt_material_create_kind) links that kind and
 * what it uses alone. The kind objects are static and constant: every
 * function of this block may be called from any number of threads at once. */
typedef struct mt_material_kind mt_material_kind;

#define MT_MATERIAL_KINDS(X)                                                               \
    X(matte) X(plastic) X(glass) X(mirror) X(metal) X(shinymetal) X(substrate)             \
    X(translucent) X(uber) X(mix) X(measured) X(subsurface) X(kdsubsurface)

#define MT_MATERIAL_KIND_DECLARE_(name) MT_API extern const mt_material_kind mt_##name##_material;
MT_MATERIAL_KINDS(MT_MATERIAL_KIND_DECLARE_)

/* As mt_material_create, for the kind k (e.g. &mt_plastic_material): a new
 * reference (mt_material_destroy), or NULL with err filled (MT_ERR_INVALID
 * for a NULL k or a parameter out of range). */
MT_API mt_material *mt_material_create_kind(const mt_material_kind *k, const mt_transform *mtl2world,
                                            const mt_texparams *tp, const mt_material_ctx *ctx,
                                            mt_error *err);
/* The kind's pbrt-v2 name ("plastic"), a static string; k must not be NULL. */
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

/* The kinds' names in registry order (a static, NULL-terminated array of
 * static strings); *count (may be NULL) receives their number. */
MT_API const char *const *mt_material_types(int *count);

#ifdef __cplusplus
}
#endif

#endif
