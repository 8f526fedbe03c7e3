/*
 * uber (pbrt-v2 uber.cpp): opacity-weighted diffuse, glossy and specular
 * lobes plus transmission of 1 - opacity. pbrt-v2 clamps the opacity from
 * below only, so opacity > 1 gives a negative transmission (erratum
 * uber-opacity), and builds every dielectric lobe with (index, 1): the glossy
 * and specular Fresnel terms see the surface from inside and the specular
 * transmission refracts the opposite way to glass's (erratum dielectric-side).
 * pbrt-v2's BSDF for uber has eta 1.
 */
#include "materials/material_impl.h"

enum { KD, KS, KR, KT, ROUGHNESS, INDEX, OPACITY };
static const mt_tex_slot slots[] = {
    {"Kd", 0, {0.25f, 0.25f, 0.25f}, MT_RANGE_CLAMP0, "diffuse reflectance"},
    {"Ks", 0, {0.25f, 0.25f, 0.25f}, MT_RANGE_CLAMP0, "glossy reflectance"},
    {"Kr", 0, {0}, MT_RANGE_CLAMP0, "specular reflectance"},
    {"Kt", 0, {0}, MT_RANGE_CLAMP0, "specular transmittance"},
    {"roughness", 1, {0.1f}, MT_RANGE_NONNEG, "the Blinn exponent is 1/roughness (at most 10000)"},
    {"index", 1, {1.5f}, MT_RANGE_POS, "index of refraction of the glossy and specular lobes"},
    {"opacity", 0, {1, 1, 1}, MT_RANGE_CLAMP0,
     "weight of the lobes; 1 - opacity passes straight through (above 1: negative, erratum uber-opacity; "
     "clamped to [0, 1] in corrected mode)"}};

/* The lobes uber_add can add: the transmission of 1 - opacity unless the
 * opacity is the constant 1 (after the mode's clamp), and each scale's lobe
 * unless it or the opacity is a constant black. */
static int uber_max(const mt_material *m)
{
    mt_rgb op;
    int n;
    if (!mt__slot_constant(m, OPACITY, &op)) return 5;
    op = (m->mode & MT_FIX_UBER_OPACITY) ? mt_rgb_clamp(op, 0, 1) : mt_rgb_clamp0(op);
    n = !mt_rgb_equal(op, mt_rgb_gray(1));
    if (mt_rgb_is_black(op)) return n;
    return n + mt__slot_may_be_nonblack(m, KD) + mt__slot_may_be_nonblack(m, KS) + mt__slot_may_be_nonblack(m, KR) + mt__slot_may_be_nonblack(m, KT);
}

static mt_status uber_add(const mt_material *m, mt_bsdf *b, const mt_diffgeom *dgs, mt_arena *a, mt_error *err)
{
    mt_mode mode = m->mode;
    mt_rgb op = MT_RGB(m, OPACITY, dgs), kd, ks, kr, kt;
    mt_real e;
    if (mode & MT_FIX_UBER_OPACITY) op = mt_rgb_clamp(op, 0, 1);
    if (!mt_rgb_equal(op, mt_rgb_gray(1)))
        MT_ADD(b, mt_specular_transmission_create(a, mode, mt_rgb_sub(mt_rgb_gray(1), op), 1, 1, err), err);
    kd = mt_rgb_mul(op, MT_RGB(m, KD, dgs));
    if (!mt_rgb_is_black(kd)) MT_ADD(b, mt_lambertian_create(a, mode, kd, err), err);
    e = MT_FLOAT(m, INDEX, dgs);
    ks = mt_rgb_mul(op, MT_RGB(m, KS, dgs));
    if (!mt_rgb_is_black(ks)) {
        mt_fresnel fr = (mode & MT_FIX_DIELECTRIC_SIDE) ? mt_fresnel_dielectric(1, e) : mt_fresnel_dielectric(e, 1);
        mt_real rough = MT_FLOAT(m, ROUGHNESS, dgs);
        MT_ADD(b, mt_microfacet_create(a, mode, ks, fr, mt_blinn(1 / rough), err), err);
    }
    kr = mt_rgb_mul(op, MT_RGB(m, KR, dgs));
    if (!mt_rgb_is_black(kr)) {
        mt_fresnel fr = (mode & MT_FIX_DIELECTRIC_SIDE) ? mt_fresnel_dielectric(1, e) : mt_fresnel_dielectric(e, 1);
        MT_ADD(b, mt_specular_reflection_create(a, mode, kr, fr, err), err);
    }
    kt = mt_rgb_mul(op, MT_RGB(m, KT, dgs));
    if (!mt_rgb_is_black(kt)) {
        if (mode & MT_FIX_DIELECTRIC_SIDE)
            MT_ADD(b, mt_specular_transmission_create(a, mode, kt, 1, e, err), err);
        else
            MT_ADD(b, mt_specular_transmission_create(a, mode, kt, e, 1, err), err);
    }
    return MT_OK;
}

const mt_material_ops mt__uber_ops = {"uber", uber_max, uber_add, NULL, NULL, NULL, NULL, slots, 7, NULL, NULL, 0};

mt_material *mt__uber_create(const mt_transform *xf, const mt_texparams *tp, const mt_material_ctx *ctx, mt_error *err)
{
    return mt__material_new(sizeof(mt_material), &mt__uber_ops, tp, err);
}
