/* pbrt-v2 ConstantTexture (textures/constant.h): the same value everywhere. */
#include "textures/create.h"

typedef struct constant {
    mt_texture base;
    mt_rgb value; /* c[0] for the float variant */
} constant;

static mt_real constant_float(const mt_texture *t, const mt_diffgeom *dg)
{
    (void)dg;
    return ((const constant *)t)->value.c[0];
}

static mt_rgb constant_rgb(const mt_texture *t, const mt_diffgeom *dg)
{
    (void)dg;
    return ((const constant *)t)->value;
}

static const mt_texture_ops constant_ops = {
    .name = "constant",
    .eval_float = constant_float,
    .eval_rgb = constant_rgb,
};

int mt__texture_is_constant(const mt_texture *t) { return t->ops == &constant_ops; }

mt_texture *mt__tex_constant(int is_float, mt_rgb v, mt_mode mode, mt_error *err)
{
    constant *c;
    if (is_float) v = mt_rgb_gray(v.c[0]);
    if (!mt__tex_check_rgb(v, "value", "constant", err)) return NULL;
    c = mt__texture_alloc(sizeof *c, &constant_ops, is_float, mode, err);
    if (!c) return NULL;
    c->value = v;
    return &c->base;
}

mt_texture *mt_texture_constant_float(mt_real v, mt_error *err)
{
    mt_error_clear(err);
    return mt__tex_constant(1, mt_rgb_gray(v), MT_MODE_PBRT_V2, err);
}

mt_texture *mt_texture_constant_rgb(mt_rgb v, mt_error *err)
{
    mt_error_clear(err);
    return mt__tex_constant(0, v, MT_MODE_PBRT_V2, err);
}

static mt_texture *constant_create(int is_float, const mt_transform *tex2world, const mt_texparams *tp,
                          mt_error *err)
{
    mt_rgb v;
    if (mt__tex_value(tp, is_float, "value", 1, &v, err)) return NULL;
    return mt__tex_constant(is_float, v, tp->mode, err);
}

static const mt__texture_param_doc constant_params[] = {{"value", "finite", "the value everywhere"}};

const mt_texture_kind mt_constant_texture = {
    .name = "constant",
    .has_float = 1,
    .create = constant_create,
    .params = constant_params,
    .nparams = MT_COUNT(constant_params),
};
