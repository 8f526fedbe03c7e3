/* pbrt-v2 WrinkledTexture (textures/wrinkled.h): Turbulence of the
 * 3D-mapped point, its octaves limited by the footprint. */
#include "textures/noise.h"
#include "textures/tex.h"

static const mt_texture_ops wrinkled_ops = {"wrinkled", mt__noise_tex_float, mt__tex_gray_rgb,
                                            NULL};

mt_texture *mt__tex_wrinkled(int is_float, const mt_map3d *map, int octaves, mt_real roughness,
                             mt_mode mode, mt_error *err)
{
    return mt__noise_alloc(sizeof(mt__noise_tex), &wrinkled_ops, is_float, map, octaves,
                           roughness, mt__turbulence, mode, err);
}
