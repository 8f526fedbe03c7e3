/*
 * tracer/geometry.h -- the geometry of materia's tracer: rays, pbrt-v2's
 * shapes, and a BVH over them (internal to the library; the camera, lights,
 * integrators and renderer are built on it).
 *
 * Life cycle (Embree's build / commit / query model):
 *
 *   mt_geometry *g = mt_geometry_create();
 *   for each Shape statement:
 *       mt_shape *s = mt_shape_from_statement(st, o2w, reverse_orientation, &opt, err);
 *       mt_shape_set_user(s, material_or_light);       -- opaque to the geometry
 *       mt_geometry_attach(g, s, err);                  -- g owns s from now on
 *   mt_geometry_commit(g, err);                         -- builds the BVH once
 *   then, from any number of threads, with no locks and no writes to g:
 *       if (mt_geometry_intersect(g, &ray, &hit)) {
 *           mt_surface sf;
 *           mt_hit_surface(&hit, &ray, &sf);            -- pbrt-v2's DifferentialGeometry
 *           mt_surface_differentials(&sf, &raydiff);    -- ComputeDifferentials
 *           mt_surface_shading(&sf, &dg_shading);       -- GetShadingGeometry
 *           next = mt_surface_spawn(&sf, wi);           -- robust secondary ray
 *       }
 *       visible = !mt_geometry_occluded(g, &shadow_ray);
 *   mt_geometry_destroy(g);                             -- frees the shapes too
 *
 * Shapes keep pbrt-v2's parameterisations, partial derivatives and normal
 * orientation (sphere, disk, cylinder, trianglemesh and loopsubdiv, which
 * becomes a triangle mesh), pbrt-v2's geometry errata included unless the
 * shape's mode (mt_shape_options.mode) fixes them: loop-normals,
 * disk-partials, normal-derivatives, triangle-facing (hits and shading),
 * and the sampling ones below. Intersection is more careful than pbrt-v2's:
 * quadrics are solved in double precision in object space, triangles with
 * the watertight test of Woop, Benthin and Wald (JCGT 2013), and every hit
 * carries a conservative bound on the error of its point (pbrt-v3, section
 * 3.9) so that secondary rays leave the surface without pbrt-v2's
 * scene-scale epsilons. pbrt-v2's rayEpsilon is reported as well
 * (mt_surface.ray_epsilon) for a renderer that wants its exact behaviour.
 */
#ifndef MT_TRACER_GEOMETRY_H
#define MT_TRACER_GEOMETRY_H

#include <stdint.h>
#include "materia/diffgeom.h"
#include "materia/mode.h"
#include "materia/params.h"
#include "materia/parser.h"
#include "materia/transform.h"

/* ---- rays ------------------------------------------------------------------ */

/* The segment o + t d for tmin <= t <= tmax; d need not be unit length. */
typedef struct mt_ray {
    mt_vec3 o, d;
    mt_real tmin, tmax;
} mt_ray;

/* pbrt-v2's RayDifferential: the main ray and two neighbours offset by one
 * pixel in x and y (only meaningful when has_differentials). */
typedef struct mt_raydiff {
    mt_ray ray;
    int has_differentials;
    mt_vec3 rx_o, rx_d, ry_o, ry_d;
} mt_raydiff;

/* Infinity for tmax: the largest finite mt_real, so that tmax * (1 + eps)
 * and comparisons never meet an Inf. */
#define MT_RAY_TMAX MT_REAL_MAX

static inline mt_ray mt_ray_make(mt_vec3 o, mt_vec3 d, mt_real tmin, mt_real tmax)
{
    mt_ray r;
    r.o = o;
    r.d = d;
    r.tmin = tmin;
    r.tmax = tmax;
    return r;
}
static inline mt_vec3 mt_ray_at(const mt_ray *r, mt_real t)
{
    return mt_v3(r->o.x + t * r->d.x, r->o.y + t * r->d.y, r->o.z + t * r->d.z);
}
/* A ray differential without differentials. */
mt_raydiff mt_raydiff_from_ray(const mt_ray *r);
/* pbrt-v2 RayDifferential::ScaleDifferentials: the neighbours moved towards
 * (s < 1) or away from the main ray (1 / sqrt(samples per pixel) in pbrt-v2). */
