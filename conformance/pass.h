/*
 * The pass over one configuration, shared by its parts: pass.c (the
 * directions: samples, identity, cells, chi-square, pdf integral,
 * furnace), pairs.c (reciprocity, agree f and pdf), delta.c (delta lobes,
 * agree delta, Helmholtz) and impl_extremes.c. Internal to the core.
 */
#ifndef CF_PASS_H
#define CF_PASS_H

#include "core.h"

/* A delta lobe seen at one incoming direction: its direction, its
 * contribution f |cos theta_i| (the lobe's weight in the albedo, whatever
 * the probability the sampler gives it) and eta_i / eta_o from Snell's law
 * of its own directions (0 when wo or wi is too close to the normal to
 * tell, and for reflection). */
#define CF_MAX_LOBES 16
typedef struct cf_lobe {
    double wi[3], c[3], f[3];
    unsigned flags;
    double ratio;
    int count; /* probes that found it */
} cf_lobe;

/* The non-delta sample directions of a direction that the pass keeps
 * beside their counts: the pairs' half that starts where it samples. */
#define CF_KEEP_DIRS 48

/* What the pass keeps of one incoming direction. */
typedef struct cf_wo_data {
    cf_v3 wo;
    int index;           /* in the configuration's set (its seeds) */
    long n;              /* main samples */
    long *counts;        /* the non-delta samples in each of its cells (its layout's) */
    long ndirs;          /* how many */
    cf_v3 first[CF_KEEP_DIRS]; /* the first of them (the pairs start from them) */
    long across;         /* of them and of the pilot's, how many across the surface (by ng) */
    cf_v3 *pilot;        /* the pilot's non-delta directions */
    long npilot, npilot_drawn;
    long invalid, unlike, nid, delta, delta_trans;
    double mc[3], mc2[3]; /* sums of f |cos| / pdf and its square over the samples */
    cf_lobe lobes[CF_MAX_LOBES];
    int nlobes;
    cf_samp *probe;      /* the probes' answers (test), and materia's */
    cf_samp *probe_ref;
    int nprobe;
} cf_wo_data;

typedef struct cf_ctx {
    const cf_run *run;
    const cf_case *c;
    cf_impl *test, *ref;
    cf_outcome *out;
    const cf_outcome *fixed;
    unsigned stages;
    cf_v3 ns, ng;       /* the shading and geometric normals of its "at" lines */
    double allow;       /* rounding allowance of an integral of its values: (64 + 3 e) eps,
                           eps at least a float's (the suite's directions are floats) */
    double allow_own;   /* of one of its values against another at the same inputs: its eps */
    double z;           /* the two-sided z of the run's per-test level */
    int nwo;
    cf_wo_data *w;
    int density;        /* some non-delta sample, or some eval > 0 */
    double eta;         /* inside / outside index, from Snell's law of its answers; 0 unknown */
    int eta_n;
    double eta_spread;
} cf_ctx;

/* The probe grid: (uc, u1, u2) triples that reach every delta lobe of a
 * pbrt-v2 sampler (uc over its components) and both branches of a one-lobe
 * Fresnel sampler (uc rescaled, or u1). */
int cf_probe_grid(float (*u)[3], int max);
int cf_probe_count(void);
/* The lobes among a direction's probe answers. */
void cf_find_lobes(const cf_ctx *x, cf_v3 wo, const cf_samp *s, int n, cf_lobe *lobes, int *nlobes);

int cf_pairs(cf_ctx *x);
int cf_delta_agree(cf_ctx *x);
int cf_helmholtz(cf_ctx *x);
int cf_extremes_check(cf_ctx *x);

/* Cells: the integrals of the implementation's eval over each cell at wo.
 * other = 0: per cell v[0] pdf (written to cellv), totals of pdf, f |cos|
 * rgb and f |cos| where the pdf is 0 rgb (7); other = 1: across the
 * surface (by ng) only, totals of f(wo, w) |cos| rgb and f(w, wo) |cos| rgb
 * (6). err: the cubature's error estimates of the totals. */
typedef struct cf_regions {
    int *first;          /* cell c's regions: first[c] .. first[c + 1] - 1 */
    double (*rect)[5];   /* phi0 phi1 z0 z1 and the start grid's side */
    int n;
} cf_regions;
/* The regions each cell's cubature starts from, placed where the pilot's
 * points lie in it and towards narrower neighbours (cells.c). */
int cf_regions_build(cf_regions *g, const cf_layout *l, const cf_v3 *pilot, long n);
void cf_regions_free(cf_regions *g);
int cf_cells_integrate(cf_impl *im, const cf_layout *l, const cf_regions *rg, cf_v3 wo, cf_v3 ns, cf_v3 ng, int other,
                       long n, double *cellv, double *total, double *err);
int cf_cells_ref_pdf(const mt_bsdf *b, const cf_layout *l, const cf_regions *rg, cf_v3 wo, long n, double *cellv);

/* Sets r's outcome and formatted statistic. */
void cf_set(cf_result *r, int ok, const char *bound, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;

double cf_dot(cf_v3 a, cf_v3 b);
/* The bound of a comparison with materia at a value v whose spread under
 * the perturbations is s (pairs.c). */
double cf_ref_bound(double v, double s, double rel, double vmax);
/* w turned by 4 eps radians towards +-t1 (k = 0, 1) or +-t2 (k = 2, 3), two
 * directions perpendicular to it: every way a rounding can move it. */
cf_v3 cf_perturb(cf_v3 w, int k, double eps);
/* sin theta of w about the unit normal n */
double cf_sin_about(cf_v3 w, cf_v3 n);
double cf_rel(double a, double b);
/* "(x, y, z), theta T deg, phi P deg" */
void cf_describe_wo(cf_v3 wo, char *out, size_t n);

#endif
