/*
 * MERL tables of any BSDF: the direction pair at a position of pbrt-v2's
 * half-angle table, and the file values that reproduce a BSDF's reflection
 * there.
 *
 * The parameterisation is MERL's, read backwards from the index arithmetic
 * of pbrt-v2's RegularHalfangleBRDF::f: sqrt(theta_h / (pi/2)), theta_d and
 * phi_d in bins of 1/90, pi/180 and pi/180. A pair with phi_h = 0 stands for
 * all phi_h (the table is isotropic), and the difference vector is taken in
 * pbrt-v2's half-angle frame (whx = (cos theta_h, 0, -sin theta_h), why = y).
 */
#include "measured/measured_impl.h"
#include "materia/tools/merl.h"

void mt_merl_directions(double uh, double ud, double up, mt_vec3 *wo, mt_vec3 *wi)
{
    const double half_pi = 1.57079632679489661923;
    double s = uh / MT_MERL_THETA_H, th = s * s * half_pi;
    double td = ud / MT_MERL_THETA_D * half_pi, pd = up / MT_MERL_PHI_D * (2 * half_pi);
    double sh = sin(th), ch = cos(th), st = sin(td);
    /* wi's coordinates in the half vector's frame (pbrt-v2's wd) */
    double dx = st * cos(pd), dy = st * sin(pd), dz = cos(td);
    double ix = dx * ch + dz * sh, iy = dy, iz = -dx * sh + dz * ch;
    /* wo = 2 (wi . wh) wh - wi, with wi . wh = dz */
    *wi = mt_v3((mt_real)ix, (mt_real)iy, (mt_real)iz);
    *wo = mt_v3((mt_real)(2 * dz * sh - ix), (mt_real)-iy, (mt_real)(2 * dz * ch - iz));
}

mt_status mt_merl_tabulate(const mt_bsdf *b, mt_merl_at at, double *values, mt_error *err)
{
    double off = at == MT_MERL_AT_CENTRE ? 0.5 : 0;
    int ith, itd, ipd, c;
    mt_error_clear(err);
    if (!b || !values) return mt_error_set(err, MT_ERR_INVALID, "mt_merl_tabulate: no %s", b ? "values" : "BSDF");
    for (ith = 0; ith < MT_MERL_THETA_H; ++ith)
        for (itd = 0; itd < MT_MERL_THETA_D; ++itd)
            for (ipd = 0; ipd < MT_MERL_PHI_D; ++ipd) {
                size_t i = (size_t)ipd + MT_MERL_PHI_D * ((size_t)itd + (size_t)ith * MT_MERL_THETA_D);
                mt_vec3 wo, wi;
                mt_rgb f = mt_rgb_black();
                mt_merl_directions(ith + off, itd + off, ipd + off, &wo, &wi);
                if (wo.z > 0 && wi.z > 0)
                    f = mt_bsdf_f(b, mt_bsdf_local_to_world(b, wo), mt_bsdf_local_to_world(b, wi),
                                  MT_BSDF_ALL);
                if (!mt_rgb_is_finite(f))
                    return mt_error_set(err, MT_ERR_INVALID,
                                        "MERL table: f is not finite at theta_h %d, theta_d %d, "
                                        "phi_d %d", ith, itd, ipd);
                for (c = 0; c < 3; ++c)
                    values[(size_t)c * MT_MERL_SAMPLES + i] = (double)f.c[c] / (double)mt__merl_scale[c];
            }
    return MT_OK;
}
