/*
 * mix (pbrt-v2 mixmat.cpp): the BSDFs of two named materials, each component
 * wrapped in a ScaledBxDF: namedmaterial1's by amount, namedmaterial2's by
 * 1 - amount (both clamped from below). pbrt-v2 writes the second material's
 * components after the first's without a bound, past its 8 slots when they
 * are more (erratum mix-overflow): here a mix that can make more than 8 at
 * some point is an error when created (a lobe that a constant black parameter
 * leaves out at every point does not count).
 * A missing named material is an error (pbrt-v2 warns and uses a matte).
 */
#include <stdio.h>
#include <string.h>
#include "materials/material_impl.h"
#include "materials/uniform.h"

enum { AMOUNT };
static const mt_tex_slot slots[] = {
    {"amount", 0, {0.5f, 0.5f, 0.5f}, MT_RANGE_CLAMP0,
     "weight of namedmaterial1; namedmaterial2 has 1 - amount, also taken as 0 below 0"}};
static const mt_param_doc other[] = {
    {"namedmaterial1", "string", "(required)", "a MakeNamedMaterial name", "the first material"},
    {"namedmaterial2", "string", "(required)", "a MakeNamedMaterial name", "the second material"}};

typedef struct mix {
    mt_material base;
    mt_material *m1, *m2;
} mix;

static int mix_max(const mt_material *m)
{
    const mix *x = (const mix *)m;
    return mt__material_max_bxdfs(x->m1) + mt__material_max_bxdfs(x->m2);
}

static mt_bsdf *mix_get_bsdf(const mt_material *m, const mt_diffgeom *dg_geom, const mt_diffgeom *dg_shading,
                             mt_arena *arena, mt_error *err)
{
    const mix *x = (const mix *)m;
    mt_bsdf *b1 = mt_material_get_bsdf(x->m1, dg_geom, dg_shading, arena, err), *b2;
    mt_rgb s1, s2;
    int i, n1, n2;
    if (!b1) return NULL;
    b2 = mt_material_get_bsdf(x->m2, dg_geom, dg_shading, arena, err);
    if (!b2) return NULL;
    /* pbrt-v2 evaluates the amount at the unbumped shading point */
    s1 = MT_RGB(m, AMOUNT, dg_shading);
    s2 = mt_rgb_clamp0(mt_rgb_sub(mt_rgb_gray(1), s1));
    n1 = mt_bsdf_count(b1);
    n2 = mt_bsdf_count(b2);
    for (i = 0; i < n1; ++i) {
        mt_bxdf *sc = mt_scaled_bxdf_create(arena, m->mode, mt_bsdf_component(b1, i), s1, err);
        if (!sc) return NULL;
        mt__bsdf_set_component(b1, i, sc);
    }
    for (i = 0; i < n2; ++i)
        if (mt_bsdf_add(b1, mt_scaled_bxdf_create(arena, m->mode, mt_bsdf_component(b2, i), s2, err), err)) return NULL;
    return b1;
}

int mt__mix_is_uniform(const mt_material *m)
{
    const mix *x = (const mix *)m;
    return m->ops == &mt__mix_ops && mt__material_is_uniform(x->m1) && mt__material_is_uniform(x->m2);
}

static void mix_destroy(mt_material *m)
{
    mix *x = (mix *)m;
    mt_material_release(x->m1);
    mt_material_release(x->m2);
}

const mt_material_ops mt__mix_ops = {"mix", mix_max, NULL, NULL, NULL, mix_destroy, mix_get_bsdf, slots, 1, NULL, other, 2};

static mt_material *named(const mt_texparams *tp, const mt_material_ctx *ctx, const char *param, mt_error *err)
{
    const char *name = NULL;
    const mt_material *m;
    if (mt_texparams_string(tp, param, "", &name, err) != MT_OK) return NULL;
    if (!name[0]) {
        mt_error_param(err, MT_ERR_INVALID, param, "mix material: no \"string %s\" given", param);
        return NULL;
    }
    /* a lookup that fails to build the material it found says why in err
     * (out of memory, nesting too deep): that error is kept */
    mt_error_clear(err);
    m = ctx->lookup ? ctx->lookup(ctx->lookup_ctx, name) : NULL;
    if (!m) {
        if (err && err->status != MT_OK) return NULL;
        mt_error_param(err, MT_ERR_NOT_FOUND, param, "mix material: named material \"%s\" undefined", name);
        return NULL;
    }
    return mt_material_retain((mt_material *)m);
}

mt_material *mt__mix_create(const mt_transform *xf, const mt_texparams *tp, const mt_material_ctx *ctx, mt_error *err)
{
    mix *x = mt__material_new(sizeof *x, &mt__mix_ops, tp, err);
    if (!x) return NULL;
    if (!(x->m1 = named(tp, ctx, "namedmaterial1", err)) || !(x->m2 = named(tp, ctx, "namedmaterial2", err))) {
        mt_material_release(&x->base);
        return NULL;
    }
    if (mix_max(&x->base) > MT_MAX_BXDFS) {
        mt_error_set(err, MT_ERR_LIMIT,
                     "mix material: \"%s\" and \"%s\" can make %d BxDFs together, more than a BSDF holds (%d)",
                     mt_material_type(x->m1), mt_material_type(x->m2), mix_max(&x->base), MT_MAX_BXDFS);
        mt_material_release(&x->base);
        return NULL;
    }
    return &x->base;
}
