/*
 * The graphics-state statements about appearance (pbrt-v2 api.cpp):
 * Texture creates a texture at once and binds it by name; Material records a
 * type and its parameters; MakeNamedMaterial records everything pbrt-v2
 * builds the named material from; NamedMaterial selects one;
 * AreaLightSource records the light shapes will carry.
 */
#include <string.h>
#include "core/alloc.h"
#include "params/state_internal.h"

static int animated(const mt_state *s)
{
    return memcmp(&s->t[0].m, &s->t[1].m, sizeof s->t[0].m) != 0;
}

static void warn_if_animated(mt_state *s, const mt_statement *st)
{
    /* pbrt-v2 WARN_IF_ANIMATED_TRANSFORM */
    if (animated(s))
        mt__state_warn(s, st,
                       "Animated transformations set; ignoring for \"%s\" and using the start "
                       "transform only", st->directive);
}

/* An error from a callee, given the statement's location if it has none. */
static mt_status located(const mt_statement *st, mt_error *err, mt_status rc)
{
    if (err && rc != MT_OK && !err->file[0]) mt_error_locate(err, st->file, st->line, st->column);
    return rc;
}

/* pbrt-v2 pbrtTexture: TextureParams(params, params, floatTextures,
 * spectrumTextures) -- the statement's list serves as both the geometry and
 * the material list -- and the texture made under curTransform[0]. */
mt_status mt__state_texture(mt_state *s, const mt_statement *st, mt_error *err)
{
    const char *name = st->args[0].string, *type = st->args[1].string;
    const char *cls = st->args[2].string;
    mt_texparams tp;
    mt_texture *tex;
    mt_status rc;
    int is_float;
    if (strcmp(type, "float") == 0)
        is_float = 1;
    else if (strcmp(type, "color") == 0 || strcmp(type, "spectrum") == 0)
        is_float = 0;
    else
        return mt__state_fail(st, err, MT_ERR_INVALID,
                              "Texture \"%.100s\": type \"%.60s\" unknown (float, color or "
                              "spectrum)", name, type);
    if (mt_texture_table_get(s->g.textures, name, is_float))
        mt__state_warn(s, st, "Texture \"%s\" being redefined", name);
    warn_if_animated(s, st);
    tp.geom = st->params;
    tp.material = st->params;
    tp.textures = s->g.textures;
    tp.mode = s->mode;
    if (err) mt_error_clear(err);
    tex = mt_texture_create(cls, is_float, &s->t[0], &tp, err);
    if (!tex) {
        if (err && err->status == MT_OK) mt_error_set(err, MT_ERR_INVALID, "texture not created");
        return located(st, err, err ? err->status : MT_ERR_INVALID);
    }
    rc = mt_texture_table_set(s->g.textures, name, tex, err);
    mt_texture_destroy(tex); /* the table holds its own reference */
    if (rc != MT_OK) return located(st, err, rc);
    mt_paramset_report_unused(st->params, s->warn, s->warn_ctx);
    return MT_OK;
}

/* *name = the statement's first argument, *params = its parameters. */
static mt_status record(const mt_statement *st, char **name, mt__shared_params **params,
                        mt_error *err)
{
    mt__shared_params *sp = mt__shared_params_new(st->params);
    if (!sp || !mt__replace_string(name, st->args[0].string)) {
        mt__shared_params_release(sp);
        return mt__state_fail(st, err, MT_ERR_NOMEM, "out of memory");
    }
    mt__shared_params_release(*params);
    *params = sp;
    return MT_OK;
}

/* pbrt-v2 pbrtMaterial: material = name; materialParams = params;
 * currentNamedMaterial = "". */
mt_status mt__state_material(mt_state *s, const mt_statement *st, mt_error *err)
{
    mt_status rc = record(st, &s->g.material, &s->g.material_params, err);
    if (rc == MT_OK) mt__replace_string(&s->g.current_named, NULL);
    return rc;
}

