/*
 * The process-wide image-map cache: pbrt-v2 reads each texture file once
 * per process and shares its MIPMap between every ImageTexture built with
 * the same filename, filtering options, wrap mode, scale and gamma
 * (textures/imagemap.h TexInfo, imagemap.cpp GetTexture; float and spectrum
 * textures have separate maps). Here the key also holds the mode (the
 * trilinear width erratum lives in the pyramid). A mutex guards the list;
 * the pyramids are read-only once made, so sharing them between threads
 * needs no lock.
 *
 * Texels are converted as pbrt-v2's convertIn does: RGB textures store
 * pow(scale * rgb, gamma) per component, float textures pow(scale * y(rgb),
 * gamma) with y() the RGBSpectrum luminance; a one-channel image is gray
 * RGB (v, v, v) first, as pbrt-v2's image readers make it. pow of a negative
 * value to a non-integer gamma (NaN in pbrt-v2) gives 0, by the MIP-map's
 * texel rule.
 */
#include <pthread.h>
#include <string.h>
#include "core/alloc.h"
#include "image/mipmap_impl.h"

typedef struct cache_entry {
    struct cache_entry *next;
    char *path;
    int trilinear, float_texture;
    mt_real maxaniso, scale, gamma;
    mt_wrap wrap;
    mt_mode mode;
    mt_mipmap *mipmap;
} cache_entry;

static pthread_mutex_t cache_lock = PTHREAD_MUTEX_INITIALIZER;
static cache_entry *cache_head;

static int same_key(const cache_entry *e, const char *path, int trilinear, mt_real maxaniso,
                    mt_wrap wrap, mt_real scale, mt_real gamma, int float_texture, mt_mode mode)
{
    return e->trilinear == trilinear && e->maxaniso == maxaniso && e->wrap == wrap &&
           e->scale == scale && e->gamma == gamma && e->float_texture == float_texture &&
           e->mode == mode && strcmp(e->path, path) == 0;
}

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

static mt_mipmap *load(const char *path, int trilinear, mt_real maxaniso, mt_wrap wrap,
                       mt_real scale, mt_real gamma, int float_texture, mt_mode mode,
                       mt_error *err)
{
    mt_image img;
    mt_real *texels;
    mt_mipmap *m;
    if (mt_image_read(path, &img, err) != MT_OK) return NULL;
    texels = convert_texels(&img, scale, gamma, float_texture);
    if (!texels) {
        mt_image_free(&img);
        mt_error_set(err, MT_ERR_NOMEM, "%s: out of memory", path);
        return NULL;
    }
    m = mt__mipmap_create_raw(img.width, img.height, float_texture ? 1 : 3, texels, trilinear,
                              maxaniso, wrap, mode, err);
    mt__free(texels);
    mt_image_free(&img);
    return m;
}

mt_mipmap *mt_mipmap_cache_get(const char *path, int trilinear, mt_real maxaniso, mt_wrap wrap,
                               mt_real scale, mt_real gamma, int float_texture, mt_mode mode,
                               mt_error *err)
{
    cache_entry *e;
    mt_mipmap *m = NULL;
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
    trilinear = trilinear != 0;
    float_texture = float_texture != 0;
    pthread_mutex_lock(&cache_lock);
    for (e = cache_head; e; e = e->next)
        if (same_key(e, path, trilinear, maxaniso, wrap, scale, gamma, float_texture, mode)) {
            m = e->mipmap;
            break;
        }
    if (!m) {
        /* loaded under the lock: a second thread asking for the same file
         * waits for this one instead of reading it again */
        m = load(path, trilinear, maxaniso, wrap, scale, gamma, float_texture, mode, err);
        e = m ? mt__calloc(1, sizeof *e) : NULL;
        if (e) e->path = mt__strdup(path);
        if (m && (!e || !e->path)) {
            if (e) mt__free(e);
            mt_mipmap_destroy(m);
            m = NULL;
            mt_error_set(err, MT_ERR_NOMEM, "%s: out of memory", path);
        } else if (m) {
            e->trilinear = trilinear;
            e->float_texture = float_texture;
            e->maxaniso = maxaniso;
            e->scale = scale;
            e->gamma = gamma;
            e->wrap = wrap;
            e->mode = mode;
            e->mipmap = m;
            e->next = cache_head;
            cache_head = e;
        }
    }
    pthread_mutex_unlock(&cache_lock);
    return m;
}

int mt_mipmap_cache_size(void)
{
    const cache_entry *e;
    int n = 0;
    pthread_mutex_lock(&cache_lock);
    for (e = cache_head; e; e = e->next) n++;
    pthread_mutex_unlock(&cache_lock);
    return n;
}

void mt_mipmap_cache_clear(void)
{
    cache_entry *e, *next;
    pthread_mutex_lock(&cache_lock);
    for (e = cache_head; e; e = next) {
        next = e->next;
        mt_mipmap_destroy(e->mipmap);
        mt__free(e->path);
        mt__free(e);
    }
    cache_head = NULL;
    pthread_mutex_unlock(&cache_lock);
}
