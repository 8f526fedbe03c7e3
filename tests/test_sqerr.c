/*
 * The squared error against a noisy reference (tests/support/sqerr.h, what
 * tradeoff/imgerr.c reports for the samples-per-pixel measurement): hand
 * values; then synthetic renders with a known answer, pixels that are means of
 * exponentially distributed samples (a heavy right tail, as path-traced
 * radiance has) accumulated with mt_imgacc, where the mean squared error of
 * an image of Na samples per pixel is known exactly: the estimate with the
 * reference's variance subtracted must find it, with and without a planted
 * bias, and the estimate without the subtraction (what a comparison that
 * ignores the reference's noise reports) must be caught missing it. With
 * stratified samples (as low-discrepancy ones, better than independent) a
 * render's own variance image overestimates its variance: the subtraction
 * with it must be caught taking too much, and the reference of two renders
 * with independent seeds (t_sqerr_pair) must find the exact answer.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "materia/tools/imgcmp.h"
#include "support/check.h"
#include "support/sqerr.h"
#include "support/timage.h"

#define W 32
#define H 24
#define TRIALS 40

static void test_hand_values(void)
{
    /* one pixel, RGB: d = -0.5, 0, 1; vb = 0.1, 0.2, 0.3 */
    mt_image a = t_image_make(1, 1, 3, 0), b = t_image_make(1, 1, 4, 0), vb = t_image_make(1, 1, 3, 0),
             va = t_image_make(1, 1, 3, 0.5f), small = t_image_make(2, 1, 3, 0);
    const float av[3] = {1, 2, 3}, bv[4] = {1.5f, 2, 2, 1}, vv[3] = {0.1f, 0.2f, 0.3f};
    t_sqerr e;
    char msg[256];
    memcpy(a.data, av, sizeof av);
    memcpy(b.data, bv, sizeof bv); /* RGBA: the alpha is not compared */
    memcpy(vb.data, vv, sizeof vv);
    if (t_check(t_sqerr_compute(&a, &va, &b, &vb, &e, msg, sizeof msg) == 0, "sqerr: hand values compute", "%s",
                msg)) {
        double w0 = 1 / (1.5 * 1.5 + 0.01), w1 = 1 / (4 + 0.01);
        t_check(e.n == 3, "sqerr: 3 colour values (alpha ignored)", "n = %zu", e.n);
        t_near(e.mse_raw, 1.25 / 3, 1e-7, "sqerr: raw mse = (0.25 + 0 + 1) / 3");
        t_near(e.ref_var, 0.2, 1e-7, "sqerr: reference variance = mean vb = 0.2");
        t_near(e.mse, 1.25 / 3 - 0.2, 1e-7, "sqerr: mse = raw - mean vb");
        t_near(e.relmse_raw, (0.25 * w0 + 1 * w1) / 3, 1e-7, "sqerr: raw relmse weights by 1 / (b^2 + 0.01)");
        t_near(e.relmse, ((0.25 - 0.1) * w0 - 0.2 * w1 + (1 - 0.3) * w1) / 3, 1e-7,
               "sqerr: relmse subtracts vb / (b^2 + 0.01)");
        t_near(e.a_var, 0.5, 1e-7, "sqerr: mean va");
    }
    t_check(t_sqerr_compute(&small, NULL, &b, &vb, &e, msg, sizeof msg) == -1 && strstr(msg, "2x1"),
            "sqerr: a size mismatch is an error naming the sizes", "%s", msg);
    vb.data[1] = -0.1f;
    t_check(t_sqerr_compute(&a, NULL, &b, &vb, &e, msg, sizeof msg) == -1 && strstr(msg, "channel 1"),
            "sqerr: a negative variance is an error naming the pixel and channel", "%s", msg);
    vb.data[1] = (float)NAN;
    t_check(t_sqerr_compute(&a, NULL, &b, &vb, &e, msg, sizeof msg) == -1, "sqerr: a NaN variance is an error",
            "%s", msg);
    mt_image_destroy(&a);
    mt_image_destroy(&b);
    mt_image_destroy(&vb);
    mt_image_destroy(&va);
    mt_image_destroy(&small);
}

/* The expectation of value k of the synthetic scene: 0.05 to 2, varied. */
static double mu_of(int k)
{
    return 0.05 + 1.95 * fmod(0.618034 * k, 1.0);
}

/* An image of n samples per pixel with their expectation mu (+ the bias in
 * the left quarter of the image when bias != 0): the mean and the variance of
 * the mean from mt_imgacc, as a render gives them. Exponential samples,
 * -mu ln(1 - u): variance mu^2 with u uniform; with strat, sample s has u
 * uniform in [s / n, (s + 1) / n), one sample per stratum. */
