/*
 * Materials from the graphics state (pbrt-v2 api.cpp MakeMaterial and
 * GraphicsState::CreateMaterial): the selected material specification turned
 * into a material, with a mix's named materials resolved through the state.
 */
#include <string.h>
#include "materia/state.h"
#include "materials/material_impl.h"
#include "materials/from_state.h"

#define MAX_NESTING 16 /* mixes of mixes; a cycle of names stops here */

typedef struct resolver {
    const mt_state *state; /* NULL: no named materials */
    mt_mode mode;
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
    if (!r->state) {
        mt_error_set(r->err, MT_ERR_NOT_FOUND, "no named material \"%s\" (no state to look it up in)", name);
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
    mt_material_ctx ctx = {lookup_named, NULL};
    ctx.lookup_ctx = r;
    /* a named material's own parameters come first, then those of the
     * Material current when it was made; a plain Material's parameters come
     * after the shape's (pbrt-v2's TextureParams(geom, material)) */
    tp.geom = spec->name ? spec->geom : shape_params;
    tp.material = spec->material;
    tp.textures = spec->textures;
    tp.mode = r->mode;
    return mt_material_create(spec->type, &spec->transform, &tp, &ctx, r->err);
}

/* The material spec describes, with a mix's named materials from s (may be
 * NULL); the named materials made on the way are released once the mix
 * holds them. */
mt_material *mt__material_from_spec(const mt_state *s, const mt_material_spec *spec, mt_mode mode,
                                    const mt_paramset *shape_params, mt_error *err)
{
    resolver r;
    mt_material *m;
    int i;
    memset(&r, 0, sizeof r);
    r.state = s;
    r.mode = mode;
    r.err = err;
    m = from_spec(&r, spec, shape_params);
    for (i = 0; i < r.nmade; ++i) mt_material_destroy(r.made[i]);
    return m;
}

mt_material *mt_material_from_state(const mt_state *s, const mt_paramset *shape_params, mt_error *err)
{
    mt_material_spec spec;
    mt_error_clear(err);
    mt_state_material(s, &spec);
    return mt__material_from_spec(s, &spec, mt_state_mode(s), shape_params, err);
}

mt_material *mt_material_named_from_state(const mt_state *s, const char *name, mt_error *err)
{
    mt_material_spec spec;
    mt_error_clear(err);
    if (mt_state_named_material(s, name, &spec, err) != MT_OK) return NULL;
    return mt__material_from_spec(s, &spec, mt_state_mode(s), NULL, err);
}
