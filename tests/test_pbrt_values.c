/*
 * pbrt-v2's own answers (../shared/reference/pbrt-v2-values/), fed through
 * the query tool in pbrt-v2 mode: BSDF eval and sample rows of every material
 * configuration (with the light-leak rows' tilted geometric normals), BSSRDF
 * coefficients, texture values and bump-mapped shading frames.
 *
 * Tolerances (float build): f and pdf 1e-4 relative, sampled directions 1e-5,
 * flags equal, BSSRDF coefficients 1e-5 relative, textures 1e-4 relative,
 * bumped frames 2e-3 absolute (the reference README: bump mapping takes small
 * finite differences, which magnify float rounding). Rows that differ because
 * of a documented erratum would be listed here with it; in the double build
 * the ill-conditioned rows are reported and the float build carries the
 * verdict (see test_pbrt_bxdf_values.c). Skipped when ../shared is absent.
 */
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "support/check.h"

#define MAXF 48

typedef struct row {
    char id[64], kind[16];
    double v[MAXF];
    int n;
} row;

/* Splits a CSV line into fields (empty fields read as NAN). */
static int split(char *line, char **f, int max)
{
    int n = 0;
    char *p = line;
    line[strcspn(line, "\r\n")] = 0;
    while (n < max) {
        f[n++] = p;
        p = strchr(p, ',');
        if (!p) break;
        *p++ = 0;
    }
    return n;
}

static double num(const char *s) { return *s ? atof(s) : NAN; }

static int close_rel(double got, double want, double rel) { return fabs(got - want) <= rel * fmax(fabs(got), fabs(want)) + 1e-9; }

typedef struct feed {
    FILE *in;
    int nq;           /* queries written */
    char **expect;    /* per query: the kind of answer, for the comparison */
} feed;

static const char *shared;

/* Runs the query tool on the file `in`, answers into `out`. */
static int run_tool(const char *tool, const char *in, const char *out)
{
    char cmd[4096];
    snprintf(cmd, sizeof cmd, "'%s' --dir '%s/reference/scenes' < '%s' > '%s'", tool, shared, in, out);
    return system(cmd);
}

/* One comparison group: the lines of the answers file, checked by cmp. */
typedef int (*cmp_fn)(const row *r, const char *answer, char *why, size_t n);

static int cmp_eval(const row *r, const char *a, char *why, size_t n)
{
    double f[4];
    if (sscanf(a, "%lf %lf %lf %lf", &f[0], &f[1], &f[2], &f[3]) != 4) return snprintf(why, n, "answer '%s'", a), 0;
    if (close_rel(f[0], r->v[9], 1e-4) && close_rel(f[1], r->v[10], 1e-4) && close_rel(f[2], r->v[11], 1e-4) &&
        close_rel(f[3], r->v[12], 1e-4))
        return 1;
    snprintf(why, n, "f %.9g %.9g %.9g pdf %.9g, pbrt-v2 %.9g %.9g %.9g %.9g", f[0], f[1], f[2], f[3], r->v[9],
             r->v[10], r->v[11], r->v[12]);
    return 0;
}

static int cmp_sample(const row *r, const char *a, char *why, size_t n)
{
    double s[7];
    unsigned flags;
    double dw;
    if (sscanf(a, "%lf %lf %lf %lf %lf %lf %lf %u", &s[0], &s[1], &s[2], &s[3], &s[4], &s[5], &s[6], &flags) != 8)
        return snprintf(why, n, "answer '%s'", a), 0;
    dw = fmax(fabs(s[0] - r->v[3]), fmax(fabs(s[1] - r->v[4]), fabs(s[2] - r->v[5])));
    if (dw <= 1e-5 && close_rel(s[3], r->v[9], 1e-4) && close_rel(s[4], r->v[10], 1e-4) &&
        close_rel(s[5], r->v[11], 1e-4) && close_rel(s[6], r->v[12], 1e-4) && (int)flags == (int)r->v[13])
        return 1;
    snprintf(why, n, "wi %.9g %.9g %.9g f %.9g pdf %.9g flags %u; pbrt-v2 %.9g %.9g %.9g f %.9g pdf %.9g flags %d",
             s[0], s[1], s[2], s[3], s[6], flags, r->v[3], r->v[4], r->v[5], r->v[9], r->v[12], (int)r->v[13]);
    return 0;
}

