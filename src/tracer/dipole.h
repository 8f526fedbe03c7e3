/*
 * Internal: pbrt-v2's DipoleSubsurfaceIntegrator (integrators/
 * dipolesubsurface.cpp, renderers/surfacepoints.cpp): irradiance points on
 * the surfaces whose material has a BSSRDF, their irradiance, the octree of
 * Jensen and Buhler's hierarchical integration, and the dipole's diffusion
 * reflectance. Built once per render (mt_scene_render) from the scene, the
 * seed and the mode; read-only while the image is rendered.
 */
#ifndef MT_TRACER_DIPOLE_H
#define MT_TRACER_DIPOLE_H

#include "materia/arena.h"
#include "materia/render.h"
#include "tracer/geometry.h"

struct mt_scene;

/* pbrt-v2 SurfacePoint plus the irradiance: an IrradiancePoint. */
typedef struct mt__ss_point {
    mt_vec3 p, n;     /* n: the geometric normal turned towards the ray that found the point */
    mt_vec3 ng;       /* the geometric normal as the shape gives it (for leaving the surface) */
    mt_vec3 p_error;  /* bound on the error of p (rays leave by it) */
    mt_real area;
    mt_real ray_epsilon; /* pbrt-v2's rayEpsilon (kept for the points file) */
    mt_rgb E;
    int next;         /* the next point of the same octree leaf, -1 at the end */
} mt__ss_point;

/* pbrt-v2 DiffusionReflectance: the dipole's Rd(d^2) for one medium. */
typedef struct mt__diffusion {
    mt_rgb zpos, zneg, sigma_tr, alphap;
    mt_real A;
} mt__diffusion;

/* Fdr(eta), the average diffuse Fresnel reflectance seen from inside:
 * pbrt-v2's polynomial fit, or (corrected, MT_FIX_FDR_RANGE) the
 * hemispherical integral of the dielectric Fresnel reflectance. */
mt_real mt__fdr(mt_real eta, mt_mode mode);
void mt__diffusion_init(mt__diffusion *rd, mt_rgb sigma_a, mt_rgb sigmap_s, mt_real fdr);
mt_rgb mt__diffusion_eval(const mt__diffusion *rd, mt_real d2);

typedef struct mt__ss_node mt__ss_node;

/* Everything the preprocess builds. */
typedef struct mt__dipole {
    mt__ss_point *pts;
    int npts;
    mt_vec3 lo, hi;      /* the octree's bounds: the points' bounding box */
    mt__ss_node *root;   /* NULL when there are no points (or no lights) */
    mt_arena *arena;     /* the octree's nodes */
    mt_real maxerror;
    mt_mode mode;
    /* what the preprocess did, for tests and the stats */
    long paths, candidates, max_repeated_fails;
    double seconds_points, seconds_irradiance;
} mt__dipole;

/* The integrator's parameters, from the scene (pbrt-v2's names and defaults:
 * maxerror 0.05, minsampledistance 0.25, pointsfile ""). */
typedef struct mt__dipole_params {
    mt_real maxerror, min_dist;
    mt__ss_point *file_pts; /* read from "pointsfile" at load time (owned by the scene) */
    int nfile_pts;
} mt__dipole_params;

/* pbrt-v2's maxFails of FindPoissonPointDistribution. */
#define MT__DIPOLE_MAX_FAILS 2000

/* The preprocess: points (from the file, else the Poisson deposition from
 * the camera position), their irradiance, the octree. Progress goes to
 * o->stage. Deterministic: the same scene, mode and seed give the same bits
 * on any number of threads. */
mt_status mt__dipole_build(const struct mt_scene *s, const mt_render_options *o, int nthreads,
                           mt__dipole *d, mt_error *err);
void mt__dipole_free(mt__dipole *d);

/* The steps of the preprocess, for tests. */
mt_status mt__dipole_deposit(const struct mt_scene *s, uint64_t seed, int nthreads, mt_real min_dist,
                             const mt_render_options *o, mt__dipole *d, mt_error *err);
void mt__dipole_fix_areas(mt__dipole *d, mt_real min_dist);
mt_status mt__dipole_irradiance(const struct mt_scene *s, uint64_t seed, int nthreads,
                                const mt_render_options *o, mt__dipole *d, mt_error *err);
mt_status mt__dipole_octree(mt__dipole *d, mt_error *err);

/* pbrt-v2 SubsurfaceOctreeNode::Mo at p: the hierarchical sum over the
 * points of Rd(|p - p_i|^2) E_i A_i, clusters taken whole when their solid
 * angle sumArea / d^2 is below maxerror and p is outside their cell. */
mt_rgb mt__dipole_mo(const mt__dipole *d, mt_vec3 p, const mt__diffusion *rd, mt_real maxerror);
/* The same sum over every point (for tests). */
mt_rgb mt__dipole_mo_brute(const mt__dipole *d, mt_vec3 p, const mt__diffusion *rd);

/* Reads pbrt-v2's points file (8 floats per point: position, normal, area,
 * ray epsilon; '#' comments), errors located in the file. */
mt_status mt__dipole_read_points(const char *path, mt__ss_point **pts, int *npts, mt_error *err);

#endif
