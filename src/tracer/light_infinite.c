/*
 * pbrt-v2's InfiniteAreaLight (lights/infinite.cpp): a constant radiance or
 * a latitude-longitude map times L, as a MIPMap (RGB, EWA-ready, repeat
 * wrap, resampled to powers of two); importance sampling by the map's
 * luminance at the level of one texel's width, weighted by sin(theta), with
 * a Distribution2D; (s, t) = (phi / 2 pi, theta / pi) in light space.
 *
 * The map is read here rather than through the texture cache: pbrt-v2
 * builds the sampling distribution at the size of the file's image (before
 * the pyramid's resampling to powers of two) and multiplies the texels by L
 * before the pyramid is built.
 */
#include "materia/sampling.h"
#include "core/alloc.h"
#include "tracer/light.h"

static mt_status constant_init(mt__light *l, mt_error *err)
{
    /* a 1x1 map: the distribution is uniform in (u, v) */
    mt_real y = mt_rgb_y(l->L);
    return mt__distrib2d_init(&l->distrib, &y, 1, 1, err);
}

static mt_status map_init(mt__light *l, const char *path, mt_mode mode, mt_error *err)
{
    mt_image img;
    mt_real *lum, filter;
    int w, h, u, v, c;
    size_t i;
    /* through pbrt-v2's ReadImage in pbrt-v2 mode, as InfiniteAreaLight
     * reads its map: the image-reading errata (EXR through half, Y-only EXR
     * black, PFM rows upside down) apply to environment maps too */
    mt_status st = mt_image_read_mode(path, mode, &img, err);
    if (st != MT_OK) return st;
    if (img.channels != 3) {
        /* gray or RGBA: keep the RGB (gray repeated), as pbrt-v2's ReadImage */
        mt_image rgb;
        if ((st = mt_image_create(&rgb, img.width, img.height, 3, err)) != MT_OK) {
            mt_image_destroy(&img);
            return st;
        }
        for (i = 0; i < (size_t)img.width * (size_t)img.height; ++i)
            for (c = 0; c < 3; ++c)
                rgb.data[3 * i + c] = img.data[i * (size_t)img.channels + (img.channels == 1 ? 0 : c)];
        mt_image_destroy(&img);
        img = rgb;
    }
    for (i = 0; i < (size_t)img.width * (size_t)img.height; ++i)
        for (c = 0; c < 3; ++c) img.data[3 * i + c] = (float)(img.data[3 * i + c] * l->L.c[c]);
    w = img.width;
    h = img.height;
    l->map = mt_mipmap_create(&img, 0, 8, MT_WRAP_REPEAT, mode, err);
    mt_image_destroy(&img);
    if (!l->map) return err ? err->status : MT_ERR_NOMEM;
    lum = mt__malloc((size_t)w * (size_t)h * sizeof *lum);
    if (!lum) return mt_error_set(err, MT_ERR_NOMEM, "%s: out of memory for the light's distribution", path);
    /* pbrt-v2: img[u + v w] = Lookup(u / w, v / h, 1 / max(w, h)).y() * sin(pi (v + .5) / h) */
    filter = (mt_real)1 / (mt_real)(w > h ? w : h);
    for (v = 0; v < h; ++v) {
        mt_real vp = (mt_real)v / (mt_real)h;
        mt_real sin_theta = mt_sin(MT_PI * ((mt_real)v + (mt_real)0.5) / (mt_real)h);
        for (u = 0; u < w; ++u) {
            mt_real up = (mt_real)u / (mt_real)w;
            lum[(size_t)u + (size_t)v * (size_t)w] =
                mt_rgb_y(mt_mipmap_lookup_width(l->map, up, vp, filter)) * sin_theta;
        }
    }
    st = mt__distrib2d_init(&l->distrib, lum, w, h, err);
    mt__free(lum);
    return st;
}

mt_status mt__infinite_init(mt__light *l, const char *mapname, mt_mode mode, mt_error *err)
{
    l->map = NULL;
    return mapname && *mapname ? map_init(l, mapname, mode, err) : constant_init(l, err);
}

static mt_rgb radiance_at(const mt__light *l, mt_real s, mt_real t)
{
    return l->map ? mt_mipmap_lookup_width(l->map, s, t, 0) : l->L;
}

mt_rgb mt__infinite_le(const mt__light *l, mt_vec3 d)
{
    mt_vec3 w;
    if (!l->map) return l->L;
    w = mt_v3_normalize(mt__m3_apply(l->w2l3, d));
    return radiance_at(l, mt_spherical_phi(w) * MT_INV_2PI, mt_spherical_theta(w) * MT_INV_PI);
}

void mt__infinite_sample(const mt__light *l, mt_real u1, mt_real u2, mt_vec3 *wi, mt_real *pdf,
                         mt_rgb *Li)
{
    mt_real uv[2], map_pdf, theta, phi, st, ct;
    mt__distrib2d_sample(&l->distrib, u1, u2, uv, &map_pdf);
    *pdf = 0;
    *Li = mt_rgb_black();
    if (!(map_pdf > 0)) return;
    theta = uv[1] * MT_PI;
    phi = uv[0] * 2 * MT_PI;
    ct = mt_cos(theta);
    st = mt_sin(theta);
    if (st == 0) return;
    *wi = mt_v3_normalize(
        mt__m3_apply(l->l2w3, mt_v3(st * mt_cos(phi), st * mt_sin(phi), ct)));
    /* dA = (2 pi) (pi) sin(theta) du dv */
    *pdf = map_pdf / (2 * MT_PI * MT_PI * st);
    *Li = radiance_at(l, uv[0], uv[1]);
}

mt_real mt__infinite_pdf(const mt__light *l, mt_vec3 wi)
{
    mt_vec3 w = mt_v3_normalize(mt__m3_apply(l->w2l3, wi));
    mt_real theta, phi, st;
    if (!l->map) {
        /* one cell: the density is uniform in (phi, theta) */
        st = mt_sqrt(mt_max(0, 1 - w.z * w.z));
        if (st == 0 || !(l->distrib.marginal.func_int > 0)) return 0;
        return 1 / (2 * MT_PI * MT_PI * st);
    }
    theta = mt_spherical_theta(w);
    phi = mt_spherical_phi(w);
    st = mt_sin(theta);
    if (st == 0) return 0;
    return mt__distrib2d_pdf(&l->distrib, phi * MT_INV_2PI, theta * MT_INV_PI) /
           (2 * MT_PI * MT_PI * st);
}