void mt_raydiff_scale(mt_raydiff *r, mt_real s);

/* ---- shapes ---------------------------------------------------------------- */

typedef enum mt_shape_kind {
    MT_SHAPE_SPHERE,
    MT_SHAPE_DISK,
    MT_SHAPE_CYLINDER,
    MT_SHAPE_TRIANGLES /* "trianglemesh" and "loopsubdiv" */
} mt_shape_kind;

typedef struct mt_shape mt_shape;

/* Zero-initialize (or memset) before filling: a zero mode is pbrt-v2's. */
typedef struct mt_shape_options {
    mt_warning_fn warn; /* pbrt-v2's warnings (extra uvs, discarded uvs); may be NULL */
    void *warn_ctx;
    /* The geometry errata the shape fixes (the MT_FIX_* bits of the
     * "geometry" layer, include/materia/mode.h; others are ignored): the
     * shape keeps its mode, and every query on it answers in that mode. */
    mt_mode mode;
} mt_shape_options;

/* A shape of pbrt-v2 type `type` ("sphere", "disk", "cylinder",
 * "trianglemesh", "loopsubdiv") from its parameters, with pbrt-v2's
 * parameter names and defaults (shapes/<type>.cpp, Create*Shape), placed by
 * the object-to-world transform o2w, its normal reversed when
 * reverse_orientation (the state's ReverseOrientation). NULL with err set
 * when the type is unknown or unsupported ("cone", "paraboloid",
 * "hyperboloid", "heightfield", "nurbs", "plymesh": MT_ERR_UNSUPPORTED),
 * when a parameter is invalid (a radius <= 0, zmin = zmax, phimax <= 0, an
 * index out of range, a count that does not match P, a mesh that is not a
 * manifold for loopsubdiv: MT_ERR_INVALID) or memory runs out. Where pbrt-v2
 * warns and drops data (too few uvs, wrong N or S counts) materia refuses
 * the shape; where it only warns (more uvs than vertices) the warning goes to
 * opt->warn. The "alpha" parameter (a cut-out) is unsupported when it names a
 * texture or is the float 0 (pbrt-v2 ignores other floats). opt may be NULL. Parameters are marked used; the caller
 * reports the unused ones (mt_paramset_report_unused). */
mt_shape *mt_shape_create(const char *type, const mt_paramset *ps, const mt_transform *o2w,
                          int reverse_orientation, const mt_shape_options *opt, mt_error *err);

/* The same for a "Shape" statement: errors and warnings are located at the
 * statement's file and line when the parameter concerned has no location of
 * its own, and unused parameters are reported through opt->warn. */
mt_shape *mt_shape_from_statement(const mt_statement *st, const mt_transform *o2w,
                                  int reverse_orientation, const mt_shape_options *opt,
                                  mt_error *err);

/* A triangle mesh from arrays (indices: 3 per triangle; N, S, uv may be
 * NULL), as pbrt-v2's TriangleMesh constructor takes them: P, N, S in object
 * space. The arrays are copied. opt may be NULL (pbrt-v2 mode). */
mt_shape *mt_shape_create_mesh(const mt_transform *o2w, int reverse_orientation, int ntris,
                               const int *indices, int nverts, const mt_vec3 *P,
                               const mt_vec3 *N, const mt_vec3 *S, const mt_real *uv,
                               const mt_shape_options *opt, mt_error *err);

void mt_shape_destroy(mt_shape *s);

mt_shape_kind mt_shape_kind_of(const mt_shape *s);
/* Primitives the shape is made of: its triangles, or 1 for a quadric. */
uint32_t mt_shape_prim_count(const mt_shape *s);
/* pbrt-v2's ReverseOrientation ^ TransformSwapsHandedness (mt_diffgeom.flip). */
int mt_shape_flip(const mt_shape *s);
int mt_shape_reverse_orientation(const mt_shape *s);
/* The mode the shape was created in (mt_shape_options.mode). */
mt_mode mt_shape_mode(const mt_shape *s);
const mt_transform *mt_shape_object_to_world(const mt_shape *s);
/* World bounds of one primitive (conservative). */
void mt_shape_prim_bounds(const mt_shape *s, uint32_t prim, mt_vec3 *lo, mt_vec3 *hi);

