/* mirror (pbrt-v2 mirror.cpp): specular reflection with no Fresnel term. */
#include "materials/material_impl.h"

static const mt_tex_slot slots[] = {{"Kr", 0, {0.9f, 0.9f, 0.9f}, MT_RANGE_CLAMP0, "specular reflectance (no Fresnel term)"}};

static int mirror_max(const mt_material *m) { return mt__slot_may_be_nonblack(m, 0); }

static mt_status mirror_add(const mt_material *m, mt_bsdf *b, const mt_diffgeom *dgs, mt_arena *a, mt_error *err)
{
    mt_rgb R = MT_RGB(m, 0, dgs);
    if (!mt_rgb_is_black(R)) MT_ADD(b, mt_specular_reflection_create(a, m->mode, R, mt_fresnel_noop(), err), err);
    return MT_OK;
}

const mt_material_ops mt__mirror_ops = {"mirror", mirror_max, mirror_add, NULL, NULL, NULL, NULL, slots, 1, NULL, NULL, 0};

mt_material *mt__mirror_create(const mt_transform *xf, const mt_texparams *tp, const mt_material_ctx *ctx, mt_error *err)
{
    return mt__material_new(sizeof(mt_material), &mt__mirror_ops, tp, err);
}
