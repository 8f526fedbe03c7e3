/*
 * Image comparison: pbrt-v2's noise metric on images with hand-computed
 * answers (partial border blocks, zero pixels, the +0.01) and on Gaussian
 * noise with a closed-form answer; the percentile definition; per-pixel
 * errors; the sample accumulator; the z-test on hand values, on 200 pairs of
 * independent noisy "renders" of one synthetic scene (false alarms at the
 * stated rate, z calibrated), against a +2% bias in a region and with
 * zero-variance background; errors and allocation failures. Where
 * ../shared exists, pbrt-v2's own renders.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "materia/tools/imgcmp.h"
#include "support/check.h"
#include "support/kinds.h"
#include "support/timage.h"

/* ---- helpers ---------------------------------------------------------- */

/* A standard normal deviate (Box-Muller; u1 in (0, 1]). */
static double gauss(mt_rng *r)
{
    double u1 = 1 - mt_rng_uniform_d(r), u2 = mt_rng_uniform_d(r);
    return sqrt(-2 * log(u1)) * cos(2 * 3.14159265358979323846 * u2);
}

/* ---- the percentile ---------------------------------------------------- */

static void test_percentile(void)
{
    double four[4] = {3, 1, 4, 2}, five[5] = {50, 10, 40, 20, 30}, one[1] = {7};
    double hundred[101];
    int i;
    t_near(mt_imgcmp_percentile(four, 4, 0.5), 2.5, 1e-15, "percentile: median of 1..4 is 2.5");
    t_near(mt_imgcmp_percentile(four, 4, 0), 1, 0, "percentile: q = 0 is the minimum");
    t_near(mt_imgcmp_percentile(four, 4, 1), 4, 0, "percentile: q = 1 is the maximum");
    /* h = 4 * 0.99 = 3.96: 40 + 0.96 * 10 (nearest rank would say 50) */
    t_near(mt_imgcmp_percentile(five, 5, 0.99), 49.6, 1e-12,
           "percentile: p99 of 10..50 interpolates to 49.6");
    t_near(mt_imgcmp_percentile(one, 1, 0.99), 7, 0, "percentile: one value");
    for (i = 0; i <= 100; ++i) hundred[i] = 100 - i;
    t_near(mt_imgcmp_percentile(hundred, 101, 0.99), 99, 1e-12, "percentile: p99 of 0..100 is 99");
    t_near(mt_imgcmp_percentile(NULL, 0, 0.5), 0, 0, "percentile: no values give 0");
}

/* ---- the noise metric by hand ------------------------------------------ */

/* A 6 x 5 image in blocks of 4: blocks (0,0) 4x4, (1,0) 2x4, (0,1) 4x1, (1,1)
 * 2x1 pixels. Channel by channel:
 *   R: b = 0; a = 0.16 at (0,0) -> block mean 0.01, r = 0.01 / 0.01 = 1; a =
 *      0.06 at (5,4) -> mean of 2 pixels 0.03, r = 3 (a full-block divisor
 *      would give 0.375, dropping partial blocks would lose it).
 *   G: b = 1; a = 1.808 at (4,0) -> mean 1.101, r = 0.101 / 1.01 = 0.1; a =
 *      0.5 on row 4, x < 4 -> r = 0.5 / 1.01.
 *   B: b = 0.3; a = 0.31 on block (0,0) -> r = 0.01 / 0.31.
 * Twelve values, seven zeros: sorted ..., 0.01/0.31, 0.1, 0.5/1.01, 1, 3;
 * p99: h = 11 * 0.99 = 10.89, 1 + 0.89 * (3 - 1) = 2.78. */
static void hand_images(mt_image *a, mt_image *b)
{
    int x, y;
    *a = t_image_make(6, 5, 3, 0);
    *b = t_image_make(6, 5, 3, 0);
    for (y = 0; y < 5; ++y)
        for (x = 0; x < 6; ++x) {
            float *pa = t_image_px(a, x, y), *pb = t_image_px(b, x, y);
            pb[0] = 0, pb[1] = 1, pb[2] = 0.3f;
            pa[0] = 0, pa[1] = 1, pa[2] = 0.3f;
            if (x < 4 && y < 4) pa[2] = 0.31f;
            if (x < 4 && y == 4) pa[1] = 0.5f;
        }
    t_image_px(a, 0, 0)[0] = 0.16f;
    t_image_px(a, 5, 4)[0] = 0.06f;
    t_image_px(a, 4, 0)[1] = 1.808f;
}

