/*
 * The power of the chi-square against a smooth sampler/pdf mismatch
 * (power.h). A sampled density q = p (1 + eps g), g of mean 0 under p and
 * constant over each cell's row of cos theta_i, moves the expected count of
 * cell c from n p_c to n p_c (1 + eps g_c), so Pearson's statistic over the
 * cells is a non-central chi-square of non-centrality
 * lambda = n eps^2 sum_c p_c g_c^2 (Cochran 1952; the classical result for
 * local alternatives). Its power at level alpha is the upper tail of that
 * distribution beyond the central quantile. A configuration is caught when
 * any of its directions' tests fails: 1 - prod_w (1 - power_w).
 */
#include <math.h>
#include "power.h"

double cf_chi2_upper_quantile(double alpha, double dof)
{
    double lo = 0, hi = dof + 10 * sqrt(2 * dof) + 100;
    int i;
    while (cf_chi2_pvalue(hi, dof) > alpha) hi *= 2;
    for (i = 0; i < 200; ++i) {
        double mid = 0.5 * (lo + hi);
        if (cf_chi2_pvalue(mid, dof) > alpha)
            lo = mid;
        else
            hi = mid;
    }
    return 0.5 * (lo + hi);
}

double cf_ncchi2_sf(double crit, double dof, double lambda)
{
    /* sum_j Poisson(j; lambda / 2) Q_{dof + 2 j}(crit), from the mode out
     * both ways until the weights are negligible */
    double m = lambda / 2, sum = 0, w0;
    long j0 = (long)floor(m), j;
    if (!(lambda > 0)) return cf_chi2_pvalue(crit, dof);
    w0 = exp(-m + (double)j0 * log(m > 0 ? m : 1) - lgamma((double)j0 + 1));
    for (j = j0; j >= 0; --j) {
        double w = exp(-m + (double)j * log(m) - lgamma((double)j + 1));
        sum += w * cf_chi2_pvalue(crit, dof + 2.0 * (double)j);
        if (w < 1e-14 * w0 && j < j0) break;
    }
    for (j = j0 + 1;; ++j) {
        double w = exp(-m + (double)j * log(m) - lgamma((double)j + 1));
        sum += w * cf_chi2_pvalue(crit, dof + 2.0 * (double)j);
        if (w < 1e-14 * w0) break;
    }
    return fmin(1, sum);
}

double cf_power_shape(const cf_layout *l, const double *pdfc)
{
    double total = 0, below = 0, v = 0;
    int r, c;
    for (c = 0; c < l->ncell; ++c) total += pdfc[c] > 0 ? pdfc[c] : 0;
    if (!(total > 0)) return 0;
    for (r = 0; r < l->nrow; ++r) {
        double pr = 0, g;
        for (c = l->first[r]; c < l->first[r + 1]; ++c) pr += pdfc[c] > 0 ? pdfc[c] : 0;
        /* the mean of 2 F - 1 over the row: F runs from below / total to
         * (below + pr) / total across it */
        g = (2 * below + pr) / total - 1;
        v += pr * g * g;
        below += pr;
    }
    return v;
}

double cf_power_shape_cos(const cf_layout *l, const double *pdfc)
{
    double total = 0, m = 0, v = 0;
    int r, c, pass;
    for (pass = 0; pass < 2; ++pass)
        for (r = 0; r < l->nrow; ++r) {
            double pr = 0, a = fabs(l->z[r]), b = fabs(l->z[r + 1]);
            /* the mean of |z| over the row, at its middle (a row that
             * crosses the horizon: its two halves) */
            double mid = l->z[r] < 0 && l->z[r + 1] > 0 ? (a * a + b * b) / (2 * (a + b)) : 0.5 * (a + b);
            for (c = l->first[r]; c < l->first[r + 1]; ++c) pr += pdfc[c] > 0 ? pdfc[c] : 0;
            if (!pass) {
                total += pr;
                m += pr * mid;
            } else {
                v += pr * (mid - m) * (mid - m);
            }
            if (!pass && r == l->nrow - 1 && total > 0) m /= total;
        }
    return total > 0 ? v : 0;
}

/* The probability of catching eps. */
static double catch_prob(double eps, int nwo, const long *n, const long *dof, const double *v, double alpha)
{
    double miss = 1;
    int w;
    for (w = 0; w < nwo; ++w) {
        double crit;
        if (dof[w] < 1 || !(v[w] > 0) || n[w] < 1) continue;
        crit = cf_chi2_upper_quantile(alpha, (double)dof[w]);
        miss *= 1 - cf_ncchi2_sf(crit, (double)dof[w], (double)n[w] * eps * eps * v[w]);
    }
    return 1 - miss;
}

double cf_power_min_eps(int nwo, const long *n, const long *dof, const double *v, double alpha, double want)
{
    double lo = 0, hi = 1;
    int i;
    if (catch_prob(hi, nwo, n, dof, v, alpha) < want) return 1;
    for (i = 0; i < 50; ++i) {
        double mid = 0.5 * (lo + hi);
        if (catch_prob(mid, nwo, n, dof, v, alpha) >= want)
            hi = mid;
        else
            lo = mid;
    }
    return hi;
}

long cf_power_samples(double eps, int nwo, int ncell, int nz, double alpha, double want, long max)
{
    long n[CF_MAX_WO], dof[CF_MAX_WO], lo = 1, hi = max;
    double v[CF_MAX_WO];
    int w;
    if (nwo > CF_MAX_WO) nwo = CF_MAX_WO;
    for (w = 0; w < nwo; ++w) {
        dof[w] = ncell - 1;
        v[w] = (1 - 1.0 / ((double)nz * nz)) / 3;
    }
    for (w = 0; w < nwo; ++w) n[w] = hi;
    if (catch_prob(eps, nwo, n, dof, v, alpha) < want) return max;
    while (hi - lo > 1 && hi - lo > lo / 1000) {
        long mid = lo + (hi - lo) / 2;
        for (w = 0; w < nwo; ++w) n[w] = mid;
        if (catch_prob(eps, nwo, n, dof, v, alpha) >= want)
            hi = mid;
        else
            lo = mid;
    }
    return hi;
}
