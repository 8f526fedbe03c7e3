/*
 * Internal: the shape record and what the shape files share -- the
 * per-kind operations, object-space ray transforms in double precision, the
 * finishing of a DifferentialGeometry, error bounds, and pbrt-v2's
 * Distribution1D for choosing a primitive by area.
 */
#ifndef MT_TRACER_SHAPE_IMPL_H
#define MT_TRACER_SHAPE_IMPL_H

#include "tracer/geometry.h"

struct mt_shape {
    mt_shape_kind kind;
    mt_transform o2w, w2o;
    int reverse_orientation, swaps_handedness, flip;
    mt_mode mode; /* the geometry errata fixed (mt_shape_options.mode) */
    /* o2w's linear part is sim_scale times an orthogonal matrix (a
     * similarity: spheres stay spheres); 0 when it is not */
    double sim_scale;
    /* w2o is a translation (identity linear part, last row 0 0 0 1) */
    int w2o_translation;
    void *user;

    /* quadrics, as pbrt-v2 stores them (its float arithmetic in mt_real) */
    mt_real radius, zmin, zmax, phi_max; /* sphere, cylinder; disk: radius, phi_max */
    mt_real theta_min, theta_max;        /* sphere */
    mt_vec3 center;                      /* sphere: o2w of the origin */
    /* sphere under an affine similarity (else ball_ok = 0): its world
     * centre rounded to mt_real, |ball_c|_1, and an upper bound of the
     * squared world radius and of the radius (mt__sphere_missed) */
    int ball_ok;
    mt_vec3 ball_c;
    mt_real ball_c1, ball_r2, ball_r;
    mt_real height, inner_radius;        /* disk */

    /* triangle meshes (pbrt-v2 TriangleMesh: P in world space, N and S in
     * object space, uv optional) */
    uint32_t ntris, nverts;
    int *indices;
    mt_vec3 *P, *N, *S;
    mt_real *uv;
    /* per triangle: dpdu, dpdv and the hit normal, computed once when the
     * mesh has at most MT__TRI_FRAMES_MAX triangles (NULL otherwise) */
    mt_vec3 *tri_frames;

    /* pbrt-v2 ShapeSet's Distribution1D over the primitives' areas */
    mt_real *areas; /* nprims */
    mt_real *cdf;   /* nprims + 1 */
    mt_real area_sum, area_int;
};

uint32_t mt__shape_nprims(const mt_shape *s);

/* ---- per-kind operations (sphere.c, disk.c, cylinder.c, trianglemesh.c) ---- */

/* Quadrics: ray (already in object space, in double) against the shape;
 * returns 1 with *t and the object-space point p when it hits in [tmin, tmax]. */
typedef struct mt__oray {
    double o[3], d[3];
    double tmin, tmax;
} mt__oray;

int mt__sphere_hit(const mt_shape *s, const mt__oray *r, double *t, double p[3]);
int mt__disk_hit(const mt_shape *s, const mt__oray *r, double *t, double p[3]);
int mt__cylinder_hit(const mt_shape *s, const mt__oray *r, double *t, double p[3]);
/* want_uv = 0: (u, v) left 0 (mt_hit_surface_no_uv) */
void mt__sphere_surface(const mt_shape *s, const double p[3], int want_uv, mt_surface *sf);
void mt__disk_surface(const mt_shape *s, const double p[3], mt_surface *sf);
void mt__cylinder_surface(const mt_shape *s, const double p[3], mt_surface *sf);
mt_real mt__sphere_area(const mt_shape *s);
mt_real mt__disk_area(const mt_shape *s);
mt_real mt__cylinder_area(const mt_shape *s);
mt_vec3 mt__sphere_sample(const mt_shape *s, mt_real u1, mt_real u2, mt_vec3 *ns);
mt_vec3 mt__disk_sample(const mt_shape *s, mt_real u1, mt_real u2, mt_vec3 *ns);
mt_vec3 mt__cylinder_sample(const mt_shape *s, mt_real u1, mt_real u2, mt_vec3 *ns);
mt_vec3 mt__sphere_sample_from(const mt_shape *s, mt_vec3 p, mt_real u1, mt_real u2,
                               mt_vec3 *ns);
