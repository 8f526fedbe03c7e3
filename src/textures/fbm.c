/* pbrt-v2 FBmTexture (textures/fbm.h): FBm of the 3D-mapped point, its
 * octaves limited by the footprint. */
#include "textures/noise.h"
#include "textures/create.h"

static const mt_texture_ops fbm_ops = {
    .name = "fbm",
    .eval_float = mt__noise_tex_float,
    .eval_rgb = mt__tex_gray_rgb,
};

mt_texture *mt__tex_fbm(int is_float, const mt_map3d *map, int octaves, mt_real roughness,
                        mt_mode mode, mt_error *err)
{
    return mt__noise_alloc(sizeof(mt__noise_tex), &fbm_ops, is_float, map, octaves, roughness,
                           mt__fbm, mode, err);
}

static mt_texture *fbm_create(int is_float, const mt_transform *tex2world, const mt_texparams *tp,
                          mt_error *err)
{
    return mt__tex_create_octaves(mt__tex_fbm, is_float, tex2world, tp, err);
}

const mt_texture_kind mt_fbm_texture = {
    .name = "fbm",
    .has_float = 1,
    .create = fbm_create,
};
