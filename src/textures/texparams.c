/*
 * pbrt-v2's TextureParams (core/paramset.cpp): a statement's parameters
 * read through two lists, the geometry's (a Shape's) first and then the
 * material's, with "texture" parameters naming textures of the table.
 *
 * A value is taken from the geometry when it has the parameter, else from
 * the material; pbrt-v2 looks the name up in both (FindOneFloat(n,
 * material.FindOneFloat(n, def))), so both count as used here too. Unlike
 * pbrt-v2, which prints an error and falls back to the parameter's value, a
 * texture name that is not in the table, or names a texture of the other
 * kind, is an error naming the parameter.
 */
#include <stdio.h>
#include "textures/probe.h"
#include "textures/tex.h"
#include "params/paramset_internal.h"

static mt__texparams_probe_fn probe_fn;
static void *probe_ctx;

void mt__texparams_set_probe(mt__texparams_probe_fn fn, void *ctx)
{
    probe_fn = fn;
    probe_ctx = ctx;
}

void mt__texparams_probe(const char *name, const char *type, const char *def, const char *const *choices)
{
    if (probe_fn) probe_fn(probe_ctx, name, type, def, choices);
}

/* The probe with a default formatted as a scene would write it. */
static void probe_real(const char *name, const char *type, mt_real v)
{
    char buf[32];
    if (!probe_fn) return;
    snprintf(buf, sizeof buf, "%.4g", (double)v);
    probe_fn(probe_ctx, name, type, buf, NULL);
}

static void probe_triple(const char *name, const char *type, const mt_real *v)
{
    char buf[96];
    if (!probe_fn) return;
    snprintf(buf, sizeof buf, "%.4g %.4g %.4g", (double)v[0], (double)v[1], (double)v[2]);
    probe_fn(probe_ctx, name, type, buf, NULL);
}

static const mt_paramset *source(const mt_texparams *tp, const char *name)
{
    if (tp->geom && mt_paramset_find(tp->geom, name)) {
        if (tp->material) mt_paramset_mark_used(tp->material, name);
        return tp->geom;
    }
    return tp->material;
}

mt_status mt_texparams_float(const mt_texparams *tp, const char *name, mt_real def,
                             mt_real *out, mt_error *err)
{
    probe_real(name, "float", def);
    return mt_params_float(source(tp, name), name, def, out, err);
}

mt_status mt_texparams_int(const mt_texparams *tp, const char *name, int def, int *out,
                           mt_error *err)
{
    probe_real(name, "integer", (mt_real)def);
    return mt_params_int(source(tp, name), name, def, out, err);
}

mt_status mt_texparams_bool(const mt_texparams *tp, const char *name, int def, int *out,
                            mt_error *err)
{
    mt__texparams_probe(name, "bool", def ? "true" : "false", NULL);
    return mt_params_bool(source(tp, name), name, def, out, err);
}

mt_status mt_texparams_string(const mt_texparams *tp, const char *name, const char *def,
                              const char **out, mt_error *err)
{
    mt__texparams_probe(name, "string", def, NULL);
    return mt_params_string(source(tp, name), name, def, out, err);
}

mt_status mt_texparams_filename(const mt_texparams *tp, const char *name, const char *def,
                                char *out, size_t size, mt_error *err)
{
    mt__texparams_probe(name, "string", def, NULL);
    return mt_params_filename(source(tp, name), name, def, out, size, err);
}

mt_status mt_texparams_vector(const mt_texparams *tp, const char *name, mt_vec3 def,
                              mt_vec3 *out, mt_error *err)
{
    mt_real v[3];
    v[0] = def.x, v[1] = def.y, v[2] = def.z;
    probe_triple(name, "vector", v);
    return mt_params_vector(source(tp, name), name, def, out, err);
}

mt_status mt_texparams_rgb(const mt_texparams *tp, const char *name, mt_rgb def, mt_rgb *out,
                           mt_error *err)
{
    probe_triple(name, "rgb", def.c);
    return mt_params_rgb(source(tp, name), name, def, out, err);
}

