/*
 * --repro DIR: for each failed check, DIR/<configuration>-<check>.txt, a
 * file of protocol lines (the mode, the configuration's statements and
 * "at" lines, then the queries that show the failure: the worst queries of
 * a pointwise check, every sample of the incoming direction where a
 * statistical one failed) that the implementation answers when it is piped
 * in, with comments (not answered) saying what to look for, and the
 * command that re-runs that one check alone on that one configuration and,
 * for a statistical check, that one direction (--check, --wo), at the
 * run's own significance, so that it gives the same verdict.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "impl.h"

static void slug(const char *s, char *out, size_t n)
{
    size_t j = 0;
    for (; *s && j + 1 < n; ++s)
        out[j++] = (*s >= 'a' && *s <= 'z') || (*s >= 'A' && *s <= 'Z') || (*s >= '0' && *s <= '9') || *s == '.' ||
                           *s == '-'
                       ? *s
                       : '_';
    out[j] = 0;
}

/* name as a POSIX extended regular expression matching it alone, inside
 * single quotes for the shell */
static size_t regex_of(const char *name, char *out, size_t n)
{
    size_t j = 0;
    if (j + 1 < n) out[j++] = '^';
    for (; *name && j + 6 < n; ++name) {
        if (strchr(".[]{}()*+?^$|\\", *name)) out[j++] = '\\';
        if (*name == '\'') {
            memcpy(out + j, "'\\''", 4);
            j += 4;
            continue;
        }
        out[j++] = *name;
    }
    if (j + 1 < n) out[j++] = '$';
    out[j] = 0;
    return j;
}

static int statistical(int k)
{
    return k == CK_CHI2 || k == CK_MEAN || k == CK_INTEGRAL || k == CK_CHI2_MATERIA || k == CK_FURNACE_MC || k == CK_FURNACE;
}

void cf_repro_command(const cf_repro *rp, const cf_run *run, const cf_case *c, int k, int w, char *out, size_t n)
{
    char re[400];
    int at;
    (void)run;
    regex_of(c->name, re, sizeof re);
    at = snprintf(out, n, "%s --only '%s' --check '%s'", rp->rerun, re, cf_checks[k].name);
    if (w >= 0 && at > 0 && (size_t)at < n) snprintf(out + at, n - (size_t)at, " --wo %d", w);
}

int cf_repro_write(const cf_repro *rp, const cf_run *run, const cf_case *c, const cf_outcome *o,
                   char paths[CK_NCHECK][2048], char *msg, size_t nm)
{
    int k, j, r = 0;
    char s[200], path[4096], tmp[4200], cmd[9000], q[200];
    for (k = 0; k < CK_NCHECK; ++k) {
        const cf_result *res = &o->res[k];
        FILE *f;
        int w = statistical(k) ? res->wo : -1;
        paths[k][0] = 0;
        if (res->ok != 0 || o->xfail[k]) continue;
        slug(c->name, s, sizeof s);
        snprintf(path, sizeof path, "%.3000s/%s-%s-%s.txt", rp->dir, s, mt_mode_name(run->mode), cf_checks[k].name);
        for (j = (int)strlen(path) - 1; j > 0 && path[j] != '/'; --j)
            if (path[j] == ' ' || path[j] == '=') path[j] = '_';
        snprintf(tmp, sizeof tmp, "%s.tmp", path);
        if (!(f = fopen(tmp, "w"))) {
            snprintf(msg, nm, "cannot write \"%.200s\"", tmp);
            r = -1;
            continue;
        }
        cf_repro_command(rp, run, c, k, w, cmd, sizeof cmd);
        fprintf(f, "# materia-conformance --repro: \"%s\", check \"%s\" (%s), mode %s: FAIL\n", c->name,
                cf_checks[k].name, cf_kind_name(cf_checks[k].kind), mt_mode_name(run->mode));
        fprintf(f, "# %s (bound: %s)\n", res->statistic, res->bound);
        if (res->where[0]) fprintf(f, "# at %s\n", res->where);
        fprintf(f, "# %s\n", cf_checks[k].what);
        fprintf(f, "# Pipe this file into the implementation (every line but these comments is answered);\n"
                   "# re-run this check alone:\n#   %s\n",
                   cmd);
        fprintf(f, "%s\n", run->mode == MT_MODE_PBRT_V2 ? "mode pbrt-v2" : "mode corrected");
        for (j = 0; j < c->nlines; ++j) fprintf(f, "%s\n", c->lines[j]);
        if (w >= 0 && w < o->nwo) {
            long n = o->pw_n[w] > 0 ? o->pw_n[w] : run->cfg.samples, i; /* --power: the pass's own */
            float (*u)[3] = malloc((size_t)n * sizeof *u);
            if (!u) {
                fclose(f);
                remove(tmp);
                snprintf(msg, nm, "out of memory");
                return -1;
            }
            cf_sample_numbers(c->name, w, 0, run->sample_numbers, n, u);
            fprintf(f, "# the %ld samples of that direction: their histogram against the integral of the pdf over\n"
                       "# the cells named above is the test\n",
                    n);
            for (i = 0; i < n; ++i) {
                cf_q_sample(q, sizeof q, o->wo[w], u[i]);
                fprintf(f, "%s\n", q);
            }
            free(u);
        }
        for (j = 0; j < CF_WORST && res->worst[j].query[0]; ++j) {
            fprintf(f, "# worst %d: expected %s, got %s (err/tol %.3g)\n", j + 1, res->worst[j].expected,
                    res->worst[j].got, res->worst[j].score);
            if (res->worst[j].query2[0] && k == CK_IDENTITY) fprintf(f, "%s\n", res->worst[j].query2);
            fprintf(f, "%s\n", res->worst[j].query);
            if (res->worst[j].query2[0] && k != CK_IDENTITY) fprintf(f, "%s\n", res->worst[j].query2);
        }
        if (fclose(f) || rename(tmp, path)) {
            remove(tmp);
            snprintf(msg, nm, "cannot write \"%.200s\"", path);
            r = -1;
            continue;
        }
        snprintf(paths[k], 2048, "%.300s; alone: %.1700s", path, cmd);
    }
    return r;
}
