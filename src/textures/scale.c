/* pbrt-v2 ScaleTexture (textures/scale.h): tex1 * tex2. */
#include "textures/tex.h"

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

static const mt_texture_ops scale_ops = {"scale", scale_float, scale_rgb, mt__pair_finalize};

mt_texture *mt__tex_scale(int is_float, mt_texture *tex1, mt_texture *tex2, mt_mode mode,
                          mt_error *err)
{
    return mt__pair_alloc(sizeof(mt__pair_tex), &scale_ops, is_float, tex1, "tex1", tex2, "tex2",
                          mode, err);
}