/* The same, and *uniform = 1 with *pdf = mt__sphere_pdf_from's value when
 * that is the same for every direction (the cone seen from p, which the
 * sample has just measured). */
mt_vec3 mt__sphere_sample_from_pdf(const mt_shape *s, mt_vec3 p, mt_real u1, mt_real u2, mt_vec3 *ns,
                                   int *uniform, mt_real *pdf);
/* 1 with *pdf when the sphere handles Pdf(p, wi) itself (the cone seen
 * from outside). */
int mt__sphere_pdf_from(const mt_shape *s, mt_vec3 p, mt_vec3 wi, mt_real *pdf);
/* Whether the sphere is sampled by area as seen from any point (an ellipsoid
 * with quadric-scale fixed): its samples are then the first point along
 * their ray and its pdf sums every point along a direction. */
int mt__sphere_area_sampled(const mt_shape *s);
/* 1 when the line of r certainly misses the sphere by more than any
 * rounding of this test and of the double-precision one (mt_shape_intersect
 * would return 0); 0 when it may not. */
int mt__sphere_missed(const mt_shape *s, const mt_ray *r);

/* Object-space bounds of a quadric (pbrt-v2 ObjectBound). */
void mt__quadric_object_bounds(const mt_shape *s, double lo[3], double hi[3]);

/* Creation from parameters; each fills the kind-specific fields of s. */
mt_status mt__sphere_init(mt_shape *s, const mt_paramset *ps, mt_error *err);
mt_status mt__disk_init(mt_shape *s, const mt_paramset *ps, mt_error *err);
mt_status mt__cylinder_init(mt_shape *s, const mt_paramset *ps, mt_error *err);

/* Meshes (trianglemesh.c). */
mt_status mt__trianglemesh_init(mt_shape *s, const mt_paramset *ps, const mt_shape_options *opt,
                                mt_error *err);
mt_status mt__mesh_init(mt_shape *s, int ntris, const int *indices, int nverts, const mt_vec3 *P,
                        const mt_vec3 *N, const mt_vec3 *S, const mt_real *uv, mt_error *err);
/* The normal mt__triangle_surface gives the triangle's hits (its frame's
 * third vector), without the rest of the surface. */
mt_vec3 mt__triangle_normal(const mt_shape *s, uint32_t prim);
void mt__triangle_surface(const mt_shape *s, uint32_t prim, mt_real b1, mt_real b2, mt_real t,
                          const mt_ray *r, mt_surface *sf);
void mt__triangle_shading(const mt_surface *sf, mt_diffgeom *shading);
mt_real mt__triangle_area(const mt_shape *s, uint32_t prim);
mt_vec3 mt__triangle_sample(const mt_shape *s, uint32_t prim, mt_real u1, mt_real u2,
                            mt_vec3 *ns);
/* pbrt-v2 Triangle::GetUVs: the vertices' uvs, or (0,0), (1,0), (1,1). */
void mt__triangle_uvs(const mt_shape *s, uint32_t prim, mt_real uv[3][2]);
/* A hit's dpdu, dpdv and normal depend on its triangle alone: for small
 * meshes, whose 36 bytes a triangle then stay in the caches, they are
 * computed once (s->tri_frames); a large mesh's are computed at each hit
 * rather than fetched from one more array. */
#define MT__TRI_FRAMES_MAX 4096u
mt_status mt__triangle_frames_init(mt_shape *s, mt_error *err);

/* Loop subdivision (loopsubdiv.c): refines the control mesh and creates the
 * limit mesh in s as pbrt-v2's LoopSubdiv::Refine does. */
mt_status mt__loopsubdiv_init(mt_shape *s, const mt_paramset *ps, mt_error *err);

/* Sampling tables (shapeset.c): pbrt-v2's Distribution1D over the areas. */
mt_status mt__shape_areas_init(mt_shape *s, mt_error *err);

/* ---- shared helpers (shape.c) ------------------------------------------------ */

