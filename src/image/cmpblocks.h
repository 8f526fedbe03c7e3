/*
 * Internal to the image comparisons (imgcmp.c, ztest.c): checking that two
 * images can be compared, and block means over a grid whose right and bottom
 * blocks are narrower when the image side is not a multiple of the block.
 */
#ifndef MT_IMAGE_CMPBLOCKS_H
#define MT_IMAGE_CMPBLOCKS_H

#include "materia/image.h"

typedef struct mt__grid {
    int width, height; /* the image */
    int block;         /* block side in pixels */
    int bx, by;        /* blocks across and down: ceil(width / block), ... */
    int nc;            /* colour channels compared: 1 or 3 */
} mt__grid;

/* Colour channels compared: 1 for a one-channel image, 3 otherwise. */
int mt__cmp_channels(const mt_image *img);

/* Checks that `img` (called `name` in messages) is a valid image of the
 * grid's size and colour channels with finite values, non-negative when
 * nonneg is set (variances). */
mt_status mt__cmp_check(const mt_image *img, const char *name, const mt__grid *g, int nonneg,
                        mt_error *err);

/* Sets up the grid of a against b, checks both (names "a", "b" in messages)
 * and the block size. */
mt_status mt__cmp_pair(const mt_image *a, const mt_image *b, int block, mt__grid *g,
                       mt_error *err);

/* The number of pixels in block (i, j). */
int mt__block_pixels(const mt__grid *g, int i, int j);

/* Block means of the colour channels of img, as a new array of
 * bx * by * nc doubles ((j * bx + i) * nc + c); NULL when out of memory. */
double *mt__block_means(const mt_image *img, const mt__grid *g, mt_error *err);

/* |a - b| / (|b| + 0.01): pbrt-v2's relative difference of two block means. */
double mt__reldiff(double a, double b);

/* A new image of bx x by pixels and nc channels holding v (as float). */
mt_status mt__blocks_image(const double *v, const mt__grid *g, mt_image *out, mt_error *err);

#endif
