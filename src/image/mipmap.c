/*
 * pbrt-v2's MIPMap (core/mipmap.h), written anew in C: the pyramid, texel
 * access with the wrap modes, the bilinear "triangle" filter, the isotropic
 * trilinear lookup and the EWA lookup with its Gaussian weight table.
 * Arithmetic is in mt_real and in pbrt-v2's order of operations, so that
 * the float build gives pbrt-v2's float answers; a float texture's value
 * travels in all three components of an mt_rgb, each component undergoing
 * exactly pbrt-v2's float operations.
 *
 * Where pbrt-v2 has undefined behaviour (a NaN coordinate, a footprint so
 * large that a float-to-int conversion overflows, an EWA box of billions of
 * texels) materia returns a defined value, as the comments below say.
 */
#include <string.h>
#include "core/alloc.h"
#include "image/mipmap_impl.h"

static const mt_real black_texel[3] = {0, 0, 0};

/* MIPMap::Texel: the texel at (s, t) of a level under the wrap mode. */
static const mt_real *texel_at(const mt_mipmap *m, int level, int s, int t)
{
    const mt__level *l = &m->level[level];
    switch (m->wrap) {
    case MT_WRAP_REPEAT:
        /* every level's sides are powers of two: the mask is pbrt-v2's Mod,
         * negative arguments included (two's complement) */
        s &= l->w - 1;
        t &= l->h - 1;
        break;
    case MT_WRAP_CLAMP:
        s = s < 0 ? 0 : (s > l->w - 1 ? l->w - 1 : s);
        t = t < 0 ? 0 : (t > l->h - 1 ? l->h - 1 : t);
        break;
    case MT_WRAP_BLACK:
        if (s < 0 || s >= l->w || t < 0 || t >= l->h) return black_texel;
        break;
    }
    return l->texels + ((size_t)t * (size_t)l->w + (size_t)s) * (size_t)m->nc;
}

static mt_rgb texel_rgb(const mt_mipmap *m, int level, int s, int t)
{
    const mt_real *p = texel_at(m, level, s, t);
    return m->nc == 1 ? mt_rgb_gray(p[0]) : mt_rgb_make(p[0], p[1], p[2]);
}

/* pbrt.h Log2: logf(x) * (1 / logf(2)), in mt_real. */
static mt_real log2_pbrt(mt_real x) { return mt_log(x) * (1 / mt_log((mt_real)2)); }

/* pbrt.h Log2Int(float(v)) as pbrt-v2 computes it, in float whatever mt_real
 * is: the number of levels is structure, not precision. (In float,
 * logf(8192) / logf(2) is 12.999999: pbrt-v2 gives 8192- and 32768-texel
 * images one level fewer, and materia reproduces that.) */
static int log2int_float(int v)
{
    volatile float inv = 1.f / logf(2.f);
    return (int)floorf(logf((float)v) * inv);
}

/* Coordinates a float-to-int conversion can take. */
static int int_range(mt_real x) { return x > (mt_real)-1e9 && x < (mt_real)1e9; }

/* MIPMap::triangle: bilinear interpolation of a level. */
static mt_rgb triangle(const mt_mipmap *m, int level, mt_real s, mt_real t)
{
    const mt__level *l;
    int s0, t0;
    mt_real ds, dt;
    mt_rgb r;
    level = level < 0 ? 0 : (level > m->levels - 1 ? m->levels - 1 : level);
    l = &m->level[level];
    s = s * (mt_real)l->w - (mt_real)0.5;
    t = t * (mt_real)l->h - (mt_real)0.5;
    if (!int_range(s) || !int_range(t)) {
        /* pbrt-v2: undefined (Floor2Int overflows). Far outside the image:
         * black, the edge texels, or the periodic image, by wrap mode. */
        if (m->wrap == MT_WRAP_BLACK) return mt_rgb_black();
        if (m->wrap == MT_WRAP_CLAMP) {
            s = mt_clamp(s, -1, (mt_real)l->w);
            t = mt_clamp(t, -1, (mt_real)l->h);
        } else {
            s = mt_fmod(s, (mt_real)l->w);
            t = mt_fmod(t, (mt_real)l->h);
        }
    }
    s0 = (int)mt_floor(s);
    t0 = (int)mt_floor(t);
    ds = s - (mt_real)s0;
    dt = t - (mt_real)t0;
    r = mt_rgb_scale(texel_rgb(m, level, s0, t0), (1 - ds) * (1 - dt));
    r = mt_rgb_add(r, mt_rgb_scale(texel_rgb(m, level, s0, t0 + 1), (1 - ds) * dt));
    r = mt_rgb_add(r, mt_rgb_scale(texel_rgb(m, level, s0 + 1, t0), ds * (1 - dt)));
    return mt_rgb_add(r, mt_rgb_scale(texel_rgb(m, level, s0 + 1, t0 + 1), ds * dt));
}

