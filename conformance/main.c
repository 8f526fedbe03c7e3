/*
 * materia-conformance: the physics checks of every BxDF configuration in the
 * catalog, in both modes, printed as one table (one row per configuration and
 * check: measured statistic and bound). In pbrt-v2 mode a check that fails
 * is re-run with the corrections one at a time: when one erratum's fix makes
 * it pass, the row is an expected failure (XFAIL) naming the erratum and the
 * measured deviation; otherwise it is a failure.
 *
 *   materia-conformance [--full | --lite] [--only REGEX] [--skip REGEX] [--threads N]
 *   materia-conformance --errata             the measured size of each erratum
 *   materia-conformance --dump FILE          values for the float/double comparison
 *   materia-conformance --ulps OTHER_BINARY  compare with the other precision
 *   materia-conformance --impl 'COMMAND' ... another implementation, through
 *                                            the query protocol (impl_main.c)
 *   materia-conformance --write-data DIR     the files the --impl catalog and
 *                                            the vectors name (@DATA@)
 *
 * Exit status 0 when every check passes, 1 when one fails, 2 on a wrong
 * command line (an --only that selects nothing included).
 */
#include <errno.h>
#include <pthread.h>
#include <regex.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "conformance.h"
#include "impl.h"
#include "materia/material.h"

typedef struct job {
    const cf_subject *s;
    cf_rows rows;
} job;

typedef struct pool {
    job *jobs;
    int njobs, next;
    const cf_run *run;
    pthread_mutex_t lock;
} pool;

static void add_row(cf_rows *rows, const cf_subject *s, mt_mode mode, const char *check, const char *statistic,
                    const char *bound, cf_verdict v, const char *note, const char *detail)
{
    cf_row row;
    memset(&row, 0, sizeof row);
    snprintf(row.subject, sizeof row.subject, "%s", s->name);
    snprintf(row.mode, sizeof row.mode, "%s", mt_mode_name(mode));
    snprintf(row.check, sizeof row.check, "%s", check);
    snprintf(row.kind, sizeof row.kind, "physics");
    snprintf(row.statistic, sizeof row.statistic, "%s", statistic);
    snprintf(row.bound, sizeof row.bound, "%s", bound);
    snprintf(row.note, sizeof row.note, "%s", note ? note : "");
    snprintf(row.detail, sizeof row.detail, "%s", detail ? detail : "");
    row.verdict = v;
    cf_rows_add(rows, &row);
}

/* Every check of s in one mode: the core's pass on materia's BSDF. */
static int run_checks(const cf_subject *s, mt_mode mode, const cf_run *run0, cf_outcome *o, char *msg, size_t n)
{
    cf_case c;
    cf_impl im;
    cf_run run = *run0;
    int r;
    run.mode = mode;
    cf_subject_case(s, &c);
    memset(o, 0, sizeof *o);
    cf_impl_materia(&im, mode);
    r = im.ops->open(&im, &c);
    if (!r) r = cf_run_case(&run, &c, &im, NULL, NULL, o);
    if (r) snprintf(msg, n, "%s", im.msg[0] ? im.msg : "out of memory");
    im.ops->close(&im);
    return r;
}

/* The lines under a failed row: its direction and cells, its worst queries. */
static void detail_of(const cf_result *r, char *out, size_t n)
{
    size_t at = 0;
    int w;
    out[0] = 0;
    if (r->where[0]) at += (size_t)snprintf(out, n, "      at %s\n", r->where);
    for (w = 0; w < CF_WORST && r->worst[w].query[0] && at < n; ++w)
        at += (size_t)snprintf(out + at, n - at, "      worst: %s -> expected %.120s, got %.120s (err/tol %.3g)\n",
                               r->worst[w].query, r->worst[w].expected, r->worst[w].got, r->worst[w].score);
}

/* Attribution of a pbrt-v2-mode failure to errata: starting from every
 * correction of the BxDF, BSDF and material layers, drop each correction the
 * check still passes without; what remains is an irreducible set of errata
 * that explains the failure. The reruns use fewer samples and cells: they
 * label a failure whose size the full run has measured. Their verdicts are
 * kept per mode because every failing check of a subject asks the same
 * questions. */
typedef struct memo {
    mt_mode mode[32];
    signed char ok[32][CK_NCHECK];
    int ran[32];
    int n;
} memo;

