/*
 * Statistics for the suite: the chi-square upper tail (the regularized upper
 * incomplete gamma function Q(k/2, x/2), by its series or its continued
 * fraction as in Numerical Recipes' gammq), normal quantiles, and the Sidak
 * correction that keeps the whole suite's false-alarm rate at alpha.
 */
#include <math.h>
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
