/*
 * The conformance core: one pass of checks over one configuration of an
 * implementation, whatever the implementation is. The implementation is
 * reached through batched operations only (cf_impl_ops): build a
 * configuration from pbrt-v2 statements at a shading point (or answer that
 * it is unsupported), evaluate f and pdf for arrays of direction pairs,
 * sample arrays of (uc, u1, u2), and declare its conventions. Three kinds
 * of implementation stand behind them: materia's own BSDFs in this process
 * (backend_materia.c), a child process speaking the text protocol
 * (backend_child.c), and whatever else fills cf_impl_ops (a plugin).
 *
 * Every check is registered once in cf_checks[] (checks.c) with its kind
 * (physics: the implementation against itself and physics; agreement:
 * against materia's answers) and the number of statistical tests it makes
 * per incoming direction, from which the Sidak correction of a run is
 * derived (cf_run_tests). cf_run_case runs the checks of one configuration
 * and fills one cf_result per check. docs/CONFORMANCE-SUITE.md describes
 * the checks and their bounds.
 */
#ifndef CF_CORE_H
#define CF_CORE_H

#include "child.h"
#include "conformance.h"
#include "strbuf.h"

/* ---- conventions an implementation declares (docs/PROTOCOL.md) -------- */
enum { CF_IMPORTANCE = 0, CF_RADIANCE = 1 };
typedef struct cf_conventions {
    int transport;      /* CF_IMPORTANCE (pbrt-v2's BTDF values) or CF_RADIANCE */
    int sample_numbers; /* 3: uc chooses, u1 u2 direct; 2: uc chooses and is rescaled, u1 second */
    int batch;          /* the most triples of an evals/samples line (protocol 3); 1: none */
    int hex;            /* it reads, and after "numbers hex" writes, C99 hexadecimal floats (protocol 3) */
} cf_conventions;

/* pbrt-v2's: importance, 3. */
cf_conventions cf_conventions_default(void);
/* The answer to "conventions": "key value" pairs separated by single
 * spaces; unknown keys are ignored, a known key with another value is an
 * error. 0, or -1 and why. */
int cf_conventions_parse(const char *answer, cf_conventions *c, char *why, size_t n);
/* "transport importance sample-numbers 3" */
void cf_conventions_format(const cf_conventions *c, char *out, size_t n);

/* ---- directions and answers ---------------------------------------------- */
typedef struct cf_v3 {
    double x, y, z;
} cf_v3;

typedef struct cf_eval {
    double f[3], pdf;
} cf_eval;

typedef struct cf_samp {
    double wi[3], f[3], pdf;
    unsigned flags;
} cf_samp;

/* Flags of a sampled component (pbrt-v2's bits, the protocol's). */
enum { CF_REFLECTION = 1, CF_TRANSMISSION = 2, CF_DIFFUSE = 4, CF_GLOSSY = 8, CF_SPECULAR = 16 };

cf_v3 cf_v3_make(double x, double y, double z);
/* Each component rounded to float: the suite's inputs are floats, so that
 * a float and a double implementation read the same numbers. */
cf_v3 cf_v3_float(cf_v3 v);

/* ---- a configuration --------------------------------------------------------- */
#define CF_MAX_LINES 16
#define CF_MAX_WO 16
enum {
    CF_CASE_TWO_SIDED = 1 << 0,   /* incoming directions from below too */
    CF_CASE_SHADING_GAP = 1 << 1, /* shading normal != geometric: f where the pdf is 0 is allowed */
    CF_CASE_QUICK = 1 << 2,       /* in the reduced set (--quick) */
    CF_CASE_RADIANCE = 1 << 3,    /* materia in-process with its radiance-transmission option */
    CF_CASE_INFORMATIVE = 1 << 4  /* a broken variant that need not be caught (sensitivity) */
};
enum { CF_EXPECT_NONE, CF_EXPECT_LE, CF_EXPECT_EQ };

typedef struct cf_case {
    char name[128];
    char *lines[CF_MAX_LINES];    /* pbrt-v2 statements and "at" lines, one per answer */
    int nlines;
    const cf_subject *subject;    /* or: a BSDF built by subject->build (materia in-process only) */
    unsigned flags;
    int expect;                   /* the albedo: CF_EXPECT_LE or _EQ expect_rho, or nothing */
    double expect_rho;
    double lobe_exponent;         /* as sharp as cos^e: rounding allowances grow with e */
    int nwo;                      /* explicit incoming directions (a catalog file), or 0 */
    cf_v3 wo[CF_MAX_WO];
    const char *source;           /* "builtin", or the catalog file it came from */
} cf_case;

