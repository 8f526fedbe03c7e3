/*
 * Internal: the material base and the helpers every material shares. A kind
 * of material is an operations table; its struct embeds mt_material first.
 */
#ifndef MT_MATERIALS_IMPL_H
#define MT_MATERIALS_IMPL_H

#include "materia/bump.h"
#include "materia/material.h"
#include "bsdf_internal.h"

typedef struct mt_material_ops {
    const char *type;
    /* the most BxDFs get_bsdf can add (a mix must stay within MT_MAX_BXDFS) */
    int (*max_bxdfs)(const mt_material *m);
    mt_status (*add_bxdfs)(const mt_material *m, mt_bsdf *bsdf, const mt_diffgeom *dgs,
                           mt_arena *arena, mt_error *err);
    /* the BSDF's eta (pbrt-v2 passes the index for glass and translucent) */
    mt_real (*eta)(const mt_material *m, const mt_diffgeom *dgs);
    int (*bssrdf)(const mt_material *m, const mt_diffgeom *dgs, mt_bssrdf *out);
    void (*destroy)(mt_material *m);
    /* a whole get_bsdf of its own (the mix); NULL for the common path */
    mt_bsdf *(*get_bsdf)(const mt_material *m, const mt_diffgeom *dg_geom,
                         const mt_diffgeom *dg_shading, mt_arena *arena, mt_error *err);
} mt_material_ops;

#define MT_MATERIAL_SLOTS 8

struct mt_material {
    const mt_material_ops *ops;
    int refs;
    mt_mode mode;
    mt_texture *bump;                     /* NULL without "bumpmap" */
    mt_texture *tex[MT_MATERIAL_SLOTS];   /* the type's texture parameters */
};

/* A texture-or-constant parameter of a material type: pbrt-v2's name, the
 * kind of texture, and its default. */
typedef struct mt_tex_slot {
    const char *name;
    int is_float;
    mt_real def[3];
} mt_tex_slot;

/* A material of size bytes (zeroed) whose tex[i] are looked up from tp as
 * slots[i] says, plus "bumpmap"; NULL with err filled (nothing leaked) when
 * a parameter is wrong or memory is exhausted. */
void *mt__material_new(size_t size, const mt_material_ops *ops, const mt_tex_slot *slots, int nslots,
                       const mt_texparams *tp, mt_error *err);

/* The most BxDFs the material can add. */
int mt__material_max_bxdfs(const mt_material *m);

/* Evaluations shared by the materials: a spectrum texture clamped from below
 * (pbrt-v2's Evaluate(dgs).Clamp()), and a float texture. */
mt_rgb mt__tex_rgb(const mt_texture *t, const mt_diffgeom *dg);
mt_real mt__tex_float(const mt_texture *t, const mt_diffgeom *dg);

/* tex[i] evaluated at the shading point (spectra clamped from below). */
#define MT_RGB(m, i, dgs) mt__tex_rgb((m)->tex[(i)], (dgs))
#define MT_FLOAT(m, i, dgs) mt__tex_float((m)->tex[(i)], (dgs))

/* Adds x (NULL: a creator failed and err says why) to the BSDF. */
#define MT_ADD(bsdf, x, err)                                   \
    do {                                                       \
        mt_status st_ = mt_bsdf_add((bsdf), (x), (err));       \
        if (st_) return st_;                                   \
    } while (0)

/* Creators of the material types (one file each). */
typedef mt_material *(*mt_material_create_fn)(const mt_transform *mtl2world, const mt_texparams *tp,
                                              const mt_material_ctx *ctx, mt_error *err);
mt_material *mt__matte_create(const mt_transform *, const mt_texparams *, const mt_material_ctx *, mt_error *);
mt_material *mt__plastic_create(const mt_transform *, const mt_texparams *, const mt_material_ctx *, mt_error *);
mt_material *mt__glass_create(const mt_transform *, const mt_texparams *, const mt_material_ctx *, mt_error *);
mt_material *mt__mirror_create(const mt_transform *, const mt_texparams *, const mt_material_ctx *, mt_error *);
mt_material *mt__metal_create(const mt_transform *, const mt_texparams *, const mt_material_ctx *, mt_error *);
mt_material *mt__shinymetal_create(const mt_transform *, const mt_texparams *, const mt_material_ctx *, mt_error *);
mt_material *mt__substrate_create(const mt_transform *, const mt_texparams *, const mt_material_ctx *, mt_error *);
mt_material *mt__translucent_create(const mt_transform *, const mt_texparams *, const mt_material_ctx *, mt_error *);
mt_material *mt__uber_create(const mt_transform *, const mt_texparams *, const mt_material_ctx *, mt_error *);
mt_material *mt__mix_create(const mt_transform *, const mt_texparams *, const mt_material_ctx *, mt_error *);
mt_material *mt__measured_create(const mt_transform *, const mt_texparams *, const mt_material_ctx *, mt_error *);
mt_material *mt__subsurface_create(const mt_transform *, const mt_texparams *, const mt_material_ctx *, mt_error *);
mt_material *mt__kdsubsurface_create(const mt_transform *, const mt_texparams *, const mt_material_ctx *, mt_error *);


#endif