static void test_noise_by_hand(void)
{
    mt_image a, b, map;
    mt_noise_metric m;
    mt_error err;
    /* block by block, R G B */
    double r[12] = {1, 0, 0.01 / 0.31, 0, 0.1, 0, 0, 0.5 / 1.01, 0, 3, 0, 0};
    double mean = 0, ya, yb;
    int k, ok;
    hand_images(&a, &b);
    for (k = 0; k < 12; ++k) mean += r[k] / 12;
    ok = mt_imgcmp_noise(&a, &b, 4, &m, &err) == MT_OK;
    t_check(ok && m.blocks_x == 2 && m.blocks_y == 2 && m.channels == 3,
            "noise by hand: 6x5 in blocks of 4 is a 2x2 grid of 3 channels", "%d x %d x %d",
            m.blocks_x, m.blocks_y, m.channels);
    t_near(m.mean, mean, 2e-6, "noise by hand: mean (partial blocks, zero b, the +0.01)");
    t_near(m.max, 3, 2e-6, "noise by hand: max is the 2-pixel corner block");
    t_near(m.p99, 2.78, 5e-6, "noise by hand: p99 interpolated between the two largest");
    ya = 0.212671 * 0.22 / 30 + 0.715160 * 28.808 / 30 + 0.072169 * 9.16 / 30;
    yb = 0.715160 + 0.072169 * 0.3;
    t_near(m.y_a, ya, 2e-6, "noise by hand: mean y of a with pbrt-v2's weights");
    t_near(m.lum_ratio, ya / yb, 2e-6, "noise by hand: luminance ratio");

    /* the block map holds the same twelve values */
    ok = mt_imgcmp_reldiff_blocks(&a, &b, 4, &map, &err) == MT_OK;
    if (ok) {
        double worst = 0;
        for (k = 0; k < 12; ++k) worst = fmax(worst, fabs(map.data[k] - r[k]));
        t_check(map.width == 2 && map.height == 2 && map.channels == 3 && worst < 2e-6,
                "noise by hand: block map values", "off by %g", worst);
        mt_image_destroy(&map);
    } else
        t_fail("noise by hand: block map values", "%s", err.message);

    /* one block bigger than the image: whole-image means */
    ok = mt_imgcmp_noise(&a, &b, 8, &m, &err) == MT_OK;
    t_check(ok && m.blocks_x == 1 && m.blocks_y == 1 &&
                fabs(m.max - (0.22 / 30) / 0.01) < 2e-6,
            "noise by hand: a block larger than the image is the whole image",
            "max %g, want %g", m.max, 0.22 / 30 / 0.01);
    mt_image_destroy(&a);
    mt_image_destroy(&b);
}

/* Images with pixel noise of standard deviation sd around v, independent in
 * a and b: 4x4 block means have sd / 4, their difference sd sqrt(2) / 4, and
 * |d| is half-normal: mean sd sqrt(2) / 4 * sqrt(2 / pi), 99th percentile
 * times 2.5758293 (the two-sided 1% point). Divided by v + 0.01 (the
 * denominator's own noise, 1% of v here, changes it by ~1e-4). */
static void test_noise_gaussian(void)
{
    const int w = 256, h = 256;
    const double v = 0.5, sd = 0.02, s = sd * sqrt(2.0) / 4 / (v + 0.01);
    mt_image a = t_image_make(w, h, 3, 0), b = t_image_make(w, h, 3, 0);
    mt_noise_metric m;
    mt_rng rng;
    size_t k;
    mt_rng_seed(&rng, 5, 1);
    for (k = 0; k < (size_t)w * h * 3; ++k) {
        a.data[k] = (float)(v + sd * gauss(&rng));
        b.data[k] = (float)(v + sd * gauss(&rng));
    }
    if (mt_imgcmp_noise(&a, &b, 4, &m, NULL) != MT_OK) {
        t_fail("noise of gaussian images", "failed");
        return;
    }
    /* 12288 values: the mean has a relative sd of 0.68%, the p99 of 1.2% */
    t_rel(m.mean, s * sqrt(2 / 3.14159265358979323846), 0.03, 0,
          "noise of gaussian images: mean is the half-normal mean of a block difference");
    t_rel(m.p99, s * 2.5758293035489, 0.05, 0,
          "noise of gaussian images: p99 is the half-normal 99% point");
    t_rel(m.lum_ratio, 1, 2e-4, 0, "noise of gaussian images: luminance ratio 1");
    mt_image_destroy(&a);
    mt_image_destroy(&b);
}

/* ---- per-pixel errors --------------------------------------------------- */

