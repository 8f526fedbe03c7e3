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
    /* pbrt-v2 mode: a check materia fails too, on the same queries and the
     * same way, is pbrt-v2's own behaviour (impl_xfail.c) */
    if (!o->protocol && run->mode == MT_MODE_PBRT_V2) {
        int any = 0;
        for (k = 0; k < CK_NCHECK; ++k) any |= o->res[k].ok == 0;
        if (any) {
            cf_impl self;
            cf_impl_result mine[CK_NCHECK];
            memset(mine, 0, sizeof mine);
            if (!cf_impl_open(&self, NULL, run->timeout, run->mode, (const char *const *)o->lines, o->nlines) &&
                !cf_impl_checks(run, o->c, &self, &ref, mine))
                for (k = 0; k < CK_NCHECK; ++k)
                    if (o->res[k].ok == 0 && mine[k].ok == 0)
                        o->xfail[k] = cf_impl_same_failure(run, &o->res[k], &mine[k], o->res[k].note,
                                                           sizeof o->res[k].note);
            cf_impl_results_free(mine);
            cf_impl_close(&self);
        }
    }
    cf_impl_results_free(o->res);
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
            "       [--report FILE] [--plots DIR [--plots-all]]\n"
            "Runs the material-level suite through COMMAND (run by sh -c), a program that speaks the\n"
            "query protocol of materia-query on its standard input and output.\n"
            "  --mode M       pbrt-v2 or corrected (the default)\n"
            "  --only REGEX   the configurations whose name matches (POSIX extended); none is an error\n"
            "  --data DIR     where the suite writes the files configurations name (default: a\n"
            "                 temporary directory); they reach COMMAND as absolute paths\n"
            "  --timeout S    seconds allowed for each answer, > 0 and at most 1e6 (default 10)\n"
            "  --samples N    samples per incoming direction, 100 to 1e8 (default 40000; --quick 8000)\n"
            "  --cells N      N x (N+1) chi-square cells, 4 to 200 (default 20; --quick 12)\n"
            "  --quick        the reduced set of make check: fewer configurations, directions, samples\n"
            "  --threads N    configurations run at once, 1 to 16 (default: the number of processors)\n"
            "  --report FILE  the whole result as JSON (schema in docs/CONFORMANCE-SUITE.md)\n"
            "  --plots DIR    a PNG for every chi-square that fails (with --plots-all: every one)\n"
            "Each option is given once; a value may not begin with \"--\".\n"
            "Exit status: 0 every check passed, 1 a check failed, 2 bad usage.\n",
            argv0);
}

/* The command line of --impl, read. */
typedef struct opts {
    const char *command, *mode, *only, *data, *report, *plots;
    int quick, plots_all, cells, threads;
    long samples;
    double timeout;
} opts;

/* A whole number of [lo, hi] (no sign of overflow, nothing after it). */
static int whole(const char *argv0, const char *opt, const char *v, long lo, long hi, long *out)
{
    char *e;
    long x;
    errno = 0;
    x = strtol(v, &e, 10);
    if (e == v || *e || errno || x < lo || x > hi) {
        fprintf(stderr, "%s: %s: \"%s\" is not a whole number of %ld to %ld\n", argv0, opt, v, lo, hi);
        return -1;
    }
    *out = x;
    return 0;
}

/* Reads argv into o: 0 to run, 1 when --help or --version was answered
 * (status 0), 2 on a usage error (the message names the option). Every
 * option that takes a value must have one that is not itself an option:
 * "--impl --help" asks for this help, not for the command "--help". */
