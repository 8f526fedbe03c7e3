/*
 * Fresnel reflectance (pbrt-v2 reflection.h/.cpp FrDiel, FrCond and the
 * Fresnel classes) and the FresnelApproxEta/K helpers of shinymetal.
 */
#include "bxdfs/kinds.h"

mt_fresnel mt_fresnel_conductor(mt_rgb eta, mt_rgb k)
{
    mt_fresnel f;
    f.kind = MT_FRESNEL_CONDUCTOR;
    f.eta = eta;
    f.k = k;
    f.eta_i = f.eta_t = 1;
    return f;
}

mt_fresnel mt_fresnel_dielectric(mt_real eta_i, mt_real eta_t)
{
    mt_fresnel f;
    f.kind = MT_FRESNEL_DIELECTRIC;
    f.eta = f.k = mt_rgb_black();
    f.eta_i = eta_i;
    f.eta_t = eta_t;
    return f;
}

mt_fresnel mt_fresnel_noop(void)
{
    mt_fresnel f;
    f.kind = MT_FRESNEL_NOOP;
    f.eta = f.k = mt_rgb_black();
    f.eta_i = f.eta_t = 1;
    return f;
}

/* Unpolarized reflectance: the mean of the squared parallel and perpendicular
 * amplitude ratios. The denominators vanish only for cosi = cost = 0, which
 * FresnelDielectric never passes (sin t = 1 is total internal reflection). */
static mt_real fr_diel(mt_real cosi, mt_real cost, mt_real etai, mt_real etat)
{
    mt_real rparl = ((etat * cosi) - (etai * cost)) / ((etat * cosi) + (etai * cost));
    mt_real rperp = ((etai * cosi) - (etat * cost)) / ((etai * cosi) + (etat * cost));
    return (rparl * rparl + rperp * rperp) / 2;
}

mt_rgb mt_fr_diel(mt_real cosi, mt_real cost, mt_rgb etai, mt_rgb etat)
{
    return mt_rgb_make(fr_diel(cosi, cost, etai.c[0], etat.c[0]), fr_diel(cosi, cost, etai.c[1], etat.c[1]),
                       fr_diel(cosi, cost, etai.c[2], etat.c[2]));
}

/* The conductor approximation pbrt-v2 uses. With eta = k = 0 and cosi = 0 the
 * perpendicular term is 0/0 in pbrt-v2; its limit, 1, is returned. */
mt_rgb mt_fr_cond(mt_real cosi, mt_rgb eta, mt_rgb k)
{
    mt_rgb r;
    int c;
    for (c = 0; c < 3; ++c) {
        mt_real e = eta.c[c], kk = k.c[c];
        mt_real tmp = (e * e + kk * kk) * cosi * cosi;
        mt_real rparl2 = (tmp - (2 * e * cosi) + 1) / (tmp + (2 * e * cosi) + 1);
        mt_real tmp_f = e * e + kk * kk;
        mt_real den = tmp_f + (2 * e * cosi) + cosi * cosi;
        mt_real rperp2 = den > 0 ? (tmp_f - (2 * e * cosi) + cosi * cosi) / den : 1;
        r.c[c] = (rparl2 + rperp2) / 2;
    }
    return r;
}

mt_rgb mt_fresnel_evaluate(const mt_fresnel *f, mt_real cosi)
{
    switch (f->kind) {
    case MT_FRESNEL_CONDUCTOR:
        return mt_fr_cond(mt_fabs(cosi), f->eta, f->k);
    case MT_FRESNEL_DIELECTRIC: {
        mt_real ei = f->eta_i, et = f->eta_t, sint;
        int entering;
        cosi = mt_clamp(cosi, -1, 1);
        entering = cosi > 0;
        if (!entering) {
            mt_real t = ei;
            ei = et;
            et = t;
        }
        sint = ei / et * mt_sqrt(mt_max(0, 1 - cosi * cosi));
        if (sint >= 1) return mt_rgb_gray(1); /* total internal reflection */
        /* the indices are scalars: one channel's value is every channel's */
        return mt_rgb_gray(fr_diel(mt_fabs(cosi), mt_sqrt(mt_max(0, 1 - sint * sint)), ei, et));
    }
    case MT_FRESNEL_NOOP:
        break;
    }
    return mt_rgb_gray(1);
}

/* shinymetal.cpp: a conductor whose normal-incidence reflectance is Fr. */
mt_rgb mt_fresnel_approx_eta(mt_rgb fr)
{
    mt_rgb r = mt_rgb_clamp(fr, 0, (mt_real)0.999), s = mt_rgb_sqrt(r);
    return mt_rgb_div(mt_rgb_add(mt_rgb_gray(1), s), mt_rgb_sub(mt_rgb_gray(1), s));
}

mt_rgb mt_fresnel_approx_k(mt_rgb fr)
{
    mt_rgb r = mt_rgb_clamp(fr, 0, (mt_real)0.999);
    return mt_rgb_scale(mt_rgb_sqrt(mt_rgb_div(r, mt_rgb_sub(mt_rgb_gray(1), r))), 2);
}

int mt__check_fresnel(const mt_fresnel *f, const char *kind, mt_error *err)
{
    int c;
    switch (f->kind) {
    case MT_FRESNEL_CONDUCTOR:
        for (c = 0; c < 3; ++c)
            if (!mt_is_finite(f->eta.c[c]) || !mt_is_finite(f->k.c[c]) || f->eta.c[c] < 0 ||
                f->k.c[c] < 0) {
                mt_error_param(err, MT_ERR_INVALID, "fresnel",
                               "%s: conductor eta and k must be finite and non-negative", kind);
                return 0;
            }
        return 1;
    case MT_FRESNEL_DIELECTRIC:
        if (!(mt_is_finite(f->eta_i) && mt_is_finite(f->eta_t) && f->eta_i > 0 && f->eta_t > 0)) {
            mt_error_param(err, MT_ERR_INVALID, "fresnel",
                           "%s: dielectric indices must be finite and positive (got %g, %g)",
                           kind, (double)f->eta_i, (double)f->eta_t);
            return 0;
        }
        return 1;
    case MT_FRESNEL_NOOP:
        return 1;
    }
    mt_error_param(err, MT_ERR_INVALID, "fresnel", "%s: unknown Fresnel kind", kind);
    return 0;
}
