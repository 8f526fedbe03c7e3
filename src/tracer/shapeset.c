/*
 * Area, sampling and pdf of shapes for area lights: pbrt-v2's Shape::Area,
 * Sample, Pdf per primitive (core/shape.cpp and the shapes), and its
 * ShapeSet (core/light.cpp), which samples a primitive by area through a
 * Distribution1D (core/montecarlo.h).
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

mt_real mt_shape_pdf_from(const mt_shape *s, uint32_t prim, mt_vec3 p, mt_vec3 wi)
{
    mt_real pdf;
    mt_ray r;
    mt_hit hit;
    mt_surface sf;
    if (s->kind == MT_SHAPE_SPHERE && mt__sphere_pdf_from(s, p, &pdf)) return pdf;
    /* pbrt-v2 Shape::Pdf: intersect the ray (p, wi, mint 1e-3) and convert
     * the area density 1 / Area to solid angle */
    r = mt_ray_make(p, wi, (mt_real)1e-3, MT_RAY_TMAX);
    if (!mt_shape_intersect(s, prim, &r, &hit)) return 0;
    mt_hit_surface(&hit, &r, &sf);
    pdf = mt_v3_len2(mt_v3_sub(p, mt_ray_at(&r, hit.t))) /
          (mt_v3_absdot(sf.dg.n, mt_v3_neg(wi)) * mt_shape_area(s, prim));
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
    mt_ray r = mt_ray_make(p, mt_v3_sub(pt, p), (mt_real)1e-3, MT_RAY_TMAX);
    mt_real thit = 1;
    mt_hit hit, last;
    int any = 0;
    /* pbrt-v2 ShapeSet::Sample: each primitive is intersected with the same
     * unbounded ray, and the last one hit (not the closest) gives the point
     * and the normal. A single convex shape has only one candidate. */
    for (i = 0; i < n; ++i)
        if (mt_shape_intersect(s, i, &r, &hit)) {
            last = hit;
            thit = hit.t;
            any = 1;
        }
    if (any) {
        mt_surface sf;
        mt_hit_surface(&last, &r, &sf);
        *ns = sf.dg.n;
    }
    return mt_ray_at(&r, thit);
}

mt_real mt_shape_set_pdf_from(const mt_shape *s, mt_vec3 p, mt_vec3 wi)
{
    uint32_t n = mt__shape_nprims(s), i;
    mt_real pdf = 0;
    if (!(s->area_sum > 0)) return 0;
    for (i = 0; i < n; ++i) pdf += s->areas[i] * mt_shape_pdf_from(s, i, p, wi);
    return pdf / s->area_sum;
}
