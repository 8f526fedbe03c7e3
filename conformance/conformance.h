/*
 * The conformance suite: what is checked, on what, and how the results are
 * reported. See docs/CONFORMANCE-SUITE.md for the checks and their bounds.
 */
#ifndef MT_CONFORMANCE_H
#define MT_CONFORMANCE_H

#include "materia.h"
#include "materia/tools/cubature.h"

/* ---- subjects: a BSDF built in the identity frame at the default point -- */
typedef struct cf_subject cf_subject;
typedef mt_status (*cf_build_fn)(const cf_subject *s, mt_arena *a, mt_mode mode, mt_bsdf **out,
                                 mt_error *err);

enum {
    CF_FURNACE_LE1 = 1 << 0,   /* rho <= 1 (up to float noise) for every wo */
    CF_FURNACE_EXACT = 1 << 1, /* rho == expect_rho for every wo */
    CF_BROKEN = 1 << 2,        /* a deliberately wrong variant: must be caught */
    CF_NO_CHI2 = 1 << 3,       /* only delta lobes: no density to test */
    CF_TWO_SIDED = 1 << 4,     /* test wo below the surface too */
    CF_FURNACE_LE = 1 << 5,    /* rho <= expect_rho (a documented bound) */
    CF_SHADING_GAP = 1 << 6,   /* shading normal != geometric normal: f may be > 0 where
                                  the pdf is 0 (reported, not an error) */
    CF_RADIANCE_OPT = 1 << 7       /* built with the radiance-transmission option (radiance transport) */
};

struct cf_subject {
    const char *name;
    const char *family; /* the BxDF (or combination) this exercises */
    cf_build_fn build;
    double p[8];
    unsigned flags;
    double expect_rho;   /* for CF_FURNACE_EXACT / CF_FURNACE_LE */
    double lobe_exponent; /* sharpness, for float-noise allowances (0: smooth) */
    const char *scene;    /* materials: pbrt-v2 statements ending in a Material */
};

const cf_subject *cf_subjects(int *count);
/* Every material over a grid of its parameters, built from statements. */
const cf_subject *cf_material_subjects(int *count);
/* Builds s->scene's material at the default shading point (p[0], p[1], p[2]
 * non-zero: the geometric normal, else +z). */
mt_status cf_build_material(const cf_subject *s, mt_arena *a, mt_mode mode, mt_bsdf **out, mt_error *err);
const cf_subject *cf_broken_subjects(int *count);

/* ---- statistics ---------------------------------------------------------- */
double cf_chi2_pvalue(double chi2, double dof);        /* upper tail */
double cf_normal_two_sided_z(double alpha);           /* z with P(|Z| > z) = alpha */
double cf_sidak(double alpha, long tests);             /* per-test significance */

/* ---- run configuration --------------------------------------------------- */
typedef struct cf_config {
    int full;          /* --full: many more samples and finer cells */
    long samples;      /* per (subject, mode, wo) */
    int nphi, nz;      /* chi-square cells */
    double alpha;      /* suite-wide significance (0.01) */
    long tests;        /* statistical tests in the run (for Sidak) */
    double alpha_test; /* per-test significance */
    int threads;
    const char *only;  /* substring filter on subject names */
} cf_config;

/* ---- results ------------------------------------------------------------- */
typedef enum { CF_PASS, CF_FAIL, CF_XFAIL, CF_SKIP, CF_INFO } cf_verdict;

typedef struct cf_row {
    char subject[128];
    char mode[16];
    char check[24];
    char kind[12];      /* "physics" or "agreement" */
    char statistic[200];
    char bound[64];
    char note[400];
    char detail[1400];  /* lines printed under a failed row (its direction, cells, worst queries) */
    cf_verdict verdict;
} cf_row;

typedef struct cf_rows {
    cf_row *rows;
    int n, cap;
} cf_rows;

void cf_rows_add(cf_rows *r, const cf_row *row);
/* One line per row: verdict, configuration, mode, check, kind, statistic,
 * bound, note; a failed row's detail under it. */
void cf_rows_print(const cf_rows *r);
void cf_rows_free(cf_rows *r);
int cf_rows_count(const cf_rows *r, cf_verdict v, const char *kind);
const char *cf_verdict_name(cf_verdict v);

/* ---- the equal-area grid of the sphere --------------------------------------
 * The cells the chi-square used before its cells were laid where a pilot
 * sample falls (cells.c): nphi x nz cells of equal area. tradeoff/power.c
 * measures the power of such grids. */
int cf_cell_of(const cf_config *cfg, mt_vec3 w);
mt_status cf_integrate_cell(mt_cubature_fn f, void *ctx, const cf_config *cfg, int c, long count, long n,
                            double abs_tol, double out[7], double *err_pdf, mt_error *err);
/* The integrand for a BSDF: wo, with the components of flags: pdf, f |cos|
 * rgb, f |cos| where the pdf is 0 rgb. */
typedef struct cf_bsdf_pass {
    const mt_bsdf *bsdf;
    mt_vec3 wo;
    unsigned flags;
} cf_bsdf_pass;
void cf_bsdf_integrand(void *ctx, double phi, double z, double *out);
/* The extremes grid's directions (cos theta 1 to 0 and below, three phi). */
int cf_extreme_directions(mt_vec3 *d, int max);
typedef struct cf_chi2 {
    double chi2, p;    /* p = -1: a hard failure */
    long dof;
    int hard;          /* samples where the expected count is 0 */
    double hard_count;
    int hard_cell;
} cf_chi2;
/* counts[c] samples in cell c of expected probability pdfc[c] (ncell
 * cells); of n samples in_cells landed in cells, the others (failed or
 * delta) are one more cell of probability 1 - integral. Cells below 5
 * expected are pooled; a sample in a cell of probability 0 is a hard
 * failure (p = -1). */
void cf_chi2_counts(int ncell, const long *counts, const double *pdfc, long n, long in_cells, double integral,
                    cf_chi2 *out);
/* The same over the grid of cfg (nphi x nz cells). */
void cf_chi2_cells(const cf_config *cfg, const long *counts, const double *pdfc, long n, long in_cells,
                   double integral, cf_chi2 *out);

/* Checks that are not per subject. */
void cf_light_leak(cf_rows *rows);
void cf_material_leak(cf_rows *rows);
void cf_distribution_normalization(cf_rows *rows);
void cf_furnace_table(cf_rows *rows);
void cf_extreme_grid(cf_rows *rows);
void cf_rejects_invalid(cf_rows *rows);


/* The statistical tests of the suite's own run (both modes, every subject;
 * full: 1 --full, -1 --lite, 0 the default), as its Sidak correction counts
 * them. */
long cf_suite_tests(int full);

/* The measured size of each BxDF/BSDF erratum (--errata). */
int cf_errata_report(void);

/* Float-versus-double comparison: --dump writes values, --ulps compares. */
int cf_dump(const char *path);
void cf_ulps(const char *other_binary, cf_rows *rows);

#endif
