/*
 * materia-conformance --impl 'COMMAND' (or --impl-inprocess): the options,
 * the conventions the implementation declares, the pool of worker threads
 * (each configuration gets a fresh child, so one that crashes or hangs
 * costs only its own checks), the expected failures of pbrt-v2 mode, the
 * table, --repro files and the JSON report. See docs/CONFORMANCE-SUITE.md.
 */
#include <dlfcn.h>
#include <errno.h>
#include <pthread.h>
#include <regex.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "impl.h"
#include "materia/impl.h"
#include "power.h"

/* --power's samples per direction at most (the pass answers them a chunk
 * at a time: the bound is time, not memory) */
#define POWER_MAX_SAMPLES 1000000000L
/* the configurations a --catalog FILE may hold */
#define MAX_CATALOGS 16

typedef struct cfg_out {
    cf_case c;
    cf_outcome o;
    char repro[CK_NCHECK][2048];
    long samples;   /* --power: its samples per direction (0: the run's) */
    double min_eps[CF_PW_NREF]; /* the smallest reference mismatch (sampler warp, pdf shape) it
                                   catches in 95% of runs (1: none), or -1 */
    int min_by[CF_PW_NREF];     /* by which test (power.h) */
    long queries;   /* eval and sample queries the implementation answered */
} cfg_out;

typedef struct pool {
    cfg_out *out;
    int n, next, hangs;
    const cf_run *run;
    const char *command; /* NULL: materia in this process, or the plugin */
    const mt_impl_plugin *plugin;
    void *plugin_state;
    double timeout;
    cf_conventions conv;
    double eps;
    const cf_repro *repro;
    pthread_mutex_t lock;
} pool;

static void run_one(pool *p, cfg_out *o)
{
    cf_run local = *p->run;
    const cf_run *run = &local;
    cf_impl test, ref, *refp = NULL;
    int r, k;
    if (o->samples) local.cfg.samples = o->samples;
    memset(&o->o, 0, sizeof o->o);
    o->o.status = CF_OK;
    o->min_eps[0] = o->min_eps[1] = -1;
    for (k = 0; k < CK_NCHECK; ++k) o->o.res[k].ok = -1;
    /* materia, the reference, in the implementation's transport */
    if (run->compare) {
        cf_impl_materia(&ref, run->mode);
        ref.conv = p->conv;
        if (ref.ops->open(&ref, &o->c)) {
            if (!strcmp(o->c.source, "builtin")) {
                o->o.status = CF_FAILED;
                snprintf(o->o.msg, sizeof o->o.msg, "the catalog: %.700s", ref.msg);
                ref.ops->close(&ref);
                return;
            }
            snprintf(o->o.no_agreement, sizeof o->o.no_agreement, "%.290s", ref.msg);
            ref.ops->close(&ref);
        } else {
            refp = &ref;
        }
    }
    if (p->command)
        cf_impl_child(&test, run->mode, p->command, p->timeout);
    else if (p->plugin)
        cf_impl_lib(&test, run->mode, p->plugin, p->plugin_state);
    else
        cf_impl_materia(&test, run->mode);
    test.conv = p->conv;
    if (p->command || p->plugin) test.eps = p->eps;
    r = test.ops->open(&test, &o->c);
    if (!r) r = cf_run_case(run, &o->c, &test, refp, NULL, &o->o);
    o->o.agreement = refp != NULL;
    if (r) {
        o->o.status = r == CF_UNSUPPORTED ? CF_UNSUPPORTED : r == CF_NOMEM ? CF_NOMEM : CF_FAILED;
        snprintf(o->o.msg, sizeof o->o.msg, "%s", r == CF_NOMEM && !test.msg[0] ? "out of memory" : test.msg);
    }
    o->queries = test.queries;
    if (test.ops->close(&test) && !r) {
        o->o.status = CF_FAILED;
        snprintf(o->o.msg, sizeof o->o.msg, "%s", test.msg);
    }
    if (test.child.hung) {
        pthread_mutex_lock(&p->lock);
        p->hangs++;
        pthread_mutex_unlock(&p->lock);
    }
    /* pbrt-v2 mode: a check materia fails too, on the same queries and the
     * same way, is pbrt-v2's own behaviour (impl_xfail.c) */
    if (o->o.status == CF_OK && refp && run->mode == MT_MODE_PBRT_V2) {
        int any = 0;
        for (k = 0; k < CK_NCHECK; ++k) any |= o->o.res[k].ok == 0 && cf_checks[k].kind == CF_PHYSICS;
        if (any) {
            cf_impl self;
            cf_outcome mine;
            cf_run quiet = *run;
            quiet.plots = NULL;
            quiet.sample_numbers = 3; /* materia's own */
            memset(&mine, 0, sizeof mine);
            cf_impl_materia(&self, run->mode);
            self.conv = p->conv;
            if (!self.ops->open(&self, &o->c) && !cf_run_case(&quiet, &o->c, &self, refp, &o->o, &mine))
                for (k = 0; k < CK_NCHECK; ++k)
                    if (o->o.res[k].ok == 0 && mine.res[k].ok == 0)
                        o->o.xfail[k] = cf_same_failure(run->cfg.alpha_test, &o->o.res[k], &mine.res[k],
                                                        o->o.res[k].note, sizeof o->o.res[k].note);
            cf_outcome_free(&mine);
            self.ops->close(&self);
        }
    }
    if (refp) ref.ops->close(&ref);
    /* the smallest smooth mismatch its chi-squares could catch */
    if (o->o.status == CF_OK && (o->o.res[CK_CHI2].ok >= 0 || o->o.res[CK_MEAN].ok >= 0))
    {
        cf_power_dir pd[CF_MAX_WO];
        int w, rf, tt;
        memset(pd, 0, sizeof pd);
        for (w = 0; w < o->o.nwo && w < CF_MAX_WO; ++w) {
            pd[w].n = o->o.pw_n[w];
            pd[w].dof = o->o.pw_dof[w];
            pd[w].mdof = o->o.pw_mdof[w];
            memcpy(pd[w].v, o->o.pw_v[w], sizeof pd[w].v);
        }
        for (rf = 0; rf < CF_PW_NREF; ++rf)
            for (tt = 0; tt < CF_PW_NTEST; ++tt) {
                double e = cf_power_min_eps(tt, rf, o->o.nwo, pd, run->cfg.alpha_test, 0.95);
                if (tt == 0 || e < o->min_eps[rf]) {
                    o->min_eps[rf] = e;
                    o->min_by[rf] = tt;
                }
            }
    }
    /* the reproducers of its failures */
    if (p->repro && o->o.status == CF_OK) {
        char msg[300];
        if (cf_repro_write(p->repro, run, &o->c, &o->o, o->repro, msg, sizeof msg))
            fprintf(stderr, "materia-conformance: --repro: %s\n", msg);
    }
    /* the measures and the cells; the verdicts and notes stay for the report */
    cf_outcome_free(&o->o);
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
            p->out[i].o.status = CF_FAILED;
            snprintf(p->out[i].o.msg, sizeof p->out[i].o.msg, "not run: the implementation hung %d times already", hangs);
            continue;
        }
        run_one(p, &p->out[i]);
    }
    return NULL;
}

