/*
 * The material base: reference counting, the registry of the 13 pbrt-v2
 * material types, and pbrt-v2's Material::GetBSDF skeleton -- bump mapping
 * (when a "bumpmap" is given), a BSDF for the shading frame and the geometric
 * normal, then the type's BxDFs.
 */
#include <stdio.h>
#include <string.h>
#include "materials/material_impl.h"
#include "materials/uniform.h"
#include "core/alloc.h"

/* The registry: pbrt-v2's names, one creator each. */
#define MATERIALS(X)                                                                     \
    X(matte) X(plastic) X(glass) X(mirror) X(metal) X(shinymetal) X(substrate)            \
    X(translucent) X(uber) X(mix) X(measured) X(subsurface) X(kdsubsurface)
#define NAME(n) #n,
#define CREATOR(n) mt__##n##_create,
#define OPS(n) &mt__##n##_ops,
static const char *const names[] = {MATERIALS(NAME)};
static const mt_material_create_fn creators[] = {MATERIALS(CREATOR)};
static const mt_material_ops *const all_ops[] = {MATERIALS(OPS)};
#define NTYPES (int)(sizeof names / sizeof names[0])

const mt_material_ops *mt__material_ops(const char *type)
{
    int i;
    for (i = 0; i < NTYPES; ++i)
        if (!strcmp(names[i], type)) return all_ops[i];
    return NULL;
}

const char *mt__range_text(mt_range r)
{
    switch (r) {
    case MT_RANGE_ANY: return "any";
    case MT_RANGE_CLAMP0: return "any; below 0 taken as 0";
    case MT_RANGE_SIGMA: return "any; clamped to [0, 90]";
    case MT_RANGE_APPROX: return "any; clamped to [0, 0.999]";
    case MT_RANGE_NONNEG: return ">= 0";
    case MT_RANGE_POS: return "> 0";
    }
    return "?";
}

void mt__material_locate_param(const mt_texparams *tp, const char *name, mt_error *err)
{
    const mt_param *p = tp->geom ? mt_paramset_find(tp->geom, name) : NULL;
    if (!p && tp->material) p = mt_paramset_find(tp->material, name);
    if (p && p->file) mt_error_locate(err, p->file, p->line, p->column);
}

/* A constant value (a plain value, or a "texture" naming a constant texture)
 * outside the slot's range: an error naming the parameter, at its line.
 * pbrt-v2 would build BxDFs with a negative exponent or a zero index, which
 * render black or NaN; a texture that varies is evaluated per point and a
 * bad value there fails where the BSDF is built. */
static mt_status check_range(const mt_tex_slot *sl, const mt_texture *t, const mt_texparams *tp,
                             mt_error *err)
{
    mt_diffgeom dg = mt_diffgeom_default();
    mt_rgb v;
    int c, n = sl->is_float ? 1 : 3;
    if ((sl->range != MT_RANGE_NONNEG && sl->range != MT_RANGE_POS) ||
        strcmp(mt_texture_class(t), "constant") != 0)
        return MT_OK;
    v = mt_texture_eval_rgb(t, &dg);
    for (c = 0; c < n; ++c) {
        mt_real x = v.c[c];
        /* -0 too: 1/-0 is an exponent of -infinity */
        int ok = sl->range == MT_RANGE_POS ? x > 0 : (x > 0 || (x == 0 && !signbit(x)));
        if (ok) continue;
        if (n == 1)
            mt_error_param(err, MT_ERR_INVALID, sl->name, "%s is %g%s; it must be %s", sl->name, (double)x,
                           x == 0 && signbit(x) ? " (its inverse is -infinity)" : "", mt__range_text(sl->range));
        else
            mt_error_param(err, MT_ERR_INVALID, sl->name, "%s is [%g %g %g]; each component must be %s",
                           sl->name, (double)v.c[0], (double)v.c[1], (double)v.c[2], mt__range_text(sl->range));
        mt__material_locate_param(tp, sl->name, err);
        return MT_ERR_INVALID;
    }
    return MT_OK;
}

const char *const *mt_material_types(int *count)
{
    if (count) *count = NTYPES;
    return names;
}

mt_material *mt_material_create(const char *type, const mt_transform *mtl2world,
                                const mt_texparams *tp, const mt_material_ctx *ctx, mt_error *err)
{
    int i;
    mt_transform id = mt_transform_identity();
    mt_material_ctx none = {NULL, NULL, NULL, NULL};
    if (!type) return mt_error_set(err, MT_ERR_INVALID, "material: no type given"), NULL;
    for (i = 0; i < NTYPES; ++i)
        if (!strcmp(names[i], type)) return creators[i](mtl2world ? mtl2world : &id, tp, ctx ? ctx : &none, err);
    mt_error_set(err, MT_ERR_UNSUPPORTED, "material type \"%s\" unknown", type);
    return NULL;
}

void *mt__material_new(size_t size, const mt_material_ops *ops, const mt_texparams *tp, mt_error *err)
{
    mt_tex_slot slots[MT_MATERIAL_SLOTS];
    if (!ops->defaults) return mt__material_new_with(size, ops, ops->slots, tp, err);
    memcpy(slots, ops->slots, (size_t)ops->nslots * sizeof *slots);
    ops->defaults(slots);
    return mt__material_new_with(size, ops, slots, tp, err);
}

