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
#include <stdlib.h>
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


const char *const cf_power_test_name[CF_PW_NTEST] = {"chi2", "mean wi"};

double cf_power_row_h(const cf_layout *l, int r)
{
    double a = fabs(l->z[r]), b = fabs(l->z[r + 1]);
    return l->z[r] < 0 && l->z[r + 1] > 0 ? (a * a + b * b) / (2 * (a + b)) : 0.5 * (a + b);
}

void cf_mean_funcs(const cf_layout *l, int c, double h[CF_MEAN_DIM])
{
    double p0, p1, z0, z1, z, s, phi;
    cf_layout_bounds(l, c, &p0, &p1, &z0, &z1);
    z = 0.5 * (z0 + z1);
    s = sqrt(fmax(0, 1 - z * z));
    phi = 0.5 * (p0 + p1);
    h[0] = s * cos(phi);
    h[1] = s * sin(phi);
    h[2] = z;
    h[3] = cf_power_row_h(l, cf_layout_row(l, c));
}

int cf_mean_basis_of(const cf_layout *l, const double *pc, cf_mean_basis *b)
{
    double total = 0, S[CF_MEAN_DIM][CF_MEAN_DIM], h[CF_MEAN_DIM];
    int c, j, k, i;
    memset(b, 0, sizeof *b);
    memset(S, 0, sizeof S);
    for (c = 0; c < l->ncell; ++c) {
        double p = pc[c] > 0 ? pc[c] : 0;
        if (!(p > 0)) continue;
        cf_mean_funcs(l, c, h);
        total += p;
        for (j = 0; j < CF_MEAN_DIM; ++j) {
            b->mu[j] += p * h[j];
            for (k = 0; k < CF_MEAN_DIM; ++k) S[j][k] += p * h[j] * h[k];
        }
    }
    if (!(total > 0)) return 0;
    for (j = 0; j < CF_MEAN_DIM; ++j) b->mu[j] /= total;
    for (j = 0; j < CF_MEAN_DIM; ++j)
        for (k = 0; k < CF_MEAN_DIM; ++k) S[j][k] = S[j][k] / total - b->mu[j] * b->mu[k];
    for (j = 0; j < CF_MEAN_DIM; ++j) b->var[j] = fmax(S[j][j], 0);
    /* Gram-Schmidt in the covariance's inner product: combinations of the
     * centred functions, orthonormal under the pdf; a function that the
     * others already give (z = |z| above the surface) adds no dimension */
    for (j = 0; j < CF_MEAN_DIM; ++j) {
        double v[CF_MEAN_DIM] = {0, 0, 0, 0}, nn = 0;
        v[j] = 1;
        for (k = 0; k < b->rank; ++k) {
            double dot = 0;
            for (i = 0; i < CF_MEAN_DIM; ++i) dot += b->a[k][i] * S[i][j];
            for (i = 0; i < CF_MEAN_DIM; ++i) v[i] -= dot * b->a[k][i];
        }
        for (i = 0; i < CF_MEAN_DIM; ++i)
            for (k = 0; k < CF_MEAN_DIM; ++k) nn += v[i] * S[i][k] * v[k];
        if (!(nn > 1e-9 * S[j][j]) || !(nn > 1e-14)) continue;
        for (i = 0; i < CF_MEAN_DIM; ++i) b->a[b->rank][i] = v[i] / sqrt(nn);
        b->rank++;
    }
    return b->rank;
}

