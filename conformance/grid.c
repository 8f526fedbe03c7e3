/*
 * The equal-area grid of the sphere (nphi x nz cells in phi and cos theta,
 * an odd number of rows so that the horizon lies inside one) and the
 * cubature of a BSDF over its cells: the cells the suite's chi-square used
 * before they were laid where a pilot sample falls (cells.c), kept for the
 * measurement of such grids' power (tradeoff/power.c).
 */
#include <stdio.h>
#include <string.h>
#include "conformance.h"

#define TWO_PI 6.283185307179586476925

void cf_bsdf_integrand(void *ctx, double phi, double z, double *out)
{
    const cf_bsdf_pass *p = ctx;
    mt_vec3 wi = mt_sphere_direction(phi, z);
    mt_rgb f = mt_bsdf_f(p->bsdf, p->wo, wi, p->flags);
    double c = fabs(z), pdf = mt_bsdf_pdf(p->bsdf, p->wo, wi, p->flags);
    out[0] = pdf;
    out[1] = f.c[0] * c;
    out[2] = f.c[1] * c;
    out[3] = f.c[2] * c;
    out[4] = pdf > 0 ? 0 : out[1];
    out[5] = pdf > 0 ? 0 : out[2];
    out[6] = pdf > 0 ? 0 : out[3];
}

int cf_cell_of(const cf_config *cfg, mt_vec3 w)
{
    double phi = atan2(w.y, w.x), z = w.z;
    int ip, iz;
    if (phi < 0) phi += TWO_PI;
    ip = (int)(phi / TWO_PI * cfg->nphi);
    iz = (int)((z + 1) / 2 * cfg->nz);
    if (ip >= cfg->nphi) ip = cfg->nphi - 1;
    if (ip < 0) ip = 0;
    if (iz >= cfg->nz) iz = cfg->nz - 1;
    if (iz < 0) iz = 0;
    return ip * cfg->nz + iz;
}

mt_status cf_integrate_cell(mt_cubature_fn f, void *ctx, const cf_config *cfg, int c, long count, long n,
                            double abs_tol, double out[7], double *err_pdf, mt_error *err)
{
    int ncell = cfg->nphi * cfg->nz, ip = c / cfg->nz, iz = c % cfg->nz, part, k;
    int sub = mt_cubature_grid((double)count * ncell / (double)n);
    double p0 = TWO_PI * ip / cfg->nphi, p1 = TWO_PI * (ip + 1) / cfg->nphi;
    double z0 = -1 + 2.0 * iz / cfg->nz, z1 = -1 + 2.0 * (iz + 1) / cfg->nz;
    for (k = 0; k < 7; ++k) out[k] = 0;
    *err_pdf = 0;
    /* the horizon splits the middle row: integrate its halves apart */
    for (part = 0; part < 2; ++part) {
        double a = z0, b = z1;
        mt_cubature_result r;
        mt_status st;
        if (z0 < 0 && z1 > 0) {
            if (part == 0)
                b = 0;
            else
                a = 0;
        } else if (part == 1) {
            break;
        }
        st = mt_cubature(f, ctx, 7, p0, p1, a, b, sub, sub, 1e-7, abs_tol, 225L * 8 * sub * sub, &r, err);
        if (st) return st;
        for (k = 0; k < 7; ++k) out[k] += r.value[k];
        *err_pdf += r.error[0];
    }
    return MT_OK;
}

void cf_chi2_cells(const cf_config *cfg, const long *counts, const double *pdfc, long n, long in_cells,
                   double integral, cf_chi2 *out)
{
    cf_chi2_counts(cfg->nphi * cfg->nz, counts, pdfc, n, in_cells, integral, out);
}