static void render(mt_rng *r, int n, double bias, int strat, mt_image *mean, mt_image *var)
{
    mt_error err;
    mt_imgacc *acc = mt_imgacc_create(W, H, 3, &err);
    int x, y, c, s;
    if (!acc) {
        fprintf(stderr, "out of memory for the test images\n");
        exit(1);
    }
    for (y = 0; y < H; ++y)
        for (x = 0; x < W; ++x)
            for (s = 0; s < n; ++s) {
                float v[3];
                for (c = 0; c < 3; ++c) {
                    int k = (y * W + x) * 3 + c;
                    double m = mu_of(k) + (x < W / 4 ? bias : 0);
                    double u = mt_rng_uniform_d(r);
                    if (strat) u = (s + u) / n;
                    v[c] = (float)(-m * log(1 - u));
                }
                mt_imgacc_add(acc, x, y, v);
            }
    if (mt_imgacc_finish(acc, mean, var, &err) != MT_OK) t_fail("sqerr: accumulator", "finish failed");
    mt_imgacc_destroy(acc);
}

/* The mean and its standard error over the trials of one estimate. */
typedef struct trial_stat {
    double s, s2;
} trial_stat;

static void stat_add(trial_stat *st, double x)
{
    st->s += x;
    st->s2 += x * x;
}

static double stat_mean(const trial_stat *st)
{
    return st->s / TRIALS;
}

static double stat_se(const trial_stat *st)
{
    double m = stat_mean(st);
    return sqrt(fmax(st->s2 / TRIALS - m * m, 0) / (TRIALS - 1));
}

static void free_images(mt_image *img, int n)
{
    int i;
    for (i = 0; i < n; ++i) mt_image_destroy(&img[i]);
}

/* TRIALS pairs (image of na samples with a bias, reference of nr samples):
 * the mean and the standard error over the trials of the estimate, without
 * and with the subtraction, against the exact mean squared error. */
static void known_answer(int na, int nr, double bias, const char *label)
{
    mt_rng rng;
    trial_stat st[3];
    double truth = 0, noise = 0, se[3], mean[3];
    int t, k, i;
    char name[160];
    memset(st, 0, sizeof st);
    mt_rng_seed(&rng, 20261205, (uint64_t)(na * 1000 + nr) + (bias != 0));
    for (k = 0; k < W * H * 3; ++k) {
        double m = mu_of(k) + ((k / 3) % W < W / 4 ? bias : 0);
        noise += m * m / na;
        truth += m * m / na + ((k / 3) % W < W / 4 ? bias * bias : 0);
    }
    truth /= W * H * 3;
    noise /= W * H * 3;
    for (t = 0; t < TRIALS; ++t) {
        mt_image im[4]; /* a, its variance, b, its variance */
        t_sqerr e;
        char msg[256];
        render(&rng, na, bias, 0, &im[0], &im[1]);
        render(&rng, nr, 0, 0, &im[2], &im[3]);
        if (t_sqerr_compute(&im[0], &im[1], &im[2], &im[3], &e, msg, sizeof msg)) {
            t_fail("sqerr: known answer", "%s", msg);
            return;
        }
        /* the raw estimate, the unbiased one, and the variance images'
         * prediction of the raw one (a's variance + b's, plus the bias) */
        stat_add(&st[0], e.mse_raw);
        stat_add(&st[1], e.mse);
        stat_add(&st[2], e.a_var + e.ref_var);
        free_images(im, 4);
    }
    for (i = 0; i < 3; ++i) {
        mean[i] = stat_mean(&st[i]);
        se[i] = stat_se(&st[i]);
    }
    /* 4 standard errors: a false failure about once in 16000 runs */
    snprintf(name, sizeof name, "sqerr: %s: mean of (a - b)^2 - vb finds the exact mse", label);
    t_check(fabs(mean[1] - truth) <= 4 * se[1], name, "%.6g against %.6g (se %.3g)", mean[1], truth, se[1]);
    snprintf(name, sizeof name, "sqerr: %s: the raw mean of (a - b)^2 misses it by the reference's variance",
             label);
    t_check(fabs(mean[0] - truth) > 4 * se[0] && fabs(mean[0] - truth - (mean[0] - mean[1])) <= 4 * se[1], name,
            "raw %.6g, exact %.6g (se %.3g), reference variance %.6g", mean[0], truth, se[0], mean[0] - mean[1]);
    if (bias == 0) {
        /* with independent samples the variance images predict the raw error */
        snprintf(name, sizeof name, "sqerr: %s: va + vb predicts the raw error (independent samples)", label);
        t_check(fabs(mean[0] - mean[2]) <= 4 * (se[0] + se[2]), name, "raw %.6g, va + vb %.6g", mean[0], mean[2]);
    } else {
        /* the bias is seen: an estimate of the noise alone would miss it */
        snprintf(name, sizeof name, "sqerr: %s: the estimate holds the bias, not only the noise", label);
        t_check(mean[1] - noise > 4 * se[1], name, "%.6g, the noise alone %.6g (se %.3g)", mean[1], noise, se[1]);
    }
}