/* World ray to object space, in double. */
void mt__ray_to_object(const mt_shape *s, const mt_ray *r, mt__oray *out);
/* Fills sf from object-space p, dpdu, dpdv, dndu, dndv (double): transforms
 * them to world space as pbrt-v2 does (dndu, dndv as normals), n = the
 * normalized world dpdu x dpdv negated when s->flip (when that cross product
 * vanishes, the object-space normal nfallback transformed as a normal), and
 * p_error from the object-space bound perr through the transform. */
void mt__surface_from_object(const mt_shape *s, const double p[3], const double perr[3],
                             const double dpdu[3], const double dpdv[3], const double dndu[3],
                             const double dndv[3], const double nfallback[3], mt_real u,
                             mt_real v, mt_surface *sf);
/* dA_world / dA_object at a point of a quadric with unit object-space
 * normal n: |det L| |L^-T n| for the linear part L of o2w (erratum
 * quadric-scale: pbrt-v2 measures areas in object space). */
double mt__area_scale(const mt_shape *s, const double n[3]);
/* pbrt-v2's Weingarten equations: dndu, dndv from the first and second
 * fundamental forms (zero where E G - F^2 vanishes). */
void mt__weingarten(const double dpdu[3], const double dpdv[3], const double d2pduu[3],
                    const double d2pduv[3], const double d2pdvv[3], double dndu[3],
                    double dndv[3]);
/* phi = atan2(y, x) in [0, 2 pi) (pbrt-v2's quadrics). */
double mt__phi(double x, double y);
/* Whether phimax cuts anything away: with phimax = 360 degrees (2 pi
 * rounded up to mt_real) no phi in [0, 2 pi) exceeds it, and the hit tests
 * skip the atan2. */
static inline int mt__phi_cut(const mt_shape *s) { return (double)s->phi_max < 6.283185307179586; }
/* The roots t0 <= t1 of a t^2 + 2 b t + c = 0 given disc4 = b^2 - a c
 * computed by the caller (in a cancellation-free form); 0 when none. */
int mt__quadratic(double a, double b, double c, double disc4, double *t0, double *t1);

/* pbrt-v3's gamma(n) = n eps / (1 - n eps), eps = half the machine epsilon,
 * for mt_real and for double. */
static inline mt_real mt__gamma(int n)
{
    mt_real e = MT_REAL_EPSILON * (mt_real)0.5;
    return (n * e) / (1 - n * e);
}
static inline double mt__gamma_d(int n)
{
    double e = 1.1102230246251565e-16;
    return (n * e) / (1 - n * e);
}

/* The neighbouring mt_real towards dir. */
static inline mt_real mt__next_toward(mt_real x, mt_real dir)
{
#if MT_USE_DOUBLE
    return nextafter(x, dir);
#else
    return nextafterf(x, dir);
#endif
}

/* Quadric hits for the BVH and mt_shape_intersect (shape.c): r in
 * [r->tmin, tmax] (the BVH's current closest hit, without a copy of the
 * ray); hit may be NULL when only whether is asked (an any-hit query). */
int mt__quadric_intersect_to(const mt_shape *s, const mt_ray *r, mt_real tmax, mt_hit *hit);

/* pbrt-v2's choice between the two roots of a quadric: the nearer root in
 * [tmin, tmax] whose point passes the shape's clipping (z range, phimax),
 * else the farther. point_ok computes the (reprojected) object-space point
 * at t into p and says whether it lies on the clipped shape. */
typedef int (*mt__point_ok_fn)(const mt_shape *s, const mt__oray *r, double t, double p[3]);
int mt__pick_root(const mt_shape *s, const mt__oray *r, double t0, double t1,
                  mt__point_ok_fn point_ok, double *t, double p[3]);

/* pbrt-v2 SolveLinearSystem2x2 (transform.cpp): (a00 a01; a10 a11) x = b;
 * 0 when |det| < 1e-10 or the solution is not finite (ray.c). */
int mt__solve2x2(mt_real a00, mt_real a01, mt_real a10, mt_real a11, mt_real b0, mt_real b1,
                 mt_real *x0, mt_real *x1);

/* A location for messages about parameter name: its own, else the fallback. */
void mt__locate_param(mt_error *err, const mt_paramset *ps, const char *name);

#endif
