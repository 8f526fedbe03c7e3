/*
 * pbrt-v2's disk (shapes/disk.cpp): height, radius, innerradius, phimax;
 * u = phi / phimax, v = 1 - (rho - innerradius) / (radius - innerradius)
 * (v = 1 at the inner edge). The normal is +z in object space.
 *
 * Erratum disk-partials (MT_FIX_DISK_PARTIALS): pbrt-v2 as released
 * (992b6aa, then 26fb330) has dpdu = phimax (-y, x, 0), the derivative of
 * its (u, v), but dpdv = (x, y) (radius - innerradius) / rho, the opposite
 * of the derivative (rho = radius - v (radius - innerradius) falls as v
 * grows). The hit's normal, Normalize(Cross(dpdu, dpdv)), is then -z in
 * object space, while Disk::Sample gives +z: an area light on a disk emits
 * towards -z when a ray hits it and towards +z when it is sampled. pbrt-v2
 * mode keeps this; corrected mode has pbrt-v3's (x, y) (innerradius -
 * radius) / rho and the normal +z. (The 2012 snapshot had dpdu with an extra
 * factor phimax / 2 pi and dpdv = -(x, y) / (1 - v) (radius - innerradius) /
 * radius, with the normal +z.) At the exact centre the derivatives are 0/0
 * and the normal NaN in pbrt-v2; here they are taken 1e-5 radius off the
 * centre, as pbrt-v2's sphere does at its poles.
 *
 * Erratum partial-sampling (MT_FIX_PARTIAL_SAMPLING): pbrt-v2's Sample()
 * covers the full disk of the outer radius whatever innerradius and phimax
 * are, while Area() and Pdf() describe the partial disk; corrected mode
 * samples the annulus sector uniformly.
 */
#include "materia/sampling.h"
#include "tracer/shape_impl.h"

mt_status mt__disk_init(mt_shape *s, const mt_paramset *ps, mt_error *err)
{
    mt_real h, r, ri, pm;
    mt_status st;
    if ((st = mt_params_float(ps, "height", 0, &h, err)) != MT_OK ||
        (st = mt_params_float(ps, "radius", 1, &r, err)) != MT_OK ||
        (st = mt_params_float(ps, "innerradius", 0, &ri, err)) != MT_OK ||
        (st = mt_params_float(ps, "phimax", 360, &pm, err)) != MT_OK)
        return st;
    s->kind = MT_SHAPE_DISK;
    s->height = h;
    s->radius = r;
    s->inner_radius = ri;
    s->phi_max = mt_radians(mt_clamp(pm, 0, 360));
    if (!(r > 0)) {
        mt__locate_param(err, ps, "radius");
        return mt_error_param(err, MT_ERR_INVALID, "radius", "disk radius %g is not positive",
                              (double)r);
    }
    if (!(ri >= 0 && ri < r)) {
        mt__locate_param(err, ps, "innerradius");
        return mt_error_param(err, MT_ERR_INVALID, "innerradius",
                              "disk innerradius %g is not in [0, radius %g)", (double)ri,
                              (double)r);
    }
    if (!(s->phi_max > 0)) {
        mt__locate_param(err, ps, "phimax");
        return mt_error_param(err, MT_ERR_INVALID, "phimax", "disk phimax %g is not positive",
                              (double)pm);
    }
    return MT_OK;
}

