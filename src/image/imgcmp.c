/*
 * pbrt-v2's noise metric (../shared/reference/pbrt-v2/noise.txt: 4x4 block
 * means, |a - b| / (b + 0.01) per block and channel, mean, 99th percentile,
 * max, luminance ratio) and per-pixel errors.
 */
#include <math.h>
#include <stdlib.h>
#include "core/alloc.h"
#include "image/cmpblocks.h"
#include "materia/tools/imgcmp.h"
#include "materia/rgb.h"

static int cmp_double(const void *pa, const void *pb)
{
    double a = *(const double *)pa, b = *(const double *)pb;
    return a < b ? -1 : a > b;
}

double mt_imgcmp_percentile(double *v, size_t n, double q)
{
    double h, f;
    size_t lo;
    if (n == 0) return 0;
    qsort(v, n, sizeof *v, cmp_double);
    if (!(q > 0)) return v[0];
    if (q >= 1) return v[n - 1];
    h = (double)(n - 1) * q;
    lo = (size_t)h;
    f = h - (double)lo;
    return lo + 1 < n ? v[lo] + f * (v[lo + 1] - v[lo]) : v[lo];
}

/* Mean luminance: y of the mean colour (y is linear, so this is the mean of
 * the pixels' y), with pbrt-v2's weights. */
static double mean_y(const mt_image *img, const mt__grid *g)
{
    double s[3] = {0, 0, 0}, n = (double)g->width * (double)g->height;
    size_t k, np = (size_t)g->width * (size_t)g->height;
    int c;
    for (k = 0; k < np; ++k)
        for (c = 0; c < g->nc; ++c) s[c] += img->data[k * (size_t)img->channels + (size_t)c];
    if (g->nc == 1) return s[0] / n;
    return (double)mt_rgb_y(mt_rgb_make((mt_real)(s[0] / n), (mt_real)(s[1] / n),
                                        (mt_real)(s[2] / n)));
}

/* The per-block, per-channel relative differences of a against b. */
static double *reldiffs(const mt_image *a, const mt_image *b, const mt__grid *g,
                        mt_error *err)
{
    double *ma = mt__block_means(a, g, err), *mb = ma ? mt__block_means(b, g, err) : NULL;
    size_t n = (size_t)g->bx * (size_t)g->by * (size_t)g->nc, k;
    if (!mb) {
        mt__free(ma);
        return NULL;
    }
    for (k = 0; k < n; ++k) ma[k] = mt__reldiff(ma[k], mb[k]);
    mt__free(mb);
    return ma;
}

mt_status mt_imgcmp_noise(const mt_image *a, const mt_image *b, int block,
                          mt_noise_metric *out, mt_error *err)
{
    mt__grid g;
    mt_status st;
    double *r, sum = 0, mx = 0;
    size_t n, k;
    mt_error_clear(err);
    if (!out) return mt_error_set(err, MT_ERR_INVALID, "mt_imgcmp_noise: no output");
    if ((st = mt__cmp_pair(a, b, block, &g, err)) != MT_OK) return st;
    if (!(r = reldiffs(a, b, &g, err))) return MT_ERR_NOMEM;
    n = (size_t)g.bx * (size_t)g.by * (size_t)g.nc;
    for (k = 0; k < n; ++k) {
        sum += r[k];
        if (r[k] > mx) mx = r[k];
    }
    out->mean = sum / (double)n;
    out->max = mx;
    out->p99 = mt_imgcmp_percentile(r, n, 0.99);
    mt__free(r);
    out->y_a = mean_y(a, &g);
    out->y_b = mean_y(b, &g);
    out->lum_ratio = out->y_b != 0 ? out->y_a / out->y_b : (out->y_a == 0 ? 1 : 0);
    out->blocks_x = g.bx;
    out->blocks_y = g.by;
    out->channels = g.nc;
    return MT_OK;
}

mt_status mt_imgcmp_pixel_errors(const mt_image *a, const mt_image *b, mt_pixel_errors *out,
                                 mt_error *err)
{
    mt__grid g;
    mt_status st;
    double se = 0, rse = 0, n;
    int x, y, c;
    mt_error_clear(err);
    if (!out) return mt_error_set(err, MT_ERR_INVALID, "mt_imgcmp_pixel_errors: no output");
    if ((st = mt__cmp_pair(a, b, 1, &g, err)) != MT_OK) return st;
    out->max_abs = 0;
    out->max_x = out->max_y = out->max_c = 0;
    for (y = 0; y < g.height; ++y)
        for (x = 0; x < g.width; ++x)
            for (c = 0; c < g.nc; ++c) {
                size_t p = (size_t)y * (size_t)g.width + (size_t)x;
                double va = a->data[p * (size_t)a->channels + (size_t)c];
                double vb = b->data[p * (size_t)b->channels + (size_t)c];
                double d = va - vb;
                se += d * d;
                rse += d * d / (vb * vb + MT_IMGCMP_OFFSET);
                if (fabs(d) > out->max_abs) {
                    out->max_abs = fabs(d);
                    out->max_x = x;
                    out->max_y = y;
                    out->max_c = c;
                }
            }
    n = (double)g.width * (double)g.height * (double)g.nc;
    out->rmse = sqrt(se / n);
    out->relmse = rse / n;
    return MT_OK;
}

mt_status mt_imgcmp_reldiff_blocks(const mt_image *a, const mt_image *b, int block,
                                   mt_image *map, mt_error *err)
{
    mt__grid g;
    mt_status st;
    double *r;
    mt_error_clear(err);
    if (!map) return mt_error_set(err, MT_ERR_INVALID, "mt_imgcmp_reldiff_blocks: no output");
    if ((st = mt__cmp_pair(a, b, block, &g, err)) != MT_OK) return st;
    if (!(r = reldiffs(a, b, &g, err))) return MT_ERR_NOMEM;
    st = mt__blocks_image(r, &g, map, err);
    mt__free(r);
    return st;
}
