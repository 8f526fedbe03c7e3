/*
 * The materials in the suite: each of pbrt-v2's material types over a grid of
 * its parameters, written as pbrt-v2 statements and built through the
 * graphics state as a scene would build them, at the default shading point.
 * The same checks run on them as on the BxDFs; furnace expectations follow
 * CONFORMANCE.md: energy conserving where the coefficients sum to at most 1,
 * reported (additive) otherwise -- shinymetal's defaults reach about 1.9.
 */
#include <string.h>
#include "conformance.h"
#include "materia/material.h"
#include "materia/state.h"

static mt_status apply(void *ctx, const mt_statement *st, mt_error *err)
{
    int handled = 0;
    mt_status s = mt_state_apply(ctx, st, &handled, err);
    if (!s && !handled) s = mt_error_set(err, MT_ERR_UNSUPPORTED, "%s in a material subject", st->directive);
    return s;
}

mt_status cf_build_material(const cf_subject *s, mt_arena *a, mt_mode mode, mt_bsdf **out, mt_error *err)
{
    mt_state *state = mt_state_create(mode);
    mt_material *m = NULL;
    mt_diffgeom dg = mt_diffgeom_default(), geom;
    mt_status st;
    *out = NULL;
    if (!state) return mt_error_set(err, MT_ERR_NOMEM, "out of memory");
    st = mt_parse_string(s->scene, s->name, ".", 1, NULL, apply, state, err);
    if (!st) m = mt_material_from_state(state, NULL, err);
    if (m) {
        geom = dg;
        if (s->p[0] != 0 || s->p[1] != 0 || s->p[2] != 0)
            geom.n = mt_v3_normalize(mt_v3((mt_real)s->p[0], (mt_real)s->p[1], (mt_real)s->p[2]));
        *out = mt_material_get_bsdf(m, &geom, &dg, a, err);
        st = *out ? MT_OK : err->status;
    } else if (!st) {
        st = err->status;
    }
    mt_material_destroy(m);
    mt_state_destroy(state);
    return st;
}

#define LE1 CF_FURNACE_LE1
#define EXACT CF_FURNACE_EXACT
#define DELTA CF_NO_CHI2
#define BOTH CF_TWO_SIDED
#define M(name, flags, rho, e, scene) {name, "material", cf_build_material, {0}, flags, rho, e, scene}

static const cf_subject materials[] = {
    M("matte Kd=1", EXACT, 1, 0, "Material \"matte\" \"rgb Kd\" [1 1 1]"),
    M("matte Kd=1 sigma=20", CF_FURNACE_LE, 1.02, 0, "Material \"matte\" \"rgb Kd\" [1 1 1] \"float sigma\" [20]"),
    M("matte sigma=120 (clamped to 90)", CF_FURNACE_LE, 1.02, 0, "Material \"matte\" \"rgb Kd\" [1 1 1] \"float sigma\" [120]"),
    M("matte default", LE1, 0, 0, "Material \"matte\""),
    M("plastic default", LE1, 0, 10, "Material \"plastic\""),
    M("plastic Kd=0.5 Ks=0.5 r=0.01", LE1, 0, 100, "Material \"plastic\" \"rgb Kd\" [.5 .5 .5] \"rgb Ks\" [.5 .5 .5] \"float roughness\" [.01]"),
    M("plastic Kd=1 Ks=1 r=0.3 (additive)", 0, 0, 3.4, "Material \"plastic\" \"rgb Kd\" [1 1 1] \"rgb Ks\" [1 1 1] \"float roughness\" [.3]"),
    M("glass default", EXACT | DELTA | BOTH, 1, 0, "Material \"glass\""),
    M("glass index=1.000001", EXACT | DELTA | BOTH, 1, 0, "Material \"glass\" \"float index\" [1.000001]"),
    M("glass index=2.4 Kt=0.5", LE1 | DELTA | BOTH, 0, 0, "Material \"glass\" \"float index\" [2.4] \"rgb Kt\" [.5 .5 .5]"),
    M("mirror default", EXACT | DELTA, 0.9, 0, "Material \"mirror\""),
    M("metal default (copper)", LE1, 0, 100, "Material \"metal\""),
    M("metal roughness=0.3", LE1, 0, 3.4, "Material \"metal\" \"float roughness\" [.3]"),
    M("shinymetal default (additive, ~1.9)", 0, 0, 10, "Material \"shinymetal\""),
    M("shinymetal Ks=0.3 Kr=0.3 (additive at grazing)", 0, 0, 10, "Material \"shinymetal\" \"rgb Ks\" [.3 .3 .3] \"rgb Kr\" [.3 .3 .3]"),
    M("substrate default", LE1, 0, 10, "Material \"substrate\""),
    M("substrate u=0.01 v=0.5", LE1, 0, 100, "Material \"substrate\" \"float uroughness\" [.01] \"float vroughness\" [.5]"),
    M("translucent default", LE1 | BOTH, 0, 10, "Material \"translucent\""),
    M("translucent Kd=0.5 Ks=0.5 r=t=1 (additive)", BOTH, 0, 10,
      "Material \"translucent\" \"rgb Kd\" [.5 .5 .5] \"rgb Ks\" [.5 .5 .5] \"rgb reflect\" [1 1 1] \"rgb transmit\" [1 1 1]"),
    M("uber default", LE1, 0, 10, "Material \"uber\""),
    M("uber opacity=0.5", LE1 | BOTH, 0, 10, "Material \"uber\" \"rgb opacity\" [.5 .5 .5]"),
    M("uber Kr=0.5 Kt=0.5 (additive)", BOTH, 0, 10, "Material \"uber\" \"rgb Kr\" [.5 .5 .5] \"rgb Kt\" [.5 .5 .5]"),
    M("uber opacity=1.5 (pbrt-v2: negative transmission)", BOTH, 0, 10, "Material \"uber\" \"rgb opacity\" [1.5 1.5 1.5]"),
    M("mix matte/plastic amount=0.3", LE1, 0, 10,
      "MakeNamedMaterial \"a\" \"string type\" \"matte\" \"rgb Kd\" [.8 .2 .2] "
      "MakeNamedMaterial \"b\" \"string type\" \"plastic\" \"rgb Kd\" [.1 .1 .5] \"rgb Ks\" [.5 .5 .5] \"float roughness\" [.1] "
      "Material \"mix\" \"string namedmaterial1\" \"a\" \"string namedmaterial2\" \"b\" \"rgb amount\" [.3 .3 .3]"),
    M("mix glass/mirror amount=0.5", LE1 | DELTA | BOTH, 0, 0,
      "MakeNamedMaterial \"g\" \"string type\" \"glass\" MakeNamedMaterial \"m\" \"string type\" \"mirror\" "
      "Material \"mix\" \"string namedmaterial1\" \"g\" \"string namedmaterial2\" \"m\""),
    M("subsurface default", LE1 | DELTA, 0, 0, "Material \"subsurface\""),
    M("kdsubsurface default", LE1 | DELTA, 0, 0, "Material \"kdsubsurface\""),
    M("matte with a bump map", LE1 | CF_SHADING_GAP, 0, 0,
      "Texture \"w\" \"float\" \"wrinkled\" \"float scale\" [0.3] Material \"matte\" \"texture bumpmap\" \"w\" \"rgb Kd\" [1 1 1]"),
};

const cf_subject *cf_material_subjects(int *count)
{
    *count = (int)(sizeof materials / sizeof materials[0]);
    return materials;
}
