/*
 * The check table: every check of the suite, once. Its kind says whether it
 * holds the implementation against itself and physics or against materia;
 * its count of statistical tests per incoming direction is what the Sidak
 * correction of a run is derived from, so a check that adds a test changes
 * the correction by construction; its stages are what the pass computes
 * for it (a check run alone, --check, computes only those).
 */
#include <string.h>
#include "core.h"

#define S ST_SAMPLES
#define P ST_PAIRS

const cf_check_def cf_checks[CK_NCHECK] = {
    /* the fractions of invalid samples and of samples unlike eval: two
     * binomial comparisons with materia's in pbrt-v2 mode */
    {"identity", CF_PHYSICS, 0, 2, S | P | ST_IDENTITY,
     "every sample finite, f >= 0, pdf >= 0, wi unit; a non-delta sample's f and pdf are eval's at its wi"},
    /* one chi-square (and one two-sample homogeneity test against materia's
     * histogram in pbrt-v2 mode) per direction */
    {"chi2", CF_PHYSICS, 1, 1, S | P | ST_CELLS, "its sampled directions follow its own pdf"},
    /* one chi-square of 3 or 4 degrees of freedom per direction: the means
     * of its sampled directions, linear contrasts of the chi-square's
     * counts, few degrees of freedom where the chi-square has hundreds, so a
     * smooth mismatch along them needs several times fewer samples
     * (power.h); in pbrt-v2 mode, the four means compared with materia's */
    {"mean wi", CF_PHYSICS, 1, 4, S | P | ST_CELLS,
     "the mean of its sampled directions (x, y, z, |z|) equals the mean its own pdf gives, by the chi-square's cubature"},
    {"pdf integral", CF_PHYSICS, 1, 1, S | P | ST_CELLS,
     "the integral of its pdf equals the fraction of its samples that land in a cell"},
    {"chi2 materia", CF_AGREEMENT, 1, 1, S | P | ST_CELLS | ST_REFCELLS,
     "its sampled directions follow materia's pdf"},
    /* one comparison per colour channel */
    {"furnace MC=quad", CF_PHYSICS, 3, 3, S | P | ST_CELLS | ST_PROBES,
     "the Monte Carlo albedo of its samples equals the albedo by cubature of its f and its delta lobes"},
    /* the albedo is a cubature and a sum over delta lobes: no noise */
    {"furnace", CF_PHYSICS, 0, 0, S | P | ST_CELLS | ST_PROBES,
     "the energy the configuration returns (in its transport) meets the expectation"},
    {"agree f", CF_AGREEMENT, 0, 0, S | P, "eval's f equals materia's"},
    {"agree pdf", CF_AGREEMENT, 0, 0, S | P, "eval's pdf equals materia's"},
    {"agree delta", CF_AGREEMENT, 0, 0, S | P | ST_PROBES, "its delta lobes are materia's, direction and f"},
    {"reciprocity", CF_PHYSICS, 0, 0, S | P,
     "f(wo, wi) = f(wi, wo); across the surface, the generalized form of its transport"},
    {"helmholtz", CF_PHYSICS, 0, 0, S | P | ST_HELM,
     "specular transmission there and back: T(T(w)) = w, the lobes' weights in its transport, one index"},
    {"extremes", CF_PHYSICS, 0, 0, S | P | ST_EXTREMES,
     "eval and sample finite and non-negative at grazing, normal and degenerate directions"},
};

int cf_check_find(const char *name)
{
    int k;
    for (k = 0; k < CK_NCHECK; ++k)
        if (!strcmp(cf_checks[k].name, name)) return k;
    return -1;
}

const char *cf_kind_name(int kind) { return kind == CF_AGREEMENT ? "agreement" : "physics"; }

long cf_run_tests(const cf_run *run, const cf_case *cases, int ncases, int modes, int xfail)
{
    long per_wo = 0, tests = 0;
    int i, k;
    cf_v3 wo[CF_MAX_WO];
    for (k = 0; k < CK_NCHECK; ++k) {
        if (cf_checks[k].kind == CF_AGREEMENT && !run->compare) continue;
        if (run->only_check >= 0 && run->only_check != k) continue;
        per_wo += cf_checks[k].tests_per_wo + (xfail ? cf_checks[k].xfail_tests_per_wo : 0);
    }
    for (i = 0; i < ncases; ++i) tests += (long)cf_case_wo(&cases[i], run->quick, wo) * per_wo * modes;
    return tests;
}