static void usage(FILE *f, const char *argv0)
{
    fprintf(f,
            "usage: %s --impl 'COMMAND' [--mode pbrt-v2|corrected] [--compare materia|none] [--catalog FILE]...\n"
            "       [--only REGEX] [--skip REGEX] [--check NAME] [--wo K] [--quick] [--samples N] [--cells N] [--significance P]\n"
            "       [--transport importance|radiance] [--sample-numbers 3|2] [--data DIR] [--timeout SECONDS] [--plain]\n"
            "       [--threads N] [--report FILE] [--plots DIR [--plots-all]] [--repro DIR] [--power EPS] [--seed S]\n"
            "       %s --impl-inprocess ...   materia itself, in this process, in place of COMMAND\n"
            "       %s --impl-lib PLUGIN.so [--impl-arg STRING] ...   a plugin (include/materia/impl.h)\n"
            "Runs the material-level suite through COMMAND (run by sh -c), a program that speaks the\n"
            "query protocol of materia-query on its standard input and output.\n"
            "  --impl COMMAND the implementation (required, or --impl-inprocess)\n"
            "  --impl-inprocess  materia itself in this process, instead of COMMAND\n"
            "  --impl-lib P   a plugin (a shared object filling include/materia/impl.h), loaded into this\n"
            "                 process and called in batches, instead of COMMAND\n"
            "  --impl-arg S   with --impl-lib: the string its create() receives (default: none)\n"
            "  --mode M       pbrt-v2 or corrected (corrected, the default: a renderer is compared with the\n"
            "                 physics; every other tool defaults to pbrt-v2)\n"
            "  --compare C    materia (the default): the agreement checks against materia run too;\n"
            "                 none: the physics checks alone\n"
            "  --catalog F    the configurations of F (docs/CONFORMANCE-SUITE.md gives its format), or\n"
            "                 \"builtin\" for the suite's own; several may be given (default: builtin)\n"
            "  --only REGEX   the configurations whose name matches (POSIX extended; default: all, or\n"
            "                 with --quick the quick set); none is an error\n"
            "  --skip REGEX   leave out the configurations whose name matches (default: none)\n"
            "  --check NAME   that check alone (default: all): identity, chi2, pdf integral, chi2 materia,\n"
            "                 furnace MC=quad, furnace, agree f, agree pdf, agree delta, reciprocity,\n"
            "                 helmholtz, extremes\n"
            "  --wo K         the K-th incoming direction of each configuration alone (0 first; default: all)\n"
            "  --significance P  each statistical test at level P (default: 0.01 for the run, Sidak)\n"
            "  --transport T  importance or radiance, the transport applied (default: the implementation's\n"
            "                 answer to \"conventions\", or importance)\n"
            "  --sample-numbers S  3 or 2, the random numbers' convention (default: its answer, or 3)\n"
            "  --data DIR     where the suite writes the files configurations name (default: a\n"
            "                 temporary directory); they reach COMMAND as absolute paths\n"
            "  --timeout S    seconds allowed for each answer, > 0 and at most 1e6 (default 10)\n"
            "  --plain        one query a line, decimal numbers, even to an implementation whose\n"
            "                 conventions announce batch N or numbers hex (default: those when it does;\n"
            "                 docs/PROTOCOL.md)\n"
            "  --samples N    samples per incoming direction, 100 to 1e8 (default 100000, or 40000 through\n"
            "                 the text protocol one query a line (--plain, protocols 1 and 2); --quick 8000)\n"
            "  --cells N      N x (N+1) chi-square cells, 4 to 200 (default 20; --quick 12)\n",
            argv0, argv0, argv0);
    /* two strings: a C99 compiler need take no more than 4095 characters in one */
    fprintf(f,
            "  --power EPS    samples per direction, for each configuration from its pilot, so that a smooth\n"
            "                 sampler warp and a smooth pdf shape of relative size EPS (0.001 to 0.5) are each\n"
            "                 caught in 95%% of runs by chi2 or mean wi (docs/CONFORMANCE-SUITE.md, \"Power\";\n"
            "                 at most 1e9; default: --samples)\n"
            "  --seed S       another draw of every random number of the run, 1 to 2^63 (default: the\n"
            "                 suite's own, 0)\n"
            "  --quick        the reduced set of make check: fewer configurations, directions, samples\n"
            "                 (default: not)\n"
            "  --threads N    configurations run at once, 1 to 16 (default: the number of processors)\n"
            "  --report FILE  the whole result as JSON (schema in docs/CONFORMANCE-SUITE.md; default: none)\n"
            "  --plots DIR    a PNG for every chi-square that fails (default: none)\n"
            "  --plots-all    with --plots: a PNG for every chi-square (default: for the failures)\n"
            "  --repro DIR    for every failure, a file of protocol lines that shows it when piped into\n"
            "                 COMMAND, and the command that re-runs that check alone (default: none)\n"
            "  --help, -h     this help\n"
            "  --version      materia's version and precision\n"
            "Each option is given once (--catalog as often as needed); a value may not begin with \"--\".\n"
            "Exit status: 0 every check passed, 1 a check failed, 2 bad usage.\n");
}