/* The renderer's data for the shape (material, area light, ...): the
 * geometry never looks at it. */
void mt_shape_set_user(mt_shape *s, void *user);
void *mt_shape_user(const mt_shape *s);

/* Triangle meshes: counts and (world-space) vertex data, for tools and tests.
 * NULL for arrays the mesh does not have; N and S stay in object space. */
typedef struct mt_mesh_view {
    uint32_t ntris, nverts;
    const int *indices;
    const mt_vec3 *P; /* world space */
    const mt_vec3 *N, *S;
    const mt_real *uv;
} mt_mesh_view;
int mt_shape_mesh(const mt_shape *s, mt_mesh_view *out); /* 0 for quadrics */

/* ---- hits and surfaces ------------------------------------------------------ */

/* What a closest-hit query returns: cheap to record for every candidate; the
 * differential geometry is computed once, for the hit that is kept. */
typedef struct mt_hit {
    mt_real t;
    const mt_shape *shape;
    uint32_t prim;   /* triangle index within the shape; 0 for quadrics */
    uint32_t id;     /* the primitive's index in its geometry (prim for a lone shape) */
    mt_real b1, b2;  /* triangles: barycentric weights of the 2nd and 3rd vertex */
    double pobj[3];  /* quadrics: the hit point in object space */
} mt_hit;

/* One primitive of one shape against a ray (no BVH): 1 and *hit filled when
 * the ray meets it within [tmin, tmax]. */
int mt_shape_intersect(const mt_shape *s, uint32_t prim, const mt_ray *r, mt_hit *hit);
int mt_shape_occluded(const mt_shape *s, uint32_t prim, const mt_ray *r);
/* 1 when mt_shape_intersect(s, prim, r) certainly returns 0 by a test much
 * cheaper than it (a sphere whose ball the ray's line misses by far more
 * than any rounding); 0 when it may hit (or the shape has no such test). */
int mt_shape_missed(const mt_shape *s, uint32_t prim, const mt_ray *r);

/* A surface point: pbrt-v2's DifferentialGeometry (dg.n is its nn: the
 * normalized dpdu x dpdv in world space, negated when dg.flip) plus what is
 * needed to leave it. */
typedef struct mt_surface {
    mt_diffgeom dg;      /* screen-space differentials zero until mt_surface_differentials */
    mt_vec3 p_error;     /* |error| of dg.p per axis, a conservative bound (pbrt-v3) */
    mt_real ray_epsilon; /* pbrt-v2's rayEpsilon: 5e-4 t for quadrics, 1e-3 t for triangles */
    const mt_shape *shape;
    uint32_t prim;
} mt_surface;

/* The surface at a hit of ray r (the ray the hit came from). */
void mt_hit_surface(const mt_hit *hit, const mt_ray *r, mt_surface *sf);
/* The same without the texture coordinates where they cost inverse
 * trigonometric functions (a sphere's u = phi / phimax and v from theta:
 * atan2 and acos): dg.u and dg.v are left 0, everything else is
 * mt_hit_surface's, bit for bit (a sphere's partial derivatives and normal
 * come from the point alone). For callers that read the geometry only, or
 * whose material evaluates no texture there. */
void mt_hit_surface_no_uv(const mt_hit *hit, const mt_ray *r, mt_surface *sf);
/* The surface normal dg.n alone, the bits mt_hit_surface gives: for a
 * triangle without the point, its error bound and (u, v) (an area light's
 * ShapeSet asks for nothing else, twice a vertex). */
mt_vec3 mt_hit_normal(const mt_hit *hit, const mt_ray *r);

/* pbrt-v2 DifferentialGeometry::ComputeDifferentials: dpdx, dpdy and the
 * (u, v) derivatives from the neighbouring rays' intersections with the
 * tangent plane; all zero without differentials, when a neighbour is
 * parallel to the plane, or when the 2x2 system is singular (|det| < 1e-10). */
