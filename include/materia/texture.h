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
 * Textures are created from a statement's parameters by class name
 * (mt_texture_create), which reads them as pbrt-v2's TextureParams does: the
 * geometry's parameters first, then the material's, and "texture" parameters
 * from the table of named textures.
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

/* Evaluation reads dg's p, u, v and screen-space differentials, allocates
 * nothing and may run in any number of threads at once; the result is finite
 * for finite input. A spectrum texture read as a float gives its luminance
 * (mt_rgb_y, what pbrt-v2's float image maps store); a float texture read as
 * RGB is gray. Reference counts are atomic; a texture holds references to
 * the textures it is made of. */
MT_API mt_real mt_texture_eval_float(const mt_texture *t, const mt_diffgeom *dg);
MT_API mt_rgb mt_texture_eval_rgb(const mt_texture *t, const mt_diffgeom *dg);
MT_API int mt_texture_is_float(const mt_texture *t);
MT_API const char *mt_texture_class(const mt_texture *t);
MT_API mt_texture *mt_texture_retain(mt_texture *t);
MT_API void mt_texture_release(mt_texture *t);

/* Constant textures (what a plain value in a material's parameters becomes). */
MT_API mt_texture *mt_texture_constant_float(mt_real v, mt_error *err);
MT_API mt_texture *mt_texture_constant_rgb(mt_rgb v, mt_error *err);

/* Named textures, in two namespaces (float and spectrum) as in pbrt-v2. */
MT_API mt_texture_table *mt_texture_table_create(void);
/* A copy sharing the textures (AttributeBegin); NULL when out of memory. */
MT_API mt_texture_table *mt_texture_table_clone(const mt_texture_table *t);
MT_API void mt_texture_table_destroy(mt_texture_table *t);
/* Binds name to tex in tex's namespace, replacing (and releasing) an
 * earlier binding. The table takes its own reference: the caller keeps, and
 * later releases, the one it holds. */
MT_API mt_status mt_texture_table_set(mt_texture_table *t, const char *name, mt_texture *tex,
                                      mt_error *err);
/* The texture bound to name, or NULL (no new reference). */
MT_API mt_texture *mt_texture_table_get(const mt_texture_table *t, const char *name,
                                        int is_float);

/* pbrt-v2's TextureParams. */
typedef struct mt_texparams {
    const mt_paramset *geom;     /* may be NULL */
    const mt_paramset *material; /* may be NULL */
    const mt_texture_table *textures;
    mt_mode mode;
} mt_texparams;

/* TextureParams::GetFloatTexture / GetSpectrumTexture: the named texture a
 * "texture" parameter gives, else a constant from the value or def. Returns a
 * new reference, or NULL (err filled: unknown texture name, wrong type). */
MT_API mt_texture *mt_texparams_float_texture(const mt_texparams *tp, const char *name,
                                              mt_real def, mt_error *err);
MT_API mt_texture *mt_texparams_spectrum_texture(const mt_texparams *tp, const char *name,
                                                 mt_rgb def, mt_error *err);
/* A float texture only when the parameter is present (e.g. "bumpmap"):
 * *out = NULL when absent. */
MT_API mt_status mt_texparams_float_texture_opt(const mt_texparams *tp, const char *name,
                                                mt_texture **out, mt_error *err);
/* Scalar lookups, geometry parameters first (pbrt-v2 TextureParams::Find*). */
MT_API mt_status mt_texparams_float(const mt_texparams *tp, const char *name, mt_real def,
                                    mt_real *out, mt_error *err);
MT_API mt_status mt_texparams_int(const mt_texparams *tp, const char *name, int def, int *out,
                                  mt_error *err);
MT_API mt_status mt_texparams_bool(const mt_texparams *tp, const char *name, int def, int *out,
                                   mt_error *err);
MT_API mt_status mt_texparams_string(const mt_texparams *tp, const char *name, const char *def,
                                     const char **out, mt_error *err);
MT_API mt_status mt_texparams_filename(const mt_texparams *tp, const char *name,
                                       const char *def, char *out, size_t size, mt_error *err);
MT_API mt_status mt_texparams_vector(const mt_texparams *tp, const char *name, mt_vec3 def,
                                     mt_vec3 *out, mt_error *err);
MT_API mt_status mt_texparams_rgb(const mt_texparams *tp, const char *name, mt_rgb def,
                                  mt_rgb *out, mt_error *err);

/* Creates a texture of pbrt-v2 class class_name ("constant", "checkerboard",
 * ...), float or spectrum, declared under the transform tex2world (pbrt-v2's
 * current transform at the Texture statement; NULL for the identity). NULL
 * with err filled for an unknown class, a class without that variant, or a
 * bad parameter: an unknown "mapping", "aamode", "wrap" or "dimension", a
 * missing or unreadable image, octaves outside [0, 128], ... (pbrt-v2 warns
 * and substitutes a default for some of these). tp->mode selects pbrt-v2's
 * behaviour or the corrections (MT_FIX_MAPPING_3D, MT_FIX_DOTS_INSIDE, ...). */
MT_API mt_texture *mt_texture_create(const char *class_name, int is_float,
                                     const mt_transform *tex2world, const mt_texparams *tp,
                                     mt_error *err);

/* ---- texture kinds and the registry ------------------------------------------
 * A kind is one of pbrt-v2's texture classes. The registry lists every kind
 * once, in MT_TEXTURE_KINDS: X(name) declares the kind's object
 * mt_<name>_texture (defined in src/textures/<name>.c), and the registry's
 * functions below iterate the same list. Creating by name
 * (mt_texture_create, mt_texture_kind_find, a Texture statement) links every
 * kind into a static program, imagemap and its image reading included;
 * creating from a kind's object (mt_texture_create_kind) links that kind and
 * what it uses alone. */
typedef struct mt_texture_kind mt_texture_kind;

#define MT_TEXTURE_KINDS(X)                                                                \
    X(constant) X(scale) X(mix) X(bilerp) X(imagemap) X(uv) X(checkerboard) X(dots) X(fbm)   \
    X(wrinkled) X(windy) X(marble)

#define MT_TEXTURE_KIND_DECLARE_(name) MT_API extern const mt_texture_kind mt_##name##_texture;
MT_TEXTURE_KINDS(MT_TEXTURE_KIND_DECLARE_)

/* As mt_texture_create, for the kind k (e.g. &mt_checkerboard_texture). */
MT_API mt_texture *mt_texture_create_kind(const mt_texture_kind *k, int is_float,
                                          const mt_transform *tex2world, const mt_texparams *tp,
                                          mt_error *err);
/* The kind's pbrt-v2 class name ("checkerboard"). */
MT_API const char *mt_texture_kind_name(const mt_texture_kind *k);
/* 1 when pbrt-v2 has a float variant of the class (all but uv and marble). */
MT_API int mt_texture_kind_has_float(const mt_texture_kind *k);

/* The registry: the number of kinds, the i-th (0 <= i < count, in
 * MT_TEXTURE_KINDS order; NULL outside), and the kind of a class name (NULL
 * when there is none). */
MT_API int mt_texture_kind_count(void);
MT_API const mt_texture_kind *mt_texture_kind_at(int i);
MT_API const mt_texture_kind *mt_texture_kind_find(const char *name);

/* The class names in registry order, NULL-terminated; *count (may be NULL)
 * receives their number. */
MT_API const char *const *mt_texture_classes(int *count);

#ifdef __cplusplus
}
#endif

#endif
