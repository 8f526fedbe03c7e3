/* substrate (pbrt-v2 substrate.cpp): FresnelBlend with the Ashikhmin-Shirley
 * anisotropic distribution, exponents 1/uroughness and 1/vroughness. The
 * lobe is left out when Kd and Ks are both black (pbrt-v2 commit 4c20ad4). */
#include "materials/material_impl.h"

enum { KD, KS, UROUGH, VROUGH };
static const mt_tex_slot slots[] = {
    {"Kd", 0, {0.5f, 0.5f, 0.5f}, MT_RANGE_CLAMP0, "diffuse reflectance of the substrate"},
    {"Ks", 0, {0.5f, 0.5f, 0.5f}, MT_RANGE_CLAMP0, "normal-incidence reflectance of the coat"},
    {"uroughness", 1, {0.1f}, MT_RANGE_NONNEG, "the anisotropic exponent along dpdu is 1/uroughness"},
    {"vroughness", 1, {0.1f}, MT_RANGE_NONNEG, "the anisotropic exponent along dpdv is 1/vroughness"}};

static int substrate_max(const mt_material *m) { return mt__slot_may_be_nonblack(m, KD) || mt__slot_may_be_nonblack(m, KS); }

static mt_status substrate_add(const mt_material *m, mt_bsdf *b, const mt_diffgeom *dgs, mt_arena *a, mt_error *err)
{
    mt_rgb d = MT_RGB(m, KD, dgs), s = MT_RGB(m, KS, dgs);
    mt_real u, v;
    if (mt_rgb_is_black(d) && mt_rgb_is_black(s)) return MT_OK;
    u = MT_FLOAT(m, UROUGH, dgs);
    v = MT_FLOAT(m, VROUGH, dgs);
    return mt_bsdf_add(b, mt_fresnelblend_create(a, m->mode, d, s, mt_anisotropic(1 / u, 1 / v), err), err);
}

const mt_material_ops mt__substrate_ops = {"substrate", substrate_max, substrate_add, NULL, NULL, NULL, NULL, slots, 4, NULL, NULL, 0};

mt_material *mt__substrate_create(const mt_transform *xf, const mt_texparams *tp, const mt_material_ctx *ctx, mt_error *err)
{
    return mt__material_new(sizeof(mt_material), &mt__substrate_ops, tp, err);
}
