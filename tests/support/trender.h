/*
 * Rendering helpers for the renderer's tests and benchmarks: scenes from
 * text, renders at a chosen sample count and thread count, and image
 * statistics (the mean over a region and its standard error from the
 * per-pixel variance image).
 *
 * The helpers are static inline: every file in tests/support is linked into
 * every test, and a function there would pull the whole renderer into tests
 * that define stand-ins for parts of the library (test_state).
 */
#ifndef MT_TEST_TRENDER_H
#define MT_TEST_TRENDER_H

#include <math.h>
#include <string.h>
#include "materia/render.h"
#include "support/check.h"

static inline void t__count_warning(void *ctx, const char *file, int line, const char *msg)
{
    (void)file;
    (void)line;
    (void)msg;
    if (ctx) ++*(int *)ctx;
}

/* The scene in text (dir resolves file names; may be NULL); warnings are
 * counted in *nwarn when not NULL. NULL with err on failure. */
static inline mt_scene *t_scene(const char *text, const char *dir, int *nwarn, mt_error *err)
{
    mt_render_options o;
    mt_render_options_default(&o);
    if (nwarn) *nwarn = 0;
    o.warn = t__count_warning;
    o.warn_ctx = nwarn;
    return mt_scene_load_string(text, "<test>", dir, &o, err);
}

/* t_scene, or NULL after a FAIL line naming the check and the error. */
static inline mt_scene *t_scene_or_fail(const char *check, const char *text)
{
    mt_error err;
    mt_scene *s = t_scene(text, NULL, NULL, &err);
    if (!s) {
        char buf[1024];
        t_fail(check, "scene: %s", mt_error_format(&err, buf, sizeof buf));
    }
    return s;
}

/* Renders s with spp samples (0: the scene's), threads (0: all), seed; the
 * variance goes to var when not NULL. */
static inline mt_status t_render(const mt_scene *s, int spp, int threads, uint64_t seed,
                                 mt_image *img, mt_image *var, mt_error *err)
{
    mt_render_options o;
    mt_render_options_default(&o);
    o.spp = spp;
    o.threads = threads;
    o.seed = seed;
    return mt_scene_render(s, &o, img, var, NULL, err);
}

/* Over the pixels [x0, x1) x [y0, y1): the mean of channel c and the
 * standard error of that mean (the square root of the summed per-pixel
 * variances divided by the pixel count). */
static inline void t_region_stats(const mt_image *img, const mt_image *var, int x0, int y0,
                                  int x1, int y1, int c, double *mean, double *se)
{
    double sum = 0, vsum = 0;
    long n = 0;
    int x, y;
    for (y = y0; y < y1; ++y)
        for (x = x0; x < x1; ++x) {
            size_t i = ((size_t)y * (size_t)img->width + (size_t)x) * (size_t)img->channels + (size_t)c;
            sum += img->data[i];
            if (var) vsum += var->data[i];
            ++n;
        }
    *mean = n ? sum / (double)n : 0;
    *se = n ? sqrt(vsum) / (double)n : 0;
}

/* 1 when the two images have the same size and bit-identical pixels. */
static inline int t_images_identical(const mt_image *a, const mt_image *b)
{
    return a->width == b->width && a->height == b->height && a->channels == b->channels &&
           memcmp(a->data, b->data,
                  (size_t)a->width * (size_t)a->height * (size_t)a->channels * sizeof(float)) == 0;
}

#endif