static const signed char *checks_in(const cf_subject *s, const cf_run *run, mt_mode mode, memo *m)
{
    int i, k;
    cf_outcome o;
    char msg[200];
    for (i = 0; i < m->n; ++i)
        if (m->mode[i] == mode) return m->ran[i] ? m->ok[i] : NULL;
    if (m->n == 32) return NULL;
    m->mode[m->n] = mode;
    m->ran[m->n] = run_checks(s, mode, run, &o, msg, sizeof msg) == 0;
    for (k = 0; k < CK_NCHECK; ++k) m->ok[m->n][k] = (signed char)o.res[k].ok;
    cf_outcome_free(&o);
    return m->ran[m->n++] ? m->ok[m->n - 1] : NULL;
}

static void attribute(const cf_subject *s, const cf_run *run, int k, memo *m, char *note, size_t n)
{
    int count, i;
    const mt_erratum *e = mt_errata(&count);
    mt_mode set = 0;
    const signed char *r;
    cf_run lite = *run;
    lite.cfg.samples = 20000;
    lite.cfg.nphi = 16;
    lite.cfg.nz = 17;
    lite.plots = NULL;
    note[0] = 0;
    for (i = 0; i < count; ++i)
        if (e[i].bit && (!strcmp(e[i].layer, "bxdf") || !strcmp(e[i].layer, "bsdf") || !strcmp(e[i].layer, "material")))
            set |= e[i].bit;
    /* a check the correction makes pass, or makes moot (pbrt-v2's scaled
     * specular lobe has a pdf where the corrected one has no density to
     * test), is explained by it */
    r = checks_in(s, &lite, set, m);
    if (!r || r[k] == 0) return;
    for (i = 0; i < count; ++i) {
        if (!(set & e[i].bit)) continue;
        r = checks_in(s, &lite, set & ~e[i].bit, m);
        if (r && r[k] != 0) set &= ~e[i].bit;
    }
    for (i = 0; i < count; ++i)
        if (set & e[i].bit) {
            size_t l = strlen(note);
            snprintf(note + l, n - l, "%s%s", l ? " + " : "erratum ", e[i].id);
        }
}

static void run_subject(const cf_subject *s, const cf_run *run, cf_rows *rows)
{
    int mi, k;
    memo *m = calloc(1, sizeof *m);
    for (mi = 0; mi < 2; ++mi) {
        mt_mode mode = mi ? MT_MODE_CORRECTED : MT_MODE_PBRT_V2;
        cf_outcome o;
        char msg[800], detail[1400];
        if (run_checks(s, mode, run, &o, msg, sizeof msg)) {
            char st[200];
            snprintf(st, sizeof st, "could not run: %.100s", msg);
            add_row(rows, s, mode, "setup", st, "", CF_FAIL, NULL, NULL);
            cf_outcome_free(&o);
            continue;
        }
        for (k = 0; k < CK_NCHECK; ++k) {
            char note[300] = "";
            cf_verdict v;
            const cf_result *r = &o.res[k];
            if (r->ok < 0) continue;
            if (r->ok) {
                v = CF_PASS;
            } else if (mode == MT_MODE_PBRT_V2) {
                if (m) attribute(s, run, k, m, note, sizeof note);
                v = note[0] ? CF_XFAIL : CF_FAIL;
            } else {
                v = CF_FAIL;
            }
            detail_of(r, detail, sizeof detail);
            add_row(rows, s, mode, cf_checks[k].name, r->statistic, r->bound, v, note, v == CF_FAIL ? detail : NULL);
        }
        cf_outcome_free(&o);
    }
    free(m);
}

/* A broken variant must fail at least one check (corrected mode). */
static void run_broken(const cf_subject *s, const cf_run *run, cf_rows *rows)
{
    cf_outcome o;
    char msg[800], by[400] = "", st[200];
    int k, caught = 0;
    if (run_checks(s, MT_MODE_CORRECTED, run, &o, msg, sizeof msg)) {
        snprintf(st, sizeof st, "could not run: %.100s", msg);
        add_row(rows, s, MT_MODE_CORRECTED, "power", st, "", CF_FAIL, NULL, NULL);
        cf_outcome_free(&o);
        return;
    }
    for (k = 0; k < CK_NCHECK; ++k)
        if (o.res[k].ok == 0) {
            size_t l = strlen(by);
            snprintf(by + l, sizeof by - l, "%s%s [%.80s]", caught ? "; " : "", cf_checks[k].name, o.res[k].statistic);
            caught++;
        }
    cf_outcome_free(&o);
    snprintf(st, sizeof st, "caught by %d check%s", caught, caught == 1 ? "" : "s");
    add_row(rows, s, MT_MODE_CORRECTED, "power", st, ">= 1 check fails",
            caught ? CF_PASS : (s->p[7] != 0 ? CF_INFO : CF_FAIL), by, NULL);
}