static int parse(int argc, char **argv, opts *o)
{
    static const char *const valued[] = {"--impl", "--mode", "--only", "--data", "--timeout", "--samples",
                                         "--cells", "--threads", "--report", "--plots"};
    const char *sv[sizeof valued / sizeof valued[0]] = {NULL}; /* their values, in that order */
    size_t k, nv = sizeof valued / sizeof valued[0];
    int i;
    long x;
    memset(o, 0, sizeof *o);
    for (i = 1; i < argc; ++i)
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            usage(stdout, argv[0]);
            return 1;
        } else if (!strcmp(argv[i], "--version")) {
            printf("materia-conformance (materia) %s, %s\n", mt_version(), mt_precision());
            return 1;
        }
    for (i = 1; i < argc; ++i) {
        const char *a = argv[i];
        if (!strcmp(a, "--quick") || !strcmp(a, "--plots-all")) {
            int *flag = a[2] == 'q' ? &o->quick : &o->plots_all;
            if (*flag) {
                fprintf(stderr, "%s: %s is given twice\n", argv[0], a);
                return 2;
            }
            *flag = 1;
            continue;
        }
        for (k = 0; k < nv && strcmp(a, valued[k]); ++k) continue;
        if (k == nv) {
            fprintf(stderr, "%s: unknown argument \"%s\" (--impl --help lists the options)\n", argv[0], a);
            return 2;
        }
        if (i + 1 >= argc || !strncmp(argv[i + 1], "--", 2)) {
            fprintf(stderr, "%s: %s needs a value%s%s%s\n", argv[0], a, i + 1 < argc ? " (got the option \"" : "",
                    i + 1 < argc ? argv[i + 1] : "", i + 1 < argc ? "\")" : "");
            return 2;
        }
        if (sv[k]) {
            fprintf(stderr, "%s: %s is given twice (\"%s\" and \"%s\")\n", argv[0], a, sv[k], argv[i + 1]);
            return 2;
        }
        sv[k] = argv[++i];
    }
    o->command = sv[0];
    o->mode = sv[1] ? sv[1] : "corrected";
    o->only = sv[2];
    o->data = sv[3];
    o->report = sv[8];
    o->plots = sv[9];
    if (!o->command || !o->command[strspn(o->command, " \t\n")]) {
        fprintf(stderr, "%s: --impl needs a command (the program to test, run by sh -c)\n", argv[0]);
        return 2;
    }
    if (strcmp(o->mode, "pbrt-v2") && strcmp(o->mode, "corrected")) {
        fprintf(stderr, "%s: --mode: \"%s\" is neither pbrt-v2 nor corrected\n", argv[0], o->mode);
        return 2;
    }
    o->timeout = 10;
    if (sv[4]) {
        char *e;
        o->timeout = strtod(sv[4], &e);
        if (e == sv[4] || *e || !(o->timeout > 0) || !(o->timeout <= 1e6)) {
            fprintf(stderr, "%s: --timeout: \"%s\" is not a number of seconds > 0 and <= 1e6\n", argv[0], sv[4]);
            return 2;
        }
    }
    if (sv[5] && whole(argv[0], "--samples", sv[5], 100, 100000000, &o->samples)) return 2;
    if (sv[6]) {
        if (whole(argv[0], "--cells", sv[6], 4, 200, &x)) return 2;
        o->cells = (int)x;
    }
    if (sv[7]) {
        if (whole(argv[0], "--threads", sv[7], 1, 16, &x)) return 2;
        o->threads = (int)x;
    }
    if (o->plots_all && !o->plots) {
        fprintf(stderr, "%s: --plots-all needs --plots DIR\n", argv[0]);
        return 2;
    }
    return 0;
}

/* --report FILE must be writable before the run, not after it: FILE.tmp is
 * created (and removed) where the report will be written. */
static int report_writable(const char *argv0, const char *path)
{
    char tmp[4200];
    struct stat st;
    FILE *f;
    if (!stat(path, &st) && S_ISDIR(st.st_mode)) {
        fprintf(stderr, "%s: --report: \"%s\" is a directory\n", argv0, path);
        return -1;
    }
    snprintf(tmp, sizeof tmp, "%.4000s.tmp", path);
    if (!(f = fopen(tmp, "w"))) {
        fprintf(stderr, "%s: --report: cannot write \"%s\": %s\n", argv0, path, strerror(errno));
        return -1;
    }
    fclose(f);
    remove(tmp);
    return 0;
}

/* --plots DIR and --data DIR: made when missing; an existing file that is
 * not a directory is an error. */
