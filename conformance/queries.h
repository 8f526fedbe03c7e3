/*
 * Queries the float and the double build answer alike, and the distance in
 * ULPs between their answers: the suite's float-versus-double check
 * (ulps.c) and make tradeoff's precision measurement (tradeoff/precision.c).
 */
#ifndef MT_CONF_QUERIES_H
#define MT_CONF_QUERIES_H

#include "materia.h"

/* x rounded to float, as mt_real: an input both builds represent exactly.
 * Rounded through a volatile float (GCC 12's vectorizer may drop a plain
 * (double)(float) pair: docs/CONTRIBUTING.md). */
mt_real cf_as_float(double x);

/* A direction uniform over the sphere whose components are floats. */
mt_vec3 cf_query_dir(mt_rng *r);

/* One query: f and pdf of (wo, wi); sample_f of (wo, uc, u1, u2). */
typedef struct cf_query {
    mt_vec3 wo, wi;
    mt_real uc, u1, u2;
} cf_query;

/* The next query of the stream r, drawn in a fixed order (wo, wi, uc, u1,
 * u2), so that both builds and every compiler make the same queries. */
cf_query cf_query_next(mt_rng *r);

/* |a - b| in units of the spacing of a binary floating-point type with `bits`
 * significant bits (24: float, 53: double) at max(|a|, |b|, floor): floor
 * puts values far below their configuration's scale on that scale, where
 * their rounding is harmless. 0 when a == b, or when that magnitude is below
 * the type's smallest normal number (where the spacing stops shrinking with
 * the magnitude, both values are rounding noise). */
double cf_ulp_distance(double a, double b, double floor, int bits);

#endif
