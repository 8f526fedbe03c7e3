/*
 * The power of the conformance suite's chi-square (tradeoff/5-power.sh): the
 * fraction of runs, over seeds, in which the test catches a pdf that is
 * wrong by a relative eps, against the sample count and the cell count.
 *
 * The subject is pbrt-v2's default plastic (Lambertian + Blinn exponent 10,
 * "plastic default" of conformance/materials.c), wo at 45 degrees in the xz
 * plane, in corrected mode: in pbrt-v2 mode Blinn's sampler returns
 * directions below the horizon with a pdf > 0 where Pdf() is 0, a hard
 * failure of every run that would hide the power being measured. The planted error is a pure change of shape: the claimed pdf is
 * p (1 + eps sin phi), which integrates to the same total as p (the BSDF is
 * symmetric under y -> -y), so only the chi-square can see it; its relative
 * error reaches eps. The expected counts are the suite's own: each cell's
 * integral by cf_integrate_cell (adaptive cubature in double), of p and of
 * p sin phi (so every eps costs one cubature), and the test is
 * cf_chi2_cells at the per-test significance that make check uses (0.01,
 * Sidak over the run's tests, counted as conformance/main.c counts them).
 *
 * Output, CSV on stdout: cells, samples, eps, runs, detected, power, the
 * seconds of one run's sampling and of the cells' cubature; "# alpha" lines.
 *
 * usage: power RUNS MAX_SAMPLES
 */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "../conformance/conformance.h"
#include "support/timing.h"

#define TWO_PI 6.283185307179586

static const double eps_list[] = {0, 0.005, 0.01, 0.02, 0.05};
#define NEPS (int)(sizeof eps_list / sizeof eps_list[0])
static const int cells[][2] = {{16, 17}, {32, 33}, {100, 101}};
#define NCELLS (int)(sizeof cells / sizeof cells[0])
/* --lite, make check and check-full use 2e4, 1e5 and 4e6 */
static const long n_list[] = {10000, 20000, 50000, 100000, 200000, 500000, 1000000, 2000000, 4000000};
#define NN (int)(sizeof n_list / sizeof n_list[0])

/* out[0] = pdf, out[1] = pdf sin phi: the two parts of the claimed pdf */
static void integrand(void *ctx, double phi, double z, double *out)
{
    double v[7];
    int k;
    cf_bsdf_integrand(ctx, phi, z, v);
    out[0] = v[0];
    out[1] = v[0] * sin(phi);
    for (k = 2; k < 7; ++k) out[k] = 0;
}

/* make check's per-test significance (conformance/main.c) */
static double suite_alpha(void)
{
    long tests = cf_suite_tests(0);
    printf("# tests %ld\n", tests);
    return cf_sidak(0.01, tests);
}

