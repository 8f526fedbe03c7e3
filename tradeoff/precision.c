/*
 * Float against double (tradeoff/1-precision.sh), for every configuration
 * of the conformance catalog of --impl (conformance/impl_catalog.c: the 13
 * materials across their parameters, built from pbrt-v2 statements as
 * materia-query builds them), in pbrt-v2 mode.
 *
 *   precision answers DATA_DIR NQ > FILE
 *       (each build) NQ queries per configuration, inputs representable in
 *       float and the same in both builds: f (rgb) and pdf of (wo, wi), the
 *       sampled direction and its pdf for (wo, u); values as hex floats
 *       (exact); then the ns per call of f, pdf and sample_f (CPU time of the
 *       thread, median of 5 repetitions).
 *   precision compare FLOAT_FILE DOUBLE_FILE > CSV
 *       (the double build) the float build's error against the double
 *       build's, in float ULPs at the larger magnitude (values far below the
 *       configuration's scale, 1e-7 of it, compared at that floor, as
 *       conformance/ulps.c does); the double build's own error in double
 *       ULPs against long double for the configurations with a closed form
 *       cheap to write (Lambertian f and pdf); the times and their ratio.
 */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "../conformance/impl.h"
#include "../conformance/queries.h"
#include "support/timing.h"

#define NV 8 /* f rgb, pdf, sampled wi xyz, sample pdf */
#define REPS 5

/* The n queries of configuration ci (the same in both builds); NULL when out
 * of memory. */
static cf_query *make_queries(int n, int ci)
{
    mt_rng rng;
    cf_query *q = malloc(sizeof *q * (size_t)n);
    int i;
    if (!q) return NULL;
    mt_rng_seed(&rng, 1212, (uint64_t)ci);
    for (i = 0; i < n; ++i) q[i] = cf_query_next(&rng);
    return q;
}

static volatile double sink;

/* ns per call of op (0 f, 1 pdf, 2 sample_f) over the n queries q */
static double time_op(const mt_bsdf *b, const cf_query *q, int n, int op)
{
    double t[REPS];
    int r, i, l, loops = 1 + 20000 / n;
    for (r = 0; r < REPS; ++r) {
        double s = 0, t0 = t_cpu_now();
        for (l = 0; l < loops; ++l)
            for (i = 0; i < n; ++i) {
                if (op == 0)
                    s += mt_bsdf_f(b, q[i].wo, q[i].wi, MT_BSDF_ALL).c[1];
                else if (op == 1)
                    s += mt_bsdf_pdf(b, q[i].wo, q[i].wi, MT_BSDF_ALL);
                else
                    s += mt_bsdf_sample_f(b, q[i].wo, q[i].uc, q[i].u1, q[i].u2, MT_BSDF_ALL).pdf;
            }
        sink = s;
        t[r] = (t_cpu_now() - t0) * 1e9 / ((double)loops * n);
    }
    return t_median(t, REPS);
}

/* the configuration's lines with @DATA@ replaced by dir */
static int config_lines(const cf_impl_config *c, const char *dir, char buf[CI_MAX_LINES][2048], const char **lines)
{
    int n = 0, k;
    for (k = 0; k < CI_MAX_LINES && c->lines[k]; ++k) {
        const char *s = c->lines[k], *at;
        char *o = buf[n];
        size_t room = sizeof buf[n];
        while ((at = strstr(s, "@DATA@")) != NULL) {
            int w = snprintf(o, room, "%.*s%s", (int)(at - s), s, dir);
            if (w < 0 || (size_t)w >= room) return -1;
            o += w;
            room -= (size_t)w;
            s = at + 6;
        }
        if ((size_t)snprintf(o, room, "%s", s) >= room) return -1;
        lines[n] = buf[n];
        n++;
    }
    return n;
}

static int answers(const char *dir, int nq)
{
    int nc, ci, i;
    const cf_impl_config *cs = cf_impl_configs(&nc);
    char msg[512];
    if (cf_impl_write_data(dir, msg, sizeof msg)) {
        fprintf(stderr, "precision: %s\n", msg);
        return 1;
    }
    printf("precision %s %d %d\n", mt_precision(), nc, nq);
    for (ci = 0; ci < nc; ++ci) {
        char buf[CI_MAX_LINES][2048];
        const char *lines[CI_MAX_LINES];
        int nl = config_lines(&cs[ci], dir, buf, lines);
        cf_impl im;
        cf_query *q = NULL;
        if (nl < 0 || cf_materia_open(&im, MT_MODE_PBRT_V2, lines, nl)) {
            fprintf(stderr, "precision: %s: %s\n", cs[ci].name, nl < 0 ? "line too long" : im.msg);
            return 1;
        }
        if (!(q = make_queries(nq, ci))) {
            fprintf(stderr, "precision: out of memory\n");
            return 1;
        }
        for (i = 0; i < nq; ++i) {
            mt_rgb f = mt_bsdf_f(im.bsdf, q[i].wo, q[i].wi, MT_BSDF_ALL);
            mt_real pdf = mt_bsdf_pdf(im.bsdf, q[i].wo, q[i].wi, MT_BSDF_ALL);
            mt_bsdf_sample s = mt_bsdf_sample_f(im.bsdf, q[i].wo, q[i].uc, q[i].u1, q[i].u2, MT_BSDF_ALL);
            printf("%d %a %a %a %a %a %a %a %a\n", ci, (double)f.c[0], (double)f.c[1], (double)f.c[2], (double)pdf,
                   (double)s.wi.x, (double)s.wi.y, (double)s.wi.z, (double)s.pdf);
        }
        printf("time %d %.5g %.5g %.5g\n", ci, time_op(im.bsdf, q, nq, 0), time_op(im.bsdf, q, nq, 1),
               time_op(im.bsdf, q, nq, 2));
        free(q);
        cf_impl_close(&im);
    }
    return 0;
}

