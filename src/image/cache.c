/*
 * The process-wide image-map cache: pbrt-v2 reads each texture file once
 * per process and shares its MIPMap between every ImageTexture built with
 * the same filename, filtering options, wrap mode, scale and gamma
 * (textures/imagemap.h TexInfo, imagemap.cpp GetTexture; float and spectrum
 * textures have separate maps). Here the key also holds the mode's bits
 * that change the pyramid (MT__MIPMAP_MODE_BITS: the trilinear width
 * erratum lives in the pyramid, and the image-reading errata change its
 * texels), so that one file used in both modes gives two pyramids. The
 * entries live in the generic cache of core/cache.h; the pyramids are
 * read-only once made, so sharing them between threads needs no lock, and
 * they belong to the cache (callers borrow them).
 *
 * Texels are converted as pbrt-v2's convertIn does: RGB textures store
 * pow(scale * rgb, gamma) per component, float textures pow(scale * y(rgb),
 * gamma) with y() the RGBSpectrum luminance; a one-channel image is gray
 * RGB (v, v, v) first, as pbrt-v2's image readers make it. pow of a negative
 * value to a non-integer gamma (NaN in pbrt-v2) gives 0, by the MIP-map's
 * texel rule.
 */
#include <stdio.h>
#include <string.h>
#include "core/alloc.h"
#include "core/cache.h"
#include "image/formats.h"
#include "image/mipmap_impl.h"

/* What a pyramid is made from: the cache key's contents. */
typedef struct texinfo {
    const char *path;
    int trilinear, float_texture;
    mt_real maxaniso, scale, gamma;
    mt_wrap wrap;
    mt_mode mode; /* MT__MIPMAP_MODE_BITS only */
} texinfo;

/* imagemap.h convertIn, texel by texel. */
static mt_real *convert_texels(const mt_image *img, mt_real scale, mt_real gamma,
                               int float_texture)
{
    size_t n = (size_t)img->width * (size_t)img->height, k;
    int nc = float_texture ? 1 : 3, c;
    mt_real *out = mt__malloc(n * (size_t)nc * sizeof *out);
    if (!out) return NULL;
    for (k = 0; k < n; k++) {
        const float *p = img->data + k * (size_t)img->channels;
        mt_rgb rgb = img->channels == 1 ? mt_rgb_gray(p[0]) : mt_rgb_make(p[0], p[1], p[2]);
        if (float_texture) {
            out[k] = mt_pow(scale * mt_rgb_y(rgb), gamma);
        } else {
            for (c = 0; c < 3; c++) out[k * 3 + (size_t)c] = mt_pow(scale * rgb.c[c], gamma);
        }
    }
    return out;
}

/* The cache's builder: reads the file as the mode's textures see it. */
static void *load_pyramid(void *ctx, mt_error *err)
{
    const texinfo *ti = ctx;
    mt_image img;
    mt_real *texels;
    mt_mipmap *m;
    /* through the formats the program links (image/formats.h): making
     * textures from statements does not link OpenEXR and libpng */
    if (mt__image_read_linked(ti->path, ti->mode, &img, err) != MT_OK) return NULL;
    texels = convert_texels(&img, ti->scale, ti->gamma, ti->float_texture);
    if (!texels) {
        mt_image_destroy(&img);
        mt_error_set(err, MT_ERR_NOMEM, "%s: out of memory", ti->path);
        return NULL;
    }
    m = mt__mipmap_create_raw(img.width, img.height, ti->float_texture ? 1 : 3, texels,
                              ti->trilinear, ti->maxaniso, ti->wrap, ti->mode, err);
    mt__free(texels);
    mt_image_destroy(&img);
    return m;
}

static void destroy(void *m) { mt_mipmap_destroy(m); }

static mt__cache mipmap_cache = MT__CACHE_INIT(NULL, destroy);

/* The key: every field but the path in a fixed format (numbers as exact
 * hexadecimal floats; -0 as 0, since the key compares values as pbrt-v2's
 * TexInfo does), then the path. NULL when out of memory. */
static char *make_key(const texinfo *ti)
{
    char head[160];
    size_t hl, pl;
    char *key;
    int n = snprintf(head, sizeof head, "%d %d %d %a %a %a %x|", ti->trilinear,
                     ti->float_texture, (int)ti->wrap, (double)(ti->maxaniso + 0),
                     (double)(ti->scale + 0), (double)(ti->gamma + 0), ti->mode);
    if (n < 0 || (size_t)n >= sizeof head) return NULL;
    hl = (size_t)n;
    pl = strlen(ti->path);
    key = mt__malloc(hl + pl + 1);
    if (!key) return NULL;
    memcpy(key, head, hl);
    memcpy(key + hl, ti->path, pl + 1);
    return key;
}

mt_mipmap *mt_mipmap_cache_get(const char *path, int trilinear, mt_real maxaniso, mt_wrap wrap,
                               mt_real scale, mt_real gamma, int float_texture, mt_mode mode,
                               mt_error *err)
{
    texinfo ti;
    char *key;
    mt_mipmap *m;
    mt_error_clear(err);
    if (!path || !path[0]) {
        mt_error_param(err, MT_ERR_INVALID, "filename", "no image file name");
        return NULL;
    }
    if (maxaniso != maxaniso) {
        mt_error_param(err, MT_ERR_INVALID, "maxanisotropy", "must be a number");
        return NULL;
    }
    if (!mt_is_finite(scale)) {
        mt_error_param(err, MT_ERR_INVALID, "scale", "must be a finite number");
        return NULL;
    }
    if (!mt_is_finite(gamma)) {
        mt_error_param(err, MT_ERR_INVALID, "gamma", "must be a finite number");
        return NULL;
    }
    ti.path = path;
    ti.trilinear = trilinear != 0;
    ti.float_texture = float_texture != 0;
    ti.maxaniso = maxaniso;
    ti.scale = scale;
    ti.gamma = gamma;
    ti.wrap = wrap;
    ti.mode = mode & MT__MIPMAP_MODE_BITS;
    key = make_key(&ti);
    if (!key) {
        mt_error_set(err, MT_ERR_NOMEM, "%s: out of memory", path);
        return NULL;
    }
    m = mt__cache_get(&mipmap_cache, key, path, load_pyramid, &ti, err);
    mt__free(key);
    return m;
}

int mt_mipmap_cache_size(void) { return mt__cache_size(&mipmap_cache); }

void mt_mipmap_cache_clear(void) { mt__cache_clear(&mipmap_cache); }
