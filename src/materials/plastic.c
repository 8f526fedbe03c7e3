/* plastic (pbrt-v2 plastic.cpp): a Lambertian base and a Blinn microfacet
 * coat. pbrt-v2 builds the coat's Fresnel term as FresnelDielectric(1.5, 1),
 * the dielectric seen from inside (erratum dielectric-side). A black Kd adds
 * no Lambertian and a black Ks no coat (pbrt-v2 commit 4c20ad4; its 2012
 * source added both whatever they were, so that half the samples went to a
 * black lobe and every pdf averaged over two components). */
#include "materials/material_impl.h"

enum { KD, KS, ROUGHNESS };
static const mt_tex_slot slots[] = {
    {"Kd", 0, {0.25f, 0.25f, 0.25f}, MT_RANGE_CLAMP0, "diffuse reflectance"},
    {"Ks", 0, {0.25f, 0.25f, 0.25f}, MT_RANGE_CLAMP0, "glossy reflectance"},
    {"roughness", 1, {0.1f}, MT_RANGE_NONNEG, "the Blinn exponent is 1/roughness (at most 10000)"}};

static int plastic_max(const mt_material *m) { return mt__slot_may_be_nonblack(m, KD) + mt__slot_may_be_nonblack(m, KS); }

static mt_status plastic_add(const mt_material *m, mt_bsdf *b, const mt_diffgeom *dgs, mt_arena *a, mt_error *err)
{
    mt_rgb kd = MT_RGB(m, KD, dgs), ks;
    mt_fresnel fr;
    mt_real rough;
    if (!mt_rgb_is_black(kd)) MT_ADD(b, mt_lambertian_create(a, m->mode, kd, err), err);
    ks = MT_RGB(m, KS, dgs);
    if (mt_rgb_is_black(ks)) return MT_OK;
    fr = (m->mode & MT_FIX_DIELECTRIC_SIDE) ? mt_fresnel_dielectric(1, 1.5f) : mt_fresnel_dielectric(1.5f, 1);
    rough = MT_FLOAT(m, ROUGHNESS, dgs);
    MT_ADD(b, mt_microfacet_create(a, m->mode, ks, fr, mt_blinn(1 / rough), err), err);
    return MT_OK;
}

const mt_material_ops mt__plastic_ops = {"plastic", plastic_max, plastic_add, NULL, NULL, NULL, NULL, slots, 3, NULL, NULL, 0};

mt_material *mt__plastic_create(const mt_transform *xf, const mt_texparams *tp, const mt_material_ctx *ctx, mt_error *err)
{
    return mt__material_new(sizeof(mt_material), &mt__plastic_ops, tp, err);
}
