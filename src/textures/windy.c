/* pbrt-v2 WindyTexture (textures/windy.h): waves (FBm, 6 octaves) scaled by
 * a slowly varying wind strength (|FBm| at a tenth of the frequency, 3
 * octaves), both with omega 0.5. No parameters. */
#include "textures/noise.h"
#include "textures/create.h"

static mt_real windy_float(const mt_texture *t, const mt_diffgeom *dg)
{
    const mt__noise_tex *n = (const mt__noise_tex *)t;
    mt_vec3 dpdx, dpdy, p = mt__map3d_apply(&n->map, dg, &dpdx, &dpdy);
    mt_real tenth = (mt_real)0.1, half = (mt_real)0.5;
    mt_real wind = mt__fbm(mt_v3_scale(p, tenth), mt_v3_scale(dpdx, tenth),
                           mt_v3_scale(dpdy, tenth), half, 3);
    mt_real height = mt__fbm(p, dpdx, dpdy, half, 6);
    return mt_fabs(wind) * height;
}

static const mt_texture_ops windy_ops = {
    .name = "windy",
    .eval_float = windy_float,
    .eval_rgb = mt__tex_gray_rgb,
};

mt_texture *mt__tex_windy(int is_float, const mt_map3d *map, mt_mode mode, mt_error *err)
{
    return mt__noise_alloc(sizeof(mt__noise_tex), &windy_ops, is_float, map, 6, (mt_real)0.5,
                           mt__fbm, mode, err);
}

static mt_texture *windy_create(int is_float, const mt_transform *tex2world, const mt_texparams *tp,
                          mt_error *err)
{
    mt_map3d m = mt__map3d(tex2world, tp->mode);
    return mt__tex_windy(is_float, &m, tp->mode, err);
}

const mt_texture_kind mt_windy_texture = {
    .name = "windy",
    .has_float = 1,
    .create = windy_create,
};
