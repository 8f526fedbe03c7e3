/*
 * The suite's own run (materia-conformance without --impl): its subjects as
 * configurations of the core, materia's BSDFs built by each subject's
 * function, its settings, and the count of its statistical tests (the Sidak
 * correction, derived from the check table).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "core.h"

/* A subject of the catalog as a configuration of the core: built by its
 * own function, materia in this process. */
void cf_subject_case(const cf_subject *s, cf_case *c)
{
    memset(c, 0, sizeof *c);
    snprintf(c->name, sizeof c->name, "%s", s->name);
    c->subject = s;
    c->flags = ((s->flags & CF_TWO_SIDED) ? CF_CASE_TWO_SIDED : 0) | ((s->flags & CF_SHADING_GAP) ? CF_CASE_SHADING_GAP : 0) |
               ((s->flags & CF_RADIANCE_OPT) ? CF_CASE_RADIANCE : 0);
    c->expect = (s->flags & CF_FURNACE_EXACT) ? CF_EXPECT_EQ
                : (s->flags & (CF_FURNACE_LE1 | CF_FURNACE_LE)) ? CF_EXPECT_LE
                                                                 : CF_EXPECT_NONE;
    c->expect_rho = (s->flags & CF_FURNACE_LE1) ? 1 : s->expect_rho;
    c->lobe_exponent = s->lobe_exponent;
    c->source = "builtin";
}

/* The settings of a run of the suite's own catalog: --full, --lite or the
 * default (quick). */
void cf_suite_settings(cf_run *run, int full)
{
    memset(run, 0, sizeof *run);
    run->cfg.full = full;
    run->cfg.alpha = 0.01;
    run->cfg.samples = full > 0 ? 4000000 : full < 0 ? 20000 : 100000;
    /* cells laid where a pilot sample falls each hold about the same share
     * of the samples: 24 x 25 of them test a lobe more finely than the 32 x
     * 33 cells of equal area the suite used before, at 57% of the cubature */
    run->cfg.nphi = full > 0 ? 100 : full < 0 ? 16 : 24;
    run->cfg.nz = full > 0 ? 101 : full < 0 ? 17 : 25;
    run->only_check = run->only_wo = -1;
    /* in this process an eval costs little: many more samples' f and pdf
     * are set against eval than through the protocol */
    run->identity_samples = 50000;
}

/* The statistical tests of the suite's run over these subjects: both modes,
 * and the broken ones in corrected mode alone (cf_run_tests). */
long cf_suite_tests_of(const cf_run *run, const cf_subject *const *subs, int n)
{
    long tests = 0;
    int i;
    for (i = 0; i < n; ++i) {
        cf_case c;
        cf_subject_case(subs[i], &c);
        tests += cf_run_tests(run, &c, 1, (subs[i]->flags & CF_BROKEN) ? 1 : 2, 0);
    }
    return tests;
}

long cf_suite_tests(int full)
{
    int nsub, nbroken, nmat, i, n = 0;
    const cf_subject *subs = cf_subjects(&nsub), *brk = cf_broken_subjects(&nbroken), *mats = cf_material_subjects(&nmat);
    const cf_subject **all = malloc((size_t)(nsub + nmat + nbroken) * sizeof *all);
    cf_run run;
    long tests;
    if (!all) return -1;
    for (i = 0; i < nsub + nmat + nbroken; ++i)
        all[n++] = i < nsub ? &subs[i] : i < nsub + nmat ? &mats[i - nsub] : &brk[i - nsub - nmat];
    cf_suite_settings(&run, full);
    tests = cf_suite_tests_of(&run, all, n);
    free(all);
    return tests;
}