void mt_surface_differentials(mt_surface *sf, const mt_raydiff *rd);

/* pbrt-v2 Shape::GetShadingGeometry: for a triangle mesh with per-vertex N
 * or S, the interpolated shading frame (ss, ts, ns) with dndu/dndv from the
 * vertex normals; otherwise a copy of the geometric dg. The screen-space
 * differentials are copied from sf->dg. The shading normal is not turned to
 * the geometric normal's side (pbrt-v2 does not). */
void mt_surface_shading(const mt_surface *sf, mt_diffgeom *shading);
/* 0 when mt_surface_shading would copy sf->dg unchanged (every shape but a
 * triangle mesh with N or S): the caller may use sf->dg itself. */
int mt_surface_has_shading(const mt_surface *sf);

/* ---- leaving a surface -------------------------------------------------------
 * pbrt-v3's robust spawning (OffsetRayOrigin): the origin moves off the
 * surface along the geometric normal by the error bound, to w's side, and is
 * rounded away from the surface; tmin is 0. With watertight triangles and
 * conservative t tests this never re-hits the surface the ray leaves, at any
 * scene scale, where pbrt-v2's epsilon (1e-3 t) can both leak and self-hit. */
mt_vec3 mt_offset_ray_origin(mt_vec3 p, mt_vec3 p_error, mt_vec3 n, mt_vec3 w);
/* A ray from sf in direction w (tmax = MT_RAY_TMAX). */
mt_ray mt_surface_spawn(const mt_surface *sf, mt_vec3 w);
/* A shadow ray from sf to the point p: d = p - origin, tmax = 1 - 1e-4
 * (pbrt-v3's ShadowEpsilon). */
mt_ray mt_surface_spawn_to(const mt_surface *sf, mt_vec3 p);
/* A shadow ray between two surface points (both ends offset). */
mt_ray mt_surface_spawn_between(const mt_surface *from, const mt_surface *to);

/* ---- sampling, for area lights (pbrt-v2 Shape and ShapeSet) ------------------
 * In pbrt-v2 mode these are pbrt-v2's, errata included; the shape's mode
 * fixes them (include/materia/mode.h, the geometry layer: partial-sampling,
 * quadric-scale, triangle-facing, shapeset-hit). */

/* Area of one primitive (pbrt-v2 Shape::Area: object-space for quadrics,
 * world-space for triangles, in both modes). */
mt_real mt_shape_area(const mt_shape *s, uint32_t prim);
/* pbrt-v2 Shape::Sample(u1, u2, &Ns): a point on the primitive and its
 * normal *ns (for triangles, negated under ReverseOrientation only in
 * pbrt-v2 mode; as a hit's normal with triangle-facing fixed). pbrt-v2's
 * sphere and disk cover the full shape whatever their clipping; with
 * partial-sampling fixed, the clipped shape, uniformly in object area. */
mt_vec3 mt_shape_sample(const mt_shape *s, uint32_t prim, mt_real u1, mt_real u2, mt_vec3 *ns);
/* pbrt-v2 Shape::Sample(p, u1, u2, &Ns): for a sphere seen from outside, a
 * direction uniform in the cone it subtends and the point where it meets the
 * sphere; otherwise as mt_shape_sample. With partial-sampling fixed, a cone
 * direction that misses a clipped sphere gives a zero *ns (no emission; its
 * pdf is 0). With quadric-scale fixed the cone has the world radius, and a
 * sphere under a transform that is not a similarity is area-sampled and
 * moved to the first point of the ray from p through the sample, as
 * ShapeSet does (its pdf then sums every point along a direction). */
mt_vec3 mt_shape_sample_from(const mt_shape *s, uint32_t prim, mt_vec3 p, mt_real u1, mt_real u2,
                             mt_vec3 *ns);
