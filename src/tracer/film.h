/*
 * Internal: pbrt-v2's ImageFilm (film/image.cpp) -- the crop window, the
 * sample extent, filtered accumulation and the final normalization -- with
 * accumulators in double and per-pixel statistics for the variance of each
 * pixel's value.
 *
 * A sample at raster position (ix, iy) adds to every pixel (x, y) with
 * ceil(ix - 0.5 - xwidth) <= x <= floor(ix - 0.5 + xwidth) (likewise y),
 * weight filter(x - (ix - 0.5), y - (iy - 0.5)), as pbrt-v2's AddSample.
 * The renderer accumulates each tile into a buffer of its own covering the
 * pixels the tile's samples reach, and merges the buffers into the image in
 * tile order, so that the sums do not depend on the thread schedule.
 */
#ifndef MT_TRACER_FILM_H
#define MT_TRACER_FILM_H

#include "materia/image.h"
#include "materia/rgb.h"
#include "tracer/filter.h"

typedef struct mt__film {
    int xres, yres;
    int x0, y0, width, height; /* the crop window in pixels (pbrt-v2's xPixelStart, ...) */
    mt__filter filter;
    int sx0, sx1, sy0, sy1;    /* pixels whose samples reach the crop window: [sx0, sx1) */
} mt__film;

/* Filter-weighted sums of one pixel: W = sum w, W2 = sum w^2, and per
 * channel sum w L, sum w^2 L, sum w^2 L^2. */
typedef struct mt__pixel_acc {
    double w, w2;
    double wl[3], w2l[3], w2l2[3];
} mt__pixel_acc;

/* The pixels [x0, x0 + w) x [y0, y0 + h) of the image. */
typedef struct mt__film_buf {
    int x0, y0, w, h;
    /* the sums of w^2 terms (W2, w^2 L, w^2 L^2) kept: only the variance
     * reads them (1 after mt__film_buf_alloc) */
    int second_moments;
    size_t cap; /* pixels allocated */
    mt__pixel_acc *px;
} mt__film_buf;

/* pbrt-v2's crop window (clamped to [0, 1], each pair ordered) in pixels,
 * and the sample extent for the filter. */
void mt__film_init(mt__film *f, int xres, int yres, const mt_real crop[4],
                   const mt__filter *filter);

/* The largest buffer a tile of tile x tile sample pixels needs. */
size_t mt__film_tile_pixels(const mt__film *f, int tile);
/* Points b at the pixels the sample pixels [sx0, sx1) x [sy0, sy1) reach
 * (within the crop window) and clears them; b->cap must suffice. */
void mt__film_buf_cover(const mt__film *f, mt__film_buf *b, int sx0, int sx1, int sy0, int sy1);
mt_status mt__film_buf_alloc(mt__film_buf *b, size_t pixels, mt_error *err);
void mt__film_buf_free(mt__film_buf *b);

/* AddSample: the radiance L of the sample at (ix, iy) into b. */
void mt__film_add(const mt__film *f, mt__film_buf *b, mt_real ix, mt_real iy, mt_rgb L);
/* Adds src into dst (dst covers src). */
void mt__film_buf_merge(mt__film_buf *dst, const mt__film_buf *src);

/* The image (sum w L / sum w, negatives clamped to 0 as pbrt-v2's
 * WriteImage) and, when var is not NULL, the variance of each value:
 * sum w^2 (L - m)^2 / W^2 with the unbiasing factor n / (n - 1) for the
 * effective count n = W^2 / W2 (0 where fewer than two samples). b covers the
 * whole crop window. */
mt_status mt__film_develop(const mt__film *f, const mt__film_buf *b, mt_image *img,
                           mt_image *var, mt_error *err);

#endif