static int make_dir(const char *argv0, const char *opt, const char *dir)
{
    struct stat st;
    const char *why;
    if (!mkdir(dir, 0777)) return 0;
    if (errno != EEXIST)
        why = strerror(errno);
    else if (!stat(dir, &st) && S_ISDIR(st.st_mode))
        return 0;
    else
        why = "a file of that name exists";
    fprintf(stderr, "%s: %s: cannot make the directory \"%s\": %s\n", argv0, opt, dir, why);
    return -1;
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
    opts op;
    const char *data;
    int i, n, nsel = 0, threads, t, passed = 0, failed = 0, xfailed = 0, need_data = 0;
    long nproc = sysconf(_SC_NPROCESSORS_ONLN);
    const cf_impl_config *all = cf_impl_configs(&n);
    regex_t re;
    pool p;
    pthread_t th[16];
    char tmpdir[4096] = "", absdata[4096];
    if ((i = parse(argc, argv, &op))) return i == 1 ? 0 : 2;
    memset(&run, 0, sizeof run);
    run.command = op.command;
    run.timeout = op.timeout;
    run.plots = op.plots;
    run.plots_all = op.plots_all;
    run.mode = !strcmp(op.mode, "pbrt-v2") ? MT_MODE_PBRT_V2 : MT_MODE_CORRECTED;
    data = op.data;
    threads = op.threads ? op.threads : nproc > 0 ? (int)(nproc > 16 ? 16 : nproc) : 2;
    if (op.only && regcomp(&re, op.only, REG_EXTENDED | REG_NOSUB)) {
        fprintf(stderr, "%s: --only: \"%s\" is not a regular expression\n", argv[0], op.only);
        return 2;
    }
    p.out = calloc((size_t)n, sizeof *p.out);
    if (!p.out) return 2;
    for (i = 0; i < n; ++i) {
        if (op.only ? regexec(&re, all[i].name, 0, NULL, 0) != 0 : op.quick && !(all[i].flags & CI_QUICK)) continue;
        p.out[nsel++].c = &all[i];
    }
    if (op.only) regfree(&re);
    if (!nsel || (op.report && report_writable(argv[0], op.report)) ||
        (run.plots && make_dir(argv[0], "--plots", run.plots))) {
        if (!nsel)
            fprintf(stderr, "%s: --only \"%s\" selects no configuration (see docs/CONFORMANCE-SUITE.md for the names)\n",
                    argv[0], op.only ? op.only : "");
        free(p.out);
        return 2;
    }
    run.cfg.samples = op.samples ? op.samples : op.quick ? 8000 : 40000;
    run.cfg.nphi = op.cells ? op.cells : op.quick ? 12 : 20;
    run.cfg.nz = run.cfg.nphi + 1;
    run.cfg.alpha = 0.01;
    run.nwo_max = op.quick ? 2 : 4;
    for (i = 0; i < nsel; ++i) {
        int j;
        for (j = 0; j < CI_MAX_LINES && p.out[i].c->lines[j]; ++j) need_data |= strstr(p.out[i].c->lines[j], "@DATA@") != NULL;
        /* chi2, chi2 materia, pdf integral, furnace MC=quad per direction;
         * in pbrt-v2 mode as many comparisons with materia's failures
         * (impl_xfail.c: its histograms, pdf integral, furnace, identity) */
        run.cfg.tests += (run.mode == MT_MODE_PBRT_V2 ? 8L : 4L) * run.nwo_max *
                         ((p.out[i].c->flags & CI_TWO_SIDED) ? 2 : 1);
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
        } else if (make_dir(argv[0], "--data", data)) {
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
           run.command, mt_precision(), op.mode, nsel, run.cfg.samples, run.cfg.nphi, run.cfg.nz, run.cfg.tests,
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
            printf("%-5s %-44s %-9s %-15s %s\n", "FAIL", o->c->name, op.mode, "protocol", o->protocol_msg);
            failed++;
            continue;
        }
        for (k = 0; k < CK_NCHECK; ++k) {
            const cf_impl_result *r = &o->res[k];
            if (r->ok < 0) continue;
            printf("%-5s %-44s %-9s %-15s %-62s %-18s%s%s\n", verdict(o, k), o->c->name, op.mode,
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
    if (op.report && write_report(op.report, &run, op.mode, p.out, nsel, passed, failed, xfailed)) {
        fprintf(stderr, "%s: --report: cannot write \"%s\": %s\n", argv[0], op.report, strerror(errno));
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
