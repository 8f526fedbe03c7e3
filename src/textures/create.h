/*
 * Internal: the readers pbrt-v2's texture creators share (a mapping, two
 * children, octaves), for the kinds' creators (textures/kind.h).
 */
#ifndef MT_TEXTURES_CREATE_H
#define MT_TEXTURES_CREATE_H

#include "textures/kind.h"
#include "textures/tex.h"

/* (texparams.c) A float or spectrum child texture with a gray default. */
mt_texture *mt__tex_child(const mt_texparams *tp, int is_float, const char *name, mt_real def,
                          mt_error *err);
/* (texparams.c) A float or spectrum value with a gray default, as an RGB. */
mt_status mt__tex_value(const mt_texparams *tp, int is_float, const char *name, mt_real def,
                        mt_rgb *out, mt_error *err);
/* A string parameter's value among choices (NULL-terminated): its index, or
 * -1 with err naming the parameter and the class cls. */
int mt__tex_choice(const mt_texparams *tp, const char *name, const char *def,
                   const char *const *choices, const char *cls, mt_error *err);
/* The 2D mapping "mapping" chooses (uv, spherical, cylindrical, planar) with
 * its parameters, as every pbrt-v2 creator of a 2D texture reads it. */
mt_status mt__tex_mapping2d(const mt_transform *tex2world, const mt_texparams *tp,
                            const char *cls, mt_map2d *m, mt_error *err);
/* "octaves" (8) and "roughness" (0.5): fbm, wrinkled and marble. */
mt_status mt__tex_octaves(const mt_texparams *tp, int *octaves, mt_real *roughness,
                          mt_error *err);
/* fbm and wrinkled: ctor (mt__tex_fbm, mt__tex_wrinkled) with the 3D mapping
 * of tex2world and the octaves read. */
typedef mt_texture *(*mt__octave_ctor)(int is_float, const mt_map3d *map, int octaves,
                                       mt_real roughness, mt_mode mode, mt_error *err);
mt_texture *mt__tex_create_octaves(mt__octave_ctor ctor, int is_float, const mt_transform *tex2world,
                                   const mt_texparams *tp, mt_error *err);

/* Two child textures (a with default da, b with db) and, for the mix, an
 * amount: the caller releases all three with mt__tex_children_put, whether
 * or not mt__tex_children_get succeeded (1) or failed (0, err filled). */
typedef struct mt__tex_children {
    mt_texture *a, *b, *amount;
} mt__tex_children;
int mt__tex_children_get(const mt_texparams *tp, int is_float, const char *na, mt_real da,
                         const char *nb, mt_real db, mt__tex_children *c, mt_error *err);
void mt__tex_children_put(mt__tex_children *c);

#endif