static int verdict(const char *name, int rows, int bad, int expected_rows)
{
    if (!MT_USE_DOUBLE) return t_check(bad == 0 && rows >= expected_rows, name, "%d of %d rows differ", bad, rows);
    t_skip(name, "double build: %d of %d rows agree to the float tolerances; pbrt-v2 computed in float, the float "
                 "build carries the verdict", rows - bad, rows);
    return 1;
}

/* BSDF rows: every configuration's statements, then its queries. */
static void bsdf_values(const char *tool, const char *tmp)
{
    char path[1024], in[1100], out[1100], line[4096];
    FILE *cf, *vf, *fi, *fo;
    char ids[64][64], ng[64][96];
    int nid = 0, i;
    row *rows = NULL;
    int nrows = 0, cap = 0;
    snprintf(path, sizeof path, "%s/reference/pbrt-v2-values/bsdf-configs.txt", shared);
    snprintf(in, sizeof in, "%s/bsdf.in", tmp);
    snprintf(out, sizeof out, "%s/bsdf.out", tmp);
    cf = fopen(path, "r");
    snprintf(path, sizeof path, "%s/reference/pbrt-v2-values/bsdf-values.csv", shared);
    vf = fopen(path, "r");
    fi = fopen(in, "w");
    if (!cf || !vf || !fi) {
        t_fail("pbrt-v2 BSDF values", "cannot open the reference files");
        return;
    }
    /* read all value rows */
    while (fgets(line, sizeof line, vf)) {
        char *f[20];
        int n = split(line, f, 20), k;
        if (n < 16 || !strcmp(f[0], "id")) continue;
        if (nrows == cap) rows = realloc(rows, sizeof *rows * (size_t)(cap = cap ? 2 * cap : 1024));
        snprintf(rows[nrows].id, sizeof rows[nrows].id, "%s", f[0]);
        snprintf(rows[nrows].kind, sizeof rows[nrows].kind, "%s", f[1]);
        for (k = 2; k < 16; ++k) rows[nrows].v[k - 2] = num(f[k]);
        rows[nrows].n = 14;
        nrows++;
    }
    fclose(vf);
    fprintf(fi, "mode pbrt-v2\n");
    while (fgets(line, sizeof line, cf) && nid < 64) {
        char *tab = strchr(line, '\t'), *hash;
        line[strcspn(line, "\r\n")] = 0;
        if (!tab) continue;
        *tab = 0;
        snprintf(ids[nid], sizeof ids[nid], "%.63s", line);
        ng[nid][0] = 0;
        if ((hash = strstr(tab + 1, "# ng="))) {
            double x, y, z;
            if (sscanf(hash + 5, "%lf,%lf,%lf", &x, &y, &z) == 3)
                snprintf(ng[nid], sizeof ng[nid], "%.9g %.9g %.9g", x, y, z);
            *hash = 0;
        }
        /* the configuration's statements, in their own attribute block */
        fprintf(fi, "AttributeBegin\n%s\nat ng %s\n", tab + 1, ng[nid][0] ? ng[nid] : "0 0 1");
        for (i = 0; i < nrows; ++i) {
            const double *v = rows[i].v;
            if (strcmp(rows[i].id, ids[nid])) continue;
            if (!strcmp(rows[i].kind, "eval"))
                fprintf(fi, "eval %.9g %.9g %.9g %.9g %.9g %.9g\n", v[0], v[1], v[2], v[3], v[4], v[5]);
            else
                fprintf(fi, "sample %.9g %.9g %.9g %.9g %.9g %.9g\n", v[0], v[1], v[2], v[6], v[7], v[8]);
        }
        fprintf(fi, "bssrdf\nAttributeEnd\n");
        nid++;
    }
    fclose(cf);
    fclose(fi);
    if (run_tool(tool, in, out) != 0 || !(fo = fopen(out, "r"))) {
        t_fail("pbrt-v2 BSDF values", "the query tool failed");
        free(rows);
        return;
    }
    /* answers come in the order of the input's answering lines */
    fgets(line, sizeof line, fo); /* mode */
    {
        char bname[128];
        double bss[64][7];
        int have_bss[64] = {0}, c;
        for (c = 0; c < nid; ++c) {
            int nrow = 0, bad = 0, shown = 0;
            fgets(line, sizeof line, fo); /* AttributeBegin */
            fgets(line, sizeof line, fo); /* the statements: ok */
            if (strncmp(line, "ok", 2)) {
                line[strcspn(line, "\n")] = 0;
                t_fail(ids[c], "statements rejected: %s", line);
            }
            fgets(line, sizeof line, fo); /* at ng */
            for (i = 0; i < nrows; ++i) {
                char why[512];
                if (strcmp(rows[i].id, ids[c])) continue;
                if (!fgets(line, sizeof line, fo)) break;
                line[strcspn(line, "\n")] = 0;
                nrow++;
                if (!(strcmp(rows[i].kind, "eval") ? cmp_sample : cmp_eval)(&rows[i], line, why, sizeof why)) {
                    bad++;
                    if (shown++ < 3) printf("  %s %s row %d: %s\n", ids[c], rows[i].kind, nrow, why);
                }
            }
            snprintf(bname, sizeof bname, "pbrt-v2 values %.63s (materia-query)", ids[c]);
            verdict(bname, nrow, bad, 400);
            fgets(line, sizeof line, fo); /* bssrdf */
            have_bss[c] = sscanf(line, "%lf %lf %lf %lf %lf %lf %lf", &bss[c][0], &bss[c][1], &bss[c][2], &bss[c][3],
                                 &bss[c][4], &bss[c][5], &bss[c][6]) == 7;
            fgets(line, sizeof line, fo); /* AttributeEnd */
        }
        fclose(fo);
        /* BSSRDF coefficients */
        snprintf(path, sizeof path, "%s/reference/pbrt-v2-values/bssrdf-values.csv", shared);
        if ((vf = fopen(path, "r"))) {
            while (fgets(line, sizeof line, vf)) {
                char *f[10];
                int n = split(line, f, 10), k, ok = 1;
                if (n < 8 || !strcmp(f[0], "id")) continue;
                for (c = 0; c < nid && strcmp(ids[c], f[0]); ++c) {
                }
                if (c == nid || !have_bss[c]) {
                    t_fail(f[0], "no BSSRDF answered");
                    continue;
                }
                for (k = 0; k < 7; ++k)
                    if (!close_rel(bss[c][k], num(f[k + 1]), 1e-5)) ok = 0;
                snprintf(bname, sizeof bname, "pbrt-v2 BSSRDF %.64s (materia-query)", f[0]);
                t_check(ok, bname, "sigma_a %.9g %.9g %.9g sigma'_s %.9g %.9g %.9g eta %.9g; pbrt-v2 %s %s %s %s %s %s %s",
                        bss[c][0], bss[c][1], bss[c][2], bss[c][3], bss[c][4], bss[c][5], bss[c][6], f[1], f[2], f[3],
                        f[4], f[5], f[6], f[7]);
            }
            fclose(vf);
        }
    }
    free(rows);
}