static void test_pixel_errors(void)
{
    mt_image a = t_image_make(2, 1, 1, 0), b = t_image_make(2, 1, 1, 0);
    mt_pixel_errors e;
    /* d = 0.5 over b = 0 and d = -2 over b = 3 (the first largest |d|) */
    a.data[0] = 0.5f, b.data[0] = 0;
    a.data[1] = 1, b.data[1] = 3;
    if (mt_imgcmp_pixel_errors(&a, &b, &e, NULL) != MT_OK) {
        t_fail("pixel errors", "failed");
        return;
    }
    t_near(e.rmse, sqrt((0.25 + 4) / 2), 1e-12, "pixel errors: rmse");
    t_near(e.relmse, (0.25 / 0.01 + 4 / 9.01) / 2, 1e-9, "pixel errors: relmse over b^2 + 0.01");
    t_check(e.max_abs == 2 && e.max_x == 1 && e.max_y == 0 && e.max_c == 0,
            "pixel errors: largest difference and where", "%g at (%d, %d) %d", e.max_abs,
            e.max_x, e.max_y, e.max_c);
    mt_image_destroy(&a);
    mt_image_destroy(&b);
}

/* ---- what cannot be compared -------------------------------------------- */

static int fails_with(mt_status got, const mt_error *err, const char *words, const char *name)
{
    return t_check(got == MT_ERR_INVALID && strstr(err->message, words) != NULL, name,
                   "status %d, message \"%s\"", (int)got, err->message);
}

static void test_errors(void)
{
    mt_image a = t_image_make(8, 8, 3, 0.5f), b = t_image_make(8, 6, 3, 0.5f), y = t_image_make(8, 8, 1, 0.5f);
    mt_image rgba = t_image_make(8, 8, 4, 0.5f), var = t_image_make(8, 8, 3, 0.01f);
    mt_noise_metric m;
    mt_ztest_result z;
    mt_error err;
    fails_with(mt_imgcmp_noise(&a, &b, 4, &m, &err), &err, "size mismatch",
               "errors: size mismatch");
    fails_with(mt_imgcmp_noise(&a, &y, 4, &m, &err), &err, "channel mismatch",
               "errors: one channel against three");
    fails_with(mt_imgcmp_noise(&a, &a, 0, &m, &err), &err, "block size", "errors: block size 0");
    /* RGBA against RGB: alpha is not compared */
    t_image_px(&rgba, 3, 3)[3] = 0;
    t_check(mt_imgcmp_noise(&rgba, &a, 4, &m, &err) == MT_OK && m.max == 0,
            "errors: RGBA compares with RGB, alpha ignored", "%s", err.message);
    t_image_px(&a, 5, 2)[1] = NAN;
    fails_with(mt_imgcmp_noise(&a, &rgba, 4, &m, &err), &err, "non-finite value at pixel (5, 2)",
               "errors: a NaN is named by pixel");
    t_image_px(&a, 5, 2)[1] = 0.5f;
    t_image_px(&var, 1, 7)[2] = -1e-6f;
    fails_with(mt_imgcmp_ztest(&a, &var, &rgba, NULL, NULL, &z, NULL, &err), &err,
               "negative variance", "errors: a negative variance");
    t_image_px(&var, 1, 7)[2] = 0;
    {
        mt_ztest_options o = mt_ztest_defaults();
        o.alpha = 1;
        fails_with(mt_imgcmp_ztest(&a, &var, &a, NULL, &o, &z, NULL, &err), &err, "significance",
                   "errors: alpha 1");
    }
    mt_image_destroy(&a);
    mt_image_destroy(&b);
    mt_image_destroy(&y);
    mt_image_destroy(&rgba);
    mt_image_destroy(&var);
}

/* ---- the accumulator --------------------------------------------------- */

static void test_accumulator(void)
{
    mt_error err;
    mt_imgacc *acc = mt_imgacc_create(2, 1, 1, &err);
    mt_image mean, var, wrong = t_image_make(3, 1, 1, 0);
    float s;
    int i;
    if (!acc) {
        t_fail("accumulator", "%s", err.message);
        return;
    }
    for (i = 1; i <= 4; ++i) {
        s = (float)i;
        mt_imgacc_add(acc, 0, 0, &s); /* 1 2 3 4: mean 2.5, s^2 5/3, var of mean 5/12 */
        s = 0.1f;
        mt_imgacc_add(acc, 1, 0, &s); /* identical: variance exactly 0 */
    }
    mt_imgacc_add(acc, 2, 0, &s); /* outside: ignored */
    if (mt_imgacc_finish(acc, &mean, &var, &err) == MT_OK) {
        t_near(mean.data[0], 2.5, 0, "accumulator: mean");
        t_near(var.data[0], 5.0 / 12, 1e-7, "accumulator: variance of the mean, s^2 / n");
        t_check(mean.data[1] == 0.1f && var.data[1] == 0,
                "accumulator: identical samples give their value and variance exactly 0",
                "%.9g %.9g", mean.data[1], var.data[1]);
        mt_image_destroy(&mean);
        mt_image_destroy(&var);
    } else
        t_fail("accumulator: mean", "%s", err.message);
    fails_with(mt_imgacc_add_image(acc, &wrong, &err), &err, "added to an accumulator",
               "accumulator: an image of another size");
    mt_imgacc_destroy(acc);
    acc = mt_imgacc_create(2, 1, 1, &err);
    s = 1;
    mt_imgacc_add(acc, 0, 0, &s);
    mt_imgacc_add(acc, 0, 0, &s);
    mt_imgacc_add(acc, 1, 0, &s);
    fails_with(mt_imgacc_finish(acc, &mean, NULL, &err), &err, "pixel (1, 0) has 1 sample",
               "accumulator: one sample is not enough for a variance");
    mt_imgacc_destroy(acc);
    mt_image_destroy(&wrong);
}