/* The variance of the mean of n stratified samples of -ln(1 - u) (one u in
 * each [i / n, (i + 1) / n)), in closed form: with s = 1 - u over a stratum
 * [s0, s1] of width h, E[-ln s] = [s - s ln s] / h and E[ln^2 s] = [s ln^2 s
 * - 2 s ln s + 2 s] / h between s0 and s1 (s ln s -> 0 at 0). */
static double strat_var(int n)
{
    double h = 1.0 / n, v = 0;
    int i;
    for (i = 0; i < n; ++i) {
        double s0 = 1 - (i + 1) * h, s1 = 1 - i * h;
        double l0 = s0 > 0 ? log(s0) : 0, l1 = log(s1);
        double m1 = ((s1 - s1 * l1) - (s0 - s0 * l0)) / h;
        double m2 = ((s1 * l1 * l1 - 2 * s1 * l1 + 2 * s1) - (s0 * l0 * l0 - 2 * s0 * l0 + 2 * s0)) / h;
        v += m2 - m1 * m1;
    }
    return v / ((double)n * n);
}

/* Stratified renders: the image of na samples against (1) one reference of
 * 2 nr samples with its own variance image and (2) the reference of two
 * renders of nr samples each (seeds of their own): the same samples, so the
 * same Var(b); only where vb comes from differs. */
static void stratified(int na, int nr)
{
    mt_rng rng;
    trial_stat st[2];
    double truth = 0, vimg = 0, vtrue = 0;
    int t, k;
    char name[160], msg[256];
    memset(st, 0, sizeof st);
    mt_rng_seed(&rng, 20261205, 77);
    for (k = 0; k < W * H * 3; ++k) truth += mu_of(k) * mu_of(k);
    vtrue = truth / (W * H * 3) * strat_var(2 * nr);
    truth = truth / (W * H * 3) * strat_var(na);
    for (t = 0; t < TRIALS; ++t) {
        /* a, b of 2 nr samples, r1 and r2 of nr, the mean of r1 and r2; each
         * followed by its variance image */
        mt_image im[10];
        t_sqerr e[2];
        render(&rng, na, 0, 1, &im[0], &im[1]);
        render(&rng, 2 * nr, 0, 1, &im[2], &im[3]);
        render(&rng, nr, 0, 1, &im[4], &im[5]);
        render(&rng, nr, 0, 1, &im[6], &im[7]);
        if (t_sqerr_pair(&im[4], &im[6], &im[8], &im[9], msg, sizeof msg) ||
            t_sqerr_compute(&im[0], NULL, &im[2], &im[3], &e[0], msg, sizeof msg) ||
            t_sqerr_compute(&im[0], NULL, &im[8], &im[9], &e[1], msg, sizeof msg)) {
            t_fail("sqerr: stratified", "%s", msg);
            return;
        }
        vimg += e[0].ref_var / TRIALS;
        stat_add(&st[0], e[0].mse);
        stat_add(&st[1], e[1].mse);
        free_images(im, 10);
    }
    snprintf(name, sizeof name, "sqerr: stratified %d spp: the variance image of %d stratified spp overestimates", na,
             2 * nr);
    t_check(vimg > 2 * vtrue, name, "mean vb %.4g, exact Var(b) %.4g", vimg, vtrue);
    snprintf(name, sizeof name, "sqerr: stratified %d spp: subtracting that variance image is caught too low", na);
    t_check(truth - stat_mean(&st[0]) > 4 * stat_se(&st[0]), name, "%.6g against %.6g (se %.3g)", stat_mean(&st[0]),
            truth, stat_se(&st[0]));
    snprintf(name, sizeof name, "sqerr: stratified %d spp: the reference of two renders finds the exact mse", na);
    t_check(fabs(stat_mean(&st[1]) - truth) <= 4 * stat_se(&st[1]), name, "%.6g against %.6g (se %.3g)",
            stat_mean(&st[1]), truth, stat_se(&st[1]));
}

int main(void)
{
    test_hand_values();
    /* a reference at 4 times the samples: the raw estimate is 25% high */
    known_answer(16, 64, 0, "16 spp against 64");
    /* a planted bias of 0.2 in a quarter of the image adds 0.2^2 / 4 = 0.01
     * (and raises the noise there) */
    known_answer(16, 64, 0.2, "16 spp with a bias, against 64");
    /* a reference with as few samples as the image: the raw estimate doubles */
    known_answer(8, 8, 0, "8 spp against 8");
    /* stratified: 8 spp against two references of 16 (32 in all) */
    stratified(8, 16);
    return t_status();
}
