/*
 * materia-conformance: the physics checks of every BxDF configuration in the
 * catalog, in both modes, printed as one table (one row per configuration and
 * check: measured statistic and bound). In pbrt-v2 mode a check that fails
 * is re-run with the corrections one at a time: when one erratum's fix makes
 * it pass, the row is an expected failure (XFAIL) naming the erratum and the
 * measured deviation; otherwise it is a failure.
 *
 *   materia-conformance [--full] [--only TEXT] [--threads N]
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
    const cf_config *cfg;
    pthread_mutex_t lock;
} pool;

static void add_row(cf_rows *rows, const cf_subject *s, mt_mode mode, const char *check,
                    const cf_result *r, cf_verdict v, const char *note)
{
    cf_row row;
    memset(&row, 0, sizeof row);
    snprintf(row.subject, sizeof row.subject, "%s", s->name);
    snprintf(row.mode, sizeof row.mode, "%s", mt_mode_name(mode));
    snprintf(row.check, sizeof row.check, "%s", check);
    snprintf(row.statistic, sizeof row.statistic, "%s", r->statistic);
    snprintf(row.bound, sizeof row.bound, "%s", r->bound);
    snprintf(row.note, sizeof row.note, "%s", note ? note : "");
    row.verdict = v;
    cf_rows_add(rows, &row);
}

enum { K_IDENTITY, K_CHI2, K_INTEGRAL, K_FURNACE_MC, K_FURNACE, K_RECIPROCITY, K_HELMHOLTZ, NCHECK };
static const char *check_names[NCHECK] = {"identity", "chi2", "pdf integral", "furnace MC=quad",
                                          "furnace", "reciprocity", "helmholtz"};

/* Every check of s in one mode; results[k].ok < 0 when not applicable. */
static mt_status run_checks(const cf_subject *s, mt_mode mode, const cf_config *cfg,
                            cf_result results[NCHECK], mt_error *err)
{
    cf_sample_report rep;
    mt_status st;
    int k;
    for (k = 0; k < NCHECK; ++k) {
        memset(&results[k], 0, sizeof results[k]);
        results[k].ok = -1;
    }
    if ((st = cf_sampling_checks(s, mode, cfg, &rep, err))) return st;
    results[K_IDENTITY] = rep.identity;
    if (rep.has_density) {
        results[K_CHI2] = rep.chi2;
        results[K_INTEGRAL] = rep.integral;
    }
    results[K_FURNACE_MC] = rep.furnace_mc;
    results[K_FURNACE] = rep.furnace_bound;
    if (rep.has_density && (st = cf_reciprocity(s, mode, &results[K_RECIPROCITY], err))) return st;
    if ((s->flags & CF_NO_CHI2) && (s->flags & CF_TWO_SIDED) && strstr(s->family, "transmission") &&
        (st = cf_helmholtz(s, mode, &results[K_HELMHOLTZ], err)))
        return st;
    return MT_OK;
}

/* Attribution of a pbrt-v2-mode failure to errata: starting from every
 * correction of the BxDF, BSDF and material layers, drop each correction the
 * check still passes without; what remains is an irreducible set of errata
 * that explains the failure. The reruns use fewer samples and cells: they
 * label a failure whose size the full run has measured. Results are cached
 * per mode because every failing check of a subject asks the same questions. */
typedef struct memo {
    mt_mode mode[32];
    cf_result r[32][NCHECK];
    int ok[32];
    int n;
} memo;

static const cf_result *checks_in(const cf_subject *s, const cf_config *cfg, mt_mode mode, memo *m)
{
    int i;
    mt_error err;
    for (i = 0; i < m->n; ++i)
        if (m->mode[i] == mode) return m->ok[i] ? m->r[i] : NULL;
    if (m->n == 32) return NULL;
    mt_error_clear(&err);
    m->mode[m->n] = mode;
    m->ok[m->n] = run_checks(s, mode, cfg, m->r[m->n], &err) == MT_OK;
    return m->ok[m->n++] ? m->r[m->n - 1] : NULL;
}

