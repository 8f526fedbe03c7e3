/* pbrt-v2 MixTexture (textures/mix.h): (1 - amount) tex1 + amount tex2, the
 * amount a float texture. */
#include "textures/create.h"

typedef struct mix_tex {
    mt__pair_tex pair;
    mt_texture *amount;
} mix_tex;

static mt_real mix_float(const mt_texture *t, const mt_diffgeom *dg)
{
    const mix_tex *m = (const mix_tex *)t;
    mt_real a = mt__tex_f(m->pair.tex1, dg), b = mt__tex_f(m->pair.tex2, dg);
    return mt__tex_blend(mt__tex_f(m->amount, dg), a, b);
}

static mt_rgb mix_rgb(const mt_texture *t, const mt_diffgeom *dg)
{
    const mix_tex *m = (const mix_tex *)t;
    mt_rgb a = mt__tex_rgb(m->pair.tex1, dg), b = mt__tex_rgb(m->pair.tex2, dg);
    return mt__tex_blend_rgb(mt__tex_f(m->amount, dg), a, b);
}

static void mix_finalize(mt_texture *t)
{
    mt__pair_finalize(t);
    mt_texture_destroy(((mix_tex *)t)->amount);
}

static const mt_texture_ops mix_ops = {
    .name = "mix",
    .eval_float = mix_float,
    .eval_rgb = mix_rgb,
    .finalize = mix_finalize,
};

mt_texture *mt__tex_mix(int is_float, mt_texture *tex1, mt_texture *tex2, mt_texture *amount,
                        mt_mode mode, mt_error *err)
{
    mix_tex *m;
    if (!mt__tex_check_child(amount, 1, "amount", "mix", err)) return NULL;
    m = mt__pair_alloc(sizeof *m, &mix_ops, is_float, tex1, "tex1", tex2, "tex2", mode, err);
    if (!m) return NULL;
    m->amount = mt_texture_retain(amount);
    return &m->pair.base;
}

static mt_texture *mixtex_create(int is_float, const mt_transform *tex2world, const mt_texparams *tp,
                          mt_error *err)
{
    mt__tex_children c;
    mt_texture *t = NULL;
    if (mt__tex_children_get(tp, is_float, "tex1", 0, "tex2", 1, &c, err) &&
        (c.amount = mt_texparams_float_texture(tp, "amount", (mt_real)0.5, err)))
        t = mt__tex_mix(is_float, c.a, c.b, c.amount, tp->mode, err);
    mt__tex_children_put(&c);
    return t;
}

static const mt__texture_param_doc mixtex_params[] = {
    {"tex1", "any", "(1 - amount) tex1 + amount tex2"},
    {"tex2", "any", "(1 - amount) tex1 + amount tex2"},
    {"amount", "any (used as it is)", "the weight of tex2"},
};

const mt_texture_kind mt_mix_texture = {
    .name = "mix",
    .has_float = 1,
    .create = mixtex_create,
    .params = mixtex_params,
    .nparams = MT_COUNT(mixtex_params),
};
