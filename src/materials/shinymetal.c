/*
 * shinymetal (pbrt-v2 shinymetal.cpp): a Blinn microfacet lobe and a specular
 * lobe, each a conductor whose normal-incidence reflectance is Ks (resp. Kr):
 * eta from FresnelApproxEta and k = 0 (pbrt-v2 defines FresnelApproxK but
 * builds both conductors with k = 0, which inverts the reflectance exactly).
 * A black Ks adds no glossy lobe and a black Kr no specular one (pbrt-v2
 * commit 4c20ad4). Without "bumpmap" there is no bump mapping, as for every
 * material (pbrt-v2 commit bab4b9b; the 2012 source bump-mapped with a
 * constant 0, which turns the shading normal to the geometric normal's side).
 */
#include "materials/material_impl.h"

enum { KS, ROUGHNESS, KR };
static const mt_tex_slot slots[] = {
    {"Ks", 0, {1, 1, 1}, MT_RANGE_APPROX, "normal-incidence reflectance of the glossy lobe"},
    {"roughness", 1, {0.1f}, MT_RANGE_NONNEG, "the Blinn exponent is 1/roughness (at most 10000)"},
    {"Kr", 0, {1, 1, 1}, MT_RANGE_APPROX, "normal-incidence reflectance of the specular lobe"}};

static int shiny_max(const mt_material *m) { return mt__slot_may_be_nonblack(m, KS) + mt__slot_may_be_nonblack(m, KR); }

static mt_status shiny_add(const mt_material *m, mt_bsdf *b, const mt_diffgeom *dgs, mt_arena *a, mt_error *err)
{
    mt_rgb spec = MT_RGB(m, KS, dgs), R = MT_RGB(m, KR, dgs);
    mt_real rough = MT_FLOAT(m, ROUGHNESS, dgs);
    if (!mt_rgb_is_black(spec)) {
        mt_fresnel frmf = mt_fresnel_conductor(mt_fresnel_approx_eta(spec), mt_rgb_black());
        MT_ADD(b, mt_microfacet_create(a, m->mode, mt_rgb_gray(1), frmf, mt_blinn(1 / rough), err), err);
    }
    if (!mt_rgb_is_black(R)) {
        mt_fresnel frsr = mt_fresnel_conductor(mt_fresnel_approx_eta(R), mt_rgb_black());
        MT_ADD(b, mt_specular_reflection_create(a, m->mode, mt_rgb_gray(1), frsr, err), err);
    }
    return MT_OK;
}

const mt_material_ops mt__shinymetal_ops = {"shinymetal", shiny_max, shiny_add, NULL, NULL, NULL, NULL, slots, 3, NULL, NULL, 0};

mt_material *mt__shinymetal_create(const mt_transform *xf, const mt_texparams *tp, const mt_material_ctx *ctx,
                                   mt_error *err)
{
    return mt__material_new(sizeof(mt_material), &mt__shinymetal_ops, tp, err);
}