/* Texture rows: each configuration declares "t" (after its transforms). */
static void texture_values(const char *tool, const char *tmp)
{
    char path[1024], in[1100], out[1100], line[4096];
    FILE *cf, *vf, *fi, *fo;
    char ids[64][64];
    int is_float[64];
    int nid = 0, c;
    row *rows = NULL;
    int nrows = 0, cap = 0, i;
    snprintf(path, sizeof path, "%s/reference/pbrt-v2-values/texture-values.csv", shared);
    vf = fopen(path, "r");
    snprintf(path, sizeof path, "%s/reference/pbrt-v2-values/texture-configs.txt", shared);
    cf = fopen(path, "r");
    snprintf(in, sizeof in, "%s/tex.in", tmp);
    snprintf(out, sizeof out, "%s/tex.out", tmp);
    fi = fopen(in, "w");
    if (!cf || !vf || !fi) {
        t_fail("pbrt-v2 texture values", "cannot open the reference files");
        return;
    }
    while (fgets(line, sizeof line, vf)) {
        char *f[24];
        int n = split(line, f, 24), k;
        if (n < 17 || !strcmp(f[0], "id")) continue;
        if (nrows == cap) rows = realloc(rows, sizeof *rows * (size_t)(cap = cap ? 2 * cap : 2048));
        snprintf(rows[nrows].id, sizeof rows[nrows].id, "%s", f[0]);
        for (k = 1; k < n && k - 1 < MAXF; ++k) rows[nrows].v[k - 1] = num(f[k]);
        rows[nrows].n = n - 1;
        nrows++;
    }
    fclose(vf);
    fprintf(fi, "mode pbrt-v2\n");
    while (fgets(line, sizeof line, cf) && nid < 64) {
        char *t1 = strchr(line, '\t'), *t2;
        line[strcspn(line, "\r\n")] = 0;
        if (!t1 || !(t2 = strchr(t1 + 1, '\t'))) continue;
        *t1 = *t2 = 0;
        snprintf(ids[nid], sizeof ids[nid], "%.63s", line);
        is_float[nid] = !strcmp(t1 + 1, "float");
        fprintf(fi, "AttributeBegin\n%s\n", t2 + 1);
        for (i = 0; i < nrows; ++i) {
            const double *v = rows[i].v;
            if (strcmp(rows[i].id, ids[nid])) continue;
            /* columns: p(0-2) u v(3,4) dudx dudy dvdx dvdy (5-8) dpdx(9-11) dpdy(12-14) */
            fprintf(fi, "at p %.9g %.9g %.9g uv %.9g %.9g duvdx %.9g %.9g duvdy %.9g %.9g dpdx %.9g %.9g %.9g dpdy %.9g %.9g %.9g\n",
                    v[0], v[1], v[2], v[3], v[4], v[5], v[7], v[6], v[8], v[9], v[10], v[11], v[12], v[13], v[14]);
            fprintf(fi, "texture \"t\"\n");
        }
        fprintf(fi, "AttributeEnd\n");
        nid++;
    }
    fclose(cf);
    fclose(fi);
    if (run_tool(tool, in, out) != 0 || !(fo = fopen(out, "r"))) {
        t_fail("pbrt-v2 texture values", "the query tool failed");
        free(rows);
        return;
    }
    fgets(line, sizeof line, fo);
    for (c = 0; c < nid; ++c) {
        int nrow = 0, bad = 0, shown = 0, nan_rows = 0, absent = 0;
        char name[128];
        fgets(line, sizeof line, fo); /* AttributeBegin */
        fgets(line, sizeof line, fo); /* statements */
        if (strncmp(line, "ok", 2)) {
            line[strcspn(line, "\n")] = 0;
            /* an image format this build left out (make NO_EXR=1) */
            if ((absent = strstr(line, "this build of materia has no") != NULL))
                t_skip(ids[c], "%s", line);
            else
                t_fail(ids[c], "statements rejected: %s", line);
        }
        for (i = 0; i < nrows; ++i) {
            double got[3];
            const double *v = rows[i].v;
            int k, ok = 1, ng;
            if (strcmp(rows[i].id, ids[c])) continue;
            fgets(line, sizeof line, fo); /* at */
            if (!fgets(line, sizeof line, fo)) break;
            nrow++;
            ng = sscanf(line, "%lf %lf %lf", &got[0], &got[1], &got[2]);
            if (ng != (is_float[c] ? 1 : 3)) ok = 0;
            if (ok && isnan(v[15])) {
                /* pbrt-v2 answered NaN: one-sided footprints crossing a check
                 * edge (erratum checker-one-sided); materia's answer must be
                 * finite, and the row is listed, not compared */
                nan_rows++;
                line[strcspn(line, "\n")] = 0;
                printf("  %s row %d: pbrt-v2 NaN (erratum checker-one-sided), materia %s\n", ids[c], nrow, line);
                for (k = 0; k < ng; ++k)
                    if (!isfinite(got[k])) ok = 0;
                if (!ok) bad++;
                continue;
            }
            for (k = 0; ok && k < ng; ++k)
                if (!close_rel(got[k], v[15 + k], 1e-4)) ok = 0;
            if (!ok) {
                bad++;
                line[strcspn(line, "\n")] = 0;
                if (shown++ < 3)
                    printf("  %s row %d (p %g %g %g uv %g %g): %s; pbrt-v2 %.9g %.9g %.9g\n", ids[c], nrow, v[0], v[1],
                           v[2], v[3], v[4], line, v[15], v[16], v[17]);
            }
        }
        fgets(line, sizeof line, fo); /* AttributeEnd */
        snprintf(name, sizeof name, "pbrt-v2 texture values %.63s (materia-query)", ids[c]);
        if (absent) continue;
        verdict(name, nrow, bad, 108);
        if (nan_rows)
            t_xfail(name, "%d rows where pbrt-v2 returns NaN (erratum checker-one-sided) answered finite", nan_rows);
    }
    fclose(fo);
    free(rows);
}

