/*
 * Internal: pbrt-v2's TextureParams lookups (the geometry's list first, then
 * the material's; "texture" parameters from the named textures), which the
 * materials and texture classes read their parameters with.
 */
#ifndef MT_TEXTURES_TEXPARAMS_H
#define MT_TEXTURES_TEXPARAMS_H

#include "materia/texture.h"

/* TextureParams::GetFloatTexture / GetSpectrumTexture: the named texture a
 * "texture" parameter gives, else a constant from the value or def. Returns a
 * new reference, or NULL (err filled: unknown texture name, wrong type). */
mt_texture *mt_texparams_float_texture(const mt_texparams *tp, const char *name,
                                       mt_real def, mt_error *err);
mt_texture *mt_texparams_spectrum_texture(const mt_texparams *tp, const char *name,
                                          mt_rgb def, mt_error *err);
/* A float texture only when the parameter is present (e.g. "bumpmap"):
 * *out = NULL when absent. */
mt_status mt_texparams_float_texture_opt(const mt_texparams *tp, const char *name,
                                         mt_texture **out, mt_error *err);
/* Scalar lookups, geometry parameters first (pbrt-v2 TextureParams::Find*). */
mt_status mt_texparams_float(const mt_texparams *tp, const char *name, mt_real def,
                             mt_real *out, mt_error *err);
mt_status mt_texparams_int(const mt_texparams *tp, const char *name, int def, int *out,
                           mt_error *err);
mt_status mt_texparams_bool(const mt_texparams *tp, const char *name, int def, int *out,
                            mt_error *err);
mt_status mt_texparams_string(const mt_texparams *tp, const char *name, const char *def,
                              const char **out, mt_error *err);
mt_status mt_texparams_filename(const mt_texparams *tp, const char *name,
                                const char *def, char *out, size_t size, mt_error *err);
mt_status mt_texparams_vector(const mt_texparams *tp, const char *name, mt_vec3 def,
                              mt_vec3 *out, mt_error *err);
mt_status mt_texparams_rgb(const mt_texparams *tp, const char *name, mt_rgb def,
                           mt_rgb *out, mt_error *err);

#endif