/* ---- the z-test by hand ------------------------------------------------- */

/* One 4x4 block: a = 1, b = 1 - d, var_a = 0.0016 per pixel, var_b = 0:
 * the block mean's variance is 16 * 0.0016 / 16^2 = 1e-4, z = d / 0.01.
 * Three channels: m = 3, threshold 1 - 0.995^(1/3) = 0.00166945 (half of
 * alpha = 0.01 goes to the local tests), |z| 3.1434916 (bisection in
 * Python's math.erfc); the global test has the same threshold (3 channels
 * at alpha / 2) and one z per channel: bias_z = z. */
static void test_ztest_by_hand(void)
{
    mt_image a = t_image_make(4, 4, 3, 1), b = t_image_make(4, 4, 3, 0.9f), va = t_image_make(4, 4, 3, 0.0016f), zmap;
    mt_ztest_result r;
    mt_error err;
    double thr = 1 - pow(0.995, 1.0 / 3);
    int ok = mt_imgcmp_ztest(&a, &va, &b, NULL, NULL, &r, &zmap, &err) == MT_OK;
    t_check(ok && r.tests == 3 && r.exact == 0 && !r.pass && r.beyond == 3,
            "z-test by hand: d = 0.1 is z = 10, three tests fail", "%s tests %ld beyond %ld",
            ok ? "" : err.message, r.tests, r.beyond);
    if (ok) {
        t_near(zmap.data[0], 10, 1e-4, "z-test by hand: the z map holds z = 10");
        t_near(r.max_abs_z, 10, 1e-4, "z-test by hand: max |z|");
        mt_image_destroy(&zmap);
    }
    t_near(r.threshold, thr, 1e-12, "z-test by hand: Sidak threshold for m = 3");
    t_near(r.z_threshold, 3.1434916, 1e-6, "z-test by hand: |z| at the threshold");
    t_near(r.bias_z_threshold, 3.1434916, 1e-6, "z-test by hand: |bias z| at the threshold");
    t_near(r.bias_z[1], 10, 1e-4, "z-test by hand: one block: bias z = z");
    t_near(r.mean_rel, 0.1 / 0.91, 1e-6, "z-test by hand: mean relative difference");
    mt_image_destroy(&b);
    b = t_image_make(4, 4, 3, 0.98f);
    ok = mt_imgcmp_ztest(&a, &va, &b, NULL, NULL, &r, NULL, &err) == MT_OK;
    t_check(ok && r.pass, "z-test by hand: d = 0.02 (z = 2) passes", "min p %g", r.min_p);
    t_near(r.min_p, erfc(2 / sqrt(2.0)), 1e-5, "z-test by hand: min p = erfc(2 / sqrt 2)");
    /* rounding-level variance (a sky in a mirror: identical samples, float
     * accumulation; sd below 1e-6 of the mean): deterministic, compared
     * within exact_rel = 1e-4 */
    {
        mt_image a3 = t_image_make(4, 4, 3, 0.32f), b3 = t_image_make(4, 4, 3, 0.32000002f),
                 v3 = t_image_make(4, 4, 3, 1e-18f), c3 = t_image_make(4, 4, 3, 0.3201f);
        ok = mt_imgcmp_ztest(&a3, &v3, &b3, &v3, NULL, &r, NULL, &err) == MT_OK;
        t_check(ok && r.pass && r.exact == 3 && r.tests == 0,
                "z-test by hand: a rounding-level variance is no z-test (1 ulp apart passes)",
                "pass %d exact %ld tests %ld max z %g", r.pass, r.exact, r.tests, r.max_abs_z);
        ok = mt_imgcmp_ztest(&a3, &v3, &c3, &v3, NULL, &r, NULL, &err) == MT_OK;
        t_check(ok && !r.pass && r.exact_mismatch == 3,
                "z-test by hand: a rounding-level variance with means 3e-4 apart fails as a mismatch",
                "pass %d mismatches %ld", r.pass, r.exact_mismatch);
        mt_image_destroy(&a3);
        mt_image_destroy(&b3);
        mt_image_destroy(&v3);
        mt_image_destroy(&c3);
    }
    /* a small but real noise, sd 9e-5 of the mean (below exact_rel, above
     * rounding), means 1.5 sd apart: a z-test that passes (z = 1.5), not an
     * equality within exact_rel that would fail */
    {
        mt_ztest_options o = mt_ztest_defaults();
        mt_image a4 = t_image_make(1, 1, 3, 0.32f), b4 = t_image_make(1, 1, 3, 0.32f + 4.32e-5f),
                 v4 = t_image_make(1, 1, 3, 4.1472e-10f);
        o.block = 1;
        ok = mt_imgcmp_ztest(&a4, &v4, &b4, &v4, &o, &r, NULL, &err) == MT_OK;
        t_check(ok && r.pass && r.exact == 0 && r.tests == 3 && fabs(r.max_abs_z - 1.5) < 0.01,
                "z-test by hand: a noise of 9e-5 of the mean is z-tested, not compared exactly",
                "pass %d exact %ld tests %ld max z %g", r.pass, r.exact, r.tests, r.max_abs_z);
        mt_image_destroy(&a4);
        mt_image_destroy(&b4);
        mt_image_destroy(&v4);
    }
    /* 64 blocks of z = 1: no block is beyond 3.7 (Sidak over 192 tests) but
     * the global test sums them: bias_z = 64 / sqrt 64 = 8 */
    {
        mt_image a2 = t_image_make(32, 32, 3, 1), b2 = t_image_make(32, 32, 3, 0.99f),
                 v2 = t_image_make(32, 32, 3, 0.0016f);
        ok = mt_imgcmp_ztest(&a2, &v2, &b2, NULL, NULL, &r, NULL, &err) == MT_OK;
        t_check(ok && !r.pass && r.beyond == 0 && r.tests == 192 && fabs(r.bias_z[2] - 8) < 1e-3 &&
                    fabs(r.max_abs_z - 1) < 1e-3,
                "z-test by hand: a 1% bias everywhere is found by the global test alone",
                "pass %d, beyond %ld, tests %ld, bias z %g, max z %g", r.pass, r.beyond, r.tests,
                r.bias_z[2], r.max_abs_z);
        mt_image_destroy(&a2);
        mt_image_destroy(&b2);
        mt_image_destroy(&v2);
    }
    /* per pixel: each pixel's variance 0.0016, z = 0.02 / 0.04 = 0.5 */
    {
        mt_ztest_options o = mt_ztest_defaults();
        o.block = 1;
        ok = mt_imgcmp_ztest(&a, NULL, &b, &va, &o, &r, NULL, &err) == MT_OK;
        t_check(ok && r.tests == 48 && fabs(r.max_abs_z - 0.5) < 1e-4,
                "z-test by hand: per pixel, variance on the reference side", "%ld tests, max z %g",
                r.tests, r.max_abs_z);
    }
    /* no variance at all: every pair exact, m = 0 */
    ok = mt_imgcmp_ztest(&a, NULL, &a, NULL, NULL, &r, NULL, &err) == MT_OK;
    t_check(ok && r.pass && r.tests == 0 && r.exact == 3 && r.min_p == 1 && r.threshold == 0.01,
            "z-test by hand: equal images without variance are all exact and pass",
            "tests %ld exact %ld", r.tests, r.exact);
    ok = mt_imgcmp_ztest(&a, NULL, &b, NULL, NULL, &r, NULL, &err) == MT_OK;
    t_check(ok && !r.pass && r.exact_mismatch == 3,
            "z-test by hand: unequal images without variance fail as exact mismatches",
            "mismatches %ld", r.exact_mismatch);
    mt_image_destroy(&a);
    mt_image_destroy(&b);
    mt_image_destroy(&va);
}

