/*
 * The dipole's diffusion reflectance (pbrt-v2 integrators/
 * dipolesubsurface.cpp DiffusionReflectance; Jensen, Marschner, Levoy and
 * Hanrahan 2001) and the diffuse Fresnel reflectance Fdr it is built with.
 */
#include "materia/bxdf.h"
#include "materia/material.h"
#include "tracer/dipole.h"

/* The hemispherical average 2 int_0^1 Fr(mu) mu dmu of the dielectric
 * Fresnel reflectance for light inside a medium of relative index eta
 * meeting its boundary. For eta > 1 the part below the critical cosine is
 * total internal reflection (exactly mu_c^2) and the rest is integrated
 * over the cosine of the transmitted angle, c, where mu dmu = c dc / eta^2
 * and the integrand is smooth (in mu it has a square-root kink at mu_c).
 * Simpson's rule with 128 intervals: 1e-7 against a 200000-point sum. */
static double fr_inside(double mu, double cost, double e)
{
    double a = (mu - e * cost) / (mu + e * cost), b = (e * mu - cost) / (e * mu + cost);
    return (a * a + b * b) / 2;
}

static mt_real fdr_integral(mt_real eta)
{
    enum { N = 128 };
    double e = (double)eta, sum = 0, h = 1.0 / N, base = 0;
    int i;
    for (i = 0; i <= N; ++i) {
        double x = h * i, w = (i == 0 || i == N) ? 1 : (i & 1) ? 4 : 2, f;
        if (e > 1) {
            /* x = cos theta_t */
            double mu = sqrt(fmax(0, 1 - (1 - x * x) / (e * e)));
            f = 2 * fr_inside(mu, x, e) * x / (e * e);
        } else {
            /* x = mu */
            double sint = e * sqrt(fmax(0, 1 - x * x));
            f = 2 * fr_inside(x, sqrt(fmax(0, 1 - sint * sint)), e) * x;
        }
        sum += w * f;
    }
    if (e > 1) base = 1 - 1 / (e * e);
    return (mt_real)(base + sum * h / 3);
}

mt_real mt__fdr(mt_real eta, mt_mode mode)
{
    if (mode & MT_FIX_FDR_RANGE) return fdr_integral(eta);
    return mt_fdr(eta);
}

void mt__diffusion_init(mt__diffusion *rd, mt_rgb sigma_a, mt_rgb sigmap_s, mt_real fdr)
{
    mt_rgb sigmap_t = mt_rgb_add(sigma_a, sigmap_s);
    int c;
    rd->A = (1 + fdr) / (1 - fdr);
    for (c = 0; c < 3; ++c) {
        mt_real st = sigmap_t.c[c];
        rd->sigma_tr.c[c] = mt_sqrt(3 * sigma_a.c[c] * st);
        rd->alphap.c[c] = sigmap_s.c[c] / st;
        rd->zpos.c[c] = 1 / st;
        rd->zneg.c[c] = -rd->zpos.c[c] * (1 + (mt_real)(4.0 / 3.0) * rd->A);
    }
}

mt_rgb mt__diffusion_eval(const mt__diffusion *rd, mt_real d2)
{
    mt_rgb out;
    int c;
    for (c = 0; c < 3; ++c) {
        mt_real zp = rd->zpos.c[c], zn = rd->zneg.c[c], str = rd->sigma_tr.c[c];
        mt_real dpos = mt_sqrt(d2 + zp * zp), dneg = mt_sqrt(d2 + zn * zn);
        mt_real v = rd->alphap.c[c] / (mt_real)(4 * MT_PI) *
                    ((zp * (dpos * str + 1) * mt_exp(-str * dpos)) / (dpos * dpos * dpos) -
                     (zn * (dneg * str + 1) * mt_exp(-str * dneg)) / (dneg * dneg * dneg));
        /* pbrt-v2's Spectrum::Clamp(): negative values to 0. Both terms are
         * positive for Fdr < 1; an A of pbrt-v2's Fdr beyond its range (or a
         * sigma that is 0) can make a term 0/0: 0, never a NaN */
        out.c[c] = v > 0 && mt_is_finite(v) ? v : 0;
    }
    return out;
}
