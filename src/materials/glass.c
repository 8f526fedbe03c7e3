/* glass (pbrt-v2 glass.cpp): specular reflection and transmission through a
 * dielectric of index "index"; the BSDF carries the index as its eta. */
#include "materials/material_impl.h"

enum { KR, KT, INDEX };
static const mt_tex_slot slots[] = {{"Kr", 0, {1, 1, 1}, MT_RANGE_CLAMP0, "specular reflectance"},
                                    {"Kt", 0, {1, 1, 1}, MT_RANGE_CLAMP0, "specular transmittance"},
                                    {"index", 1, {1.5f}, MT_RANGE_POS, "index of refraction (outside: 1)"}};

static int glass_max(const mt_material *m) { return mt__slot_may_be_nonblack(m, KR) + mt__slot_may_be_nonblack(m, KT); }

static mt_real glass_eta(const mt_material *m, const mt_diffgeom *dgs) { return MT_FLOAT(m, INDEX, dgs); }

static mt_status glass_add(const mt_material *m, mt_bsdf *b, const mt_diffgeom *dgs, mt_arena *a, mt_error *err)
{
    mt_real ior = MT_FLOAT(m, INDEX, dgs);
    mt_rgb R = MT_RGB(m, KR, dgs), T = MT_RGB(m, KT, dgs);
    if (!mt_rgb_is_black(R))
        MT_ADD(b, mt_specular_reflection_create(a, m->mode, R, mt_fresnel_dielectric(1, ior), err), err);
    if (!mt_rgb_is_black(T)) MT_ADD(b, mt_specular_transmission_create(a, m->mode, T, 1, ior, err), err);
    return MT_OK;
}

const mt_material_ops mt__glass_ops = {"glass", glass_max, glass_add, glass_eta, NULL, NULL, NULL, slots, 3, NULL, NULL, 0};

mt_material *mt__glass_create(const mt_transform *xf, const mt_texparams *tp, const mt_material_ctx *ctx, mt_error *err)
{
    return mt__material_new(sizeof(mt_material), &mt__glass_ops, tp, err);
}
