/*
 * The power of the suite's chi-square against a smooth mismatch between an
 * implementation's sampler and its pdf (power.c): the non-centrality a
 * configuration's own cells give, the smallest mismatch a run could have
 * caught, and the samples per direction that catch a given one (--power).
 */
#ifndef CF_POWER_H
#define CF_POWER_H

#include "core.h"

/* The probability that the chi-square of dof degrees of freedom with
 * non-centrality lambda exceeds crit (the Poisson mixture of central
 * chi-squares, exact to 1e-12). */
double cf_ncchi2_sf(double crit, double dof, double lambda);
/* The x with cf_chi2_pvalue(x, dof) = alpha. */
double cf_chi2_upper_quantile(double alpha, double dof);

/* Two tests see a smooth mismatch at each direction: the chi-square over
 * its cells (CF_PW_CHI2, dof degrees of freedom) and the mean of its
 * sampled directions (CF_PW_MEAN: the means of x, y, z and |z| of wi at
 * the cells' centres against its pdf's, a chi-square of as many degrees of
 * freedom as those functions are independent under the pdf, 3 for a
 * reflection, 4 with transmission); two reference mismatches of relative
 * size eps are what they are measured against:
 *
 *  CF_PW_WARP   the sampled density is p (1 + eps g), g = 2 F(z) - 1 with F
 *               the distribution of z = cos theta_i under p's non-delta part
 *               (the warp u -> u + eps u (1 - u) of an inverse-CDF sampler of
 *               cos theta_i); the pdf honest
 *  CF_PW_SHAPE  the pdf is p (1 + eps s (|cos theta_i| - m)), m the mean
 *               and sd the standard deviation of |cos theta_i| under p,
 *               s = (1 / sqrt 18) / sd: a tilt measured in the lobe's own
 *               spread, exactly 1 + eps (cos theta_i - m) on a Lambertian
 *               lobe; the samples follow p
 *
 * Each test's statistic is then (for small eps) a non-central chi-square
 * of non-centrality n eps^2 v: v[test][ref] of a direction, from its cells
 * and the probability pc of each (the non-delta part: it sums to the
 * fraction of samples that land in a cell; from the cubature of its pdf,
 * or from its pilot's counts). The chi-square's v is the sum over rows of
 * P_r g_r^2 (g constant over a row: Cochran 1952); the mean test's is the
 * squared length of the mismatch's projection on its functions
 * (orthonormalized under the pdf): far fewer degrees of freedom see the
 * part of a smooth mismatch that lies along them with far fewer samples. */
enum { CF_PW_CHI2, CF_PW_MEAN, CF_PW_NTEST };
enum { CF_PW_WARP, CF_PW_SHAPE, CF_PW_NREF };
extern const char *const cf_power_test_name[CF_PW_NTEST];

/* |cos theta_i| of row r: the mean of |z| over the row (a row across the
 * horizon: over its two halves) */
double cf_power_row_h(const cf_layout *l, int r);

/* The mean test's functions at cell c, what each sample in it counts as:
 * x, y, z of its centre (mid z, mid phi) and its row's |z|. */
#define CF_MEAN_DIM 4
void cf_mean_funcs(const cf_layout *l, int c, double h[CF_MEAN_DIM]);
/* Their means under cell probabilities pc, and rank combinations of them,
 * centred, orthonormal under pc (a[k] . (h - mu)): its rank. */
typedef struct cf_mean_basis {
    int rank;
    double mu[CF_MEAN_DIM], var[CF_MEAN_DIM]; /* the functions' means and variances */
    double a[CF_MEAN_DIM][CF_MEAN_DIM];
} cf_mean_basis;
int cf_mean_basis_of(const cf_layout *l, const double *pc, cf_mean_basis *b);

/* The shapes of a direction, and the mean test's degrees of freedom. */
void cf_power_shapes(const cf_layout *l, const double *pc, double v[CF_PW_NTEST][CF_PW_NREF], int *mdof);

/* What a configuration's power is computed from: per direction, its samples
 * n, the chi-square's degrees of freedom, the mean test's, and the shapes. */
typedef struct cf_power_dir {
    long n, dof, mdof;
    double v[CF_PW_NTEST][CF_PW_NREF];
} cf_power_dir;

/* The probability that test catches the reference mismatch ref of size eps
 * at a configuration (caught when any direction's test fails), each test at
 * level alpha. */
double cf_power_catch(int test, int ref, double eps, int nwo, const cf_power_dir *d, double alpha);

/* The smallest eps of ref that test catches with probability want (1 or
 * more: not at any eps < 1). */
double cf_power_min_eps(int test, int ref, int nwo, const cf_power_dir *d, double alpha, double want);

/* The samples per direction with which each reference mismatch of size eps
 * is caught with probability want by the test most powerful against it
 * (the most the two references need), from the directions' shapes (their
 * n ignored), capped at max; 0 when no test sees either reference (no
 * direction has cells: delta lobes alone). */
long cf_power_samples_for(double eps, int nwo, const cf_power_dir *d, double alpha, double want, long max);

/* An estimate before any pilot (the pilot's size is set from it): the
 * samples per direction with which the chi-square catches the warp eps with
 * probability want: nwo directions of ncell cells in nz rows (equal-probability
 * rows, the pilot's, and no delta part: the configuration's own cells may
 * give less, which the run's printed figure shows), capped at max. */
long cf_power_samples(double eps, int nwo, int ncell, int nz, double alpha, double want, long max);

#endif
