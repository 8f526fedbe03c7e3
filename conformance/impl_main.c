/*
 * materia-conformance --impl 'COMMAND': the options, the pool of worker
 * threads (each configuration gets a fresh child, so one that crashes or
 * hangs costs only its own checks), the expected failures of pbrt-v2 mode
 * and the report. See docs/CONFORMANCE-SUITE.md.
 */
#include <errno.h>
#include <pthread.h>
#include <regex.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "impl.h"

typedef struct cfg_out {
    const cf_impl_config *c;
    char *lines[CI_MAX_LINES];
    int nlines;
    int protocol;               /* the implementation failed the protocol */
    char protocol_msg[800];
    cf_impl_result res[CK_NCHECK];
    int xfail[CK_NCHECK];
} cfg_out;

typedef struct pool {
    cfg_out *out;
    int n, next, hangs;
    const cf_impl_run *run;
    pthread_mutex_t lock;
} pool;

static char *subst(const char *line, const char *data)
{
    const char *p = strstr(line, "@DATA@");
    size_t n = strlen(line) + strlen(data) + 1;
    char *s = malloc(n);
    if (!s) return NULL;
    if (!p) {
        memcpy(s, line, strlen(line) + 1);
        return s;
    }
    snprintf(s, n, "%.*s%s%s", (int)(p - line), line, data, p + 6);
    while ((p = strstr(s, "@DATA@"))) { /* more than one */
        char *t = subst(s, data);
        free(s);
        s = t;
        if (!s) return NULL;
    }
    return s;
}

static void run_one(pool *p, cfg_out *o)
{
    const cf_impl_run *run = p->run;
    cf_impl test, ref;
    int r, k;
    if (cf_impl_open(&ref, NULL, run->timeout, run->mode, (const char *const *)o->lines, o->nlines)) {
        o->protocol = 1;
        snprintf(o->protocol_msg, sizeof o->protocol_msg, "the catalog: %.700s", ref.msg);
        cf_impl_close(&ref);
        return;
    }
    if (cf_impl_open(&test, run->command, run->timeout, run->mode, (const char *const *)o->lines, o->nlines)) {
        o->protocol = 1;
        snprintf(o->protocol_msg, sizeof o->protocol_msg, "setup: %.700s", test.msg);
    } else {
        r = cf_impl_checks(run, o->c, &test, &ref, o->res);
        if (r == -2) {
            o->protocol = 1;
            snprintf(o->protocol_msg, sizeof o->protocol_msg, "out of memory");
        } else if (r) {
            o->protocol = 1;
            snprintf(o->protocol_msg, sizeof o->protocol_msg, "%s", test.msg);
        }
    }
    if (cf_impl_close(&test) && !o->protocol) {
        o->protocol = 1;
        snprintf(o->protocol_msg, sizeof o->protocol_msg, "%s", test.msg);
    }
    if (test.child.hung) {
        pthread_mutex_lock(&p->lock);
        p->hangs++;
        pthread_mutex_unlock(&p->lock);
    }
    /* pbrt-v2 mode: a check materia fails too is pbrt-v2's own behaviour */
    if (!o->protocol && run->mode == MT_MODE_PBRT_V2) {
        int any = 0;
        for (k = 0; k < CK_NCHECK; ++k) any |= o->res[k].ok == 0;
        if (any) {
            cf_impl self;
            cf_impl_result mine[CK_NCHECK];
            if (!cf_impl_open(&self, NULL, run->timeout, run->mode, (const char *const *)o->lines, o->nlines) &&
                !cf_impl_checks(run, o->c, &self, &ref, mine))
                for (k = 0; k < CK_NCHECK; ++k)
                    if (o->res[k].ok == 0 && mine[k].ok == 0) {
                        o->xfail[k] = 1;
                        snprintf(o->res[k].note, sizeof o->res[k].note, "materia fails it too in pbrt-v2 mode (%.120s)",
                                 mine[k].statistic);
                    }
            cf_impl_close(&self);
        }
    }
    cf_impl_close(&ref);
}