static mt_rgb top_texel(const mt_mipmap *m) { return texel_rgb(m, m->levels - 1, 0, 0); }

mt_rgb mt_mipmap_lookup_width(const mt_mipmap *m, mt_real s, mt_real t, mt_real width)
{
    mt_real level;
    int il;
    if (!m || !mt_is_finite(s) || !mt_is_finite(t)) return mt_rgb_black();
    /* NaN or infinite width: the infinitely wide footprint's limit */
    if (!(width <= MT_REAL_MAX)) return top_texel(m);
    level = (mt_real)(m->levels - 1) + log2_pbrt(mt_max(width, (mt_real)1e-8));
    if (level < 0) return triangle(m, 0, s, t);
    if (level >= (mt_real)(m->levels - 1)) return top_texel(m);
    il = (int)mt_floor(level);
    {
        mt_real delta = level - (mt_real)il;
        return mt_rgb_add(mt_rgb_scale(triangle(m, il, s, t), 1 - delta),
                          mt_rgb_scale(triangle(m, il + 1, s, t), delta));
    }
}

/* Texels an EWA box may visit before the defined fallback below takes over
 * (pbrt-v2 would loop for minutes, or overflow, with an unbounded
 * maxanisotropy and a footprint across many texture periods). */
#define EWA_MAX_TEXELS ((double)(1 << 24))

/* MIPMap::EWA. *ok = 0 when the box is beyond EWA_MAX_TEXELS (or the ellipse
 * degenerate), for the caller's fallback. */
static mt_rgb ewa(const mt_mipmap *m, int level, mt_real s, mt_real t, mt_real ds0, mt_real dt0,
                  mt_real ds1, mt_real dt1, int *ok)
{
    const mt__level *l;
    mt_real A, B, C, invF, det, invDet, uSqrt, vSqrt, sumWts = 0, lo_s, hi_s, lo_t, hi_t;
    mt_rgb sum = mt_rgb_black();
    int s0, s1, t0, t1, is, it;
    if (level >= m->levels) return top_texel(m);
    l = &m->level[level];
    s = s * (mt_real)l->w - (mt_real)0.5;
    t = t * (mt_real)l->h - (mt_real)0.5;
    ds0 *= (mt_real)l->w;
    dt0 *= (mt_real)l->h;
    ds1 *= (mt_real)l->w;
    dt1 *= (mt_real)l->h;
    /* the ellipse's implicit coefficients, including one texel of
     * reconstruction filter (the + 1), normalized to F = 1 */
    A = dt0 * dt0 + dt1 * dt1 + 1;
    B = -2 * (ds0 * dt0 + ds1 * dt1);
    C = ds0 * ds0 + ds1 * ds1 + 1;
    invF = 1 / (A * C - B * B * (mt_real)0.25);
    A *= invF;
    B *= invF;
    C *= invF;
    /* its bounding box in texels */
    det = -B * B + 4 * A * C;
    invDet = 1 / det;
    uSqrt = mt_sqrt(det * C);
    vSqrt = mt_sqrt(A * det);
    lo_s = s - 2 * invDet * uSqrt;
    hi_s = s + 2 * invDet * uSqrt;
    lo_t = t - 2 * invDet * vSqrt;
    hi_t = t + 2 * invDet * vSqrt;
    if (!(det > 0) || !int_range(lo_s) || !int_range(hi_s) || !int_range(lo_t) ||
        !int_range(hi_t) ||
        ((double)hi_s - (double)lo_s + 1) * ((double)hi_t - (double)lo_t + 1) > EWA_MAX_TEXELS) {
        *ok = 0;
        return sum;
    }
    s0 = (int)mt_ceil(lo_s);
    s1 = (int)mt_floor(hi_s);
    t0 = (int)mt_ceil(lo_t);
    t1 = (int)mt_floor(hi_t);
    for (it = t0; it <= t1; ++it) {
        mt_real tt = (mt_real)it - t;
        for (is = s0; is <= s1; ++is) {
            mt_real ss = (mt_real)is - s;
            mt_real r2 = A * ss * ss + B * ss * tt + C * tt * tt;
            if (r2 < 1) {
                int k = (int)(r2 * (mt_real)MT__WEIGHT_LUT_SIZE);
                mt_real w;
                k = k < 0 ? 0 : (k > MT__WEIGHT_LUT_SIZE - 1 ? MT__WEIGHT_LUT_SIZE - 1 : k);
                w = m->weight_lut[k];
                sum = mt_rgb_add(sum, mt_rgb_scale(texel_rgb(m, level, is, it), w));
                sumWts += w;
            }
        }
    }
    /* pbrt-v2 divides 0 by 0 when no texel has weight; the ellipse always
     * holds one in exact arithmetic, so this is only a guard */
    if (!(sumWts > 0)) {
        *ok = 0;
        return sum;
    }
    return mt_rgb_divs(sum, sumWts);
}

