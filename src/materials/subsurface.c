/*
 * subsurface and kdsubsurface (pbrt-v2 subsurface.cpp, kdsubsurface.cpp): a
 * specular dielectric surface (Kr with FresnelDielectric(1, index)) over a
 * medium the dipole integrator renders. subsurface takes sigma_a and
 * sigma_prime_s (or a named measured medium, "name"), times "scale";
 * kdsubsurface inverts a diffuse reflectance Kd and a mean free path.
 * pbrt-v2 evaluates the BSSRDF at the unbumped shading point.
 */
#include "materials/material_impl.h"
#include "materials/media.h"

enum { KR, INDEX, SIGMA_A, SIGMA_PRIME_S };
enum { KD = SIGMA_A, MFP };

typedef struct subsurface {
    mt_material base;
    mt_real scale;
} subsurface;

static int ss_max(const mt_material *m) { return 1; }

static mt_status ss_add(const mt_material *m, mt_bsdf *b, const mt_diffgeom *dgs, mt_arena *a, mt_error *err)
{
    mt_rgb R = MT_RGB(m, KR, dgs);
    mt_real e = MT_FLOAT(m, INDEX, dgs);
    if (!mt_rgb_is_black(R)) MT_ADD(b, mt_specular_reflection_create(a, m->mode, R, mt_fresnel_dielectric(1, e), err), err);
    return MT_OK;
}

static int ss_bssrdf(const mt_material *m, const mt_diffgeom *dgs, mt_bssrdf *out)
{
    mt_real scale = ((const subsurface *)m)->scale;
    /* pbrt-v2 does not clamp these */
    out->sigma_a = mt_rgb_scale(mt_texture_eval_rgb(m->tex[SIGMA_A], dgs), scale);
    out->sigma_prime_s = mt_rgb_scale(mt_texture_eval_rgb(m->tex[SIGMA_PRIME_S], dgs), scale);
    out->eta = MT_FLOAT(m, INDEX, dgs);
    return 1;
}

static int kd_bssrdf(const mt_material *m, const mt_diffgeom *dgs, mt_bssrdf *out)
{
    mt_real e = MT_FLOAT(m, INDEX, dgs), mfp = MT_FLOAT(m, MFP, dgs);
    mt_subsurface_from_diffuse(MT_RGB(m, KD, dgs), mfp, e, &out->sigma_a, &out->sigma_prime_s);
    out->eta = e;
    return 1;
}

static const mt_material_ops ss_ops = {"subsurface", ss_max, ss_add, NULL, ss_bssrdf, NULL, NULL};
static const mt_material_ops kd_ops = {"kdsubsurface", ss_max, ss_add, NULL, kd_bssrdf, NULL, NULL};

mt_material *mt__subsurface_create(const mt_transform *xf, const mt_texparams *tp, const mt_material_ctx *ctx,
                                   mt_error *err)
{
    /* pbrt-v2's defaults are whole milk's coefficients */
    mt_rgb sa = mt_rgb_make(0.0011f, 0.0024f, 0.014f), sps = mt_rgb_make(2.55f, 3.21f, 3.77f);
    const char *name = "";
    mt_real scale = 1;
    mt_tex_slot slots[4] = {{"Kr", 0, {1, 1, 1}}, {"index", 1, {1.3f}}, {"sigma_a", 0, {0}}, {"sigma_prime_s", 0, {0}}};
    subsurface *x;
    int c;
    if (mt_texparams_string(tp, "name", "", &name, err) || mt_texparams_float(tp, "scale", 1, &scale, err))
        return NULL;
    if (name[0] && !mt__medium_lookup(name, &sa, &sps)) {
        /* pbrt-v2 warns and uses the defaults: a misspelt medium is an error here */
        mt_error_param(err, MT_ERR_NOT_FOUND, "name", "subsurface material: no measured medium named \"%s\"", name);
        return NULL;
    }
    if (!mt_is_finite(scale)) {
        mt_error_param(err, MT_ERR_INVALID, "scale", "subsurface material: scale is not finite");
        return NULL;
    }
    for (c = 0; c < 3; ++c) {
        slots[SIGMA_A].def[c] = sa.c[c];
        slots[SIGMA_PRIME_S].def[c] = sps.c[c];
    }
    x = mt__material_new(sizeof *x, &ss_ops, slots, 4, tp, err);
    if (x) x->scale = scale;
    return x ? &x->base : NULL;
}

mt_material *mt__kdsubsurface_create(const mt_transform *xf, const mt_texparams *tp, const mt_material_ctx *ctx,
                                     mt_error *err)
{
    static const mt_tex_slot slots[4] = {
        {"Kr", 0, {1, 1, 1}}, {"index", 1, {1.3f}}, {"Kd", 0, {0.5f, 0.5f, 0.5f}}, {"meanfreepath", 1, {1}}};
    return mt__material_new(sizeof(mt_material), &kd_ops, slots, 4, tp, err);
}
