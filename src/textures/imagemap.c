/*
 * pbrt-v2 ImageTexture (textures/imagemap.h): the MIP-map of an image file
 * looked up at the mapped (s, t) with the mapping's derivatives as the
 * filter footprint (trilinear or EWA, as the pyramid was made). The pyramid
 * belongs to the process-wide cache (pbrt-v2 reads each file once per
 * process); the texture only refers to it. A float image map's texels are
 * luminance, which the cache stores in all three channels.
 */
#include "materia/mipmap.h"
#include "textures/tex.h"

typedef struct imagemap {
    mt_texture base;
    mt_map2d map;
    const mt_mipmap *mip;
} imagemap;

static mt_rgb lookup(const mt_texture *t, const mt_diffgeom *dg)
{
    const imagemap *im = (const imagemap *)t;
    mt_st st;
    mt__map2d_apply(&im->map, dg, &st);
    return mt_mipmap_lookup(im->mip, st.s, st.t, st.dsdx, st.dtdx, st.dsdy, st.dtdy);
}

static mt_real imagemap_float(const mt_texture *t, const mt_diffgeom *dg)
{
    return lookup(t, dg).c[0];
}

static const mt_texture_ops imagemap_ops = {"imagemap", imagemap_float, lookup, NULL};

mt_texture *mt__tex_imagemap(int is_float, const mt_map2d *map, const mt_mipmap *mip,
                             mt_mode mode, mt_error *err)
{
    imagemap *im;
    if (mt__map2d_check(map, "imagemap", err)) return NULL;
    if (!mip) {
        mt_error_set(err, MT_ERR_INVALID, "imagemap texture: no MIP-map");
        return NULL;
    }
    im = mt__texture_alloc(sizeof *im, &imagemap_ops, is_float, mode, err);
    if (!im) return NULL;
    im->map = *map;
    im->mip = mip;
    return &im->base;
}
