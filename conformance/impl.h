/*
 * materia-conformance --impl COMMAND: the material-level suite run through
 * any program that speaks the query protocol (README, "The query tool"),
 * and, for reference, through materia itself in-process. See
 * docs/CONFORMANCE-SUITE.md, "Testing another implementation".
 */
#ifndef CF_IMPL_H
#define CF_IMPL_H

#include "child.h"
#include "conformance.h"
#include "strbuf.h"
#include "materia/tools/query.h"

/* ---- one implementation: a child process, or materia in-process -------- */
typedef struct cf_eval {
    double f[3], pdf;
} cf_eval;

typedef struct cf_samp {
    double wi[3], f[3], pdf;
    unsigned flags;
} cf_samp;

typedef struct cf_impl {
    int inproc;          /* materia itself (mt_query and its BSDF) */
    cf_child child;
    mt_query *q;
    mt_arena *arena;
    mt_bsdf *bsdf;
    const char *mode_line; /* "mode corrected": ends each batch (answered ok) */
    char msg[800];       /* the protocol failure, when failed */
    int failed;
    cf_strbuf text;      /* the batch being written */
    const char **ans;
    int ans_cap;
    long queries;        /* answered so far */
} cf_impl;

/* Starts command (NULL: materia in-process) and sends the mode line and the
 * configuration's lines (statements, at), each to be answered "ok". */
int cf_impl_open(cf_impl *im, const char *command, double timeout, mt_mode mode, const char *const *lines,
                 int nlines);
/* n evals / samples; 0, or -1 with msg naming the query at fault. Directions
 * and random numbers are floats (printed exactly with 9 digits), so float
 * and double implementations read the same values. */
int cf_impl_eval(cf_impl *im, int n, const mt_vec3 *wo, const mt_vec3 *wi, cf_eval *out);
int cf_impl_sample(cf_impl *im, int n, const mt_vec3 *wo, const float (*u)[3], cf_samp *out);
/* Ends the child (its exit and any extra output are checked: -1 and msg). */
int cf_impl_close(cf_impl *im);

/* ---- the catalog of configurations --------------------------------------- */
enum {
    CI_FURNACE_LE1 = 1 << 0,   /* albedo <= 1 for every wo */
    CI_TWO_SIDED = 1 << 1,     /* wo from below too */
    CI_SHADING_GAP = 1 << 2,   /* shading normal != geometric: f where the pdf is 0 */
    CI_QUICK = 1 << 3          /* in the reduced set (--quick) */
};

#define CI_MAX_LINES 10
typedef struct cf_impl_config {
    const char *name;
    const char *lines[CI_MAX_LINES]; /* statements and at lines; "@DATA@" is the data directory */
    unsigned flags;
    double lobe_exponent;            /* sharpness, for rounding allowances */
} cf_impl_config;

const cf_impl_config *cf_impl_configs(int *count);
/* Writes the files the catalog names (a MERL table, spectra) into dir. */
int cf_impl_write_data(const char *dir, char *msg, size_t n);

/* ---- the run --------------------------------------------------------------- */
typedef struct cf_impl_run {
    cf_config cfg;       /* samples, cells, alpha and Sidak */
    const char *command;
    double timeout;
    mt_mode mode;
    const char *data;    /* absolute */
    int nwo_max;         /* incoming directions per side */
    const char *plots;   /* --plots DIR, or NULL */
    int plots_all;       /* a picture of every chi-square, not only the failed */
} cf_impl_run;

/* The picture of one chi-square (impl_plot.c): expected counts, histogram
 * and |o - e| / sqrt(e) over the cells, labelled, as a PNG. */
int cf_impl_plot(const char *path, const char *title, const char *subtitle, const char *expected_label,
                 const cf_config *cfg, const long *counts, const double *pdfc, long n, mt_error *err);

/* The worst queries of a failed check, for the report. */
#define CI_WORST 3
typedef struct cf_worst {
    double score; /* err / tol */
    char query[160], expected[400], got[200];
} cf_worst;

enum {
    CK_IDENTITY, CK_CHI2, CK_INTEGRAL, CK_CHI2_MATERIA, CK_FURNACE_MC, CK_FURNACE, CK_AGREE_F, CK_AGREE_PDF,
    CK_AGREE_DELTA, CK_RECIPROCITY, CK_HELMHOLTZ, CK_EXTREMES, CK_NCHECK
};
/* What a check measured, unit by unit (an incoming direction, a colour
 * channel, a pair of directions), so that a failure in pbrt-v2 mode can be
 * set against materia's on the same queries (impl_xfail.c): a statistic s
 * whose own tolerance is z se + sys (se its standard error, z the run's
 * two-sided z at alpha_test, sys the allowance for cubature and rounding). */
typedef struct cf_unit {
    double s, se, sys;
    double at;        /* cos theta of wo, or the pair's number */
    const char *what; /* a format with one %g, for at */
} cf_unit;

typedef struct cf_measure {
    cf_unit *u;
    int n, cap;
    long *hist;       /* a chi-square's histograms: per wo, its cells and one more (failed and delta samples) */
    double *hist_at;  /* each histogram's cos theta of wo */
    int nhist, cap_hist, bins;
    int oom;          /* a unit was lost: the measure cannot be compared */
} cf_measure;

/* One check's outcome: ok < 0 not applicable. */
typedef struct cf_impl_result {
    int ok;
    char statistic[160], bound[64], note[240];
    cf_worst worst[CI_WORST];
    cf_measure m;
} cf_impl_result;

void cf_measure_add(cf_impl_result *r, double s, double se, double sys, double at, const char *what);
void cf_measure_hist(cf_impl_result *r, const long *counts, int ncell, long other, double at);
void cf_impl_results_free(cf_impl_result res[CK_NCHECK]);
/* pbrt-v2 mode: a check that test failed and materia (mine, on the same
 * queries) failed too. 1 when test fails it the way materia does (every
 * unit within the two tolerances, every histogram like materia's by a
 * two-sample chi-square), else 0; note says which. */
int cf_impl_same_failure(const cf_impl_run *run, const cf_impl_result *test, const cf_impl_result *mine, char *note,
                         size_t n);

extern const char *const cf_impl_check_names[CK_NCHECK];

/* Every check of one configuration: test is the implementation under test,
 * ref materia in-process in the same mode (both opened on the config). 0, or
 * -1 when test failed the protocol (its msg says how). */
int cf_impl_checks(const cf_impl_run *run, const cf_impl_config *c, cf_impl *test, cf_impl *ref,
                   cf_impl_result res[CK_NCHECK]);
/* Adds w to the worst list when it is among the worst. */
void cf_worst_add(cf_worst *list, double score, const char *query, const char *expected, const char *got);

/* The whole --impl run (argv as given to materia-conformance). */
int cf_impl_main(int argc, char **argv);

#endif
