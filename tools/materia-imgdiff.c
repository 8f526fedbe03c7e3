/*
 * materia-imgdiff: compares an image with a reference (docs/RENDERER.md,
 * "Comparing images"): pbrt-v2's noise metric, RMSE, relative MSE, the
 * largest difference, and with variance images the z-test; optionally a heat
 * map.
 *
 *   materia-imgdiff A B [--block N] [--var-a VA] [--var-b VB] [--alpha P]
 *                   [--heatmap OUT.png] [--heatmap-max V] [--heatmap-z]
 *                   [--fail-above X] [--fail-ztest]
 *
 * A is the image under test, B the reference (relative differences divide by
 * B). Exit status: 0 when the images were compared (and passed what
 * --fail-above and --fail-ztest ask), 1 on a failure (a file unreadable,
 * sizes or channels that differ, the mean relative difference -- pbrt-v2's
 * metric, noise-mean -- above --fail-above X, the z-test failed under
 * --fail-ztest), 2 on a wrong command line.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "materia.h"
#include "materia/image.h"
#include "materia/tools/imgcmp.h"
#include "toolargs.h"

static const char *prog = "materia-imgdiff";

typedef struct args {
    const char *a, *b, *var_a, *var_b, *heatmap;
    int block, heatmap_z, fail_ztest;
    double alpha, heatmap_max, fail_above; /* fail_above < 0: not given */
} args;

static int usage(FILE *f)
{
    fprintf(f,
            "usage: %s A B [--block N] [--var-a VA] [--var-b VB] [--alpha P]\n"
            "       [--heatmap OUT.png] [--heatmap-max V] [--heatmap-z]\n"
            "       [--fail-above X] [--fail-ztest]\n"
            "       %s --help | --version\n",
            prog, prog);
    if (f == stdout) /* --help: every option with its default */
        fputs("A: the image under test, B: the reference (EXR, PNG or PFM). Prints pbrt-v2's noise\n"
              "metric (block means of |a - b| / (b + 0.01)), RMSE, relative MSE, the largest\n"
              "difference, and the z-test when a variance image is given.\n"
              "  --block N          block side of the noise metric and the z-test, 1 to 4096 (default 4)\n"
              "  --var-a VA         the variance image of A (default: none)\n"
              "  --var-b VB         the variance image of B (default: none); with either, the z-test\n"
              "  --alpha P          the z-test's level over all blocks, 1e-12 to 0.5 (default 0.01)\n"
              "  --heatmap OUT.png  a heat map of the blocks' relative difference (default: none)\n"
              "  --heatmap-max V    the heat map's top value (default 0.1, or the z-test's threshold\n"
              "                     with --heatmap-z)\n"
              "  --heatmap-z        the heat map shows the blocks' z values (needs a variance image;\n"
              "                     default: the relative difference)\n"
              "  --fail-above X     exit 1 when the noise metric's mean is above X (default: never)\n"
              "  --fail-ztest       exit 1 when the z-test fails (default: report only)\n"
              "  --help, -h         this text;  --version  materia's version and precision\n"
              "Exit status: 0 compared, 1 failure (an unreadable file, over --fail-above, the z-test\n"
              "failed with --fail-ztest), 2 wrong command line.\n",
              f);
    return f == stdout ? 0 : 2;
}