/* The command line of --impl, read. */
typedef struct opts {
    const char *command, *mode, *only, *data, *report, *plots, *compare, *check, *repro, *transport, *snum, *skip;
    const char *lib, *lib_arg;
    double power;
    long seed;
    const mt_impl_plugin *linked; /* mt_impl_run_suite's plugin */
    const char *catalogs[MAX_CATALOGS];
    int ncatalogs, quick, plots_all, cells, threads, inprocess, wo, plain;
    long samples;
    double timeout, significance;
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
static int parse(int argc, char **argv, opts *o, const mt_impl_plugin *linked)
{
    static const char *const valued[] = {"--impl", "--mode", "--only", "--data", "--timeout", "--samples", "--cells",
                                         "--threads", "--report", "--plots", "--compare", "--check", "--wo",
                                         "--significance", "--transport", "--sample-numbers", "--repro", "--catalog",
                                         "--skip", "--impl-lib", "--impl-arg", "--power", "--seed"};
    enum { V_CATALOG = 17 };
    const char *sv[sizeof valued / sizeof valued[0]] = {NULL}; /* their values, in that order */
    size_t k, nv = sizeof valued / sizeof valued[0];
    int i;
    long x;
    memset(o, 0, sizeof *o);
    o->wo = -1;
    o->linked = linked;
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
        if (!strcmp(a, "--quick") || !strcmp(a, "--plots-all") || !strcmp(a, "--impl-inprocess") ||
            !strcmp(a, "--plain")) {
            int *flag = a[2] == 'q'                    ? &o->quick
                        : !strcmp(a, "--plots-all") ? &o->plots_all
                        : !strcmp(a, "--plain")     ? &o->plain
                                                    : &o->inprocess;
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
        if (k == V_CATALOG) {
            if (o->ncatalogs == MAX_CATALOGS) {
                fprintf(stderr, "%s: --catalog is given more than %d times\n", argv[0], MAX_CATALOGS);
                return 2;
            }
            o->catalogs[o->ncatalogs++] = argv[++i];
            continue;
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
    o->compare = sv[10] ? sv[10] : "materia";
    o->check = sv[11];
    o->transport = sv[14];
    o->snum = sv[15];
    o->repro = sv[16];
    o->skip = sv[18];
    o->lib = sv[19];
    o->lib_arg = sv[20];
    if ((o->inprocess != 0) + (o->command != NULL) + (o->lib != NULL) + (linked != NULL) > 1) {
        fprintf(stderr, "%s: %s name two implementations: give one\n", argv[0],
                linked  ? "the linked plugin and --impl, --impl-lib or --impl-inprocess"
                : o->lib ? "--impl-lib and --impl or --impl-inprocess"
                         : "--impl and --impl-inprocess");
        return 2;
    }
    if (o->lib_arg && !o->lib && !linked) {
        fprintf(stderr, "%s: --impl-arg needs --impl-lib\n", argv[0]);
        return 2;
    }
    if (o->lib && !o->lib[0]) {
        fprintf(stderr, "%s: --impl-lib needs the path of a shared object\n", argv[0]);
        return 2;
    }
    if (!o->inprocess && !o->lib && !linked && (!o->command || !o->command[strspn(o->command, " \t\n")])) {
        fprintf(stderr, "%s: --impl needs a command (the program to test, run by sh -c)\n", argv[0]);
        return 2;
    }
    if (strcmp(o->mode, "pbrt-v2") && strcmp(o->mode, "corrected")) {
        fprintf(stderr, "%s: --mode: \"%s\" is neither pbrt-v2 nor corrected\n", argv[0], o->mode);
        return 2;
    }
    if (strcmp(o->compare, "materia") && strcmp(o->compare, "none")) {
        fprintf(stderr, "%s: --compare: \"%s\" is neither materia nor none\n", argv[0], o->compare);
        return 2;
    }
    if (o->check && cf_check_find(o->check) < 0) {
        fprintf(stderr, "%s: --check: \"%s\" is not a check (--impl --help lists them)\n", argv[0], o->check);
        return 2;
    }
    if (o->transport && strcmp(o->transport, "importance") && strcmp(o->transport, "radiance")) {
        fprintf(stderr, "%s: --transport: \"%s\" is neither importance nor radiance\n", argv[0], o->transport);
        return 2;
    }
    if (o->snum && strcmp(o->snum, "3") && strcmp(o->snum, "2")) {
        fprintf(stderr, "%s: --sample-numbers: \"%s\" is neither 3 nor 2\n", argv[0], o->snum);
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
    if (sv[13]) {
        char *e;
        o->significance = strtod(sv[13], &e);
        if (e == sv[13] || *e || !(o->significance > 0) || !(o->significance < 1)) {
            fprintf(stderr, "%s: --significance: \"%s\" is not a probability > 0 and < 1\n", argv[0], sv[13]);
            return 2;
        }
    }
    if (sv[5] && whole(argv[0], "--samples", sv[5], 100, 100000000, &o->samples)) return 2;
    if (sv[21]) {
        char *e;
        o->power = strtod(sv[21], &e);
        if (e == sv[21] || *e || !(o->power >= 0.001) || !(o->power <= 0.5)) {
            fprintf(stderr, "%s: --power: \"%s\" is not a relative size of 0.001 to 0.5\n", argv[0], sv[21]);
            return 2;
        }
        if (sv[5]) {
            fprintf(stderr, "%s: --power and --samples both set the samples: give one\n", argv[0]);
            return 2;
        }
    }
    if (sv[22] && whole(argv[0], "--seed", sv[22], 0, 0x7fffffffffffffffL, &o->seed)) return 2;
    if (sv[6]) {
        if (whole(argv[0], "--cells", sv[6], 4, 200, &x)) return 2;
        o->cells = (int)x;
    }
    if (sv[7]) {
        if (whole(argv[0], "--threads", sv[7], 1, 16, &x)) return 2;
        o->threads = (int)x;
    }
    if (sv[12]) {
        if (whole(argv[0], "--wo", sv[12], 0, CF_MAX_WO - 1, &x)) return 2;
        o->wo = (int)x;
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

/* --plots, --repro and --data DIR: made when missing; an existing file that
 * is not a directory is an error. */
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

static const char *verdict(const cfg_out *o, int k)
{
    return o->o.res[k].ok ? "PASS" : o->o.xfail[k] ? "XFAIL" : "FAIL";
}

typedef struct totals {
    int passed[2], failed[2], xfailed, skipped;
} totals;

/* --report FILE: the whole result as JSON (docs/CONFORMANCE-SUITE.md gives
 * the schema), written to FILE.tmp and renamed. */
static int write_report(const char *path, const cf_run *run, const char *command, const char *impl_name,
                        const cf_conventions *conv, int declared, const cfg_out *out, int n, const totals *t)
{
    char tmp[4200], cv[80];
    FILE *f;
    int i, k, j, first = 1;
    snprintf(tmp, sizeof tmp, "%.4000s.tmp", path);
    if (!(f = fopen(tmp, "w"))) return -1;
    cf_conventions_format(conv, cv, sizeof cv);
    fprintf(f, "{\n  \"schema\": \"materia-conformance-impl 2\",\n  \"command\": ");
    json_str(f, command);
    fprintf(f, ",\n  \"implementation\": ");
    json_str(f, impl_name);
    fprintf(f, ",\n  \"conventions\": ");
    json_str(f, cv);
    fprintf(f, ", \"conventions_declared\": %s", declared ? "true" : "false");
    fprintf(f, ",\n  \"materia\": {\"version\": ");
    json_str(f, mt_version());
    fprintf(f, ", \"precision\": ");
    json_str(f, mt_precision());
    fprintf(f, "},\n  \"mode\": ");
    json_str(f, mt_mode_name(run->mode));
    fprintf(f, ", \"compare\": \"%s\"", run->compare ? "materia" : "none");
    fprintf(f,
            ",\n  \"settings\": {\"samples\": %ld, \"cells\": [%d, %d], \"quick\": %s, \"alpha\": %g, "
            "\"tests\": %ld, \"alpha_test\": %.6g},\n  \"results\": [",
            run->cfg.samples, run->cfg.nphi, run->cfg.nz, run->quick ? "true" : "false", run->cfg.alpha, run->cfg.tests,
            run->cfg.alpha_test);
    for (i = 0; i < n; ++i) {
        const cfg_out *o = &out[i];
        for (k = 0; k < CK_NCHECK + 1; ++k) {
            const cf_result *r = k < CK_NCHECK ? &o->o.res[k] : NULL;
            int bad = o->o.status == CF_FAILED || o->o.status == CF_NOMEM, skip = o->o.status == CF_UNSUPPORTED;
            if ((bad || skip) ? k != CK_NCHECK : (k == CK_NCHECK || r->ok < 0)) continue;
            fprintf(f, "%s\n    {\"configuration\": ", first ? "" : ",");
            first = 0;
            json_str(f, o->c.name);
            fprintf(f, ", \"source\": ");
            json_str(f, o->c.source);
            fprintf(f, ", \"statements\": [");
            for (j = 0; j < o->c.nlines; ++j) {
                if (j) fputs(", ", f);
                json_str(f, o->c.lines[j]);
            }
            fprintf(f, "], \"check\": ");
            json_str(f, r ? cf_checks[k].name : skip ? "unsupported" : "protocol");
            fprintf(f, ", \"kind\": ");
            json_str(f, r ? cf_kind_name(cf_checks[k].kind) : "physics");
            fprintf(f, ", \"verdict\": ");
            json_str(f, r ? verdict(o, k) : skip ? "SKIP" : "FAIL");
            fprintf(f, ", \"statistic\": ");
            json_str(f, r ? r->statistic : o->o.msg);
            fprintf(f, ", \"bound\": ");
            json_str(f, r ? r->bound : skip ? "supported" : "every answer well formed");
            fprintf(f, ", \"note\": ");
            json_str(f, r ? r->note : "");
            fprintf(f, ", \"where\": ");
            json_str(f, r && !r->ok ? r->where : "");
            fprintf(f, ", \"repro\": ");
            json_str(f, r && !r->ok ? o->repro[k] : "");
            fprintf(f, ", \"worst\": [");
            for (j = 0; r && j < CF_WORST && r->worst[j].query[0]; ++j) {
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
    {
        long q = 0;
        for (i = 0; i < n; ++i) q += out[i].queries;
        fprintf(f, "\n  ],\n  \"queries\": %ld,", q);
    }
    fprintf(f,
            "\n  \"physics\": {\"passed\": %d, \"failed\": %d, \"expected_failures\": %d},\n"
            "  \"agreement\": {\"passed\": %d, \"failed\": %d},\n  \"skipped\": %d,\n"
            "  \"passed\": %d,\n  \"failed\": %d,\n  \"expected_failures\": %d\n}\n",
            t->passed[0], t->failed[0], t->xfailed, t->passed[1], t->failed[1], t->skipped, t->passed[0] + t->passed[1],
            t->failed[0] + t->failed[1], t->xfailed);
    if (fclose(f)) {
        remove(tmp);
        return -1;
    }
    return rename(tmp, path);
}

/* The table: one row per configuration and check, a failed row's direction,
 * worst queries and reproducer under it. */
static void print_rows(const cfg_out *out, int n, const char *mode, totals *t)
{
    int i, k, w;
    memset(t, 0, sizeof *t);
    for (i = 0; i < n; ++i) {
        const cfg_out *o = &out[i];
        if (o->o.status == CF_UNSUPPORTED) {
            printf("%-5s %-50s %-9s %-15s %-9s %s\n", "SKIP", o->c.name, mode, "unsupported", "-", o->o.msg);
            t->skipped++;
            continue;
        }
        if (o->o.status != CF_OK) {
            printf("%-5s %-50s %-9s %-15s %-9s %s\n", "FAIL", o->c.name, mode, "protocol", "physics", o->o.msg);
            t->failed[0]++;
            continue;
        }
        for (k = 0; k < CK_NCHECK; ++k) {
            const cf_result *r = &o->o.res[k];
            int kind = cf_checks[k].kind;
            if (r->ok < 0) continue;
            printf("%-5s %-50s %-9s %-15s %-9s %-62s %-18s%s%s\n", verdict(o, k), o->c.name, mode, cf_checks[k].name,
                   cf_kind_name(kind), r->statistic, r->bound, r->note[0] ? " " : "", r->note);
            if (r->ok)
                t->passed[kind]++;
            else if (o->o.xfail[k])
                t->xfailed++;
            else
                t->failed[kind]++;
            if (r->ok || o->o.xfail[k]) continue;
            if (r->where[0]) printf("      at %s\n", r->where);
            for (w = 0; w < CF_WORST && r->worst[w].query[0]; ++w)
                printf("      worst: %s -> expected %s, got %s (err/tol %.3g)\n", r->worst[w].query, r->worst[w].expected,
                       r->worst[w].got, r->worst[w].score);
            if (o->repro[k][0]) printf("      repro: %s\n", o->repro[k]);
        }
        if (o->min_eps[0] >= 0) {
            char pw[300], e[2][80];
            long ns = 0;
            int j;
            for (j = 0; !ns && j < o->o.nwo; ++j) ns = o->o.pw_n[j];
            for (j = 0; j < CF_PW_NREF; ++j)
                if (o->min_eps[j] >= 1)
                    snprintf(e[j], sizeof e[j], "none below 100%%");
                else
                    snprintf(e[j], sizeof e[j], "%.3g%% (%s)", 100 * o->min_eps[j], cf_power_test_name[o->min_by[j]]);
            snprintf(pw, sizeof pw, "caught in 95%% of runs: a sampler warp of %s, a pdf shape of %s; %ld samples per "
                     "direction", e[0], e[1], ns);
            printf("%-5s %-50s %-9s %-15s %-9s %s\n", "POWER", o->c.name, mode, "power", "physics", pw);
        }
        if (o->o.no_agreement[0])
            printf("%-5s %-50s %-9s %-15s %-9s physics only: materia cannot build it (%s)\n", "INFO", o->c.name, mode,
                   "agreement", "agreement", o->o.no_agreement);
    }
}

/* --impl-lib PATH: the plugin's table (and its handle in *dl), or NULL
 * and msg. */
static const mt_impl_plugin *load_plugin(const char *path, void **dl, char *msg, size_t n)
{
    union {
        void *p;
        mt_impl_entry_fn f;
    } entry; /* dlsym's object pointer as a function pointer, as POSIX allows */
    const mt_impl_plugin *p;
    const char *e;
    /* a bare name would be searched on the library path: a file is meant */
    char file[4200];
    snprintf(file, sizeof file, "%s%s", strchr(path, '/') ? "" : "./", path);
    *dl = dlopen(file, RTLD_NOW | RTLD_LOCAL);
    if (!*dl) {
        e = dlerror();
        snprintf(msg, n, "cannot load \"%s\": %s", path, e ? e : "dlopen failed");
        return NULL;
    }
    entry.p = dlsym(*dl, MT_IMPL_ENTRY);
    if (!entry.p) {
        snprintf(msg, n, "\"%s\" exports no %s (include/materia/impl.h)", path, MT_IMPL_ENTRY);
        return NULL;
    }
    if (!(p = entry.f())) snprintf(msg, n, "\"%s\": %s returned NULL", path, MT_IMPL_ENTRY);
    return p;
}

static int impl_main(int argc, char **argv, const mt_impl_plugin *linked);

int cf_impl_main(int argc, char **argv) { return impl_main(argc, argv, NULL); }

int mt_impl_run_suite(const mt_impl_plugin *plugin, int argc, char **argv)
{
    if (!plugin) return 2;
    return impl_main(argc, argv, plugin);
}

static int impl_main(int argc, char **argv, const mt_impl_plugin *linked)
{
    cf_run run;
    opts op;
    const char *data;
    int i, nsel = 0, ncase = 0, capcase = 0, threads, t, need_data = 0, declared = 0, fails, status = 2, have_re = 0;
    int have_skip = 0;
    long nproc = sysconf(_SC_NPROCESSORS_ONLN);
    cf_case *cases = NULL;
    regex_t re, skip_re;
    pool p;
    pthread_t th[16];
    char tmpdir[4096] = "", absdata[4096], impl_name[256] = "materia (in this process)", cv[80];
    char rerun[8192], msg[600];
    cf_repro repro;
    cf_conventions conv = cf_conventions_default();
    double eps = 0;
    totals tot;
    const mt_impl_plugin *plugin = NULL;
    void *dl = NULL, *pstate = NULL;
    const char *what; /* the implementation, in the header and the report */
    char whatbuf[4200], nsamp[80], lines[96] = "";
    if ((i = parse(argc, argv, &op, linked))) return i == 1 ? 0 : 2;
    p.out = NULL;
    p.n = 0;
    memset(&run, 0, sizeof run);
    run.mode = !strcmp(op.mode, "pbrt-v2") ? MT_MODE_PBRT_V2 : MT_MODE_CORRECTED;
    run.compare = !strcmp(op.compare, "materia");
    run.quick = op.quick;
    run.only_check = op.check ? cf_check_find(op.check) : -1;
    run.only_wo = op.wo;
    run.plots = op.plots;
    run.plots_all = op.plots_all;
    run.identity_samples = 4000;
    data = op.data;
    threads = op.threads ? op.threads : nproc > 0 ? (int)(nproc > 16 ? 16 : nproc) : 2;
    if (op.only && regcomp(&re, op.only, REG_EXTENDED | REG_NOSUB)) {
        fprintf(stderr, "%s: --only: \"%s\" is not a regular expression\n", argv[0], op.only);
        return 2;
    }
    have_re = op.only != NULL;
    if (op.skip && regcomp(&skip_re, op.skip, REG_EXTENDED | REG_NOSUB)) {
        fprintf(stderr, "%s: --skip: \"%s\" is not a regular expression\n", argv[0], op.skip);
        goto done;
    }
    have_skip = op.skip != NULL;
    if (!op.ncatalogs) op.catalogs[op.ncatalogs++] = "builtin";
    /* the configurations, their files' directory named "@DATA@" until the
     * selection is known (a usage error makes no directory) */
    for (i = 0; i < op.ncatalogs; ++i) {
        if (!strcmp(op.catalogs[i], "builtin")) {
            int n, j;
            const cf_impl_config *all = cf_impl_configs(&n);
            for (j = 0; j < n; ++j) {
                if (ncase == capcase) {
                    cf_case *nc = realloc(cases, (size_t)(capcase = capcase ? 2 * capcase : 64) * sizeof *nc);
                    if (!nc) goto done;
                    cases = nc;
                }
                if (cf_case_from_config(&cases[ncase], &all[j], NULL)) goto done;
                ncase++;
            }
        } else if (cf_catalog_read(op.catalogs[i], &cases, &ncase, &capcase, msg, sizeof msg)) {
            fprintf(stderr, "%s: --catalog: %s\n", argv[0], msg);
            goto done;
        }
    }
    p.out = calloc((size_t)(ncase ? ncase : 1), sizeof *p.out);
    if (!p.out) goto done;
    for (i = 0; i < ncase; ++i) {
        int j;
        if ((op.only ? regexec(&re, cases[i].name, 0, NULL, 0) != 0 : op.quick && !(cases[i].flags & CF_CASE_QUICK)) ||
            (have_skip && !regexec(&skip_re, cases[i].name, 0, NULL, 0))) {
            cf_case_free(&cases[i]);
            continue;
        }
        for (j = 0; j < cases[i].nlines; ++j) need_data |= strstr(cases[i].lines[j], "@DATA@") != NULL;
        p.out[nsel++].c = cases[i];
    }
    free(cases);
    cases = NULL;
    ncase = 0;
    p.n = nsel;
    if (!nsel) {
        fprintf(stderr, "%s: --only \"%s\" selects no configuration (see docs/CONFORMANCE-SUITE.md for the names)\n",
                argv[0], op.only ? op.only : "");
        goto done;
    }
    if (op.wo >= 0)
        for (i = 0; i < nsel; ++i) {
            cf_v3 wo[CF_MAX_WO];
            int nwo = cf_case_wo(&p.out[i].c, op.quick, wo);
            if (op.wo >= nwo) {
                fprintf(stderr, "%s: --wo %d: \"%s\" has %d incoming directions (0 to %d)\n", argv[0], op.wo,
                        p.out[i].c.name, nwo, nwo - 1);
                goto done;
            }
        }
    if ((op.report && report_writable(argv[0], op.report)) || (run.plots && make_dir(argv[0], "--plots", run.plots)) ||
        (op.repro && make_dir(argv[0], "--repro", op.repro)))
        goto done;
    /* the data directory, absolute: the suite's catalog names files in it */
    if (need_data) {
        if (!data && op.repro) { /* a reproducer names the files: they stay */
            snprintf(absdata, sizeof absdata, "%.4000s/data", op.repro);
            data = absdata;
            if (make_dir(argv[0], "--repro", data)) goto done;
        } else if (!data) {
            const char *tdir = getenv("TMPDIR");
            snprintf(tmpdir, sizeof tmpdir, "%s/materia-impl.XXXXXX", tdir && *tdir ? tdir : "/tmp");
            if (!mkdtemp(tmpdir)) {
                fprintf(stderr, "%s: cannot make a temporary directory: %s\n", argv[0], strerror(errno));
                goto done;
            }
            data = tmpdir;
        } else if (make_dir(argv[0], "--data", data)) {
            goto done;
        }
        if (data[0] != '/') {
            char cwd[2048], rel[4096];
            snprintf(rel, sizeof rel, "%s", data);
            if (!getcwd(cwd, sizeof cwd)) {
                fprintf(stderr, "%s: --data: cannot name the current directory: %s\n", argv[0], strerror(errno));
                goto done;
            }
            snprintf(absdata, sizeof absdata, "%s/%.2000s", cwd, rel);
        } else if (data != absdata) {
            snprintf(absdata, sizeof absdata, "%s", data);
        }
        if (cf_impl_write_data(absdata, msg, sizeof msg)) {
            fprintf(stderr, "%s: writing the data files: %s\n", argv[0], msg);
            goto done;
        }
        for (i = 0; i < nsel; ++i)
            if (cf_case_set_data(&p.out[i].c, absdata)) goto done;
    }
    /* the implementation's conventions: its answer, or the options' */
    if (op.lib || op.linked) {
        plugin = op.linked ? op.linked : load_plugin(op.lib, &dl, msg, sizeof msg);
        if (!plugin || cf_impl_lib_probe(plugin, &conv, &declared, &eps, impl_name, sizeof impl_name, msg, sizeof msg)) {
            fprintf(stderr, "%s: --impl-lib: %s\n", argv[0], msg);
            goto done;
        }
        msg[0] = 0;
        if (plugin->create && !(pstate = plugin->create(op.lib_arg, msg, sizeof msg))) {
            fprintf(stderr, "%s: --impl-lib: the plugin's create(%s%s%s) failed: %s\n", argv[0], op.lib_arg ? "\"" : "",
                    op.lib_arg ? op.lib_arg : "NULL", op.lib_arg ? "\"" : "", msg[0] ? msg : "(no message)");
            goto done;
        }
    } else if (!op.inprocess) {
        if (cf_impl_probe(op.command, op.timeout, &conv, &declared, &eps, impl_name, sizeof impl_name, msg, sizeof msg)) {
            printf("FAIL  %-50s %-9s %-15s %-9s %s\n", "(the implementation)", op.mode, "protocol", "physics", msg);
            printf("0 passed, 1 failed\n");
            status = 1;
            goto done;
        }
    } else {
        snprintf(impl_name, sizeof impl_name, "materia %s precision %s (in this process)", mt_version(), mt_precision());
        declared = 1;
    }
    if (op.transport) conv.transport = !strcmp(op.transport, "radiance") ? CF_RADIANCE : CF_IMPORTANCE;
    if (op.snum) conv.sample_numbers = op.snum[0] - '0';
    if (op.plain) conv.batch = 1, conv.hex = 0;
    run.sample_numbers = conv.sample_numbers;
    /* 100000: a smooth 2% sampler warp of a diffuse lobe is caught in 95%
     * of runs through the text protocol (docs/BENCHMARKS.md), and the whole
     * catalog through materia-query takes less CPU time than 40000 did
     * with one decimal query a line; an implementation that speaks only
     * that (protocols 1 and 2, or --plain) keeps 40000 and its run time */
    run.cfg.samples = op.samples ? op.samples : op.quick ? 8000 : op.command && conv.batch <= 1 ? 40000 : 100000;
    run.cfg.nphi = op.cells ? op.cells : op.quick ? 12 : 20;
    run.cfg.nz = run.cfg.nphi + 1;
    run.cfg.alpha = 0.01;
    {
        cf_case *sel = malloc((size_t)nsel * sizeof *sel);
        if (!sel) goto done;
        for (i = 0; i < nsel; ++i) sel[i] = p.out[i].c;
        /* pbrt-v2 mode: the comparisons with materia's failures count too */
        run.cfg.tests = cf_run_tests(&run, sel, nsel, 1, run.mode == MT_MODE_PBRT_V2 && run.compare);
        free(sel);
    }
    run.cfg.alpha_test = op.significance > 0 ? op.significance : cf_sidak(run.cfg.alpha, run.cfg.tests);
    cf_set_run_seed((uint64_t)op.seed);
    /* --power: each configuration's samples from its pilot (pass.c); an
     * estimate before it sizes the pilot */
    run.power = op.power;
    run.power_max = POWER_MAX_SAMPLES;
    if (op.power > 0)
        for (i = 0; i < nsel; ++i) {
            cf_v3 wo[CF_MAX_WO];
            int nwo = cf_case_wo(&p.out[i].c, op.quick, wo);
            p.out[i].samples = cf_power_samples(op.power, nwo, run.cfg.nphi * run.cfg.nz, run.cfg.nz, run.cfg.alpha_test,
                                                0.95, POWER_MAX_SAMPLES);
            if (p.out[i].samples < 100) p.out[i].samples = 100;
        }
    /* the command line a reproducer re-runs with */
    {
        size_t at = 0;
        at += (size_t)snprintf(rerun + at, sizeof rerun - at, "materia-conformance");
        if (op.inprocess)
            at += (size_t)snprintf(rerun + at, sizeof rerun - at, " --impl-inprocess");
        else if (op.lib)
            at += (size_t)snprintf(rerun + at, sizeof rerun - at, " --impl-lib '%s'%s%s%s", op.lib,
                                   op.lib_arg ? " --impl-arg '" : "", op.lib_arg ? op.lib_arg : "", op.lib_arg ? "'" : "");
        else if (op.linked)
            at += (size_t)snprintf(rerun + at, sizeof rerun - at, " (the linked plugin)");
        else {
            const char *s;
            at += (size_t)snprintf(rerun + at, sizeof rerun - at, " --impl '");
            for (s = op.command; *s && at + 8 < sizeof rerun; ++s)
                at += (size_t)(*s == '\'' ? snprintf(rerun + at, sizeof rerun - at, "'\\''") : snprintf(rerun + at, sizeof rerun - at, "%c", *s));
            at += (size_t)snprintf(rerun + at, sizeof rerun - at, "'");
        }
        at += (size_t)snprintf(rerun + at, sizeof rerun - at, " --mode %s --compare %s", op.mode, op.compare);
        for (i = 0; i < op.ncatalogs; ++i) at += (size_t)snprintf(rerun + at, sizeof rerun - at, " --catalog '%s'", op.catalogs[i]);
        if (need_data && op.repro) at += (size_t)snprintf(rerun + at, sizeof rerun - at, " --data '%s'", absdata);
        if (op.quick) at += (size_t)snprintf(rerun + at, sizeof rerun - at, " --quick");
        if (op.transport) at += (size_t)snprintf(rerun + at, sizeof rerun - at, " --transport %s", op.transport);
        if (op.snum) at += (size_t)snprintf(rerun + at, sizeof rerun - at, " --sample-numbers %s", op.snum);
        if (op.power > 0)
            at += (size_t)snprintf(rerun + at, sizeof rerun - at, " --power %g", op.power);
        else
            at += (size_t)snprintf(rerun + at, sizeof rerun - at, " --samples %ld", run.cfg.samples);
        if (op.seed) at += (size_t)snprintf(rerun + at, sizeof rerun - at, " --seed %ld", op.seed);
        snprintf(rerun + at, sizeof rerun - at, " --cells %d --significance %.6g --timeout %g", run.cfg.nphi,
                 run.cfg.alpha_test, op.timeout);
    }
    repro.dir = op.repro;
    repro.rerun = rerun;
    cf_conventions_format(&conv, cv, sizeof cv);
    if (op.inprocess)
        what = "in this process";
    else if (plugin)
        snprintf(whatbuf, sizeof whatbuf, "plugin %.4000s", op.lib ? op.lib : "(linked)"), what = whatbuf;
    else
        snprintf(whatbuf, sizeof whatbuf, "'%.4000s'", op.command), what = whatbuf;
    /* how the text protocol is spoken (docs/PROTOCOL.md, "Batched queries") */
    if (op.command && !op.inprocess && !plugin && conv.batch > 1)
        snprintf(lines, sizeof lines, "; lines: evals/samples of up to %d triples%s", conv.batch < 256 ? conv.batch : 256,
                 conv.hex ? ", hexadecimal numbers" : "");
    else if (op.command && !op.inprocess && !plugin)
        snprintf(lines, sizeof lines, "; lines: one query each%s", conv.hex ? ", hexadecimal numbers" : "");
    if (op.power > 0)
        snprintf(nsamp, sizeof nsamp, "samples per direction set by --power %g", op.power);
    else
        snprintf(nsamp, sizeof nsamp, "%ld samples per direction", run.cfg.samples);
    printf("materia-conformance --impl %s (materia %s build, mode %s, compare %s): %d configurations, %s%s,\n%d x %d cells at most, %ld statistical tests, each at %.3g (Sidak: %.2g for the whole run)%s, "
           "%g s per answer\nimplementation: %s; conventions: %s (%s)%s\n",
           what, mt_precision(), op.mode, op.compare, nsel, nsamp, op.seed ? ", seeded" : "", run.cfg.nphi, run.cfg.nz, run.cfg.tests,
           run.cfg.alpha_test, run.cfg.alpha, op.significance > 0 ? " [--significance]" : "", op.timeout, impl_name, cv,
           op.transport || op.snum ? "set on the command line" : declared ? "its answer" : "pbrt-v2's: it answers no conventions",
           lines);
    fflush(stdout);
    p.n = nsel;
    p.next = 0;
    p.hangs = 0;
    p.run = &run;
    p.command = op.inprocess || plugin ? NULL : op.command;
    p.plugin = plugin;
    p.plugin_state = pstate;
    p.timeout = op.timeout;
    p.conv = conv;
    p.eps = eps;
    p.repro = op.repro ? &repro : NULL;
    pthread_mutex_init(&p.lock, NULL);
    if (threads > nsel) threads = nsel;
    for (t = 0; t < threads; ++t) pthread_create(&th[t], NULL, worker, &p);
    for (t = 0; t < threads; ++t) pthread_join(th[t], NULL);
    pthread_mutex_destroy(&p.lock);
    print_rows(p.out, nsel, op.mode, &tot);
    fails = tot.failed[0] + tot.failed[1];
    if (op.report && write_report(op.report, &run, op.inprocess ? "(in this process)" : plugin ? what : op.command, impl_name, &conv,
                                  declared, p.out, nsel, &tot)) {
        fprintf(stderr, "%s: --report: cannot write \"%s\": %s\n", argv[0], op.report, strerror(errno));
        fails++;
    }
    printf("physics: %d passed, %d failed, %d expected failures (pbrt-v2's behaviour, which materia shares)\n",
           tot.passed[0], tot.failed[0], tot.xfailed);
    if (run.compare)
        printf("agreement: %d passed, %d failed\n", tot.passed[1], tot.failed[1]);
    else
        printf("agreement: not run (--compare none)\n");
    printf("%d configurations skipped (unsupported)\n", tot.skipped);
    printf("%d passed, %d failed\n", tot.passed[0] + tot.passed[1], fails);
    status = fails ? 1 : 0;
done:
    for (i = 0; i < ncase; ++i) cf_case_free(&cases[i]);
    free(cases);
    for (i = 0; p.out && i < p.n; ++i) cf_case_free(&p.out[i].c);
    free(p.out);
    if (have_re) regfree(&re);
    if (have_skip) regfree(&skip_re);
    if (tmpdir[0]) rm_data(tmpdir);
    if (plugin && plugin->destroy && pstate) plugin->destroy(pstate);
    if (dl) dlclose(dl);
    return status;
}
