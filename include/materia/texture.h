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
struct mt_state; /* materia/state.h */

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
MT_API void mt_texture_destroy(mt_texture *t);

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

/* The class names, for help texts and tests; *count receives their number. */
MT_API const char *const *mt_texture_classes(int *count);

#ifdef __cplusplus
}
#endif

#endif