/* Returns -1 to go on, else the exit status. */
static int parse(int argc, char **argv, args *a)
{
    int i, npos = 0;
    double v;
    memset(a, 0, sizeof *a);
    a->block = MT_IMGCMP_BLOCK;
    a->alpha = 0.01;
    a->heatmap_max = -1;
    a->fail_above = -1;
    for (i = 1; i < argc; ++i) {
        const char *o = argv[i], *val = i + 1 < argc ? argv[i + 1] : NULL;
        if (!strcmp(o, "--help") || !strcmp(o, "-h")) return usage(stdout);
        if (!strcmp(o, "--version")) {
            printf("%s (materia) %s, %s\n", prog, mt_version(), mt_precision());
            return 0;
        }
        if (!strcmp(o, "--heatmap-z"))
            a->heatmap_z = 1;
        else if (!strcmp(o, "--fail-ztest"))
            a->fail_ztest = 1;
        else if (!val && (!strcmp(o, "--var-a") || !strcmp(o, "--var-b") || !strcmp(o, "--heatmap") ||
                          !strcmp(o, "--block") || !strcmp(o, "--alpha") || !strcmp(o, "--heatmap-max") ||
                          !strcmp(o, "--fail-above")))
            return tool_no_value(prog, o);
        else if (!strcmp(o, "--var-a"))
            a->var_a = argv[++i];
        else if (!strcmp(o, "--var-b"))
            a->var_b = argv[++i];
        else if (!strcmp(o, "--heatmap"))
            a->heatmap = argv[++i];
        else if (!strcmp(o, "--block")) {
            if (!tool_number(prog, o, argv[++i], 1, 4096, 1, &v)) return 2;
            a->block = (int)v;
        } else if (!strcmp(o, "--alpha")) {
            if (!tool_number(prog, o, argv[++i], 1e-12, 0.5, 0, &a->alpha)) return 2;
        } else if (!strcmp(o, "--heatmap-max")) {
            if (!tool_number(prog, o, argv[++i], 1e-30, 1e30, 0, &a->heatmap_max)) return 2;
        } else if (!strcmp(o, "--fail-above")) {
            if (!tool_number(prog, o, argv[++i], 0, 1e30, 0, &a->fail_above)) return 2;
        } else if (o[0] == '-' && o[1]) {
            fprintf(stderr, "%s: unknown option %s\n", prog, o);
            return usage(stderr);
        } else if (npos == 0)
            a->a = o, npos++;
        else if (npos == 1)
            a->b = o, npos++;
        else {
            fprintf(stderr, "%s: one image to test and one reference, not also \"%s\"\n", prog, o);
            return 2;
        }
    }
    if (npos != 2) {
        fprintf(stderr, "%s: needs two images, the one to test and the reference\n", prog);
        return usage(stderr);
    }
    if (a->heatmap_z && !a->var_a && !a->var_b) {
        fprintf(stderr, "%s: --heatmap-z needs --var-a or --var-b\n", prog);
        return 2;
    }
    if (a->heatmap) { /* before reading and comparing the images */
        mt_error err;
        if (mt_image_check_writable(a->heatmap, &err) != MT_OK) {
            fprintf(stderr, "%s: --heatmap: %s\n", prog, err.message);
            return 1;
        }
    }
    return -1;
}

/* Reads path into img and checks it has the size and colour channels of ref
 * (when ref is not NULL), with messages naming both files. */
static int load(const char *path, mt_image *img, const mt_image *ref, const char *ref_path)
{
    mt_error err;
    mt_error_clear(&err);
    if (mt_image_read(path, img, &err) != MT_OK) {
        fprintf(stderr, "%s: %s\n", prog, err.message);
        return 0;
    }
    if (!ref) return 1;
    if (img->width != ref->width || img->height != ref->height) {
        fprintf(stderr, "%s: size mismatch: %s is %d x %d but %s is %d x %d\n", prog, path,
                img->width, img->height, ref_path, ref->width, ref->height);
        return 0;
    }
    if ((img->channels == 1) != (ref->channels == 1)) {
        fprintf(stderr, "%s: channel mismatch: %s has %d channel%s but %s has %d\n", prog, path,
                img->channels, img->channels == 1 ? "" : "s", ref_path, ref->channels);
        return 0;
    }
    return 1;
}

static int fail(const mt_error *err)
{
    fprintf(stderr, "%s: %s\n", prog, err->message);
    return 1;
}

/* Writes the heat map of the block map `blocks`; 1 on success. */
static int heatmap(const args *a, const mt_image *blocks, int w, int h, double vmax)
{
    mt_image out;
    mt_error err;
    mt_error_clear(&err);
    if (mt_imgcmp_heatmap(blocks, a->block, w, h, vmax, 1, &out, &err) != MT_OK) return !fail(&err);
    if (mt_image_write(a->heatmap, &out, NULL, 0, &err) != MT_OK) {
        mt_image_destroy(&out);
        return !fail(&err);
    }
    mt_image_destroy(&out);
    printf("heatmap %s (%s, 0 to %g)\n", a->heatmap, a->heatmap_z ? "|z|" : "relative difference",
           vmax);
    return 1;
}

static const char *const channel_names[] = {"R", "G", "B"};

static const char *chan(const mt_image *img, int c)
{
    return img->channels == 1 ? "Y" : channel_names[c];
}

