/*
 * The statistics of a golden image whose error is not only sampling noise:
 * the dipole integrator's point set and irradiance samples change with the
 * seed and put smooth blotches over a subsurface object, correlated over
 * many pixels, which no per-pixel variance describes. So the golden set is K
 * renders with seeds 1..K, and the check compares a few aggregate numbers --
 * the mean of each channel over blocks of 16x16 pixels, over the whole
 * image and over its central box -- with their spread over those K renders (tools/materia-golden.c
 * writes them, tests/test_golden.c reads them).
 *
 * Static inline: shared by a tool and a test, as tests/support/trender.h.
 */
#ifndef MT_TEST_BLOCKSTATS_H
#define MT_TEST_BLOCKSTATS_H

#include <stdio.h>
#include "materia/image.h"

#define T_BLOCKSTAT_SIDE 16
#define T_BLOCKSTAT_MAX 1024

/* The statistics of img: per block of T_BLOCKSTAT_SIDE (the last row and
 * column of blocks may be narrower) and channel, the mean, then the mean of
 * each channel over the image, then over the central box. Returns their count (0 when out does not
 * have room). */
static inline int t_blockstats(const mt_image *img, double *out, int max)
{
    int B = T_BLOCKSTAT_SIDE, nbx = (img->width + B - 1) / B, nby = (img->height + B - 1) / B;
    int c, bx, by, x, y, n = 0, nc = img->channels < 3 ? img->channels : 3;
    if ((nbx * nby + 2) * nc > max) return 0;
    for (by = 0; by < nby; ++by)
        for (bx = 0; bx < nbx; ++bx)
            for (c = 0; c < nc; ++c) {
                double s = 0;
                long k = 0;
                for (y = by * B; y < (by + 1) * B && y < img->height; ++y)
                    for (x = bx * B; x < (bx + 1) * B && x < img->width; ++x, ++k)
                        s += img->data[((size_t)y * (size_t)img->width + (size_t)x) * (size_t)img->channels + (size_t)c];
                out[n++] = s / (double)k;
            }
    for (c = 0; c < nc; ++c) {
        double s = 0;
        size_t i, np = (size_t)img->width * (size_t)img->height;
        for (i = 0; i < np; ++i) s += img->data[i * (size_t)img->channels + (size_t)c];
        out[n++] = s / (double)np;
    }
    /* the central box, [w/4, 3w/4) x [h/6, 5h/6): where the golden scenes'
     * sphere is, so that its mean averages the blotches over the object */
    for (c = 0; c < nc; ++c) {
        double s = 0;
        long k = 0;
        for (y = img->height / 6; y < 5 * img->height / 6; ++y)
            for (x = img->width / 4; x < 3 * img->width / 4; ++x, ++k)
                s += img->data[((size_t)y * (size_t)img->width + (size_t)x) * (size_t)img->channels + (size_t)c];
        out[n++] = k ? s / (double)k : 0;
    }
    return n;
}

#endif
