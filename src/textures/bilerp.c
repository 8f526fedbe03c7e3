/* pbrt-v2 BilerpTexture (textures/bilerp.h): the bilinear interpolation of
 * v00, v01, v10, v11 at the mapped (s, t). */
#include "textures/create.h"

typedef struct bilerp {
    mt_texture base;
    mt_map2d map;
    mt_rgb v[4]; /* v00, v01, v10, v11 */
} bilerp;

/* (1-s)(1-t) v00 + (1-s) t v01 + s (1-t) v10 + s t v11, summed left to right
 * as pbrt-v2 does, for one component. */
static mt_real lerp4(const mt_real w[4], const bilerp *b, int c)
{
    return w[0] * b->v[0].c[c] + w[1] * b->v[1].c[c] + w[2] * b->v[2].c[c] + w[3] * b->v[3].c[c];
}

static void weights(const bilerp *b, const mt_diffgeom *dg, mt_real w[4])
{
    mt_st st;
    mt__map2d_apply(&b->map, dg, &st);
    w[0] = (1 - st.s) * (1 - st.t);
    w[1] = (1 - st.s) * st.t;
    w[2] = st.s * (1 - st.t);
    w[3] = st.s * st.t;
}

static mt_real bilerp_float(const mt_texture *t, const mt_diffgeom *dg)
{
    mt_real w[4];
    weights((const bilerp *)t, dg, w);
    return lerp4(w, (const bilerp *)t, 0);
}

static mt_rgb bilerp_rgb(const mt_texture *t, const mt_diffgeom *dg)
{
    const bilerp *b = (const bilerp *)t;
    mt_real w[4];
    weights(b, dg, w);
    return mt_rgb_make(lerp4(w, b, 0), lerp4(w, b, 1), lerp4(w, b, 2));
}

static const mt_texture_ops bilerp_ops = {
    .name = "bilerp",
    .eval_float = bilerp_float,
    .eval_rgb = bilerp_rgb,
};

mt_texture *mt__tex_bilerp(int is_float, const mt_map2d *map, const mt_rgb v[4], mt_mode mode,
                           mt_error *err)
{
    static const char *const names[4] = {"v00", "v01", "v10", "v11"};
    bilerp *b;
    int i;
    if (mt__map2d_check(map, "bilerp", err)) return NULL;
    for (i = 0; i < 4; ++i)
        if (!mt__tex_check_rgb(v[i], names[i], "bilerp", err)) return NULL;
    b = mt__texture_alloc(sizeof *b, &bilerp_ops, is_float, mode, err);
    if (!b) return NULL;
    b->map = *map;
    for (i = 0; i < 4; ++i) b->v[i] = v[i];
    return &b->base;
}

static mt_texture *bilerp_create(int is_float, const mt_transform *tex2world, const mt_texparams *tp,
                          mt_error *err)
{
    static const char *const names[4] = {"v00", "v01", "v10", "v11"};
    static const mt_real defs[4] = {0, 1, 0, 1};
    mt_map2d m;
    mt_rgb v[4];
    int i;
    if (mt__tex_mapping2d(tex2world, tp, "bilerp", &m, err)) return NULL;
    for (i = 0; i < 4; ++i)
        if (mt__tex_value(tp, is_float, names[i], defs[i], &v[i], err)) return NULL;
    return mt__tex_bilerp(is_float, &m, v, tp->mode, err);
}

static const mt__texture_param_doc bilerp_params[] = {
    {"v00", "finite", "the value at (u, v) = (0, 0)"},
    {"v01", "finite", "the value at (0, 1)"},
    {"v10", "finite", "the value at (1, 0)"},
    {"v11", "finite", "the value at (1, 1)"},
};

const mt_texture_kind mt_bilerp_texture = {
    .name = "bilerp",
    .has_float = 1,
    .create = bilerp_create,
    .params = bilerp_params,
    .nparams = MT_COUNT(bilerp_params),
};