/* Each material type's largest reflectance over its grid (CONFORMANCE.md asks
 * for it: additive materials exceed 1 when their coefficients sum above 1). */
static void cf_albedo_summary(const job *jobs, int njobs, cf_rows *rows)
{
    int count, t, i, j;
    const char *const *types = mt_material_types(&count);
    for (t = 0; t < count; ++t) {
        double best = -1;
        char where[96] = "";
        cf_row r;
        for (i = 0; i < njobs; ++i) {
            const cf_subject *s = jobs[i].s;
            size_t len = strlen(types[t]);
            if (!s->scene || strncmp(s->name, types[t], len) || s->name[len] != ' ') continue;
            for (j = 0; j < jobs[i].rows.n; ++j) {
                const cf_row *x = &jobs[i].rows.rows[j];
                double lo, hi;
                if (strcmp(x->check, "furnace") || strcmp(x->mode, "corrected")) continue;
                if (sscanf(x->statistic, "rho %lf..%lf", &lo, &hi) == 2 && hi > best) {
                    best = hi;
                    snprintf(where, sizeof where, "%.90s", s->name);
                }
            }
        }
        if (best < 0) continue;
        memset(&r, 0, sizeof r);
        snprintf(r.subject, sizeof r.subject, "albedo: %s", types[t]);
        snprintf(r.mode, sizeof r.mode, "corrected");
        snprintf(r.check, sizeof r.check, "max albedo");
        snprintf(r.statistic, sizeof r.statistic, "max rho %.4f (%s)", best, where);
        snprintf(r.bound, sizeof r.bound, "report");
        r.verdict = CF_INFO;
        cf_rows_add(rows, &r);
    }
}

static void *worker(void *arg)
{
    pool *p = arg;
    for (;;) {
        int i;
        pthread_mutex_lock(&p->lock);
        i = p->next++;
        pthread_mutex_unlock(&p->lock);
        if (i >= p->njobs) break;
        if (p->jobs[i].s->flags & CF_BROKEN)
            run_broken(p->jobs[i].s, p->run, &p->jobs[i].rows);
        else
            run_subject(p->jobs[i].s, p->run, &p->jobs[i].rows);
    }
    return NULL;
}

static int count_verdicts(const cf_rows *r, cf_verdict v) { return cf_rows_count(r, v, NULL); }

static const char usage_text[] =
    "usage: materia-conformance [--full | --lite] [--only REGEX] [--skip REGEX] [--threads N] [--ulps OTHER_BINARY]\n"
    "       materia-conformance --errata | --dump FILE | --write-data DIR | --help | --version\n"
    "       materia-conformance --impl 'COMMAND' ... | --impl-inprocess ... (--impl --help)\n"
    "Runs the physics checks of every BxDF configuration in the catalog, in both modes\n"
    "(docs/CONFORMANCE-SUITE.md).\n"
    "  --full          4000000 samples per direction, 100 x 101 cells at most (slow); default:\n"
    "                  100000 samples, 24 x 25 cells\n"
    "  --lite          20000 samples, 16 x 17 cells (what the sanitizer builds run; default: not)\n"
    "  --only REGEX    only the configurations whose name matches REGEX, a POSIX extended\n"
    "                  regular expression (default: all; \"pointwise\": the checks that are not\n"
    "                  per configuration alone); an error when none does\n"
    "  --skip REGEX    leave out the configurations whose name matches REGEX (default: none)\n"
    "  --threads N     worker threads, 1 to 16 (default: the processors online)\n"
    "  --ulps OTHER    compare with the other precision's materia-conformance (default: not)\n"
    "  --errata        the measured size of each pbrt-v2 erratum, instead of the checks\n"
    "  --write-data DIR  writes the files the --impl catalog and vectors/ name as @DATA@ (two\n"
    "                  spectra and a MERL table) into DIR, instead of the checks\n"
    "  --dump FILE     writes the values the float/double comparison reads, instead of the\n"
    "                  checks\n"
    "  --impl COMMAND  another implementation through the query protocol, instead of the\n"
    "                  suite's own run (--impl --help)\n"
    "  --impl-inprocess  materia itself in this process, as --impl runs it, instead of the\n"
    "                  suite's own run (--impl --help)\n"
    "  --impl-lib PLUGIN.so  a plugin (include/materia/impl.h) loaded into this process, instead\n"
    "                  of the suite's own run (--impl --help, docs/PLUGIN.md)\n"
    "  --help, -h      this help\n"
    "  --version       materia's version and precision\n"
    "Exit status: 0 all passed, 1 a check failed, 2 wrong command line.\n";