typedef struct dump {
    int nc, nq;
    double *v;     /* nc * nq * NV */
    double *t;     /* nc * 3 */
} dump;

static int read_dump(const char *path, dump *d)
{
    FILE *fp = fopen(path, "r");
    char prec[16];
    int ci, i, k, c2;
    if (!fp || fscanf(fp, "precision %15s %d %d", prec, &d->nc, &d->nq) != 3 || d->nc < 1 || d->nq < 1) {
        fprintf(stderr, "precision: %s: not an answers file\n", path);
        if (fp) fclose(fp);
        return -1;
    }
    d->v = malloc(sizeof(double) * (size_t)d->nc * (size_t)d->nq * NV);
    d->t = malloc(sizeof(double) * (size_t)d->nc * 3);
    if (!d->v || !d->t) return -1;
    for (ci = 0; ci < d->nc; ++ci) {
        for (i = 0; i < d->nq; ++i) {
            double *v = d->v + ((size_t)ci * d->nq + i) * NV;
            if (fscanf(fp, "%d %la %la %la %la %la %la %la %la", &c2, &v[0], &v[1], &v[2], &v[3], &v[4], &v[5], &v[6],
                       &v[7]) != 9 || c2 != ci)
                goto bad;
        }
        if (fscanf(fp, " time %d %lf %lf %lf", &c2, &d->t[3 * ci], &d->t[3 * ci + 1], &d->t[3 * ci + 2]) != 4 || c2 != ci)
            goto bad;
    }
    fclose(fp);
    (void)k;
    return 0;
bad:
    fprintf(stderr, "precision: %s: malformed at configuration %d\n", path, ci);
    fclose(fp);
    return -1;
}

static int cmp_double(const void *x, const void *y)
{
    double a = *(const double *)x, b = *(const double *)y;
    return a < b ? -1 : a > b;
}

static double pct(double *v, int n, double p)
{
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return v[(int)(p * (n - 1))];
}

/* Lambertian in long double, pbrt-v2 BSDF::f and Lambertian::f / Pdf in the
 * default frame (shading = geometric = +z, local = world): R / pi where wo
 * and wi are on the same side, and |cos wi| / pi. The Kd of each matte
 * configuration without Oren-Nayar, texture or tilt. */
static int lambert_kd(const char *name, long double kd[3])
{
    if (!strcmp(name, "matte Kd=1")) {
        kd[0] = kd[1] = kd[2] = 1;
        return 1;
    }
    if (!strcmp(name, "matte default")) {
        kd[0] = kd[1] = kd[2] = 0.5L;
        return 1;
    }
    if (!strcmp(name, "matte coloured Kd=0.7,0.2,0.05")) {
        kd[0] = 0.7L;
        kd[1] = 0.2L;
        kd[2] = 0.05L;
        return 1;
    }
    return 0;
}

