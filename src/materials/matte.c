/* matte (pbrt-v2 matte.cpp): Lambertian when sigma is 0, Oren-Nayar
 * otherwise, with sigma (degrees) clamped to [0, 90]; nothing when Kd is
 * black (pbrt-v2 commit 4c20ad4, "Fix some Materials to not add black BxDF
 * components": the BSDF is then empty, f = 0 and every sample fails). */
#include "materials/material_impl.h"

enum { KD, SIGMA };
static const mt_tex_slot slots[] = {
    {"Kd", 0, {0.5f, 0.5f, 0.5f}, MT_RANGE_CLAMP0, "diffuse reflectance"},
    {"sigma", 1, {0}, MT_RANGE_SIGMA, "Oren-Nayar roughness: the standard deviation of the facet angle, in degrees"}};

static int matte_max(const mt_material *m) { return mt__slot_may_be_nonblack(m, KD); }

static mt_status matte_add(const mt_material *m, mt_bsdf *b, const mt_diffgeom *dgs, mt_arena *a, mt_error *err)
{
    mt_rgb r = MT_RGB(m, KD, dgs);
    mt_real sig;
    if (mt_rgb_is_black(r)) return MT_OK;
    sig = mt_clamp(MT_FLOAT(m, SIGMA, dgs), 0, 90);
    if (sig == 0) return mt_bsdf_add(b, mt_lambertian_create(a, m->mode, r, err), err);
    return mt_bsdf_add(b, mt_orennayar_create(a, m->mode, r, sig, err), err);
}

const mt_material_ops mt__matte_ops = {"matte", matte_max, matte_add, NULL, NULL, NULL, NULL, slots, 2, NULL, NULL, 0};

mt_material *mt__matte_create(const mt_transform *xf, const mt_texparams *tp, const mt_material_ctx *ctx, mt_error *err)
{
    return mt__material_new(sizeof(mt_material), &mt__matte_ops, tp, err);
}