static void *worker(void *arg)
{
    pool *p = arg;
    for (;;) {
        int i, hangs;
        pthread_mutex_lock(&p->lock);
        i = p->next++;
        hangs = p->hangs;
        pthread_mutex_unlock(&p->lock);
        if (i >= p->n) break;
        if (hangs >= 3) {
            p->out[i].protocol = 1;
            snprintf(p->out[i].protocol_msg, sizeof p->out[i].protocol_msg,
                     "not run: the implementation hung %d times already", hangs);
            continue;
        }
        run_one(p, &p->out[i]);
    }
    return NULL;
}

static void usage(FILE *f, const char *argv0)
{
    fprintf(f,
            "usage: %s --impl 'COMMAND' [--mode pbrt-v2|corrected] [--only REGEX] [--data DIR]\n"
            "       [--timeout SECONDS] [--samples N] [--cells N] [--quick] [--threads N]\n"
            "Runs the material-level suite through COMMAND (run by sh -c), a program that speaks the\n"
            "query protocol of materia-query on its standard input and output.\n"
            "  --mode M       pbrt-v2 or corrected (the default)\n"
            "  --only REGEX   the configurations whose name matches (POSIX extended); none is an error\n"
            "  --data DIR     where the suite writes the files configurations name (default: a\n"
            "                 temporary directory); they reach COMMAND as absolute paths\n"
            "  --timeout S    seconds allowed for each answer (default 10)\n"
            "  --samples N    samples per incoming direction (default 40000; --quick 8000)\n"
            "  --cells N      N x (N+1) chi-square cells (default 20; --quick 12)\n"
            "  --quick        the reduced set of make check: fewer configurations, directions, samples\n"
            "  --threads N    configurations run at once (default: the number of processors)\n"
            "  --report FILE  the whole result as JSON (schema in docs/CONFORMANCE-SUITE.md)\n"
            "  --plots DIR    a PNG for every chi-square that fails (with --plots-all: every one)\n"
            "Exit status: 0 every check passed, 1 a check failed, 2 bad usage.\n",
            argv0);
}

static int rm_data(const char *dir)
{
    static const char *const files[] = {"eta.spd", "k.spd", "plastic.merl"};
    char p[4200];
    size_t i;
    for (i = 0; i < sizeof files / sizeof files[0]; ++i) {
        snprintf(p, sizeof p, "%s/%s", dir, files[i]);
        remove(p);
    }
    return rmdir(dir);
}

/* A JSON string: quotes, backslashes and control characters escaped. */
static void json_str(FILE *f, const char *s)
{
    fputc('"', f);
    for (; *s; ++s) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\')
            fprintf(f, "\\%c", c);
        else if (c < 0x20)
            fprintf(f, "\\u%04x", c);
        else
            fputc(c, f);
    }
    fputc('"', f);
}

static const char *verdict(const cfg_out *o, int k);

/* --report FILE: the whole result as JSON (docs/CONFORMANCE-SUITE.md gives
 * the schema), written to FILE.tmp and renamed. */
