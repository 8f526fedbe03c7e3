/*
 * Ray differentials (pbrt-v2 geometry.h RayDifferential and diffgeom.cpp
 * ComputeDifferentials) and robust spawning of rays from surfaces (pbrt-v3
 * section 3.9.5, OffsetRayOrigin; ShadowEpsilon = 1e-4).
 */
#include <string.h>
#include "tracer/shape_impl.h"

mt_raydiff mt_raydiff_from_ray(const mt_ray *r)
{
    mt_raydiff rd;
    rd.ray = *r;
    rd.has_differentials = 0;
    rd.rx_o = rd.ry_o = r->o;
    rd.rx_d = rd.ry_d = r->d;
    return rd;
}

static mt_vec3 lerp_from(mt_vec3 base, mt_vec3 v, mt_real s)
{
    return mt_v3_add(base, mt_v3_scale(mt_v3_sub(v, base), s));
}

void mt_raydiff_scale(mt_raydiff *r, mt_real s)
{
    r->rx_o = lerp_from(r->ray.o, r->rx_o, s);
    r->ry_o = lerp_from(r->ray.o, r->ry_o, s);
    r->rx_d = lerp_from(r->ray.d, r->rx_d, s);
    r->ry_d = lerp_from(r->ray.d, r->ry_d, s);
}

static mt_real axis(mt_vec3 v, int i) { return i == 0 ? v.x : (i == 1 ? v.y : v.z); }

int mt__solve2x2(mt_real a00, mt_real a01, mt_real a10, mt_real a11, mt_real b0, mt_real b1,
                  mt_real *x0, mt_real *x1)
{
    mt_real det = a00 * a11 - a01 * a10;
    if (mt_fabs(det) < (mt_real)1e-10) return 0;
    *x0 = (a11 * b0 - a01 * b1) / det;
    *x1 = (a00 * b1 - a10 * b0) / det;
    return mt_is_finite(*x0) && mt_is_finite(*x1);
}

/* Where the ray (o, d) meets the plane n . x + dist = 0; 0 when it does not
 * (pbrt-v2 only rejects a NaN t; an infinite one would give Inf
 * differentials, so it is rejected too). */
static int plane_point(mt_vec3 n, mt_real dist, mt_vec3 o, mt_vec3 d, mt_vec3 *p)
{
    mt_real t = -(mt_v3_dot(n, o) + dist) / mt_v3_dot(n, d);
    if (!mt_is_finite(t)) return 0;
    *p = mt_v3_add(o, mt_v3_scale(d, t));
    return mt_v3_is_finite(*p);
}

void mt_surface_differentials(mt_surface *sf, const mt_raydiff *rd)
{
    mt_diffgeom *dg = &sf->dg;
    mt_vec3 n = dg->n, px, py;
    mt_real dist = -mt_v3_dot(n, dg->p), ax = mt_fabs(n.x), ay = mt_fabs(n.y), az = mt_fabs(n.z);
    int a0, a1;
    dg->dpdx = dg->dpdy = mt_v3(0, 0, 0);
    dg->dudx = dg->dvdx = dg->dudy = dg->dvdy = 0;
    if (!rd->has_differentials || !plane_point(n, dist, rd->rx_o, rd->rx_d, &px) ||
        !plane_point(n, dist, rd->ry_o, rd->ry_d, &py))
        return;
    dg->dpdx = mt_v3_sub(px, dg->p);
    dg->dpdy = mt_v3_sub(py, dg->p);
    /* solve in the coordinate plane the normal is most nearly perpendicular to */
    if (ax > ay && ax > az) a0 = 1, a1 = 2;
    else if (ay > az) a0 = 0, a1 = 2;
    else a0 = 0, a1 = 1;
    if (!mt__solve2x2(axis(dg->dpdu, a0), axis(dg->dpdv, a0), axis(dg->dpdu, a1), axis(dg->dpdv, a1),
                axis(dg->dpdx, a0), axis(dg->dpdx, a1), &dg->dudx, &dg->dvdx))
        dg->dudx = dg->dvdx = 0;
    if (!mt__solve2x2(axis(dg->dpdu, a0), axis(dg->dpdv, a0), axis(dg->dpdu, a1), axis(dg->dpdv, a1),
                axis(dg->dpdy, a0), axis(dg->dpdy, a1), &dg->dudy, &dg->dvdy))
        dg->dudy = dg->dvdy = 0;
}

/* ---- spawning ----------------------------------------------------------------- */

/* The neighbouring mt_real above (up) or below v, by its bits (pbrt-v3's
 * NextFloatUp/Down, cheaper than nextafter); infinities and NaN stay. */
#if MT_USE_DOUBLE
typedef uint64_t real_bits;
#define TRUE_MIN 0x1p-1074
#else
typedef uint32_t real_bits;
#define TRUE_MIN 0x1p-149f
#endif
static mt_real next_real(mt_real v, int up)
{
    real_bits b;
    if (!mt_is_finite(v)) return v;
    if (v == 0) return up ? TRUE_MIN : -TRUE_MIN;
    memcpy(&b, &v, sizeof b);
    /* the bits of a positive value grow with it, a negative one's with -v */
    if ((v > 0) == (up != 0)) ++b;
    else --b;
    memcpy(&v, &b, sizeof b);
    return v;
}

mt_vec3 mt_offset_ray_origin(mt_vec3 p, mt_vec3 err, mt_vec3 n, mt_vec3 w)
{
    mt_real d = mt_fabs(n.x) * err.x + mt_fabs(n.y) * err.y + mt_fabs(n.z) * err.z;
    mt_vec3 off = mt_v3_scale(n, d), po;
    if (mt_v3_dot(w, n) < 0) off = mt_v3_neg(off);
    po = mt_v3_add(p, off);
    /* round away from p, so that the rounding of the sum cannot undo the offset */
    if (off.x != 0) po.x = next_real(po.x, off.x > 0);
    if (off.y != 0) po.y = next_real(po.y, off.y > 0);
    if (off.z != 0) po.z = next_real(po.z, off.z > 0);
    return po;
}

mt_ray mt_surface_spawn(const mt_surface *sf, mt_vec3 w)
{
    return mt_ray_make(mt_offset_ray_origin(sf->dg.p, sf->p_error, sf->dg.n, w), w, 0,
                       MT_RAY_TMAX);
}

#define SHADOW_EPSILON ((mt_real)1e-4)

mt_ray mt_surface_spawn_to(const mt_surface *sf, mt_vec3 p)
{
    mt_vec3 o = mt_offset_ray_origin(sf->dg.p, sf->p_error, sf->dg.n, mt_v3_sub(p, sf->dg.p));
    return mt_ray_make(o, mt_v3_sub(p, o), 0, 1 - SHADOW_EPSILON);
}

mt_ray mt_surface_spawn_between(const mt_surface *from, const mt_surface *to)
{
    mt_vec3 o = mt_offset_ray_origin(from->dg.p, from->p_error, from->dg.n,
                                     mt_v3_sub(to->dg.p, from->dg.p));
    mt_vec3 t = mt_offset_ray_origin(to->dg.p, to->p_error, to->dg.n, mt_v3_sub(o, to->dg.p));
    return mt_ray_make(o, mt_v3_sub(t, o), 0, 1 - SHADOW_EPSILON);
}