/* ---- the z-test on synthetic renders -------------------------------------- */

/* A 32x32 "scene": columns x < 4 are background, every sample 0.25 (zero
 * variance); elsewhere the expected value mu = 0.3 + 0.5 x / 31 (times 1, 1.1,
 * 0.9 for R, G, B) and per-sample standard deviation 0.05 in the top half,
 * 0.3 in the bottom half. Samples are uniform on mu +- sqrt(3) sd. */
#define SW 32
#define SH 32

static double scene_mu(int x, int c) { return (0.3 + 0.5 * x / 31.0) * (c == 1 ? 1.1 : c == 2 ? 0.9 : 1); }
static double scene_sd(int x, int y) { return x < 4 ? 0 : y < 16 ? 0.05 : 0.3; }

/* Renders spp samples per pixel; pixels in [bx0, bx1) x [by0, by1) have
 * their expected value times (1 + bias). Returns the mean and its variance. */
static int render(mt_rng *rng, int spp, double bias, int bx0, int bx1, int by0, int by1,
                  mt_image *mean, mt_image *var)
{
    mt_imgacc *acc = mt_imgacc_create(SW, SH, 3, NULL);
    int x, y, s, c, ok;
    if (!acc) return 0;
    for (y = 0; y < SH; ++y)
        for (x = 0; x < SW; ++x)
            for (s = 0; s < spp; ++s) {
                float v[3];
                for (c = 0; c < 3; ++c) {
                    double mu = x < 4 ? 0.25 : scene_mu(x, c);
                    if (x >= bx0 && x < bx1 && y >= by0 && y < by1) mu *= 1 + bias;
                    v[c] = (float)(mu + scene_sd(x, y) * sqrt(3.0) *
                                            (2 * mt_rng_uniform_d(rng) - 1));
                }
                mt_imgacc_add(acc, x, y, v);
            }
    ok = mt_imgacc_finish(acc, mean, var, NULL) == MT_OK;
    mt_imgacc_destroy(acc);
    return ok;
}