static int write_report(const char *path, const cf_impl_run *run, const char *mode_name, const cfg_out *out, int n,
                        int passed, int failed, int xfailed)
{
    char tmp[4200];
    FILE *f;
    int i, k, j, first = 1;
    snprintf(tmp, sizeof tmp, "%.4000s.tmp", path);
    if (!(f = fopen(tmp, "w"))) return -1;
    fprintf(f, "{\n  \"schema\": \"materia-conformance-impl 1\",\n  \"command\": ");
    json_str(f, run->command);
    fprintf(f, ",\n  \"materia\": {\"version\": ");
    json_str(f, mt_version());
    fprintf(f, ", \"precision\": ");
    json_str(f, mt_precision());
    fprintf(f, "},\n  \"mode\": ");
    json_str(f, mode_name);
    fprintf(f,
            ",\n  \"settings\": {\"samples\": %ld, \"cells\": [%d, %d], \"directions_per_side\": %d, \"alpha\": %g, "
            "\"tests\": %ld, \"alpha_test\": %.6g, \"timeout\": %g},\n  \"results\": [",
            run->cfg.samples, run->cfg.nphi, run->cfg.nz, run->nwo_max, run->cfg.alpha, run->cfg.tests,
            run->cfg.alpha_test, run->timeout);
    for (i = 0; i < n; ++i) {
        const cfg_out *o = &out[i];
        for (k = 0; k < CK_NCHECK + 1; ++k) {
            const cf_impl_result *r = k < CK_NCHECK ? &o->res[k] : NULL;
            if (o->protocol ? k != CK_NCHECK : (k == CK_NCHECK || r->ok < 0)) continue;
            fprintf(f, "%s\n    {\"configuration\": ", first ? "" : ",");
            first = 0;
            json_str(f, o->c->name);
            fprintf(f, ", \"statements\": [");
            for (j = 0; j < o->nlines; ++j) {
                if (j) fputs(", ", f);
                json_str(f, o->lines[j]);
            }
            fprintf(f, "], \"check\": ");
            json_str(f, r ? cf_impl_check_names[k] : "protocol");
            fprintf(f, ", \"verdict\": ");
            json_str(f, r ? verdict(o, k) : "FAIL");
            fprintf(f, ", \"statistic\": ");
            json_str(f, r ? r->statistic : o->protocol_msg);
            fprintf(f, ", \"bound\": ");
            json_str(f, r ? r->bound : "every answer well formed");
            fprintf(f, ", \"note\": ");
            json_str(f, r ? r->note : "");
            fprintf(f, ", \"worst\": [");
            for (j = 0; r && j < CI_WORST && r->worst[j].query[0]; ++j) {
                fprintf(f, "%s{\"query\": ", j ? ", " : "");
                json_str(f, r->worst[j].query);
                fprintf(f, ", \"expected\": ");
                json_str(f, r->worst[j].expected);
                fprintf(f, ", \"got\": ");
                json_str(f, r->worst[j].got);
                fprintf(f, ", \"err_over_tol\": %.6g}", r->worst[j].score);
            }
            fprintf(f, "]}");
        }
    }
    fprintf(f, "\n  ],\n  \"passed\": %d,\n  \"failed\": %d,\n  \"expected_failures\": %d\n}\n", passed, failed,
            xfailed);
    if (fclose(f)) {
        remove(tmp);
        return -1;
    }
    return rename(tmp, path);
}

static const char *verdict(const cfg_out *o, int k)
{
    return o->res[k].ok ? "PASS" : o->xfail[k] ? "XFAIL" : "FAIL";
}

