/*
 * Rendering helpers for the renderer's tests and benchmarks: scenes from
 * text, renders at a chosen sample count and thread count, and image
 * statistics (the mean over a region and its standard error from the
 * per-pixel variance image).
 */
#ifndef MT_TEST_TRENDER_H
#define MT_TEST_TRENDER_H

#include "materia/render.h"

/* The scene in text (dir resolves file names; may be NULL); warnings are
 * counted in *nwarn when not NULL. NULL with err on failure. */
mt_scene *t_scene(const char *text, const char *dir, int *nwarn, mt_error *err);

/* Renders s with spp samples (0: the scene's), threads (0: all), seed; the
 * variance goes to var when not NULL. Returns the status. */
mt_status t_render(const mt_scene *s, int spp, int threads, uint64_t seed, mt_image *img,
                   mt_image *var, mt_error *err);

/* Over the pixels [x0, x1) x [y0, y1): the mean of channel c and the
 * standard error of that mean (the square root of the summed per-pixel
 * variances divided by the pixel count). */
void t_region_stats(const mt_image *img, const mt_image *var, int x0, int y0, int x1, int y1,
                    int c, double *mean, double *se);

/* 1 when the two images have the same size and bit-identical pixels. */
int t_images_identical(const mt_image *a, const mt_image *b);

#endif
