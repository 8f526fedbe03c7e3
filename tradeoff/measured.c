/*
 * measured: what each form of a measured BRDF costs and how far it is from
 * the BRDF it stands for (tradeoff/4-measured.sh).
 *
 *   measured --out DIR [--brdfs DIR] [--quick]
 *
 * 1. Analytic truth (DIR/4-measured-analytic.csv). pbrt-v2's plastic
 *    (Lambertian Kd plus a Blinn microfacet lobe, exponent 1/roughness, with
 *    FresnelDielectric(1.5, 1): materials/plastic.cpp), at two roughnesses,
 *    stands for a measured material whose truth is known. Its two measured
 *    forms are compared with it:
 *    - irregular data (pbrt-v2's IrregIsotropicBRDF: k-d search of the
 *      remapped samples, Gaussian-weighted): N direction pairs drawn
 *      uniformly over both hemispheres, each with the plastic's f, for N
 *      from 1000 to 256000;
 *    - the MERL half-angle table (RegularHalfangleBRDF: the bin's value) at
 *      pbrt-v2's 90 x 90 x 180 bins, each sampled at its centre
 *      (mt_merl_tabulate), and coarser tables: the full table's bins averaged
 *      over k x k x k blocks (90/k x 90/k x 180/k bins, a coarser
 *      measurement), held at pbrt-v2's resolution because pbrt-v2 reads
 *      only that one: the lookup costs the same, the data would be k^3
 *      times smaller.
 * 2. The real irregular files (DIR/4-measured-files.csv): each .brdf of
 *    --brdfs (../shared/reference/scenes/brdfs) against its own MERL table
 *    (tabulated at bin centres from the irregular BRDF): the table's error
 *    taking the irregular BRDF as the truth, and the time per call of each.
 *
 * Error: the relative RMS difference sqrt(sum |f - f_true|^2 / sum
 * |f_true|^2) over the three channels and M direction pairs, both
 * cosine-distributed over the upper hemisphere: the projected solid angle,
 * the measure under which a surface is seen and lit. (With wo uniform, the
 * few pairs at grazing wo, where pbrt-v2's microfacet f grows as 1/cos
 * theta_o, dominate the sum and the figure changes with the draw.) Beside
 * it, the median over the pairs of the relative difference (rel_median),
 * the typical pair's error. Time: ns per f call on one thread, its CPU
 * time (CLOCK_THREAD_CPUTIME_ID, so that other processes on a shared machine
 * do not count), the median of 5 runs over 4096 pairs.
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "materia.h"
#include "support/timing.h"
#include "materia/tools/merl.h"

#define NT 4096 /* pairs per timing run */
#define REPS 5

/* pbrt-v2 measured.cpp: the MERL file's channel scales. */
static const double merl_scale[3] = {1.0 / 1500.0, 1.15 / 1500.0, 1.66 / 1500.0};

typedef struct pairs {
    int n;
    mt_vec3 *wo, *wi;
} pairs;

static void die(const char *what, const mt_error *err)
{
    char buf[512];
    if (err) mt_error_format(err, buf, sizeof buf);
    fprintf(stderr, "measured: %s%s%s\n", what, err ? ": " : "", err ? buf : "");
    exit(1);
}