/* Adds a line (copied, "@DATA@" replaced by data when data is not NULL). */
int cf_case_add_line(cf_case *c, const char *line, const char *data);
/* Replaces "@DATA@" in its lines by data. */
int cf_case_set_data(cf_case *c, const char *data);
void cf_case_free(cf_case *c);

/* The incoming directions of c: its own, or the suite's set (cos theta
 * 0.9999 and 1 - 1e-6 at several azimuths, 0.7, 0.3, 0.03; --quick: three
 * of them), from below too when two-sided. Floats. */
int cf_case_wo(const cf_case *c, int quick, cf_v3 *wo);

/* ---- an implementation ------------------------------------------------------- */
enum { CF_OK = 0, CF_FAILED = -1, CF_NOMEM = -2, CF_UNSUPPORTED = -3 };

typedef struct cf_impl cf_impl;
typedef struct cf_impl_ops {
    const char *kind; /* "materia", "protocol" */
    /* builds the configuration (mode, statements, "at" lines) */
    int (*open)(cf_impl *im, const cf_case *c);
    /* n pairs: f and pdf */
    int (*eval)(cf_impl *im, int n, const cf_v3 *wo, const cf_v3 *wi, cf_eval *out);
    /* n samples of wo with (uc, u1, u2) */
    int (*sample)(cf_impl *im, int n, const cf_v3 *wo, const float (*u)[3], cf_samp *out);
    /* ends it; CF_FAILED when a child misbehaved at the end */
    int (*close)(cf_impl *im);
} cf_impl_ops;

struct cf_impl {
    const cf_impl_ops *ops;
    /* given before open */
    mt_mode mode;
    const char *command; /* a child: the command, run by sh -c */
    double timeout;      /* a child: seconds per answer */
    cf_conventions conv; /* what the suite applies (declared, or overridden) */
    double eps;          /* its precision's epsilon (float or double) */
    /* state */
    int failed;          /* CF_FAILED or CF_UNSUPPORTED once something went wrong */
    char msg[800];       /* what */
    long queries;
    const mt_bsdf *bsdf; /* materia in-process: the BSDF it answers with */
    int direct;          /* answers at once (in-process): the core may ask one at a time */
    /* backend state */
    cf_child child;
    cf_strbuf text;
    const char **ans;
    int ans_cap;
    const char *mode_line;
    void *q;             /* materia: its mt_query session */
    mt_arena *arena;
    const struct mt_impl_plugin *plugin; /* a plugin (backend_lib.c): its table, state, configuration */
    void *plugin_state, *plugin_cfg;
};

/* materia's own BSDFs in this process (its mt_query session, or a
 * subject's builder); mode and conventions are set by the caller. */
void cf_impl_materia(cf_impl *im, mt_mode mode);
/* A child process running command (sh -c) that speaks the protocol. */
void cf_impl_child(cf_impl *im, mt_mode mode, const char *command, double timeout);
/* A plugin (include/materia/impl.h) in this process, its state made by
 * its create (backend_lib.c). */
void cf_impl_lib(cf_impl *im, mt_mode mode, const struct mt_impl_plugin *plugin, void *state);
/* A plugin's declarations read as a protocol speaker's (cf_impl_probe):
 * 0, or -1 and msg. */
int cf_impl_lib_probe(const struct mt_impl_plugin *plugin, cf_conventions *conv, int *declared, double *eps, char *name,
                      size_t nn, char *msg, size_t nm);
/* Asks a protocol speaker its version and conventions (a child of its
 * own). 0, or -1 and msg. name gets "NAME VERSION precision P". */
int cf_impl_probe(const char *command, double timeout, cf_conventions *conv, int *declared, double *eps,
                  char *name, size_t nn, char *msg, size_t nm);
/* An "error ..." answer that says unsupported (after any "FILE:LINE:COL:"
 * position, the message starts with the word "unsupported"): the message. */
const char *cf_unsupported(const char *answer);