/* pbrt-v2 Shape::Pdf(p, wi) (solid angle, wi unit): the cone pdf for a
 * sphere seen from outside; otherwise distance^2 / (|cos| area) at the
 * primitive's hit by the ray (p, wi, tmin 1e-3), 0 when it misses or the
 * value is not finite. Fixed: the cone only for directions that meet a
 * clipped sphere (partial-sampling); the world density of a quadric
 * (quadric-scale); every point of a quadric along the ray, summed
 * (shapeset-hit, and any area-sampled ellipsoid). */
mt_real mt_shape_pdf_from(const mt_shape *s, uint32_t prim, mt_vec3 p, mt_vec3 wi);

/* pbrt-v2 ShapeSet: every primitive of the shape, one chosen with
 * probability proportional to its area (ucomp) and sampled with (u1, u2).
 * _from samples as seen from p and, as pbrt-v2 as released does, returns
 * the primitive's sample and normal; with shapeset-hit fixed, the point
 * where the ray from p towards the sample first meets the set (tmin 1e-3),
 * with that primitive's normal. */
mt_real mt_shape_total_area(const mt_shape *s);
mt_vec3 mt_shape_set_sample(const mt_shape *s, mt_real ucomp, mt_real u1, mt_real u2,
                            mt_vec3 *ns);
mt_vec3 mt_shape_set_sample_from(const mt_shape *s, mt_vec3 p, mt_real ucomp, mt_real u1,
                                 mt_real u2, mt_vec3 *ns);
/* sum over primitives of area_i Pdf_i(p, wi) / total area. */
mt_real mt_shape_set_pdf_from(const mt_shape *s, mt_vec3 p, mt_vec3 wi);
/* mt_shape_sample_from of primitive 0 into *pt and, when the shape's
 * mt_shape_set_pdf_from(s, p, wi) has the same value for every direction wi
 * (a lone sphere seen from outside: pbrt-v2's cone pdf, measured by the
 * sample itself), that value in *pdf and 1 returned; 0 otherwise. */
int mt_shape_sample_from_pdf(const mt_shape *s, mt_vec3 p, mt_real u1, mt_real u2, mt_vec3 *ns,
                             mt_vec3 *pt, mt_real *pdf);

/* ---- the scene's geometry and its BVH ------------------------------------------ */

typedef struct mt_geometry mt_geometry;

mt_geometry *mt_geometry_create(void);
/* Frees the BVH and every attached shape. */
void mt_geometry_destroy(mt_geometry *g);
/* Adds s (which g owns from now on; on failure s is destroyed). Only before
 * mt_geometry_commit. */
mt_status mt_geometry_attach(mt_geometry *g, mt_shape *s, mt_error *err);
/* Builds the BVH over every primitive (binned SAH); after it g is read-only
 * and every query below is thread-safe. */
mt_status mt_geometry_commit(mt_geometry *g, mt_error *err);

/* The closest hit in [tmin, tmax]: 1 and *hit, or 0. Equal distances are
 * resolved towards the smaller hit->id, so that the answer does not depend on
 * the traversal order. */
int mt_geometry_intersect(const mt_geometry *g, const mt_ray *r, mt_hit *hit);
/* Any hit in [tmin, tmax]. */
int mt_geometry_occluded(const mt_geometry *g, const mt_ray *r);

uint32_t mt_geometry_shape_count(const mt_geometry *g);
const mt_shape *mt_geometry_shape(const mt_geometry *g, uint32_t i);
/* Total primitives; the shape and local index of global primitive id. */
uint32_t mt_geometry_prim_count(const mt_geometry *g);
const mt_shape *mt_geometry_prim(const mt_geometry *g, uint32_t id, uint32_t *prim);
/* World bounds of everything (empty geometry: lo > hi). */
void mt_geometry_bounds(const mt_geometry *g, mt_vec3 *lo, mt_vec3 *hi);

typedef struct mt_bvh_stats {
    uint32_t inner_nodes, leaves, prims, max_depth, max_leaf_prims;
    double sah_cost; /* expected cost in node visits + primitive tests */
    size_t bytes;    /* nodes and primitive data */
} mt_bvh_stats;
void mt_geometry_stats(const mt_geometry *g, mt_bvh_stats *st);

#endif