static int compare(const char *fpath, const char *dpath)
{
    dump f, d;
    int nc, ci, i, k, n;
    const cf_impl_config *cs = cf_impl_configs(&nc);
    double *ef, *ep, *ew, *ed;
    if (read_dump(fpath, &f) || read_dump(dpath, &d)) return 1;
    if (f.nc != d.nc || f.nq != d.nq || f.nc != nc) {
        fprintf(stderr, "precision: the two files answer different queries\n");
        return 1;
    }
    n = f.nq;
    ef = malloc(sizeof(double) * 3 * (size_t)n);
    ep = malloc(sizeof(double) * 2 * (size_t)n);
    ew = malloc(sizeof(double) * 3 * (size_t)n);
    ed = malloc(sizeof(double) * 4 * (size_t)n);
    if (!ef || !ep || !ew || !ed) return 1;
    printf("index,material,configuration,f_ulps_median,f_ulps_p99,f_ulps_max,pdf_ulps_median,pdf_ulps_p99,"
           "pdf_ulps_max,dir_ulps_median,dir_ulps_p99,dir_ulps_max,float_ulps_p99_all,double_vs_longdouble_ulps_max,"
           "float_ns_f,float_ns_pdf,float_ns_sample,double_ns_f,double_ns_pdf,double_ns_sample,time_ratio_double_float\n");
    for (ci = 0; ci < nc; ++ci) {
        const double *fv = f.v + (size_t)ci * n * NV, *dv = d.v + (size_t)ci * n * NV;
        double sf = 0, sp = 0, all99, ldmax = -1, tf, td;
        long double kd[3];
        char mat[32], name[128];
        int nd = 0;
        for (i = 0; i < n; ++i) {
            for (k = 0; k < 3; ++k) sf = fmax(sf, fabs(dv[i * NV + k]));
            sp = fmax(sp, fmax(fabs(dv[i * NV + 3]), fabs(dv[i * NV + 7])));
        }
        for (i = 0; i < n; ++i) {
            const double *a = fv + i * NV, *b = dv + i * NV;
            for (k = 0; k < 3; ++k) {
                ef[3 * i + k] = cf_ulp_distance(a[k], b[k], 1e-7 * sf, 24);
                ew[3 * i + k] = cf_ulp_distance(a[4 + k], b[4 + k], 1e-7, 24);
            }
            ep[2 * i] = cf_ulp_distance(a[3], b[3], 1e-7 * sp, 24);
            ep[2 * i + 1] = cf_ulp_distance(a[7], b[7], 1e-7 * sp, 24);
        }
        if (lambert_kd(cs[ci].name, kd)) {
            /* the queries again, as the answers file made them */
            cf_query *q = make_queries(n, ci);
            if (!q) return 1;
            for (i = 0; i < n; ++i) {
                long double wo = q[i].wo.z, wi = q[i].wi.z, pi = 3.14159265358979323846264338327950288L;
                long double pdf = wo * wi > 0 ? fabsl(wi) / pi : 0;
                for (k = 0; k < 3; ++k)
                    ed[nd++] = cf_ulp_distance(dv[i * NV + k], (double)(wo * wi > 0 ? kd[k] / pi : 0), 1e-7 * sf, 53);
                ed[nd++] = cf_ulp_distance(dv[i * NV + 3], (double)pdf, 1e-7 * sp, 53);
            }
            free(q);
            ldmax = pct(ed, nd, 1);
        }
        /* the 99th percentile over every value of the configuration */
        {
            double *all = malloc(sizeof(double) * 8 * (size_t)n);
            if (!all) return 1;
            memcpy(all, ef, sizeof(double) * 3 * (size_t)n);
            memcpy(all + 3 * n, ep, sizeof(double) * 2 * (size_t)n);
            memcpy(all + 5 * n, ew, sizeof(double) * 3 * (size_t)n);
            all99 = pct(all, 8 * n, 0.99);
            free(all);
        }
        sscanf(cs[ci].name, "%31s", mat);
        /* the CSV's fields are plain: a comma in a name becomes ';' */
        {
            char *c;
            snprintf(name, sizeof name, "%s", cs[ci].name);
            for (c = name; *c; ++c)
                if (*c == ',' || *c == '"') *c = ';';
        }
        tf = f.t[3 * ci] + f.t[3 * ci + 1] + f.t[3 * ci + 2];
        td = d.t[3 * ci] + d.t[3 * ci + 1] + d.t[3 * ci + 2];
        printf("%d,%s,%s,%.3g,%.3g,%.3g,", ci, mat, name, pct(ef, 3 * n, 0.5), pct(ef, 3 * n, 0.99),
               pct(ef, 3 * n, 1));
        printf("%.3g,%.3g,%.3g,", pct(ep, 2 * n, 0.5), pct(ep, 2 * n, 0.99), pct(ep, 2 * n, 1));
        printf("%.3g,%.3g,%.3g,%.3g,", pct(ew, 3 * n, 0.5), pct(ew, 3 * n, 0.99), pct(ew, 3 * n, 1), all99);
        if (ldmax >= 0)
            printf("%.3g,", ldmax);
        else
            printf(",");
        printf("%.4g,%.4g,%.4g,%.4g,%.4g,%.4g,%.4f\n", f.t[3 * ci], f.t[3 * ci + 1], f.t[3 * ci + 2], d.t[3 * ci],
               d.t[3 * ci + 1], d.t[3 * ci + 2], td / tf);
    }
    free(ef);
    free(ep);
    free(ew);
    free(ed);
    return 0;
}

int main(int argc, char **argv)
{
    if (argc == 4 && !strcmp(argv[1], "answers")) {
        int nq = atoi(argv[3]);
        if (nq < 16 || nq > 1 << 20) {
            fprintf(stderr, "precision: NQ %s not in 16..1048576\n", argv[3]);
            return 2;
        }
        return answers(argv[2], nq);
    }
    if (argc == 4 && !strcmp(argv[1], "compare")) return compare(argv[2], argv[3]);
    fprintf(stderr, "usage: precision answers DATA_DIR NQ > FILE | precision compare FLOAT_FILE DOUBLE_FILE > CSV\n");
    return 2;
}