static void *xmalloc(size_t n)
{
    void *p = malloc(n);
    if (!p) die("out of memory", NULL);
    return p;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* wo and wi cosine-distributed over the upper hemisphere. */
static pairs make_pairs(int n, uint64_t seed)
{
    pairs p;
    mt_rng rng;
    int i;
    p.n = n;
    p.wo = xmalloc(sizeof *p.wo * (size_t)n);
    p.wi = xmalloc(sizeof *p.wi * (size_t)n);
    mt_rng_seed(&rng, seed, 1);
    for (i = 0; i < n; i++) {
        mt_real u0 = mt_rng_uniform(&rng), u1 = mt_rng_uniform(&rng), u2 = mt_rng_uniform(&rng),
                u3 = mt_rng_uniform(&rng);
        p.wo[i] = mt_cosine_sample_hemisphere(u0, u1);
        p.wi[i] = mt_cosine_sample_hemisphere(u2, u3);
    }
    return p;
}

static void free_pairs(pairs *p)
{
    free(p->wo);
    free(p->wi);
}

/* A BRDF is either a BSDF (the analytic truth) or one BxDF. */
typedef struct brdf {
    const mt_bsdf *bsdf;
    const mt_bxdf *bxdf;
} brdf;

static mt_rgb brdf_f(brdf b, mt_vec3 wo, mt_vec3 wi)
{
    return b.bsdf ? mt_bsdf_f(b.bsdf, wo, wi, MT_BSDF_ALL) : mt_bxdf_f(b.bxdf, wo, wi);
}

static volatile double sink;

/* ns per call, the median of REPS runs over the first NT pairs of p. */
static double time_f(brdf b, const pairs *p)
{
    double t[REPS];
    int r, i, n = p->n < NT ? p->n : NT;
    for (r = 0; r < REPS; r++) {
        double s = 0, t0 = t_cpu_now();
        for (i = 0; i < n; i++) s += brdf_f(b, p->wo[i], p->wi[i]).c[1];
        t[r] = (t_cpu_now() - t0) / n * 1e9;
        sink += s;
    }
    return t_median(t, REPS);
}

/* f of the truth at every pair, 3 values a pair. */
static double *values_of(brdf b, const pairs *p)
{
    double *v = xmalloc(sizeof *v * 3 * (size_t)p->n);
    int i, c;
    for (i = 0; i < p->n; i++) {
        mt_rgb f = brdf_f(b, p->wo[i], p->wi[i]);
        for (c = 0; c < 3; c++) v[3 * i + c] = f.c[c];
    }
    return v;
}

static double rel_rms(brdf b, const pairs *p, const double *truth)
{
    double num = 0, den = 0;
    int i, c;
    for (i = 0; i < p->n; i++) {
        mt_rgb f = brdf_f(b, p->wo[i], p->wi[i]);
        for (c = 0; c < 3; c++) {
            double d = f.c[c] - truth[3 * i + c];
            num += d * d;
            den += truth[3 * i + c] * truth[3 * i + c];
        }
    }
    return den > 0 ? sqrt(num / den) : 0;
}

/* The median over the pairs of sum_c |f - f_true| / (sum_c |f_true| + 1e-3):
 * the typical pair, where the RMS figure is the lobes' (a few pairs with
 * large f weigh most in it). */
static double rel_median(brdf b, const pairs *p, const double *truth)
{
    double *r = malloc(sizeof *r * (size_t)p->n), med;
    int i, c;
    if (!r) die("out of memory", NULL);
    for (i = 0; i < p->n; i++) {
        mt_rgb f = brdf_f(b, p->wo[i], p->wi[i]);
        double num = 0, den = 1e-3;
        for (c = 0; c < 3; c++) {
            num += fabs(f.c[c] - truth[3 * i + c]);
            den += fabs(truth[3 * i + c]);
        }
        r[i] = num / den;
    }
    qsort(r, (size_t)p->n, sizeof r[0], cmp_double);
    med = r[p->n / 2];
    free(r);
    return med;
}

/* pbrt-v2's plastic at the standard shading point (n = +z: local = world). */
static mt_bsdf *plastic(mt_arena *a, double roughness, mt_error *err)
{
    mt_diffgeom dg = mt_diffgeom_default();
    mt_bsdf *b = mt_bsdf_create(a, MT_MODE_PBRT_V2, &dg, dg.n, 1, err);
    mt_bxdf *d, *s;
    if (!b) return NULL;
    d = mt_lambertian_create(a, MT_MODE_PBRT_V2, mt_rgb_make(0.35f, 0.12f, 0.08f), err);
    s = mt_microfacet_create(a, MT_MODE_PBRT_V2, mt_rgb_gray(0.3f), mt_fresnel_dielectric(1.5f, 1),
                             mt_blinn((mt_real)(1 / roughness)), err);
    if (!d || !s || mt_bsdf_add(b, d, err) != MT_OK || mt_bsdf_add(b, s, err) != MT_OK) return NULL;
    return b;
}

/* The MERL table of b (bin centres) in mt_measured_halfangle_create's
 * order: rgb[3 * index + channel], scaled back from the file's units. */
static mt_real *tabulate(const mt_bsdf *b)
{
    double *file = xmalloc(sizeof *file * 3 * (size_t)MT_MERL_SAMPLES);
    mt_real *rgb = xmalloc(sizeof *rgb * 3 * (size_t)MT_MERL_SAMPLES);
    mt_error err;
    size_t i;
    int c;
    if (mt_merl_tabulate(b, MT_MERL_AT_CENTRE, file, &err) != MT_OK) die("tabulating", &err);
    for (c = 0; c < 3; c++)
        for (i = 0; i < (size_t)MT_MERL_SAMPLES; i++)
            rgb[3 * i + (size_t)c] = (mt_real)(file[(size_t)c * MT_MERL_SAMPLES + i] * merl_scale[c]);
    free(file);
    return rgb;
}

/* Each k x k x k block of bins replaced by its mean (k divides 90). */
static mt_real *downsample(const mt_real *rgb, int k)
{
    mt_real *out = xmalloc(sizeof *out * 3 * (size_t)MT_MERL_SAMPLES);
    int h, d, p, i, j, l, c;
    for (h = 0; h < MT_MERL_THETA_H; h += k)
        for (d = 0; d < MT_MERL_THETA_D; d += k)
            for (p = 0; p < MT_MERL_PHI_D; p += k)
                for (c = 0; c < 3; c++) {
                    double s = 0;
                    for (i = h; i < h + k; i++)
                        for (j = d; j < d + k; j++)
                            for (l = p; l < p + k; l++)
                                s += rgb[3 * ((size_t)l + 180 * ((size_t)j + 90 * (size_t)i)) + (size_t)c];
                    s /= (double)k * k * k;
                    for (i = h; i < h + k; i++)
                        for (j = d; j < d + k; j++)
                            for (l = p; l < p + k; l++)
                                out[3 * ((size_t)l + 180 * ((size_t)j + 90 * (size_t)i)) + (size_t)c] = (mt_real)s;
                }
    return out;
}

/* Irregular data of n uniformly drawn pairs with the truth's values. */
static mt_measured *irregular_of(brdf truth, int n, uint64_t seed, mt_error *err)
{
    mt_vec3 *wo = xmalloc(sizeof *wo * (size_t)n), *wi = xmalloc(sizeof *wi * (size_t)n);
    mt_rgb *v = xmalloc(sizeof *v * (size_t)n);
    mt_measured *m;
    mt_rng rng;
    int i;
    mt_rng_seed(&rng, seed, 2);
    for (i = 0; i < n; i++) {
        mt_real u0 = mt_rng_uniform(&rng), u1 = mt_rng_uniform(&rng), u2 = mt_rng_uniform(&rng),
                u3 = mt_rng_uniform(&rng);
        wo[i] = mt_uniform_sample_hemisphere(u0, u1);
        wi[i] = mt_uniform_sample_hemisphere(u2, u3);
        v[i] = brdf_f(truth, wo[i], wi[i]);
    }
    m = mt_measured_irregular_create(wo, wi, v, n, err);
    free(wo);
    free(wi);
    free(v);
    return m;
}

static FILE *open_csv(const char *dir, const char *name, char *path, size_t size)
{
    FILE *f;
    snprintf(path, size, "%s/%s.tmp", dir, name);
    f = fopen(path, "w");
    if (!f) {
        fprintf(stderr, "measured: cannot write %s\n", path);
        exit(1);
    }
    return f;
}

static void close_csv(FILE *f, const char *path)
{
    char final[1100];
    size_t n = strlen(path) - 4; /* drop ".tmp" */
    if (fclose(f) != 0) die("writing a CSV file", NULL);
    snprintf(final, sizeof final, "%.*s", (int)n, path);
    if (rename(path, final) != 0) die("renaming a CSV file", NULL);
}

static void analytic(const char *out, int quick)
{
    static const double rough[2] = {0.1, 0.02};
    static const int ks[] = {1, 2, 3, 5, 6, 9, 10, 15, 18, 30, 45};
    static const int ns[] = {1000, 4000, 16000, 64000, 256000};
    int nns = quick ? 3 : 5, nks = quick ? 6 : (int)(sizeof ks / sizeof ks[0]);
    char path[1100];
    FILE *f = open_csv(out, "4-measured-analytic.csv", path, sizeof path);
    pairs p = make_pairs(quick ? 4000 : 100000, 11);
    int r, i;
    fprintf(f, "material,form,param,bytes,ns_per_call,rel_rms,rel_median\n");
    for (r = 0; r < 2; r++) {
        mt_arena *a = mt_arena_create(0);
        mt_error err;
        mt_bsdf *b = plastic(a, rough[r], &err);
        brdf truth = {NULL, NULL};
        double *tv;
        mt_real *full;
        char name[64];
        if (!b) die("building the plastic", &err);
        truth.bsdf = b;
        snprintf(name, sizeof name, "plastic roughness %g", rough[r]);
        tv = values_of(truth, &p);
        fprintf(f, "%s,analytic,0,0,%.2f,0,0\n", name, time_f(truth, &p));
        for (i = 0; i < nns; i++) {
            mt_measured *m = irregular_of(truth, ns[i], 100 + (uint64_t)i, &err);
            brdf x = {NULL, NULL};
            if (!m) die("irregular data", &err);
            x.bxdf = mt_irregular_isotropic_brdf_create(a, MT_MODE_PBRT_V2, m, &err);
            if (!x.bxdf) die("irregular BRDF", &err);
            /* pbrt-v2 keeps a Point and an RGB Spectrum (six floats) a sample */
            fprintf(f, "%s,irregular,%d,%d,%.2f,%.5g,%.5g\n", name, ns[i], ns[i] * 24, time_f(x, &p),
                    rel_rms(x, &p, tv), rel_median(x, &p, tv));
            fprintf(stderr, "measured: %s irregular %d done\n", name, ns[i]);
            mt_measured_destroy(m);
        }
        full = tabulate(b);
        for (i = 0; i < nks; i++) {
            int k = ks[i];
            mt_real *t = k == 1 ? full : downsample(full, k);
            mt_measured *m = mt_measured_halfangle_create(t, &err);
            brdf x = {NULL, NULL};
            long bins = (long)(90 / k) * (90 / k) * (180 / k);
            if (!m) die("half-angle table", &err);
            x.bxdf = mt_regular_halfangle_brdf_create(a, MT_MODE_PBRT_V2, m, &err);
            if (!x.bxdf) die("half-angle BRDF", &err);
            /* the MERL file holds three doubles a bin */
            fprintf(f, "%s,merl,%d,%ld,%.2f,%.5g,%.5g\n", name, 90 / k, 24 * bins, time_f(x, &p),
                    rel_rms(x, &p, tv), rel_median(x, &p, tv));
            mt_measured_destroy(m);
            if (t != full) free(t);
        }
        fprintf(stderr, "measured: %s tables done\n", name);
        free(full);
        free(tv);
        mt_arena_destroy(a);
    }
    free_pairs(&p);
    close_csv(f, path);
}

static void files(const char *out, const char *dir, int quick)
{
    static const char *const names[] = {"mystique", "acryl_blue", "cayman", "garnet_red", "krylon_blue"};
    int nf = quick ? 1 : 5, i;
    char path[1100];
    FILE *f = open_csv(out, "4-measured-files.csv", path, sizeof path);
    pairs p = make_pairs(quick ? 4000 : 100000, 12);
    fprintf(f, "file,samples,ns_irregular,ns_merl,rel_rms_merl,rel_median_merl,tabulate_s\n");
    for (i = 0; i < nf; i++) {
        char file[1100];
        mt_arena *a = mt_arena_create(0);
        mt_error err;
        mt_diffgeom dg = mt_diffgeom_default();
        mt_measured *m, *t;
        brdf irr = {NULL, NULL}, merl = {NULL, NULL};
        mt_bsdf *b;
        mt_real *rgb;
        double *tv, t0, ti, tm, e;
        snprintf(file, sizeof file, "%s/%s.brdf", dir, names[i]);
        m = mt_measured_load(file, &err);
        if (!m) die(file, &err);
        irr.bxdf = mt_irregular_isotropic_brdf_create(a, MT_MODE_PBRT_V2, m, &err);
        b = mt_bsdf_create(a, MT_MODE_PBRT_V2, &dg, dg.n, 1, &err);
        if (!irr.bxdf || !b || mt_bsdf_add(b, (mt_bxdf *)irr.bxdf, &err) != MT_OK) die(file, &err);
        t0 = t_cpu_now();
        rgb = tabulate(b);
        t0 = t_cpu_now() - t0;
        t = mt_measured_halfangle_create(rgb, &err);
        if (!t) die(file, &err);
        merl.bxdf = mt_regular_halfangle_brdf_create(a, MT_MODE_PBRT_V2, t, &err);
        if (!merl.bxdf) die(file, &err);
        tv = values_of(irr, &p);
        ti = time_f(irr, &p);
        tm = time_f(merl, &p);
        e = rel_rms(merl, &p, tv);
        fprintf(f, "%s,%d,%.2f,%.2f,%.5g,%.5g,%.2f\n", names[i], mt_measured_count(m), ti, tm, e,
                rel_median(merl, &p, tv), t0);
        fprintf(stderr, "measured: %s done\n", names[i]);
        free(tv);
        free(rgb);
        mt_measured_destroy(t);
        mt_measured_destroy(m);
        mt_arena_destroy(a);
    }
    mt_measured_cache_clear();
    free_pairs(&p);
    close_csv(f, path);
}

int main(int argc, char **argv)
{
    const char *out = NULL, *brdfs = NULL;
    int quick = 0, i;
    for (i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--out") && i + 1 < argc) out = argv[++i];
        else if (!strcmp(argv[i], "--brdfs") && i + 1 < argc) brdfs = argv[++i];
        else if (!strcmp(argv[i], "--quick")) quick = 1;
        else {
            fprintf(stderr, "usage: measured --out DIR [--brdfs DIR] [--quick]\n");
            return 2;
        }
    }
    if (!out) {
        fprintf(stderr, "usage: measured --out DIR [--brdfs DIR] [--quick]\n");
        return 2;
    }
    analytic(out, quick);
    if (brdfs) files(out, brdfs, quick);
    return 0;
}
