/*
 * materia/texture.h -- pbrt-v2's textures and their mappings.
 *
 * A texture is a reference-counted handle that evaluates to a float or to an
 * RGB spectrum at a shading point (mt_diffgeom: p, u, v and the screen-space
 * differentials). Every pbrt-v2 texture class exists with its name,
 * parameters and defaults: constant, scale, mix, bilerp, imagemap, uv,
 * checkerboard (2D with aamode none/closedform, and 3D), dots, fbm, wrinkled,
 * windy, marble -- float and spectrum variants where pbrt-v2 has both (it has
 * no float uv or marble).
 *
 * The short ways: mt_texture_from_text (a Texture statement) and
 * mt_texture_from_params (typed parameters), below; mt_texture_create is the
 * low-level constructor, which reads parameters as pbrt-v2's TextureParams
 * does: the geometry's first, then the material's, and "texture" parameters
 * from a table of named textures.
 *
 * Lifetime: every function that returns a texture, except
 * mt_texture_table_get, returns a new reference, which mt_texture_destroy
 * ends; mt_texture_retain gives another. A texture holds references to the
 * textures it is made of, and an image map to its pyramid in the cache.
 *
 * Thread safety: a texture is read-only once created: any number of
 * threads may evaluate it at once, and retain and destroy it (atomic
 * reference counts). A texture table belongs to one thread at a time while
 * it changes; mt_texture_table_get may be called from any number of
 * threads on a table that no thread changes.
 */
#ifndef MATERIA_TEXTURE_H
#define MATERIA_TEXTURE_H

#include "materia/diffgeom.h"
#include "materia/mode.h"
#include "materia/params.h"
#include "materia/rgb.h"
#include "materia/transform.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct mt_texture mt_texture;
typedef struct mt_texture_table mt_texture_table;
struct mt_state; /* materia/state.h */

/* The value at a shading point: evaluation reads dg's p, u, v and
 * screen-space differentials (zero differentials: no filtering), allocates
 * nothing, and gives a finite result for finite input. A spectrum texture
 * read as a float gives its luminance (mt_rgb_y, what pbrt-v2's float image
 * maps store); a float texture read as RGB is gray. */
MT_API mt_real mt_texture_eval_float(const mt_texture *t, const mt_diffgeom *dg);
MT_API mt_rgb mt_texture_eval_rgb(const mt_texture *t, const mt_diffgeom *dg);
/* 1 for a float texture, 0 for a spectrum one; the class name ("checkerboard",
 * a static string). */
MT_API int mt_texture_is_float(const mt_texture *t);
MT_API const char *mt_texture_class(const mt_texture *t);
/* Another reference to t (returned; t may be NULL), and the end of one. */
MT_API mt_texture *mt_texture_retain(mt_texture *t);
MT_API void mt_texture_destroy(mt_texture *t);

/* A constant texture (what a plain value in a material's parameters
 * becomes): a new reference, or NULL with err filled (MT_ERR_NOMEM). */
MT_API mt_texture *mt_texture_constant_float(mt_real v, mt_error *err);
MT_API mt_texture *mt_texture_constant_rgb(mt_rgb v, mt_error *err);

/* A table of named textures, in two namespaces (float and spectrum) as in
 * pbrt-v2; NULL when out of memory. An mt_state holds one (and
 * mt_state_set_texture binds in it): most programs need no table of their
 * own. mt_texture_table_destroy releases the table's references. */
MT_API mt_texture_table *mt_texture_table_create(void);
/* A copy sharing the textures (AttributeBegin); NULL when out of memory. */
MT_API mt_texture_table *mt_texture_table_clone(const mt_texture_table *t);
MT_API void mt_texture_table_destroy(mt_texture_table *t);
/* Binds name (copied) to tex in tex's namespace, replacing (and destroying
 * its reference to) an earlier binding. The table takes its own reference:
 * the caller keeps, and later destroys, the one it holds. MT_ERR_INVALID
 * for a NULL table, name or texture, MT_ERR_NOMEM. */
MT_API mt_status mt_texture_table_set(mt_texture_table *t, const char *name, mt_texture *tex,
                                      mt_error *err);
/* The texture bound to name in the float (is_float != 0) or spectrum
 * namespace, borrowed (valid while the binding is); NULL when there is none
 * or t is NULL. */
MT_API mt_texture *mt_texture_table_get(const mt_texture_table *t, const char *name,
                                        int is_float);

/* pbrt-v2's TextureParams, for mt_texture_create and mt_material_create. */
typedef struct mt_texparams {
    const mt_paramset *geom;     /* may be NULL */
    const mt_paramset *material; /* may be NULL */
    const mt_texture_table *textures; /* may be NULL: no named textures */
    mt_mode mode;
} mt_texparams;