mt_rgb mt_mipmap_lookup(const mt_mipmap *m, mt_real s, mt_real t, mt_real ds0, mt_real dt0,
                        mt_real ds1, mt_real dt1)
{
    mt_real major, minor, lod, d;
    mt_rgb a, b;
    int ilod, ok = 1;
    if (!m || !mt_is_finite(s) || !mt_is_finite(t)) return mt_rgb_black();
    if (!mt_is_finite(ds0) || !mt_is_finite(dt0) || !mt_is_finite(ds1) || !mt_is_finite(dt1))
        return top_texel(m);
    if (m->trilinear) {
        mt_real w = mt_max(mt_max(mt_fabs(ds0), mt_fabs(dt0)), mt_max(mt_fabs(ds1), mt_fabs(dt1)));
        /* erratum trilinear-width: pbrt-v2 filters over twice the footprint */
        if (!(m->mode & MT_FIX_TRILINEAR_WIDTH)) w = 2 * w;
        return mt_mipmap_lookup_width(m, s, t, w);
    }
    /* the major axis is (ds0, dt0) */
    if (ds0 * ds0 + dt0 * dt0 < ds1 * ds1 + dt1 * dt1) {
        mt_real x = ds0;
        ds0 = ds1;
        ds1 = x;
        x = dt0;
        dt0 = dt1;
        dt1 = x;
    }
    major = mt_sqrt(ds0 * ds0 + dt0 * dt0);
    minor = mt_sqrt(ds1 * ds1 + dt1 * dt1);
    /* clamp the eccentricity: lengthen the minor axis */
    if (minor * m->maxaniso < major && minor > 0) {
        mt_real scale = major / (minor * m->maxaniso);
        ds1 *= scale;
        dt1 *= scale;
        minor *= scale;
    }
    if (minor == 0) return triangle(m, 0, s, t);
    lod = mt_max(0, (mt_real)m->levels - 1 + log2_pbrt(minor));
    /* an axis whose square overflowed: pbrt-v2 converts an infinite lod to
     * int; the infinitely wide footprint's limit is the top level */
    if (!(lod < (mt_real)1e6)) return top_texel(m);
    ilod = (int)mt_floor(lod);
    d = lod - (mt_real)ilod;
    a = ewa(m, ilod, s, t, ds0, dt0, ds1, dt1, &ok);
    b = ewa(m, ilod + 1, s, t, ds0, dt0, ds1, dt1, &ok);
    /* the defined fallback for a box beyond EWA_MAX_TEXELS: the isotropic
     * filter over the ellipse's bounding square */
    if (!ok) return mt_mipmap_lookup_width(m, s, t, 2 * major);
    return mt_rgb_add(mt_rgb_scale(a, 1 - d), mt_rgb_scale(b, d));
}

mt_rgb mt_mipmap_texel(const mt_mipmap *m, int level, int s, int t)
{
    if (!m) return mt_rgb_black();
    level = level < 0 ? 0 : (level > m->levels - 1 ? m->levels - 1 : level);
    return texel_rgb(m, level, s, t);
}

int mt_mipmap_levels(const mt_mipmap *m) { return m ? m->levels : 0; }
int mt_mipmap_width(const mt_mipmap *m, int level)
{
    return m && level >= 0 && level < m->levels ? m->level[level].w : 0;
}
int mt_mipmap_height(const mt_mipmap *m, int level)
{
    return m && level >= 0 && level < m->levels ? m->level[level].h : 0;
}
int mt_mipmap_channels(const mt_mipmap *m) { return m ? m->nc : 0; }

/* ---- creation ----------------------------------------------------- */

static mt_real sanitize(mt_real v)
{
    if (v != v) return 0;
    return mt_clamp(v, -MT__TEXEL_MAX, MT__TEXEL_MAX);
}

void mt_mipmap_destroy(mt_mipmap *m)
{
    int i;
    if (!m) return;
    for (i = 0; i < m->levels; i++) mt__free(m->level[i].texels);
    mt__free(m);
}

/* Level i from level i - 1: the box filter over four texels, read through
 * the wrap mode (which matters when a side is already 1). */
static void downsample(mt_mipmap *m, int i)
{
    mt__level *l = &m->level[i];
    int s, t, c;
    for (t = 0; t < l->h; t++)
        for (s = 0; s < l->w; s++) {
            const mt_real *a = texel_at(m, i - 1, 2 * s, 2 * t),
                          *b = texel_at(m, i - 1, 2 * s + 1, 2 * t),
                          *e = texel_at(m, i - 1, 2 * s, 2 * t + 1),
                          *f = texel_at(m, i - 1, 2 * s + 1, 2 * t + 1);
            mt_real *dst = l->texels + ((size_t)t * (size_t)l->w + (size_t)s) * (size_t)m->nc;
            for (c = 0; c < m->nc; c++) dst[c] = (mt_real)0.25 * (a[c] + b[c] + e[c] + f[c]);
        }
}

