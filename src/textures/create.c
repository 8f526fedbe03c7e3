/*
 * The readers pbrt-v2's texture creators share (textures/<class>.cpp: every 2D
 * class reads its mapping the same way; fbm, wrinkled and marble their
 * octaves). pbrt-v2's creators print an error and fall back to a default for
 * an unknown "mapping", "aamode" or "wrap"; materia reports an error naming
 * the parameter instead.
 */
#include <string.h>
#include "textures/create.h"
#include "textures/probe.h"

static const mt__texture_param_doc common[] = {
    {"mapping", "uv, spherical, cylindrical or planar", "how (u, v) are found at a point"},
    {"uscale", "finite", "uv mapping: u times uscale"},
    {"vscale", "finite", "uv mapping: v times vscale"},
    {"udelta", "finite", "uv and planar mappings: added to u"},
    {"vdelta", "finite", "uv and planar mappings: added to v"},
    {"v1", "finite", "planar mapping: u is the point's projection on v1"},
    {"v2", "finite", "planar mapping: v is the point's projection on v2"},
    {"octaves", "0 to 128", "noise octaves (fewer where the filter width asks)"},
    {"roughness", "finite; the octaves' total weight finite", "weight of each octave relative to the last"},
};

const mt__texture_param_doc *mt__texture_common_docs(int *count)
{
    *count = MT_COUNT(common);
    return common;
}

int mt__tex_choice(const mt_texparams *tp, const char *name, const char *def,
                   const char *const *choices, const char *cls, mt_error *err)
{
    const char *s;
    int i;
    if (mt_texparams_string(tp, name, def, &s, err)) return -1;
    mt__texparams_probe(name, "string", def, choices);
    for (i = 0; choices[i]; ++i)
        if (!strcmp(s, choices[i])) return i;
    mt_error_param(err, MT_ERR_INVALID, name, "%s texture: unknown %s \"%s\"", cls, name, s);
    return -1;
}

mt_status mt__tex_mapping2d(const mt_transform *tex2world, const mt_texparams *tp,
                            const char *cls, mt_map2d *m, mt_error *err)
{
    static const char *const kinds[] = {"uv", "spherical", "cylindrical", "planar", NULL};
    mt_real su, sv, du, dv;
    mt_vec3 v1, v2;
    mt_status st;
    switch (mt__tex_choice(tp, "mapping", "uv", kinds, cls, err)) {
    case 0:
        if ((st = mt_texparams_float(tp, "uscale", 1, &su, err)) ||
            (st = mt_texparams_float(tp, "vscale", 1, &sv, err)) ||
            (st = mt_texparams_float(tp, "udelta", 0, &du, err)) ||
            (st = mt_texparams_float(tp, "vdelta", 0, &dv, err)))
            return st;
        *m = mt__map2d_uv(su, sv, du, dv);
        break;
    case 1:
        *m = mt__map2d_spherical(tex2world, tp->mode);
        break;
    case 2:
        *m = mt__map2d_cylindrical(tex2world, tp->mode);
        break;
    case 3:
        if ((st = mt_texparams_vector(tp, "v1", mt_v3(1, 0, 0), &v1, err)) ||
            (st = mt_texparams_vector(tp, "v2", mt_v3(0, 1, 0), &v2, err)) ||
            (st = mt_texparams_float(tp, "udelta", 0, &du, err)) ||
            (st = mt_texparams_float(tp, "vdelta", 0, &dv, err)))
            return st;
        *m = mt__map2d_planar(v1, v2, du, dv);
        break;
    default:
        return MT_ERR_INVALID;
    }
    return mt__map2d_check(m, cls, err);
}

mt_status mt__tex_octaves(const mt_texparams *tp, int *octaves, mt_real *roughness, mt_error *err)
{
    mt_status st = mt_texparams_int(tp, "octaves", 8, octaves, err);
    return st ? st : mt_texparams_float(tp, "roughness", (mt_real)0.5, roughness, err);
}

mt_texture *mt__tex_create_octaves(mt__octave_ctor ctor, int is_float, const mt_transform *tex2world,
                                   const mt_texparams *tp, mt_error *err)
{
    mt_map3d m = mt__map3d(tex2world, tp->mode);
    mt_real rough;
    int oct;
    if (mt__tex_octaves(tp, &oct, &rough, err)) return NULL;
    return ctor(is_float, &m, oct, rough, tp->mode, err);
}

int mt__tex_children_get(const mt_texparams *tp, int is_float, const char *na, mt_real da,
                         const char *nb, mt_real db, mt__tex_children *c, mt_error *err)
{
    c->amount = NULL;
    c->b = NULL;
    c->a = mt__tex_child(tp, is_float, na, da, err);
    if (c->a) c->b = mt__tex_child(tp, is_float, nb, db, err);
    return c->b != NULL;
}

void mt__tex_children_put(mt__tex_children *c)
{
    mt_texture_destroy(c->a);
    mt_texture_destroy(c->b);
    mt_texture_destroy(c->amount);
}
