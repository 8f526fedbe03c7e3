/*
 * pbrt-v2 ImageTexture (textures/imagemap.h): the MIP-map of an image file
 * looked up at the mapped (s, t) with the mapping's derivatives as the
 * filter footprint (trilinear or EWA, as the pyramid was made). The pyramid
 * belongs to the process-wide cache (pbrt-v2 reads each file once per
 * process); the texture only refers to it. A float image map's texels are
 * luminance, which the cache stores in all three channels.
 */
#include "materia/mipmap.h"
#include "textures/create.h"

typedef struct imagemap {
    mt_texture base;
    mt_map2d map;
    const mt_mipmap *mip;
} imagemap;

static mt_rgb imagemap_lookup(const mt_texture *t, const mt_diffgeom *dg)
{
    const imagemap *im = (const imagemap *)t;
    mt_st st;
    mt__map2d_apply(&im->map, dg, &st);
    return mt_mipmap_lookup(im->mip, st.s, st.t, st.dsdx, st.dtdx, st.dsdy, st.dtdy);
}

static mt_real imagemap_float(const mt_texture *t, const mt_diffgeom *dg)
{
    return imagemap_lookup(t, dg).c[0];
}

static const mt_texture_ops imagemap_ops = {
    .name = "imagemap",
    .eval_float = imagemap_float,
    .eval_rgb = imagemap_lookup,
};

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

/* pbrt-v2 CreateImage*Texture: the parameters checked here; the pyramid
 * comes from the process-wide MIP-map cache (each file read once). */
static mt_texture *imagemap_create(int is_float, const mt_transform *tex2world, const mt_texparams *tp,
                          mt_error *err)
{
    static const char *const wraps[] = {"repeat", "black", "clamp", NULL}; /* mt_wrap order */
    mt_map2d m;
    mt_real maxaniso, scale, gamma;
    int trilinear, wrap;
    char path[4096];
    const mt_mipmap *mip;
    if (mt__tex_mapping2d(tex2world, tp, "imagemap", &m, err) ||
        mt_texparams_float(tp, "maxanisotropy", 8, &maxaniso, err) ||
        mt_texparams_bool(tp, "trilinear", 0, &trilinear, err) ||
        (wrap = mt__tex_choice(tp, "wrap", "repeat", wraps, "imagemap", err)) < 0 ||
        mt_texparams_float(tp, "scale", 1, &scale, err) ||
        mt_texparams_float(tp, "gamma", 1, &gamma, err) ||
        mt_texparams_filename(tp, "filename", "", path, sizeof path, err))
        return NULL;
    if (!mt__tex_check_real(scale, "scale", "imagemap", err) ||
        !mt__tex_check_real(gamma, "gamma", "imagemap", err))
        return NULL;
    /* pow(0, gamma) is infinite for gamma < 0 */
    if (gamma < 0) {
        mt_error_param(err, MT_ERR_INVALID, "gamma", "imagemap texture: gamma %g is negative",
                       (double)gamma);
        return NULL;
    }
    if (!path[0]) {
        mt_error_param(err, MT_ERR_INVALID, "filename", "imagemap texture: no filename");
        return NULL;
    }
    /* the pyramid is the cache's, shared and read-only */
    mip = mt_mipmap_cache_get(path, trilinear, maxaniso, (mt_wrap)wrap, scale, gamma, is_float,
                              tp->mode, err);
    if (!mip) return NULL;
    return mt__tex_imagemap(is_float, &m, mip, tp->mode, err);
}

static const mt__texture_param_doc imagemap_params[] = {
    {"filename", "an .exr, .png or .pfm file (required)", "the image, read once per process"},
    {"maxanisotropy", "> 0 (with EWA filtering)", "the longest ellipse axis over the shortest"},
    {"trilinear", "true or false", "trilinear filtering instead of EWA"},
    {"wrap", "repeat, black or clamp", "lookups outside [0, 1]"},
    {"scale", "finite", "texel values times scale"},
    {"gamma", ">= 0", "texel values to the power gamma (after scale)"},
};

const mt_texture_kind mt_imagemap_texture = {
    .name = "imagemap",
    .has_float = 1,
    .create = imagemap_create,
    .params = imagemap_params,
    .nparams = MT_COUNT(imagemap_params),
};
