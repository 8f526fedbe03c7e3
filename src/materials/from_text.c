/*
 * Materials in one call, for programs that embed materia: from pbrt-v2
 * statements given as text, or from a list of typed parameters. Both go
 * through a graphics state -- the caller's, which keeps named textures and
 * materials from one call to the next, or a temporary one -- and both report
 * every parameter the material did not read: to the state's warning
 * callback, or as an error when it has none.
 */
#include <stdio.h>
#include <string.h>
#include "materials/from_state.h"
#include "params/paramset_internal.h"
#include "params/state_text.h"

/* The caller's state, or a new one in pbrt-v2 mode (*own set). */
static mt_state *state_or_new(mt_state *s, mt_state **own, mt_error *err)
{
    *own = NULL;
    if (s) return s;
    *own = mt_state_create(MT_MODE_PBRT_V2);
    if (!*own) mt_error_set(err, MT_ERR_NOMEM, "out of memory for a graphics state");
    return *own;
}

/* m, or NULL (m destroyed) when the list has a parameter it did not use and
 * the state has no warning callback. */
static mt_material *checked(mt_material *m, const mt_state *s, const mt_paramset *ps, mt_error *err)
{
    char what[64];
    void *ctx;
    mt_warning_fn warn = mt__state_warning(s, &ctx);
    if (!m) return NULL;
    snprintf(what, sizeof what, "%s material", mt_material_type(m));
    if (mt__params_check_unused(ps, warn, ctx, what, err) == MT_OK) return m;
    mt_material_destroy(m);
    return NULL;
}

mt_material *mt_material_from_text(const char *text, mt_state *state, mt_error *err)
{
    mt_state *own, *s;
    mt__text_summary sum;
    mt_material_spec spec;
    mt_material *m = NULL;
    mt_error_clear(err);
    if (!text) return mt_error_set(err, MT_ERR_INVALID, "mt_material_from_text: no text given"), NULL;
    if (!(s = state_or_new(state, &own, err))) return NULL;
    if (mt__state_apply_text(s, text, &sum, err) != MT_OK) goto done;
    if (sum.materials == 0) {
        mt_error_set(err, MT_ERR_INVALID,
                     "mt_material_from_text: no Material or NamedMaterial statement in the text");
        goto done;
    }
    mt_state_material(s, &spec);
    m = mt__material_from_spec(s, &spec, mt_state_mode(s), NULL, err);
    /* a named material reads its own list first (pbrt-v2 reports that one) */
    m = checked(m, s, spec.name ? spec.geom : spec.material, err);
done:
    mt_state_destroy(own);
    return m;
}

mt_material *mt_material_from_params(const char *type, const mt_param *params, int nparams,
                                     const mt_state *state, mt_error *err)
{
    mt_material_spec spec;
    mt_paramset *ps;
    mt_material *m;
    mt_error_clear(err);
    if (!type) return mt_error_set(err, MT_ERR_INVALID, "mt_material_from_params: no type given"), NULL;
    if (!(ps = mt__paramset_from_list(params, nparams, err))) return NULL;
    memset(&spec, 0, sizeof spec);
    spec.type = type;
    spec.material = ps;
    spec.textures = state ? mt_state_textures(state) : NULL;
    spec.transform = state ? *mt_state_transform(state) : mt_transform_identity();
    m = mt__material_from_spec(state, &spec, state ? mt_state_mode(state) : MT_MODE_PBRT_V2, NULL, err);
    m = checked(m, state, ps, err);
    mt_paramset_destroy(ps);
    return m;
}