static void attribute(const cf_subject *s, const cf_config *cfg, int k, memo *m, char *note, size_t n)
{
    int count, i;
    const mt_erratum *e = mt_errata(&count);
    mt_mode set = 0;
    const cf_result *r;
    cf_config lite = *cfg;
    lite.samples = 20000;
    lite.nphi = 16;
    lite.nz = 17;
    note[0] = 0;
    for (i = 0; i < count; ++i)
        if (e[i].bit && (!strcmp(e[i].layer, "bxdf") || !strcmp(e[i].layer, "bsdf") || !strcmp(e[i].layer, "material")))
            set |= e[i].bit;
    r = checks_in(s, &lite, set, m);
    if (!r || r[k].ok != 1) return;
    for (i = 0; i < count; ++i) {
        if (!(set & e[i].bit)) continue;
        r = checks_in(s, &lite, set & ~e[i].bit, m);
        if (r && r[k].ok == 1) set &= ~e[i].bit;
    }
    for (i = 0; i < count; ++i)
        if (set & e[i].bit) {
            size_t l = strlen(note);
            snprintf(note + l, n - l, "%s%s", l ? " + " : "erratum ", e[i].id);
        }
}

static void run_subject(const cf_subject *s, const cf_config *cfg, cf_rows *rows)
{
    int mi, k;
    memo *m = calloc(1, sizeof *m);
    for (mi = 0; mi < 2; ++mi) {
        mt_mode mode = mi ? MT_MODE_CORRECTED : MT_MODE_PBRT_V2;
        cf_result r[NCHECK];
        mt_error err;
        mt_error_clear(&err);
        if (run_checks(s, mode, cfg, r, &err) != MT_OK) {
            cf_result e;
            memset(&e, 0, sizeof e);
            snprintf(e.statistic, sizeof e.statistic, "could not run: %.100s", err.message);
            add_row(rows, s, mode, "setup", &e, CF_FAIL, NULL);
            continue;
        }
        for (k = 0; k < NCHECK; ++k) {
            char note[160] = "";
            cf_verdict v;
            if (r[k].ok < 0) continue;
            if (r[k].ok) {
                v = CF_PASS;
            } else if (mode == MT_MODE_PBRT_V2) {
                if (m) attribute(s, cfg, k, m, note, sizeof note);
                v = note[0] ? CF_XFAIL : CF_FAIL;
            } else {
                v = CF_FAIL;
            }
            add_row(rows, s, mode, check_names[k], &r[k], v, note);
        }
    }
    free(m);
}

/* A broken variant must fail at least one check (corrected mode). */
static void run_broken(const cf_subject *s, const cf_config *cfg, cf_rows *rows)
{
    cf_result r[NCHECK], verdict;
    mt_error err;
    int k, caught = 0;
    char by[160] = "";
    mt_error_clear(&err);
    memset(&verdict, 0, sizeof verdict);
    if (run_checks(s, MT_MODE_CORRECTED, cfg, r, &err) != MT_OK) {
        snprintf(verdict.statistic, sizeof verdict.statistic, "could not run: %.100s", err.message);
        add_row(rows, s, MT_MODE_CORRECTED, "power", &verdict, CF_FAIL, NULL);
        return;
    }
    for (k = 0; k < NCHECK; ++k)
        if (r[k].ok == 0) {
            size_t l = strlen(by);
            snprintf(by + l, sizeof by - l, "%s%s [%s]", caught ? "; " : "", check_names[k], r[k].statistic);
            caught++;
        }
    snprintf(verdict.statistic, sizeof verdict.statistic, "caught by %d check%s", caught, caught == 1 ? "" : "s");
    snprintf(verdict.bound, sizeof verdict.bound, ">= 1 check fails");
    add_row(rows, s, MT_MODE_CORRECTED, "power", &verdict,
            caught ? CF_PASS : (s->p[7] != 0 ? CF_INFO : CF_FAIL), by);
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
            run_broken(p->jobs[i].s, p->cfg, &p->jobs[i].rows);
        else
            run_subject(p->jobs[i].s, p->cfg, &p->jobs[i].rows);
    }
    return NULL;
}

static int count_verdicts(const cf_rows *r, cf_verdict v)
{
    int i, n = 0;
    for (i = 0; i < r->n; ++i) n += r->rows[i].verdict == v;
    return n;
}

static const char usage_text[] =
    "usage: materia-conformance [--full | --lite] [--only TEXT] [--threads N] [--ulps OTHER_BINARY]\n"
    "       materia-conformance --errata | --dump FILE | --write-data DIR | --help | --version\n"
    "       materia-conformance --impl 'COMMAND' ... (--impl --help)\n"
    "Runs the physics checks of every BxDF configuration in the catalog, in both modes\n"
    "(docs/CONFORMANCE-SUITE.md).\n"
    "  --full          40 times the samples and 10 times the cells (slow)\n"
    "  --lite          fewer samples (what the sanitizer builds run)\n"
    "  --only TEXT     only the configurations whose name contains TEXT (\"pointwise\": the\n"
    "                  pair-by-pair checks alone); an error when none does\n"
    "  --threads N     worker threads, 1 to 16 (default: the processors online)\n"
    "  --ulps OTHER    compare with the other precision's materia-conformance\n"
    "  --errata        the measured size of each pbrt-v2 erratum\n"
    "  --write-data DIR  writes the files the --impl catalog and vectors/ name as @DATA@ (two\n"
    "                  spectra and a MERL table) into DIR\n"
    "  --dump FILE     the values the float/double comparison reads\n"
    "Exit status 0 all passed, 1 a check failed, 2 wrong command line.\n";

