/*
 * Checks shared by the tests of MERL tables: a BSDF tabulated at the MERL
 * grid (mt_merl_tabulate), written and read back as a RegularHalfangleBRDF,
 * compared with the BSDF itself.
 */
#ifndef MT_TEST_MERL_CHECK_H
#define MT_TEST_MERL_CHECK_H

#include "materia.h"

/* The direction pair (local frame) at continuous MERL coordinates: uh in
 * units of theta_h bins (sqrt scale), ud of theta_d bins, up of phi_d bins,
 * the whole pair turned by phi_h about the normal. Computed in double; the
 * grid points are the integers (mt_merl_grid_directions). */
void t_merl_pair(double uh, double ud, double up, double phi_h, mt_vec3 *wo, mt_vec3 *wi);

/* Compares table (a BSDF holding the RegularHalfangleBRDF read back) with
 * truth (the BSDF tabulated), both with world = local, over random bins
 * away from the grid's degenerate regions (theta_h bins below 8, where the
 * half vector's float angle is quantized; theta_d below 2 degrees, where
 * phi_d is undefined; bins reaching within cos 0.05 of the horizon):
 *   - inside a bin the table gives truth at the bin's lower corner (the grid
 *     point) to the storage rounding;
 *   - anywhere, |table - truth| is within the bin's corner variation (the
 *     most f changes from the grid point to another corner of the bin: the
 *     error bound of a piecewise-constant lookup where f is monotone across
 *     a bin);
 *   - the mean error grows linearly with the offset into the bin (first
 *     order in the bin width).
 * Prints the checks under the name prefix and the measured errors. */
void t_merl_roundtrip_checks(const char *prefix, const mt_bsdf *truth, const mt_bsdf *table);

#endif
