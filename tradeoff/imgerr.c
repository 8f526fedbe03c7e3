/*
 * imgerr: the error of a render against a reference image, as one line of
 * numbers for the samples-per-pixel measurement (tradeoff/2-spp.sh).
 *
 *   imgerr A REF [REF2]
 *
 * prints "rmse relmse rel_p50 rel_p90 rel_p99 noise_mean rmse_raw ref_share"
 * over every pixel and colour channel (alpha ignored, so pbrt-v2's RGBA EXR
 * compares with materia's RGB). The reference b is REF, or with REF2 (a render
 * of the same scene with another seed) the mean of the two, whose own noise
 * is then estimated, vb = (REF - REF2)^2 / 4 per pixel and channel, and taken
 * out of the squared error (tests/support/sqerr.h derives it; no model of the
 * samples is needed, unlike a renderer's variance image, which overestimates
 * the variance of low-discrepancy renders):
 *   rmse       sqrt(mean ((a - b)^2 - vb)): A's error against the reference's
 *              expectation (0 if that estimate falls below 0); rmse_raw
 *              without REF2;
 *   relmse     mean ((a - b)^2 - vb) / (b^2 + 0.01) (Rousselle et al. 2011, as
 *              materia-imgdiff);
 *   rel_pN     the N-th percentile of |a - b| / (|b| + 0.01) (the reference's
 *              noise left in);
 *   noise_mean pbrt-v2's block metric (4x4 block means,
 *              ../shared/reference/README.md);
 *   rmse_raw   sqrt(mean (a - b)^2), the reference's noise left in;
 *   ref_share  mean vb / mean (a - b)^2, the share of the reference's noise in
 *              the raw squared error (NA without REF2).
 *
 *   imgerr --variance-check REF VAR REF2 VAR2
 *
 * prints "measured claimed ratio" for two renders with their variance images
 * (materia-render --variance): measured = mean (REF - REF2)^2 / 2, the
 * variance of one render, unbiased whatever the samples; claimed = the mean
 * of the two variance images; ratio = claimed / measured (1 for independent
 * samples, above 1 where the samples do better than independent ones).
 *
 * Exit status 1 when an image cannot be read or the images differ in size, 2
 * on a wrong command line.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "materia/image.h"
#include "materia/tools/imgcmp.h"
#include "support/sqerr.h"

static int fail(const char *what, const mt_error *err)
{
    char buf[512];
    mt_error_format(err, buf, sizeof buf);
    fprintf(stderr, "imgerr: %s: %s\n", what, buf);
    return 1;
}

/* The relative error of every pixel and colour channel, in *out (malloc'ed). */
static size_t relative_errors(const mt_image *a, const mt_image *b, double **out)
{
    int nc = a->channels >= 3 ? 3 : 1;
    size_t n = (size_t)a->width * (size_t)a->height, i, k = 0;
    double *v = malloc(sizeof *v * n * (size_t)nc);
    int c;
    if (!v) return 0;
    for (i = 0; i < n; i++)
        for (c = 0; c < nc; c++) {
            double x = a->data[i * (size_t)a->channels + (size_t)c],
                   y = b->data[i * (size_t)b->channels + (size_t)c];
            v[k++] = fabs(x - y) / (fabs(y) + MT_IMGCMP_OFFSET);
        }
    *out = v;
    return k;
}

static int read_all(int n, char **paths, mt_image *img)
{
    mt_error err;
    int k;
    memset(img, 0, sizeof *img * (size_t)n);
    for (k = 0; k < n; k++)
        if (mt_image_read(paths[k], &img[k], &err) != MT_OK) return fail(paths[k], &err);
    return 0;
}

static void free_all(int n, mt_image *img)
{
    int k;
    for (k = 0; k < n; k++) mt_image_destroy(&img[k]);
}

/* imgerr --variance-check REF VAR REF2 VAR2 */
static int variance_check(char **paths)
{
    mt_image img[4];
    t_sqerr e1, e2;
    char msg[512];
    if (read_all(4, paths, img)) return 1;
    /* (REF - REF2)^2 is the raw squared error of one against the other; the
     * variance images enter as the "reference" variance of each side */
    if (t_sqerr_compute(&img[0], &img[1], &img[2], &img[3], &e1, msg, sizeof msg) ||
        t_sqerr_compute(&img[0], NULL, &img[2], NULL, &e2, msg, sizeof msg)) {
        fprintf(stderr, "imgerr: %s against %s: %s\n", paths[0], paths[2], msg);
        free_all(4, img);
        return 1;
    }
    printf("%.6e %.6e ", e2.mse_raw / 2, (e1.a_var + e1.ref_var) / 2);
    if (e2.mse_raw > 0)
        printf("%.4f\n", (e1.a_var + e1.ref_var) / e2.mse_raw);
    else
        printf("NA\n");
    free_all(4, img);
    return 0;
}

int main(int argc, char **argv)
{
    mt_image img[3], b, vb; /* A, REF, REF2; the reference and its variance */
    mt_error err;
    mt_noise_metric nm;
    t_sqerr e;
    char msg[512];
    double *rel = NULL, p50, p90, p99;
    size_t n;
    int nin = argc - 1, pair;
    if (argc == 6 && !strcmp(argv[1], "--variance-check")) return variance_check(argv + 2);
    if ((nin != 2 && nin != 3) || argv[1][0] == '-' || argv[2][0] == '-' || (nin == 3 && argv[3][0] == '-')) {
        fprintf(stderr, "usage: imgerr A REF [REF2] | imgerr --variance-check REF VAR REF2 VAR2\n");
        return 2;
    }
    pair = nin == 3;
    if (read_all(nin, argv + 1, img)) return 1;
    memset(&vb, 0, sizeof vb);
    b = img[1];
    if (pair && t_sqerr_pair(&img[1], &img[2], &b, &vb, msg, sizeof msg)) {
        fprintf(stderr, "imgerr: %s and %s: %s\n", argv[2], argv[3], msg);
        return 1;
    }
    if (t_sqerr_compute(&img[0], NULL, &b, pair ? &vb : NULL, &e, msg, sizeof msg)) {
        fprintf(stderr, "imgerr: %s against %s: %s\n", argv[1], argv[2], msg);
        return 1;
    }
    if (mt_imgcmp_noise(&img[0], &b, MT_IMGCMP_BLOCK, &nm, &err) != MT_OK) return fail("compare", &err);
    n = relative_errors(&img[0], &b, &rel);
    if (!n) {
        fprintf(stderr, "imgerr: out of memory\n");
        return 1;
    }
    /* mt_imgcmp_percentile sorts in place: ascending order keeps later calls valid. */
    p50 = mt_imgcmp_percentile(rel, n, 0.5);
    p90 = mt_imgcmp_percentile(rel, n, 0.9);
    p99 = mt_imgcmp_percentile(rel, n, 0.99);
    printf("%.6e %.6e %.6e %.6e %.6e %.6e %.6e", sqrt(fmax(e.mse, 0)), e.relmse, p50, p90, p99, nm.mean,
           sqrt(e.mse_raw));
    if (pair && e.mse_raw > 0)
        printf(" %.4f\n", e.ref_var / e.mse_raw);
    else
        printf(" NA\n");
    free(rel);
    if (pair) {
        mt_image_destroy(&b);
        mt_image_destroy(&vb);
    }
    free_all(nin, img);
    return 0;
}