/* One trial: a at 16 samples per pixel, b (the golden) at 64. */
static int trial(mt_rng *rng, double bias, int region[4], mt_ztest_result *r, mt_image *zmap)
{
    mt_image a, va, b, vb;
    int ok;
    if (!render(rng, 16, bias, region[0], region[1], region[2], region[3], &a, &va)) return 0;
    if (!render(rng, 64, 0, 0, 0, 0, 0, &b, &vb)) return 0;
    ok = mt_imgcmp_ztest(&a, &va, &b, &vb, NULL, r, zmap, NULL) == MT_OK;
    mt_image_destroy(&a);
    mt_image_destroy(&va);
    mt_image_destroy(&b);
    mt_image_destroy(&vb);
    return ok;
}

/* 200 honest trials: each fails with probability 0.01, so the number of
 * failures is Binomial(200, 0.01): mean 2, P(>= 9) = 2.6e-4 -- more than 8
 * means the test is miscalibrated. The 200 * 168 z values are N(0, 1): mean
 * z^2 within 0.02 of 1 (its sd is sqrt(2 / 33600) = 0.0077) and 5% beyond
 * 1.96 (sd 0.12%); so are the 600 global bias z. A variance off by 10% (a forgotten side, n for n - 1 on
 * few samples, n instead of n^2) misses these. */
static void test_ztest_false_alarms(void)
{
    int region[4] = {0, 0, 0, 0}, t, failures = 0, exact_ok = 1, bad = 0;
    long nz = 0, beyond196 = 0;
    double z2 = 0, bias2 = 0;
    mt_rng rng;
    mt_rng_seed(&rng, 2024, 7);
    for (t = 0; t < 200; ++t) {
        mt_ztest_result r;
        mt_image zmap;
        size_t k;
        if (!trial(&rng, 0, region, &r, &zmap)) {
            bad++;
            continue;
        }
        failures += !r.pass;
        bias2 += r.bias_z[0] * r.bias_z[0] + r.bias_z[1] * r.bias_z[1] + r.bias_z[2] * r.bias_z[2];
        /* the background column of blocks: 8 blocks x 3 channels, all equal */
        exact_ok &= r.exact == 24 && r.exact_mismatch == 0 && r.tests == 168;
        for (k = 0; k < (size_t)zmap.width * zmap.height * 3; ++k) {
            if (k / 3 % (size_t)zmap.width == 0) continue; /* background */
            z2 += (double)zmap.data[k] * zmap.data[k];
            beyond196 += fabs(zmap.data[k]) > 1.959964;
            nz++;
        }
        mt_image_destroy(&zmap);
    }
    t_check(bad == 0, "z-test trials: every trial runs", "%d failed to run", bad);
    t_check(failures <= 8, "z-test trials: honest renders fail at the rate alpha = 0.01",
            "%d of 200 failed (binomial: mean 2, P(>= 9) = 2.6e-4)", failures);
    printf("# %d of 200 honest trials failed\n", failures);
    t_check(exact_ok, "z-test trials: zero-variance background is exact and equal", "no");
    t_check(nz == 200 * 168 && fabs(z2 / (double)nz - 1) < 0.02,
            "z-test trials: z is calibrated (mean z^2 = 1)", "mean z^2 %.4f over %ld", z2 / (double)nz,
            nz);
    t_rel((double)beyond196 / (double)nz, 0.05, 0.1, 0,
          "z-test trials: 5% of |z| beyond 1.96");
    /* 600 bias z, N(0, 1): the mean square's sd is sqrt(2 / 600) = 0.058 */
    t_near(bias2 / 600, 1, 0.2, "z-test trials: the global bias z is calibrated (mean square 1)");
}

/* +2% in the 8x8 region x, y in [24, 32) x [0, 8) (mu about 0.7-0.8, sd 0.05
 * per sample: a block mean's sd is 0.05 / 16 at 16 spp, 0.05 / 32 at 64 spp,
 * so the bias of ~0.015 is z ~ 4.3 against a threshold of ~4.0): every one
 * of 20 trials must fail, with its beyond-threshold blocks in the region
 * (outside it, 20 * 156 honest tests at p = 6e-5: Poisson(0.19), P(> 2) =
 * 1e-3). */