/* Bump rows: the bumped shading frame at real sphere intersections. */
static void bump_values(const char *tool, const char *tmp)
{
    char path[1024], in[1100], out[1100], line[8192], config[4096] = "";
    FILE *cf, *vf, *fi, *fo;
    row *rows = NULL;
    int nrows = 0, cap = 0, i, bad = 0, shown = 0;
    snprintf(path, sizeof path, "%s/reference/pbrt-v2-values/bump-configs.txt", shared);
    cf = fopen(path, "r");
    snprintf(path, sizeof path, "%s/reference/pbrt-v2-values/bump-values.csv", shared);
    vf = fopen(path, "r");
    snprintf(in, sizeof in, "%s/bump.in", tmp);
    snprintf(out, sizeof out, "%s/bump.out", tmp);
    fi = fopen(in, "w");
    if (!cf || !vf || !fi || !fgets(config, sizeof config, cf)) {
        t_fail("pbrt-v2 bump values", "cannot open the reference files");
        return;
    }
    fclose(cf);
    config[strcspn(config, "\r\n")] = 0;
    while (fgets(line, sizeof line, vf)) {
        char *f[48];
        int n = split(line, f, 48), k;
        if (n < 41 || !strcmp(f[0], "id")) continue;
        if (nrows == cap) rows = realloc(rows, sizeof *rows * (size_t)(cap = cap ? 2 * cap : 256));
        for (k = 1; k < n && k - 1 < MAXF; ++k) rows[nrows].v[k - 1] = num(f[k]);
        nrows++;
    }
    fclose(vf);
    fprintf(fi, "mode pbrt-v2\n%s\n", strchr(config, '\t') ? strchr(config, '\t') + 1 : config);
    for (i = 0; i < nrows; ++i) {
        const double *v = rows[i].v;
        /* ro, p(1-3), uv(4,5), n(6-8), dpdu(9-11), dpdv(12-14), dndu(15-17),
         * dndv(18-20), dudx dudy dvdx dvdy (21-24), dpdx(25-27), dpdy(28-30) */
        fprintf(fi, "at flip %d p %.9g %.9g %.9g uv %.9g %.9g n %.9g %.9g %.9g ng %.9g %.9g %.9g dpdu %.9g %.9g %.9g dpdv %.9g %.9g %.9g "
                    "dndu %.9g %.9g %.9g dndv %.9g %.9g %.9g duvdx %.9g %.9g duvdy %.9g %.9g dpdx %.9g %.9g %.9g dpdy %.9g %.9g %.9g\nshading\n",
                (int)v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8], v[6], v[7], v[8], v[9], v[10], v[11], v[12],
                v[13], v[14], v[15], v[16], v[17], v[18], v[19], v[20], v[21], v[23], v[22], v[24], v[25], v[26], v[27],
                v[28], v[29], v[30]);
    }
    fclose(fi);
    if (run_tool(tool, in, out) != 0 || !(fo = fopen(out, "r"))) {
        t_fail("pbrt-v2 bump values", "the query tool failed");
        free(rows);
        return;
    }
    fgets(line, sizeof line, fo);
    fgets(line, sizeof line, fo);
    if (strncmp(line, "ok", 2)) t_fail("pbrt-v2 bump values", "statements rejected: %s", line);
    for (i = 0; i < nrows; ++i) {
        double s[9];
        int k, ok;
        fgets(line, sizeof line, fo); /* at */
        if (!fgets(line, sizeof line, fo)) break;
        ok = sscanf(line, "%lf %lf %lf %lf %lf %lf %lf %lf %lf", &s[0], &s[1], &s[2], &s[3], &s[4], &s[5], &s[6], &s[7],
                    &s[8]) == 9;
        for (k = 0; ok && k < 9; ++k)
            if (fabs(s[k] - rows[i].v[31 + k]) > 2e-3) ok = 0;
        if (!ok) {
            bad++;
            line[strcspn(line, "\n")] = 0;
            if (shown++ < 3)
                printf("  bump row %d: %s; pbrt-v2 %.6g %.6g %.6g %.6g %.6g %.6g %.6g %.6g %.6g\n", i, line, rows[i].v[31],
                       rows[i].v[32], rows[i].v[33], rows[i].v[34], rows[i].v[35], rows[i].v[36], rows[i].v[37],
                       rows[i].v[38], rows[i].v[39]);
        }
    }
    fclose(fo);
    free(rows);
    verdict("pbrt-v2 bump values (materia-query)", nrows, bad, 100);
}

int main(int argc, char **argv)
{
    char tool[1024], tmpl[] = "/tmp/materia-pbrtv-XXXXXX", cmd[1100];
    const char *slash;
    (void)argc;
    shared = t_shared_dir();
    if (!shared) {
        t_skip("pbrt-v2 values through materia-query", "../shared is absent");
        return 0;
    }
    /* build/<precision>/tests/this -> build/<precision>/bin/materia-query */
    slash = strrchr(argv[0], '/');
    snprintf(tool, sizeof tool, "%.*s/../bin/materia-query", slash ? (int)(slash - argv[0]) : 1, slash ? argv[0] : ".");
    if (access(tool, X_OK) != 0) {
        t_fail("pbrt-v2 values through materia-query", "%s not found", tool);
        return t_status();
    }
    if (!mkdtemp(tmpl)) {
        t_fail("pbrt-v2 values through materia-query", "no temporary directory");
        return t_status();
    }
    bsdf_values(tool, tmpl);
    texture_values(tool, tmpl);
    bump_values(tool, tmpl);
    snprintf(cmd, sizeof cmd, "rm -rf '%.900s'", tmpl);
    if (system(cmd) != 0) t_fail("cleanup", "could not remove %s", tmpl);
    return t_status();
}
