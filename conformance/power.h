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

/* The reference mismatch: the sampled density is p (1 + eps g), g = 2 F(z)
 * - 1 with F the distribution of z = cos theta_i under p's non-delta part
 * (the warp u -> u + eps u (1 - u) of an inverse-CDF sampler of cos
 * theta_i). Over cells laid in rows of z, with pdfc the probability of
 * each cell, the chi-square's non-centrality is n eps^2 v: this returns v,
 * the sum over rows of P_r g_r^2, g_r the mean of g over row r. */
double cf_power_shape(const cf_layout *l, const double *pdfc);

/* The same for a pdf whose shape is off by 1 + eps (|cos theta_i| - m), m
 * the mean of |cos theta_i| under it (the row's mean of |z| taken at its
 * middle): weaker than the warp where the lobe is narrow in cos theta_i. */
double cf_power_shape_cos(const cf_layout *l, const double *pdfc);

/* The smallest eps a configuration catches with probability want: its
 * directions' samples n[w], degrees of freedom dof[w] and shapes v[w]
 * (directions with dof 0 or v 0 see nothing), each test at alpha; caught
 * when any direction's chi-square fails. 1 or more: not at any eps < 1. */
double cf_power_min_eps(int nwo, const long *n, const long *dof, const double *v, double alpha, double want);

/* The samples per direction that catch eps with probability want, before
 * the run: nwo directions of ncell cells in nz rows (equal-probability
 * rows, the pilot's, and no delta part: the configuration's own cells may
 * give less, which the run's printed figure shows), capped at max. */
long cf_power_samples(double eps, int nwo, int ncell, int nz, double alpha, double want, long max);

#endif
