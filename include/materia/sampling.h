/*
 * materia/sampling.h -- Monte Carlo helpers with pbrt-v2's exact mappings
 * (montecarlo.h/.cpp, geometry.h), so that the same uniform numbers give the
 * same points and directions as pbrt-v2.
 *
 * Thread safety: functions of their arguments alone, except the stratified
 * ones, which draw from the mt_rng they are given (one thread at a time
 * per generator).
 */
#ifndef MATERIA_SAMPLING_H
#define MATERIA_SAMPLING_H

#include "materia/vec.h"
#include "materia/rng.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Shirley-Chiu concentric map of [0,1)^2 to the unit disk, with pbrt-v2's
 * region tests and its degenerate case (the center maps to the origin). */
MT_API void mt_concentric_sample_disk(mt_real u1, mt_real u2, mt_real *dx, mt_real *dy);
MT_API void mt_uniform_sample_disk(mt_real u1, mt_real u2, mt_real *x, mt_real *y);

/* Cosine-weighted upper hemisphere via the concentric disk (Malley). */
MT_API mt_vec3 mt_cosine_sample_hemisphere(mt_real u1, mt_real u2);
MT_API mt_real mt_cosine_hemisphere_pdf(mt_real costheta);

/* z = u1, phi = 2 pi u2. */
MT_API mt_vec3 mt_uniform_sample_hemisphere(mt_real u1, mt_real u2);
MT_API mt_real mt_uniform_hemisphere_pdf(void);

/* z = 1 - 2 u1, phi = 2 pi u2. */
MT_API mt_vec3 mt_uniform_sample_sphere(mt_real u1, mt_real u2);
MT_API mt_real mt_uniform_sphere_pdf(void);

/* Uniform in the cone about +z with cos(theta) >= costhetamax. */
MT_API mt_vec3 mt_uniform_sample_cone(mt_real u1, mt_real u2, mt_real costhetamax);
/* The same about the frame (x, y, z), pbrt-v2's Lerp form. */
MT_API mt_vec3 mt_uniform_sample_cone_frame(mt_real u1, mt_real u2, mt_real costhetamax,
                                            mt_vec3 x, mt_vec3 y, mt_vec3 z);
MT_API mt_real mt_uniform_cone_pdf(mt_real costhetamax);

/* Barycentric (u, v) uniform over a triangle (pbrt-v2 UniformSampleTriangle). */
MT_API void mt_uniform_sample_triangle(mt_real u1, mt_real u2, mt_real *u, mt_real *v);

/* Spherical coordinates (pbrt-v2 geometry.h). */
MT_API mt_vec3 mt_spherical_direction(mt_real sintheta, mt_real costheta, mt_real phi);
MT_API mt_vec3 mt_spherical_direction_frame(mt_real sintheta, mt_real costheta, mt_real phi,
                                            mt_vec3 x, mt_vec3 y, mt_vec3 z);
/* acos of the clamped z, in [0, pi]. */
MT_API mt_real mt_spherical_theta(mt_vec3 v);
/* atan2(y, x) moved into [0, 2 pi). */
MT_API mt_real mt_spherical_phi(mt_vec3 v);

/* Jittered (or centred) stratified samples, pbrt-v2's StratifiedSample1D/2D;
 * samp receives n (1D) or 2 * nx * ny (2D) values, each below one. */
MT_API void mt_stratified_sample_1d(mt_real *samp, int n, mt_rng *rng, int jitter);
MT_API void mt_stratified_sample_2d(mt_real *samp, int nx, int ny, mt_rng *rng, int jitter);
/* Row y of that 2D grid alone (2 * nx values), drawing the same numbers. */
MT_API void mt_stratified_row_2d(mt_real *samp, int nx, int ny, int y, mt_rng *rng, int jitter);

/* Multiple importance sampling weights (Veach). */
MT_API mt_real mt_balance_heuristic(int nf, mt_real fpdf, int ng, mt_real gpdf);
MT_API mt_real mt_power_heuristic(int nf, mt_real fpdf, int ng, mt_real gpdf);

#ifdef __cplusplus
}
#endif

#endif