/* ---- the checks ---------------------------------------------------------------- */
enum {
    CK_IDENTITY, CK_CHI2, CK_MEAN, CK_INTEGRAL, CK_CHI2_MATERIA, CK_FURNACE_MC, CK_FURNACE, CK_AGREE_F, CK_AGREE_PDF,
    CK_AGREE_DELTA, CK_RECIPROCITY, CK_HELMHOLTZ, CK_EXTREMES, CK_NCHECK
};
enum { CF_PHYSICS, CF_AGREEMENT };
/* What a check needs computed (the stages of the pass). */
enum {
    ST_SAMPLES = 1 << 0,  /* the main samples of each direction (always) */
    ST_IDENTITY = 1 << 1, /* eval where samples went */
    ST_CELLS = 1 << 2,    /* pilot samples, cells, cubature of its own eval */
    ST_REFCELLS = 1 << 3, /* cubature of materia's pdf over the same cells */
    ST_PROBES = 1 << 4,   /* delta lobes by stratified random numbers */
    ST_PAIRS = 1 << 5,    /* pairs of directions both ways (always) */
    ST_HELM = 1 << 6,     /* specular transmission there and back */
    ST_EXTREMES = 1 << 7
};
typedef struct cf_check_def {
    const char *name;
    int kind;               /* CF_PHYSICS or CF_AGREEMENT */
    int tests_per_wo;       /* statistical tests per incoming direction (Sidak) */
    int xfail_tests_per_wo; /* pbrt-v2 mode: comparisons with materia's failure per direction */
    unsigned stages;        /* what it needs */
    const char *what;       /* one line: what it asserts */
} cf_check_def;
extern const cf_check_def cf_checks[CK_NCHECK];
/* The check called name, or -1. */
int cf_check_find(const char *name);
const char *cf_kind_name(int kind);

/* The worst queries of a failed check. */
#define CF_WORST 3
typedef struct cf_worst {
    double score; /* err / tol */
    char query[200], expected[400], got[240];
    char query2[200]; /* a second query that shows it (the reverse, the way back), or "" */
} cf_worst;
void cf_worst_add(cf_worst *list, double score, const char *query, const char *expected, const char *got,
                  const char *query2);

/* What a check measured, unit by unit (an incoming direction, a colour
 * channel, a pair), so that a failure in pbrt-v2 mode can be set against
 * materia's on the same queries (impl_xfail.c): a statistic s whose own
 * tolerance is z se + sys. */
typedef struct cf_unit {
    double s, se, sys;
    double at;
    const char *what; /* a format with one %g, for at */
} cf_unit;
typedef struct cf_measure {
    cf_unit *u;
    int n, cap;
    long *hist;      /* chi-square histograms: per direction, its cells and one more */
    double *hist_at;
    int *hist_bins;
    int nhist, cap_hist;
    int oom;
} cf_measure;

/* One check's outcome. */
typedef struct cf_result {
    int ok;              /* 1 passed, 0 failed, -1 not run */
    char statistic[200], bound[64], note[400];
    cf_worst worst[CF_WORST];
    cf_measure m;
    int wo;              /* the incoming direction a statistical failure is worst at, or -1 */
    char where[672];     /* that direction (vector, theta, phi) and its worst cells (pass.c: a direction, its count, its cells) */
} cf_result;

void cf_measure_add(cf_result *r, double s, double se, double sys, double at, const char *what);
void cf_measure_hist(cf_result *r, const long *counts, int ncell, long other, double at);
void cf_results_free(cf_result res[CK_NCHECK]);

/* ---- cells: where the chi-square counts ------------------------------------ */
/* The sphere in rows of cos theta (the horizon always a boundary) and, in
 * each row, columns of phi, laid where a pilot sample of the
 * implementation's own sampler fell (equal counts of it per row and per
 * column), so that a sharp lobe is spread over many cells. The pilot is
 * independent of the samples tested, so the cells are fixed before them and
 * the chi-square stays a test of the pdf. */
typedef struct cf_layout {
    int nrow, ncell;
    double *z;      /* nrow + 1 boundaries, -1 .. 1 */
    int *first;     /* nrow + 1: row r holds cells first[r] .. first[r + 1] - 1 */
    double *phi;    /* ncell: the start of each cell's phi range (the next cell's, or 2 pi, ends it) */
} cf_layout;
int cf_layout_from(cf_layout *l, const cf_v3 *pilot, long n, int nphi, int nz);
int cf_layout_copy(cf_layout *dst, const cf_layout *src);
void cf_layout_free(cf_layout *l);
int cf_layout_cell(const cf_layout *l, double x, double y, double z);
void cf_layout_bounds(const cf_layout *l, int c, double *p0, double *p1, double *z0, double *z1);
int cf_layout_row(const cf_layout *l, int c); /* the row holding cell c */

/* ---- a run ----------------------------------------------------------------------- */
typedef struct cf_run {
    cf_config cfg;       /* samples, cells, alpha, tests, alpha_test */
    mt_mode mode;
    int compare;         /* 1: the agreement checks against materia run */
    int quick;           /* the reduced set of incoming directions */
    int only_check;      /* -1, or the one check run (--check) */
    int only_wo;         /* -1, or the one incoming direction (--wo) */
    const char *plots;   /* --plots DIR */
    int plots_all;
    long identity_samples; /* samples per direction whose f and pdf are set against eval */
    int sample_numbers;  /* the implementation's (3 or 2): with 2, u2 is held at 1/2 */
    double power;        /* --power EPS: each configuration's samples per direction chosen
                            from its pilot (power.h), cfg.samples only sizing the pilot; or 0 */
    long power_max;      /* their most */
} cf_run;

