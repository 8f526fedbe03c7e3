/*
 * pbrt-v2 statements given as text and applied to a graphics state: the
 * short way to textures and materials for a program that embeds materia
 * (mt_material_from_text and mt_texture_from_text are built on it).
 */
#include <stdio.h>
#include <string.h>
#include "params/paramset_internal.h"
#include "params/state_internal.h"
#include "params/state_text.h"

typedef struct text_apply_ctx {
    mt_state *s;
    mt__text_summary *sum;
} text_apply_ctx;

static mt_status apply_one(void *ctx, const mt_statement *st, mt_error *err)
{
    text_apply_ctx *a = ctx;
    int handled = 0;
    mt_status rc;
    rc = mt_state_apply(a->s, st, &handled, err);
    if (rc != MT_OK) return rc;
    if (!handled)
        return mt__state_fail(st, err, MT_ERR_INVALID,
                              "%s is not a statement about materials and textures (Texture, Material, "
                              "MakeNamedMaterial, NamedMaterial, transforms and AttributeBegin/End "
                              "are)", st->directive);
    if (!strcmp(st->directive, "Material") || !strcmp(st->directive, "NamedMaterial"))
        a->sum->materials++;
    if (!strcmp(st->directive, "Texture")) {
        a->sum->textures++;
        snprintf(a->sum->texture, sizeof a->sum->texture, "%s", st->args[0].string);
        a->sum->texture_is_float = !strcmp(st->args[1].string, "float");
        /* with a callback the state has reported them; without one, an error */
        if (!a->s->warn) {
            char what[300];
            snprintf(what, sizeof what, "Texture \"%.256s\"", st->args[0].string);
            return mt__params_check_unused(st->params, NULL, NULL, what, err);
        }
    }
    return MT_OK;
}

mt_status mt__state_apply_text(mt_state *s, const char *text, mt__text_summary *sum, mt_error *err)
{
    mt_parse_options opt;
    mt__text_summary none;
    text_apply_ctx a;
    if (!s || !text) return mt_error_set(err, MT_ERR_INVALID, "no %s given", s ? "text" : "state");
    memset(&opt, 0, sizeof opt);
    opt.warn = s->warn;
    opt.warn_ctx = s->warn_ctx;
    memset(sum ? sum : &none, 0, sizeof none);
    a.s = s;
    a.sum = sum ? sum : &none;
    return mt_parse_string(text, NULL, NULL, 1, &opt, apply_one, &a, err);
}

mt_status mt_state_apply_text(mt_state *s, const char *text, mt_error *err)
{
    mt_error_clear(err);
    return mt__state_apply_text(s, text, NULL, err);
}

mt_status mt_state_set_texture(mt_state *s, const char *name, mt_texture *tex, mt_error *err)
{
    mt_error_clear(err);
    if (!s || !name || !tex)
        return mt_error_set(err, MT_ERR_INVALID, "mt_state_set_texture: no %s given",
                            !s ? "state" : !name ? "name" : "texture");
    return mt_texture_table_set(s->g.textures, name, tex, err);
}

mt_warning_fn mt__state_warning(const mt_state *s, void **ctx)
{
    if (ctx) *ctx = s ? s->warn_ctx : NULL;
    return s ? s->warn : NULL;
}
