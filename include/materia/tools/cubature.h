/*
 * materia/tools/cubature.h -- adaptive cubature in double precision, and
 * reflectance by quadrature.
 *
 * mt_cubature integrates a vector-valued function over a rectangle with
 * tensor-product Gauss-Kronrod rules (7-point Gauss embedded in 15-point
 * Kronrod on each axis; the difference of the two estimates is the error
 * estimate), refining the region with the largest error until every
 * component meets its tolerance. Narrow peaks that no initial node sees
 * cannot be found by any quadrature: callers that know where mass may lie
 * start from a finer grid there (mt_bxdf_rho_quad uses the BxDF's own
 * sampler to find it).
 *
 * Thread safety: functions of their arguments (the integrand is called on
 * the calling thread).
 */
#ifndef MATERIA_TOOLS_CUBATURE_H
#define MATERIA_TOOLS_CUBATURE_H

#include "materia/bsdf.h"

#ifdef __cplusplus
extern "C" {
#endif

#define MT_CUBATURE_MAX_COMPONENTS 8

typedef void (*mt_cubature_fn)(void *ctx, double x, double y, double *out);

typedef struct mt_cubature_result {
    double value[MT_CUBATURE_MAX_COMPONENTS];
    double error[MT_CUBATURE_MAX_COMPONENTS];
    long evaluations;
    int converged; /* every component met max(abs_tol, rel_tol * |value|) */
} mt_cubature_result;

/* Integrates f (ncomp components) over [x0,x1] x [y0,y1], starting from an
 * nx by ny grid of regions, until converged or max_evals evaluations.
 * Returns MT_ERR_NOMEM or MT_ERR_INVALID (bad arguments) with err filled. */
MT_API mt_status mt_cubature(mt_cubature_fn f, void *ctx, int ncomp, double x0, double x1,
                             double y0, double y1, int nx, int ny, double rel_tol,
                             double abs_tol, long max_evals, mt_cubature_result *res,
                             mt_error *err);

/* The initial grid side for a cell in which a sampler put `ratio` times the
 * average number of samples: 1 for ordinary cells, up to 8 (node spacing of
 * a few milliradians in the cells used here) for cells holding a sharp peak.
 * A quadrature only finds mass its nodes see; the sampler says where to look,
 * the value is still the integral. */
MT_API int mt_cubature_grid(double ratio);

/* The direction with azimuth phi and cos(theta) = z: dw = dphi dz. */
MT_API mt_vec3 mt_sphere_direction(double phi, double z);

/* Hemispherical-directional reflectance of one BxDF by quadrature in double:
 * the integral of f(wo, wi) |cos theta_i| over the hemisphere the BxDF scatters
 * into (wo's for reflection, the other for transmission), to relative
 * tolerance rel_tol; a delta lobe contributes its sampled weight. */
MT_API mt_rgb mt_bxdf_rho_quad(const mt_bxdf *b, mt_vec3 wo, double rel_tol);

/* The sum over the matching components of mt_bxdf_rho_quad: BSDF::rho's
 * estimand computed exactly. In pbrt-v2 mode wo reaches the BxDFs in world
 * coordinates, as in pbrt-v2 (erratum rho-world-space). */
MT_API mt_rgb mt_bsdf_rho_quad(const mt_bsdf *b, mt_vec3 wo, unsigned flags, double rel_tol);

#ifdef __cplusplus
}
#endif

#endif
