/*
 * Microfacet distributions: Blinn and Anisotropic (Ashikhmin and Shirley,
 * "An Anisotropic Phong BRDF Model", 2000), as pbrt-v2 reflection.h/.cpp
 * defines, samples and evaluates them, in pbrt-v2's order of operations.
 */
#include "bxdfs/kinds.h"
#include "materia/sampling.h"

static mt_real clamp_exponent(mt_real e)
{
    /* pbrt-v2: exponents above 10000 (or NaN) are 10000. */
    return (mt_is_nan(e) || e > 10000) ? 10000 : e;
}

mt_distribution mt_blinn(mt_real exponent)
{
    mt_distribution d;
    d.kind = MT_DIST_BLINN;
    d.exponent = clamp_exponent(exponent);
    d.ex = d.ey = 0;
    return d;
}

mt_distribution mt_anisotropic(mt_real ex, mt_real ey)
{
    mt_distribution d;
    d.kind = MT_DIST_ANISOTROPIC;
    d.exponent = 0;
    d.ex = clamp_exponent(ex);
    d.ey = clamp_exponent(ey);
    return d;
}

int mt__check_distribution(const mt_distribution *d, const char *kind, mt_error *err)
{
    int ok = d->kind == MT_DIST_BLINN ? (d->exponent >= 0 && mt_is_finite(d->exponent))
                                      : (d->ex >= 0 && d->ey >= 0 && mt_is_finite(d->ex) &&
                                         mt_is_finite(d->ey));
    if (!ok)
        mt_error_param(err, MT_ERR_INVALID, "exponent",
                       "%s: microfacet exponents must be non-negative", kind);
    return ok;
}

/* The Ashikhmin-Shirley density at wh, with coefficient c: sqrt((ex+2)(ey+2))
 * for D, sqrt((ex+1)(ey+1)) for the sampling density of wh. */
static mt_real aniso_density(const mt_distribution *d, mt_vec3 wh, mt_real coef, mt_mode mode)
{
    mt_real costhetah = mt_abs_cos_theta(wh);
    mt_real ds = 1 - costhetah * costhetah;
    mt_real e;
    if (ds <= 0) /* wh is the normal: pbrt-v2 returns 0 (erratum anisotropic-normal) */
        return (mode & MT_FIX_ANISOTROPIC_NORMAL) ? coef * MT_INV_2PI : 0;
    e = (d->ex * wh.x * wh.x + d->ey * wh.y * wh.y) / ds;
    return coef * MT_INV_2PI * mt_pow(costhetah, e);
}

mt_real mt_distribution_d(const mt_distribution *d, mt_vec3 wh, mt_mode mode)
{
    if (d->kind == MT_DIST_BLINN) {
        mt_real costhetah = mt_abs_cos_theta(wh);
        return (d->exponent + 2) * MT_INV_2PI * mt_pow(costhetah, d->exponent);
    }
    return aniso_density(d, wh, mt_sqrt((d->ex + 2) * (d->ey + 2)), mode);
}

/* Density of wi = reflect(wo, wh) given the density of wh (pbrt-v2: D(wh) |cos|
 * / (4 wo.wh)); 0 when wo and wh face away from each other. */
static mt_real wi_pdf(mt_real wh_density, mt_real wodotwh)
{
    if (wodotwh <= 0) return 0;
    return wh_density / (2 * MT_PI * 4 * wodotwh);
}

static mt_real blinn_pdf(const mt_distribution *d, mt_real costheta, mt_real wodotwh)
{
    if (wodotwh <= 0) return 0;
    return wi_pdf((d->exponent + 1) * mt_pow(costheta, d->exponent), wodotwh);
}

static mt_real aniso_pdf(const mt_distribution *d, mt_vec3 wh, mt_real wodotwh, mt_mode mode)
{
    /* pbrt-v2 computes sqrt((ex+1)(ey+1)) INV_TWOPI pow(...) / (4 wo.wh) in float. */
    if (wodotwh <= 0) return 0;
    return aniso_density(d, wh, mt_sqrt((d->ex + 1) * (d->ey + 1)), mode) / (4 * wodotwh);
}

static void sample_first_quadrant(const mt_distribution *d, mt_real u1, mt_real u2, mt_real *phi,
                                  mt_real *costheta)
{
    mt_real cosphi, sinphi;
    if (d->ex == d->ey)
        *phi = MT_PI * u1 * (mt_real)0.5;
    else
        *phi = mt_atan(mt_sqrt((d->ex + 1) / (d->ey + 1)) * mt_tan(MT_PI * u1 * (mt_real)0.5));
    cosphi = mt_cos(*phi);
    sinphi = mt_sin(*phi);
    *costheta = mt_pow(u2, 1 / (d->ex * cosphi * cosphi + d->ey * sinphi * sinphi + 1));
}

void mt_distribution_sample(const mt_distribution *d, mt_vec3 wo, mt_real u1, mt_real u2,
                            mt_vec3 *wi, mt_real *pdf, mt_mode mode)
{
    mt_real costheta, sintheta, phi, wodotwh;
    mt_vec3 wh;
    if (d->kind == MT_DIST_BLINN) {
        costheta = mt_pow(u1, 1 / (d->exponent + 1));
        sintheta = mt_sqrt(mt_max(0, 1 - costheta * costheta));
        phi = u2 * 2 * MT_PI;
    } else {
        /* Sample the first quadrant and mirror it into the one u1 selects. */
        if (u1 < 0.25f) {
            sample_first_quadrant(d, 4 * u1, u2, &phi, &costheta);
        } else if (u1 < 0.5f) {
            sample_first_quadrant(d, 4 * (0.5f - u1), u2, &phi, &costheta);
            phi = MT_PI - phi;
        } else if (u1 < 0.75f) {
            sample_first_quadrant(d, 4 * (u1 - 0.5f), u2, &phi, &costheta);
            phi += MT_PI;
        } else {
            sample_first_quadrant(d, 4 * (1 - u1), u2, &phi, &costheta);
            phi = 2 * MT_PI - phi;
        }
        sintheta = mt_sqrt(mt_max(0, 1 - costheta * costheta));
    }
    wh = mt_spherical_direction(sintheta, costheta, phi);
    if (!mt_same_hemisphere(wo, wh)) wh = mt_v3_neg(wh);
    wodotwh = mt_v3_dot(wo, wh);
    *wi = mt_v3_add(mt_v3_neg(wo), mt_v3_scale(wh, 2 * wodotwh));
    *pdf = d->kind == MT_DIST_BLINN ? blinn_pdf(d, costheta, wodotwh)
                                    : aniso_pdf(d, wh, wodotwh, mode);
}

mt_real mt_distribution_pdf(const mt_distribution *d, mt_vec3 wo, mt_vec3 wi, mt_mode mode)
{
    mt_vec3 wh = mt_v3_add(wo, wi);
    if (mt_v3_is_zero(wh)) return 0; /* pbrt-v2 would normalize a zero vector */
    wh = mt_v3_normalize(wh);
    if (d->kind == MT_DIST_BLINN)
        return blinn_pdf(d, mt_abs_cos_theta(wh), mt_v3_dot(wo, wh));
    return aniso_pdf(d, wh, mt_v3_dot(wo, wh), mode);
}