static void test_ztest_bias(void)
{
    int region[4] = {24, 32, 0, 8}, t, detected = 0, outside = 0;
    mt_rng rng;
    mt_rng_seed(&rng, 99, 3);
    for (t = 0; t < 20; ++t) {
        mt_ztest_result r;
        mt_image zmap;
        int bx, by, c;
        if (!trial(&rng, 0.02, region, &r, &zmap)) continue;
        detected += !r.pass;
        for (by = 0; by < zmap.height; ++by)
            for (bx = 0; bx < zmap.width; ++bx)
                for (c = 0; c < 3; ++c)
                    if (fabs(t_image_px(&zmap, bx, by)[c]) >= r.z_threshold && !(bx >= 6 && by < 2))
                        outside++;
        mt_image_destroy(&zmap);
    }
    t_check(detected == 20, "z-test: a +2% bias in a 8x8 region is detected",
            "%d of 20 trials", detected);
    t_check(outside <= 2, "z-test: the blocks beyond the threshold are in the biased region",
            "%d outside", outside);
}

/* Zero-variance pixels: a background value off by 1e-3 fails however good
 * the p-values; within exact_rel (1e-4 of the value) passes; exact_rel 0
 * asks for equality. */
static void test_ztest_exact(void)
{
    mt_image a, va, b, vb;
    mt_ztest_result r;
    mt_ztest_options o = mt_ztest_defaults();
    mt_rng rng;
    mt_rng_seed(&rng, 3, 3);
    if (!render(&rng, 16, 0, 0, 0, 0, 0, &a, &va) || !render(&rng, 64, 0, 0, 0, 0, 0, &b, &vb)) {
        t_fail("z-test exact", "render failed");
        return;
    }
    t_image_px(&a, 1, 9)[0] = 0.25f + 1e-3f;
    mt_imgcmp_ztest(&a, &va, &b, &vb, NULL, &r, NULL, NULL);
    t_check(!r.pass && r.exact_mismatch == 1,
            "z-test exact: background off by 1e-3 fails as one exact mismatch",
            "pass %d, mismatches %ld, min p %g", r.pass, r.exact_mismatch, r.min_p);
    t_image_px(&a, 1, 9)[0] = 0.25f * (1 + 2e-6f);
    mt_imgcmp_ztest(&a, &va, &b, &vb, NULL, &r, NULL, NULL);
    t_check(r.exact_mismatch == 0,
            "z-test exact: background off by float rounding (2e-6) is equal", "%ld mismatches",
            r.exact_mismatch);
    o.exact_rel = 0;
    mt_imgcmp_ztest(&a, &va, &b, &vb, &o, &r, NULL, NULL);
    t_check(!r.pass && r.exact_mismatch == 1, "z-test exact: exact_rel 0 asks for equality",
            "%ld mismatches", r.exact_mismatch);
    mt_image_destroy(&a);
    mt_image_destroy(&va);
    mt_image_destroy(&b);
    mt_image_destroy(&vb);
}

/* ---- allocation failures ------------------------------------------------ */

static void test_alloc_failures(void)
{
    mt_image a, b, va = t_image_make(6, 5, 3, 1e-4f), map;
    mt_noise_metric m;
    mt_ztest_result r;
    int n, fails = 0, ok = 1;
    hand_images(&a, &b);
    for (n = 0; n < 100; ++n) {
        mt_status s1, s2, s3;
        mt_alloc_fail_after(n);
        s1 = mt_imgcmp_noise(&a, &b, 4, &m, NULL);
        mt_alloc_fail_after(n);
        s2 = mt_imgcmp_ztest(&a, &va, &b, &va, NULL, &r, &map, NULL);
        if (s2 == MT_OK) mt_image_destroy(&map);
        mt_alloc_fail_after(n);
        s3 = mt_imgcmp_reldiff_blocks(&a, &b, 4, &map, NULL);
        mt_alloc_fail_after(-1);
        if (s3 == MT_OK) mt_image_destroy(&map);
        ok &= (s1 == MT_OK || s1 == MT_ERR_NOMEM) && (s2 == MT_OK || s2 == MT_ERR_NOMEM) &&
              (s3 == MT_OK || s3 == MT_ERR_NOMEM);
        fails += s1 != MT_OK || s2 != MT_OK || s3 != MT_OK;
        if (s1 == MT_OK && s2 == MT_OK && s3 == MT_OK) break;
    }
    t_check(ok && fails > 0 && n < 100,
            "allocation failures: every one reported as out of memory (leaks: sanitizer build)",
            "%d failures, ok %d", fails, ok);
    mt_image_destroy(&a);
    mt_image_destroy(&b);
    mt_image_destroy(&va);
}

/* ---- pbrt-v2's renders ---------------------------------------------------- */