int main(int argc, char **argv)
{
    cf_config cfg;
    int nsub, nbroken, nmat, i, t, nthreads;
    const cf_subject *subs = cf_subjects(&nsub), *brk = cf_broken_subjects(&nbroken), *mats = cf_material_subjects(&nmat);
    pool p;
    pthread_t th[16];
    cf_rows extra = {0, 0, 0};
    const char *ulps_other = NULL;
    long nproc = sysconf(_SC_NPROCESSORS_ONLN);
    for (i = 1; i < argc; ++i)
        if (!strcmp(argv[i], "--impl")) return cf_impl_main(argc, argv);
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
    memset(&cfg, 0, sizeof cfg);
    cfg.alpha = 0.01;
    cfg.threads = nproc > 0 ? (int)(nproc > 16 ? 16 : nproc) : 2;
    for (i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--full"))
            cfg.full = 1;
        else if (!strcmp(argv[i], "--lite"))
            cfg.full = -1;
        else if (!strcmp(argv[i], "--only") && i + 1 < argc)
            cfg.only = argv[++i];
        else if (!strcmp(argv[i], "--threads") && i + 1 < argc) {
            char *end;
            long n = strtol(argv[++i], &end, 10);
            if (end == argv[i] || *end || n < 1 || n > 16) {
                fprintf(stderr, "materia-conformance: --threads needs a whole number from 1 to 16, not \"%s\"\n",
                        argv[i]);
                return 2;
            }
            cfg.threads = (int)n;
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
    cfg.samples = cfg.full > 0 ? 4000000 : cfg.full < 0 ? 20000 : 100000;
    cfg.nphi = cfg.full > 0 ? 100 : cfg.full < 0 ? 16 : 32;
    cfg.nz = cfg.full > 0 ? 101 : cfg.full < 0 ? 17 : 33;
    /* Sidak over every statistical test of the run: chi2, integral and the
     * furnace's Monte Carlo comparison, per direction, mode and subject */
    p.jobs = calloc((size_t)(nsub + nmat + nbroken), sizeof *p.jobs);
    p.njobs = 0;
    cfg.tests = 0;
    for (i = 0; i < nsub + nmat + nbroken; ++i) {
        const cf_subject *s = i < nsub ? &subs[i] : i < nsub + nmat ? &mats[i - nsub] : &brk[i - nsub - nmat];
        mt_vec3 wos[8];
        if (cfg.only && !strstr(s->name, cfg.only)) continue;
        p.jobs[p.njobs++].s = s;
        cfg.tests += (long)cf_wo_set(s, wos, 8) * 3 * ((s->flags & CF_BROKEN) ? 1 : 2);
    }
    if (cfg.only && p.njobs == 0 && strcmp(cfg.only, "pointwise") != 0) {
        fprintf(stderr, "materia-conformance: --only \"%s\" selects no configuration\n", cfg.only);
        free(p.jobs);
        return 2;
    }
    cfg.alpha_test = cf_sidak(cfg.alpha, cfg.tests);
    printf("materia-conformance (%s build, %s): %d configurations, %ld samples per direction, %dx%d cells,\n"
           "%ld statistical tests, each at %.3g (Sidak: %.2g for the whole run)\n",
           mt_precision(), cfg.full > 0 ? "full" : cfg.full < 0 ? "lite" : "quick", p.njobs, cfg.samples, cfg.nphi, cfg.nz, cfg.tests,
           cfg.alpha_test, cfg.alpha);
    printf("%-5s %-50s %-9s %-14s %-62s %-18s %s\n", "", "configuration", "mode", "check", "statistic", "bound",
           "note");
    fflush(stdout);
    p.next = 0;
    p.cfg = &cfg;
    pthread_mutex_init(&p.lock, NULL);
    nthreads = cfg.threads < p.njobs ? cfg.threads : (p.njobs > 0 ? p.njobs : 1);
    for (t = 0; t < nthreads; ++t) pthread_create(&th[t], NULL, worker, &p);
    /* the pair-by-pair checks run here meanwhile */
    if (!cfg.only || !strcmp(cfg.only, "pointwise")) { /* --only pointwise: these alone */
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
