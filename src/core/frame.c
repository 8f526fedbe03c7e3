/* Shading frames and pbrt-v2's CoordinateSystem. */
#include "materia/frame.h"
#include "materia/diffgeom.h"

void mt_coordinate_system(mt_vec3 v1, mt_vec3 *v2, mt_vec3 *v3)
{
    /* pbrt-v2 geometry.h: zero the smaller of x and y so the division is
     * well conditioned for any unit v1. */
    if (mt_fabs(v1.x) > mt_fabs(v1.y)) {
        mt_real inv = 1 / mt_sqrt(v1.x * v1.x + v1.z * v1.z);
        *v2 = mt_v3(-v1.z * inv, 0, v1.x * inv);
    } else {
        mt_real inv = 1 / mt_sqrt(v1.y * v1.y + v1.z * v1.z);
        *v2 = mt_v3(0, v1.z * inv, -v1.y * inv);
    }
    *v3 = mt_v3_cross(v1, *v2);
}

mt_frame mt_frame_from_normal(mt_vec3 n)
{
    mt_frame f;
    f.n = n;
    mt_coordinate_system(n, &f.s, &f.t);
    return f;
}

mt_diffgeom mt_diffgeom_default(void)
{
    mt_diffgeom dg;
    mt_vec3 zero = mt_v3(0, 0, 0);
    dg.p = zero;
    dg.n = mt_v3(0, 0, 1);
    dg.dpdu = mt_v3(1, 0, 0);
    dg.dpdv = mt_v3(0, 1, 0);
    dg.dndu = dg.dndv = zero;
    dg.u = dg.v = (mt_real)0.5;
    dg.dpdx = dg.dpdy = zero;
    dg.dudx = dg.dvdx = dg.dudy = dg.dvdy = 0;
    dg.flip = 0;
    return dg;
}
