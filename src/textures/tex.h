/*
 * Internal: the texture object, its operations table, and the constructors
 * of every class from plain values (each class's creator, textures/kind.h,
 * reads a statement's parameters and calls its constructor; tests call them
 * directly).
 *
 * A texture is a struct whose first member is mt_texture. Each pbrt-v2 class
 * has one operations table (eval_float, eval_rgb, finalize); the handle's
 * is_float says which variant it is. Constructors validate their arguments
 * (a message names the parameter), retain the textures they are given and
 * return a texture with one reference, or NULL with err filled.
 */
#ifndef MT_TEXTURES_TEX_H
#define MT_TEXTURES_TEX_H

#include "materia/texture.h"
#include "textures/texparams.h"
#include "textures/mapping.h"

typedef struct mt_texture_ops {
    const char *name; /* pbrt-v2's class name: "checkerboard", ... */
    /* The float variant's value (called only when is_float). */
    mt_real (*eval_float)(const mt_texture *t, const mt_diffgeom *dg);
    /* The spectrum variant's value (called only when !is_float). */
    mt_rgb (*eval_rgb)(const mt_texture *t, const mt_diffgeom *dg);
    /* Releases what the texture holds (children); NULL when nothing. */
    void (*finalize)(mt_texture *t);
} mt_texture_ops;

struct mt_texture {
    const mt_texture_ops *ops;
    int is_float;
    mt_mode mode;
    long refs; /* atomic: textures are shared between materials and threads */
};

/* Whether t is a ConstantTexture (its value the same at every point). */
int mt__texture_is_constant(const mt_texture *t);

/* Allocates size bytes (a struct starting with mt_texture) with one reference. */
void *mt__texture_alloc(size_t size, const mt_texture_ops *ops, int is_float, mt_mode mode,
                        mt_error *err);

/* The value of a child texture as the parent's variant needs it. */
static inline mt_real mt__tex_f(const mt_texture *t, const mt_diffgeom *dg)
{
    return t->ops->eval_float(t, dg);
}
static inline mt_rgb mt__tex_rgb(const mt_texture *t, const mt_diffgeom *dg)
{
    return t->ops->eval_rgb(t, dg);
}

/* Argument checks shared by the constructors (they fill err and return 0). */
int mt__tex_check_real(mt_real v, const char *param, const char *cls, mt_error *err);
int mt__tex_check_rgb(mt_rgb v, const char *param, const char *cls, mt_error *err);
/* A child texture: present, and float or spectrum as the parent needs. */
int mt__tex_check_child(const mt_texture *t, int is_float, const char *param, const char *cls,
                        mt_error *err);

/* pbrt-v2 evaluates (1 - w) a + w b component by component (mix.h,
 * checkerboard.h); these keep that order of operations. */
static inline mt_real mt__tex_blend(mt_real w, mt_real a, mt_real b)
{
    return (1 - w) * a + w * b;
}
static inline mt_rgb mt__tex_blend_rgb(mt_real w, mt_rgb a, mt_rgb b)
{
    return mt_rgb_add(mt_rgb_scale(a, 1 - w), mt_rgb_scale(b, w));
}

/* Textures that choose between two children by a weight w (checkerboard,
 * dots): tex1 when w is 0, tex2 when w is 1 (only that child is evaluated, as
 * pbrt-v2's point-sampled paths do), the blend otherwise. */
static inline mt_real mt__tex_pick_float(mt_real w, const mt_texture *tex1,
                                         const mt_texture *tex2, const mt_diffgeom *dg)
{
    if (w == 0) return mt__tex_f(tex1, dg);
    if (w == 1) return mt__tex_f(tex2, dg);
    return mt__tex_blend(w, mt__tex_f(tex1, dg), mt__tex_f(tex2, dg));
}
static inline mt_rgb mt__tex_pick_rgb(mt_real w, const mt_texture *tex1, const mt_texture *tex2,
                                      const mt_diffgeom *dg)
{
    if (w == 0) return mt__tex_rgb(tex1, dg);
    if (w == 1) return mt__tex_rgb(tex2, dg);
    return mt__tex_blend_rgb(w, mt__tex_rgb(tex1, dg), mt__tex_rgb(tex2, dg));
}

/* eval_rgb of the classes whose spectrum variant is their float value as
 * gray (pbrt-v2 converts the float result to Spectrum: fbm, wrinkled, windy). */
mt_rgb mt__tex_gray_rgb(const mt_texture *t, const mt_diffgeom *dg);

/* The classes made of two children and a weight (checkerboard, dots) and
 * those made of noise (fbm, wrinkled, windy, marble) share their layout. */
