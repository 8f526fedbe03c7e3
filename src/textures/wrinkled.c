/* pbrt-v2 WrinkledTexture (textures/wrinkled.h): Turbulence of the
 * 3D-mapped point, its octaves limited by the footprint. */
#include "textures/noise.h"
#include "textures/create.h"

static const mt_texture_ops wrinkled_ops = {
    .name = "wrinkled",
    .eval_float = mt__noise_tex_float,
    .eval_rgb = mt__tex_gray_rgb,
};

mt_texture *mt__tex_wrinkled(int is_float, const mt_map3d *map, int octaves, mt_real roughness,
                             mt_mode mode, mt_error *err)
{
    return mt__noise_alloc(sizeof(mt__noise_tex), &wrinkled_ops, is_float, map, octaves,
                           roughness, mt__turbulence, mode, err);
}

static mt_texture *wrinkled_create(int is_float, const mt_transform *tex2world, const mt_texparams *tp,
                          mt_error *err)
{
    return mt__tex_create_octaves(mt__tex_wrinkled, is_float, tex2world, tp, err);
}

const mt_texture_kind mt_wrinkled_texture = {
    .name = "wrinkled",
    .has_float = 1,
    .create = wrinkled_create,
};