int cf_impl_main(int argc, char **argv)
{
    cf_impl_run run;
    const char *only = NULL, *data = NULL, *mode_name = "corrected", *report = NULL;
    int i, n, nsel = 0, quick = 0, threads, t, cells = 0, passed = 0, failed = 0, xfailed = 0, need_data = 0;
    long samples = 0, nproc = sysconf(_SC_NPROCESSORS_ONLN);
    const cf_impl_config *all = cf_impl_configs(&n);
    regex_t re;
    pool p;
    pthread_t th[16];
    char tmpdir[4096] = "", absdata[4096];
    memset(&run, 0, sizeof run);
    run.timeout = 10;
    threads = nproc > 0 ? (int)(nproc > 16 ? 16 : nproc) : 2;
    for (i = 1; i < argc; ++i) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            usage(stdout, argv[0]);
            return 0;
        } else if (!strcmp(a, "--quick")) {
            quick = 1;
            continue;
        } else if (!strcmp(a, "--plots-all")) {
            run.plots_all = 1;
            continue;
        }
        if (!v) {
            fprintf(stderr, "%s: %s needs a value\n", argv[0], a);
            usage(stderr, argv[0]);
            return 2;
        }
        i++;
        if (!strcmp(a, "--impl"))
            run.command = v;
        else if (!strcmp(a, "--mode"))
            mode_name = v;
        else if (!strcmp(a, "--only"))
            only = v;
        else if (!strcmp(a, "--data"))
            data = v;
        else if (!strcmp(a, "--report"))
            report = v;
        else if (!strcmp(a, "--plots"))
            run.plots = v;
        else if (!strcmp(a, "--timeout")) {
            char *e;
            run.timeout = strtod(v, &e);
            if (*e || !(run.timeout > 0) || run.timeout > 1e6) {
                fprintf(stderr, "%s: --timeout: \"%s\" is not a number of seconds > 0\n", argv[0], v);
                return 2;
            }
        } else if (!strcmp(a, "--samples")) {
            char *e;
            samples = strtol(v, &e, 10);
            if (*e || samples < 100 || samples > 100000000) {
                fprintf(stderr, "%s: --samples: \"%s\" is not an integer of 100..1e8\n", argv[0], v);
                return 2;
            }
        } else if (!strcmp(a, "--cells")) {
            char *e;
            cells = (int)strtol(v, &e, 10);
            if (*e || cells < 4 || cells > 200) {
                fprintf(stderr, "%s: --cells: \"%s\" is not an integer of 4..200\n", argv[0], v);
                return 2;
            }
        } else if (!strcmp(a, "--threads")) {
            char *e;
            threads = (int)strtol(v, &e, 10);
            if (*e || threads < 1 || threads > 16) {
                fprintf(stderr, "%s: --threads: \"%s\" is not an integer of 1..16\n", argv[0], v);
                return 2;
            }
        } else {
            fprintf(stderr, "%s: unknown argument \"%s\"\n", argv[0], a);
            usage(stderr, argv[0]);
            return 2;
        }
    }
    if (!run.command || !*run.command) {
        fprintf(stderr, "%s: --impl needs a command\n", argv[0]);
        return 2;
    }
    if (!strcmp(mode_name, "pbrt-v2"))
        run.mode = MT_MODE_PBRT_V2;
    else if (!strcmp(mode_name, "corrected"))
        run.mode = MT_MODE_CORRECTED;
    else {
        fprintf(stderr, "%s: --mode: \"%s\" is neither pbrt-v2 nor corrected\n", argv[0], mode_name);
        return 2;
    }
    if (run.plots_all && !run.plots) {
        fprintf(stderr, "%s: --plots-all needs --plots DIR\n", argv[0]);
        return 2;
    }
    if (run.plots && mkdir(run.plots, 0777) && errno != EEXIST) {
        fprintf(stderr, "%s: --plots: cannot make \"%s\": %s\n", argv[0], run.plots, strerror(errno));
        return 2;
    }
    if (only && regcomp(&re, only, REG_EXTENDED | REG_NOSUB)) {
        fprintf(stderr, "%s: --only: \"%s\" is not a regular expression\n", argv[0], only);
        return 2;
    }
    p.out = calloc((size_t)n, sizeof *p.out);
    if (!p.out) return 2;
    for (i = 0; i < n; ++i) {
        if (only ? regexec(&re, all[i].name, 0, NULL, 0) != 0 : quick && !(all[i].flags & CI_QUICK)) continue;
        p.out[nsel++].c = &all[i];
    }
    if (only) regfree(&re);
    if (!nsel) {
        fprintf(stderr, "%s: --only \"%s\" selects no configuration (see docs/CONFORMANCE-SUITE.md for the names)\n",
                argv[0], only ? only : "");
        free(p.out);
        return 2;
    }
    run.cfg.samples = samples ? samples : quick ? 8000 : 40000;
    run.cfg.nphi = cells ? cells : quick ? 12 : 20;
    run.cfg.nz = run.cfg.nphi + 1;
    run.cfg.alpha = 0.01;
    run.nwo_max = quick ? 2 : 4;
    for (i = 0; i < nsel; ++i) {
        int j;
        for (j = 0; j < CI_MAX_LINES && p.out[i].c->lines[j]; ++j) need_data |= strstr(p.out[i].c->lines[j], "@DATA@") != NULL;
        /* chi2, chi2 materia, pdf integral, furnace MC=quad per direction */
        run.cfg.tests += 4L * run.nwo_max * ((p.out[i].c->flags & CI_TWO_SIDED) ? 2 : 1);
    }
    run.cfg.alpha_test = cf_sidak(run.cfg.alpha, run.cfg.tests);
    /* the data directory, absolute */
    if (need_data) {
        char msg[600];
        if (!data) {
            const char *tdir = getenv("TMPDIR");
            snprintf(tmpdir, sizeof tmpdir, "%s/materia-impl.XXXXXX", tdir && *tdir ? tdir : "/tmp");
            if (!mkdtemp(tmpdir)) {
                fprintf(stderr, "%s: cannot make a temporary directory: %s\n", argv[0], strerror(errno));
                return 2;
            }
            data = tmpdir;
        } else if (mkdir(data, 0777) && errno != EEXIST) {
            fprintf(stderr, "%s: --data: cannot make \"%s\": %s\n", argv[0], data, strerror(errno));
            return 2;
        }
        if (data[0] == '/') {
            snprintf(absdata, sizeof absdata, "%s", data);
        } else {
            char cwd[2048];
            if (!getcwd(cwd, sizeof cwd)) {
                fprintf(stderr, "%s: --data: cannot name the current directory: %s\n", argv[0], strerror(errno));
                return 2;
            }
            snprintf(absdata, sizeof absdata, "%s/%.2000s", cwd, data);
        }
        if (cf_impl_write_data(absdata, msg, sizeof msg)) {
            fprintf(stderr, "%s: writing the data files: %s\n", argv[0], msg);
            if (tmpdir[0]) rm_data(tmpdir);
            return 2;
        }
        run.data = absdata;
    } else {
        run.data = data ? data : ".";
    }
    for (i = 0; i < nsel; ++i) {
        int j;
        for (j = 0; j < CI_MAX_LINES && p.out[i].c->lines[j]; ++j) p.out[i].lines[j] = subst(p.out[i].c->lines[j], run.data);
        p.out[i].nlines = j;
    }
    printf("materia-conformance --impl '%s' (materia %s build, mode %s): %d configurations, %ld samples per direction,\n"
           "%dx%d cells, %ld statistical tests, each at %.3g (Sidak: %.2g for the whole run), %g s per answer\n",
           run.command, mt_precision(), mode_name, nsel, run.cfg.samples, run.cfg.nphi, run.cfg.nz, run.cfg.tests,
           run.cfg.alpha_test, run.cfg.alpha, run.timeout);
    fflush(stdout);
    p.n = nsel;
    p.next = 0;
    p.hangs = 0;
    p.run = &run;
    pthread_mutex_init(&p.lock, NULL);
    if (threads > nsel) threads = nsel;
    for (t = 0; t < threads; ++t) pthread_create(&th[t], NULL, worker, &p);
    for (t = 0; t < threads; ++t) pthread_join(th[t], NULL);
    pthread_mutex_destroy(&p.lock);
    for (i = 0; i < nsel; ++i) {
        cfg_out *o = &p.out[i];
        int k, w;
        if (o->protocol) {
            printf("%-5s %-44s %-9s %-15s %s\n", "FAIL", o->c->name, mode_name, "protocol", o->protocol_msg);
            failed++;
            continue;
        }
        for (k = 0; k < CK_NCHECK; ++k) {
            const cf_impl_result *r = &o->res[k];
            if (r->ok < 0) continue;
            printf("%-5s %-44s %-9s %-15s %-62s %-18s%s%s\n", verdict(o, k), o->c->name, mode_name,
                   cf_impl_check_names[k], r->statistic, r->bound, r->note[0] ? " " : "", r->note);
            if (r->ok)
                passed++;
            else if (o->xfail[k])
                xfailed++;
            else
                failed++;
            if (!r->ok && !o->xfail[k])
                for (w = 0; w < CI_WORST && r->worst[w].query[0]; ++w)
                    printf("      worst: %s -> expected %s, got %s (err/tol %.3g)\n", r->worst[w].query,
                           r->worst[w].expected, r->worst[w].got, r->worst[w].score);
        }
    }
    if (report && write_report(report, &run, mode_name, p.out, nsel, passed, failed, xfailed)) {
        fprintf(stderr, "%s: --report: cannot write \"%s\": %s\n", argv[0], report, strerror(errno));
        failed++;
    }
    for (i = 0; i < nsel; ++i) {
        int j;
        for (j = 0; j < p.out[i].nlines; ++j) free(p.out[i].lines[j]);
    }
    free(p.out);
    if (tmpdir[0]) rm_data(tmpdir);
    printf("%d expected failures (pbrt-v2's behaviour, which materia shares)\n", xfailed);
    printf("%d passed, %d failed\n", passed, failed);
    return failed ? 1 : 0;
}
