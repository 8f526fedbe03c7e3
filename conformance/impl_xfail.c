/*
 * pbrt-v2 mode's expected failures (materia-conformance --impl). pbrt-v2
 * fails some physics checks (its glossy sampling pdf, for one: erratum
 * glossy-sample-pdf), and an implementation that reproduces pbrt-v2 fails
 * them too. Such a failure is expected (XFAIL) only when it is pbrt-v2's
 * own: materia, run through the same check on the same queries (the same
 * incoming directions, random numbers and pairs), fails it too, and by as
 * much. Each check records what it measured unit by unit (cf_measure: an
 * incoming direction, a colour channel, a pair), and the two failures are
 * the same when
 *
 *   every unit:  |s_test - s_materia| <= z sqrt(se_test^2 + se_materia^2)
 *                                        + sys_test + sys_materia
 *
 * The check's own tolerance of s is z se + sys (a standard error, and the
 * allowance for cubature and rounding); two estimates of the same quantity
 * differ by at most their allowances added and by noise whose standard error
 * is sqrt(se_test^2 + se_materia^2) when they are independent (less when an
 * implementation maps random numbers as materia does: its samples are then
 * materia's), so a correct implementation passes with probability 1 -
 * alpha_test per unit. And
 *
 *   every histogram of its samples is distributed as materia's: the
 *   two-sample chi-square of homogeneity over the same cells (equal totals:
 *   sum (a - b)^2 / (a + b), Numerical Recipes' chstwo), p >= alpha_test.
 *
 * Anything else is a FAIL whose note says how it differs: "fails it worse
 * than pbrt-v2 does" when its statistic is further from passing than
 * materia's, "differently" otherwise.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "core.h"

/* The two-sample chi-square of two histograms with the same total: p. Bins
 * whose two counts add to less than 10 (5 expected in each) are pooled. */
static double homogeneity_p(const long *a, const long *b, int bins)
{
    double chi2 = 0, pa = 0, pb = 0;
    long used = 0;
    int i;
    for (i = 0; i < bins; ++i) {
        double s = (double)a[i] + (double)b[i], d = (double)a[i] - (double)b[i];
        if (s <= 0) continue;
        if (s < 10) {
            pa += (double)a[i];
            pb += (double)b[i];
            continue;
        }
        chi2 += d * d / s;
        used++;
    }
    if (pa + pb > 0) {
        chi2 += (pa - pb) * (pa - pb) / (pa + pb);
        used++;
    }
    return used > 1 ? cf_chi2_pvalue(chi2, (double)(used - 1)) : 1;
}

int cf_same_failure(double alpha_test, const cf_result *test, const cf_result *mine, char *note, size_t n)
{
    const cf_measure *a = &test->m, *b = &mine->m;
    double z = cf_normal_two_sided_z(alpha_test), worst = 0, min_p = 2;
    int i, wu = -1, wh = -1;
    size_t at = 0;
    if (a->oom || b->oom || a->n != b->n || a->nhist != b->nhist ||
        (a->nhist && memcmp(a->hist_bins, b->hist_bins, (size_t)a->nhist * sizeof *a->hist_bins))) {
        snprintf(note, n, "materia fails it too in pbrt-v2 mode, but what it measured cannot be set against materia's");
        return 0;
    }
    if (!a->n && !a->nhist) {
        snprintf(note, n, "materia fails it too in pbrt-v2 mode, but this check has no measure to compare the two by");
        return 0;
    }
    for (i = 0; i < a->n; ++i) {
        const cf_unit *x = &a->u[i], *y = &b->u[i];
        double d = fabs(x->s - y->s), tol = z * sqrt(x->se * x->se + y->se * y->se) + x->sys + y->sys;
        double r = d == 0 ? 0 : tol > 0 ? d / tol : 1e30;
        if (!isfinite(r)) r = 1e30;
        if (r > worst || wu < 0) {
            worst = fmax(worst, r);
            wu = i;
        }
    }
    for (i = 0; i < a->nhist; ++i) {
        double p = homogeneity_p(a->hist + at, b->hist + at, a->hist_bins[i]);
        at += (size_t)a->hist_bins[i];
        if (p < min_p) {
            min_p = p;
            wh = i;
        }
    }
    if (worst <= 1 && min_p >= alpha_test) {
        char same[96] = "identical measures";
        if (worst > 0) snprintf(same, sizeof same, "differences at most %.2g of their tolerance", worst);
        if (wh >= 0)
            snprintf(same + strlen(same), sizeof same - strlen(same), "; its samples distributed as materia's, p %.2g",
                     min_p);
        snprintf(note, n, "materia fails it too in pbrt-v2 mode (%.90s), the same way (%s)", mine->statistic, same);
        return 1;
    }
    if (worst > 1) {
        const cf_unit *x = &a->u[wu], *y = &b->u[wu];
        char where[96];
        snprintf(where, sizeof where, x->what, x->at);
        snprintf(note, n, "materia fails it too in pbrt-v2 mode, but this fails it %s: %.70s %.4g, materia %.4g "
                          "(difference %.3g times its tolerance)",
                 fabs(x->s) > fabs(y->s) ? "worse than pbrt-v2 does" : "differently from pbrt-v2", where, x->s, y->s,
                 worst);
    } else {
        snprintf(note, n, "materia fails it too in pbrt-v2 mode, but this fails it differently from pbrt-v2: its "
                          "samples are not distributed as materia's (two-sample chi-square p %.3g at cos %.3g)",
                 min_p, a->hist_at[wh]);
    }
    return 0;
}
