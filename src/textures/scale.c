/* pbrt-v2 ScaleTexture (textures/scale.h): tex1 * tex2. */
#include "textures/create.h"

static mt_real scale_float(const mt_texture *t, const mt_diffgeom *dg)
{
    const mt__pair_tex *s = (const mt__pair_tex *)t;
    return mt__tex_f(s->tex1, dg) * mt__tex_f(s->tex2, dg);
}

static mt_rgb scale_rgb(const mt_texture *t, const mt_diffgeom *dg)
{
    const mt__pair_tex *s = (const mt__pair_tex *)t;
    return mt_rgb_mul(mt__tex_rgb(s->tex1, dg), mt__tex_rgb(s->tex2, dg));
}

static const mt_texture_ops scale_ops = {
    .name = "scale",
    .eval_float = scale_float,
    .eval_rgb = scale_rgb,
    .finalize = mt__pair_finalize,
};

mt_texture *mt__tex_scale(int is_float, mt_texture *tex1, mt_texture *tex2, mt_mode mode,
                          mt_error *err)
{
    return mt__pair_alloc(sizeof(mt__pair_tex), &scale_ops, is_float, tex1, "tex1", tex2, "tex2",
                          mode, err);
}

static mt_texture *scale_create(int is_float, const mt_transform *tex2world, const mt_texparams *tp,
                          mt_error *err)
{
    mt__tex_children c;
    mt_texture *t = NULL;
    if (mt__tex_children_get(tp, is_float, "tex1", 1, "tex2", 1, &c, err))
        t = mt__tex_scale(is_float, c.a, c.b, tp->mode, err);
    mt__tex_children_put(&c);
    return t;
}

static const mt__texture_param_doc scale_params[] = {
    {"tex1", "any", "tex1 times tex2"},
    {"tex2", "any", "tex1 times tex2"},
};

const mt_texture_kind mt_scale_texture = {
    .name = "scale",
    .has_float = 1,
    .create = scale_create,
    .params = scale_params,
    .nparams = MT_COUNT(scale_params),
};
