/*
 * Per-pixel running mean and variance (Welford, "Note on a method for
 * calculating corrected sums of squares and products", Technometrics 4,
 * 1962): one pass, in double, no cancellation, and a variance of exactly 0
 * for identical samples.
 */
#include "core/alloc.h"
#include "materia/tools/imgcmp.h"

struct mt_imgacc {
    int width, height, channels;
    double *mean, *m2; /* per pixel and channel */
    long *n;           /* samples per pixel */
};

mt_imgacc *mt_imgacc_create(int width, int height, int channels, mt_error *err)
{
    mt_imgacc *acc;
    size_t np, nv;
    mt_error_clear(err);
    if (width < 1 || height < 1 || width > 65536 || height > 65536 ||
        (channels != 1 && channels != 3 && channels != 4)) {
        mt_error_set(err, MT_ERR_INVALID, "invalid accumulator size %d x %d x %d", width,
                     height, channels);
        return NULL;
    }
    np = (size_t)width * (size_t)height;
    nv = np * (size_t)channels;
    acc = mt__calloc(1, sizeof *acc);
    if (acc) {
        acc->mean = mt__calloc(nv, sizeof *acc->mean);
        acc->m2 = mt__calloc(nv, sizeof *acc->m2);
        acc->n = mt__calloc(np, sizeof *acc->n);
    }
    if (!acc || !acc->mean || !acc->m2 || !acc->n) {
        mt_imgacc_destroy(acc);
        mt_error_set(err, MT_ERR_NOMEM, "out of memory for a %d x %d accumulator", width,
                     height);
        return NULL;
    }
    acc->width = width;
    acc->height = height;
    acc->channels = channels;
    return acc;
}

void mt_imgacc_destroy(mt_imgacc *acc)
{
    if (!acc) return;
    mt__free(acc->mean);
    mt__free(acc->m2);
    mt__free(acc->n);
    mt__free(acc);
}

void mt_imgacc_add(mt_imgacc *acc, int x, int y, const float *v)
{
    size_t p, k;
    double n;
    int c;
    if (!acc || x < 0 || y < 0 || x >= acc->width || y >= acc->height) return;
    p = (size_t)y * (size_t)acc->width + (size_t)x;
    n = (double)++acc->n[p];
    for (c = 0, k = p * (size_t)acc->channels; c < acc->channels; ++c, ++k) {
        double d = (double)v[c] - acc->mean[k];
        acc->mean[k] += d / n;
        acc->m2[k] += d * ((double)v[c] - acc->mean[k]);
    }
}

mt_status mt_imgacc_add_image(mt_imgacc *acc, const mt_image *img, mt_error *err)
{
    int x, y;
    mt_error_clear(err);
    if (!acc || !img || !img->data)
        return mt_error_set(err, MT_ERR_INVALID, "mt_imgacc_add_image: no accumulator or image");
    if (img->width != acc->width || img->height != acc->height ||
        img->channels != acc->channels)
        return mt_error_set(err, MT_ERR_INVALID,
                            "image of %d x %d x %d added to an accumulator of %d x %d x %d",
                            img->width, img->height, img->channels, acc->width, acc->height,
                            acc->channels);
    for (y = 0; y < img->height; ++y)
        for (x = 0; x < img->width; ++x)
            mt_imgacc_add(acc, x, y,
                          img->data + ((size_t)y * (size_t)img->width + (size_t)x) *
                                          (size_t)img->channels);
    return MT_OK;
}

mt_status mt_imgacc_finish(const mt_imgacc *acc, mt_image *mean, mt_image *var_of_mean,
                           mt_error *err)
{
    size_t np, p, k;
    mt_status st;
    int c;
    mt_error_clear(err);
    if (!acc) return mt_error_set(err, MT_ERR_INVALID, "mt_imgacc_finish: no accumulator");
    np = (size_t)acc->width * (size_t)acc->height;
    for (p = 0; p < np; ++p)
        if (acc->n[p] < 2)
            return mt_error_set(err, MT_ERR_INVALID,
                                "pixel (%d, %d) has %ld sample%s: a variance needs two or more",
                                (int)(p % (size_t)acc->width), (int)(p / (size_t)acc->width),
                                acc->n[p], acc->n[p] == 1 ? "" : "s");
    if (mean && (st = mt_image_create(mean, acc->width, acc->height, acc->channels, err)) != MT_OK)
        return st;
    if (var_of_mean &&
        (st = mt_image_create(var_of_mean, acc->width, acc->height, acc->channels, err)) != MT_OK) {
        if (mean) mt_image_destroy(mean);
        return st;
    }
    for (p = 0; p < np; ++p) {
        double n = (double)acc->n[p];
        for (c = 0, k = p * (size_t)acc->channels; c < acc->channels; ++c, ++k) {
            if (mean) mean->data[k] = (float)acc->mean[k];
            if (var_of_mean) var_of_mean->data[k] = (float)(acc->m2[k] / (n - 1) / n);
        }
    }
    return MT_OK;
}
