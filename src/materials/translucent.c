/*
 * translucent (pbrt-v2 translucent.cpp): diffuse and glossy lobes, each both
 * reflected (scaled by "reflect") and transmitted as a mirrored BRDF (scaled
 * by "transmit"). pbrt-v2's translucent has no "index" parameter: the index
 * is 1.5, the BSDF's eta and the glossy Fresnel term's, which pbrt-v2 builds
 * as FresnelDielectric(1.5, 1) (erratum dielectric-side). A lobe whose scale
 * (reflect or transmit times Kd or Ks) is black is left out, as in pbrt-v2.
 */
#include "materials/material_impl.h"

enum { KD, KS, ROUGHNESS, REFLECT, TRANSMIT };
static const mt_tex_slot slots[] = {
    {"Kd", 0, {0.25f, 0.25f, 0.25f}, MT_RANGE_CLAMP0, "diffuse reflectance"},
    {"Ks", 0, {0.25f, 0.25f, 0.25f}, MT_RANGE_CLAMP0, "glossy reflectance"},
    {"roughness", 1, {0.1f}, MT_RANGE_NONNEG, "the Blinn exponent is 1/roughness (at most 10000)"},
    {"reflect", 0, {0.5f, 0.5f, 0.5f}, MT_RANGE_CLAMP0, "scale of the reflected lobes"},
    {"transmit", 0, {0.5f, 0.5f, 0.5f}, MT_RANGE_CLAMP0, "scale of the transmitted lobes"}};

static int translucent_max(const mt_material *m)
{
    int r = mt__slot_may_be_nonblack(m, REFLECT), t = mt__slot_may_be_nonblack(m, TRANSMIT);
    return (mt__slot_may_be_nonblack(m, KD) + mt__slot_may_be_nonblack(m, KS)) * (r + t);
}

#define TRANSLUCENT_IOR 1.5f

static mt_real translucent_eta(const mt_material *m, const mt_diffgeom *dgs) { return TRANSLUCENT_IOR; }

static mt_status translucent_add(const mt_material *m, mt_bsdf *b, const mt_diffgeom *dgs, mt_arena *a, mt_error *err)
{
    mt_real ior = TRANSLUCENT_IOR;
    mt_rgb r = MT_RGB(m, REFLECT, dgs), t = MT_RGB(m, TRANSMIT, dgs), kd, ks;
    mt_mode mode = m->mode;
    if (mt_rgb_is_black(r) && mt_rgb_is_black(t)) return MT_OK;
    kd = MT_RGB(m, KD, dgs);
    if (!mt_rgb_is_black(kd)) {
        if (!mt_rgb_is_black(r)) MT_ADD(b, mt_lambertian_create(a, mode, mt_rgb_mul(r, kd), err), err);
        if (!mt_rgb_is_black(t))
            MT_ADD(b, mt_brdf_to_btdf_create(a, mode, mt_lambertian_create(a, mode, mt_rgb_mul(t, kd), err), err),
                   err);
    }
    ks = MT_RGB(m, KS, dgs);
    if (!mt_rgb_is_black(ks)) {
        mt_real rough = MT_FLOAT(m, ROUGHNESS, dgs);
        mt_fresnel fr = (mode & MT_FIX_DIELECTRIC_SIDE) ? mt_fresnel_dielectric(1, ior) : mt_fresnel_dielectric(ior, 1);
        if (!mt_rgb_is_black(r))
            MT_ADD(b, mt_microfacet_create(a, mode, mt_rgb_mul(r, ks), fr, mt_blinn(1 / rough), err), err);
        if (!mt_rgb_is_black(t))
            MT_ADD(b,
                   mt_brdf_to_btdf_create(a, mode, mt_microfacet_create(a, mode, mt_rgb_mul(t, ks), fr, mt_blinn(1 / rough), err),
                                          err),
                   err);
    }
    return MT_OK;
}

const mt_material_ops mt__translucent_ops = {"translucent", translucent_max, translucent_add, translucent_eta, NULL, NULL, NULL, slots, 5, NULL, NULL, 0};

mt_material *mt__translucent_create(const mt_transform *xf, const mt_texparams *tp, const mt_material_ctx *ctx,
                                    mt_error *err)
{
    return mt__material_new(sizeof(mt_material), &mt__translucent_ops, tp, err);
}