mt_mipmap *mt__mipmap_create_raw(int w, int h, int nc, const mt_real *texels, int trilinear,
                                 mt_real maxaniso, mt_wrap wrap, mt_mode mode, mt_error *err)
{
    mt_mipmap *m;
    mt_real *base;
    size_t n, k;
    int levels, i;
    if (w < 1 || h < 1 || (nc != 1 && nc != 3) || !texels || w > (1 << 24) || h > (1 << 24)) {
        mt_error_set(err, MT_ERR_INVALID, "a MIP-map needs an image of 1 or 3 channels");
        return NULL;
    }
    if (wrap != MT_WRAP_REPEAT && wrap != MT_WRAP_BLACK && wrap != MT_WRAP_CLAMP) {
        mt_error_param(err, MT_ERR_INVALID, "wrap", "unknown wrap mode %d", (int)wrap);
        return NULL;
    }
    if (!trilinear && !(maxaniso > 0)) {
        mt_error_param(err, MT_ERR_INVALID, "maxanisotropy",
                       "must be positive for EWA filtering (got %g)", (double)maxaniso);
        return NULL;
    }
    n = (size_t)w * (size_t)h * (size_t)nc;
    base = mt__malloc(n * sizeof *base);
    if (!base) goto nomem;
    for (k = 0; k < n; k++) base[k] = sanitize(texels[k]);
    if (!mt__is_pow2(w) || !mt__is_pow2(h)) {
        mt_real *z = mt__resample_pow2(w, h, nc, base, wrap, &w, &h);
        mt__free(base);
        base = z;
        if (!base) goto nomem;
    }
    levels = 1 + log2int_float(w > h ? w : h);
    m = mt__calloc(1, sizeof *m + (size_t)levels * sizeof(mt__level));
    if (!m) {
        mt__free(base);
        goto nomem;
    }
    m->nc = nc;
    m->levels = levels;
    m->trilinear = trilinear != 0;
    m->maxaniso = maxaniso;
    m->wrap = wrap;
    m->mode = mode;
    m->level[0].w = w;
    m->level[0].h = h;
    m->level[0].texels = base;
    for (i = 1; i < levels; i++) {
        mt__level *l = &m->level[i];
        l->w = m->level[i - 1].w / 2 > 1 ? m->level[i - 1].w / 2 : 1;
        l->h = m->level[i - 1].h / 2 > 1 ? m->level[i - 1].h / 2 : 1;
        l->texels = mt__malloc((size_t)l->w * (size_t)l->h * (size_t)nc * sizeof(mt_real));
        if (!l->texels) {
            mt_mipmap_destroy(m);
            goto nomem;
        }
        downsample(m, i);
    }
    /* the EWA filter's Gaussian, exp(-alpha r^2) - exp(-alpha), alpha = 2 */
    for (i = 0; i < MT__WEIGHT_LUT_SIZE; i++) {
        mt_real alpha = 2, r2 = (mt_real)i / (mt_real)(MT__WEIGHT_LUT_SIZE - 1);
        m->weight_lut[i] = mt_exp(-alpha * r2) - mt_exp(-alpha);
    }
    return m;
nomem:
    mt_error_set(err, MT_ERR_NOMEM, "out of memory for a %d x %d MIP-map", w, h);
    return NULL;
}

mt_mipmap *mt_mipmap_create(const mt_image *img, int trilinear, mt_real maxaniso, mt_wrap wrap,
                            mt_mode mode, mt_error *err)
{
    mt_mipmap *m;
    mt_real *texels;
    size_t n, k;
    int nc, c;
    mt_error_clear(err);
    if (!img || !img->data || img->width < 1 || img->height < 1 ||
        (img->channels != 1 && img->channels != 3 && img->channels != 4)) {
        mt_error_set(err, MT_ERR_INVALID, "mt_mipmap_create: not a valid image");
        return NULL;
    }
    nc = img->channels == 1 ? 1 : 3;
    n = (size_t)img->width * (size_t)img->height;
    texels = mt__malloc(n * (size_t)nc * sizeof *texels);
    if (!texels) {
        mt_error_set(err, MT_ERR_NOMEM, "out of memory for a MIP-map");
        return NULL;
    }
    for (k = 0; k < n; k++)
        for (c = 0; c < nc; c++)
            texels[k * (size_t)nc + (size_t)c] = (mt_real)img->data[k * (size_t)img->channels + (size_t)c];
    m = mt__mipmap_create_raw(img->width, img->height, nc, texels, trilinear, maxaniso, wrap, mode,
                              err);
    mt__free(texels);
    return m;
}
