/*
 * Internal: the watertight ray-triangle test of Woop, Benthin and Wald,
 * "Watertight Ray/Triangle Intersection", JCGT 2(1), 2013, with pbrt-v3's
 * conservative rejection of hits too close to the origin (section 3.9.6).
 *
 * The ray is fixed once (mt__tri_ray_init): kz is the axis of its largest
 * direction component, (kx, ky) the other two in cyclic order, and the shear
 * (sx, sy, sz) maps the direction to +z. Each triangle is then translated
 * to the origin, sheared, and tested with three 2D edge functions. An edge
 * shared by two triangles gives exactly negated edge functions in both (the
 * same products, subtracted in the opposite order), so a ray through the
 * edge hits at least one of them: no ray slips between triangles of a
 * closed mesh. Exact zeros are recomputed in double in the float build (the
 * paper's fallback). This needs a*b - c*d evaluated without fused
 * multiply-adds, as C99 compilers do by default (gcc -std=c99 implies
 * -ffp-contract=off; clang contracts only for FMA targets).
 */
#ifndef MT_TRACER_TRIANGLE_H
#define MT_TRACER_TRIANGLE_H

#include "tracer/shape_impl.h"

typedef struct mt__tri_ray {
    mt_real o[3];
    int kx, ky, kz;
    mt_real sx, sy, sz;
} mt__tri_ray;

static inline void mt__tri_ray_init(mt__tri_ray *tr, const mt_ray *r)
{
    mt_real d[3];
    mt_real ax = mt_fabs(r->d.x), ay = mt_fabs(r->d.y), az = mt_fabs(r->d.z);
    tr->o[0] = r->o.x;
    tr->o[1] = r->o.y;
    tr->o[2] = r->o.z;
    d[0] = r->d.x;
    d[1] = r->d.y;
    d[2] = r->d.z;
    tr->kz = ax > ay ? (ax > az ? 0 : 2) : (ay > az ? 1 : 2);
    tr->kx = tr->kz == 2 ? 0 : tr->kz + 1;
    tr->ky = tr->kx == 2 ? 0 : tr->kx + 1;
    tr->sx = d[tr->kx] / d[tr->kz];
    tr->sy = d[tr->ky] / d[tr->kz];
    tr->sz = 1 / d[tr->kz];
}

static inline mt_real mt__max3(mt_real a, mt_real b, mt_real c) { return mt_max(a, mt_max(b, c)); }

/* The triangle (v0, v1, v2) against the ray: 1 with the distance *t in
 * [tmin, tmax] and the barycentric weights *b1, *b2 of v1 and v2. A
 * vertex's coordinates are stride reals apart (1: x, y, z in a row; the
 * BVH's packets of four triangles store them 4 apart). The BVH's SIMD test
 * of a packet performs exactly these operations, in this order. */
static inline int mt__tri_hit(const mt__tri_ray *r, const mt_real *v0, const mt_real *v1,
                              const mt_real *v2, int stride, mt_real tmin, mt_real tmax,
                              mt_real *t, mt_real *b1, mt_real *b2)
{
    const int kx = r->kx * stride, ky = r->ky * stride, kz = r->kz * stride;
    mt_real ox = r->o[r->kx], oy = r->o[r->ky], oz = r->o[r->kz];
    mt_real az = v0[kz] - oz, bz = v1[kz] - oz, cz = v2[kz] - oz;
    mt_real ax = (v0[kx] - ox) - r->sx * az, ay = (v0[ky] - oy) - r->sy * az;
    mt_real bx = (v1[kx] - ox) - r->sx * bz, by = (v1[ky] - oy) - r->sy * bz;
    mt_real cx = (v2[kx] - ox) - r->sx * cz, cy = (v2[ky] - oy) - r->sy * cz;
    /* pbrt-v3's e0, e1, e2: the edge functions opposite v0, v1, v2 */
    mt_real e0 = bx * cy - by * cx, e1 = cx * ay - cy * ax, e2 = ax * by - ay * bx;
    mt_real det, ts, inv, tt;
#if !MT_USE_DOUBLE
    if (e0 == 0 || e1 == 0 || e2 == 0) {
        e0 = (mt_real)((double)bx * cy - (double)by * cx);
        e1 = (mt_real)((double)cx * ay - (double)cy * ax);
        e2 = (mt_real)((double)ax * by - (double)ay * bx);
    }
#endif
    if ((e0 < 0 || e1 < 0 || e2 < 0) && (e0 > 0 || e1 > 0 || e2 > 0)) return 0;
    det = e0 + e1 + e2;
    if (det == 0) return 0;
    az *= r->sz;
    bz *= r->sz;
    cz *= r->sz;
    ts = e0 * az + e1 * bz + e2 * cz;
    if (det < 0 ? ts >= 0 : ts <= 0) return 0;
    inv = 1 / det;
    tt = ts * inv;
    if (!(tt >= tmin && tt <= tmax)) return 0;
    {
        /* pbrt-v3: reject t within its own error bound of zero, so that a
         * ray leaving a surface never re-hits it at t ~ 0 */
        mt_real mzt = mt__max3(mt_fabs(az), mt_fabs(bz), mt_fabs(cz));
        mt_real mxt = mt__max3(mt_fabs(ax), mt_fabs(bx), mt_fabs(cx));
        mt_real myt = mt__max3(mt_fabs(ay), mt_fabs(by), mt_fabs(cy));
        mt_real dz = mt__gamma(3) * mzt, dx = mt__gamma(5) * (mxt + mzt);
        mt_real dy = mt__gamma(5) * (myt + mzt);
        mt_real de = 2 * (mt__gamma(2) * mxt * myt + dy * mxt + dx * myt);
        mt_real me = mt__max3(mt_fabs(e0), mt_fabs(e1), mt_fabs(e2));
        mt_real dt = (3 * ((mt__gamma(3) * me * mzt + de * mzt) + dz * me)) * mt_fabs(inv);
        if (tt <= dt) return 0;
    }
    *t = tt;
    *b1 = e1 * inv;
    *b2 = e2 * inv;
    return 1;
}

#endif