/* The "texture" parameter called name, geometry first (pbrt-v2
 * geomParams.FindTexture, then materialParams.FindTexture); NULL if none. */
static const mt_param *texture_param(const mt_texparams *tp, const char *name,
                                     const mt_paramset **list)
{
    const mt_paramset *lists[2];
    int i;
    lists[0] = tp->geom;
    lists[1] = tp->material;
    for (i = 0; i < 2; ++i) {
        const mt_param *p = lists[i] ? mt__paramset_find_type(lists[i], name, MT_PARAM_TEXTURE) : NULL;
        if (p) {
            *list = lists[i];
            return p;
        }
    }
    return NULL;
}

/* The texture a "texture" parameter names, as a new reference. */
static mt_status named_texture(const mt_texparams *tp, const char *name, int is_float,
                               mt_texture **out, int *found, mt_error *err)
{
    const mt_paramset *list = NULL;
    const mt_param *p = texture_param(tp, name, &list);
    const char *texname = NULL;
    mt_texture *t;
    mt_status st;
    *out = NULL;
    *found = 0;
    if (!p) return MT_OK;
    *found = 1;
    st = mt_params_texture(list, name, &texname, err);
    if (st) return st;
    t = mt_texture_table_get(tp->textures, texname, is_float);
    if (t) {
        *out = mt_texture_retain(t);
        return MT_OK;
    }
    if (mt_texture_table_get(tp->textures, texname, !is_float))
        st = mt_error_param(err, MT_ERR_INVALID, name,
                            "texture \"%s\" is a %s texture; a %s texture is needed here",
                            texname, is_float ? "spectrum" : "float",
                            is_float ? "float" : "spectrum");
    else
        st = mt_error_param(err, MT_ERR_NOT_FOUND, name, "no %s texture named \"%s\"",
                            is_float ? "float" : "spectrum", texname);
    mt_error_locate(err, p->file, p->line, p->column);
    return st;
}

mt_texture *mt_texparams_float_texture(const mt_texparams *tp, const char *name, mt_real def,
                                       mt_error *err)
{
    mt_texture *t;
    mt_real v;
    int found;
    probe_real(name, "float texture", def); /* first: the value read below reports "float" */
    if (named_texture(tp, name, 1, &t, &found, err) || found) return t;
    if (mt_texparams_float(tp, name, def, &v, err)) return NULL;
    return mt__tex_constant(1, mt_rgb_gray(v), tp->mode, err);
}

mt_texture *mt_texparams_spectrum_texture(const mt_texparams *tp, const char *name, mt_rgb def,
                                          mt_error *err)
{
    mt_texture *t;
    mt_rgb v;
    int found;
    probe_triple(name, "spectrum texture", def.c);
    if (named_texture(tp, name, 0, &t, &found, err) || found) return t;
    if (mt_texparams_rgb(tp, name, def, &v, err)) return NULL;
    return mt__tex_constant(0, v, tp->mode, err);
}

mt_status mt_texparams_float_texture_opt(const mt_texparams *tp, const char *name,
                                         mt_texture **out, mt_error *err)
{
    const mt_paramset *list;
    const mt_param *p;
    int found;
    mt_status st;
    mt__texparams_probe(name, "float texture", "none", NULL);
    st = named_texture(tp, name, 1, out, &found, err);
    if (st || found) return st;
    /* pbrt-v2 reads only a texture here and ignores a value of another type
     * (then reported unused); materia says so */
    list = source(tp, name);
    p = list ? mt_paramset_find(list, name) : NULL;
    if (!p) return MT_OK;
    st = mt_error_param(err, MT_ERR_INVALID, name,
                        "is declared \"%s %s\" but must be a \"texture\" naming a float texture",
                        p->type_name, name);
    mt_error_locate(err, p->file, p->line, p->column);
    return st;
}
