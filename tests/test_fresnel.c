/*
 * Fresnel terms against closed forms: normal incidence ((n-1)/(n+1))^2, total
 * internal reflection beyond the critical angle, Stokes reciprocity of the
 * dielectric (the same reflectance from both sides at refracted angles), the
 * conductor at k = 0 equal to the dielectric, and shinymetal's
 * FresnelApproxEta inverting the normal-incidence reflectance.
 */
#include "support/check.h"

int main(void)
{
    mt_fresnel glass = mt_fresnel_dielectric(1, 1.5f);
    mt_real r0 = mt_fresnel_evaluate(&glass, 1).c[0], crit = mt_sqrt(1 - (1 / 1.5f) * (1 / 1.5f));
    int i, ok = 1;
    t_near(r0, 0.04, 1e-6, "fresnel: dielectric 1.5 at normal incidence is 0.04");
    t_near(mt_fresnel_evaluate(&glass, -1).c[0], 0.04, 1e-6, "fresnel: the same from inside");
    t_near(mt_fresnel_evaluate(&glass, -(crit - 1e-3f)).c[0], 1, 0, "fresnel: total internal reflection past the critical angle");
    t_check(mt_fresnel_evaluate(&glass, -(crit + 1e-3f)).c[0] < 1, "fresnel: no TIR before the critical angle", "F = 1");
    for (i = 10; i < 100; ++i) {
        /* Stokes: F(theta_i) outside = F(theta_t) inside (from cos 0.1 up:
         * nearer grazing the float rounding of cos theta_t dominates) */
        mt_real ci = (mt_real)i / 100, si = mt_sqrt(1 - ci * ci), st = si / 1.5f, ct = mt_sqrt(1 - st * st);
        mt_real a = mt_fresnel_evaluate(&glass, ci).c[0], b = mt_fresnel_evaluate(&glass, -ct).c[0];
        if (fabs(a - b) > 1e-5) ok = 0;
    }
    t_check(ok, "fresnel: dielectric reflectance is the same from both sides at refracted angles", "differs");
    for (i = 0, ok = 1; i <= 100; ++i) {
        mt_rgb cond = mt_fr_cond((mt_real)i / 100, mt_rgb_gray(1.5f), mt_rgb_black());
        if (!mt_rgb_is_finite(cond) || cond.c[0] < 0 || cond.c[0] > 1) ok = 0;
    }
    t_check(ok, "fresnel: conductor reflectance in [0, 1] over incidence", "outside");
    /* pbrt-v2's FrCond is an approximation; at normal incidence it is exact */
    t_near(mt_fr_cond(1, mt_rgb_gray(1.5f), mt_rgb_black()).c[0], 0.04, 1e-6,
           "fresnel: conductor with k = 0 at normal incidence is ((n-1)/(n+1))^2");
    {
        mt_rgb f0 = mt_rgb_make(0.04f, 0.5f, 0.95f), eta = mt_fresnel_approx_eta(f0), k = mt_fresnel_approx_k(f0);
        mt_rgb back = mt_fr_cond(1, eta, mt_rgb_black());
        t_near(back.c[0], 0.04, 1e-6, "fresnel: FresnelApproxEta inverts F0 = 0.04 (k = 0)");
        t_near(back.c[1], 0.5, 1e-6, "fresnel: FresnelApproxEta inverts F0 = 0.5 (k = 0)");
        t_near(back.c[2], 0.95, 1e-5, "fresnel: FresnelApproxEta inverts F0 = 0.95 (k = 0)");
        t_near(k.c[1], 2.0, 1e-6, "fresnel: FresnelApproxK(0.5) = 2 sqrt(0.5 / 0.5)");
        t_near(mt_fresnel_approx_eta(mt_rgb_gray(1)).c[0], (1 + sqrt(0.999)) / (1 - sqrt(0.999)), 0.5,
               "fresnel: FresnelApproxEta clamps F0 to 0.999");
    }
    t_near(mt_fr_cond(0, mt_rgb_black(), mt_rgb_black()).c[0], 1, 0, "fresnel: eta = k = 0 at grazing is 1, not 0/0");
    return t_status();
}
