/*
 * pbrt-v2's zoom of a non-power-of-two image up to powers of two (mipmap.h,
 * MIPMap::MIPMap and resampleWeights; Lanczos from texture.cpp): separable,
 * s first over the original rows, then t; 4 taps per output texel of a
 * Lanczos-windowed sinc with tau = 2 over a filter half-width of 2 input
 * texels, normalized to sum 1; taps outside the image follow the wrap mode
 * (black drops them); after the t pass negative values are clamped to 0.
 * Arithmetic in mt_real, in pbrt-v2's order.
 */
#include "core/alloc.h"
#include "image/mipmap_impl.h"

/* pbrt-v2 IsPowerOf2 as released (commit c2b069e): 0 is not a power of 2.
 * The MIP-map never asks about 0 (an image has at least one texel). */
int mt__is_pow2(int v) { return v && !(v & (v - 1)); }

int mt__round_up_pow2(int v)
{
    unsigned u = (unsigned)v - 1u;
    u |= u >> 1;
    u |= u >> 2;
    u |= u >> 4;
    u |= u >> 8;
    u |= u >> 16;
    return (int)(u + 1u);
}

/* pbrt.h Mod: the remainder made non-negative. */
int mt__mod(int a, int b)
{
    int n = a / b;
    a -= n * b;
    if (a < 0) a += b;
    return a;
}

/* texture.cpp Lanczos(x, tau): sinc(x tau) sinc(x) for |x| <= 1. */
static mt_real lanczos(mt_real x, mt_real tau)
{
    mt_real s, l;
    x = mt_fabs(x);
    if ((double)x < 1e-5) return 1; /* pbrt-v2 compares with the double 1e-5 */
    if (x > 1) return 0;
    x *= MT_PI;
    s = mt_sin(x * tau) / (x * tau);
    l = mt_sin(x) / x;
    return s * l;
}

typedef struct resample_weight {
    int first;
    mt_real w[4];
} resample_weight;

/* MIPMap::resampleWeights(oldres, newres). */
static resample_weight *resample_weights(int oldres, int newres)
{
    const mt_real filterwidth = 2;
    resample_weight *wt = mt__malloc(sizeof *wt * (size_t)newres);
    int i, j;
    if (!wt) return NULL;
    for (i = 0; i < newres; i++) {
        mt_real center = ((mt_real)i + (mt_real)0.5) * (mt_real)oldres / (mt_real)newres, inv;
        wt[i].first = (int)mt_floor((center - filterwidth) + (mt_real)0.5);
        for (j = 0; j < 4; j++) {
            mt_real pos = (mt_real)(wt[i].first + j) + (mt_real)0.5;
            wt[i].w[j] = lanczos((pos - center) / filterwidth, 2);
        }
        inv = 1 / (wt[i].w[0] + wt[i].w[1] + wt[i].w[2] + wt[i].w[3]);
        for (j = 0; j < 4; j++) wt[i].w[j] *= inv;
    }
    return wt;
}

/* The index a tap reads under the wrap mode, or -1 for black. */
static int wrap_index(int i, int res, mt_wrap wrap)
{
    if (wrap == MT_WRAP_REPEAT) i = mt__mod(i, res);
    else if (wrap == MT_WRAP_CLAMP) i = i < 0 ? 0 : (i > res - 1 ? res - 1 : i);
    return i >= 0 && i < res ? i : -1;
}

/* One line of the zoom: dst[i] (i < dstlen, stride dstep) from src[k]
 * (k < srclen, stride sstep) with the taps wt, nc values per texel;
 * MIPMap::MIPMap's inner loops, accumulating from 0 in tap order. */
static void zoom_line(const mt_real *src, size_t sstep, int srclen, mt_real *dst, size_t dstep,
                      int dstlen, const resample_weight *wt, mt_wrap wrap, int nc)
{
    int i, j, c;
    for (i = 0; i < dstlen; i++) {
        mt_real *d = dst + (size_t)i * dstep;
        for (c = 0; c < nc; c++) d[c] = 0;
        for (j = 0; j < 4; j++) {
            int k = wrap_index(wt[i].first + j, srclen, wrap);
            const mt_real *p;
            if (k < 0) continue;
            p = src + (size_t)k * sstep;
            for (c = 0; c < nc; c++) d[c] += wt[i].w[j] * p[c];
        }
    }
}

mt_real *mt__resample_pow2(int w, int h, int nc, const mt_real *texels, mt_wrap wrap, int *pw,
                           int *ph)
{
    int sp = mt__round_up_pow2(w), tp = mt__round_up_pow2(h), s, t, c;
    size_t px = (size_t)nc, row = (size_t)sp * px;
    resample_weight *sw = resample_weights(w, sp), *tw = resample_weights(h, tp);
    mt_real *out = mt__calloc((size_t)sp * (size_t)tp * px, sizeof(mt_real));
    mt_real *work = mt__malloc(sizeof(mt_real) * (size_t)tp * px);
    if (!sw || !tw || !out || !work) {
        mt__free(out);
        out = NULL;
        goto done;
    }
    /* zoom in s: rows t < h of out */
    for (t = 0; t < h; t++)
        zoom_line(texels + (size_t)t * (size_t)w * px, px, w, out + (size_t)t * row, px, sp, sw,
                  wrap, nc);
    /* zoom in t, column by column through a work column, then Clamp(v, 0,
     * INFINITY) */
    for (s = 0; s < sp; s++) {
        zoom_line(out + (size_t)s * px, row, h, work, px, tp, tw, wrap, nc);
        for (t = 0; t < tp; t++)
            for (c = 0; c < nc; c++) {
                mt_real v = work[(size_t)t * px + (size_t)c];
                out[(size_t)t * row + (size_t)s * px + (size_t)c] = v < 0 ? 0 : v;
            }
    }
    *pw = sp;
    *ph = tp;
done:
    mt__free(sw);
    mt__free(tw);
    mt__free(work);
    return out;
}
