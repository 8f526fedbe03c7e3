/*
 * Area, sampling and pdf of shapes for area lights: pbrt-v2's Shape::Area,
 * Sample, Pdf per primitive (core/shape.cpp and the shapes), and its
 * ShapeSet (core/light.cpp), which samples a primitive by area through a
 * Distribution1D (core/montecarlo.h).
 *
 * Two errata live here (corrected mode; pbrt-v3 has no ShapeSet):
 * - quadric-scale (MT_FIX_QUADRIC_SCALE): Shape::Pdf divides by Area(),
 *   which quadrics measure in object space, so a scaled sphere, disk or
 *   cylinder light has the wrong density (under Scale 2 four times too
 *   high: the light comes out four times too dark); corrected: the world
 *   density 1 / (Area() dA_world/dA_object) at the point.
 * - shapeset-hit (MT_FIX_SHAPESET_HIT): pbrt-v2 as released (df276f5)
 *   leaves ShapeSet::Sample's point where the primitive's Sample put it,
 *   with that primitive's normal, while ShapeSet::Pdf(p, wi) adds up the
 *   density of every primitive the direction meets: a sample on a primitive
 *   hidden behind another of the set is blocked by it, so a closed mesh
 *   light seen from outside gives only p_front / (p_front + p_back) of its
 *   light. (The 2012 snapshot moved the sample to the last primitive the
 *   ray met in index order.) Corrected: the sample moves to the closest
 *   point of the set on the ray from p through it, and the pdf of a
 *   direction sums over every point of the set along it (the density of
 *   the directions that sampling produces).
 */
#include "core/alloc.h"
#include "tracer/shape_impl.h"

mt_real mt_shape_area(const mt_shape *s, uint32_t prim)
{
    switch (s->kind) {
    case MT_SHAPE_SPHERE: return mt__sphere_area(s);
    case MT_SHAPE_DISK: return mt__disk_area(s);
    case MT_SHAPE_CYLINDER: return mt__cylinder_area(s);
    case MT_SHAPE_TRIANGLES: break;
    }
    return mt__triangle_area(s, prim);
}

mt_vec3 mt_shape_sample(const mt_shape *s, uint32_t prim, mt_real u1, mt_real u2, mt_vec3 *ns)
{
    switch (s->kind) {
    case MT_SHAPE_SPHERE: return mt__sphere_sample(s, u1, u2, ns);
    case MT_SHAPE_DISK: return mt__disk_sample(s, u1, u2, ns);
    case MT_SHAPE_CYLINDER: return mt__cylinder_sample(s, u1, u2, ns);
    case MT_SHAPE_TRIANGLES: break;
    }
    return mt__triangle_sample(s, prim, u1, u2, ns);
}

mt_vec3 mt_shape_sample_from(const mt_shape *s, uint32_t prim, mt_vec3 p, mt_real u1, mt_real u2,
                             mt_vec3 *ns)
{
    if (s->kind == MT_SHAPE_SPHERE) return mt__sphere_sample_from(s, p, u1, u2, ns);
    return mt_shape_sample(s, prim, u1, u2, ns);
}

/* The area of the primitive as the density at a hit sees it: pbrt-v2's
 * Area(); with quadric-scale fixed, a quadric's object area times the
 * world-to-object area ratio at the hit's object-space normal. */
static mt_real density_area(const mt_shape *s, uint32_t prim, const mt_hit *hit)
{
    double n[3], len;
    const double *p = hit->pobj;
    if (s->kind == MT_SHAPE_TRIANGLES || !(s->mode & MT_FIX_QUADRIC_SCALE))
        return mt_shape_area(s, prim);
    n[0] = s->kind == MT_SHAPE_DISK ? 0 : p[0];
    n[1] = s->kind == MT_SHAPE_DISK ? 0 : p[1];
    n[2] = s->kind == MT_SHAPE_CYLINDER ? 0 : (s->kind == MT_SHAPE_DISK ? 1 : p[2]);
    len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(len > 0)) return mt_shape_area(s, prim);
    n[0] /= len;
    n[1] /= len;
    n[2] /= len;
    return (mt_real)(mt_shape_area(s, prim) * mt__area_scale(s, n));
}

mt_real mt_shape_pdf_from(const mt_shape *s, uint32_t prim, mt_vec3 p, mt_vec3 wi)
{
    mt_real pdf = 0;
    mt_ray r;
    mt_hit hit;
    int more = s->kind != MT_SHAPE_TRIANGLES && s->kind != MT_SHAPE_DISK &&
               ((s->mode & MT_FIX_SHAPESET_HIT) || mt__sphere_area_sampled(s));
    if (s->kind == MT_SHAPE_SPHERE && mt__sphere_pdf_from(s, p, wi, &pdf)) return pdf;
    /* pbrt-v2 Shape::Pdf: intersect the ray (p, wi, mint 1e-3) and convert
     * the area density 1 / Area to solid angle; with shapeset-hit fixed (or
     * for an area-sampled ellipsoid, whose samples are moved to the first
     * point), a quadric's second point along the ray adds its own */
    r = mt_ray_make(p, wi, (mt_real)1e-3, MT_RAY_TMAX);
    while (mt_shape_intersect(s, prim, &r, &hit)) {
        pdf += mt_v3_len2(mt_v3_sub(p, mt_ray_at(&r, hit.t))) /
               (mt_v3_absdot(mt_hit_normal(&hit, &r), mt_v3_neg(wi)) * density_area(s, prim, &hit));
        if (!more) break;
        more = 0;
        r.tmin = mt__next_toward(hit.t, MT_REAL_MAX);
    }
    return mt_is_finite(pdf) ? pdf : 0;
}

