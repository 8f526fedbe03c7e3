/*
 * pbrt-v2's cylinder (shapes/cylinder.cpp): radius, zmin, zmax, phimax about
 * the z axis, open at both ends; u = phi / phimax, v = (z - zmin) /
 * (zmax - zmin); the normal points away from the axis.
 *
 * Solved in double precision in object space like the sphere, with the
 * discriminant r^2 (dx^2 + dy^2) - (ox dy - oy dx)^2 and the hit pulled onto
 * the cylinder (pbrt-v3: error bound gamma(3) |(x, y, 0)|).
 */
#include "tracer/shape_impl.h"

mt_status mt__cylinder_init(mt_shape *s, const mt_paramset *ps, mt_error *err)
{
    mt_real r, z0, z1, pm;
    mt_status st;
    if ((st = mt_params_float(ps, "radius", 1, &r, err)) != MT_OK ||
        (st = mt_params_float(ps, "zmin", -1, &z0, err)) != MT_OK ||
        (st = mt_params_float(ps, "zmax", 1, &z1, err)) != MT_OK ||
        (st = mt_params_float(ps, "phimax", 360, &pm, err)) != MT_OK)
        return st;
    s->kind = MT_SHAPE_CYLINDER;
    s->radius = r;
    s->zmin = mt_min(z0, z1);
    s->zmax = mt_max(z0, z1);
    s->phi_max = mt_radians(mt_clamp(pm, 0, 360));
    if (!(r > 0)) {
        mt__locate_param(err, ps, "radius");
        return mt_error_param(err, MT_ERR_INVALID, "radius",
                              "cylinder radius %g is not positive", (double)r);
    }
    if (!(s->zmin < s->zmax)) {
        mt__locate_param(err, ps, "zmin");
        return mt_error_param(err, MT_ERR_INVALID, "zmin", "cylinder zmin = zmax = %g",
                              (double)z0);
    }
    if (!(s->phi_max > 0)) {
        mt__locate_param(err, ps, "phimax");
        return mt_error_param(err, MT_ERR_INVALID, "phimax",
                              "cylinder phimax %g is not positive", (double)pm);
    }
    return MT_OK;
}

static int cylinder_point(const mt_shape *s, const mt__oray *r, double t, double p[3])
{
    double rho;
    int i;
    for (i = 0; i < 3; ++i) p[i] = r->o[i] + t * r->d[i];
    rho = sqrt(p[0] * p[0] + p[1] * p[1]);
    if (rho > 0) {
        p[0] *= s->radius / rho;
        p[1] *= s->radius / rho;
    }
    if (p[2] < s->zmin || p[2] > s->zmax) return 0;
    return !mt__phi_cut(s) || !(mt__phi(p[0], p[1]) > s->phi_max);
}

int mt__cylinder_hit(const mt_shape *s, const mt__oray *r, double *t, double p[3])
{
    const double *o = r->o, *d = r->d;
    double rad = s->radius, a, b, c, cz, t0, t1;
    a = d[0] * d[0] + d[1] * d[1];
    b = o[0] * d[0] + o[1] * d[1];
    c = o[0] * o[0] + o[1] * o[1] - rad * rad;
    cz = o[0] * d[1] - o[1] * d[0];
    if (!mt__quadratic(a, b, c, a * rad * rad - cz * cz, &t0, &t1)) return 0;
    return mt__pick_root(s, r, t0, t1, cylinder_point, t, p);
}

void mt__cylinder_surface(const mt_shape *s, const double p[3], mt_surface *sf)
{
    static const double zero[3] = {0, 0, 0};
    double pm = s->phi_max, perr[3], dpdu[3], dpdv[3], duu[3], dndu[3], dndv[3], nrm[3];
    dpdu[0] = -pm * p[1];
    dpdu[1] = pm * p[0];
    dpdu[2] = 0;
    dpdv[0] = dpdv[1] = 0;
    dpdv[2] = (double)s->zmax - s->zmin;
    duu[0] = -pm * pm * p[0];
    duu[1] = -pm * pm * p[1];
    duu[2] = 0;
    mt__weingarten(dpdu, dpdv, duu, zero, zero, dndu, dndv);
    perr[0] = mt__gamma_d(3) * fabs(p[0]);
    perr[1] = mt__gamma_d(3) * fabs(p[1]);
    perr[2] = 0;
    nrm[0] = p[0];
    nrm[1] = p[1];
    nrm[2] = 0;
    mt__surface_from_object(s, p, perr, dpdu, dpdv, dndu, dndv, nrm,
                            (mt_real)(mt__phi(p[0], p[1]) / pm),
                            (mt_real)((p[2] - s->zmin) / ((double)s->zmax - s->zmin)), sf);
}

mt_real mt__cylinder_area(const mt_shape *s) { return (s->zmax - s->zmin) * s->phi_max * s->radius; }

mt_vec3 mt__cylinder_sample(const mt_shape *s, mt_real u1, mt_real u2, mt_vec3 *ns)
{
    mt_real z = mt_lerp(u1, s->zmin, s->zmax), t = u2 * s->phi_max;
    mt_vec3 p = mt_v3(s->radius * mt_cos(t), s->radius * mt_sin(t), z);
    *ns = mt_v3_normalize(mt_transform_normal(&s->o2w, mt_v3(p.x, p.y, 0)));
    if (s->reverse_orientation) *ns = mt_v3_neg(*ns);
    return mt_transform_point(&s->o2w, p);
}