void *mt__material_new_with(size_t size, const mt_material_ops *ops, const mt_tex_slot *slots,
                            const mt_texparams *tp, mt_error *err)
{
    mt_material *m = mt__calloc(1, size);
    int i, nslots = ops->nslots;
    if (!m) {
        mt_error_set(err, MT_ERR_NOMEM, "out of memory creating a %s material", ops->type);
        return NULL;
    }
    m->ops = ops;
    m->refs = 1;
    m->mode = tp->mode;
    for (i = 0; i < nslots; ++i) {
        const mt_tex_slot *sl = &slots[i];
        m->tex[i] = sl->is_float
                        ? mt_texparams_float_texture(tp, sl->name, sl->def[0], err)
                        : mt_texparams_spectrum_texture(tp, sl->name, mt_rgb_make(sl->def[0], sl->def[1], sl->def[2]), err);
        if (!m->tex[i] || check_range(sl, m->tex[i], tp, err) != MT_OK) break;
    }
    /* a type with its own get_bsdf (the mix) has no "bumpmap" in pbrt-v2 */
    if (i < nslots || (!ops->get_bsdf && mt_texparams_float_texture_opt(tp, "bumpmap", &m->bump, err) != MT_OK)) {
        if (err) { /* say which material the parameter belongs to */
            char msg[sizeof err->message];
            snprintf(msg, sizeof msg, "%s", err->message);
            snprintf(err->message, sizeof err->message, "%s material: %.480s", ops->type, msg);
        }
        mt_material_release(m);
        return NULL;
    }
    return m;
}

mt_material *mt_material_retain(mt_material *m)
{
    if (m) __atomic_add_fetch(&m->refs, 1, __ATOMIC_RELAXED);
    return m;
}

void mt_material_release(mt_material *m)
{
    int i;
    if (!m || __atomic_sub_fetch(&m->refs, 1, __ATOMIC_ACQ_REL) != 0) return;
    if (m->ops->destroy) m->ops->destroy(m);
    mt_texture_release(m->bump);
    for (i = 0; i < MT_MATERIAL_SLOTS; ++i) mt_texture_release(m->tex[i]);
    mt__free(m);
}

const char *mt_material_type(const mt_material *m) { return m->ops->type; }
mt_mode mt_material_mode(const mt_material *m) { return m->mode; }

mt_bsdf *mt_material_get_bsdf(const mt_material *m, const mt_diffgeom *dg_geom,
                              const mt_diffgeom *dg_shading, mt_arena *arena, mt_error *err)
{
    mt_diffgeom bumped;
    const mt_diffgeom *dgs = dg_shading;
    mt_bsdf *b;
    if (m->ops->get_bsdf) return m->ops->get_bsdf(m, dg_geom, dg_shading, arena, err);
    if (m->bump) {
        mt_bump(m->bump, dg_geom, dg_shading, &bumped, 0);
        dgs = &bumped;
    }
    b = mt_bsdf_create(arena, m->mode, dgs, dg_geom->n, m->ops->eta ? m->ops->eta(m, dgs) : 1, err);
    if (!b) return NULL;
    if (m->ops->add_bxdfs(m, b, dgs, arena, err) != MT_OK) return NULL;
    return b;
}

int mt_material_get_bssrdf(const mt_material *m, const mt_diffgeom *dg_geom, const mt_diffgeom *dg_shading,
                           mt_bssrdf *out)
{
    /* pbrt-v2's GetBSSRDF reads the unbumped shading point */
    return m->ops->bssrdf ? m->ops->bssrdf(m, dg_shading, NULL, out) : 0;
}

int mt__material_has_bssrdf(const mt_material *m) { return m->ops->bssrdf != NULL; }

static int is_constant(const mt_texture *t) { return strcmp(mt_texture_class(t), "constant") == 0; }

int mt__material_is_uniform(const mt_material *m)
{
    int i;
    /* A constant bump map moves the tangents by (d - d) / du = 0 whatever du
     * the differentials give (mt_bump): the same frame without them. */
    if (m->bump && !is_constant(m->bump)) return 0;
    for (i = 0; i < m->ops->nslots; ++i)
        if (!is_constant(m->tex[i])) return 0;
    /* a get_bsdf of its own: only the mix's is known to read nothing else */
    if (m->ops->get_bsdf) return mt__mix_is_uniform(m);
    return 1;
}

int mt__material_get_bssrdf_cached(const mt_material *m, const mt_diffgeom *dg_shading,
                                   mt__bssrdf_cache *cache, mt_bssrdf *out)
{
    return m->ops->bssrdf ? m->ops->bssrdf(m, dg_shading, cache, out) : 0;
}

int mt__material_max_bxdfs(const mt_material *m) { return m->ops->max_bxdfs(m); }

int mt__slot_constant(const mt_material *m, int i, mt_rgb *v)
{
    mt_diffgeom dg;
    if (!is_constant(m->tex[i])) return 0;
    dg = mt_diffgeom_default();
    *v = mt_texture_eval_rgb(m->tex[i], &dg);
    return 1;
}

int mt__slot_may_be_nonblack(const mt_material *m, int i)
{
    mt_rgb v;
    return !mt__slot_constant(m, i, &v) || !mt_rgb_is_black(mt_rgb_clamp0(v));
}

mt_rgb mt__tex_rgb(const mt_texture *t, const mt_diffgeom *dg) { return mt_rgb_clamp0(mt_texture_eval_rgb(t, dg)); }
mt_real mt__tex_float(const mt_texture *t, const mt_diffgeom *dg) { return mt_texture_eval_float(t, dg); }