/* The statistical tests of a run over these configurations (Sidak),
 * derived from cf_checks[]: per incoming direction, the tests of every
 * check that runs (agreement ones only when comparing), and the
 * comparisons with materia's failures in pbrt-v2 mode (xfail). */
long cf_run_tests(const cf_run *run, const cf_case *cases, int ncases, int modes, int xfail);

/* The suite's own run (suite.c): a subject of its catalog as a
 * configuration (built by the subject's function), the settings of --full
 * (1), --lite (-1) or the default (0), and the tests of a run over subs. */
void cf_subject_case(const cf_subject *s, cf_case *c);
void cf_suite_settings(cf_run *run, int full);
long cf_suite_tests_of(const cf_run *run, const cf_subject *const *subs, int n);

/* The outcome of one configuration. */
typedef struct cf_outcome {
    int status;                 /* CF_OK, CF_UNSUPPORTED (msg says why), CF_FAILED (protocol), CF_NOMEM */
    char msg[800];
    int agreement;              /* 1: the agreement checks ran */
    char no_agreement[300];     /* why not, when compare but not run */
    cf_result res[CK_NCHECK];
    int xfail[CK_NCHECK];
    int nwo;
    cf_v3 wo[CF_MAX_WO];
    cf_layout layout[CF_MAX_WO]; /* the cells of each direction (ncell 0: none) */
    double eta;                 /* the relative index found (Snell or reciprocity), or 0 */
    /* the tests of each direction, for their power (power.h): samples,
     * the chi-square's degrees of freedom, and v[test][reference] over its
     * cells (chi2, mean wi; the sampler warp, the pdf shape) */
    long pw_n[CF_MAX_WO], pw_dof[CF_MAX_WO], pw_mdof[CF_MAX_WO]; /* and the mean test's */
    double pw_v[CF_MAX_WO][2][2];
} cf_outcome;

/* Runs the checks of c on test (opened on c), against ref (materia opened
 * on c in the same mode and transport, or NULL: physics only). fixed: the
 * cells to use for each direction (materia re-run on an implementation's
 * queries), or NULL. */
int cf_run_case(const cf_run *run, const cf_case *c, cf_impl *test, cf_impl *ref, const cf_outcome *fixed,
                cf_outcome *out);
void cf_outcome_free(cf_outcome *o);

/* pbrt-v2 mode: a check that test failed and materia (mine, on the same
 * queries) failed too; 1 when the same way (impl_xfail.c). */
int cf_same_failure(double alpha_test, const cf_result *test, const cf_result *mine, char *note, size_t n);

/* The seed of configuration name's k-th stream (direction, pairs, ...),
 * in the run's seeded variant (--seed S; 0, the default, is the suite's
 * own numbers). cf_set_run_seed is called once, before the run. */
uint64_t cf_seed(const char *name, int k);
void cf_set_run_seed(uint64_t seed);
/* A uniform number in [0, 1) as the float a query line carries. */
float cf_u_float(mt_rng *rng);
/* The random numbers of the main samples of direction w (n of them), and
 * of the pilot: what --repro writes again. With two sample numbers (the
 * implementation's convention) u2 is unused, and held at 1/2: an
 * implementation that declares 2 and uses it shows it. */
void cf_sample_numbers(const char *name, int w, int pilot, int sample_numbers, long n, float (*u)[3]);
/* The same numbers a chunk at a time: the stream of direction w (or its
 * pilot), then its next n triples. */
void cf_sample_stream(mt_rng *rng, const char *name, int w, int pilot);
void cf_sample_next(mt_rng *rng, int sample_numbers, long n, float (*u)[3]);

/* Query lines as the protocol writes them. */
void cf_q_eval(char *q, size_t n, cf_v3 wo, cf_v3 wi);
void cf_q_sample(char *q, size_t n, cf_v3 wo, const float *u);
void cf_a_eval(char *a, size_t n, const cf_eval *e);
void cf_a_sample(char *a, size_t n, const cf_samp *s);
/* A number as a query carries it: 9 digits when it is a float, else 17. */
int cf_format_num(char *out, size_t n, double v);

/* The picture of one chi-square (impl_plot.c). */
int cf_plot_cells(const char *path, const char *title, const char *subtitle, const char *expected_label,
                  const cf_layout *l, const long *counts, const double *pdfc, long n, mt_error *err);

#endif
