/* pbrt-v2 UVTexture (textures/uv.h): the fractional parts of the mapped
 * (s, t) as red and green. Spectrum only, as in pbrt-v2. */
#include "textures/create.h"

typedef struct uvtex {
    mt_texture base;
    mt_map2d map;
} uvtex;

static mt_real uv_float(const mt_texture *t, const mt_diffgeom *dg)
{
    (void)t;
    (void)dg;
    return 0; /* never called: the constructor makes spectrum variants only */
}

static mt_rgb uv_rgb(const mt_texture *t, const mt_diffgeom *dg)
{
    mt_st st;
    mt__map2d_apply(&((const uvtex *)t)->map, dg, &st);
    /* s - Floor2Int(s): floor(s) is the same value without the int overflow */
    return mt_rgb_make(st.s - mt_floor(st.s), st.t - mt_floor(st.t), 0);
}

static const mt_texture_ops uv_ops = {
    .name = "uv",
    .eval_float = uv_float,
    .eval_rgb = uv_rgb,
};

mt_texture *mt__tex_uv(const mt_map2d *map, mt_mode mode, mt_error *err)
{
    uvtex *u;
    if (mt__map2d_check(map, "uv", err)) return NULL;
    u = mt__texture_alloc(sizeof *u, &uv_ops, 0, mode, err);
    if (!u) return NULL;
    u->map = *map;
    return &u->base;
}

static mt_texture *uv_create(int is_float, const mt_transform *tex2world, const mt_texparams *tp,
                          mt_error *err)
{
    mt_map2d m;
    if (mt__tex_mapping2d(tex2world, tp, "uv", &m, err)) return NULL;
    return mt__tex_uv(&m, tp->mode, err);
}

const mt_texture_kind mt_uv_texture = {
    .name = "uv",
    .has_float = 0,
    .create = uv_create,
};
