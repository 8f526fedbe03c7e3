/*
 * Internal: pbrt-v2's piecewise-constant distributions (core/montecarlo.h
 * Distribution1D and Distribution2D), for the infinite light's importance
 * sampling.
 */
#ifndef MT_TRACER_DISTRIB_H
#define MT_TRACER_DISTRIB_H

#include "materia/error.h"

typedef struct mt__distrib1d {
    int count;
    mt_real *func; /* count values */
    mt_real *cdf;  /* count + 1 values */
    mt_real func_int;
} mt__distrib1d;

typedef struct mt__distrib2d {
    int nu, nv;
    mt__distrib1d *conditional; /* nv rows over u */
    mt__distrib1d marginal;     /* over v: each row's integral */
} mt__distrib2d;

/* Copies f (count >= 1 values, finite and >= 0). */
mt_status mt__distrib1d_init(mt__distrib1d *d, const mt_real *f, int count, mt_error *err);
void mt__distrib1d_free(mt__distrib1d *d);
/* pbrt-v2 SampleContinuous: x in [0, 1), *pdf = func[i] / funcInt (0 when
 * funcInt is 0), *offset the segment. */
mt_real mt__distrib1d_sample(const mt__distrib1d *d, mt_real u, mt_real *pdf, int *offset);

/* func has nu * nv values, row v at func + v * nu. */
mt_status mt__distrib2d_init(mt__distrib2d *d, const mt_real *func, int nu, int nv, mt_error *err);
void mt__distrib2d_free(mt__distrib2d *d);
/* pbrt-v2 SampleContinuous(u0, u1): uv[1] from the marginal with u1, uv[0]
 * from that row with u0; *pdf the product of the two densities. */
void mt__distrib2d_sample(const mt__distrib2d *d, mt_real u0, mt_real u1, mt_real uv[2],
                          mt_real *pdf);
/* pbrt-v2 Pdf(u, v): the density at (u, v) in [0,1]^2; 0 where the integrals
 * are 0. */
mt_real mt__distrib2d_pdf(const mt__distrib2d *d, mt_real u, mt_real v);

#endif
