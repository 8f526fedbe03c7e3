/*
 * materia/tools/imgcmp.h -- comparing a render with a reference image.
 *
 * Three comparisons, for the golden-image tests and the comparison with
 * pbrt-v2's own renders (docs/RENDERER.md, "Comparing images"):
 *
 *  - pbrt-v2's noise metric (../shared/reference/pbrt-v2/noise.txt): 4x4
 *    block means, |a - b| / (b + 0.01) per block and channel, its mean, 99th
 *    percentile and maximum over the image, and the luminance ratio
 *    mean(y(a)) / mean(y(b)). Two pbrt-v2 renders of one scene at 1024
 *    samples per pixel differ by the figures of noise.txt.
 *  - Per-pixel errors: RMSE, relative MSE, the largest difference.
 *  - A statistical test against a golden mean and variance, after Mitsuba 3's
 *    render tests: a z-test per block and channel with the Sidak correction,
 *    so that an honest render passes with probability 1 - alpha whatever the
 *    image size, and a bias larger than the noise fails.
 *
 * Plus an accumulator that turns samples (or independent images) into a mean
 * image and its variance-of-the-mean image, and a false-colour heat map.
 *
 * Conventions. "a" is the image under test, "b" the reference (the relative
 * difference divides by b). Only colour channels are compared: one for a
 * one-channel image, R, G, B otherwise (the alpha of an RGBA file, as pbrt-v2
 * writes its EXRs, is ignored), so an RGBA EXR compares with an RGB PFM.
 * Both images must have the same size and both one or both three or more
 * channels. A NaN or infinity in an input is an error naming the pixel (a
 * comparison with it means nothing). Statistics are computed in double
 * whatever mt_real is: they describe float images and must not depend on the
 * build. Blocks: an image whose side is not a multiple of the block size has
 * narrower blocks along its right and bottom edges, each the mean of the
 * pixels it holds (every pixel counts once); pbrt-v2's 160x120 renders have
 * no partial 4x4 block.
 *
 * Thread safety: the comparison functions may run in any number of threads
 * at once; an accumulator (mt_imgacc) belongs to one thread at a time.
 */
#ifndef MATERIA_TOOLS_IMGCMP_H
#define MATERIA_TOOLS_IMGCMP_H

#include "materia/error.h"
#include "materia/image.h"