/* The low-level constructor: a texture of pbrt-v2 class class_name
 * ("constant", "checkerboard", ...), float (is_float != 0) or spectrum,
 * declared under the transform tex2world (pbrt-v2's current transform at
 * the Texture statement; NULL for the identity). The lists are read, not
 * kept; reporting their unused parameters is the caller's
 * (mt_paramset_report_unused). A new reference, or NULL with err filled:
 * an unknown class (MT_ERR_NOT_FOUND), a class without that variant, or a
 * bad parameter -- an unknown "mapping", "aamode", "wrap" or "dimension", a
 * missing or unreadable image, octaves outside [0, 128], ... (pbrt-v2 warns
 * and substitutes a default for some of these). tp->mode selects pbrt-v2's
 * behaviour or the corrections (MT_FIX_MAPPING_3D, MT_FIX_DOTS_INSIDE, ...). */
MT_API mt_texture *mt_texture_create(const char *class_name, int is_float,
                                     const mt_transform *tex2world, const mt_texparams *tp,
                                     mt_error *err);

/* A texture from pbrt-v2 Texture statements given as text, in one call:
 *   mt_texture *t = mt_texture_from_text(
 *       "Texture \"checks\" \"color\" \"checkerboard\" \"float uscale\" 4 \"float vscale\" 4",
 *       NULL, &err);
 * The statements are applied to state as mt_material_from_text applies
 * them (state NULL: a temporary one in pbrt-v2 mode); the texture the last
 * Texture statement defined is returned as a new reference
 * (mt_texture_destroy), and also stays bound in the caller's state. Unused
 * parameters go to the state's warning callback, or are an error when it
 * has none. NULL with err filled on any error, or when the text has no
 * Texture statement. Thread safety as mt_material_from_text. */
MT_API mt_texture *mt_texture_from_text(const char *text, struct mt_state *state, mt_error *err);

/* A texture of pbrt-v2 class class_name, float (is_float != 0) or spectrum,
 * from a list of typed parameters, as a Texture statement with them would
 * make it:
 *   const mt_param p[] = {mt_param_float("uscale", 4), mt_param_float("vscale", 4)};
 *   mt_texture *t = mt_texture_from_params("checkerboard", 0, p, 2, NULL, &err);
 * params are copied. state may be NULL (pbrt-v2 mode, the identity
 * transform, no named textures); with a state, its named textures, mode,
 * current transform and warning callback are used and it is not modified.
 * To use the texture in a material by name, bind it with
 * mt_state_set_texture. Unused parameters go to the state's warning
 * callback, or are an error when there is none. A new reference, or NULL
 * with err filled (MT_ERR_NOT_FOUND for an unknown class). Thread safety as
 * mt_material_from_params. */
MT_API mt_texture *mt_texture_from_params(const char *class_name, int is_float, const mt_param *params,
                                          int nparams, const struct mt_state *state, mt_error *err);

/* ---- texture kinds and the registry ------------------------------------------
 * A kind is one of pbrt-v2's texture classes. The registry lists every kind
 * once, in MT_TEXTURE_KINDS: X(name) declares the kind's object
 * mt_<name>_texture (defined in src/textures/<name>.c), and the registry's
 * functions below iterate the same list. Creating by name
 * (mt_texture_create, mt_texture_kind_find, a Texture statement) links every
 * kind into a static program, imagemap and its image reading included;
 * creating from a kind's object (mt_texture_create_kind) links that kind and
 * what it uses alone. The kind objects are static and constant: every
 * function of this block may be called from any number of threads at once. */
typedef struct mt_texture_kind mt_texture_kind;

#define MT_TEXTURE_KINDS(X)                                                                \
    X(constant) X(scale) X(mix) X(bilerp) X(imagemap) X(uv) X(checkerboard) X(dots) X(fbm)   \
    X(wrinkled) X(windy) X(marble)

#define MT_TEXTURE_KIND_DECLARE_(name) MT_API extern const mt_texture_kind mt_##name##_texture;
MT_TEXTURE_KINDS(MT_TEXTURE_KIND_DECLARE_)

/* As mt_texture_create, for the kind k (e.g. &mt_checkerboard_texture): a
 * new reference (mt_texture_destroy), or NULL with err filled (MT_ERR_INVALID
 * for a NULL k, a float variant the class does not have, a bad parameter). */
MT_API mt_texture *mt_texture_create_kind(const mt_texture_kind *k, int is_float,
                                          const mt_transform *tex2world, const mt_texparams *tp,
                                          mt_error *err);
/* The kind's pbrt-v2 class name ("checkerboard"), a static string; k must
 * not be NULL. */
MT_API const char *mt_texture_kind_name(const mt_texture_kind *k);
/* 1 when pbrt-v2 has a float variant of the class (all but uv and marble). */
MT_API int mt_texture_kind_has_float(const mt_texture_kind *k);

/* The registry: the number of kinds, the i-th (0 <= i < count, in
 * MT_TEXTURE_KINDS order; NULL outside), and the kind of a class name (NULL
 * when there is none). */
MT_API int mt_texture_kind_count(void);
MT_API const mt_texture_kind *mt_texture_kind_at(int i);
MT_API const mt_texture_kind *mt_texture_kind_find(const char *name);

/* The class names in registry order (a static, NULL-terminated array of
 * static strings), for help texts and tests; *count (may be NULL) receives
 * their number. */
MT_API const char *const *mt_texture_classes(int *count);

#ifdef __cplusplus
}
#endif

#endif
