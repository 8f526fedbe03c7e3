/*
 * Float versus double: the same queries (inputs representable in float) are
 * answered by this build and by the other precision's conformance binary,
 * and the differences reported per configuration in float ULPs (units of the
 * float spacing at the larger magnitude), which is the float build's error
 * against the double build.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>
#include "conformance.h"
#include "queries.h"

#define NQ 256

/* The answers of one configuration: 8 numbers per query. */
static int answers(const cf_subject *s, mt_mode mode, int si, double *out)
{
    mt_arena *a = mt_arena_create(0);
    mt_bsdf *b;
    mt_error err;
    mt_rng rng;
    int i, n = 0;
    if (!a) return -1;
    mt_error_clear(&err);
    if (s->build(s, a, mode, &b, &err)) {
        mt_arena_destroy(a);
        return -1;
    }
    mt_rng_seed(&rng, 4242, (uint64_t)si);
    for (i = 0; i < NQ; ++i) {
        cf_query q = cf_query_next(&rng);
        mt_rgb f = mt_bsdf_f(b, q.wo, q.wi, MT_BSDF_ALL);
        mt_bsdf_sample sm = mt_bsdf_sample_f(b, q.wo, q.uc, q.u1, q.u2, MT_BSDF_ALL);
        out[n++] = f.c[0];
        out[n++] = f.c[1];
        out[n++] = f.c[2];
        out[n++] = mt_bsdf_pdf(b, q.wo, q.wi, MT_BSDF_ALL);
        out[n++] = sm.wi.x;
        out[n++] = sm.wi.z;
        out[n++] = sm.f.c[1];
        out[n++] = sm.pdf;
    }
    mt_arena_destroy(a);
    return n;
}

int cf_dump(const char *path)
{
    int nsub, si, mi, i, n;
    const cf_subject *subs = cf_subjects(&nsub);
    double *v = malloc(sizeof(double) * 8 * NQ);
    FILE *fp = fopen(path, "w");
    if (!fp || !v) {
        fprintf(stderr, "materia-conformance: cannot write %s\n", path);
        free(v);
        if (fp) fclose(fp);
        return 1;
    }
    for (si = 0; si < nsub; ++si)
        for (mi = 0; mi < 2; ++mi) {
            n = answers(&subs[si], mi ? MT_MODE_CORRECTED : MT_MODE_PBRT_V2, si, v);
            fprintf(fp, "%d %d %d", si, mi, n);
            for (i = 0; i < n; ++i) fprintf(fp, " %.17g", v[i]);
            fprintf(fp, "\n");
        }
    free(v);
    return fclose(fp) != 0;
}

static int cmp_double(const void *x, const void *y)
{
    double a = *(const double *)x, b = *(const double *)y;
    return a < b ? -1 : a > b;
}

void cf_ulps(const char *other, cf_rows *rows)
{
    char tmpl[] = "/tmp/materia-ulps-XXXXXX";
    int fd = mkstemp(tmpl), nsub, si, mi, i, n, m;
    const cf_subject *subs = cf_subjects(&nsub);
    double *mine = malloc(sizeof(double) * 8 * NQ), *theirs = malloc(sizeof(double) * 8 * NQ),
           *d = malloc(sizeof(double) * 8 * NQ);
    FILE *fp = NULL;
    pid_t pid;
    int status = -1;
    cf_row r;
    memset(&r, 0, sizeof r);
    snprintf(r.check, sizeof r.check, "float vs double");
    snprintf(r.mode, sizeof r.mode, "both");
    if (fd < 0 || !mine || !theirs || !d) goto fail;
    close(fd);
    pid = fork();
    if (pid == 0) {
        execl(other, other, "--dump", tmpl, (char *)NULL);
        _exit(127);
    }
    if (pid < 0 || waitpid(pid, &status, 0) < 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) goto fail;
    fp = fopen(tmpl, "r");
    if (!fp) goto fail;
    while (fscanf(fp, "%d %d %d", &si, &mi, &n) == 3) {
        double worst = 0, p99, med, scale = 0, bound;
        int k;
        for (i = 0; i < n && i < 8 * NQ; ++i)
            if (fscanf(fp, "%lf", &theirs[i]) != 1) goto fail;
        if (si < 0 || si >= nsub) goto fail;
        m = answers(&subs[si], mi ? MT_MODE_CORRECTED : MT_MODE_PBRT_V2, si, mine);
        if (m != n) goto fail;
        for (k = 0; k < n; ++k) scale = fmax(scale, fabs(theirs[k]) < 1e30 ? fabs(theirs[k]) : 0);
        for (k = 0; k < n; ++k) {
            /* values far below the configuration's scale (a Fresnel
             * reflectance of 1e-13 at index 1 + 1e-6) are compared at 1e-7
             * of it */
            d[k] = cf_ulp_distance(mine[k], theirs[k], 1e-7 * scale, 24);
            worst = fmax(worst, d[k]);
        }
        qsort(d, (size_t)n, sizeof *d, cmp_double);
        med = d[n / 2];
        p99 = d[(int)(0.99 * (n - 1))];
        snprintf(r.subject, sizeof r.subject, "%s", subs[si].name);
        snprintf(r.mode, sizeof r.mode, "%s", mi ? "corrected" : "pbrt-v2");
        /* ordinary queries agree to rounding; the float tolerance of the
         * identities (1e-3 relative, 8192 ulps; e ulps for a cos^e lobe)
         * bounds the 99th percentile; the maximum belongs to ill-conditioned
         * queries and is reported */
        bound = fmax(8192, 4 * subs[si].lobe_exponent);
        snprintf(r.statistic, sizeof r.statistic, "float ulps: median %.1f, 99%% %.3g, max %.3g", med, p99, worst);
        snprintf(r.bound, sizeof r.bound, "med<=16, 99%%<=%.0f", bound);
        r.verdict = med <= 16 && p99 <= bound ? CF_PASS : CF_FAIL;
        cf_rows_add(rows, &r);
    }
    fclose(fp);
    remove(tmpl);
    free(mine);
    free(theirs);
    free(d);
    return;
fail:
    if (fp) fclose(fp);
    remove(tmpl);
    free(mine);
    free(theirs);
    free(d);
    snprintf(r.subject, sizeof r.subject, "float vs double comparison");
    snprintf(r.statistic, sizeof r.statistic, "could not run %s --dump", other);
    r.verdict = CF_FAIL;
    cf_rows_add(rows, &r);
}