int main(int argc, char **argv)
{
    cf_run run;
    int nsub, nbroken, nmat, i, t, nthreads, full = 0, threads;
    const cf_subject *subs = cf_subjects(&nsub), *brk = cf_broken_subjects(&nbroken), *mats = cf_material_subjects(&nmat);
    const cf_subject **sel;
    const char *only = NULL, *skip = NULL;
    regex_t only_re, skip_re;
    int have_only = 0, have_skip = 0;
    pool p;
    pthread_t th[16];
    cf_rows extra = {0, 0, 0};
    const char *ulps_other = NULL;
    long nproc = sysconf(_SC_NPROCESSORS_ONLN);
    for (i = 1; i < argc; ++i)
        if (!strcmp(argv[i], "--impl") || !strcmp(argv[i], "--impl-inprocess") || !strcmp(argv[i], "--impl-lib"))
            return cf_impl_main(argc, argv);
    if (argc == 3 && !strcmp(argv[1], "--write-data")) {
        char msg[512];
        if (mkdir(argv[2], 0777) && errno != EEXIST) {
            fprintf(stderr, "materia-conformance: --write-data: cannot make \"%s\": %s\n", argv[2], strerror(errno));
            return 1;
        }
        if (cf_impl_write_data(argv[2], msg, sizeof msg)) {
            fprintf(stderr, "materia-conformance: --write-data: %s\n", msg);
            return 1;
        }
        return 0;
    }
    threads = nproc > 0 ? (int)(nproc > 16 ? 16 : nproc) : 2;
    for (i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--full"))
            full = 1;
        else if (!strcmp(argv[i], "--lite"))
            full = -1;
        else if (!strcmp(argv[i], "--only") && i + 1 < argc)
            only = argv[++i];
        else if (!strcmp(argv[i], "--skip") && i + 1 < argc)
            skip = argv[++i];
        else if (!strcmp(argv[i], "--threads") && i + 1 < argc) {
            char *end;
            long n = strtol(argv[++i], &end, 10);
            if (end == argv[i] || *end || n < 1 || n > 16) {
                fprintf(stderr, "materia-conformance: --threads needs a whole number from 1 to 16, not \"%s\"\n",
                        argv[i]);
                return 2;
            }
            threads = (int)n;
        } else if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            fputs(usage_text, stdout);
            return 0;
        } else if (!strcmp(argv[i], "--version")) {
            printf("materia-conformance (materia) %s, %s\n", mt_version(), mt_precision());
            return 0;
        } else if (!strcmp(argv[i], "--errata"))
            return cf_errata_report();
        else if (!strcmp(argv[i], "--dump") && i + 1 < argc)
            return cf_dump(argv[++i]) ? 1 : 0;
        else if (!strcmp(argv[i], "--ulps") && i + 1 < argc)
            ulps_other = argv[++i];
        else {
            fprintf(stderr, "materia-conformance: unknown option or missing value: %s\n%s", argv[i], usage_text);
            return 2;
        }
    }
    /* --only and --skip: POSIX extended regular expressions, as everywhere */
    if (only && strcmp(only, "pointwise") && regcomp(&only_re, only, REG_EXTENDED | REG_NOSUB)) {
        fprintf(stderr, "materia-conformance: --only: \"%s\" is not a regular expression\n", only);
        return 2;
    }
    have_only = only && strcmp(only, "pointwise");
    if (skip && regcomp(&skip_re, skip, REG_EXTENDED | REG_NOSUB)) {
        fprintf(stderr, "materia-conformance: --skip: \"%s\" is not a regular expression\n", skip);
        if (have_only) regfree(&only_re);
        return 2;
    }
    have_skip = skip != NULL;
    cf_suite_settings(&run, full);
    run.cfg.only = only;
    run.cfg.threads = threads;
    p.jobs = calloc((size_t)(nsub + nmat + nbroken), sizeof *p.jobs);
    sel = calloc((size_t)(nsub + nmat + nbroken), sizeof *sel);
    if (!p.jobs || !sel) return 2;
    p.njobs = 0;
    for (i = 0; i < nsub + nmat + nbroken; ++i) {
        const cf_subject *s = i < nsub ? &subs[i] : i < nsub + nmat ? &mats[i - nsub] : &brk[i - nsub - nmat];
        if ((only && (!have_only || regexec(&only_re, s->name, 0, NULL, 0))) ||
            (have_skip && !regexec(&skip_re, s->name, 0, NULL, 0)))
            continue;
        sel[p.njobs] = s;
        p.jobs[p.njobs++].s = s;
    }
    if (have_only) regfree(&only_re);
    if (have_skip) regfree(&skip_re);
    if (only && p.njobs == 0 && strcmp(only, "pointwise") != 0) {
        fprintf(stderr, "materia-conformance: --only \"%s\" selects no configuration\n", only);
        free(p.jobs);
        free(sel);
        return 2;
    }
    /* Sidak over every statistical test of the run, as the checks register
     * them (cf_checks[]), per direction, mode and subject */
    run.cfg.tests = cf_suite_tests_of(&run, sel, p.njobs);
    free(sel);
    run.cfg.alpha_test = cf_sidak(run.cfg.alpha, run.cfg.tests);
    printf("materia-conformance (%s build, %s): %d configurations, %ld samples per direction, %dx%d cells at most,\n"
           "%ld statistical tests, each at %.3g (Sidak: %.2g for the whole run)\n",
           mt_precision(), full > 0 ? "full" : full < 0 ? "lite" : "quick", p.njobs, run.cfg.samples, run.cfg.nphi,
           run.cfg.nz, run.cfg.tests, run.cfg.alpha_test, run.cfg.alpha);
    printf("%-5s %-50s %-9s %-15s %-9s %-62s %-18s %s\n", "", "configuration", "mode", "check", "kind", "statistic",
           "bound", "note");
    fflush(stdout);
    p.next = 0;
    p.run = &run;
    pthread_mutex_init(&p.lock, NULL);
    nthreads = threads < p.njobs ? threads : (p.njobs > 0 ? p.njobs : 1);
    for (t = 0; t < nthreads; ++t) pthread_create(&th[t], NULL, worker, &p);
    /* the pair-by-pair checks run here meanwhile */
    if (!only || !strcmp(only, "pointwise")) { /* --only pointwise: these alone */
        cf_light_leak(&extra);
        cf_material_leak(&extra);
        cf_distribution_normalization(&extra);
        cf_furnace_table(&extra);
        cf_rejects_invalid(&extra);
        cf_extreme_grid(&extra);
    }
    if (ulps_other) cf_ulps(ulps_other, &extra);
    for (t = 0; t < nthreads; ++t) pthread_join(th[t], NULL);
    pthread_mutex_destroy(&p.lock);
    {
        int pass = 0, fail = 0, xfail = 0;
        cf_albedo_summary(p.jobs, p.njobs, &extra);
        for (i = 0; i < p.njobs; ++i) {
            cf_rows_print(&p.jobs[i].rows);
            pass += count_verdicts(&p.jobs[i].rows, CF_PASS);
            fail += count_verdicts(&p.jobs[i].rows, CF_FAIL);
            xfail += count_verdicts(&p.jobs[i].rows, CF_XFAIL);
            cf_rows_free(&p.jobs[i].rows);
        }
        cf_rows_print(&extra);
        pass += count_verdicts(&extra, CF_PASS);
        fail += count_verdicts(&extra, CF_FAIL);
        printf("conformance: %d passed, %d failed, %d expected failures (pbrt-v2 errata)\n", pass, fail, xfail);
        cf_rows_free(&extra);
        free(p.jobs);
        return fail ? 1 : 0;
    }
}