int main(int argc, char **argv)
{
    int runs = argc > 1 ? atoi(argv[1]) : 20, nm, i, c, e, r, ni;
    long maxn = argc > 2 ? atol(argv[2]) : 1000000, n = 0;
    const cf_subject *mats = cf_material_subjects(&nm), *plastic = NULL;
    mt_arena *arena = mt_arena_create(0);
    mt_bsdf *bsdf;
    mt_error err;
    cf_bsdf_pass pass;
    cf_config cfg[NCELLS];
    double *A[NCELLS], *B[NCELLS], tcub[NCELLS], alpha;
    long *counts[NCELLS];
    mt_vec3 wo = mt_v3((mt_real)0.70710678, 0, (mt_real)0.70710678);
    if (runs < 1 || maxn < 1000) {
        fprintf(stderr, "usage: power RUNS MAX_SAMPLES (RUNS >= 1, MAX_SAMPLES >= 1000)\n");
        return 2;
    }
    for (i = 0; i < nm; ++i)
        if (!strcmp(mats[i].name, "plastic default")) plastic = &mats[i];
    mt_error_clear(&err);
    if (!plastic || !arena || cf_build_material(plastic, arena, MT_MODE_CORRECTED, &bsdf, &err)) {
        fprintf(stderr, "power: cannot build the plastic: %s\n", err.message);
        return 1;
    }
    alpha = suite_alpha();
    printf("# alpha_per_test %.6g\n", alpha);
    pass.bsdf = bsdf;
    pass.wo = wo;
    pass.flags = MT_BSDF_ALL;
    for (c = 0; c < NCELLS; ++c) {
        int nc = cells[c][0] * cells[c][1];
        double t0 = t_cpu_now(), v[7], ep;
        memset(&cfg[c], 0, sizeof cfg[c]);
        cfg[c].nphi = cells[c][0];
        cfg[c].nz = cells[c][1];
        cfg[c].alpha = 0.01;
        cfg[c].alpha_test = alpha;
        A[c] = malloc(sizeof(double) * (size_t)nc);
        B[c] = malloc(sizeof(double) * (size_t)nc);
        counts[c] = malloc(sizeof(long) * (size_t)nc);
        if (!A[c] || !B[c] || !counts[c]) return 1;
        for (i = 0; i < nc; ++i) {
            /* the suite's tolerance at the largest sample count */
            if (cf_integrate_cell(integrand, &pass, &cfg[c], i, maxn / nc, maxn, 0.05 / ((double)maxn * nc), v, &ep,
                                  &err)) {
                fprintf(stderr, "power: cubature: %s\n", err.message);
                return 1;
            }
            A[c][i] = v[0];
            B[c][i] = v[1];
        }
        tcub[c] = t_cpu_now() - t0;
    }
    printf("cells,samples,eps,runs,detected,power,seconds_sampling,seconds_cubature\n");
    for (ni = 0; ni < NN && (n = n_list[ni]) <= maxn; ++ni) {
        int det[NCELLS][NEPS];
        double tsamp = 0, *pdfc = NULL;
        memset(det, 0, sizeof det);
        for (r = 0; r < runs; ++r) {
            mt_rng rng;
            long k, succ = 0;
            double t0 = t_cpu_now();
            for (c = 0; c < NCELLS; ++c) memset(counts[c], 0, sizeof(long) * (size_t)(cells[c][0] * cells[c][1]));
            mt_rng_seed(&rng, 1000 + (uint64_t)r, (uint64_t)n);
            for (k = 0; k < n; ++k) {
                mt_real uc = mt_rng_uniform(&rng), u1 = mt_rng_uniform(&rng), u2 = mt_rng_uniform(&rng);
                mt_bsdf_sample sm = mt_bsdf_sample_f(bsdf, wo, uc, u1, u2, MT_BSDF_ALL);
                if (!(sm.pdf > 0)) continue;
                succ++;
                for (c = 0; c < NCELLS; ++c) counts[c][cf_cell_of(&cfg[c], sm.wi)]++;
            }
            tsamp += t_cpu_now() - t0;
            for (c = 0; c < NCELLS; ++c) {
                int nc = cells[c][0] * cells[c][1];
                double *p = realloc(pdfc, sizeof(double) * (size_t)nc);
                if (!p) return 1;
                pdfc = p;
                for (e = 0; e < NEPS; ++e) {
                    double integral = 0;
                    cf_chi2 x;
                    for (i = 0; i < nc; ++i) integral += pdfc[i] = A[c][i] + eps_list[e] * B[c][i];
                    cf_chi2_cells(&cfg[c], counts[c], pdfc, n, succ, integral, &x);
                    if (x.p < alpha) det[c][e]++;
                }
            }
        }
        free(pdfc);
        for (c = 0; c < NCELLS; ++c)
            for (e = 0; e < NEPS; ++e)
                printf("%dx%d,%ld,%g,%d,%d,%.4f,%.4g,%.4g\n", cells[c][0], cells[c][1], n, eps_list[e], runs, det[c][e],
                       (double)det[c][e] / runs, tsamp / runs, tcub[c]);
        fflush(stdout);
    }
    mt_arena_destroy(arena);
    return 0;
}