/* noise.txt's mean for scene s, or -1. */
static double noise_txt_mean(const char *dir, const char *s)
{
    char path[512], line[256], name[64];
    double mean = -1, v;
    FILE *f;
    snprintf(path, sizeof path, "%s/reference/pbrt-v2/noise.txt", dir);
    if (!(f = fopen(path, "r"))) return -1;
    while (fgets(line, sizeof line, f))
        if (line[0] != '#' && sscanf(line, "%63s %lf", name, &v) == 2 && !strcmp(name, s)) mean = v;
    fclose(f);
    return mean;
}

/* The metric of a render against itself (EXR against PFM: the same pixels)
 * is 0; a render scaled by 1.02 has luminance ratio 1.02 and every relative
 * difference below 0.02; and each material against the next differs by far
 * more than twice noise.txt's pbrt-v2-against-pbrt-v2 mean, so the
 * README's bound tells materials apart. */
static void test_pbrt_renders(void)
{
    const char *dir = t_shared_dir();
    char path[512], name[128];
    const char *scenes[T_MAX_KINDS];
    mt_image img[T_MAX_KINDS];
    mt_error err;
    int i, n = 0, nscenes = 0, ok = 1;
    if (!dir) {
        t_skip("pbrt-v2 renders", "no ../shared (set MATERIA_SHARED)");
        return;
    }
    if (!t_has_format("exr", "pbrt-v2 renders (EXR files)")) return;
    /* every material kind pbrt-v2 has a render of (all but a kind of
     * materia's own) */
    for (i = 0; i < mt_material_kind_count() && nscenes < T_MAX_KINDS; ++i) {
        const char *kind = mt_material_kind_name(mt_material_kind_at(i));
        snprintf(path, sizeof path, "%s/reference/pbrt-v2/%s.exr", dir, kind);
        if (access(path, R_OK) != 0) {
            t_skip("pbrt-v2 renders", "%s: no render of this material in pbrt-v2's reference data", path);
            continue;
        }
        scenes[nscenes++] = kind;
    }
    for (i = 0; i < nscenes && ok; ++i) {
        snprintf(path, sizeof path, "%s/reference/pbrt-v2/%s.exr", dir, scenes[i]);
        if ((ok = mt_image_read(path, &img[i], &err) == MT_OK)) n++;
    }
    if (!ok || n < 2) {
        t_fail("pbrt-v2 renders", "%s", ok ? "fewer than two renders" : err.message);
    } else {
        mt_image pfm, scaled;
        mt_noise_metric m;
        size_t k;
        snprintf(path, sizeof path, "%s/reference/pbrt-v2/matte.pfm", dir);
        if (mt_image_read(path, &pfm, &err) == MT_OK &&
            mt_imgcmp_noise(&img[0], &pfm, 4, &m, &err) == MT_OK) {
            t_check(m.mean == 0 && m.max == 0 && m.lum_ratio == 1,
                    "pbrt-v2 renders: matte EXR against PFM is 0", "mean %g", m.mean);
            scaled = t_image_make(pfm.width, pfm.height, 3, 0);
            for (k = 0; k < (size_t)pfm.width * pfm.height * 3; ++k)
                scaled.data[k] = pfm.data[k] * 1.02f;
            mt_imgcmp_noise(&scaled, &pfm, 4, &m, &err);
            t_check(fabs(m.lum_ratio - 1.02) < 1e-5 && m.max < 0.02 && m.mean > 0.01,
                    "pbrt-v2 renders: matte times 1.02", "ratio %.7f max %g mean %g",
                    m.lum_ratio, m.max, m.mean);
            mt_image_destroy(&scaled);
            mt_image_destroy(&pfm);
        } else
            t_fail("pbrt-v2 renders: matte EXR against PFM", "%s", err.message);
        for (i = 0; i < nscenes; ++i) {
            int j = (i + 1) % nscenes;
            double bound = 2 * noise_txt_mean(dir, scenes[i]);
            snprintf(name, sizeof name, "pbrt-v2 renders: %s against %s exceeds 2x noise.txt",
                     scenes[j], scenes[i]);
            if (mt_imgcmp_noise(&img[j], &img[i], 4, &m, &err) == MT_OK)
                t_check(bound > 0 && m.mean > bound, name, "mean %g, bound %g", m.mean, bound);
            else
                t_fail(name, "%s", err.message);
        }
    }
    for (i = 0; i < n; ++i) mt_image_destroy(&img[i]);
}

int main(void)
{
    test_percentile();
    test_noise_by_hand();
    test_noise_gaussian();
    test_pixel_errors();
    test_errors();
    test_accumulator();
    test_ztest_by_hand();
    test_ztest_false_alarms();
    test_ztest_bias();
    test_ztest_exact();
    test_alloc_failures();
    test_pbrt_renders();
    return t_status();
}
