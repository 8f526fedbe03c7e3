/*
 * Checks shared by the tests of MERL tables: a BSDF tabulated with
 * mt_merl_tabulate, written and read back as a RegularHalfangleBRDF,
 * compared with the BSDF itself.
 */
#ifndef MT_TEST_MERL_CHECK_H
#define MT_TEST_MERL_CHECK_H

#include "materia/tools/merl.h"

/* mt_merl_directions turned by phi_h about the normal. */
void t_merl_pair(double uh, double ud, double up, double phi_h, mt_vec3 *wo, mt_vec3 *wi);

/* Compares table (a BSDF holding the RegularHalfangleBRDF read back) with
 * truth (the BSDF tabulated at `at`), both with world = local, over random
 * bins away from the grid's degenerate regions (theta_h bins below 8, where
 * the half vector's float angle is quantized; theta_d below 2 degrees,
 * where phi_d is undefined; bins reaching within cos 0.05 of the horizon),
 * at random phi_h:
 *   - inside a bin the table gives truth at the bin's sample point (corner
 *     or centre) to the storage rounding;
 *   - anywhere in a bin, |table - truth| is within the bin's corner
 *     variation: the most truth changes from the sample point to a corner of
 *     the bin, the error bound of a piecewise-constant lookup where f is
 *     monotone across a bin;
 *   - the mean error grows linearly with the distance from the sample point
 *     (first order in the bin width).
 * Prints the checks under the name prefix, and the measured errors. */
void t_merl_roundtrip_checks(const char *prefix, const mt_bsdf *truth, const mt_bsdf *table,
                             mt_merl_at at);

#endif
