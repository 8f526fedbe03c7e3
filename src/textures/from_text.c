/*
 * Textures in one call, for programs that embed materia: from pbrt-v2
 * Texture statements given as text, or from a class name and a list of
 * typed parameters, through a graphics state (the caller's, whose named
 * textures they may use, or none). Every parameter the texture did not read
 * goes to the state's warning callback, or is an error when it has none.
 */
#include <stdio.h>
#include <string.h>
#include "materia/state.h"
#include "params/paramset_internal.h"
#include "params/state_text.h"

mt_texture *mt_texture_from_text(const char *text, mt_state *state, mt_error *err)
{
    mt_state *s = state;
    mt__text_summary sum;
    mt_texture *t = NULL;
    mt_error_clear(err);
    if (!text) return mt_error_set(err, MT_ERR_INVALID, "mt_texture_from_text: no text given"), NULL;
    if (!s && !(s = mt_state_create(MT_MODE_PBRT_V2)))
        return mt_error_set(err, MT_ERR_NOMEM, "out of memory for a graphics state"), NULL;
    if (mt__state_apply_text(s, text, &sum, err) == MT_OK) {
        if (sum.textures == 0)
            mt_error_set(err, MT_ERR_INVALID, "mt_texture_from_text: no Texture statement in the text");
        else
            t = mt_texture_retain(mt_texture_table_get(mt_state_textures(s), sum.texture, sum.texture_is_float));
    }
    if (s != state) mt_state_destroy(s);
    return t;
}

mt_texture *mt_texture_from_params(const char *class_name, int is_float, const mt_param *params,
                                   int nparams, const mt_state *state, mt_error *err)
{
    mt_texparams tp;
    mt_paramset *ps;
    mt_texture *t;
    char what[128];
    void *ctx;
    mt_warning_fn warn = mt__state_warning(state, &ctx);
    mt_error_clear(err);
    if (!class_name)
        return mt_error_set(err, MT_ERR_INVALID, "mt_texture_from_params: no class given"), NULL;
    if (!(ps = mt__paramset_from_list(params, nparams, err))) return NULL;
    /* pbrt-v2's Texture statement: its list is both of TextureParams' lists */
    tp.geom = ps;
    tp.material = ps;
    tp.textures = state ? mt_state_textures(state) : NULL;
    tp.mode = state ? mt_state_mode(state) : MT_MODE_PBRT_V2;
    t = mt_texture_create(class_name, is_float, state ? mt_state_transform(state) : NULL, &tp, err);
    snprintf(what, sizeof what, "%s texture \"%.60s\"", is_float ? "float" : "spectrum", class_name);
    if (t && mt__params_check_unused(ps, warn, ctx, what, err) != MT_OK) {
        mt_texture_destroy(t);
        t = NULL;
    }
    mt_paramset_destroy(ps);
    return t;
}