/* ---- the set of a shape's primitives ----------------------------------------------- */

mt_status mt__shape_areas_init(mt_shape *s, mt_error *err)
{
    uint32_t n = mt__shape_nprims(s), i;
    mt_real sum = 0;
    s->areas = mt__malloc((size_t)n * sizeof *s->areas);
    s->cdf = mt__malloc(((size_t)n + 1) * sizeof *s->cdf);
    if (!s->areas || !s->cdf)
        return mt_error_set(err, MT_ERR_NOMEM, "out of memory for the areas of %u primitives",
                            (unsigned)n);
    for (i = 0; i < n; ++i) {
        s->areas[i] = mt_shape_area(s, i);
        sum += s->areas[i];
    }
    s->area_sum = sum;
    /* pbrt-v2 Distribution1D: cdf[i] = cdf[i-1] + func[i-1] / n, then
     * divided by funcInt = cdf[n] (uniform steps when that is 0) */
    s->cdf[0] = 0;
    for (i = 1; i <= n; ++i) s->cdf[i] = s->cdf[i - 1] + s->areas[i - 1] / (mt_real)n;
    s->area_int = s->cdf[n];
    for (i = 1; i <= n; ++i)
        s->cdf[i] = s->area_int == 0 ? (mt_real)i / (mt_real)n : s->cdf[i] / s->area_int;
    return MT_OK;
}

mt_real mt_shape_total_area(const mt_shape *s) { return s->area_sum; }

/* Distribution1D::SampleDiscrete: the last i with cdf[i] <= u
 * (std::upper_bound, then one back). */
static uint32_t pick_prim(const mt_shape *s, mt_real u)
{
    uint32_t lo = 0, hi = mt__shape_nprims(s) + 1; /* first cdf > u lies in [lo, hi] */
    while (lo < hi) {
        uint32_t mid = lo + (hi - lo) / 2;
        if (s->cdf[mid] > u) hi = mid;
        else lo = mid + 1;
    }
    return lo == 0 ? 0 : (lo - 1 < mt__shape_nprims(s) ? lo - 1 : mt__shape_nprims(s) - 1);
}

mt_vec3 mt_shape_set_sample(const mt_shape *s, mt_real ucomp, mt_real u1, mt_real u2,
                            mt_vec3 *ns)
{
    return mt_shape_sample(s, pick_prim(s, ucomp), u1, u2, ns);
}

mt_vec3 mt_shape_set_sample_from(const mt_shape *s, mt_vec3 p, mt_real ucomp, mt_real u1,
                                 mt_real u2, mt_vec3 *ns)
{
    uint32_t n = mt__shape_nprims(s), i;
    mt_vec3 pt = mt_shape_sample_from(s, pick_prim(s, ucomp), p, u1, u2, ns);
    mt_ray r;
    mt_hit hit, last;
    int any = 0;
    /* pbrt-v2 ShapeSet::Sample as released (df276f5): the primitive's own
     * sample, no re-intersection */
    if (!(s->mode & MT_FIX_SHAPESET_HIT)) return pt;
    /* corrected (shapeset-hit): the closest point of the set on the ray
     * from p through the sample, with its normal */
    r = mt_ray_make(p, mt_v3_sub(pt, p), (mt_real)1e-3, MT_RAY_TMAX);
    for (i = 0; i < n; ++i)
        if (mt_shape_intersect(s, i, &r, &hit)) {
            last = hit;
            any = 1;
            r.tmax = hit.t;
        }
    if (!any) return pt;
    *ns = mt_hit_normal(&last, &r);
    return mt_ray_at(&r, last.t);
}

int mt_shape_sample_from_pdf(const mt_shape *s, mt_vec3 p, mt_real u1, mt_real u2, mt_vec3 *ns,
                             mt_vec3 *pt, mt_real *pdf)
{
    mt_real prim_pdf, sum = 0;
    int uniform = 0;
    if (s->kind != MT_SHAPE_SPHERE) {
        *pt = mt_shape_sample_from(s, 0, p, u1, u2, ns);
        return 0;
    }
    *pt = mt__sphere_sample_from_pdf(s, p, u1, u2, ns, &uniform, &prim_pdf);
    if (!uniform || !(s->area_sum > 0)) return 0;
    /* mt_shape_set_pdf_from's sum over the one primitive, as it computes it */
    sum += s->areas[0] * prim_pdf;
    *pdf = sum / s->area_sum;
    return 1;
}

mt_real mt_shape_set_pdf_from(const mt_shape *s, mt_vec3 p, mt_vec3 wi)
{
    uint32_t n = mt__shape_nprims(s), i;
    mt_real pdf = 0;
    if (!(s->area_sum > 0)) return 0;
    for (i = 0; i < n; ++i) pdf += s->areas[i] * mt_shape_pdf_from(s, i, p, wi);
    return pdf / s->area_sum;
}
