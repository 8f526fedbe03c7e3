/*
 * The power of the suite's tests against a smooth sampler/pdf mismatch
 * (power.h). A sampled density q = p (1 + eps g), g of mean 0 under p and
 * constant over each cell's row of cos theta_i, moves the expected count of
 * cell c from n p_c to n p_c (1 + eps g_c), so Pearson's statistic over the
 * cells is a non-central chi-square of non-centrality
 * lambda = n eps^2 sum_c p_c g_c^2 (Cochran 1952; the classical result for
 * local alternatives). Its power at level alpha is the upper tail of that
 * distribution beyond the central quantile. The mean of |cos theta_i| over
 * the same rows is one linear contrast of those counts: a normal statistic
 * shifted by the projection of the mismatch on it, a z test of one degree of
 * freedom, which needs fewer samples wherever the mismatch lies mostly along
 * |cos theta_i| (the critical value of a chi-square of 400 degrees of
 * freedom is far above that of one). A configuration is caught when any of
 * its directions' tests fails: 1 - prod_w (1 - power_w).
 */
#include <math.h>
#include <string.h>
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


const char *const cf_power_test_name[CF_PW_NTEST] = {"chi2", "mean cos"};

double cf_power_row_h(const cf_layout *l, int r)
{
    double a = fabs(l->z[r]), b = fabs(l->z[r + 1]);
    return l->z[r] < 0 && l->z[r + 1] > 0 ? (a * a + b * b) / (2 * (a + b)) : 0.5 * (a + b);
}

int cf_layout_row(const cf_layout *l, int c)
{
    int lo = 0, hi = l->nrow - 1;
    while (lo < hi) {
        int mid = (lo + hi + 1) / 2;
        if (l->first[mid] <= c)
            lo = mid;
        else
            hi = mid - 1;
    }
    return lo;
}

void cf_power_shapes(const cf_layout *l, const double *prow, double v[CF_PW_NTEST][CF_PW_NREF])
{
    double total = 0, below = 0, m = 0, chi = 0, var = 0, cov = 0;
    int r;
    memset(v, 0, sizeof(double) * CF_PW_NTEST * CF_PW_NREF);
    for (r = 0; r < l->nrow; ++r) {
        double pr = prow[r] > 0 ? prow[r] : 0;
        total += pr;
        m += pr * cf_power_row_h(l, r);
    }
    if (!(total > 0)) return;
    m /= total;
    for (r = 0; r < l->nrow; ++r) {
        double pr = prow[r] > 0 ? prow[r] : 0, h = cf_power_row_h(l, r) - m;
        /* the mean of 2 F - 1 over the row: F runs from below / total to
         * (below + pr) / total across it */
        double g = (2 * below + pr) / total - 1;
        chi += pr * g * g;
        var += pr * h * h;
        cov += pr * h * g;
        below += pr;
    }
    v[CF_PW_CHI2][CF_PW_WARP] = chi;
    v[CF_PW_CHI2][CF_PW_SHAPE] = var;
    v[CF_PW_MEAN][CF_PW_WARP] = var > 0 ? cov * cov / var : 0;
    v[CF_PW_MEAN][CF_PW_SHAPE] = var;
}

/* The probability that a two-sided z test at alpha rejects when its
 * statistic is shifted by sqrt(lambda) standard deviations. */
static double z_power(double alpha, double lambda)
{
    double z = cf_normal_two_sided_z(alpha), d = sqrt(lambda > 0 ? lambda : 0);
    return 0.5 * erfc((z - d) / sqrt(2.0)) + 0.5 * erfc((z + d) / sqrt(2.0));
}

double cf_power_catch(int test, int ref, double eps, int nwo, const cf_power_dir *d, double alpha)
{
    double miss = 1;
    int w;
    for (w = 0; w < nwo; ++w) {
        double lambda = (double)d[w].n * eps * eps * d[w].v[test][ref];
        if (!(d[w].v[test][ref] > 0) || d[w].n < 1) continue;
        if (test == CF_PW_CHI2) {
            if (d[w].dof < 1) continue;
            miss *= 1 - cf_ncchi2_sf(cf_chi2_upper_quantile(alpha, (double)d[w].dof), (double)d[w].dof, lambda);
        } else {
            miss *= 1 - z_power(alpha, lambda);
        }
    }
    return 1 - miss;
}

double cf_power_min_eps(int test, int ref, int nwo, const cf_power_dir *d, double alpha, double want)
{
    double lo = 0, hi = 1;
    int i;
    if (cf_power_catch(test, ref, hi, nwo, d, alpha) < want) return 1;
    for (i = 0; i < 50; ++i) {
        double mid = 0.5 * (lo + hi);
        if (cf_power_catch(test, ref, mid, nwo, d, alpha) >= want)
            hi = mid;
        else
            lo = mid;
    }
    return hi;
}

/* The samples per direction with which test catches ref's eps with
 * probability want, capped at max. */
static long samples_for(int test, int ref, double eps, int nwo, const cf_power_dir *d0, double alpha, double want,
                        long max)
{
    cf_power_dir d[CF_MAX_WO];
    long lo = 1, hi = max;
    int w;
    if (nwo > CF_MAX_WO) nwo = CF_MAX_WO;
    for (w = 0; w < nwo; ++w) {
        d[w] = d0[w];
        d[w].n = hi;
    }
    if (cf_power_catch(test, ref, eps, nwo, d, alpha) < want) return max;
    while (hi - lo > 1 && hi - lo > lo / 1000) {
        long mid = lo + (hi - lo) / 2;
        for (w = 0; w < nwo; ++w) d[w].n = mid;
        if (cf_power_catch(test, ref, eps, nwo, d, alpha) >= want)
            hi = mid;
        else
            lo = mid;
    }
    return hi;
}

long cf_power_samples_for(double eps, int nwo, const cf_power_dir *d, double alpha, double want, long max)
{
    long need = 1;
    int ref, test;
    for (ref = 0; ref < CF_PW_NREF; ++ref) {
        long best = max;
        for (test = 0; test < CF_PW_NTEST; ++test) {
            long n = samples_for(test, ref, eps, nwo, d, alpha, want, max);
            if (n < best) best = n;
        }
        if (best > need) need = best;
    }
    return need;
}

long cf_power_samples(double eps, int nwo, int ncell, int nz, double alpha, double want, long max)
{
    cf_power_dir d[CF_MAX_WO];
    int w;
    if (nwo > CF_MAX_WO) nwo = CF_MAX_WO;
    memset(d, 0, sizeof d);
    for (w = 0; w < nwo; ++w) {
        d[w].dof = ncell - 1;
        d[w].v[CF_PW_CHI2][CF_PW_WARP] = (1 - 1.0 / ((double)nz * nz)) / 3;
    }
    return samples_for(CF_PW_CHI2, CF_PW_WARP, eps, nwo, d, alpha, want, max);
}
