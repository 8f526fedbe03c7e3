/*
 * Statistics for the suite: the chi-square upper tail (the regularized upper
 * incomplete gamma function Q(k/2, x/2), by its series or its continued
 * fraction as in Numerical Recipes' gammq), normal quantiles, and the Sidak
 * correction that keeps the whole suite's false-alarm rate at alpha.
 */
#include <math.h>
#include <string.h>
#include "conformance.h"

static double gamma_p_series(double a, double x)
{
    double sum = 1 / a, term = sum, ap = a;
    int n;
    for (n = 0; n < 100000; ++n) {
        ap += 1;
        term *= x / ap;
        sum += term;
        if (fabs(term) < fabs(sum) * 1e-16) break;
    }
    return sum * exp(-x + a * log(x) - lgamma(a));
}

static double gamma_q_fraction(double a, double x)
{
    /* modified Lentz evaluation of the continued fraction for Q */
    const double tiny = 1e-300;
    double b = x + 1 - a, c = 1 / tiny, d = 1 / b, h = d;
    int i;
    for (i = 1; i < 100000; ++i) {
        double an = -i * (i - a), del;
        b += 2;
        d = an * d + b;
        if (fabs(d) < tiny) d = tiny;
        c = b + an / c;
        if (fabs(c) < tiny) c = tiny;
        d = 1 / d;
        del = d * c;
        h *= del;
        if (fabs(del - 1) < 1e-16) break;
    }
    return exp(-x + a * log(x) - lgamma(a)) * h;
}

double cf_chi2_pvalue(double chi2, double dof)
{
    double a = dof / 2, x = chi2 / 2;
    if (!(dof > 0)) return 1;
    if (!(x > 0)) return 1;
    if (x < a + 1) return 1 - gamma_p_series(a, x);
    return gamma_q_fraction(a, x);
}

double cf_normal_two_sided_z(double alpha)
{
    /* solve erfc(z / sqrt 2) = alpha by bisection: robust for any alpha */
    double lo = 0, hi = 40;
    int i;
    for (i = 0; i < 200; ++i) {
        double mid = 0.5 * (lo + hi);
        if (erfc(mid / sqrt(2.0)) > alpha)
            lo = mid;
        else
            hi = mid;
    }
    return 0.5 * (lo + hi);
}

double cf_sidak(double alpha, long tests)
{
    if (tests < 1) tests = 1;
    return -expm1(log1p(-alpha) / (double)tests);
}

void cf_chi2_counts(int ncell, const long *counts, const double *pdfc, long n, long in_cells, double integral,
                    cf_chi2 *out)
{
    int c;
    double chi2 = 0, pool_o = 0, pool_e = 0, e_fail, small_o = 0, small_e = 0;
    long bins = 0;
    memset(out, 0, sizeof *out);
    for (c = 0; c < ncell; ++c) {
        double e = pdfc[c] * n, o = (double)counts[c];
        if (pdfc[c] <= 0 && o > 0) {
            out->hard = 1;
            out->hard_count += o;
            out->hard_cell = c;
        }
        /* fewer than 5 expected: the chi-square's approximation fails there */
        if (e < 5) {
            pool_o += o;
            pool_e += e;
        } else {
            chi2 += (o - e) * (o - e) / e;
            bins++;
            if (!small_e || e < small_e) {
                small_e = e;
                small_o = o;
            }
        }
    }
    e_fail = fmax(0, (1 - integral) * n);
    if (e_fail < 5) {
        pool_o += (double)(n - in_cells);
        pool_e += e_fail;
    } else {
        chi2 += ((double)(n - in_cells) - e_fail) * ((double)(n - in_cells) - e_fail) / e_fail;
        bins++;
    }
    if (pool_e >= 5 || (bins == 0 && pool_e > 0)) {
        chi2 += (pool_o - pool_e) * (pool_o - pool_e) / pool_e;
        bins++;
    } else if (pool_o > 0 || pool_e > 0) {
        /* the pool's expectation is below 5 too (the cells below the
         * horizon of a reflection, a rare failed sample): its own term
         * would not be chi-square distributed (one sample where 0.004 are
         * expected adds 250), so it joins the bin expected least */
        double o = small_o + pool_o, e = small_e + pool_e;
        chi2 += (o - e) * (o - e) / e - (small_o - small_e) * (small_o - small_e) / small_e;
    }
    out->chi2 = chi2;
    out->dof = bins - 1;
    out->p = out->hard ? -1 : bins > 1 ? cf_chi2_pvalue(chi2, (double)(bins - 1)) : 1;
}
