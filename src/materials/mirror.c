/* mirror (pbrt-v2 mirror.cpp): specular reflection with no Fresnel term. */
#include "materials/material_impl.h"

static const mt_tex_slot mirror_slots[] = {{"Kr", 0, {0.9f, 0.9f, 0.9f}, MT_RANGE_CLAMP0, "specular reflectance (no Fresnel term)"}};

static int mirror_max(const mt_material *m) { return mt__slot_may_be_nonblack(m, 0); }

static mt_status mirror_add(const mt_material *m, mt_bsdf *b, const mt_diffgeom *dgs, mt_arena *a, mt_error *err)
{
    mt_rgb R = MT_RGB(m, 0, dgs);
    if (!mt_rgb_is_black(R)) MT_ADD(b, mt_specular_reflection_create(a, m->mode, R, mt_fresnel_noop(), err), err);
    return MT_OK;
}

const mt_material_kind mt_mirror_material = {
    .type = "mirror",
    .max_bxdfs = mirror_max,
    .add_bxdfs = mirror_add,
    .slots = mirror_slots,
    .nslots = MT_COUNT(mirror_slots),
};

