/* measured (pbrt-v2 measured.cpp): a measured BRDF read from "filename"
 * (resolved against the statement's directory; each file read once per
 * process), irregular isotropic samples from a .brdf file or a MERL table
 * from any other suffix, plus "bumpmap". pbrt-v2 goes on with an empty BSDF
 * when the file cannot be read; here that is an error at creation. */
#include <stdio.h>
#include "materia/measured.h"
#include "materials/material_impl.h"

typedef struct measured_material {
    mt_material base;
    mt_measured *data;
} measured_material;

static int measured_max(const mt_material *m) { return 1; }

static mt_status measured_add(const mt_material *m, mt_bsdf *b, const mt_diffgeom *dgs,
                              mt_arena *a, mt_error *err)
{
    const mt_measured *d = ((const measured_material *)m)->data;
    if (mt_measured_kind_of(d) == MT_MEASURED_HALFANGLE)
        return mt__bsdf_add(b, mt_regular_halfangle_brdf_create(a, m->mode, d, err), err);
    return mt__bsdf_add(b, mt_irregular_isotropic_brdf_create(a, m->mode, d, err), err);
}

static void measured_destroy(mt_material *m) { mt_measured_destroy(((measured_material *)m)->data); }

static const mt_param_doc measured_other[] = {
    {"filename", "string", "(required)", "a readable file",
     "a .brdf file (irregular isotropic samples) or a MERL binary table (any other suffix)"}};

static mt_material *measured_create(const mt_transform *xf, const mt_texparams *tp,
                                  const mt_material_ctx *ctx, mt_error *err)
{
    char path[4096];
    measured_material *m;
    if (mt_texparams_filename(tp, "filename", "", path, sizeof path, err) != MT_OK) return NULL;
    if (!path[0]) {
        mt_error_param(err, MT_ERR_INVALID, "filename",
                       "measured material: \"string filename\" is required");
        return NULL;
    }
    m = mt__material_new(sizeof *m, &mt_measured_material, tp, err);
    if (!m) return NULL;
    m->data = mt_measured_load(path, err);
    if (!m->data) {
        char msg[sizeof err->message];
        if (err) {
            snprintf(msg, sizeof msg, "%s", err->message);
            snprintf(err->message, sizeof err->message, "measured material: %.480s", msg);
            snprintf(err->param, sizeof err->param, "filename");
        }
        mt_material_destroy(&m->base);
        return NULL;
    }
    return &m->base;
}

const mt_material_kind mt_measured_material = {
    .type = "measured",
    .create = measured_create,
    .max_bxdfs = measured_max,
    .add_bxdfs = measured_add,
    .destroy = measured_destroy,
    .other = measured_other,
    .nother = MT_COUNT(measured_other),
};