void cf_power_shapes(const cf_layout *l, const double *pc, double v[CF_PW_NTEST][CF_PW_NREF], int *mdof)
{
    double total = 0, below = 0, m = 0, chi = 0, var = 0, spread = 0, proj[CF_PW_NREF][CF_MEAN_DIM], *g = NULL, h[CF_MEAN_DIM];
    double *prow = calloc((size_t)(l->nrow > 0 ? l->nrow : 1), sizeof *prow);
    cf_mean_basis b;
    int r, c, k, j;
    memset(v, 0, sizeof(double) * CF_PW_NTEST * CF_PW_NREF);
    memset(proj, 0, sizeof proj);
    *mdof = 0;
    if (!prow || !(g = calloc((size_t)l->nrow, sizeof *g))) goto out;
    for (c = 0; c < l->ncell; ++c) prow[cf_layout_row(l, c)] += pc[c] > 0 ? pc[c] : 0;
    for (r = 0; r < l->nrow; ++r) {
        total += prow[r];
        m += prow[r] * cf_power_row_h(l, r);
    }
    if (!(total > 0)) goto out;
    m /= total;
    for (r = 0; r < l->nrow; ++r) {
        double hr = cf_power_row_h(l, r) - m;
        /* the mean of 2 F - 1 over the row: F runs from below / total to
         * (below + pr) / total across it */
        g[r] = (2 * below + prow[r]) / total - 1;
        chi += prow[r] * g[r] * g[r];
        var += prow[r] * hr * hr;
        below += prow[r];
    }
    /* The pdf shape is measured in the lobe's own spread: the tilt is eps
     * times |cos theta_i|'s standardized deviation times a Lambertian lobe's
     * standard deviation (1 / sqrt 18), which on a Lambertian lobe is exactly
     * 1 + eps (|cos theta_i| - m). Unscaled, a narrow glossy lobe (|cos
     * theta_i| nearly constant over it) would ask for millions of samples to
     * see a tilt that changes its pdf by far less than eps anywhere. */
    spread = var > 0 ? (1.0 / 18) / var : 0;
    v[CF_PW_CHI2][CF_PW_WARP] = chi;
    v[CF_PW_CHI2][CF_PW_SHAPE] = var * spread;
    /* the mean test: the mismatch's projection on its orthonormal
     * functions, squared and summed (times the fraction in cells) */
    *mdof = cf_mean_basis_of(l, pc, &b);
    for (c = 0; c < l->ncell; ++c) {
        double p = pc[c] > 0 ? pc[c] / total : 0, ref[CF_PW_NREF];
        if (!(p > 0)) continue;
        r = cf_layout_row(l, c);
        ref[CF_PW_WARP] = g[r];
        ref[CF_PW_SHAPE] = cf_power_row_h(l, r) - m;
        cf_mean_funcs(l, c, h);
        for (k = 0; k < b.rank; ++k) {
            double e = 0;
            for (j = 0; j < CF_MEAN_DIM; ++j) e += b.a[k][j] * (h[j] - b.mu[j]);
            proj[CF_PW_WARP][k] += p * e * ref[CF_PW_WARP];
            proj[CF_PW_SHAPE][k] += p * e * ref[CF_PW_SHAPE];
        }
    }
    for (k = 0; k < b.rank; ++k) {
        v[CF_PW_MEAN][CF_PW_WARP] += total * proj[CF_PW_WARP][k] * proj[CF_PW_WARP][k];
        v[CF_PW_MEAN][CF_PW_SHAPE] += spread * total * proj[CF_PW_SHAPE][k] * proj[CF_PW_SHAPE][k];
    }
out:
    free(prow);
    free(g);
}

double cf_power_catch(int test, int ref, double eps, int nwo, const cf_power_dir *d, double alpha)
{
    double miss = 1;
    int w;
    for (w = 0; w < nwo; ++w) {
        double lambda = (double)d[w].n * eps * eps * d[w].v[test][ref];
        long dof = test == CF_PW_CHI2 ? d[w].dof : d[w].mdof;
        if (!(d[w].v[test][ref] > 0) || d[w].n < 1 || dof < 1) continue;
        miss *= 1 - cf_ncchi2_sf(cf_chi2_upper_quantile(alpha, (double)dof), (double)dof, lambda);
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

/* Whether test sees ref at all at some direction (its shape not 0). */
static int visible(int test, int ref, int nwo, const cf_power_dir *d)
{
    int w;
    for (w = 0; w < nwo; ++w)
        if (d[w].v[test][ref] > 0 && (test == CF_PW_CHI2 ? d[w].dof : d[w].mdof) >= 1) return 1;
    return 0;
}

long cf_power_samples_for(double eps, int nwo, const cf_power_dir *d, double alpha, double want, long max)
{
    long need = 0;
    int ref, test;
    for (ref = 0; ref < CF_PW_NREF; ++ref) {
        long best = max;
        int seen = 0;
        for (test = 0; test < CF_PW_NTEST; ++test) {
            long n;
            if (!visible(test, ref, nwo, d)) continue;
            seen = 1;
            n = samples_for(test, ref, eps, nwo, d, alpha, want, max);
            if (n < best) best = n;
        }
        /* a reference no test can see (a configuration of delta lobes
         * alone: no cells) asks for nothing; more samples would not help */
        if (seen && best > need) need = best;
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