#ifdef __cplusplus
extern "C" {
#endif

/* pbrt-v2's block metric with its default block size and offset. */
#define MT_IMGCMP_BLOCK 4
#define MT_IMGCMP_OFFSET 0.01

/* The 100 q-th percentile (q in [0, 1]) of n values, with linear interpolation
 * between the closest ranks (numpy's default, Hyndman and Fan's definition
 * 7): with the values sorted ascending x[0..n-1], h = (n - 1) q, the result
 * is x[floor h] + (h - floor h) (x[floor h + 1] - x[floor h]). Sorts v in
 * place. n = 0 gives 0. */
MT_API double mt_imgcmp_percentile(double *v, size_t n, double q);

/* pbrt-v2's noise metric. */
typedef struct mt_noise_metric {
    double mean, p99, max; /* of |a - b| / (|b| + 0.01) over blocks and channels */
    double y_a, y_b;       /* mean luminance (pbrt-v2's y weights, mt_rgb_y) */
    double lum_ratio;      /* y_a / y_b; 1 when both are 0, 0 when only y_b is */
    int blocks_x, blocks_y, channels; /* the block grid; values = their product */
} mt_noise_metric;

/* Block means of side `block` (MT_IMGCMP_BLOCK for pbrt-v2's figures) of a
 * and b; per block and colour channel r = |a - b| / (|b| + 0.01) (b is a
 * render, never negative; |b| keeps the denominator positive for images that
 * are); the mean, the 99th percentile (mt_imgcmp_percentile) and the maximum
 * of r; the luminance ratio over the whole image. */
MT_API mt_status mt_imgcmp_noise(const mt_image *a, const mt_image *b, int block,
                                 mt_noise_metric *out, mt_error *err);

/* Per-pixel errors over all pixels and colour channels. */
typedef struct mt_pixel_errors {
    double rmse;       /* sqrt(mean (a - b)^2) */
    double relmse;     /* mean (a - b)^2 / (b^2 + 0.01) (Rousselle et al. 2011) */
    double max_abs;    /* max |a - b| */
    int max_x, max_y, max_c; /* where it is (the first such value in reading order) */
} mt_pixel_errors;

/* The errors above, over every pixel and colour channel of a and b. */
MT_API mt_status mt_imgcmp_pixel_errors(const mt_image *a, const mt_image *b,
                                        mt_pixel_errors *out, mt_error *err);

/* Per block and colour channel |a - b| / (|b| + 0.01), as an image of
 * blocks_x x blocks_y pixels (one per block) with one or three channels:
 * the values pbrt-v2's metric summarizes, for a heat map. *map is allocated
 * (free it with mt_image_destroy). */
MT_API mt_status mt_imgcmp_reldiff_blocks(const mt_image *a, const mt_image *b, int block,
                                          mt_image *map, mt_error *err);

/* ---- the statistical test ------------------------------------------------ */

typedef struct mt_ztest_options {
    int block;      /* block side in pixels, 1 = per pixel (default 4) */
    double alpha;   /* family-wise significance (default 0.01) */
    double exact_rel; /* zero-variance blocks: equal within this fraction of
                         max(|a|, |b|) (default 1e-4; 0 asks for equality) */
} mt_ztest_options;

/* The defaults above. */
MT_API mt_ztest_options mt_ztest_defaults(void);

typedef struct mt_ztest_result {
    int pass;            /* min_p > threshold, every |bias_z| < bias_z_threshold
                            and no exact mismatch */
    long tests;          /* m: block-channel pairs with a variance, each a z-test */
    long exact;          /* block-channel pairs without sampling noise (see below) */
    long exact_mismatch; /* of these, the pairs whose means differ (see above) */
    double threshold;    /* Sidak: 1 - (1 - alpha)^(1/m); alpha when m = 0 */
    double z_threshold;  /* |z| at which p = threshold */
    double min_p;        /* the smallest two-sided p-value, 1 when m = 0 */
    double max_abs_z;    /* the largest |z| of the tests, at block (max_bx, max_by), */
    int max_bx, max_by, max_c; /*   channel max_c (all -1 when m = 0) */
    long beyond;         /* tests with p <= threshold */
    double mean_rel;     /* mean |a - b| / (|b| + 0.01) over all block-channel pairs */
    double bias_z[3];    /* per channel (1 or 3): the sum of its tests' z over sqrt(their count) */
    double bias_z_threshold; /* |bias_z| at which the global test fails */
    int bias_c;          /* the channel of the largest |bias_z| (-1 when m = 0) */
    int blocks_x, blocks_y, channels;
} mt_ztest_result;

/* Tests whether a (the mean of a render's samples per pixel) and b (the
 * golden mean) have the same expectation, given var_a and var_b: per pixel
 * and channel, the variance of each image's mean (the sample variance
 * divided by the sample count: mt_imgacc_finish gives it). Either variance
 * may be NULL (known exactly: zero). Variance images have the size and
 * colour channels of a.
 *
 * Per block (side opt->block) and colour channel: the block means ma, mb,
 * the variances of the block means va, vb (the pixel variances summed over
 * the block's n pixels and divided by n^2: pixels are independent), and
 * z = (ma - mb) / sqrt(va + vb), two-sided p = erfc(|z| / sqrt 2). Two
 * tests share the significance alpha, half each:
 * - local: with m tests, the image passes when the smallest p exceeds the
 *   Sidak threshold 1 - (1 - alpha/2)^(1/m). It finds an error confined to
 *   a region (a wrong highlight, a leak at an edge).
 * - global: per channel, bias_z = (sum of its z) / sqrt(its count), N(0, 1)
 *   for an unbiased render; the image passes when every |bias_z| is below
 *   the Sidak threshold over the channels at alpha/2. It finds a small error
 *   spread over the whole image (a colour 5% off) that no block shows alone:
 *   the z of 484 blocks each shifted by 0.5 sum to a bias_z of 11.
 * An unbiased render fails with probability at most alpha (when the tests
 * are independent -- R, G and B of one block are usually positively
 * correlated, which makes the test conservative -- and the block means
 * nearly normal: a few hundred samples per block). With variances
 * estimated from few samples z is really a t statistic, with heavier tails:
 * at 16 samples per pixel and 4x4 blocks the measured false-alarm rate is
 * 1.2% for alpha = 1% (5000 trials of tests/test_imgcmp.c's scene).
 *
 * A block-channel pair with va + vb = 0, or with sqrt(va + vb) at most
 * 1e-6 max(|ma|, |mb|) (pure background, or a sky seen in a mirror: every
 * sample identical, the variance only float rounding), is not a z-test: the means must be equal within exact_rel * max(|ma|, |mb|) --
 * float accumulation of identical samples drifts by less than 1e-4 over
 * 2^12 samples -- and a mismatch fails the image whatever the p-values.
 * Such pairs are not counted in m.
 *
 * zmap, when not NULL, receives the z of every pair as a blocks_x x
 * blocks_y image with one or three channels: 0 for a matching exact pair,
 * +-FLT_MAX for a mismatched one. opt NULL means the defaults. */
MT_API mt_status mt_imgcmp_ztest(const mt_image *a, const mt_image *var_a, const mt_image *b,
                                 const mt_image *var_b, const mt_ztest_options *opt,
                                 mt_ztest_result *out, mt_image *zmap, mt_error *err);

/* ---- means and variances from samples ------------------------------------- */

/* Per pixel and channel, the running mean and sum of squared deviations of
 * the samples added (Welford's update, in double: identical samples give a
 * variance of exactly 0, which the z-test's exact rule relies on). */
typedef struct mt_imgacc mt_imgacc;

/* An accumulator for width x height images of 1, 3 or 4 channels, with no
 * sample yet; NULL with err filled for a bad size or MT_ERR_NOMEM.
 * mt_imgacc_destroy frees it. */
MT_API mt_imgacc *mt_imgacc_create(int width, int height, int channels, mt_error *err);
MT_API void mt_imgacc_destroy(mt_imgacc *acc);
/* One sample of pixel (x, y): channels values. Out-of-range pixels are
 * ignored. */
MT_API void mt_imgacc_add(mt_imgacc *acc, int x, int y, const float *v);
/* One independent estimate of every pixel (for example a whole render with
 * its own seed): img must have the accumulator's size and channels. */
MT_API mt_status mt_imgacc_add_image(mt_imgacc *acc, const mt_image *img, mt_error *err);
/* The mean image and the variance of the mean, s^2 / n with the unbiased
 * sample variance s^2, as new images (mt_image_destroy); either output may
 * be NULL. Every pixel needs two samples or more (MT_ERR_INVALID naming the
 * first that has fewer). */
MT_API mt_status mt_imgacc_finish(const mt_imgacc *acc, mt_image *mean, mt_image *var_of_mean,
                                  mt_error *err);

/* ---- heat map ------------------------------------------------------------- */

/* A false-colour picture of a block map (mt_imgcmp_reldiff_blocks or the
 * z-test's zmap): every pixel of a width x height image takes the largest
 * |value| over the channels of its block (side `block`), mapped through an
 * inferno-like scale from black (0) through purple, red and orange to pale
 * yellow (vmax and above). When bar is non-zero a colour bar labelled 0 and
 * vmax is added under the picture. *out is a new RGB image in linear values
 * (mt_image_write makes the PNG sRGB). */
MT_API mt_status mt_imgcmp_heatmap(const mt_image *blocks, int block, int width, int height,
                                   double vmax, int bar, mt_image *out, mt_error *err);

#ifdef __cplusplus
}
#endif

#endif
