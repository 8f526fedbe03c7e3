/*
 * Checks and block means shared by the image comparisons.
 */
#include <math.h>
#include "core/alloc.h"
#include "image/cmpblocks.h"
#include "materia/tools/imgcmp.h"

int mt__cmp_channels(const mt_image *img) { return img->channels == 1 ? 1 : 3; }

mt_status mt__cmp_check(const mt_image *img, const char *name, const mt__grid *g, int nonneg,
                        mt_error *err)
{
    int x, y, c;
    if (!img || !img->data || img->width < 1 || img->height < 1 ||
        (img->channels != 1 && img->channels != 3 && img->channels != 4))
        return mt_error_set(err, MT_ERR_INVALID, "image %s is missing or empty", name);
    if (img->width != g->width || img->height != g->height)
        return mt_error_set(err, MT_ERR_INVALID,
                            "size mismatch: image %s is %d x %d, expected %d x %d", name,
                            img->width, img->height, g->width, g->height);
    if (mt__cmp_channels(img) != g->nc)
        return mt_error_set(err, MT_ERR_INVALID,
                            "channel mismatch: image %s has %d channel%s, expected %s", name,
                            img->channels, img->channels == 1 ? "" : "s",
                            g->nc == 1 ? "one (Y)" : "three or four (RGB, RGBA)");
    for (y = 0; y < img->height; ++y)
        for (x = 0; x < img->width; ++x)
            for (c = 0; c < g->nc; ++c) {
                float v = img->data[((size_t)y * (size_t)img->width + (size_t)x) *
                                        (size_t)img->channels + (size_t)c];
                if (!isfinite(v))
                    return mt_error_set(err, MT_ERR_INVALID,
                                        "image %s has a non-finite value at pixel (%d, %d), "
                                        "channel %d",
                                        name, x, y, c);
                if (nonneg && v < 0)
                    return mt_error_set(err, MT_ERR_INVALID,
                                        "image %s has a negative variance (%g) at pixel "
                                        "(%d, %d), channel %d",
                                        name, (double)v, x, y, c);
            }
    return MT_OK;
}

mt_status mt__cmp_pair(const mt_image *a, const mt_image *b, int block, mt__grid *g,
                       mt_error *err)
{
    mt_status st;
    if (!a || !a->data || a->width < 1 || a->height < 1)
        return mt_error_set(err, MT_ERR_INVALID, "image a is missing or empty");
    if (block < 1 || block > 65536)
        return mt_error_set(err, MT_ERR_INVALID, "block size %d is not between 1 and 65536",
                            block);
    g->width = a->width;
    g->height = a->height;
    g->block = block;
    g->bx = (a->width + block - 1) / block;
    g->by = (a->height + block - 1) / block;
    g->nc = mt__cmp_channels(a);
    if ((st = mt__cmp_check(a, "a", g, 0, err)) != MT_OK) return st;
    return mt__cmp_check(b, "b", g, 0, err);
}

int mt__block_pixels(const mt__grid *g, int i, int j)
{
    int w = g->width - i * g->block, h = g->height - j * g->block;
    if (w > g->block) w = g->block;
    if (h > g->block) h = g->block;
    return w * h;
}

double *mt__block_means(const mt_image *img, const mt__grid *g, mt_error *err)
{
    size_t n = (size_t)g->bx * (size_t)g->by * (size_t)g->nc, k;
    double *m = mt__calloc(n, sizeof *m);
    int x, y, c, i, j;
    if (!m) {
        mt_error_set(err, MT_ERR_NOMEM, "out of memory for %lu block means", (unsigned long)n);
        return NULL;
    }
    for (y = 0; y < g->height; ++y)
        for (x = 0; x < g->width; ++x) {
            const float *p = img->data + ((size_t)y * (size_t)g->width + (size_t)x) *
                                             (size_t)img->channels;
            double *q = m + ((size_t)(y / g->block) * (size_t)g->bx + (size_t)(x / g->block)) *
                                (size_t)g->nc;
            for (c = 0; c < g->nc; ++c) q[c] += p[c];
        }
    for (j = 0, k = 0; j < g->by; ++j)
        for (i = 0; i < g->bx; ++i) {
            double np = mt__block_pixels(g, i, j);
            for (c = 0; c < g->nc; ++c, ++k) m[k] /= np;
        }
    return m;
}

double mt__reldiff(double a, double b) { return fabs(a - b) / (fabs(b) + MT_IMGCMP_OFFSET); }

mt_status mt__blocks_image(const double *v, const mt__grid *g, mt_image *out, mt_error *err)
{
    size_t n = (size_t)g->bx * (size_t)g->by * (size_t)g->nc, k;
    mt_status st = mt_image_create(out, g->bx, g->by, g->nc, err);
    if (st != MT_OK) return st;
    for (k = 0; k < n; ++k) out->data[k] = (float)v[k];
    return MT_OK;
}
