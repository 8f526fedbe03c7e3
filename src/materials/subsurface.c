/*
 * subsurface and kdsubsurface (pbrt-v2 subsurface.cpp, kdsubsurface.cpp): a
 * specular dielectric surface (Kr with FresnelDielectric(1, index)) over a
 * medium the dipole integrator renders. subsurface takes sigma_a and
 * sigma_prime_s (or a named measured medium, "name"), times "scale";
 * kdsubsurface inverts a diffuse reflectance Kd and a mean free path.
 * pbrt-v2 evaluates the BSSRDF at the unbumped shading point.
 */
#include <string.h>
#include "materials/material_impl.h"
#include "materials/media.h"

enum { KR, INDEX, SIGMA_A, SIGMA_PRIME_S };
enum { KD = SIGMA_A, MFP };

typedef struct subsurface {
    mt_material base;
    mt_real scale;
} subsurface;

static int ss_max(const mt_material *m) { return mt__slot_may_be_nonblack(m, KR); }

static mt_status ss_add(const mt_material *m, mt_bsdf *b, const mt_diffgeom *dgs, mt_arena *a, mt_error *err)
{
    mt_rgb R = MT_RGB(m, KR, dgs);
    mt_real e = MT_FLOAT(m, INDEX, dgs);
    if (!mt_rgb_is_black(R)) MT_ADD(b, mt_specular_reflection_create(a, m->mode, R, mt_fresnel_dielectric(1, e), err), err);
    return MT_OK;
}

static int ss_bssrdf(const mt_material *m, const mt_diffgeom *dgs, mt__bssrdf_cache *cache, mt_bssrdf *out)
{
    mt_real scale = ((const subsurface *)m)->scale;
    /* pbrt-v2 does not clamp these */
    out->sigma_a = mt_rgb_scale(mt_texture_eval_rgb(m->tex[SIGMA_A], dgs), scale);
    out->sigma_prime_s = mt_rgb_scale(mt_texture_eval_rgb(m->tex[SIGMA_PRIME_S], dgs), scale);
    out->eta = MT_FLOAT(m, INDEX, dgs);
    return 1;
}

static int kd_bssrdf(const mt_material *m, const mt_diffgeom *dgs, mt__bssrdf_cache *cache, mt_bssrdf *out)
{
    mt_real e = MT_FLOAT(m, INDEX, dgs), mfp = MT_FLOAT(m, MFP, dgs);
    mt__subsurface_from_diffuse_cached(cache, MT_RGB(m, KD, dgs), mfp, e, &out->sigma_a, &out->sigma_prime_s);
    out->eta = e;
    return 1;
}

/* pbrt-v2's defaults for sigma_a and sigma_prime_s are whole milk's
 * coefficients; a "name" replaces them with the named medium's */
static const mt_tex_slot ss_slots[] = {
    {"Kr", 0, {1, 1, 1}, MT_RANGE_CLAMP0, "specular reflectance of the surface"},
    {"index", 1, {1.3f}, MT_RANGE_POS, "index of refraction of the surface and the medium"},
    {"sigma_a", 0, {0.0011f, 0.0024f, 0.014f}, MT_RANGE_NONNEG,
     "absorption coefficient, per mm (default: whole milk's, or the named medium's)"},
    {"sigma_prime_s", 0, {2.55f, 3.21f, 3.77f}, MT_RANGE_NONNEG,
     "reduced scattering coefficient, per mm (default: whole milk's, or the named medium's)"}};
static const mt_param_doc ss_other[] = {
    {"name", "string", "\"\" (none)", "a medium of the table below",
     "a measured medium whose coefficients become the defaults of sigma_a and sigma_prime_s"},
    {"scale", "float", "1", "> 0", "factor on sigma_a and sigma_prime_s (scene units per mm)"}};
static const mt_tex_slot kd_slots[] = {
    {"Kr", 0, {1, 1, 1}, MT_RANGE_CLAMP0, "specular reflectance of the surface"},
    {"index", 1, {1.3f}, MT_RANGE_POS, "index of refraction of the surface and the medium"},
    {"Kd", 0, {0.5f, 0.5f, 0.5f}, MT_RANGE_CLAMP0, "diffuse reflectance the medium is made to have"},
    {"meanfreepath", 1, {1}, MT_RANGE_POS, "mean free path in the medium"}};

const mt_material_ops mt__subsurface_ops = {"subsurface", ss_max, ss_add, NULL, ss_bssrdf, NULL, NULL,
                                            ss_slots, 4, NULL, ss_other, 2};
const mt_material_ops mt__kdsubsurface_ops = {"kdsubsurface", ss_max, ss_add, NULL, kd_bssrdf, NULL, NULL,
                                              kd_slots, 4, NULL, NULL, 0};

mt_material *mt__subsurface_create(const mt_transform *xf, const mt_texparams *tp, const mt_material_ctx *ctx,
                                   mt_error *err)
{
    mt_rgb sa = mt_rgb_black(), sps = sa;
    const char *name = "";
    mt_real scale = 1;
    mt_tex_slot slots[4];
    subsurface *x;
    int c;
    memcpy(slots, ss_slots, sizeof slots);
    if (mt_texparams_string(tp, "name", "", &name, err) || mt_texparams_float(tp, "scale", 1, &scale, err))
        return NULL;
    if (name[0] && !mt__medium_lookup(name, &sa, &sps)) {
        /* pbrt-v2 warns and uses the defaults: a misspelt medium is an error here */
        mt_error_param(err, MT_ERR_NOT_FOUND, "name", "subsurface material: no measured medium named \"%s\"", name);
        mt__material_locate_param(tp, "name", err);
        return NULL;
    }
    if (!(mt_is_finite(scale) && scale > 0)) {
        /* no coefficients, or negative ones: the dipole divides by them */
        mt_error_param(err, MT_ERR_INVALID, "scale", "subsurface material: scale is %g; it must be > 0",
                       (double)scale);
        mt__material_locate_param(tp, "scale", err);
        return NULL;
    }
    for (c = 0; name[0] && c < 3; ++c) {
        slots[SIGMA_A].def[c] = sa.c[c];
        slots[SIGMA_PRIME_S].def[c] = sps.c[c];
    }
    x = mt__material_new_with(sizeof *x, &mt__subsurface_ops, slots, tp, err);
    if (x) x->scale = scale;
    return x ? &x->base : NULL;
}

mt_material *mt__kdsubsurface_create(const mt_transform *xf, const mt_texparams *tp, const mt_material_ctx *ctx,
                                     mt_error *err)
{
    return mt__material_new(sizeof(mt_material), &mt__kdsubsurface_ops, tp, err);
}