/* pbrt-v2 pbrtMakeNamedMaterial: TextureParams(params, materialParams,
 * textures), "string type", MakeMaterial(type, curTransform[0], mp). The
 * record keeps all of it for the material layer to build from. */
mt_status mt__state_make_named(mt_state *s, const mt_statement *st, mt_error *err)
{
    const char *name = st->args[0].string, *type = NULL;
    mt__named_material *m;
    int replaced;
    mt_status rc = mt_params_string(st->params, "type", "", &type, err);
    if (rc != MT_OK) return located(st, err, rc);
    if (!type || !type[0])
        return mt__state_fail(st, err, MT_ERR_INVALID,
                              "MakeNamedMaterial \"%.100s\": no \"string type\" parameter", name);
    warn_if_animated(s, st);
    m = mt__calloc(1, sizeof *m);
    if (!m) return mt__state_fail(st, err, MT_ERR_NOMEM, "out of memory");
    m->refs = 1;
    m->transform = s->t[0];
    m->name = mt__strdup(name);
    m->type = mt__strdup(type);
    m->geom = mt__shared_params_new(st->params); /* after the lookup: "type" is used */
    m->material = s->g.material_params;
    m->material->refs++;
    m->textures = mt_texture_table_clone(s->g.textures);
    if (!m->name || !m->type || !m->geom || !m->textures) {
        mt__named_material_release(m);
        return mt__state_fail(st, err, MT_ERR_NOMEM, "out of memory");
    }
    if (!mt__gstate_bind_named(&s->g, m, &replaced))
        return mt__state_fail(st, err, MT_ERR_NOMEM, "out of memory");
    if (replaced) mt__state_warn(s, st, "Named material \"%s\" being redefined", name);
    return MT_OK;
}

/* pbrt-v2 pbrtNamedMaterial: currentNamedMaterial = name (pbrt-v2 falls back
 * to the current Material when the name is undefined at the Shape). */
mt_status mt__state_named(mt_state *s, const mt_statement *st, mt_error *err)
{
    const char *name = st->args[0].string;
    if (!mt__gstate_find_named(&s->g, name))
        return mt__state_fail(st, err, MT_ERR_NOT_FOUND,
                              "NamedMaterial \"%.100s\": no material of that name (MakeNamedMaterial "
                              "defines one)", name);
    if (!mt__replace_string(&s->g.current_named, name))
        return mt__state_fail(st, err, MT_ERR_NOMEM, "out of memory");
    return MT_OK;
}

/* pbrt-v2 pbrtAreaLightSource: areaLight = name; areaLightParams = params. */
mt_status mt__state_area_light(mt_state *s, const mt_statement *st, mt_error *err)
{
    return record(st, &s->g.area_light, &s->g.area_params, err);
}

static void spec_of(const mt__named_material *m, mt_material_spec *out)
{
    out->name = m->name;
    out->type = m->type;
    out->geom = m->geom->ps;
    out->material = m->material->ps;
    out->textures = m->textures;
    out->transform = m->transform;
}

void mt_state_material(const mt_state *s, mt_material_spec *out)
{
    /* pbrt-v2 GraphicsState::CreateMaterial */
    const mt__named_material *m =
        s->g.current_named ? mt__gstate_find_named(&s->g, s->g.current_named) : NULL;
    if (m) {
        spec_of(m, out);
        return;
    }
    out->name = NULL;
    out->type = s->g.material;
    out->geom = NULL;
    out->material = s->g.material_params->ps;
    out->textures = s->g.textures;
    out->transform = s->t[0];
}

mt_status mt_state_named_material(const mt_state *s, const char *name, mt_material_spec *out,
                                  mt_error *err)
{
    const mt__named_material *m = name ? mt__gstate_find_named(&s->g, name) : NULL;
    mt_error_clear(err);
    if (!m)
        return mt_error_set(err, MT_ERR_NOT_FOUND, "named material \"%.100s\" undefined",
                            name ? name : "");
    spec_of(m, out);
    return MT_OK;
}
