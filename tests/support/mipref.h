/*
 * Ground truth for MIP-map lookups that does not use materia's MIP-map: test
 * patterns (sums of sinusoids, whose derivatives are known), the images
 * sampled from them at texel centers, and reference filters applied to the
 * bilinear interpolant of the level-0 image, in double precision:
 *   - the box of side w (trilinear's square footprint, and what "no filter"
 *     should approximate), integrated exactly: the box of the bilinear
 *     interpolant is a separable sum of integrated tents;
 *   - the Gaussian-weighted ellipse of EWA, exp(-2 r^2) - exp(-2) for r < 1
 *     with r from the ellipse whose conjugate semi-diameters are the two
 *     differentials, by a midpoint rule in polar coordinates.
 * Each reference is itself a non-negative unit-mass kernel on the level-0
 * samples, so it reports the kernel's centroid offset and second moment
 * about the lookup point along with the value: the Taylor bounds of
 * tests/test_mipmap.c need them. Used by tests/test_mipmap.c and
 * bench/mipmap.c.
 */
#ifndef MT_TEST_MIPREF_H
#define MT_TEST_MIPREF_H

#include <stdint.h>
#include "materia.h"
#include "materia/image.h"
#include "materia/mipmap.h"

#define T_MAX_WAVES 4

/* offset + sum of a_k cos(2 pi (fx_k x + fy_k y) + phase_k); x, y in
 * texture units (0..1 spans the image). */
typedef struct t_pattern {
    int nwaves;
    double offset, a[T_MAX_WAVES], fx[T_MAX_WAVES], fy[T_MAX_WAVES], phase[T_MAX_WAVES];
} t_pattern;

/* Low frequencies (at most 3.6 cycles across the image). */
t_pattern t_pattern_smooth(void);
/* One wave of integer frequency (37, 11) cycles: about 7 texels a period
 * across a 256-texel image. */
t_pattern t_pattern_high(void);
double t_pattern_value(const t_pattern *p, double x, double y);
void t_pattern_gradient(const t_pattern *p, double x, double y, double g[2]);
/* A bound on the spectral norm of the Hessian everywhere:
 * sum |a_k| (2 pi |f_k|)^2. */
double t_pattern_hessian_bound(const t_pattern *p);

/* The n x n one-channel image of the pattern at texel centers
 * ((i + 0.5) / n), or of (x - cx) (which 1), (y - cy) (which 2),
 * (x - cx)^2 + (y - cy)^2 (which 3) for measuring kernel moments. */
void t_pattern_image(const t_pattern *p, int n, mt_image *img);
void t_moment_image(int n, int which, double cx, double cy, mt_image *img);

/* A reference filter's answer: the value and its kernel's centroid offset
 * (dx, dy) from the lookup point and second moment m2 about it. */
typedef struct t_ref {
    double value, dx, dy, m2;
} t_ref;

/* Box of side w centered at (x, y); the box must lie inside the image. */
t_ref t_ref_box(const mt_image *img, double x, double y, double w);
/* The Gaussian-weighted ellipse with conjugate semi-diameters (d0s, d0t)
 * and (d1s, d1t) centered at (x, y); it must lie inside the image. */
t_ref t_ref_ellipse(const mt_image *img, double x, double y, double d0s, double d0t, double d1s,
                    double d1t);

/* A lookup footprint: point, isotropic width and EWA differentials
 * (ds1, dt1 is the shorter axis); cs1, ct1 the shorter axis after pbrt-v2's
 * maxanisotropy clamp, i.e. the ellipse EWA filters over. Footprints come in
 * clusters of per_cluster around centers (cx, cy) so that one set of moment
 * images serves a cluster. */
typedef struct t_footprint {
    double cx, cy, x, y, w, ds0, dt0, ds1, dt1, cs1, ct1;
} t_footprint;

/* count = nclusters * per_cluster footprints for an n x n image: centers in
 * [0.35, 0.65]^2, points within 4 texels of their center, widths 0.5 to 16
 * texels, EWA major semi-axes 1 to 16 texels with axis ratios 1 to 16. */
void t_footprints(t_footprint *f, int nclusters, int per_cluster, int n, double maxaniso,
                  uint64_t seed);

/* The filters compared: point (bilinear at level 0, "no filter"),
 * trilinear at width w, trilinear at pbrt-v2's doubled width 2w, and EWA
 * with the footprint's differentials. */
enum { T_F_POINT, T_F_TRI, T_F_TRI_PBRT, T_F_EWA, T_NFILTERS };
extern const char *const t_filter_names[T_NFILTERS];
/* A filter's lookup (channel 0), and its reference: the box of side w for
 * the isotropic filters, the clamped Gaussian ellipse for EWA. */
double t_filter_lookup(const mt_mipmap *m, int filter, const t_footprint *p);
t_ref t_filter_reference(const mt_image *img, int filter, const t_footprint *p);

#endif
