/*
 * imgerr: the error of a render against a reference image, as one line of
 * numbers for the samples-per-pixel measurement (tradeoff/2-spp.sh).
 *
 *   imgerr A REF
 *
 * prints "rmse relmse rel_p50 rel_p90 rel_p99 noise_mean" where, over every
 * pixel and colour channel (alpha ignored, so pbrt-v2's RGBA EXR compares
 * with materia's RGB), rmse = sqrt(mean (a - b)^2), relmse = mean (a - b)^2 /
 * (b^2 + 0.01) (Rousselle et al. 2011, as materia-imgdiff), rel_pN the N-th
 * percentile of the relative error |a - b| / (|b| + 0.01), and noise_mean
 * pbrt-v2's block metric (4x4 block means, ../shared/reference/README.md).
 * Exit status 1 when an image cannot be read or the two differ in size, 2 on
 * a wrong command line.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include "materia/image.h"
#include "materia/imgcmp.h"

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

int main(int argc, char **argv)
{
    mt_image a, b;
    mt_error err;
    mt_pixel_errors pe;
    mt_noise_metric nm;
    double *rel = NULL, p50, p90, p99;
    size_t n;
    if (argc != 3) {
        fprintf(stderr, "usage: imgerr A REF\n");
        return 2;
    }
    if (mt_image_read(argv[1], &a, &err) != MT_OK) return fail(argv[1], &err);
    if (mt_image_read(argv[2], &b, &err) != MT_OK) return fail(argv[2], &err);
    if (mt_imgcmp_pixel_errors(&a, &b, &pe, &err) != MT_OK) return fail("compare", &err);
    if (mt_imgcmp_noise(&a, &b, MT_IMGCMP_BLOCK, &nm, &err) != MT_OK) return fail("compare", &err);
    n = relative_errors(&a, &b, &rel);
    if (!n) {
        fprintf(stderr, "imgerr: out of memory\n");
        return 1;
    }
    /* mt_imgcmp_percentile sorts in place: ascending order keeps later calls valid. */
    p50 = mt_imgcmp_percentile(rel, n, 0.5);
    p90 = mt_imgcmp_percentile(rel, n, 0.9);
    p99 = mt_imgcmp_percentile(rel, n, 0.99);
    printf("%.6e %.6e %.6e %.6e %.6e %.6e\n", pe.rmse, pe.relmse, p50, p90, p99, nm.mean);
    free(rel);
    mt_image_free(&a);
    mt_image_free(&b);
    return 0;
}