typedef struct mt__pair_tex {
    mt_texture base;
    mt_texture *tex1, *tex2;
    /* checkerboard, dots: tex2's weight at dg (see mt__tex_pick_float) */
    mt_real (*weight)(const mt_texture *t, const mt_diffgeom *dg);
} mt__pair_tex;
/* Checks and retains both children; the caller fills the rest. */
void *mt__pair_alloc(size_t size, const mt_texture_ops *ops, int is_float, mt_texture *tex1,
                     const char *name1, mt_texture *tex2, const char *name2, mt_mode mode,
                     mt_error *err);
void mt__pair_finalize(mt_texture *t);
/* eval_float and eval_rgb of the classes with a weight: tex1, tex2 or the blend. */
mt_real mt__pair_pick_float(const mt_texture *t, const mt_diffgeom *dg);
mt_rgb mt__pair_pick_rgb(const mt_texture *t, const mt_diffgeom *dg);

/* noise.h's FBm and Turbulence share this signature. */
typedef mt_real (*mt__octave_fn)(mt_vec3 p, mt_vec3 dpdx, mt_vec3 dpdy, mt_real omega,
                                 int max_octaves);

typedef struct mt__noise_tex {
    mt_texture base;
    mt_map3d map;
    int octaves;
    mt_real omega;     /* pbrt-v2's "roughness" */
    mt__octave_fn sum; /* fbm: FBm, wrinkled: Turbulence */
} mt__noise_tex;
/* Checks octaves and roughness (mt__tex_check_octaves) and fills the layout. */
void *mt__noise_alloc(size_t size, const mt_texture_ops *ops, int is_float, const mt_map3d *map,
                      int octaves, mt_real roughness, mt__octave_fn sum, mt_mode mode,
                      mt_error *err);
/* eval_float of fbm and wrinkled: sum at the 3D-mapped point and footprint. */
mt_real mt__noise_tex_float(const mt_texture *t, const mt_diffgeom *dg);

/* --- constructors, one per pbrt-v2 class (the variant given by is_float) --- */
/* value: v.c[0] for the float variant. */
mt_texture *mt__tex_constant(int is_float, mt_rgb v, mt_mode mode, mt_error *err);
/* tex1 * tex2 (scale.h). */
mt_texture *mt__tex_scale(int is_float, mt_texture *tex1, mt_texture *tex2, mt_mode mode,
                          mt_error *err);
/* (1 - amount) tex1 + amount tex2; amount is a float texture (mix.h). */
mt_texture *mt__tex_mix(int is_float, mt_texture *tex1, mt_texture *tex2, mt_texture *amount,
                        mt_mode mode, mt_error *err);
/* v[0..3] = v00, v01, v10, v11 (bilerp.h); c[0] for the float variant. */
mt_texture *mt__tex_bilerp(int is_float, const mt_map2d *map, const mt_rgb v[4], mt_mode mode,
                           mt_error *err);
/* A lookup of mip (owned by the MIP-map cache, never freed here) at the
 * mapped coordinates (imagemap.h); a float variant's pyramid holds its
 * luminance in every channel. */
struct mt_mipmap;
mt_texture *mt__tex_imagemap(int is_float, const mt_map2d *map, const struct mt_mipmap *mip,
                             mt_mode mode, mt_error *err);
/* (s - floor s, t - floor t, 0): spectrum only (uv.h). */
mt_texture *mt__tex_uv(const mt_map2d *map, mt_mode mode, mt_error *err);
/* closedform: 1 for pbrt-v2's "closedform" aamode, 0 for "none". */
mt_texture *mt__tex_checker2d(int is_float, const mt_map2d *map, mt_texture *tex1,
                              mt_texture *tex2, int closedform, mt_mode mode, mt_error *err);
mt_texture *mt__tex_checker3d(int is_float, const mt_map3d *map, mt_texture *tex1,
                              mt_texture *tex2, mt_mode mode, mt_error *err);
mt_texture *mt__tex_dots(int is_float, const mt_map2d *map, mt_texture *inside,
                         mt_texture *outside, mt_mode mode, mt_error *err);
/* FBm (fbm.h) and Turbulence (wrinkled.h) of the mapped point. */
mt_texture *mt__tex_fbm(int is_float, const mt_map3d *map, int octaves, mt_real roughness,
                        mt_mode mode, mt_error *err);
mt_texture *mt__tex_wrinkled(int is_float, const mt_map3d *map, int octaves, mt_real roughness,
                             mt_mode mode, mt_error *err);
mt_texture *mt__tex_windy(int is_float, const mt_map3d *map, mt_mode mode, mt_error *err);
/* Spectrum only (marble.h). */
mt_texture *mt__tex_marble(const mt_map3d *map, int octaves, mt_real roughness, mt_real scale,
                           mt_real variation, mt_mode mode, mt_error *err);

/* The octave count and roughness of the noise textures: octaves in [0, 128]
 * (1.99^129 overflows float: pbrt-v2's frequency would be infinite) and
 * roughness^octaves finite. */
int mt__tex_check_octaves(int octaves, mt_real roughness, const char *cls, mt_error *err);

#endif
