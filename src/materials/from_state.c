/*
 * Materials from the graphics state (pbrt-v2 api.cpp MakeMaterial and
 * GraphicsState::CreateMaterial): the selected material specification turned
 * into a material, with a mix's named materials resolved through the state.
 */
#include <string.h>
#include "materia/state.h"
#include "materials/material_impl.h"

#define MAX_NESTING 16 /* mixes of mixes; a cycle of names stops here */

typedef struct resolver {
    const mt_state *state;
    int depth;
    mt_material *made[MAX_NESTING * 2]; /* named materials created for the mix */
    int nmade;
    mt_error *err;
} resolver;

static mt_material *from_spec(resolver *r, const mt_material_spec *spec, const mt_paramset *shape_params);

static const mt_material *lookup_named(void *ctx, const char *name)
{
    resolver *r = ctx;
    mt_material_spec spec;
    mt_material *m;
    if (r->depth >= MAX_NESTING || r->nmade >= MAX_NESTING * 2) {
        mt_error_set(r->err, MT_ERR_LIMIT, "mix material: named materials nest deeper than %d (a cycle?)",
                     MAX_NESTING);
        return NULL;
    }
    if (mt_state_named_material(r->state, name, &spec, r->err) != MT_OK) return NULL;
    r->depth++;
    m = from_spec(r, &spec, NULL);
    r->depth--;
    if (m) r->made[r->nmade++] = m; /* the mix retains what it keeps */
    return m;
}

static mt_material *from_spec(resolver *r, const mt_material_spec *spec, const mt_paramset *shape_params)
{
    mt_texparams tp;
    mt_material_ctx ctx = {lookup_named, NULL, NULL, NULL};
    ctx.lookup_ctx = r;
    /* a named material's own parameters come first, then those of the
     * Material current when it was made; a plain Material's parameters come
     * after the shape's (pbrt-v2's TextureParams(geom, material)) */
    tp.geom = spec->name ? spec->geom : shape_params;
    tp.material = spec->material;
    tp.textures = spec->textures;
    tp.mode = mt_state_mode(r->state);
    return mt_material_create(spec->type, &spec->transform, &tp, &ctx, r->err);
}

mt_material *mt_material_from_state(const mt_state *s, const mt_paramset *shape_params, mt_error *err)
{
    resolver r;
    mt_material_spec spec;
    mt_material *m;
    int i;
    memset(&r, 0, sizeof r);
    r.state = s;
    r.err = err;
    mt_state_material(s, &spec);
    m = from_spec(&r, &spec, shape_params);
    for (i = 0; i < r.nmade; ++i) mt_material_release(r.made[i]);
    return m;
}

mt_material *mt_material_named_from_state(const mt_state *s, const char *name, mt_error *err)
{
    resolver r;
    mt_material_spec spec;
    mt_material *m;
    int i;
    if (mt_state_named_material(s, name, &spec, err) != MT_OK) return NULL;
    memset(&r, 0, sizeof r);
    r.state = s;
    r.err = err;
    m = from_spec(&r, &spec, NULL);
    for (i = 0; i < r.nmade; ++i) mt_material_release(r.made[i]);
    return m;
}