/* The comparison proper; returns the exit status. */
static int compare(const args *a, mt_image im[4])
{
    mt_noise_metric nm;
    mt_pixel_errors pe;
    mt_ztest_result zr;
    mt_ztest_options zo = mt_ztest_defaults();
    mt_image blocks = {0, 0, 0, NULL};
    mt_error err;
    int ztest = a->var_a || a->var_b, status = 0, k;
    const mt_image *va = a->var_a ? &im[2] : NULL, *vb = a->var_b ? &im[3] : NULL;
    mt_error_clear(&err);
    memset(&zr, 0, sizeof zr);
    if (mt_imgcmp_noise(&im[0], &im[1], a->block, &nm, &err) != MT_OK ||
        mt_imgcmp_pixel_errors(&im[0], &im[1], &pe, &err) != MT_OK)
        return fail(&err);
    printf("size %d x %d, %d colour channel%s, blocks of %d: %d x %d\n", im[0].width,
           im[0].height, nm.channels, nm.channels == 1 ? "" : "s", a->block, nm.blocks_x,
           nm.blocks_y);
    printf("noise-mean %.6g\nnoise-p99 %.6g\nnoise-max %.6g\n", nm.mean, nm.p99, nm.max);
    printf("lum-ratio %.6f (mean y %.6g and %.6g)\n", nm.lum_ratio, nm.y_a, nm.y_b);
    printf("rmse %.6g\nrelmse %.6g\n", pe.rmse, pe.relmse);
    printf("max-diff %.6g at pixel (%d, %d) %s\n", pe.max_abs, pe.max_x, pe.max_y,
           chan(&im[0], pe.max_c));
    if (ztest) {
        zo.block = a->block;
        zo.alpha = a->alpha;
        if (mt_imgcmp_ztest(&im[0], va, &im[1], vb, &zo, &zr, a->heatmap_z ? &blocks : NULL,
                            &err) != MT_OK)
            return fail(&err);
        printf("ztest %s: %ld tests, %ld beyond |z| %.3f (Sidak threshold p %.3g at alpha "
               "%g), min p %.3g, max |z| %.3f",
               zr.pass ? "pass" : "FAIL", zr.tests, zr.beyond, zr.z_threshold, zr.threshold,
               a->alpha, zr.min_p, zr.max_abs_z);
        if (zr.max_bx >= 0)
            printf(" at block (%d, %d) %s", zr.max_bx, zr.max_by, chan(&im[0], zr.max_c));
        printf("; %ld exact (zero variance), %ld differ\n", zr.exact, zr.exact_mismatch);
        if (zr.bias_c >= 0)
            printf("ztest bias: largest |sum z / sqrt m| %.3f in %s (threshold %.3f)\n",
                   fabs(zr.bias_z[zr.bias_c]), chan(&im[0], zr.bias_c), zr.bias_z_threshold);
        if (a->fail_ztest && !zr.pass) {
            fprintf(stderr, "%s: the z-test fails (%ld of %ld tests beyond the threshold, global "
                            "bias z %.3f against %.3f, %ld zero-variance blocks differ)\n",
                    prog, zr.beyond, zr.tests, zr.bias_c >= 0 ? zr.bias_z[zr.bias_c] : 0.0,
                    zr.bias_z_threshold, zr.exact_mismatch);
            status = 1;
        }
    }
    if (a->heatmap) {
        double vmax = a->heatmap_max > 0 ? a->heatmap_max : (a->heatmap_z ? zr.z_threshold : 0.1);
        if (!a->heatmap_z && mt_imgcmp_reldiff_blocks(&im[0], &im[1], a->block, &blocks, &err) != MT_OK)
            return fail(&err);
        k = heatmap(a, &blocks, im[0].width, im[0].height, vmax);
        mt_image_destroy(&blocks);
        if (!k) return 1;
    }
    if (a->fail_above >= 0 && nm.mean > a->fail_above) {
        fprintf(stderr, "%s: mean relative difference %.6g exceeds %g\n", prog, nm.mean,
                a->fail_above);
        status = 1;
    }
    return status;
}

int main(int argc, char **argv)
{
    args a;
    mt_image im[4] = {{0, 0, 0, NULL}, {0, 0, 0, NULL}, {0, 0, 0, NULL}, {0, 0, 0, NULL}};
    int status, k;
    if ((status = parse(argc, argv, &a)) >= 0) return status;
    if (!load(a.a, &im[0], NULL, NULL) || !load(a.b, &im[1], &im[0], a.a) ||
        (a.var_a && !load(a.var_a, &im[2], &im[0], a.a)) ||
        (a.var_b && !load(a.var_b, &im[3], &im[0], a.a)))
        status = 1;
    else
        status = compare(&a, im);
    for (k = 0; k < 4; ++k) mt_image_destroy(&im[k]);
    if (fflush(stdout) != 0 && status == 0) status = 1;
    return status;
}
