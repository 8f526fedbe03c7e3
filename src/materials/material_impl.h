/*
 * Internal: the material base and the helpers every material shares. A kind
 * of material is an operations table; its struct embeds mt_material first.
 */
#ifndef MT_MATERIALS_IMPL_H
#define MT_MATERIALS_IMPL_H

#include "materia/bump.h"
#include "materia/material.h"
#include "bsdf_internal.h"
#include "materials/bssrdf_cache.h"

#define MT_MATERIAL_SLOTS 8

typedef struct mt_tex_slot mt_tex_slot;
typedef struct mt_param_doc mt_param_doc;

typedef struct mt_material_ops {
    const char *type;
    /* the most BxDFs get_bsdf can add (a mix must stay within MT_MAX_BXDFS) */
    int (*max_bxdfs)(const mt_material *m);
    mt_status (*add_bxdfs)(const mt_material *m, mt_bsdf *bsdf, const mt_diffgeom *dgs,
                           mt_arena *arena, mt_error *err);
    /* the BSDF's eta (pbrt-v2 passes the index for glass and translucent) */
    mt_real (*eta)(const mt_material *m, const mt_diffgeom *dgs);
    /* cache: the thread's last SubsurfaceFromDiffuse, or NULL */
    int (*bssrdf)(const mt_material *m, const mt_diffgeom *dgs, mt__bssrdf_cache *cache, mt_bssrdf *out);
    void (*destroy)(mt_material *m);
    /* a whole get_bsdf of its own (the mix); NULL for the common path */
    mt_bsdf *(*get_bsdf)(const mt_material *m, const mt_diffgeom *dg_geom,
                         const mt_diffgeom *dg_shading, mt_arena *arena, mt_error *err);
    /* the texture parameters, read into tex[] in this order */
    const mt_tex_slot *slots;
    int nslots;
    /* fills the defaults computed at run time (metal's copper, subsurface's
     * whole milk) into a copy of slots; NULL when all are in the table */
    void (*defaults)(mt_tex_slot *slots);
    /* the parameters that are not textures, for docs/REFERENCE.md (the
     * creator reads them itself) */
    const mt_param_doc *other;
    int nother;
} mt_material_ops;


struct mt_material {
    const mt_material_ops *ops;
    int refs;
    mt_mode mode;
    mt_texture *bump;                     /* NULL without "bumpmap" */
    mt_texture *tex[MT_MATERIAL_SLOTS];   /* the type's texture parameters */
};

/* The values a material parameter may take, as pbrt-v2 uses them. The first
 * four accept every finite value (what pbrt-v2 does with it is documented);
 * a constant value outside NONNEG or POS is an error when the material is
 * created (pbrt-v2 would render it black or with NaNs). */
typedef enum mt_range {
    MT_RANGE_ANY,    /* used as it is */
    MT_RANGE_CLAMP0, /* components below 0 are taken as 0 (pbrt-v2's Clamp()) */
    MT_RANGE_SIGMA,  /* clamped to [0, 90] (degrees) */
    MT_RANGE_APPROX, /* clamped to [0, 0.999] (a reflectance turned into a conductor) */
    MT_RANGE_NONNEG, /* >= 0 */
    MT_RANGE_POS     /* > 0 */
} mt_range;

/* A texture-or-constant parameter of a material type: pbrt-v2's name, the
 * kind of texture, its default, its range and what it is (the last two for
 * the check at creation and docs/REFERENCE.md). */
struct mt_tex_slot {
    const char *name;
    int is_float;
    mt_real def[3];
    mt_range range;
    const char *what;
};

/* A parameter a creator reads itself: its type as a scene writes it, its
 * default and range in words, and what it is. */
struct mt_param_doc {
    const char *name, *type, *def, *range, *what;
};

/* The range's rule in words ("> 0", "any; below 0 taken as 0", ...). */
const char *mt__range_text(mt_range r);

/* A material of size bytes (zeroed) whose tex[i] are looked up from tp as
 * ops->slots[i] says, plus "bumpmap"; NULL with err filled (nothing leaked)
 * when a parameter is wrong (a constant outside its range included) or
 * memory is exhausted. */
void *mt__material_new(size_t size, const mt_material_ops *ops, const mt_texparams *tp, mt_error *err);

/* As mt__material_new with slots (ops->nslots of them) in place of
 * ops->slots: defaults that depend on other parameters. */
void *mt__material_new_with(size_t size, const mt_material_ops *ops, const mt_tex_slot *slots,
                            const mt_texparams *tp, mt_error *err);

/* Locates err at the parameter name of tp (the geometry's list first), when
 * it is there. */
void mt__material_locate_param(const mt_texparams *tp, const char *name, mt_error *err);

/* The operations table of a material type by pbrt-v2 name, or NULL. */
const mt_material_ops *mt__material_ops(const char *type);

/* Whether both materials of a mix are uniform (materials/uniform.h); 0 for
 * any other material. */
int mt__mix_is_uniform(const mt_material *m);

/* The most BxDFs the material can add. */
int mt__material_max_bxdfs(const mt_material *m);

/* 1 when tex[i] may be non-black at some point: 0 only for a constant
 * texture whose value, clamped from below at 0, is black. A lobe that
 * pbrt-v2 adds only for a non-black scale is never added for such a slot, so
 * it does not count against the BSDF's MT_MAX_BXDFS (a mix's bound). */
int mt__slot_may_be_nonblack(const mt_material *m, int i);

/* 1 when tex[i] is a constant texture; its value (unclamped) in *v. */
int mt__slot_constant(const mt_material *m, int i, mt_rgb *v);

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

/* Their operations tables (the registry lists them for docs/REFERENCE.md). */
extern const mt_material_ops mt__matte_ops, mt__plastic_ops, mt__glass_ops, mt__mirror_ops, mt__metal_ops,
    mt__shinymetal_ops, mt__substrate_ops, mt__translucent_ops, mt__uber_ops, mt__mix_ops, mt__measured_ops,
    mt__subsurface_ops, mt__kdsubsurface_ops;


#endif