int mt__disk_hit(const mt_shape *s, const mt__oray *r, double *t, double p[3])
{
    double th, d2, rad = s->radius, ri = s->inner_radius;
    /* pbrt-v2 skips |d.z| < 1e-7 (a scale-dependent threshold); only rays
     * exactly parallel to the plane are skipped here */
    if (r->d[2] == 0) return 0;
    th = (s->height - r->o[2]) / r->d[2];
    /* t = 0 is no hit (pbrt-v3's Disk::Intersect): a ray spawned from the
     * disk starts exactly on its plane when the plane's world point has no
     * rounding error (the plane z = 0 untransformed), and its offset along
     * the normal is then 0 */
    if (!(th >= r->tmin && th <= r->tmax && th > 0)) return 0;
    p[0] = r->o[0] + th * r->d[0];
    p[1] = r->o[1] + th * r->d[1];
    p[2] = s->height; /* exactly on the plane (pbrt-v3) */
    d2 = p[0] * p[0] + p[1] * p[1];
    if (d2 > rad * rad || d2 < ri * ri) return 0;
    if (mt__phi_cut(s) && !(p[0] == 0 && p[1] == 0) && mt__phi(p[0], p[1]) > s->phi_max) return 0;
    *t = th;
    return 1;
}

void mt__disk_surface(const mt_shape *s, const double ph[3], mt_surface *sf)
{
    static const double zero[3] = {0, 0, 0}, nz[3] = {0, 0, 1}, nmz[3] = {0, 0, -1};
    double rad = s->radius, ri = s->inner_radius, pm = s->phi_max;
    double p[3], perr[3], phi, rho, dpdu[3], dpdv[3], k;
    int fixed = (s->mode & MT_FIX_DISK_PARTIALS) != 0;
    mt_real u, v;
    p[0] = ph[0];
    p[1] = ph[1];
    p[2] = ph[2];
    perr[0] = mt__gamma_d(3) * fabs(p[0]);
    perr[1] = mt__gamma_d(3) * fabs(p[1]);
    perr[2] = 0;
    phi = p[0] == 0 && p[1] == 0 ? 0 : mt__phi(p[0], p[1]);
    rho = sqrt(p[0] * p[0] + p[1] * p[1]);
    u = (mt_real)(phi / pm);
    v = (mt_real)(1 - (rho - ri) / (rad - ri));
    if (p[0] == 0 && p[1] == 0) {
        p[0] = 1e-5 * rad;
        rho = p[0];
    }
    dpdu[0] = -pm * p[1];
    dpdu[1] = pm * p[0];
    dpdu[2] = 0;
    /* rho = radius - v (radius - innerradius): drho/dv = innerradius -
     * radius; pbrt-v2 (26fb330) has the opposite sign */
    k = (fixed ? ri - rad : rad - ri) / rho;
    dpdv[0] = p[0] * k;
    dpdv[1] = p[1] * k;
    dpdv[2] = 0;
    mt__surface_from_object(s, ph, perr, dpdu, dpdv, zero, zero, fixed ? nz : nmz, u, v, sf);
}

mt_real mt__disk_area(const mt_shape *s)
{
    return s->phi_max * (mt_real)0.5 *
           (s->radius * s->radius - s->inner_radius * s->inner_radius);
}

mt_vec3 mt__disk_sample(const mt_shape *s, mt_real u1, mt_real u2, mt_vec3 *ns)
{
    mt_real x, y;
    if ((s->mode & MT_FIX_PARTIAL_SAMPLING) && (s->inner_radius > 0 || mt__phi_cut(s))) {
        /* uniform in area on the annulus sector: rho^2 uniform between the
         * radii, phi uniform in [0, phimax] */
        mt_real ri2 = s->inner_radius * s->inner_radius, r2 = s->radius * s->radius;
        mt_real rho = mt_sqrt(mt_min(r2, ri2 + u1 * (r2 - ri2))), phi = u2 * s->phi_max;
        x = rho * mt_cos(phi);
        y = rho * mt_sin(phi);
    } else {
        /* pbrt-v2 Disk::Sample: the full disk of the outer radius */
        mt_concentric_sample_disk(u1, u2, &x, &y);
        x *= s->radius;
        y *= s->radius;
    }
    *ns = mt_v3_normalize(mt_transform_normal(&s->o2w, mt_v3(0, 0, 1)));
    if (s->reverse_orientation) *ns = mt_v3_neg(*ns);
    return mt_transform_point(&s->o2w, mt_v3(x, y, s->height));
}
